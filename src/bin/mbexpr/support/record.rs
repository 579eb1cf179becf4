//! One result of `eval` as JSON: the value with its derivatives named by
//! their directions, or every problem with its place; the name of the
//! expression and the row of `--points` when there are ones.

use mbexpr::{Evaluation, Location, Span};
use nalgebra::DMatrix;
use serde::ser::{Serialize, SerializeMap, SerializeSeq, Serializer};

/// A problem an expression or a row has: its message and, when it is in
/// the expression, the line and column there.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Problem {
    /// What is wrong and what to do.
    pub message: String,
    /// The place in the expression, when the problem has one.
    #[serde(flatten)]
    pub place: Option<Place>,
    /// The bytes of the expression it is about, for the caret.
    #[serde(skip)]
    pub span: Option<Span>,
}

/// A line and column in the expression.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Place {
    /// 1-based line.
    pub line: usize,
    /// 1-based column, in characters.
    pub column: usize,
}

impl Problem {
    /// A problem at `span` of the expression `source`.
    pub fn at(source: &str, span: Span, message: impl ToString) -> Problem {
        let Location { line, column } = Location::of(source, span.start);
        Problem {
            message: message.to_string(),
            place: Some(Place { line, column }),
            span: Some(span),
        }
    }

    /// A problem with no place in the expression (a cell of a row).
    pub fn plain(message: impl ToString) -> Problem {
        Problem {
            message: message.to_string(),
            place: None,
            span: None,
        }
    }

    /// `error at 1:5: message` or `error: message`, for text output.
    pub fn headline(&self) -> String {
        match self.place {
            Some(Place { line, column }) => format!("error at {line}:{column}: {}", self.message),
            None => format!("error: {}", self.message),
        }
    }
}

/// One result: `{"name", "row", "value", "wrt", "gradient", "hessian"}`,
/// or `{"name", "row", "errors"}`; `name` and `row` only when there are.
pub struct Record<'a> {
    /// The name of the expression (the scene's named expressions).
    pub name: Option<&'a str>,
    /// The line of the row in the `--points` file.
    pub row: Option<u64>,
    /// The derivative directions, in the order of the gradient.
    pub wrt: &'a [String],
    /// The evaluation, or what went wrong.
    pub result: Result<&'a Evaluation, &'a [Problem]>,
}

impl Serialize for Record<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        if let Some(name) = self.name {
            map.serialize_entry("name", name)?;
        }
        if let Some(row) = self.row {
            map.serialize_entry("row", &row)?;
        }
        match self.result {
            Ok(evaluation) => {
                map.serialize_entry("value", &tidy(evaluation.value))?;
                if let Some(gradient) = &evaluation.gradient {
                    map.serialize_entry("wrt", self.wrt)?;
                    map.serialize_entry("gradient", &Tidy(gradient.iter()))?;
                }
                if let Some(hessian) = &evaluation.hessian {
                    map.serialize_entry("hessian", &Rows(hessian))?;
                }
            }
            Err(problems) => map.serialize_entry("errors", problems)?,
        }
        map.end()
    }
}

/// `-0` as `0`.
pub fn tidy(value: f64) -> f64 {
    value + 0.0
}

/// Numbers, each [`tidy`].
struct Tidy<I>(I);

impl<'a, I: Iterator<Item = &'a f64> + Clone> Serialize for Tidy<I> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.0.clone().map(|&entry| tidy(entry)))
    }
}

/// A matrix as an array of its rows.
struct Rows<'a>(&'a DMatrix<f64>);

impl Serialize for Rows<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut rows = serializer.serialize_seq(Some(self.0.nrows()))?;
        for row in self.0.row_iter() {
            rows.serialize_element(&Tidy(row.iter()))?;
        }
        rows.end()
    }
}
