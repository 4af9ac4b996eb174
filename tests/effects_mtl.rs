//! The effects an OBJ/MTL file calls for, through `hider render` as a user
//! runs it, in a pixel-centre hider (the z-buffer, coloured by the colour
//! pass over its ids) and a colour-resolving one (the A-buffer): smooth
//! shading from `vn`, emission `Ke`, `illum 0`, highlights `Ks`/`Ns`,
//! texture statement options, `d -halo`, and a warning with file and line
//! for what is read but not simulated.

use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh folder for one test's files.
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hider-effects-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `quad.obj` in `dir`: one triangle with texture coordinates across the
/// unit square, of material `m` of `model.mtl`.
fn textured_triangle(dir: &Path) -> PathBuf {
    let model = dir.join("quad.obj");
    std::fs::write(
        &model,
        "mtllib model.mtl\nusemtl m\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n\
         f 1/1 2/2 3/3\n",
    )
    .unwrap();
    model
}

/// A UV sphere of `n` x `n / 2` segments as OBJ text using material
/// `material` of `model.mtl`, with vertex normals (the positions, outward)
/// when `normals`.
fn sphere_obj(n: usize, normals: bool, material: &str) -> String {
    let rings = n / 2;
    let mut obj = format!("mtllib model.mtl\nusemtl {material}\n");
    let mut vertex = |theta: f64, phi: f64| {
        let (x, y, z) = (
            theta.sin() * phi.cos(),
            theta.cos(),
            theta.sin() * phi.sin(),
        );
        obj.push_str(&format!("v {x} {y} {z}\n"));
        if normals {
            obj.push_str(&format!("vn {x} {y} {z}\n"));
        }
    };
    for i in 0..=rings {
        for j in 0..n {
            let theta = std::f64::consts::PI * i as f64 / rings as f64;
            let phi = 2.0 * std::f64::consts::PI * j as f64 / n as f64;
            vertex(theta, phi);
        }
    }
    let at = |i: usize, j: usize| i * n + j % n + 1;
    for i in 0..rings {
        for j in 0..n {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            for [p, q, r] in [[a, c, b], [a, d, c]] {
                if normals {
                    obj.push_str(&format!("f {p}//{p} {q}//{q} {r}//{r}\n"));
                } else {
                    obj.push_str(&format!("f {p} {q} {r}\n"));
                }
            }
        }
    }
    obj
}

/// Renders `model` with `hider render` (`algo`, 64 x 64, extra flags),
/// returning the RGBA pixels and stderr.
fn render(model: &Path, algo: &str, extra: &[&str]) -> (Vec<[u8; 4]>, String) {
    let out = model.with_extension(format!("{algo}.png"));
    let run = Command::new(env!("CARGO_BIN_EXE_hider"))
        .args([
            "render",
            model.to_str().unwrap(),
            "--size",
            "64",
            "--algo",
            algo,
        ])
        .args(extra)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr).into_owned();
    assert!(run.status.success(), "{algo}: {stderr}");
    let image = image::open(&out).unwrap().to_rgba8();
    let pixels = image.pixels().map(|p| p.0).collect();
    (pixels, stderr)
}

/// The covered pixels (not the black background).
fn covered(pixels: &[[u8; 4]]) -> Vec<[u8; 4]> {
    pixels
        .iter()
        .copied()
        .filter(|p| p[..3] != [0, 0, 0])
        .collect()
}

/// Distinct colours among `pixels`.
fn distinct(pixels: &[[u8; 4]]) -> usize {
    let mut v = pixels.to_vec();
    v.sort_unstable();
    v.dedup();
    v.len()
}

const HIDERS: [&str; 2] = ["zbuffer", "abuffer"];

