//! Model files: Adams solver datasets (`.adm`), command files (`.acf`) and
//! Adams View command files (`.cmd`). Every expression in them is found, with
//! the way back from each place in the expression to its line and column in
//! the file, checked, and its references to other statements verified.

mod adm;
mod cmd;
mod encoding;
pub(crate) mod initial;
pub(crate) mod linear_systems;
mod references;
mod script;
mod text;
mod variables;
mod view;
pub(crate) mod view_vocabulary;
pub mod vocabulary;
mod write;

use compact_str::CompactString;
use thiserror::Error;

pub use encoding::{Decoded, decode, decode_owned, is_binary};
pub use initial::{ConfigurationError, initial_scene};
pub use references::{FoundExpression, ModelCheck, ModelError, Problem, check_model};
pub use text::Embedded;
pub use variables::evaluation_order;
pub(crate) use view::{GENERAL_MOTION, GENERAL_MOTION_COMPONENTS};

use crate::span::Span;
use crate::syntax::MAX_NESTING;

/// Which reader a file takes, by its extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    /// A solver dataset: a title line, then statements.
    Adm,
    /// A solver command file: statements, `&` continuations.
    Acf,
    /// An Adams View command file.
    Cmd,
}

impl FileKind {
    /// The kind of a file named `path`, if it is a model file.
    pub fn of_path(path: &str) -> Option<FileKind> {
        let extension = path.rsplit_once('.')?.1.to_ascii_lowercase();
        match extension.as_str() {
            "adm" => Some(FileKind::Adm),
            "acf" => Some(FileKind::Acf),
            "cmd" => Some(FileKind::Cmd),
            _ => None,
        }
    }

    /// The kind of a file named `path` holding `text`: by its extension
    /// when that is `.adm`, `.acf` or `.cmd`, else by its first lines
    /// (`.dat`, `.mac`, no extension). A solver dataset is known by its
    /// title, `Adams View model name: ...` as Adams writes it, or by a first
    /// statement line (`UNITS/FORCE = NEWTON`, `PART/1, GROUND`) after a
    /// title; a command file by a statement on its first line. `None`: a
    /// file of expressions, one a line.
    pub fn detect(path: &str, text: &str) -> Option<FileKind> {
        if let Some(kind) = FileKind::of_path(path) {
            return Some(kind);
        }
        let mut lines = text.lines();
        let title = lines.next()?.to_ascii_lowercase();
        if title.contains("adams") && title.contains("model name") {
            return Some(FileKind::Adm);
        }
        if is_statement_line(&title, vocabulary::COMMANDS) {
            return Some(FileKind::Acf);
        }
        let first = lines
            .map(str::trim)
            .find(|line| !line.is_empty() && !line.starts_with('!'))?;
        is_statement_line(first, &vocabulary::DATASET_STATEMENTS).then_some(FileKind::Adm)
    }
}

/// Whether `line` reads as a statement of the vocabulary `known`: a known
/// name, a slash, and a `,` or `=` before any bracket (`PART/1, GROUND`;
/// never an expression such as `PART/2`).
fn is_statement_line(line: &str, known: &[&str]) -> bool {
    let Some((name, rest)) = line.trim().split_once('/') else {
        return false;
    };
    let name = name.trim().to_ascii_uppercase();
    let head = rest.split('(').next().unwrap_or_default();
    vocabulary::statement_name(&name, known).is_some() && head.contains([',', '='])
}

/// A model file as statements.
#[derive(Clone, Debug, PartialEq)]
pub struct Dataset {
    /// Which reader read it.
    pub kind: FileKind,
    /// The title line of a solver dataset.
    pub title: Option<String>,
    /// The statements (or View commands), in file order.
    pub statements: Vec<Statement>,
    /// Lines the reader could not read.
    pub problems: Vec<ReadError>,
}

/// One statement `NAME/id, KEY = value, ...` (or View command).
#[derive(Clone, Debug, PartialEq)]
pub struct Statement {
    /// The statement name, upper case (`SFORCE`; for View commands the
    /// command words, `FORCE CREATE DIRECT SINGLE_COMPONENT_FORCE`). Names,
    /// keywords and values are held inline up to 24 bytes: a model of
    /// 100 MB is millions of them.
    pub name: CompactString,
    /// The id after the slash, when there is one.
    pub id: Option<u64>,
    /// The statement's text in the file.
    pub span: Span,
    /// The arguments in order.
    pub arguments: Vec<Argument>,
}

impl Statement {
    /// Where argument `keyword` (abbreviated to no fewer than `shortest`
    /// letters) stands, or the statement's place when it is left out: where
    /// a message about the argument points.
    pub fn place_of(&self, keyword: &str, shortest: usize) -> Span {
        self.argument(keyword, shortest)
            .map_or(self.span, |argument| argument.span)
    }

