//! How a number reads in a message or a table: the one formatter every
//! message of the library and every table and output row of the binary
//! goes through.

use std::fmt;

/// A number as messages and tables show it: the shortest text that reads
/// back to the same double (written by zmij), in exponent form below `1e-5`
/// and from `1e16` on (`-1e300`, `1.5e-7`), no `.0` on a whole number, `-0`
/// as `0`, and `inf`, `-inf`, `NaN`.
///
/// ```
/// use mbexpr::Shown;
/// assert_eq!(Shown(-1e300).to_string(), "-1e300");
/// assert_eq!(Shown(0.1 + 0.2).to_string(), "0.30000000000000004");
/// assert_eq!(Shown(5e-324).to_string(), "5e-324");
/// assert_eq!(Shown(100.0).to_string(), "100");
/// assert_eq!(Shown(-0.0).to_string(), "0");
/// assert_eq!(format!("{:>6}", Shown(2.5)), "   2.5");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shown(pub f64);

/// Room to write numbers in, reused from number to number (no allocation).
pub struct ShownBuffer(zmij::Buffer);

impl ShownBuffer {
    /// An empty buffer.
    pub fn new() -> ShownBuffer {
        ShownBuffer(zmij::Buffer::new())
    }
}

impl Default for ShownBuffer {
    fn default() -> ShownBuffer {
        ShownBuffer::new()
    }
}

impl Shown {
    /// The text in three pieces written in `buffer`: the digits, then `e`
    /// and the exponent, or two empty pieces (zmij writes `1e+16` and
    /// `100.0`, shown as `1e16` and `100`).
    pub fn pieces(self, buffer: &mut ShownBuffer) -> [&str; 3] {
        // `+ 0.0` turns -0 into 0 and leaves every other value as it is.
        let printed = buffer.0.format(self.0 + 0.0);
        let printed = printed.strip_suffix(".0").unwrap_or(printed);
        match printed.bytes().position(|byte| byte == b'e') {
            Some(at) => [
                &printed[..at],
                "e",
                printed[at + 1..].trim_start_matches('+'),
            ],
            None => [printed, "", ""],
        }
    }
}

/// Takes a width and alignment (`{:>24}`) as a string does.
impl fmt::Display for Shown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut buffer = ShownBuffer::new();
        let pieces = self.pieces(&mut buffer);
        if f.width().is_some() {
            return f.pad(&pieces.concat());
        }
        for piece in pieces {
            f.write_str(piece)?;
        }
        Ok(())
    }
}

/// A count and its noun as every message writes one: the noun in the
/// plural unless the count is 1 (`1 event`, `2 events`, `0 bodies`,
/// `3 lu decompositions`; a noun of several words takes the plural on its
/// last).
///
/// ```
/// use mbexpr::Counted;
/// assert_eq!(Counted(1, "jacobian").to_string(), "1 jacobian");
/// assert_eq!(Counted(2, "body").to_string(), "2 bodies");
/// assert_eq!(Counted(0, "entry").to_string(), "0 entries");
/// assert_eq!(Counted(4, "day").to_string(), "4 days");
/// assert_eq!(Counted(2, "right-hand side").to_string(), "2 right-hand sides");
/// assert_eq!(Counted(3, "match").to_string(), "3 matches");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Counted<'a>(pub usize, pub &'a str);

impl fmt::Display for Counted<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Counted(count, noun) = *self;
        if count == 1 {
            return write!(f, "1 {noun}");
        }
        let before_last = noun.chars().rev().nth(1).unwrap_or('a');
        if let Some(stem) = noun.strip_suffix('y')
            && !"aeiou".contains(before_last)
        {
            write!(f, "{count} {stem}ies")
        } else if ["s", "x", "z", "ch", "sh"]
            .iter()
            .any(|ending| noun.ends_with(ending))
        {
            write!(f, "{count} {noun}es")
        } else {
            write!(f, "{count} {noun}s")
        }
    }
}
