//! The page's scenes: a `gen:` spec (through [`hider_scene::load_model`]),
//! a hard case of the test kit by name (`hard:NAME`), or an OBJ with its
//! MTL and textures given as bytes (a dropped file, or a bundled model the
//! page fetched from `assets/`).

use std::path::Path;

use hider_scene::memory_files::with_files;
use hider_scene::obj::{ObjOptions, load_obj_bytes};
use hider_scene::shade::{Texture, TextureRef};
use hider_scene::{Scene, load_model};

/// The seed of the hard cases the page shows (the test kit's instances
/// are deterministic per seed).
pub const HARD_CASE_SEED: u64 = 1;

/// The names of the test kit's hard cases, for the picker.
pub fn hard_case_names() -> Vec<String> {
    hider_testkit::hard_cases::all(HARD_CASE_SEED)
        .into_iter()
        .map(|(name, _)| name.to_owned())
        .collect()
}

/// The scene of a spec: `gen:NAME[:ARGS]` or `hard:NAME`.
pub fn from_spec(spec: &str) -> Result<Scene, String> {
    if let Some(name) = spec.strip_prefix("hard:") {
        return hider_testkit::hard_cases::all(HARD_CASE_SEED)
            .into_iter()
            .find(|(n, _)| *n == name)
            .map(|(_, scene)| scene)
            .ok_or_else(|| format!("no hard case named '{name}' (see the picker)"));
    }
    if !spec.starts_with("gen:") {
        return Err(format!(
            "'{spec}': a scene spec is gen:NAME or hard:NAME (drop a file for an OBJ)"
        ));
    }
    let scene = load_model(spec).map_err(|e| e.to_string())?;
    scene.validate().map_err(|e| e.to_string())?;
    Ok(scene)
}

/// The OBJ `obj_name` among `files` (file name, bytes), its MTL files and
/// textures read from the same list by file name. Textures are decoded
/// here (the file system they would be read from lazily does not exist in
/// the browser); one that does not decode keeps the material's colour,
/// with a warning in the scene's `warnings`.
pub fn from_files(files: Vec<(String, Vec<u8>)>, obj_name: &str) -> Result<Scene, String> {
    let Some((_, obj)) = files.iter().find(|(n, _)| n == obj_name) else {
        return Err(format!("'{obj_name}' is not among the dropped files"));
    };
    let obj = obj.clone();
    let mut scene = with_files(files.clone(), || {
        load_obj_bytes(
            &obj,
            Path::new(obj_name),
            Path::new(""),
            &ObjOptions::default(),
        )
    })
    .map_err(|e| e.to_string())?;
    scene.validate().map_err(|e| e.to_string())?;
    let mut warnings = Vec::new();
    for material in &mut scene.materials {
        for slot in [
            &mut material.diffuse_texture,
            &mut material.specular_texture,
        ] {
            if let Some(texture) = slot.as_mut()
                && let Some(decoded) = decode_held(texture, &files, &mut warnings)
            {
                *texture = decoded;
            }
        }
    }
    scene.warnings.extend(warnings);
    Ok(scene)
}

/// The texture `texture` names, decoded from the held file of that name
/// (`None` when no such file was given, or it does not decode: then
/// with a warning).
fn decode_held(
    texture: &TextureRef,
    files: &[(String, Vec<u8>)],
    warnings: &mut Vec<String>,
) -> Option<TextureRef> {
    let path = texture.path().to_string_lossy().replace('\\', "/");
    let name = path.rsplit('/').next().unwrap_or(&path);
    // The loader has warned of a texture that is not among the files.
    let (_, bytes) = files.iter().find(|(n, _)| n == name)?;
    let decoded = image::load_from_memory(bytes)
        .map_err(|e| e.to_string())
        .and_then(|img| {
            let rgb = img.into_rgb8();
            Texture::from_srgb8_vec(rgb.width(), rgb.height(), rgb.into_raw())
                .map_err(|e| e.to_string())
        });
    match decoded {
        Ok(t) => Some(TextureRef::from_texture(name, t).with_transform(texture.transform)),
        Err(e) => {
            warnings.push(format!(
                "texture '{name}': {e}; the material's colour is used"
            ));
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn asset(path: &str) -> Vec<u8> {
        std::fs::read(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../assets")
                .join(path),
        )
        .unwrap()
    }

    #[test]
    fn a_textured_obj_given_as_bytes_loads_with_its_texture_decoded() {
        let files = vec![
            ("checker_plane.obj".to_owned(), asset("checker_plane.obj")),
            ("checker_plane.mtl".to_owned(), asset("checker_plane.mtl")),
            ("checker.png".to_owned(), asset("checker.png")),
        ];
        let scene = from_files(files, "checker_plane.obj").unwrap();
        let texture = scene.materials[0].diffuse_texture.as_ref().unwrap();
        assert!(texture.is_decoded());
        assert_eq!(texture.get().unwrap().width(), 256);
        assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    }

    #[test]
    fn a_missing_texture_is_a_warning_and_a_bad_spec_an_error() {
        let files = vec![
            ("checker_plane.obj".to_owned(), asset("checker_plane.obj")),
            ("checker_plane.mtl".to_owned(), asset("checker_plane.mtl")),
        ];
        let scene = from_files(files, "checker_plane.obj").unwrap();
        assert!(scene.warnings.iter().any(|w| w.contains("checker.png")));
        assert!(from_spec("hard:nonesuch").unwrap_err().contains("nonesuch"));
        assert!(from_spec("cube.obj").is_err());
        assert_eq!(from_spec("gen:cube").unwrap().triangle_count(), 12);
        assert!(hard_case_names().contains(&"cyclic_overlap".to_owned()));
    }
}
