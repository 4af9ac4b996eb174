//! One chunk of an OBJ file read by the fast reader: its lines counted
//! (the first pass, which sizes every array before anything is
//! allocated), then parsed into the arrays' slots (the second pass).
//!
//! Both passes read bytes, not text: words are split at ASCII spaces and
//! tabs (and the VT and FF controls, which `str::split_whitespace` also
//! splits at), numbers and indices are read in the one plain form every
//! exporter writes. Anything else — another statement, a number in a form
//! this reader does not read (`inf`, `nan`), a byte outside ASCII where it
//! could change how a line splits into words, a lone CR — is a
//! [`Refusal`]: the whole file goes to tobj, which reads it as it always
//! did (and reports its errors, with their line).

use std::collections::HashSet;

use glam::{DVec3, Vec2, Vec3};

/// A face corner's missing texture coordinate or normal.
pub(super) const NONE: u32 = u32::MAX;

/// Why the fast reader gives a file to tobj: the line (0-based, within
/// the chunk) and what it holds.
#[derive(Debug)]
pub(super) struct Refusal {
    /// 0-based line within the chunk.
    pub line: usize,
    /// What the line holds that the fast reader does not read.
    pub why: String,
}

/// What a chunk holds, counted by the first pass.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Counts {
    /// Lines (the chunk's line ends).
    pub lines: usize,
    /// `v` statements.
    pub v: usize,
    /// `vt` statements.
    pub vt: usize,
    /// `vn` statements.
    pub vn: usize,
    /// Triangles of the `f` statements after fan-splitting.
    pub triangles: u64,
    /// `l` statements (skipped: not surfaces).
    pub l: usize,
    /// `p` statements (skipped: not surfaces).
    pub p: usize,
}

impl Counts {
    /// The counts of `self` followed by `other`.
    pub(super) fn then(self, other: Counts) -> Counts {
        Counts {
            lines: self.lines + other.lines,
            v: self.v + other.v,
            vt: self.vt + other.vt,
            vn: self.vn + other.vn,
            triangles: self.triangles + other.triangles,
            l: self.l + other.l,
            p: self.p + other.p,
        }
    }
}

/// A statement that changes the meshes tobj makes, at the triangle of its
/// chunk before which it comes.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Event {
    /// `o NAME` or `g NAME` (the name as tobj takes it).
    Object(String),
    /// `usemtl NAME`.
    Material(String),
    /// `mtllib FILE`.
    Library(String),
    /// A face whose layout (has texture coordinates, has normals) differs
    /// from the chunk's previous face of the same object, or the first face
    /// of the chunk or of an object.
    Layout(bool, bool),
}

/// A chunk parsed by the second pass.
#[derive(Debug, Default)]
pub(super) struct Parsed {
    /// Triangle corners `(v, vt, vn)`, 0-based file-wide ([`NONE`] when
    /// absent), three per triangle, faces fan-split `(v0, vi, vi+1)`.
    pub corners: Vec<[u32; 3]>,
    /// The statements that shape the meshes, with the triangle they come
    /// before.
    pub events: Vec<(usize, Event)>,
    /// The smoothing groups the chunk names (not `off` or `0`).
    pub groups: HashSet<String>,
}

/// The slots of the file-wide arrays that a chunk's statements fill.
pub(super) struct Slots<'a> {
    /// Positions (`v`), after dividing by `w`.
    pub positions: &'a mut [DVec3],
    /// Texture coordinates (`vt`).
    pub uvs: &'a mut [Vec2],
    /// Normals (`vn`).
    pub normals: &'a mut [Vec3],
}

/// `char::is_whitespace` on the ASCII bytes that may sit inside a line
/// (CR is left out: one inside a line is a lone CR, refused).
#[inline]
fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | 0x0B | 0x0C)
}

