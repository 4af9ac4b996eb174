//! MTL statements as their users mean them: texture statements with their
//! options (`map_Kd -s 2 2 tex.png`), and a warning, with file and line,
//! for every statement or option that is read but not simulated.
//!
//! The reference for what each key and option means is the MTL
//! specification (Wavefront's "MTL material format", options of section
//! "Texture map statements") and assimp's `ObjFileMtlImporter`, which
//! reads the same options. `docs/analysis.md` lists every key and what the
//! hiders do with it.

use crate::shade::TextureTransform;

/// A texture statement's value split into its options and its file.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct TextureStatement {
    /// The image file, as written (may hold spaces).
    pub file: String,
    /// `-s`, `-o` and `-clamp`, which change where the image is sampled.
    pub transform: TextureTransform,
    /// The options read but not simulated, as written (`-blendu`, `-bm`...).
    pub ignored: Vec<String>,
}

/// How many values an option takes: at least, at most.
fn arity(option: &str) -> Option<(usize, usize)> {
    Some(match option {
        "-blendu" | "-blendv" | "-bm" | "-boost" | "-cc" | "-clamp" | "-imfchan" | "-texres"
        | "-type" => (1, 1),
        "-mm" => (2, 2),
        "-o" | "-s" | "-t" => (1, 3),
        _ => return None,
    })
}

/// Splits a texture statement's value (after the key) into its options and
/// the file name: options come first, each with its values; the file is the
/// rest of the line, spaces included.
pub(super) fn texture_statement(value: &str) -> TextureStatement {
    let mut out = TextureStatement::default();
    let mut rest = value.trim_start();
    loop {
        let word_end = rest.find(char::is_whitespace).unwrap_or(rest.len());
        let option = &rest[..word_end];
        let Some((least, most)) = arity(option) else {
            break;
        };
        let mut after = rest[word_end..].trim_start();
        let mut values: Vec<&str> = Vec::new();
        // Word options take one word; numeric ones take numbers while they
        // parse, so the file name after them ends the list.
        let words_option = matches!(
            option,
            "-clamp" | "-blendu" | "-blendv" | "-cc" | "-imfchan" | "-type"
        );
        while values.len() < most {
            let end = after.find(char::is_whitespace).unwrap_or(after.len());
            let word = &after[..end];
            if word.is_empty() || !(words_option || word.parse::<f64>().is_ok()) {
                break;
            }
            values.push(word);
            after = after[end..].trim_start();
        }
        let number = |k: usize, default: f64| {
            values
                .get(k)
                .and_then(|v| v.parse::<f64>().ok())
                .filter(|v| v.is_finite())
                .unwrap_or(default)
        };
        match option {
            "-s" => {
                let u = number(0, 1.0);
                out.transform.scale = [u, number(1, u)];
            }
            "-o" => {
                let u = number(0, 0.0);
                out.transform.offset = [u, number(1, 0.0)];
            }
            "-clamp" => out.transform.clamp = values.first() == Some(&"on"),
            _ => out.ignored.push(option.to_owned()),
        }
        if values.len() < least {
            // A truncated option: the rest is taken as the file, as assimp
            // does.
            break;
        }
        rest = after;
    }
    out.file = rest.trim().to_owned();
    out
}

/// What a key is read as, when it is read but not (fully) simulated: the
/// words of the warning. `None` for keys simulated in full and for keys the
/// hiders need not know.
fn unsimulated(key: &str) -> Option<&'static str> {
    Some(match key {
        "Tf" => "the transmission filter (drawn with the opacity d only)",
        "Ni" => "the index of refraction (no refraction is simulated)",
        "sharpness" => "the reflection sharpness (no reflection is simulated)",
        "map_Ka" => "the ambient texture (the diffuse texture lights the ambient term)",
        "map_Ns" | "map_ns" | "map_NS" => "the specular exponent texture",
        "map_Bump" | "map_bump" | "bump" | "norm" | "map_Kn" => "the bump map",
        "disp" => "the displacement map",
        "decal" => "the decal texture",
        "refl" => "the reflection map",
        "Pr" | "Pm" | "Ps" | "Pc" | "Pcr" | "aniso" | "anisor" | "map_Pr" | "map_Pm" | "map_Ps"
        | "map_Ke" => "a physically based (PBR) extension",
        _ => return None,
    })
}

/// The warnings for `lines` of the MTL file named `file`: each statement
/// read but not simulated, once per key (at its first line); every texture
/// option not simulated, once per option; `illum` models above 2 (their
/// reflection and refraction terms); `d -halo`.
pub(super) fn warnings(lines: &[&str], file: &str) -> Vec<String> {
    let mut seen: Vec<String> = Vec::new();
    let mut out = Vec::new();
    let mut out_of_range = Vec::new();
    let mut once = |what: String, line: usize, message: String| {
        if !seen.contains(&what) {
            seen.push(what);
            out.push(format!("{file}:{}: {message}", line + 1));
        }
    };
    for (k, line) in lines.iter().enumerate() {
        let text = line.trim();
        let mut words = text.split_whitespace();
        let Some(key) = words.next() else {
            continue;
        };
        if let Some(what) = unsimulated(key) {
            once(
                key.to_owned(),
                k,
                format!("'{key}' is read but not simulated: {what}"),
            );
        }
        match key {
            "map_Kd" | "map_Ks" | "map_d" => {
                let statement = texture_statement(text[key.len()..].trim());
                for option in statement.ignored {
                    once(
                        format!("{key} {option}"),
                        k,
                        format!("{key} option {option} is read but not simulated"),
                    );
                }
            }
            "illum" => {
                if let Some(n) = words.next().and_then(|w| w.parse::<u32>().ok())
                    && n > 2
                {
                    once(
                        format!("illum {n}"),
                        k,
                        format!(
                            "'illum {n}': its reflection, refraction or Fresnel terms are not \
                             simulated; drawn as illum 2"
                        ),
                    );
                }
            }
            "Kd" | "Ka" | "Ks" | "Ke" | "d" | "Tr" | "Ns" => {
                let values: Vec<&str> = text.split_whitespace().skip(1).collect();
                if let Some(problem) = value_problem(key, &values) {
                    out_of_range.push(format!("{file}:{}: '{text}' {problem}", k + 1));
                }
                if key == "d" && values.first() == Some(&"-halo") {
                    once(
                        "d -halo".to_owned(),
                        k,
                        "'d -halo': the halo (opacity growing towards the silhouette) is not \
                         simulated; the plain dissolve is used"
                            .to_owned(),
                    );
                }
            }
            _ => {}
        }
    }
    out.extend(out_of_range);
    out
}

