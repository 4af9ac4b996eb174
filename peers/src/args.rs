//! The command line of `peers` (the options are listed in `main.rs`'s
//! module documentation).

use crate::llvmpipe::Target;

/// The command line.
pub(crate) struct Args {
    pub(crate) runs: usize,
    pub(crate) sizes: Vec<u32>,
    pub(crate) threads: Vec<u32>,
    pub(crate) rounds: usize,
    pub(crate) euc: bool,
    pub(crate) llvmpipe: bool,
    pub(crate) target: Target,
    pub(crate) json: Option<String>,
    pub(crate) child: bool,
    /// Also llvmpipe with 4x MSAA (`--msaa`, see `msaa.rs`).
    pub(crate) msaa: bool,
}

fn parse_list<T: std::str::FromStr>(flag: &str, value: &str) -> Result<Vec<T>, String> {
    value
        .split(',')
        .map(|v| {
            v.trim()
                .parse()
                .map_err(|_| format!("{flag}: `{v}` is not a number"))
        })
        .collect()
}

pub(crate) fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        runs: 11,
        sizes: vec![1024],
        threads: vec![1, 2],
        rounds: 2,
        euc: true,
        llvmpipe: true,
        target: Target::Fbo,
        json: None,
        child: false,
        msaa: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{flag} needs a value"));
        match flag.as_str() {
            "--runs" => args.runs = parse_list(&flag, &value()?)?[0],
            "--sizes" => args.sizes = parse_list(&flag, &value()?)?,
            "--threads" => args.threads = parse_list(&flag, &value()?)?,
            "--rounds" => args.rounds = parse_list(&flag, &value()?)?[0],
            "--json" => args.json = Some(value()?),
            "--msaa" => args.msaa = true,
            "--gl-target" => {
                let v = value()?;
                args.target = Target::parse(&v)
                    .ok_or_else(|| format!("--gl-target: `{v}` is not fbo or window"))?;
            }
            "--peers" => {
                let v = value()?;
                args.euc = v.split(',').any(|p| p == "euc");
                args.llvmpipe = v.split(',').any(|p| p == "llvmpipe");
                if !args.euc && !args.llvmpipe {
                    return Err(format!("--peers: `{v}` names neither euc nor llvmpipe"));
                }
            }
            "--child" => {
                let v = value()?;
                if v != "llvmpipe" {
                    return Err(format!("--child: unknown peer `{v}`"));
                }
                args.child = true;
            }
            "-h" | "--help" => {
                return Err(
                    "usage: peers [--runs K] [--sizes 512,1024,2048] [--threads 1,2] \
                     [--rounds R] [--peers euc,llvmpipe] [--gl-target fbo|window] [--msaa] [--json PATH]"
                        .into(),
                );
            }
            _ => return Err(format!("unknown argument `{flag}` (try --help)")),
        }
    }
    if args.runs == 0 || args.rounds == 0 || args.sizes.is_empty() || args.threads.is_empty() {
        return Err("--runs, --rounds, --sizes and --threads must not be 0 or empty".into());
    }
    if let Some(&bad) = args.sizes.iter().find(|&&s| s == 0 || s > 16384) {
        return Err(format!("--sizes: {bad} is not between 1 and 16384"));
    }
    Ok(args)
}
