//! The fast OBJ reader against tobj, the loader of record: every OBJ file
//! of the repository (and assimp's test models when they are on disk:
//! `HIDER_ASSIMP_MODELS=/path/to/assimp/test/models`), generated files
//! using every statement kind with malformed lines among them, and a file
//! of many chunks must give the same scene — or the same error — both
//! ways.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use hider_scene::obj::{ObjOptions, ObjParser, ObjStats, load_obj_stats};

/// The outcome of loading `path` with `parser`: the scene (its debug
/// form, which tells every float apart, NaN included) and how it was
/// read, or the error's message.
fn outcome(path: &Path, parser: ObjParser) -> Result<(String, ObjStats), String> {
    let options = ObjOptions {
        parser,
        ..ObjOptions::default()
    };
    load_obj_stats(path, &options)
        .map(|(scene, stats)| (format!("{scene:?}"), stats))
        .map_err(|e| e.to_string())
}

/// Loads `path` both ways, requires the same outcome, and returns whether
/// the fast reader read it (and the reason when it did not).
fn same_both_ways(path: &Path) -> Result<(), String> {
    let fast = outcome(path, ObjParser::Fast);
    let tobj = outcome(path, ObjParser::Tobj);
    match (&fast, &tobj) {
        (Ok((a, stats)), Ok((b, _))) => {
            assert!(
                a == b,
                "{}: the scenes differ (fast: {})\nfast: {a}\ntobj: {b}",
                path.display(),
                stats.fast
            );
            match stats.fast {
                true => Ok(()),
                false => Err(stats.fallback.clone().unwrap_or_default()),
            }
        }
        (Err(a), Err(b)) => {
            assert_eq!(a, b, "{}: the errors differ", path.display());
            Err(format!("error: {a}"))
        }
        _ => panic!(
            "{}: one reader failed\nfast: {fast:?}\ntobj: {tobj:?}",
            path.display()
        ),
    }
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The `.obj` files under `dir`, at any depth.
fn obj_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            obj_files(&path, out);
        } else if path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("obj"))
        {
            out.push(path);
        }
    }
}

#[test]
fn every_obj_of_the_repository_loads_the_same_both_ways() {
    let root = root();
    let mut files = Vec::new();
    for dir in ["assets", "tests/data"] {
        obj_files(&root.join(dir), &mut files);
    }
    for krate in std::fs::read_dir(root.join("crates")).unwrap().flatten() {
        obj_files(&krate.path().join("tests"), &mut files);
    }
    let repository = files.len();
    if let Some(dir) = std::env::var_os("HIDER_ASSIMP_MODELS") {
        obj_files(Path::new(&dir), &mut files);
    }
    assert!(repository >= 10, "the repository's OBJ files: {files:?}");
    let mut fast = 0;
    for path in &files {
        match same_both_ways(path) {
            Ok(()) => {
                eprintln!("{}: read fast", path.display());
                fast += 1;
            }
            Err(why) => eprintln!("{}: tobj read it: {why}", path.display()),
        }
    }
    eprintln!("{fast} of {} files read by the fast reader", files.len());
    // The bundled spider, cube and sphere are plain files.
    assert!(fast >= 3, "{fast}");
}

/// A small generator of OBJ lines (a fixed linear congruential sequence).
struct Gen(u64);