/// The lines of a chunk, without their LF or CR LF (as `BufRead::lines`
/// gives them to tobj).
fn lines(chunk: &[u8]) -> impl Iterator<Item = &[u8]> {
    let mut rest = chunk;
    std::iter::from_fn(move || {
        if rest.is_empty() {
            return None;
        }
        let (line, next) = match memchr::memchr(b'\n', rest) {
            Some(k) => (&rest[..k], &rest[k + 1..]),
            None => (rest, &rest[rest.len()..]),
        };
        rest = next;
        Some(line.strip_suffix(b"\r").unwrap_or(line))
    })
}

/// The words of a line.
fn words(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(|&b| is_space(b)).filter(|w| !w.is_empty())
}

/// What the fast reader does with a statement's keyword.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Keyword {
    V,
    Vt,
    Vn,
    F,
    /// `o` or `g`.
    Object,
    Usemtl,
    Mtllib,
    S,
    /// `l`: a polyline, skipped (with a count in a warning) unread, as the
    /// validation pass skips it.
    L,
    /// `p`: points, skipped likewise.
    P,
    Comment,
}

fn keyword(word: &[u8]) -> Option<Keyword> {
    Some(match word {
        b"v" => Keyword::V,
        b"vt" => Keyword::Vt,
        b"vn" => Keyword::Vn,
        b"f" => Keyword::F,
        b"o" | b"g" => Keyword::Object,
        b"usemtl" => Keyword::Usemtl,
        b"mtllib" => Keyword::Mtllib,
        b"s" => Keyword::S,
        b"l" => Keyword::L,
        b"p" => Keyword::P,
        [b'#', ..] => Keyword::Comment,
        _ => return None,
    })
}

fn refuse(line: usize, why: impl Into<String>) -> Refusal {
    Refusal {
        line,
        why: why.into(),
    }
}

fn unknown(line: usize, word: &[u8]) -> Refusal {
    refuse(
        line,
        format!(
            "a '{}' statement (the fast reader reads v, vt, vn, f, o, g, s, usemtl, mtllib, l and p)",
            String::from_utf8_lossy(word)
        ),
    )
}

/// The first pass: what the chunk holds, refusing statements the fast
/// reader does not read before anything is allocated for it.
pub(super) fn count(chunk: &[u8]) -> Result<Counts, Refusal> {
    let mut c = Counts::default();
    for (k, line) in lines(chunk).enumerate() {
        c.lines += 1;
        // Only the keyword is read here (and the words of a face): the
        // bytes of the other statements are left to the second pass.
        let start = line
            .iter()
            .position(|&b| !is_space(b))
            .unwrap_or(line.len());
        let line = &line[start..];
        let end = line.iter().position(|&b| is_space(b)).unwrap_or(line.len());
        match keyword(&line[..end]) {
            Some(Keyword::V) => c.v += 1,
            Some(Keyword::Vt) => c.vt += 1,
            Some(Keyword::Vn) => c.vn += 1,
            Some(Keyword::L) => c.l += 1,
            Some(Keyword::P) => c.p += 1,
            Some(Keyword::F) => {
                // Word starts: a byte that is not a blank after one that is.
                let mut n = 0u64;
                let mut blank = true;
                for &b in &line[end..] {
                    let space = is_space(b);
                    n += u64::from(blank && !space);
                    blank = space;
                }
                if n < 3 {
                    return Err(refuse(k, "a face of fewer than 3 vertices"));
                }
                c.triangles += n - 2;
            }
            Some(_) => {}
            None if line.is_empty() => {}
            None => return Err(unknown(k, &line[..end])),
        }
    }
    Ok(c)
}

