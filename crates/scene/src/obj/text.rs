//! Bytes of an OBJ or MTL file as text: UTF-8 with stray bytes replaced,
//! or UTF-16 when the file starts with a byte-order mark (as editors on
//! Windows save "Unicode" text).

use std::borrow::Cow;
use std::path::Path;

use crate::error::{Error, Result};

/// Decodes a text file: a UTF-16 byte-order mark (little or big endian)
/// selects UTF-16, a UTF-8 one is dropped, anything else is read as UTF-8
/// with invalid bytes replaced by U+FFFD (old exporters write Latin-1
/// comments and names). An odd number of UTF-16 bytes is an error naming
/// `name`.
pub(super) fn decode<'a>(bytes: &'a [u8], name: &Path) -> Result<Cow<'a, str>> {
    let big_endian = match bytes {
        [0xFF, 0xFE, ..] => false,
        [0xFE, 0xFF, ..] => true,
        [0xEF, 0xBB, 0xBF, rest @ ..] => return Ok(String::from_utf8_lossy(rest)),
        _ => return Ok(String::from_utf8_lossy(bytes)),
    };
    let body = &bytes[2..];
    if body.len() % 2 != 0 {
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