impl Gen {
    fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        self.0 >> 33
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len() as u64) as usize]
    }

    /// A number, now and then in a form the fast reader leaves to tobj or
    /// that is not a number at all.
    fn number(&mut self) -> String {
        match self.below(200) {
            0 => self
                .pick(&["nan", "inf", "1e400", "abc", "1,5", "-", "0x1"])
                .into(),
            1..=5 => self
                .pick(&["+2.", ".25", "-.5e1", "1.5E+2", "00012", "-0"])
                .into(),
            6..=10 => "0.30000000000000004".into(),
            11 => "123456789012345678901234".into(),
            _ => format!("{}", (self.below(2001) as f64 - 1000.0) / 256.0),
        }
    }

    /// An index into `n` items defined so far, 1-based or counting back,
    /// now and then out of range.
    fn index(&mut self, n: u64) -> String {
        match self.below(600) {
            0 => "0".into(),
            1 => format!("{}", n + 1),
            2 => format!("-{}", n + 1),
            _ if n == 0 => "1".into(),
            k if k < 150 => format!("-{}", 1 + self.below(n)),
            _ => format!("{}", 1 + self.below(n)),
        }
    }

    /// One statement (or a few) of a generated file.
    fn statement(&mut self, counts: &mut [u64; 3], out: &mut String) {
        let sep = match self.below(60) {
            0..=2 => "\t",
            3..=5 => "  ",
            6 => "\u{a0}",
            7 => "\x0b",
            _ => " ",
        };
        let lead = match self.below(25) {
            0 => " ",
            1 => "\t",
            _ => "",
        };
        match self.below(100) {
            0..=29 => {
                let n = match self.below(60) {
                    0..=2 => 4,
                    3 => 6,
                    4 => 2,
                    _ => 3,
                };
                let values: Vec<String> = (0..n)
                    .map(|k| match (n, k) {
                        (4, 3) => self.pick(&["1", "2", "0", "0.5"]).to_owned(),
                        _ => self.number(),
                    })
                    .collect();
                let _ = write!(out, "{lead}v{sep}{}", values.join(sep));
                counts[0] += 1;
            }
            30..=37 => {
                let n = 1 + self.below(3);
                let values: Vec<String> = (0..n).map(|_| self.number()).collect();
                let _ = write!(out, "{lead}vt {}", values.join(sep));
                counts[1] += 1;
            }
            38..=45 => {
                let n = if self.below(80) == 0 { 2 } else { 3 };
                let values: Vec<String> = (0..n).map(|_| self.number()).collect();
                let _ = write!(out, "{lead}vn {}", values.join(" "));
                counts[2] += 1;
            }
            46..=69 => {
                let n = match self.below(80) {
                    0 => 2,
                    1..=8 => 5,
                    9..=12 => 7,
                    _ => 3,
                };
                let layout = self.below(5);
                let mixed = self.below(80) == 0;
                let mut words = Vec::new();
                for k in 0..n {
                    let layout = if mixed && k == 1 {
                        (layout + 1) % 5
                    } else {
                        layout
                    };
                    let v = self.index(counts[0]);
                    let word = match layout {
                        0 => v,
                        1 => format!("{v}/{}", self.index(counts[1])),
                        2 => format!("{v}//{}", self.index(counts[2])),
                        3 => format!("{v}/{}/{}", self.index(counts[1]), self.index(counts[2])),
                        _ => format!("{v}/"),
                    };
                    words.push(word);
                }
                let _ = write!(out, "{lead}f{sep}{}", words.join(" "));
            }
            70..=75 => {
                let key = self.pick(&["o", "g"]);
                let name = self.pick(&["a", "b c", "", "caf\u{e9}", "  padded  ", "a"]);
                let lead = if self.below(8) == 0 { " " } else { "" };
                let _ = write!(out, "{lead}{key} {name}");
            }
            76..=79 => {
                let group = self.pick(&["1", "2", "off", "0", "", "3 4", "on"]);
                let _ = write!(out, "{lead}s {group}");
            }
            80..=85 => {
                let name = self.pick(&["red", "blue", "none", "", "red ", "\tred", "blue"]);
                let _ = write!(out, "usemtl {name}");
            }
            86..=87 => {
                let file = self.pick(&["m.mtl", "missing.mtl", "m.mtl", "sub dir/n.mtl"]);
                let _ = write!(out, "mtllib {file}");
            }
            88..=92 => {
                let text = self.pick(&["# a comment", "#x", "# caf\u{e9} \u{a0}", "", "   "]);
                out.push_str(text);
            }
            _ if self.below(4) > 0 => out.push_str("# filler"),
            _ => {
                let text = self.pick(&[
                    "l 1 2 3",
                    "p 1",
                    "vp 0.5",
                    "cstype bezier",
                    "foo bar",
                    "bevel on",
                    "usemap x",
                ]);
                out.push_str(text);
            }
        }
        out.push('\n');
    }

    /// A whole file: a few positions first (so that most faces resolve),
    /// then statements of every kind; line ends LF, CR LF, or now and then
    /// a lone CR; now and then a byte-order mark or a byte that is not
    /// UTF-8.
    fn file(&mut self, statements: usize) -> Vec<u8> {
        let mut counts = [0u64; 3];
        let mut text = String::new();
        for k in 0..4 {
            let _ = writeln!(text, "v {k} {} 0", k % 2);
            counts[0] += 1;
        }
        text.push_str("vt 0 0\nvt 1 0\nvn 0 0 1\n");
        counts[1] += 2;
        counts[2] += 1;
        for _ in 0..statements {
            self.statement(&mut counts, &mut text);
        }
        let mut bytes = match self.below(8) {
            0 => text.replace('\n', "\r\n").into_bytes(),
            1 => text
                .split('\n')
                .map(|line| match self.below(6) {
                    0 => format!("{line}\r"),
                    _ => format!("{line}\n"),
                })
                .collect::<String>()
                .into_bytes(),
            _ => text.into_bytes(),
        };
        match self.below(20) {
            0 => bytes.splice(0..0, [0xEF, 0xBB, 0xBF]).for_each(drop),
            1 => {
                let at = self.below(bytes.len() as u64) as usize;
                bytes.insert(at, 0xE9);
            }
            _ => {}
        }
        bytes
    }
}