/// The second pass: the chunk's statements into `slots` (sized by
/// [`count`]) and the corners of its `triangles`, resolved against
/// `before`, the counts of the chunks before it.
pub(super) fn parse(
    chunk: &[u8],
    before: Counts,
    triangles: u64,
    slots: Slots<'_>,
) -> Result<Parsed, Refusal> {
    let mut out = Parsed {
        corners: Vec::with_capacity(3 * triangles as usize),
        ..Parsed::default()
    };
    let (mut nv, mut nvt, mut nvn) = (0, 0, 0);
    let mut layout: Option<(bool, bool)> = None;
    let mut face: Vec<[u32; 3]> = Vec::new();
    for (k, line) in lines(chunk).enumerate() {
        let mut words = words(line);
        let Some(first) = words.next() else {
            continue;
        };
        let number = |w: Option<&[u8]>| {
            w.and_then(parse_f64)
                .ok_or_else(|| refuse(k, "a number in a form the fast reader does not read"))
        };
        match keyword(first).ok_or_else(|| unknown(k, first))? {
            Keyword::V => {
                let [x, y, z] = [words.next(), words.next(), words.next()].map(number);
                let mut p = DVec3::new(x?, y?, z?);
                if let Some(w) = words.next() {
                    let w = number(Some(w))?;
                    if w == 0.0 || words.next().is_some() {
                        return Err(refuse(k, "a vertex colour or a w of 0"));
                    }
                    p = DVec3::new(p.x / w, p.y / w, p.z / w);
                }
                *slots
                    .positions
                    .get_mut(nv)
                    .ok_or_else(|| refuse(k, "more positions than counted"))? = p;
                nv += 1;
            }
            Keyword::Vt => {
                let u = number(words.next())?;
                // `vt u` means v = 0 (tobj is given `vt u 0`).
                let v = match words.next() {
                    Some(w) => number(Some(w))?,
                    None => 0.0,
                };
                *slots
                    .uvs
                    .get_mut(nvt)
                    .ok_or_else(|| refuse(k, "more texture coordinates than counted"))? =
                    Vec2::new(u as f32, v as f32);
                nvt += 1;
            }
            Keyword::Vn => {
                let [x, y, z] = [words.next(), words.next(), words.next()].map(number);
                let n = Vec3::new(x? as f32, y? as f32, z? as f32);
                *slots
                    .normals
                    .get_mut(nvn)
                    .ok_or_else(|| refuse(k, "more normals than counted"))? = n;
                nvn += 1;
            }
            Keyword::F => {
                let counts = [before.v + nv, before.vt + nvt, before.vn + nvn];
                let mut shape = None;
                face.clear();
                for w in words {
                    let (corner, this) = corner(w, counts)
                        .ok_or_else(|| refuse(k, "a face vertex that does not resolve"))?;
                    if *shape.get_or_insert(this) != this {
                        return Err(refuse(k, "a face mixing vertex formats"));
                    }
                    face.push(corner);
                }
                if face.len() < 3 {
                    return Err(refuse(k, "a face of fewer than 3 vertices"));
                }
                let this = (face[0][1] != NONE, face[0][2] != NONE);
                if layout != Some(this) {
                    out.events
                        .push((out.corners.len() / 3, Event::Layout(this.0, this.1)));
                    layout = Some(this);
                }
                for pair in face[1..].windows(2) {
                    out.corners.extend([face[0], pair[0], pair[1]]);
                }
            }
            Keyword::Object => {
                let name = rest_of_line(line, 1, k)?;
                let name = if name.is_empty() {
                    "unnamed_object".to_owned()
                } else {
                    name
                };
                out.events
                    .push((out.corners.len() / 3, Event::Object(name)));
                layout = None;
            }
            keyword @ (Keyword::Usemtl | Keyword::Mtllib) => {
                // tobj takes the name after the line's first space.
                if line.get(6) != Some(&b' ') {
                    return Err(refuse(k, "a usemtl or mtllib not followed by a space"));
                }
                let name = rest_of_line(line, 7, k)?;
                let event = if keyword == Keyword::Mtllib {
                    Event::Library(name)
                } else if name.is_empty() {
                    return Err(refuse(k, "a usemtl without a name"));
                } else {
                    Event::Material(name)
                };
                out.events.push((out.corners.len() / 3, event));
            }
            Keyword::S => {
                // As the smoothing pass of the loader of record reads it.
                let text = lone_cr_free(line, k)?;
                let text = String::from_utf8_lossy(text);
                match text.split_whitespace().nth(1) {
                    None | Some("off" | "0") => {}
                    Some(group) => {
                        out.groups.insert(group.to_owned());
                    }
                }
            }
            Keyword::Comment | Keyword::L | Keyword::P => {
                lone_cr_free(line, k)?;
            }
        }
    }
    if (nv, nvt, nvn) != (slots.positions.len(), slots.uvs.len(), slots.normals.len()) {
        return Err(refuse(0, "fewer statements than counted"));
    }
    Ok(out)
}