/// With vertex normals a sphere is shaded smoothly: its image differs from
/// the faceted one, with many more distinct shades, and the shades of
/// neighbouring pixels step far less at facet edges.
#[test]
fn vertex_normals_shade_smoothly() {
    let dir = folder("smooth");
    std::fs::write(dir.join("model.mtl"), "newmtl grey\nKd 0.8 0.8 0.8\n").unwrap();
    let smooth = dir.join("smooth.obj");
    let flat = dir.join("flat.obj");
    std::fs::write(&smooth, sphere_obj(12, true, "grey")).unwrap();
    std::fs::write(&flat, sphere_obj(12, false, "grey")).unwrap();
    // Without vn, a smoothing group asks for the same smoothing.
    let grouped = dir.join("grouped.obj");
    std::fs::write(&grouped, format!("s 1\n{}", sphere_obj(12, false, "grey"))).unwrap();
    for algo in HIDERS {
        let (s, _) = render(&smooth, algo, &[]);
        let (f, _) = render(&flat, algo, &[]);
        let (g, _) = render(&grouped, algo, &[]);
        assert_ne!(s, f, "{algo}: vertex normals changed nothing");
        assert_ne!(g, f, "{algo}: the smoothing group changed nothing");
        let (ng, nf) = (distinct(&covered(&g)), distinct(&covered(&f)));
        assert!(
            2 * ng > 3 * nf,
            "{algo}: {ng} shades grouped against {nf} faceted"
        );
        let (ns, nf) = (distinct(&covered(&s)), distinct(&covered(&f)));
        // Faceted, the A-buffer's anti-aliased facet edges add shades too.
        assert!(
            2 * ns > 3 * nf,
            "{algo}: {ns} shades smooth against {nf} faceted"
        );
        // The largest step between horizontal neighbours inside the disc.
        let step = |p: &[[u8; 4]]| {
            (0..64 * 64 - 1)
                .filter(|k| k % 64 != 63 && p[*k][0] > 0 && p[k + 1][0] > 0)
                .map(|k| p[k][0].abs_diff(p[k + 1][0]))
                .max()
                .unwrap()
        };
        assert!(
            step(&s) < step(&f),
            "{algo}: smooth step {} against faceted {}",
            step(&s),
            step(&f)
        );
    }
}

/// `Ke` is added whatever the light: a black, emitting material shows its
/// emission; `illum 0` shows the diffuse colour unlit, the same on every
/// pixel whatever the facet's angle.
#[test]
fn emission_and_unlit_materials() {
    let dir = folder("emission");
    std::fs::write(
        dir.join("model.mtl"),
        "newmtl glow\nKd 0 0 0\nKe 1 0 0\n\nnewmtl flat\nKd 0.5 0.5 0.5\nillum 0\n",
    )
    .unwrap();
    let glow = dir.join("glow.obj");
    let flat = dir.join("flat.obj");
    std::fs::write(&glow, sphere_obj(12, false, "glow")).unwrap();
    std::fs::write(&flat, sphere_obj(12, false, "flat")).unwrap();
    for algo in HIDERS {
        let (g, _) = render(&glow, algo, &[]);
        let lit = covered(&g);
        assert!(lit.len() > 400, "{algo}: {} pixels", lit.len());
        // Interior pixels (full coverage in the A-buffer) are pure red.
        let red = lit.iter().filter(|p| p[..3] == [255, 0, 0]).count();
        assert!(
            red * 10 > lit.len() * 7,
            "{algo}: {red} of {} red",
            lit.len()
        );
        assert!(lit.iter().all(|p| p[1] == 0 && p[2] == 0), "{algo}");
        let (f, _) = render(&flat, algo, &[]);
        let grey = covered(&f);
        let mid = grey.iter().filter(|p| p[..3] == [188, 188, 188]).count();
        assert!(
            mid * 10 > grey.len() * 7,
            "{algo}: {mid} of {} unlit",
            grey.len()
        );
    }
}