    /// `SFORCE/7`, `PART`, for messages.
    pub fn label(&self) -> String {
        match self.id {
            Some(id) => format!("{}/{id}", self.name),
            None => self.name.to_string(),
        }
    }

    /// The argument whose keyword is `keyword` or abbreviates it (as the
    /// solver allows: `FUNC` for `FUNCTION`), given at least `shortest` letters.
    pub fn argument(&self, keyword: &str, shortest: usize) -> Option<&Argument> {
        self.arguments.iter().find(|argument| {
            argument.keyword.len() >= shortest.min(keyword.len())
                && keyword.starts_with(argument.keyword.as_str())
        })
    }

    /// The expressions among the arguments.
    pub fn expressions(&self) -> impl Iterator<Item = (&Argument, &Embedded)> {
        self.arguments
            .iter()
            .filter_map(|argument| match &argument.value {
                Value::Expression { text, .. } => Some((argument, text)),
                _ => None,
            })
    }
}

/// `KEY = value` or a bare `KEY`.
#[derive(Clone, Debug, PartialEq)]
pub struct Argument {
    /// The keyword, upper case, as written (possibly abbreviated).
    pub keyword: CompactString,
    /// Where the keyword stands.
    pub keyword_span: Span,
    /// The whole argument.
    pub span: Span,
    /// What follows the `=`.
    pub value: Value,
}

/// The value of an argument.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// A bare keyword (`GROUND`, `TRANSLATIONAL`).
    Flag,
    /// A list of values (`QP = 12, 0, 0`), each as written.
    List(Vec<ValueItem>),
    /// A function expression, joined across its continuation lines.
    Expression {
        /// The joined text and its map back to the file.
        text: Embedded,
        /// Where the expression stands in the file, continuations included.
        span: Span,
    },
}

/// The largest statement id: every whole number up to it is a double, so
/// that a reference to a statement (`I = 12`, read as a number) names it
/// and no other.
pub const LARGEST_ID: u64 = (1 << 53) - 1;

/// One item of a value list.
#[derive(Clone, Debug, PartialEq)]
pub struct ValueItem {
    /// The item as written.
    pub text: CompactString,
    /// Where it stands.
    pub span: Span,
}

impl ValueItem {
    /// The item as a number; a `D` suffix means degrees (converted to radians).
    pub fn number(&self) -> Option<f64> {
        let text = self.text.trim();
        let (digits, scale) = match text.strip_suffix(['d', 'D']) {
            Some(digits) => (digits, std::f64::consts::PI / 180.0),
            None => (text, 1.0),
        };
        digits
            .parse::<f64>()
            .ok()
            .filter(|value| value.is_finite())
            .map(|value| value * scale)
    }
}

/// A line a reader could not read.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ReadError {
    /// Text that is no statement.
    #[error(
        "this line is not a statement: expected NAME/id, KEY = value, ... (or a comment starting with `!`)"
    )]
    Unreadable {
        /// The line.
        span: Span,
    },
    /// Text in a View command file that is no command.
    #[error(
        "this is not a View command: expected its words, then `parameter = value` pairs, a line ending with `&` continuing on the next (or a comment starting with `!`)"
    )]
    UnreadableCommand {
        /// The command's text.
        span: Span,
    },
    /// A continuation line (`, KEY = value`) right after the title, where
    /// the title reads as a statement: a dataset without its title line.
    #[error(
        "this line continues `{statement}`, which is line 1, the dataset's title: Adams reads the first line as the title, never as a statement, so begin the file with a title line"
    )]
    ContinuesTheTitle {
        /// The statement the title reads as (`PART/1`).
        statement: String,
        /// The line.
        span: Span,
    },
    /// A statement's id past [`LARGEST_ID`]: the references to it are read
    /// as numbers, which hold every whole number only up to there.
    #[error("this id is too large: ids are whole numbers up to {LARGEST_ID} (2^53 - 1)")]
    IdTooLarge {
        /// The id.
        span: Span,
    },
    /// Brackets nested too deep for the recursive readers.
    #[error(
        "brackets nest deeper than {limit} levels here, so the file is not read (real models stay below 40)"
    )]
    TooDeep {
        /// The limit.
        limit: usize,
        /// The bracket past the limit.
        span: Span,
    },
    /// A View command file whose loops write more commands than the
    /// reader takes.
    #[error(
        "the loops here write more than {limit} commands, so the file is not read: check the loop's bounds (the largest models users have are about 50 000 commands)"
    )]
    TooManyCommands {
        /// The limit.
        limit: usize,
        /// The loop, or the command past the limit.
        span: Span,
    },
    /// View loops that go round more times than the reader takes.
    #[error(
        "the loops here go round more than {limit} times, so the file is not read: check the loops' bounds and conditions"
    )]
    TooManyRounds {
        /// The limit.
        limit: usize,
        /// The loop that went past it.
        span: Span,
    },
    /// View loops and `if` blocks nested past the limit.
    #[error("loops and `if` blocks nest deeper than {limit} levels here, so the file is not read")]
    NestedTooDeep {
        /// The limit.
        limit: usize,
        /// The block past the limit.
        span: Span,
    },
}