/// A fresh folder with the MTL files the generated files name.
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hider-fast-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("sub dir")).unwrap();
    std::fs::write(
        dir.join("m.mtl"),
        "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\nmap_Kd nothere.png\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("sub dir/n.mtl"),
        "newmtl red\nKd 0.5 0 0\nNi 1.5\n",
    )
    .unwrap();
    dir
}

#[test]
fn generated_files_with_every_statement_kind_load_the_same_both_ways() {
    let dir = folder("gen");
    let mut g = Gen(40);
    let (mut fast, mut errors, mut total) = (0, 0, 0);
    for k in 0..400 {
        // Mostly short files, where one odd line matters, and some long
        // ones.
        let statements = if k % 10 == 0 { 200 } else { 1 + k % 12 };
        let path = dir.join(format!("gen-{k}.obj"));
        std::fs::write(&path, g.file(statements)).unwrap();
        total += 1;
        match same_both_ways(&path) {
            Ok(()) => fast += 1,
            Err(why) if why.starts_with("error:") => errors += 1,
            Err(_) => {}
        }
    }
    eprintln!("{fast} of {total} read fast, {errors} errors");
    // Both readers were exercised, and the errors compared.
    assert!(fast >= total / 5, "{fast} of {total}");
    assert!(total - fast >= total / 5, "{fast} of {total}");
    assert!(errors >= total / 20, "{errors} of {total}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_file_of_many_chunks_loads_the_same_both_ways() {
    // About 4 MB: objects, materials, smoothing groups and face layouts
    // change across the chunk boundaries; faces count back across them.
    let dir = folder("chunks");
    let mut text = String::from("mtllib m.mtl\n");
    let mut g = Gen(7);
    let (mut nv, mut nvt, mut nvn) = (0u64, 0u64, 0u64);
    for block in 0..3000 {
        if block % 7 == 0 {
            let _ = writeln!(text, "o part {}", block / 7 % 5);
        }
        if block % 5 == 0 {
            let _ = writeln!(text, "usemtl {}", ["red", "blue", "none"][block % 3]);
        }
        if block % 11 == 0 {
            let _ = writeln!(text, "s {}", block % 4);
        }
        for _ in 0..20 {
            let [x, y, z] = [0, 1, 2].map(|_| (g.below(100_000) as f64 - 5e4) / 997.0);
            let _ = writeln!(text, "v {x} {y} {z:e}");
            let _ = writeln!(text, "vt {} {}", g.below(1000) as f64 / 1e3, 0.5);
            let _ = writeln!(text, "vn 0 0 1");
            (nv, nvt, nvn) = (nv + 1, nvt + 1, nvn + 1);
        }
        for _ in 0..20 {
            let (a, b, c) = (1 + g.below(nv), 1 + g.below(nv.min(30)), 1 + g.below(nv));
            let _ = match block % 4 {
                0 => writeln!(text, "f {a} -{b} {c}"),
                1 => writeln!(text, "f {a}/{a} -{b}/-{b} {c}/{c}"),
                2 => writeln!(text, "f {a}//{nvn} -{b}//-1 {c}//1 {a}//-2"),
                _ => writeln!(text, "f {a}/{nvt}/1 -{b}/-{b}/-1 {c}/1/{nvn}"),
            };
        }
    }
    let path = dir.join("chunks.obj");
    std::fs::write(&path, &text).unwrap();
    assert!(text.len() > 3 << 20, "{}", text.len());
    same_both_ways(&path).unwrap_or_else(|why| panic!("not read fast: {why}"));
    let (_, stats) = outcome(&path, ObjParser::Fast).unwrap();
    assert!(stats.chunks >= 3, "{stats:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn tricky_lines_load_the_same_both_ways() {
    let dir = folder("tricky");
    let four = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvn 0 0 1\n";
    for (k, tail) in [
        // A lone CR ends a comment: the line after it is a statement.
        "# c\rv 9 9 9\nf -1 1 2\n",
        "o a\rv 9 9 9\nf -1 1 2\n",
        // A name after blanks: tobj keeps the keyword in it, and the
        // split of an object whose faces change layout renames it.
        " o a\nf 1 2 3\nf 1/1 2/1 3/1\n",
        "\tg a b\nf 1 2 3\n",
        // Layout changes across usemtl and objects.
        "mtllib m.mtl\no a\nusemtl red\nf 1//1 2//1 3//1\nusemtl blue\nf 1 2 3\ng a\nf 2 3 4\n",
        "usemtl red\nf 1 2 3\nmtllib m.mtl\nusemtl red\nf 1 2 3\nusemtl none\nf 2 3 4\n",
        "mtllib m.mtl\nmtllib sub dir/n.mtl\nusemtl red\nf 1 2 3\no\n",
        // Smoothing groups with and without normals; names of groups.
        "s 1\nf 1 2 3\ns off\nf 2 3 4\ns 2\nf 1 3 4\n",
        "s 1\nf 1//1 2//1 3//1\ns 2\nf 2 3 4\n",
        // Numbers and indices in the forms exporters write.
        "v +1. -.5e1 1E2\nv 1 2 3 2\nvt 0.5\nvt 0.25 0.75 1\nvn 1 0 0 extra\nf -1/-1/-1 -2/-2/-1 3/1/1\n",
        "f 1/ 2/ 3/\nf 1/1/1 2/1/1 3/1/1 4/1/1\n",
        // Blanks of every kind, a UTF-8 name, a stray byte in a comment.
        "\x0bv\x0c1\t2  3\no caf\u{e9} \u{a0}\nf 1 2 3\n# \u{a0}\n",
    ]
    .iter()
    .enumerate()
    {
        let path = dir.join(format!("tricky-{k}.obj"));
        std::fs::write(&path, format!("{four}{tail}")).unwrap();
        if let Err(why) = same_both_ways(&path) {
            eprintln!("{tail:?}: tobj read it: {why}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn lines_and_points_are_skipped_by_both_readers_alike() {
    let dir = folder("elements");
    let path = dir.join("elements.obj");
    std::fs::write(
        &path,
        "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\nf 1 2 3\np 1 2\nl 1 x\nf 1 1 2\n",
    )
    .unwrap();
    same_both_ways(&path).unwrap_or_else(|why| panic!("not read fast: {why}"));
    let (scene, _) = outcome(&path, ObjParser::Fast).unwrap();
    assert!(
        scene.contains("skipped 2 line elements ('l') and 1 point element ('p')"),
        "{scene}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn malformed_files_fail_with_the_same_error_both_ways() {
    let dir = folder("bad");
    let good = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (k, tail) in [
        "f 1 2 4\n",
        "f 1 2\n",
        "f 0 1 2\n",
        "f -4 1 2\n",
        "f 1/1 2 3\n",
        "f 1//1 2//1 3//1\n",
        "v 1 nan 0\nf 1 2 3\n",
        "v 1 zero 0\n",
        "v 1 2\n",
        "v 1 2 3 0\nf 1 2 3\n",
        "vt 0.5 abc\nf 1 2 3\n",
        "vn 0 0\n",
        "usemtl\tred\nf 1 2 3\n",
        "",
        "# only a comment\n",
        "l 1 2 3\n",
        "f 1 2 3 # a comment\n",
    ]
    .iter()
    .enumerate()
    {
        let path = dir.join(format!("bad-{k}.obj"));
        std::fs::write(&path, format!("{good}{tail}")).unwrap();
        let fast = outcome(&path, ObjParser::Fast).map(|(s, _)| s);
        let tobj = outcome(&path, ObjParser::Tobj).map(|(s, _)| s);
        assert_eq!(fast, tobj, "{tail:?}");
    }
    // The triangle limit, refused before the meshes are built.
    let path = dir.join("limit.obj");
    std::fs::write(&path, format!("{good}f 1 2 3\nf 1 2 3\n")).unwrap();
    for parser in [ObjParser::Fast, ObjParser::Tobj] {
        let options = ObjOptions {
            max_triangles: 1,
            parser,
            ..ObjOptions::default()
        };
        let e = load_obj_stats(&path, &options).unwrap_err().to_string();
        assert_eq!(e, "triangle count 2 is over the limit of 1", "{parser:?}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