/// `line` when it holds no CR (one inside a line is a lone CR, which
/// starts a new line for the loader of record).
fn lone_cr_free(line: &[u8], k: usize) -> Result<&[u8], Refusal> {
    match memchr::memchr(b'\r', line) {
        Some(_) => Err(refuse(k, "a lone CR line end")),
        None => Ok(line),
    }
}

/// The text of `line` from byte `from` on, trimmed, as tobj reads a name
/// (`o`, `g`, `usemtl`, `mtllib`): the keyword must open the line, since
/// tobj cuts its name at a fixed place.
fn rest_of_line(line: &[u8], from: usize, k: usize) -> Result<String, Refusal> {
    if line.first().is_some_and(|&b| is_space(b)) {
        return Err(refuse(k, "a name statement after blanks"));
    }
    let rest = lone_cr_free(&line[from.min(line.len())..], k)?;
    // The bytes end at ASCII: decoding them alone replaces stray bytes
    // exactly as decoding the whole file does.
    Ok(String::from_utf8_lossy(rest).trim().to_owned())
}

/// A face vertex `v`, `v/vt`, `v/vt/vn` or `v//vn` as its corner (0-based
/// indices; negative ones count back from `counts`, the positions, texture
/// coordinates and normals defined so far) and its shape (parts, has vt,
/// has vn), which every vertex of a face shares.
fn corner(word: &[u8], counts: [usize; 3]) -> Option<([u32; 3], (u8, bool, bool))> {
    let mut parts = word.split(|&b| b == b'/');
    let mut corner = [NONE; 3];
    let mut n = 0u8;
    for (slot, part) in parts.by_ref().take(3).enumerate() {
        n += 1;
        if part.is_empty() {
            if slot == 0 {
                return None;
            }
            continue;
        }
        corner[slot] = index(part, counts[slot])?;
    }
    if parts.next().is_some() {
        return None;
    }
    Some((corner, (n, corner[1] != NONE, corner[2] != NONE)))
}

/// An OBJ index (1-based, or negative counting back) as a 0-based index
/// below `count`.
fn index(word: &[u8], count: usize) -> Option<u32> {
    let (negative, digits) = match word {
        [b'-', rest @ ..] => (true, rest),
        _ => (false, word),
    };
    if digits.is_empty() || digits.len() > 18 {
        return None;
    }
    let mut i: i64 = 0;
    for &d in digits {
        if !d.is_ascii_digit() {
            return None;
        }
        i = i * 10 + i64::from(d - b'0');
    }
    let count = count as i64;
    let resolved = if negative { count - i } else { i - 1 };
    (i != 0 && (0..count).contains(&resolved) && resolved < i64::from(NONE))
        .then_some(resolved as u32)
}

