//! A token scanner that mirrors the grammar's tokens, for the two jobs the
//! grammar cannot do well: bounding the nesting depth before pest recurses,
//! and explaining in words why a parse failed.

use super::error::ParseError;
use crate::span::{Location, Span};

/// The deepest nesting of parentheses, calls, unary signs and `**` chains
/// that the parser and every later stage accept. Real expressions stay below 30.
pub const MAX_NESTING: usize = 200;

/// The kinds of token.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Number,
    Name,
    Open,
    Close,
    Comma,
    Colon,
    /// `+ - * / **`
    Operator,
    /// A character that starts no token.
    Other,
}

#[derive(Clone, Copy, Debug)]
struct Token {
    kind: Kind,
    span: Span,
}

/// Yields the tokens of `text`, skipping blanks.
struct Tokens<'a> {
    text: &'a str,
    offset: usize,
}

impl<'a> Tokens<'a> {
    fn new(text: &'a str) -> Self {
        Self { text, offset: 0 }
    }
}

fn is_name_char(byte: u8) -> bool {
    byte.is_ascii_alphanumeric() || byte == b'_'
}

/// Length of the number literal at the start of `bytes` (which starts with a
/// digit, or a `.` and a digit), including an exponent and a degree suffix.
fn number_len(bytes: &[u8]) -> usize {
    let digits = |from: usize| {
        bytes[from..]
            .iter()
            .take_while(|byte| byte.is_ascii_digit())
            .count()
    };
    let mut len = digits(0);
    if bytes.get(len) == Some(&b'.') {
        len += 1 + digits(len + 1);
    }
    if matches!(bytes.get(len), Some(b'e' | b'E')) {
        let sign = usize::from(matches!(bytes.get(len + 1), Some(b'+' | b'-')));
        let exponent = digits(len + 1 + sign);
        if exponent > 0 {
            len += 1 + sign + exponent;
        }
    }
    if matches!(bytes.get(len), Some(b'd' | b'D')) && fortran_exponent_len(&bytes[len..]) == 0 {
        let after = bytes.get(len + 1).copied();
        if !after.is_some_and(is_name_char) {
            len += 1;
        }
    }
    len
}

/// Length of a FORTRAN exponent `D3`, `d-5` at the start of `bytes`, or 0.
fn fortran_exponent_len(bytes: &[u8]) -> usize {
    if !matches!(bytes.first(), Some(b'd' | b'D')) {
        return 0;
    }
    let sign = usize::from(matches!(bytes.get(1), Some(b'+' | b'-')));
    let digits = bytes[1 + sign..]
        .iter()
        .take_while(|byte| byte.is_ascii_digit())
        .count();
    if digits == 0 { 0 } else { 1 + sign + digits }
}

/// Length of the name at the start of `bytes` (letters, digits, `_`, dots).
fn name_len(bytes: &[u8]) -> usize {
    bytes
        .iter()
        .take_while(|&&byte| is_name_char(byte) || byte == b'.')
        .count()
}

impl Iterator for Tokens<'_> {
    type Item = Token;

    fn next(&mut self) -> Option<Token> {
        let bytes = self.text.as_bytes();
        while bytes.get(self.offset).is_some_and(u8::is_ascii_whitespace) {
            self.offset += 1;
        }
        let rest = &bytes[self.offset..];
        let first = *rest.first()?;
        let (kind, len) = match first {
            b'0'..=b'9' => (Kind::Number, number_len(rest)),
            b'.' if rest.get(1).is_some_and(u8::is_ascii_digit) => (Kind::Number, number_len(rest)),
            b'.' | b'_' | b'a'..=b'z' | b'A'..=b'Z' => (Kind::Name, name_len(rest)),
            b'(' => (Kind::Open, 1),
            b')' => (Kind::Close, 1),
            b',' => (Kind::Comma, 1),
            b':' => (Kind::Colon, 1),
            b'*' if rest.get(1) == Some(&b'*') => (Kind::Operator, 2),
            b'+' | b'-' | b'*' | b'/' => (Kind::Operator, 1),
            _ => {
                let len = self.text[self.offset..].chars().next().map_or(1, char::len_utf8);
                (Kind::Other, len)
            }
        };
        let span = Span::new(self.offset, self.offset + len);
        self.offset += len;
        Some(Token { kind, span })
    }
}

/// Whether a token of this kind ends an operand (so an operator may follow).
fn ends_operand(kind: Option<Kind>) -> bool {
    matches!(kind, Some(Kind::Number | Kind::Name | Kind::Close))
}

/// Refuses text that nests deeper than [`MAX_NESTING`], before any recursive
/// parser sees it. Counts open parentheses, runs of unary signs and chains of
/// `**`, which are what the parser and the later stages recurse on.
pub fn check_nesting(text: &str) -> Result<(), ParseError> {
    // `chain` is the unary/power chain at the current level; `saved` keeps the
    // chain of each enclosing level, `depth` their total with the parentheses.
    let mut depth = 0usize;
    let mut chain = 0usize;
    let mut saved = Vec::new();
    let mut previous: Option<Kind> = None;
    for token in Tokens::new(text) {
        match token.kind {
            Kind::Open => {
                depth += 1 + chain;
                saved.push(chain);
                chain = 0;
            }
            Kind::Close => {
                if let Some(outer) = saved.pop() {
                    depth -= 1 + outer;
                    chain = outer;
                }
            }
            Kind::Operator if text[token.span.range()] == *"**" => chain += 1,
            Kind::Operator if !ends_operand(previous) => chain += 1,
            Kind::Operator | Kind::Comma | Kind::Colon => chain = 0,
            _ => {}
        }
        if depth + chain > MAX_NESTING {
            return Err(ParseError::TooDeep {
                limit: MAX_NESTING,
                span: token.span,
            });
        }
        previous = Some(token.kind);
    }
    Ok(())
}