impl ReadError {
    /// Where the problem is.
    pub fn span(&self) -> Span {
        match self {
            ReadError::Unreadable { span }
            | ReadError::UnreadableCommand { span }
            | ReadError::ContinuesTheTitle { span, .. }
            | ReadError::IdTooLarge { span }
            | ReadError::TooDeep { span, .. }
            | ReadError::TooManyCommands { span, .. }
            | ReadError::TooManyRounds { span, .. }
            | ReadError::NestedTooDeep { span, .. } => *span,
        }
    }
}

/// A View name as the readers key it (`model::script`'s variables, the
/// View reader's objects): upper case, without quotes and the leading dot.
pub(crate) fn view_key(name: &str) -> String {
    name.trim()
        .trim_matches('"')
        .trim_start_matches('.')
        .to_ascii_uppercase()
}

/// Reads a model file of the given kind.
pub fn read(text: &str, kind: FileKind) -> Dataset {
    if let Some(span) = too_deep(text) {
        return Dataset {
            kind,
            title: None,
            statements: Vec::new(),
            problems: vec![ReadError::TooDeep {
                limit: MAX_NESTING,
                span,
            }],
        };
    }
    match kind {
        FileKind::Adm | FileKind::Acf => adm::read(text, kind),
        FileKind::Cmd => cmd::read(text),
    }
}

/// The first bracket nested deeper than [`MAX_NESTING`] within one
/// statement, which the recursive grammars must not see. The count starts
/// again at every line that begins a statement (a letter first, the line
/// before not ending in `&`).
fn too_deep(text: &str) -> Option<Span> {
    let mut depth = 0usize;
    let mut continued = false;
    for (start, line) in text.split_inclusive('\n').scan(0, |offset, line| {
        let start = *offset;
        *offset += line.len();
        Some((start, line))
    }) {
        if !continued
            && line
                .trim_start()
                .starts_with(|c: char| c.is_ascii_alphabetic())
        {
            depth = 0;
        }
        for (index, byte) in line.bytes().enumerate() {
            match byte {
                b'(' | b'{' => depth += 1,
                b')' | b'}' => depth = depth.saturating_sub(1),
                _ => continue,
            }
            if depth > MAX_NESTING {
                return Some(Span::at(start + index));
            }
        }
        continued = line.trim_end().ends_with('&');
    }
    None
}

/// How many bytes a piece that [`pieces`] gives grows to before it is cut
/// at the next line that begins a statement.
const PIECE: usize = 64 * 1024;

/// The file cut into pieces of about [`PIECE`] bytes, each cut at the
/// start of a line that begins a statement or command: a letter (or `_` in
/// a View command file) first, and no `&` on the last line before it that
/// is neither blank nor a comment (it would continue onto this line). No
/// statement runs across a cut, since a continuation line starts with `,`
/// or follows a `&`, so the readers parse each piece on its own and pest's
/// tokens never hold more than one piece. A dataset's first piece holds its
/// title line.
fn pieces(text: &str, kind: FileKind) -> impl Iterator<Item = std::ops::Range<usize>> + '_ {
    let begins = move |c: char| c.is_ascii_alphabetic() || (kind == FileKind::Cmd && c == '_');
    let mut start = 0;
    let mut offset = 0;
    let mut continued = false;
    let mut lines = text.split_inclusive('\n');
    std::iter::from_fn(move || {
        if start >= text.len() {
            return None;
        }
        for line in lines.by_ref() {
            let line_start = offset;
            offset += line.len();
            let content = line.trim_start();
            let cut = line_start - start >= PIECE && !continued && content.starts_with(begins);
            if !content.is_empty() && !content.starts_with('!') {
                continued = content.contains('&');
            }
            if cut {
                let piece = start..line_start;
                start = line_start;
                return Some(piece);
            }
        }
        let piece = start..text.len();
        start = text.len();
        Some(piece)
    })
}

/// Whether a statement named `name` is of `kind` (statement names may be
/// abbreviated to four letters or more).
pub fn is_kind(name: &str, kind: &str) -> bool {
    name == kind || (name.len() >= 4 && kind.starts_with(name))
}

/// Whether `statement` is of `kind`.
pub fn is_statement(statement: &Statement, kind: &str) -> bool {
    is_kind(&statement.name, kind)
}

/// The byte offset where a pest parse stopped.
fn pest_offset<R>(error: &pest::error::Error<R>) -> usize {
    match error.location {
        pest::error::InputLocation::Pos(offset) => offset,
        pest::error::InputLocation::Span((start, _)) => start,
    }
}