/// `illum 2` with `Ks` and `Ns` and vertex normals: a highlight where the
/// normal is halfway between the head light and the eye (the middle of the
/// sphere), brighter than the same material under `illum 1`.
#[test]
fn highlights_follow_ks_and_ns() {
    let dir = folder("specular");
    std::fs::write(
        dir.join("model.mtl"),
        "newmtl shiny\nKd 0.3 0.3 0.6\nKs 1 1 1\nNs 60\nillum 2\n\n\
         newmtl matte\nKd 0.3 0.3 0.6\nKs 1 1 1\nNs 60\nillum 1\n",
    )
    .unwrap();
    let shiny = dir.join("shiny.obj");
    let matte = dir.join("matte.obj");
    std::fs::write(&shiny, sphere_obj(24, true, "shiny")).unwrap();
    std::fs::write(&matte, sphere_obj(24, true, "matte")).unwrap();
    for algo in HIDERS {
        let (s, _) = render(&shiny, algo, &[]);
        let (m, _) = render(&matte, algo, &[]);
        let centre = |p: &[[u8; 4]]| p[32 * 64 + 32];
        assert!(
            centre(&s)[0] > centre(&m)[0] + 60,
            "{algo}: highlight {:?} against {:?}",
            centre(&s),
            centre(&m)
        );
        // Near the rim the highlight is gone: the same colour within a step.
        let rim = |p: &[[u8; 4]]| (0..64).map(|x| p[32 * 64 + x]).find(|c| c[2] > 0).unwrap();
        assert!(
            rim(&s)[2].abs_diff(rim(&m)[2]) <= 2,
            "{algo}: {:?} {:?}",
            rim(&s),
            rim(&m)
        );
    }
}

/// A checkered quad with texture statement options: `-s 2 2` repeats the
/// image twice (twice the transitions along a row), `-o` shifts it, and
/// none of them is taken for part of the file name.
#[test]
fn texture_statement_options_are_read_and_applied() {
    let dir = folder("texopts");
    std::fs::copy(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/checker.png"),
        dir.join("checker.png"),
    )
    .unwrap();
    let quad = "mtllib model.mtl\nusemtl m\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n\
                vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
    let model = dir.join("quad.obj");
    std::fs::write(&model, quad).unwrap();
    let run = |statement: &str| {
        std::fs::write(
            dir.join("model.mtl"),
            format!("newmtl m\nKd 1 1 1\nillum 0\nmap_Kd {statement}\n"),
        )
        .unwrap();
        render(&model, "zbuffer", &["--eye", "0,0,2.4"])
    };
    let transitions = |p: &[[u8; 4]]| {
        (0..63)
            .filter(|&x| (p[32 * 64 + x][0] > 128) != (p[32 * 64 + x + 1][0] > 128))
            .count()
    };
    let (plain, e) = run("checker.png");
    assert!(!e.contains("not found"), "{e}");
    let (scaled, e) = run("-s 2 2 1 checker.png");
    assert!(!e.contains("not found") && !e.contains("warning"), "{e}");
    let (clamped, e) = run("-clamp on -o 0.0625 0 checker.png");
    assert!(!e.contains("not found"), "{e}");
    let (t1, t2) = (transitions(&plain), transitions(&scaled));
    assert!(t1 >= 6, "{t1} transitions");
    assert!(t2 >= 2 * t1 - 2, "-s 2: {t2} transitions against {t1}");
    assert_ne!(clamped, plain, "-o moved nothing");
    let (_, e) = run("-blendu off checker.png");
    assert!(
        e.contains("model.mtl:4: map_Kd option -blendu is read but not simulated"),
        "{e}"
    );
}

/// `d -halo 0.5` is read as the dissolve: the material keeps its `Kd` (it
/// fell back to the default grey), and the halo is named in a warning.
#[test]
fn dissolve_halo_keeps_the_material() {
    let dir = folder("halo");
    std::fs::write(
        dir.join("model.mtl"),
        "newmtl red\nKd 1 0 0\nd -halo 1.0\nNi 1.5\n",
    )
    .unwrap();
    let model = dir.join("red.obj");
    std::fs::write(&model, sphere_obj(12, false, "red")).unwrap();
    let (p, e) = render(&model, "zbuffer", &[]);
    let lit = covered(&p);
    assert!(
        lit.iter().all(|c| c[1] == 0 && c[2] == 0 && c[0] > 0),
        "not red"
    );
    assert!(e.contains("model.mtl:3: 'd -halo'"), "{e}");
    assert!(
        e.contains("model.mtl:4: 'Ni' is read but not simulated"),
        "{e}"
    );
    assert!(!e.contains("default material"), "{e}");
}