/// An open parenthesis on the scanner's stack.
struct Opener {
    /// The function name when the parenthesis opens a call.
    function: Option<String>,
    span: Span,
}

/// Explains a failed parse: `offset` is where the grammar could go no further.
pub fn diagnose(text: &str, offset: usize) -> ParseError {
    let mut openers: Vec<Opener> = Vec::new();
    let mut previous: Option<Token> = None;
    let mut tokens = Tokens::new(text);
    let failing = loop {
        let Some(token) = tokens.next() else {
            break None;
        };
        if token.span.start >= offset {
            break Some(token);
        }
        match token.kind {
            Kind::Open => openers.push(Opener {
                function: previous
                    .filter(|token| token.kind == Kind::Name)
                    .map(|token| text[token.span.range()].to_uppercase()),
                span: token.span,
            }),
            Kind::Close => {
                openers.pop();
            }
            _ => {}
        }
        previous = Some(token);
    };
    let expects_operand = !ends_operand(previous.map(|token| token.kind));
    let Some(token) = failing else {
        return end_of_input(text, previous, openers.last(), expects_operand);
    };
    let found = &text[token.span.range()];
    let span = token.span;
    let character = found.chars().next().unwrap_or(' ');
    match character {
        '^' => return ParseError::Caret { span },
        '<' | '>' | '=' | '!' | '&' | '|' | '~' => {
            let operator: String = text[span.start..]
                .chars()
                .take_while(|c| "<>=!&|~".contains(*c))
                .collect();
            let span = Span::new(span.start, span.start + operator.len());
            return ParseError::Comparison { operator, span };
        }
        '{' | '}' => {
            return ParseError::TemplatePlaceholder {
                brace: character,
                span,
            };
        }
        _ => {}
    }
    if let Some(number) = previous.filter(|token| token.kind == Kind::Number)
        && number.span.end == span.start
    {
        let tail = fortran_exponent_len(&text.as_bytes()[span.start..]);
        if tail > 0 {
            let literal = &text[number.span.start..span.start + tail];
            let mantissa = &text[number.span.range()];
            return ParseError::FortranExponent {
                text: literal.to_string(),
                suggestion: format!("{mantissa}E{}", &text[span.start + 1..span.start + tail]),
                span: Span::new(number.span.start, span.start + tail),
            };
        }
    }
    match token.kind {
        Kind::Close if openers.is_empty() => return ParseError::UnmatchedClose { span },
        Kind::Comma | Kind::Colon if openers.is_empty() => {
            return ParseError::SeparatorOutsideCall {
                separator: character,
                span,
            };
        }
        Kind::Other => return ParseError::UnexpectedCharacter { character, span },
        _ => {}
    }
    if expects_operand {
        ParseError::ExpectedOperand {
            after: after_description(text, previous),
            found: format!("`{found}`"),
            span,
        }
    } else {
        let (expected, inside) = what_may_follow(openers.last());
        ParseError::ExpectedOperator {
            expected: expected.to_string(),
            found: format!("`{found}`"),
            inside,
            span,
        }
    }
}

/// The error for a parse that failed at the end of the input.
fn end_of_input(
    text: &str,
    previous: Option<Token>,
    innermost: Option<&Opener>,
    expects_operand: bool,
) -> ParseError {
    let span = Span::at(text.len());
    if previous.is_none() {
        return ParseError::Empty { span };
    }
    if expects_operand {
        return ParseError::ExpectedOperand {
            after: after_description(text, previous),
            found: "the end of the input".to_string(),
            span,
        };
    }
    match innermost {
        Some(opener) => ParseError::Unclosed {
            opener: opener_description(opener),
            column: Location::of(text, opener.span.start).column,
            span,
            opened: opener.span,
        },
        None => ParseError::ExpectedOperand {
            after: after_description(text, previous),
            found: "the end of the input".to_string(),
            span,
        },
    }
}

fn opener_description(opener: &Opener) -> String {
    match &opener.function {
        Some(function) => format!("the call of {function}"),
        None => "the `(`".to_string(),
    }
}

fn after_description(text: &str, previous: Option<Token>) -> String {
    match previous {
        None => "at the start".to_string(),
        Some(token) => format!("after `{}`", &text[token.span.range()]),
    }
}

/// What may follow a complete operand, and where we are ("" at the top).
fn what_may_follow(innermost: Option<&Opener>) -> (&'static str, String) {
    match innermost {
        Some(Opener {
            function: Some(function),
            ..
        }) => ("an operator, `,` or `)`", format!(" in the call of {function}")),
        Some(_) => ("an operator or `)`", String::new()),
        None => ("an operator or the end of the expression", String::new()),
    }
}
