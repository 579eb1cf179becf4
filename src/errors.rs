//! A list of errors from one stage, reported together.

use std::fmt;
use std::ops::Deref;

/// Every problem a stage found, in source order (never empty).
///
/// Derefs to a slice, and implements `Error`, so `?` works in functions that
/// return `Box<dyn Error>`; its `Display` shows the first error and how many
/// more there are.
#[derive(Clone, Debug, PartialEq)]
pub struct Errors<E>(pub Vec<E>);

impl<E> Deref for Errors<E> {
    type Target = [E];

    fn deref(&self) -> &[E] {
        &self.0
    }
}

impl<E> IntoIterator for Errors<E> {
    type Item = E;
    type IntoIter = std::vec::IntoIter<E>;

    fn into_iter(self) -> Self::IntoIter {
        self.0.into_iter()
    }
}

impl<'a, E> IntoIterator for &'a Errors<E> {
    type Item = &'a E;
    type IntoIter = std::slice::Iter<'a, E>;

    fn into_iter(self) -> Self::IntoIter {
        self.0.iter()
    }
}

impl<E: fmt::Display> fmt::Display for Errors<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0.as_slice() {
            [] => f.write_str("no error"),
            [only] => write!(f, "{only}"),
            [first, rest @ ..] => write!(f, "{first} (and {} more)", rest.len()),
        }
    }
}

impl<E: std::error::Error> std::error::Error for Errors<E> {}
