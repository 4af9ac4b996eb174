use std::path::PathBuf;

use super::*;

fn load(text: &str) -> Result<Scene> {
    load_obj_bytes(
        text.as_bytes(),
        Path::new("test.obj"),
        Path::new("/nonexistent"),
        &ObjOptions::default(),
    )
}

#[test]
fn quad_is_fan_split_in_file_order() {
    let s = load("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 2 3\n").unwrap();
    assert_eq!(s.triangle_count(), 3);
    let tris: Vec<_> = s
        .triangles()
        .map(|(_, m, t)| s.triangle_positions(m, t))
        .collect();
    let p = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    assert_eq!(tris[0], [p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)]);
    assert_eq!(tris[1], [p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)]);
}

#[test]
fn crlf_tabs_and_stray_bytes_load() {
    let mut bytes = b"# caf\xe9 \xff comment\r\nv\t0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\no na\xefme\r\nf 1//\t2// 3//\r\n".to_vec();
    // The face above uses "1//" without normals; make it plain indices.
    bytes = String::from_utf8_lossy(&bytes)
        .replace("1//\t2// 3//", "1\t2 3")
        .into_bytes();
    bytes.extend_from_slice(b"f -3 -2 -1\r\n");
    let s = load_obj_bytes(
        &bytes,
        Path::new("x.obj"),
        Path::new("."),
        &ObjOptions::default(),
    )
    .unwrap();
    assert_eq!(s.triangle_count(), 2);
}

#[test]
fn missing_mtl_is_a_warning() {
    let s = load("mtllib nothere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl x\nf 1 2 3\n").unwrap();
    assert_eq!(s.triangle_count(), 1);
    assert!(
        s.warnings.iter().any(|w| w.contains("nothere.mtl")),
        "{:?}",
        s.warnings
    );
    assert_eq!(s.meshes[0].material, None);
}

#[test]
fn errors_name_file_and_line() {
    let e = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("test.obj:4:") && e.contains("index 4"), "{e}");
    let e = load("v 0 0 0\nv 1 nan 0\n").unwrap_err().to_string();
    assert!(e.starts_with("test.obj:2:") && e.contains("NaN"), "{e}");
    let e = load("v 0 0 0\nv 1 zero 0\n").unwrap_err().to_string();
    assert!(e.contains(":2:") && e.contains("'zero'"), "{e}");
    let e = load("v 0 0 0\nv 1 0 0\nf 1 2\n").unwrap_err().to_string();
    assert!(e.contains(":3:") && e.contains("2 vertices"), "{e}");
    let e = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains(":4:") && e.contains("index 0"), "{e}");
    let e = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains(":4:") && e.contains("-4"), "{e}");
}

#[test]
fn triangle_limit_is_checked_before_loading() {
    let opts = ObjOptions {
        max_triangles: 1,
        ..ObjOptions::default()
    };
    let e = load_obj_bytes(
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 3\n",
        Path::new("big.obj"),
        Path::new("."),
        &opts,
    )
    .unwrap_err();
    assert!(matches!(
        e,
        Error::Limit {
            value: 2,
            limit: 1,
            ..
        }
    ));
}