/// Vertex colours (`v x y z r g b`) are the diffuse colour, interpolated:
/// a quad with a red, a green, a blue and a white corner shows each near
/// its corner, in both hiders (it rendered uniform grey).
#[test]
fn vertex_colours_show() {
    let dir = folder("vcolors");
    let model = dir.join("quad.obj");
    std::fs::write(
        &model,
        "v -1 -1 0 1 0 0\nv 1 -1 0 0 1 0\nv 1 1 0 0 0 1\nv -1 1 0 1 1 1\nf 1 2 3\nf 1 3 4\n",
    )
    .unwrap();
    for algo in HIDERS {
        let (p, e) = render(&model, algo, &["--eye", "0,0,2.4"]);
        assert!(!e.contains("colours"), "{e}");
        // Near the bottom-left corner (window y down): red; bottom-right:
        // green; top-right: blue.
        let at = |x: usize, y: usize| p[y * 64 + x];
        let (red, green, blue) = (at(13, 50), at(50, 50), at(50, 13));
        assert!(red[0] > 2 * red[1].max(red[2]), "{algo}: {red:?}");
        assert!(green[1] > 2 * green[0].max(green[2]), "{algo}: {green:?}");
        assert!(blue[2] > 2 * blue[0].max(blue[1]), "{algo}: {blue:?}");
    }
}

/// Faces of one object with and without `vt` each keep what they have:
/// the faces with uvs are textured (all uvs were dropped and nothing was
/// textured), the others take the material's colour, and the primitive
/// ids stay in file order.
#[test]
fn partly_textured_objects_keep_their_uvs() {
    let dir = folder("mixedvt");
    std::fs::copy(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/checker.png"),
        dir.join("checker.png"),
    )
    .unwrap();
    std::fs::write(
        dir.join("model.mtl"),
        "newmtl m\nKd 1 0.5 0.5\nillum 0\nmap_Kd checker.png\n",
    )
    .unwrap();
    let model = dir.join("mixed.obj");
    // Left half textured (two faces with vt), right half not (one face
    // without), in one object.
    std::fs::write(
        &model,
        "mtllib model.mtl\no mixed\nusemtl m\nv -1 -1 0\nv 0 -1 0\nv 0 1 0\nv -1 1 0\nv 1 -1 0\n\
         v 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\nf 2 5 6\n",
    )
    .unwrap();
    let ids = dir.join("mixed.i32");
    let (p, e) = render(
        &model,
        "zbuffer",
        &["--eye", "0,0,2.4", "--ids-out", ids.to_str().unwrap()],
    );
    assert!(!e.contains("some faces have"), "{e}");
    let row = |y: usize| -> Vec<[u8; 4]> { (0..64).map(|x| p[y * 64 + x]).collect() };
    // The textured left half shows the checker's light and dark squares
    // (times Kd); the right half's one face is flat.
    let left: Vec<[u8; 4]> = row(20)[12..30].to_vec();
    assert!(distinct(&left) >= 2, "left half not textured: {left:?}");
    let right = [p[40 * 64 + 50]];
    assert!(right[0][0] > right[0][1], "{right:?}");
    // Ids in file order: 0 and 1 on the left, 2 on the right.
    let dump = std::fs::read(&ids).unwrap();
    let id = |x: usize, y: usize| {
        let k = 4 * (y * 64 + x);
        i32::from_le_bytes([dump[k], dump[k + 1], dump[k + 2], dump[k + 3]])
    };
    assert!([0, 1].contains(&id(20, 32)), "{}", id(20, 32));
    assert_eq!(id(50, 40), 2);
}

