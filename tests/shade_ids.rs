//! `--shade ids` gives an id-coloured image in every hider: the colour
//! pass for the hiders that only write ids, the hider's own shade mode for
//! those that resolve colour (the A-buffers, supersampling and
//! anti-aliased Warnock ignored it and drew the Lambert image).

use std::path::Path;
use std::process::Command;

fn pixels(png: &Path) -> Vec<[u8; 4]> {
    image::open(png)
        .unwrap()
        .to_rgba8()
        .pixels()
        .map(|p| p.0)
        .collect()
}

fn render(algo: &str, shade: &str, out: &Path) -> Vec<[u8; 4]> {
    let run = Command::new(env!("CARGO_BIN_EXE_hider"))
        .args([
            "render", "gen:cube", "--size", "32", "--algo", algo, "--shade", shade,
        ])
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{algo}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    pixels(out)
}

#[test]
fn every_hider_colours_by_id_when_asked() {
    let dir = std::env::temp_dir().join(format!("hider-shade-ids-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let list = Command::new(env!("CARGO_BIN_EXE_hider"))
        .arg("list")
        .output()
        .unwrap();
    let names: Vec<String> = String::from_utf8_lossy(&list.stdout)
        .lines()
        .filter_map(|l| l.split_whitespace().next().map(str::to_owned))
        .collect();
    assert!(names.len() >= 20, "{names:?}");
    let out = dir.join("out.png");
    let reference = render("zbuffer", "ids", &out);
    for name in &names {
        let ids = render(name, "ids", &out);
        let lambert = render(name, "lambert", &out);
        assert_ne!(ids, lambert, "{name}: --shade ids drew the Lambert image");
        // Where the z-buffer's id image and this one agree on coverage,
        // most pixels carry the same id colour (edges of anti-aliased
        // hiders blend, approximate hiders may pick another face).
        let same = ids.iter().zip(&reference).filter(|(a, b)| a == b).count();
        assert!(
            same * 10 >= ids.len() * 8,
            "{name}: {same} of {} pixels match the z-buffer's id image",
            ids.len()
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