#[test]
fn mtl_with_windows_texture_path_and_opacity() {
    let dir = std::env::temp_dir().join(format!("hider-obj-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("m.mtl"),
        "newmtl glass\r\nKd 0.1 0.2 0.3\r\nd 0.25\r\nmap_Kd .\\tex\\a.jpg\r\nnewmtl tr\nTr 0.75\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("m.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl glass\nf 1 2 3\nusemtl tr\nf 1 3 2\n",
    )
    .unwrap();
    let s = load_obj(dir.join("m.obj")).unwrap();
    let glass = &s.materials[s.meshes[0].material.unwrap()];
    assert_eq!(glass.diffuse, [0.1, 0.2, 0.3]);
    assert_eq!(glass.opacity, 0.25);
    assert_eq!(glass.diffuse_texture, Some(dir.join("tex/a.jpg").into()));
    assert!(
        s.warnings
            .iter()
            .any(|w| w.contains("tex/a.jpg") && w.contains("glass")),
        "{:?}",
        s.warnings
    );
    let tr = &s.materials[s.meshes[1].material.unwrap()];
    assert_eq!(tr.opacity, 0.25);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn degenerate_faces_and_missing_textures_are_warnings() {
    let s = load("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 4\nf 1 2 4\n").unwrap();
    assert_eq!(s.triangle_count(), 3, "degenerate triangles keep their ids");
    assert!(
        s.warnings.iter().any(|w| w.starts_with("2 degenerate")),
        "{:?}",
        s.warnings
    );
    let e = load("v 0 0 0\nv 1 0 0\n").unwrap_err().to_string();
    assert!(e.contains("no faces"), "{e}");
}

#[test]
fn file_size_limit_is_checked_before_reading() {
    let dir = std::env::temp_dir().join(format!("hider-objsize-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("big.obj");
    std::fs::write(&p, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let opts = ObjOptions {
        max_file_bytes: 10,
        ..ObjOptions::default()
    };
    let e = load_obj_with(&p, &opts).unwrap_err();
    assert!(matches!(e, Error::Limit { limit: 10, .. }), "{e}");
    let e = load_obj(&dir).unwrap_err().to_string();
    assert!(e.contains("folder"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn missing_file_names_the_path() {
    let e = load_obj("/definitely/not/here.obj")
        .unwrap_err()
        .to_string();
    assert!(e.contains("/definitely/not/here.obj"), "{e}");
}

/// A quad (two triangles) with a polyline and points among the faces, as
/// assimp-based tools accept them.
const WITH_LINES_AND_POINTS: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
    l 1 2 3 4\nf 1 2 3 4\np 1 2 3\nl 1 3\nf 1 3 4\np 2\n";

#[test]
fn lines_and_points_are_skipped_with_a_warning() {
    let s = load(WITH_LINES_AND_POINTS).unwrap();
    assert_eq!(s.triangle_count(), 3, "the faces only");
    let warning = s
        .warnings
        .iter()
        .find(|w| w.contains("skipped 2 line elements ('l') and 2 point elements ('p')"))
        .unwrap_or_else(|| panic!("{:?}", s.warnings));
    assert!(warning.contains("test.obj"), "{warning}");
    // The face ids stay those of the faces in file order.
    let p = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    let (_, m, t) = s.triangles().nth(2).unwrap();
    assert_eq!(
        s.triangle_positions(m, t),
        [p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)]
    );
}

#[test]
fn a_file_of_only_lines_has_no_faces() {
    let e = load("v 0 0 0\nv 1 0 0\nv 1 1 0\nl 1 2 3\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("no faces"), "{e}");
}

/// Writes `obj` and `mtl` into a fresh folder and loads the OBJ.
fn load_with_mtl(name: &str, obj: &str, mtl: &str) -> (Result<Scene>, PathBuf) {
    let dir = std::env::temp_dir().join(format!("hider-obj-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("m.mtl"), mtl).unwrap();
    std::fs::write(dir.join("m.obj"), obj).unwrap();
    let scene = load_obj(dir.join("m.obj"));
    (scene, dir)
}

#[test]
fn a_broken_material_is_a_warning_naming_file_and_line() {
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
    // (MTL text, line at fault, whether 'red' survives, what is said)
    for (mtl, line, red_kept, said) in [
        (
            "newmtl red\nKd 1 0 0\n\nnewmtl\nKd 0 1 0\n",
            4,
            true,
            "'newmtl' without a name",
        ),
        (
            "newmtl red\nKd 1 0 0\nnewmtl   \n",
            3,
            true,
            "without a name",
        ),
        (
            "newmtl red\nKd 1 zero 0\nnewmtl blue\nKd 0 0 1\n",
            2,
            false,
            "'Kd 1 zero 0': material 'red' gets the default material",
        ),
    ] {
        let (s, dir) = load_with_mtl("badmtl", obj, mtl);
        let s = s.unwrap_or_else(|e| panic!("{mtl:?}: {e}"));
        assert_eq!(s.triangle_count(), 1);
        let material = s.meshes[0].material.map(|k| &s.materials[k]);
        if red_kept {
            assert_eq!(
                material.map(|m| m.diffuse),
                Some([1.0, 0.0, 0.0]),
                "{mtl:?}"
            );
        } else {
            assert_eq!(material, None, "the default material: {mtl:?}");
            let names: Vec<&str> = s.materials.iter().map(|m| m.name.as_str()).collect();
            assert_eq!(names, ["blue"], "the other materials load");
        }
        assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
        let expect = format!("{}:{line}:", dir.join("m.mtl").display());
        assert!(
            s.warnings
                .iter()
                .any(|w| w.starts_with(&expect) && w.contains(said)),
            "{mtl:?}: {:?}",
            s.warnings
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

#[test]
fn an_empty_usemtl_is_a_warning() {
    let s = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl\nf 1 2 3\n").unwrap();
    assert_eq!(s.triangle_count(), 1);
    assert!(
        s.warnings.iter().any(|w| w.starts_with("test.obj:4:")),
        "{:?}",
        s.warnings
    );
}

fn utf16(text: &str, big_endian: bool) -> Vec<u8> {
    let mut bytes = if big_endian {
        vec![0xFE, 0xFF]
    } else {
        vec![0xFF, 0xFE]
    };
    for unit in text.encode_utf16() {
        let pair = if big_endian {
            unit.to_be_bytes()
        } else {
            unit.to_le_bytes()
        };
        bytes.extend_from_slice(&pair);
    }
    bytes
}

#[test]
fn utf16_and_utf8_byte_order_marks_are_decoded() {
    let text = "# caf\u{e9}\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n";
    let mut utf8 = vec![0xEF, 0xBB, 0xBF];
    utf8.extend_from_slice(text.as_bytes());
    for bytes in [utf16(text, false), utf16(text, true), utf8] {
        let s = load_obj_bytes(
            &bytes,
            Path::new("bom.obj"),
            Path::new("."),
            &ObjOptions::default(),
        )
        .unwrap();
        assert_eq!(s.triangle_count(), 1);
    }
    // An odd byte count cannot be UTF-16: the error names the file.
    let mut odd = utf16(text, false);
    odd.push(b'\n');
    let e = load_obj_bytes(
        &odd,
        Path::new("odd.obj"),
        Path::new("."),
        &ObjOptions::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("odd.obj: ") && e.contains("UTF-16"), "{e}");
}

#[test]
fn short_colours_and_texture_coordinates_load_as_the_format_means_them() {
    // `Kd 0.5` is a grey; `Kd 1 0` and a bare `Kd` are broken (tobj
    // panicked on both); `vt u` has v = 0.
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5\nvt 0.25\nvt 1\n\
               usemtl grey\nf 1/1 2/2 3/3\nusemtl two\nf 1/1 3/3 2/2\nusemtl none\nf 2 1 3\n";
    let mtl = "newmtl grey\nKd 0.5\nnewmtl two\nKd 1 0\nnewmtl none\nKs\n";
    let (s, dir) = load_with_mtl("short", obj, mtl);
    let s = s.unwrap();
    assert_eq!(s.triangle_count(), 3);
    let grey = &s.materials[s.meshes[0].material.unwrap()];
    assert_eq!(grey.diffuse, [0.5, 0.5, 0.5]);
    assert_eq!(s.meshes[0].uvs[0], Vec2::new(0.5, 0.0));
    assert!(s.meshes[1..].iter().all(|m| m.material.is_none()));
    let mtl_path = dir.join("m.mtl").display().to_string();
    for line in [4, 6] {
        let at = format!("{mtl_path}:{line}:");
        assert!(
            s.warnings.iter().any(|w| w.starts_with(&at)),
            "{at} {:?}",
            s.warnings
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Statements read but not simulated are named once, with their line:
/// free-form geometry, and several smoothing groups (smoothed as one).
#[test]
fn unsimulated_statements_are_named() {
    let s = load(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvp 0.5\ncstype bezier\nvp 0.2\ns 1\nf 1 2 3\ns 2\nf 1 3 2\n",
    )
    .unwrap();
    let named = |needle: &str| s.warnings.iter().filter(|w| w.contains(needle)).count();
    assert_eq!(named(":4: 'vp'"), 1, "{:?}", s.warnings);
    assert_eq!(named(":5: 'cstype'"), 1, "{:?}", s.warnings);
    assert_eq!(named("'vp'"), 1, "once per keyword: {:?}", s.warnings);
    assert_eq!(named("2 smoothing groups"), 1, "{:?}", s.warnings);
    // Smoothing asked and no vn: the mesh gets vertex normals.
    assert_eq!(s.meshes[0].normals.len(), s.meshes[0].positions.len());
}

/// The fast reader cut into chunks of every size, down to one line each:
/// objects, materials, smoothing groups, layouts and negative indices
/// across chunk boundaries give the scene of tobj.
#[test]
fn the_fast_reader_gives_the_scene_of_tobj_whatever_the_chunks() {
    let text = "# head\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvn 0 0 1\n\
                o a\nf 1 2 3\nf -1 -2 -3\ns 1\nusemtl x\nf 1/1 2/2 3/1\nf 2/2 3/1 4/2\n\
                g b\r\nf 1//1 2//1 4//1 3//1\nusemtl y\nf 4 3 2\nf 1/1/1 2/1/1 3/2/1\n\
                o\nv 2 2 2\nf -1 -2 -3\n";
    let options = ObjOptions::default();
    let want = load_with_tobj(
        text.as_bytes(),
        Path::new("c.obj"),
        Path::new("/nonexistent"),
        &options,
    )
    .unwrap();
    assert_eq!(want.meshes.len(), 6, "{:#?}", want.meshes);
    for chunk in [1, 5, 13, 64, 1 << 20] {
        let (scene, chunks) = load_fast(
            text.as_bytes(),
            Path::new("c.obj"),
            Path::new("/nonexistent"),
            &options,
            chunk,
        )
        .unwrap()
        .unwrap_or_else(|why| panic!("{chunk}: {why}"));
        assert_eq!(scene, want, "chunks of {chunk} bytes");
        assert!(chunk >= 64 || chunks > 4, "{chunk}: {chunks} chunks");
    }
}

/// `map_d` is read as `map_Kd` is (its options parsed, `-s` applied, the
/// others named with file and line), as a mask; before, it was named as
/// not simulated and dropped.
#[test]
fn map_d_is_read_as_a_mask_with_its_options() {
    let dir = std::env::temp_dir().join(format!("hider-obj-map-d-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("m.mtl"),
        "newmtl leaf\nKd 1 1 1\nmap_d -s 2 2 -imfchan r disc.png\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("m.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl leaf\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    let s = load_obj(dir.join("m.obj")).unwrap();
    let leaf = &s.materials[s.meshes[0].material.unwrap()];
    let map_d = leaf.alpha_texture.as_ref().expect("map_d read");
    assert_eq!(map_d.path(), dir.join("disc.png"));
    assert!(map_d.is_mask());
    assert_eq!(map_d.transform.scale, [2.0, 2.0]);
    assert!(
        s.warnings
            .iter()
            .any(|w| w.contains("m.mtl:3: map_d option -imfchan")),
        "{:?}",
        s.warnings
    );
    assert!(
        !s.warnings
            .iter()
            .any(|w| w.contains("'map_d' is read but not")),
        "{:?}",
        s.warnings
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
