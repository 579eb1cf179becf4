//! The bytes of a file as text. A file is UTF-8 unless a byte-order mark
//! says UTF-16; a file that is not valid UTF-8 is read as Windows-1252, the
//! code page of models saved on Windows, in which every byte is a character
//! (`è`, `°`, `’` in a comment, a title or an `adams_view_name`). Each
//! character stays one column, so places in messages stay right. A UTF-8
//! byte-order mark is dropped. A text holding a NUL, or more than one
//! control character in `BINARY_SHARE` of its start, is no text file at
//! all (a library, an image): [`is_binary`]. (`docs/encoding.md` gives the
//! rule.)

use std::borrow::Cow;

use encoding_rs::{Encoding, WINDOWS_1252};

/// A file's text and the encoding it was read in.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Decoded<'b> {
    /// The text.
    pub text: Cow<'b, str>,
    /// `UTF-8`, `UTF-16LE`, `UTF-16BE` or `windows-1252`.
    pub encoding: &'static str,
}

/// The text of `bytes`, by the rule of the module, and its encoding: a
/// UTF-8 file becomes its text without a copy.
pub fn decode_owned(bytes: Vec<u8>) -> (String, &'static str) {
    match String::from_utf8(bytes) {
        Ok(text) if !text.starts_with('\u{feff}') => (text, "UTF-8"),
        Ok(text) => {
            let decoded = decode(text.as_bytes());
            (decoded.text.into_owned(), decoded.encoding)
        }
        Err(error) => {
            let decoded = decode(error.as_bytes());
            (decoded.text.into_owned(), decoded.encoding)
        }
    }
}

/// The text of `bytes`, by the rule of the module.
pub fn decode(bytes: &[u8]) -> Decoded<'_> {
    if let Some((encoding, bom)) = Encoding::for_bom(bytes) {
        let (text, _) = encoding.decode_without_bom_handling(&bytes[bom..]);
        return Decoded {
            text,
            encoding: encoding.name(),
        };
    }
    match std::str::from_utf8(bytes) {
        Ok(text) => Decoded {
            text: Cow::Borrowed(text),
            encoding: "UTF-8",
        },
        Err(_) => {
            let (text, _) = WINDOWS_1252.decode_without_bom_handling(bytes);
            Decoded {
                text,
                encoding: WINDOWS_1252.name(),
            }
        }
    }
}

/// A text is binary when more than one character in this many of its start
/// is a control character other than a blank.
const BINARY_SHARE: usize = 20;

/// Characters of a text's start that [`is_binary`] looks at.
const BINARY_WINDOW: usize = 64 * 1024;

/// Whether the decoded `text` is the content of a binary file rather than
/// text: it holds a NUL character, or more than one character in
/// `BINARY_SHARE` of its first 64 Ki characters is a control character
/// other than tab, line feed, carriage return, form feed and the DOS end
/// of file (`^Z`).
pub fn is_binary(text: &str) -> bool {
    if text.contains('\0') {
        return true;
    }
    let (mut characters, mut controls) = (0usize, 0usize);
    for character in text.chars().take(BINARY_WINDOW) {
        characters += 1;
        if character.is_control() && !matches!(character, '\t' | '\n' | '\r' | '\x0c' | '\x1a') {
            controls += 1;
        }
    }
    controls * BINARY_SHARE > characters
}
