//! Models by name, as the command line takes them: an OBJ file, or a
//! generated scene `gen:NAME[:ARGS]`.

use crate::error::{Error, Result};
use crate::model::Scene;
use crate::procedural;

/// Most segments of `gen:sphere:N`.
pub const MAX_SPHERE_SEGMENTS: u64 = 2000;

/// Most triangles of `gen:soup:COUNT`.
pub const MAX_SOUP_TRIANGLES: u64 = 10_000_000;

/// Loads an OBJ file (with its MTL), or builds the generated scene of a
/// `gen:` spec (see [`generated`]).
///
/// The loader's warnings (a missing texture, a skipped statement) are in
/// the scene's `warnings` for the caller to show.
///
/// The errors of [`load_obj`](crate::obj::load_obj) name the file (and the line); those of a
/// `gen:` spec quote it.
///
/// Without the `obj` feature a file is refused with an error saying so
/// (a `gen:` spec still loads).
///
/// ```
/// # #[cfg(feature = "obj")] {
/// let cube = hider_scene::load_model("gen:cube")?;
/// assert_eq!(cube.triangle_count(), 12);
/// let missing = hider_scene::load_model("no/such/model.obj").unwrap_err();
/// assert!(missing.to_string().starts_with("no/such/model.obj: "), "{missing}");
/// # }
/// # Ok::<(), hider_scene::Error>(())
/// ```
pub fn load_model(model: &str) -> Result<Scene> {
    if let Some(spec) = model.strip_prefix("gen:") {
        return generated(spec);
    }
    load_file(model)
}

/// An OBJ file, through [`crate::obj::load_obj`].
#[cfg(feature = "obj")]
fn load_file(model: &str) -> Result<Scene> {
    crate::obj::load_obj(model)
}

/// No OBJ loader in this build: an error naming the file and the feature.
#[cfg(not(feature = "obj"))]
fn load_file(model: &str) -> Result<Scene> {
    Err(Error::Parse {
        path: model.into(),
        line: 0,
        message: "cannot load an OBJ file: hider-scene was built without its `obj` feature".into(),
    })
}

/// The generated scene of a spec (the text after `gen:`): `cube`,
/// `sphere[:N]` (N segments, 3 to 2000, default 64),
/// `soup[:COUNT[:SEED]]` (COUNT random triangles, at most 10 000 000,
/// default 10 000, seed 1), `intersecting`, `cyclic`, `coplanar`.
pub fn generated(spec: &str) -> Result<Scene> {
    let mut parts = spec.split(':');
    let name = parts.next().unwrap_or_default();
    let mut num = |default: u64, what: &'static str| -> Result<u64> {
        match parts.next() {
            None => Ok(default),
            Some(p) => p
                .parse()
                .map_err(|_| Error::Generated(format!("gen:{spec}: bad {what} '{p}'"))),
        }
    };
    Ok(match name {
        "cube" => procedural::cube(),
        "sphere" => {
            let n = num(64, "segment count")?;
            if !(3..=MAX_SPHERE_SEGMENTS).contains(&n) {
                return Err(Error::Generated(format!(
                    "gen:{spec}: segment count {n} must be 3 to {MAX_SPHERE_SEGMENTS}"
                )));
            }
            procedural::uv_sphere(n as u32)
        }
        "soup" => {
            let count = num(10_000, "triangle count")?;
            let seed = num(1, "seed")?;
            if count > MAX_SOUP_TRIANGLES {
                return Err(Error::Generated(format!(
                    "gen:{spec}: triangle count {count} is over the limit of {MAX_SOUP_TRIANGLES}"
                )));
            }
            procedural::random_soup(count as u32, seed)
        }
        "intersecting" => procedural::intersecting_pair(),
        "cyclic" => procedural::cyclic_triple(),
        "coplanar" => procedural::coplanar_pair(),
        _ => {
            return Err(Error::Generated(format!(
                "unknown generated scene '{name}' (cube, sphere, soup, intersecting, cyclic, coplanar)"
            )));
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_specs_and_their_errors() {
        assert_eq!(load_model("gen:sphere:8").unwrap().triangle_count(), {
            procedural::uv_sphere(8).triangle_count()
        });
        assert_eq!(
            generated("soup:5:7").unwrap().triangle_count(),
            procedural::random_soup(5, 7).triangle_count()
        );
        let e = generated("sphere:x").unwrap_err();
        assert_eq!(e.to_string(), "gen:sphere:x: bad segment count 'x'");
        assert_eq!(
            generated("sphere:2").unwrap_err().to_string(),
            "gen:sphere:2: segment count 2 must be 3 to 2000"
        );
        assert_eq!(
            generated("soup:20000000").unwrap_err().to_string(),
            "gen:soup:20000000: triangle count 20000000 is over the limit of 10000000"
        );
        assert_eq!(
            generated("torus").unwrap_err().to_string(),
            "unknown generated scene 'torus' (cube, sphere, soup, intersecting, cyclic, coplanar)"
        );
    }
}
