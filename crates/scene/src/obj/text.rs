//! Bytes of an OBJ or MTL file as text: UTF-8 with stray bytes replaced,
//! or UTF-16 when the file starts with a byte-order mark (as editors on
//! Windows save "Unicode" text).

use std::borrow::Cow;
use std::path::Path;

use crate::error::{Error, Result};

/// Decodes a text file: a UTF-16 byte-order mark (little or big endian)
/// selects UTF-16, a UTF-8 one is dropped, anything else is read as UTF-8
/// with invalid bytes replaced by U+FFFD (old exporters write Latin-1
/// comments and names). Line ends may be LF, CR LF, or a lone CR (classic
/// Mac OS files, which assimp reads too): a lone CR becomes LF, so line
/// numbers in messages count the lines an editor shows. An odd number of
/// UTF-16 bytes is an error naming `name`.
pub(super) fn decode<'a>(bytes: &'a [u8], name: &Path) -> Result<Cow<'a, str>> {
    let text = decode_units(bytes, name)?;
    Ok(lone_cr_to_lf(text))
}

/// `text` with every CR not followed by LF turned into LF (borrowed when
/// there is none).
fn lone_cr_to_lf(text: Cow<'_, str>) -> Cow<'_, str> {
    let bytes = text.as_bytes();
    if !memchr::memchr_iter(b'\r', bytes).any(|k| bytes.get(k + 1) != Some(&b'\n')) {
        return text;
    }
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '\r' && chars.peek() != Some(&'\n') {
            out.push('\n');
        } else {
            out.push(c);
        }
    }
    Cow::Owned(out)
}

/// The text of a file's bytes (see [`decode`]), line ends as written.
fn decode_units<'a>(bytes: &'a [u8], name: &Path) -> Result<Cow<'a, str>> {
    let big_endian = match bytes {
        [0xFF, 0xFE, ..] => false,
        [0xFE, 0xFF, ..] => true,
        [0xEF, 0xBB, 0xBF, rest @ ..] => return Ok(String::from_utf8_lossy(rest)),
        _ => return Ok(String::from_utf8_lossy(bytes)),
    };
    let body = &bytes[2..];
    if !body.len().is_multiple_of(2) {
        return Err(Error::Parse {
            path: name.to_path_buf(),
            line: 0,
            message: format!(
                "starts with a UTF-16 byte-order mark but has an odd number of bytes ({})",
                bytes.len()
            ),
        });
    }
    let units = body.chunks_exact(2).map(|pair| {
        let pair = [pair[0], pair[1]];
        if big_endian {
            u16::from_be_bytes(pair)
        } else {
            u16::from_le_bytes(pair)
        }
    });
    Ok(Cow::Owned(
        char::decode_utf16(units)
            .map(|c| c.unwrap_or(char::REPLACEMENT_CHARACTER))
            .collect(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lone_carriage_returns_end_lines() {
        let name = Path::new("m.obj");
        assert_eq!(
            decode(b"v 0 0 0\rv 1 0 0\r", name).unwrap(),
            "v 0 0 0\nv 1 0 0\n"
        );
        assert_eq!(decode(b"a\r\nb\rc", name).unwrap(), "a\r\nb\nc");
        assert!(matches!(decode(b"a\nb", name).unwrap(), Cow::Borrowed(_)));
    }
}
