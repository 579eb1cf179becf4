//! Reading Adams View command files (`.cmd`) with `grammar/command.pest`.
//! No pest type leaves this file.

use pest::Parser;
use pest::iterators::Pair;
use pest_derive::Parser;

use super::text::Embedded;
use super::view_vocabulary;
use super::{Argument, Dataset, FileKind, ReadError, Statement, Value, ValueItem};
use crate::span::Span;

#[derive(Parser)]
#[grammar = "../grammar/command.pest"]
struct CommandParser;

/// The span of a pair in the file, its piece starting at byte `base`.
fn span_of(pair: &Pair<'_, Rule>, base: usize) -> Span {
    Span::new(pair.as_span().start(), pair.as_span().end()).shifted(base)
}

/// Whether a parameter holds an expression: `function`, `*_function`, `f1` ... `f8`,
/// a sensor's `evaluate`.
fn holds_expression(name: &str) -> bool {
    let name = name.to_ascii_lowercase();
    name == "function"
        || name == "evaluate"
        || name.ends_with("_function")
        || (name.len() == 2 && name.starts_with('f') && name.as_bytes()[1].is_ascii_digit())
}

/// Reads the commands of a View command file.
pub fn read(text: &str) -> Dataset {
    let mut dataset = Dataset {
        kind: FileKind::Cmd,
        title: None,
        statements: Vec::new(),
        problems: Vec::new(),
    };
    // Piece by piece, so that pest's tokens are those of one piece at a time.
    for piece in super::pieces(text, FileKind::Cmd) {
        let base = piece.start;
        let top = match CommandParser::parse(Rule::cmd, &text[piece]) {
            Ok(mut pairs) => pairs.next().expect("the top rule matched"),
            Err(error) => {
                let offset = base + super::pest_offset(&error);
                dataset.problems.push(ReadError::UnreadableCommand {
                    span: Span::at(offset),
                });
                continue;
            }
        };
        for pair in top.into_inner() {
            match pair.as_rule() {
                Rule::command => dataset.statements.push(command(pair, base)),
                Rule::unreadable => {
                    let span = span_of(&pair, base);
                    let length = pair.as_str().trim_end().len();
                    dataset.problems.push(ReadError::UnreadableCommand {
                        span: Span::new(span.start, span.start + length),
                    });
                }
                _ => {}
            }
        }
    }
    // View's command language carried out: variables, loops, `if`
    // blocks and values in parentheses.
    let (statements, problem) = super::script::carry_out(std::mem::take(&mut dataset.statements));
    dataset.statements = statements;
    dataset.problems.extend(problem);
    dataset
}

/// A command, its words and parameters in full where they are View's
/// abbreviations of them (`view_vocabulary`).
fn command(pair: Pair<'_, Rule>, base: usize) -> Statement {
    let span = span_of(&pair, base);
    let span = Span::new(span.start, span.start + pair.as_str().trim_end().len());
    let mut written = Vec::new();
    let mut parameters = Vec::new();
    for part in pair.into_inner() {
        match part.as_rule() {
            Rule::words => written.extend(part.into_inner().map(|word| word.as_str())),
            Rule::parameter => parameters.push(part),
            _ => {}
        }
    }
    let (words, known) = view_vocabulary::command(&written);
    let arguments: Vec<Argument> = parameters
        .into_iter()
        .map(|part| parameter(part, base, known))
        .collect();
    let id = arguments
        .iter()
        .find(|argument: &&Argument| argument.keyword == "ADAMS_ID")
        .and_then(|argument| match &argument.value {
            Value::List(items) => items
                .first()
                .and_then(|item| item.text.parse().ok())
                .filter(|&id| id <= super::LARGEST_ID),
            _ => None,
        });
    Statement {
        name: words.join(" ").into(),
        id,
        span,
        arguments,
    }
}

/// A parameter of `command`, its keyword in full where it abbreviates one
/// of the command's alone.
fn parameter(
    pair: Pair<'_, Rule>,
    base: usize,
    command: Option<view_vocabulary::Command>,
) -> Argument {
    let span = span_of(&pair, base);
    let mut inner = pair.into_inner();
    let name = inner.next().expect("a parameter starts with its name");
    let keyword = match command.map(|command| command.parameter(name.as_str())) {
        Some(view_vocabulary::Meaning::One(full)) => full.to_ascii_uppercase(),
        _ => name.as_str().to_uppercase(),
    };
    let keyword_span = span_of(&name, base);
    let values: Vec<Pair<'_, Rule>> = inner.flat_map(|values| values.into_inner()).collect();
    let value = if holds_expression(&keyword) {
        let mut embedded = Embedded::default();
        let mut expression_span: Option<Span> = None;
        for value in &values {
            let (text, start) = match value.as_rule() {
                Rule::string => {
                    let body = value
                        .clone()
                        .into_inner()
                        .next()
                        .expect("a string has a body");
                    (body.as_str(), base + body.as_span().start())
                }
                _ => (value.as_str(), base + value.as_span().start()),
            };
            embedded.push(text, start);
            let piece = span_of(value, base);
            expression_span = Some(expression_span.map_or(piece, |known| known.to(piece)));
        }
        let span = expression_span.unwrap_or(span);
        if embedded.text.is_empty() {
            // `function = ""`: View's "no function yet"; a message about
            // it points inside the quotes.
            embedded = Embedded::empty_at((span.start + 1).min(span.end));
        }
        Value::Expression {
            text: embedded,
            span,
        }
    } else {
        Value::List(
            values
                .iter()
                .map(|value| ValueItem {
                    text: value.as_str().trim_matches('"').into(),
                    span: span_of(value, base),
                })
                .collect(),
        )
    };
    Argument {
        keyword: keyword.into(),
        keyword_span,
        span,
        value,
    }
}