/// A texture that cannot be decoded (a text file named `.png`) is named in
/// a warning by the default render too (only `analyze` named it), and the
/// material's colour is used.
#[test]
fn an_undecodable_texture_is_named() {
    let dir = folder("badtex");
    std::fs::write(dir.join("fake.png"), "not an image at all").unwrap();
    std::fs::write(
        dir.join("model.mtl"),
        "newmtl m\nKd 0 1 0\nmap_Kd fake.png\n",
    )
    .unwrap();
    let model = textured_triangle(&dir);
    for algo in ["auto", "zbuffer", "abuffer"] {
        let (p, e) = render(&model, algo, &[]);
        assert!(
            e.contains("fake.png") && e.contains("the material's colour is used"),
            "{algo}: {e}"
        );
        assert!(
            covered(&p).iter().all(|c| c[1] > 0 && c[0] == 0),
            "{algo}: not green"
        );
    }
}

/// A missing texture is named once, whatever statement names it (`map_d`
/// was silent), with what is drawn instead; one that does not decode is
/// named with the material value used for its statement.
#[test]
fn every_missing_or_broken_texture_is_named_once() {
    let dir = folder("missingtex");
    std::fs::write(dir.join("fake.png"), "not an image at all").unwrap();
    let model = textured_triangle(&dir);
    for (statement, used) in [
        ("map_Kd", "diffuse colour (Kd) is used"),
        ("map_Ks", "specular colour (Ks) is used"),
        ("map_d", "opacity (d) is used"),
    ] {
        let mtl = format!("newmtl m\nKd 0 1 0\nKs 0.5 0.5 0.5\nNs 20\n{statement} gone.png\n");
        std::fs::write(dir.join("model.mtl"), mtl).unwrap();
        let (_, e) = render(&model, "auto", &[]);
        let named = e.lines().filter(|l| l.contains("gone.png")).count();
        assert_eq!(named, 1, "{statement}: {e}");
        assert!(
            e.contains(&format!("({statement}) not found")) && e.contains(used),
            "{e}"
        );
    }
    let mtl = "newmtl m\nKd 0 1 0\nmap_d fake.png\n";
    std::fs::write(dir.join("model.mtl"), mtl).unwrap();
    let (_, e) = render(&model, "auto", &[]);
    assert!(
        e.contains("fake.png") && e.contains("the material's opacity is used"),
        "{e}"
    );
}

/// An RGBA texture with transparent texels (a leaf card's cut-out) is not
/// drawn with its alpha yet: the render says so instead of showing a
/// white square without a word.
#[test]
fn a_cut_out_texture_shows_what_is_behind_it() {
    let dir = folder("cutout");
    let mut leaf = image::RgbaImage::new(16, 16);
    for (x, y, p) in leaf.enumerate_pixels_mut() {
        let inside = (x as i32 - 8).pow(2) + (y as i32 - 8).pow(2) < 36;
        *p = image::Rgba([40, 160, 40, if inside { 255 } else { 0 }]);
    }
    leaf.save(dir.join("leaf.png")).unwrap();
    std::fs::write(
        dir.join("model.mtl"),
        "newmtl m\nKd 1 1 1\nmap_Kd leaf.png\n",
    )
    .unwrap();
    let model = textured_triangle(&dir);
    let (cut, e) = render(&model, "auto", &[]);
    // No more "drawn opaque": the texels outside the disc (alpha 0, the
    // same green) are cut out and show the background; the triangle holds
    // half the disc, 0.44 of its area.
    assert!(!e.contains("not simulated"), "{e}");
    assert!(e.contains("cut-out pixels replaced"), "{e}");
    std::fs::write(dir.join("plain.mtl"), "newmtl m\nKd 1 1 1\n").unwrap();
    let plain = dir.join("plain.obj");
    let text = std::fs::read_to_string(&model).unwrap();
    std::fs::write(&plain, text.replace("model.mtl", "plain.mtl")).unwrap();
    let (whole, _) = render(&plain, "auto", &[]);
    let covered = |p: &[[u8; 4]]| {
        p.iter()
            .filter(|c| c[..3] != hider::scene::frame::BACKGROUND[..3])
            .count() as f64
    };
    let ratio = covered(&cut) / covered(&whole);
    assert!((0.3..0.6).contains(&ratio), "{ratio}");
}