/// Exact powers of ten as `f64` (10^22 is the largest one).
const POWERS: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// A finite number in the form `[+-]digits[.digits][(e|E)[+-]digits]`
/// (digits on at least one side of the point), as `str::parse::<f64>`
/// reads it, correctly rounded; `None` for any other form and for a value
/// that is not finite.
///
/// A mantissa of at most 2^53 with at most 22 decimal places or powers of
/// ten is exact as an `f64`, as is the power, so one multiplication or
/// division rounds correctly (Clinger's fast path); other values are read
/// by the standard library.
pub(super) fn parse_f64(word: &[u8]) -> Option<f64> {
    let (negative, body) = match word {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, word),
    };
    let mut mantissa: u64 = 0;
    let mut digits = 0u32;
    let mut any = false;
    let mut exponent: i64 = 0;
    let mut i = 0;
    let mut take = |b: u8, fraction: bool, exponent: &mut i64| {
        any = true;
        if mantissa == 0 && b == b'0' {
            if fraction {
                *exponent -= 1;
            }
            return;
        }
        digits += 1;
        if digits <= 19 {
            mantissa = mantissa * 10 + u64::from(b - b'0');
            if fraction {
                *exponent -= 1;
            }
        } else if !fraction {
            *exponent += 1;
        }
    };
    while i < body.len() && body[i].is_ascii_digit() {
        take(body[i], false, &mut exponent);
        i += 1;
    }
    if i < body.len() && body[i] == b'.' {
        i += 1;
        while i < body.len() && body[i].is_ascii_digit() {
            take(body[i], true, &mut exponent);
            i += 1;
        }
    }
    if !any {
        return None;
    }
    if i < body.len() && (body[i] | 0x20) == b'e' {
        i += 1;
        let negative_exponent = match body.get(i) {
            Some(b'-') => {
                i += 1;
                true
            }
            Some(b'+') => {
                i += 1;
                false
            }
            _ => false,
        };
        let start = i;
        let mut e: i64 = 0;
        while i < body.len() && body[i].is_ascii_digit() {
            e = (e * 10 + i64::from(body[i] - b'0')).min(1 << 40);
            i += 1;
        }
        if i == start {
            return None;
        }
        exponent += if negative_exponent { -e } else { e };
    }
    if i != body.len() {
        return None;
    }
    let value = if digits <= 19 && mantissa <= 1 << 53 && exponent.abs() <= 22 {
        let m = mantissa as f64;
        let power = POWERS[exponent.unsigned_abs() as usize];
        let magnitude = if exponent < 0 { m / power } else { m * power };
        if negative { -magnitude } else { magnitude }
    } else {
        std::str::from_utf8(word).ok()?.parse::<f64>().ok()?
    };
    value.is_finite().then_some(value)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_as_the_standard_library_reads_them() {
        for text in [
            "0",
            "-0",
            "1",
            "+1",
            "1.",
            ".5",
            "-.5",
            "1e5",
            "1.e5",
            "1.5E-3",
            "+.5e-3",
            "00012",
            "0.000123",
            "123456789012345678901234",
            "0.30000000000000004",
            "1e22",
            "1e23",
            "9007199254740993",
            "-1.7976931348623157e308",
            "4.9e-324",
            "1e-400",
            "0.1000000000000000000000001",
            "12345678901234567890.5",
        ] {
            let want = text.parse::<f64>().unwrap();
            let got = parse_f64(text.as_bytes()).unwrap_or_else(|| panic!("{text}"));
            assert_eq!(got.to_bits(), want.to_bits(), "{text}");
        }
        for text in [
            "", ".", "-", "e5", "1e", "1e+", "inf", "nan", "1x", "0x1", "1e400", "1,5",
        ] {
            assert_eq!(parse_f64(text.as_bytes()), None, "{text}");
        }
    }

    #[test]
    fn indices_resolve_as_the_format_says() {
        assert_eq!(index(b"1", 3), Some(0));
        assert_eq!(index(b"3", 3), Some(2));
        assert_eq!(index(b"-1", 3), Some(2));
        assert_eq!(index(b"-3", 3), Some(0));
        for bad in [&b"0"[..], b"-0", b"4", b"-4", b"+1", b"1x", b""] {
            assert_eq!(index(bad, 3), None, "{}", String::from_utf8_lossy(bad));
        }
        assert_eq!(
            corner(b"2//1", [3, 0, 1]),
            Some(([1, NONE, 0], (3, false, true)))
        );
        assert_eq!(corner(b"1/1/1/1", [3, 3, 3]), None);
        assert_eq!(corner(b"/1", [3, 3, 3]), None);
    }
}