/// What is wrong with the values of a colour (`Kd`...), a dissolve (`d`,
/// `Tr`) or an exponent (`Ns`), and what is used instead; `None` when they
/// are fine (or missing: tobj's parse reports that).
fn value_problem(key: &str, values: &[&str]) -> Option<String> {
    let numbers: Vec<f64> = values
        .iter()
        .filter(|v| **v != "-halo")
        .filter_map(|v| v.parse().ok())
        .collect();
    let (lo, hi) = match key {
        "Ns" => (0.0, 1000.0),
        _ => (0.0, 1.0),
    };
    if numbers.iter().any(|x| !x.is_finite()) {
        let used = match key {
            "d" => "opaque (1)",
            "Tr" => "opaque (0)",
            "Ns" => "0",
            _ => "0 (black)",
        };
        return Some(format!("is not a number: {used} is used"));
    }
    numbers
        .iter()
        .any(|&x| x < lo || x > hi)
        .then(|| format!("is out of range ({lo} to {hi}): clamped"))
}

/// `line` as tobj can parse it: `d -halo X` becomes `d X` (tobj refuses
/// the option and would drop the whole material).
pub(super) fn without_halo(line: &str) -> Option<String> {
    let mut words = line.split_whitespace();
    (words.next() == Some("d") && words.next() == Some("-halo"))
        .then(|| format!("d {}", words.collect::<Vec<_>>().join(" ")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texture_options_are_split_from_the_file() {
        let plain = texture_statement("tex.png");
        assert_eq!(plain.file, "tex.png");
        assert_eq!(plain.transform, TextureTransform::default());
        let scaled = texture_statement("-s 2 3 1 -o 0.5 -clamp on my tex.png");
        assert_eq!(scaled.file, "my tex.png");
        assert_eq!(scaled.transform.scale, [2.0, 3.0]);
        assert_eq!(scaled.transform.offset, [0.5, 0.0]);
        assert!(scaled.transform.clamp);
        assert!(scaled.ignored.is_empty());
        let one = texture_statement("-s 2 tex.png");
        assert_eq!(
            (one.transform.scale, one.file.as_str()),
            ([2.0, 2.0], "tex.png")
        );
        let ignored = texture_statement("-blendu off -bm 1 -mm 0 1 -imfchan m -clamp off t.png");
        assert_eq!(ignored.file, "t.png");
        assert_eq!(ignored.ignored, ["-blendu", "-bm", "-mm", "-imfchan"]);
        assert!(!ignored.transform.clamp);
        // A file named like a number after the values is still the file.
        assert_eq!(texture_statement("-o 1 2 3 4.png").file, "4.png");
    }

    #[test]
    fn unsimulated_statements_are_named_once_with_their_line() {
        let lines = [
            "newmtl a",
            "Ni 1.5",
            "Ni 1.4",
            "map_Kd -blendu off -s 2 2 a.png",
            "illum 4",
            "d -halo 0.5",
            "Kd 1 1 1",
        ];
        let w = warnings(&lines, "m.mtl");
        assert_eq!(w.len(), 4, "{w:#?}");
        assert!(w[0].starts_with("m.mtl:2: 'Ni'"), "{}", w[0]);
        assert!(
            w[1].starts_with("m.mtl:4: map_Kd option -blendu"),
            "{}",
            w[1]
        );
        assert!(w[2].starts_with("m.mtl:5: 'illum 4'"), "{}", w[2]);
        assert!(w[3].starts_with("m.mtl:6: 'd -halo'"), "{}", w[3]);
        assert_eq!(without_halo("d -halo 0.5").as_deref(), Some("d 0.5"));
        // Values that are not numbers or out of range are named.
        let bad = warnings(
            &[
                "newmtl b",
                "d nan",
                "Kd nan 0 0",
                "d -0.5",
                "Ns 2000",
                "Kd 0.5 0.5 0.5",
            ],
            "b.mtl",
        );
        assert_eq!(bad.len(), 4, "{bad:#?}");
        assert!(
            bad[0].starts_with("b.mtl:2: 'd nan' is not a number: opaque (1)"),
            "{}",
            bad[0]
        );
        assert!(
            bad[1].contains("'Kd nan 0 0' is not a number: 0 (black)"),
            "{}",
            bad[1]
        );
        assert!(
            bad[2].contains("'d -0.5' is out of range (0 to 1): clamped"),
            "{}",
            bad[2]
        );
        assert!(
            bad[3].contains("'Ns 2000' is out of range (0 to 1000)"),
            "{}",
            bad[3]
        );
        assert_eq!(without_halo("d 0.5"), None);
    }
}
