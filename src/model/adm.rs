//! Reading Adams solver datasets (`.adm`) and command files (`.acf`) with
//! `grammar/dataset.pest`. No pest type leaves this file.

use pest::Parser;
use pest::iterators::Pair;
use pest_derive::Parser;

use super::text::Embedded;
use super::{Argument, Dataset, FileKind, ReadError, Statement, Value, ValueItem};
use crate::span::Span;

#[derive(Parser)]
#[grammar = "../grammar/dataset.pest"]
struct DatasetParser;

/// The span of a pair in the file, its piece starting at byte `base`.
fn span_of(pair: &Pair<'_, Rule>, base: usize) -> Span {
    Span::new(pair.as_span().start(), pair.as_span().end()).shifted(base)
}

/// Reads the statements of a dataset (`FileKind::Adm`, with its title line)
/// or command file (`FileKind::Acf`). Lines that are no statement are
/// reported and skipped; the rest is read.
pub fn read(text: &str, kind: FileKind) -> Dataset {
    let rule = match kind {
        FileKind::Acf => Rule::acf,
        _ => Rule::adm,
    };
    let mut dataset = Dataset {
        kind,
        title: None,
        statements: Vec::new(),
        problems: Vec::new(),
    };
    // Piece by piece, so that pest's tokens are those of one piece at a
    // time, not of the whole file.
    for (index, piece) in super::pieces(text, kind).enumerate() {
        let rule = if index == 0 { rule } else { Rule::acf };
        let base = piece.start;
        let top = match DatasetParser::parse(rule, &text[piece]) {
            Ok(mut pairs) => pairs.next().expect("the top rule matched"),
            Err(error) => {
                // The grammar takes any line (`unreadable`), so this is rare: a
                // stray byte pest cannot take at all.
                let offset = base + super::pest_offset(&error);
                dataset.problems.push(ReadError::Unreadable {
                    span: Span::new(offset, offset),
                });
                continue;
            }
        };
        for pair in top.into_inner() {
            match pair.as_rule() {
                Rule::title => dataset.title = Some(pair.as_str().trim_end().to_string()),
                Rule::statement => {
                    let (statement, id_too_large) = statement(pair, base);
                    dataset.problems.extend(id_too_large);
                    dataset.statements.push(statement);
                }
                Rule::unreadable => {
                    let span = trimmed_span(&pair, base);
                    let continues_title = dataset.statements.is_empty()
                        && pair.as_str().trim_start().starts_with(',');
                    let problem = match dataset.title.as_deref().and_then(statement_name) {
                        Some(statement) if continues_title => {
                            ReadError::ContinuesTheTitle { statement, span }
                        }
                        _ => ReadError::Unreadable { span },
                    };
                    dataset.problems.push(problem);
                }
                _ => {}
            }
        }
    }
    dataset
}

/// The `NAME/id` a title line starts with where it reads as a statement
/// (`PART/1, GROUND` gives `PART/1`), in capitals.
fn statement_name(title: &str) -> Option<String> {
    let head = title.split(',').next()?.trim();
    let (name, id) = head.split_once('/')?;
    let named = !name.is_empty() && name.chars().all(|c| c.is_ascii_alphabetic() || c == '_');
    let numbered = !id.trim().is_empty() && id.trim().chars().all(|c| c.is_ascii_digit());
    (named && numbered).then(|| format!("{}/{}", name.to_ascii_uppercase(), id.trim()))
}

/// The span of a pair without its trailing blanks and line break.
fn trimmed_span(pair: &Pair<'_, Rule>, base: usize) -> Span {
    let span = span_of(pair, base);
    Span::new(span.start, span.start + pair.as_str().trim_end().len())
}

/// A statement, and the error of its id when the id is too large to hold.
fn statement(pair: Pair<'_, Rule>, base: usize) -> (Statement, Option<ReadError>) {
    let span = trimmed_span(&pair, base);
    let mut name = String::new();
    let mut id = None;
    let mut id_too_large = None;
    let mut arguments = Vec::new();
    for part in pair.into_inner() {
        match part.as_rule() {
            Rule::statement_name => name = part.as_str().to_uppercase(),
            Rule::id => {
                id = part
                    .as_str()
                    .parse()
                    .ok()
                    .filter(|&id| id <= super::LARGEST_ID);
                if id.is_none() {
                    id_too_large = Some(ReadError::IdTooLarge {
                        span: span_of(&part, base),
                    });
                }
            }
            Rule::expression_argument => arguments.push(expression_argument(part, base)),
            Rule::plain_argument => arguments.push(plain_argument(part, base)),
            _ => {}
        }
    }
    let statement = Statement {
        name: name.into(),
        id,
        span,
        arguments,
    };
    (statement, id_too_large)
}

fn expression_argument(pair: Pair<'_, Rule>, base: usize) -> Argument {
    let span = span_of(&pair, base);
    let mut keyword = String::new();
    let mut keyword_span = span;
    let mut embedded = Embedded::default();
    let mut expression_span = Span::at(span.end);
    for part in pair.into_inner() {
        match part.as_rule() {
            Rule::expression_key => {
                keyword = part.as_str().to_uppercase();
                keyword_span = span_of(&part, base);
            }
            Rule::expression => {
                expression_span = span_of(&part, base);
                // The expression's text without its continuation markers.
                let text = part.as_str();
                let start = expression_span.start;
                let mut cursor = 0;
                for continuation in part.into_inner() {
                    let cut = span_of(&continuation, base);
                    embedded.push(&text[cursor..cut.start - start], start + cursor);
                    cursor = cut.end - start;
                }
                embedded.push(&text[cursor..], start + cursor);
            }
            _ => {}
        }
    }
    Argument {
        keyword: keyword.into(),
        keyword_span,
        span,
        value: Value::Expression {
            text: embedded,
            span: expression_span,
        },
    }
}

fn plain_argument(pair: Pair<'_, Rule>, base: usize) -> Argument {
    let span = span_of(&pair, base);
    let mut keyword = String::new();
    let mut keyword_span = span;
    let mut items = Vec::new();
    for part in pair.into_inner() {
        match part.as_rule() {
            Rule::keyword => {
                keyword = part.as_str().to_uppercase();
                keyword_span = span_of(&part, base);
            }
            Rule::values => {
                for item in part
                    .into_inner()
                    .filter(|item| matches!(item.as_rule(), Rule::value | Rule::empty_value))
                {
                    let text = item.as_str().trim_end();
                    let start = base + item.as_span().start();
                    items.push(ValueItem {
                        text: text.into(),
                        span: Span::new(start, start + text.len()),
                    });
                }
            }
            _ => {}
        }
    }
    Argument {
        keyword: keyword.into(),
        keyword_span,
        span,
        value: if items.is_empty() {
            Value::Flag
        } else {
            Value::List(items)
        },
    }
}
