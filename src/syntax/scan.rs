//! A token scanner that mirrors the grammar's tokens, for the jobs the
//! grammar cannot do well: refusing, before pest recurses, input nested too
//! deep and the control characters the grammar's range of blanks would
//! take in, and explaining in words why a parse failed.

use super::error::ParseError;
use crate::span::{Location, Span};

/// The deepest tree the parser and every later stage accept: parentheses,
/// calls, and the operators of one group each add a level. The real corpus
/// stays below 40.
pub const MAX_NESTING: usize = 500;

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

/// The grammar's blanks: space, tab, and `\n`, `\v`, `\f`, `\r`.
fn is_blank(byte: &u8) -> bool {
    matches!(byte, b' ' | b'\t'..=b'\r')
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
        while bytes.get(self.offset).is_some_and(is_blank) {
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
                let len = self.text[self.offset..]
                    .chars()
                    .next()
                    .map_or(1, char::len_utf8);
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

/// The binary `+` and `-` outside any parenthesis of `text` (each after
/// an operand, and before a number or a name) at which a long expression
/// is cut into pieces of at least `piece` bytes: the loosest operators, so
/// the pieces' terms chained in order are the whole expression. A piece
/// never starts with a bracket, whose sum the parser would run on into
/// the terms after it. Their offsets.
pub(super) fn additive_cuts(text: &str, piece: usize) -> Vec<usize> {
    let mut cuts = Vec::new();
    let (mut depth, mut previous, mut piece_start) = (0usize, None, 0);
    // A cut that waits to see the token after its operator.
    let mut pending = None;
    for token in Tokens::new(text) {
        if let Some(cut) = pending.take()
            && matches!(token.kind, Kind::Number | Kind::Name)
        {
            cuts.push(cut);
            piece_start = cut;
        }
        match token.kind {
            Kind::Open => depth += 1,
            Kind::Close => depth = depth.saturating_sub(1),
            Kind::Operator
                if depth == 0
                    && token.span.len() == 1
                    && matches!(text.as_bytes()[token.span.start], b'+' | b'-')
                    && ends_operand(previous)
                    && token.span.start - piece_start >= piece =>
            {
                pending = Some(token.span.start);
            }
            _ => {}
        }
        previous = Some(token.kind);
    }
    cuts
}

/// `line` without its trailing comment: a `!` and all after it, as in model
/// files (`STEP(TIME, 0, 0, 1, 1) ! ramp`). A `!` directly before `=` is
/// not a comment but the comparison `!=`, which the parser refuses with its
/// own explanation.
pub fn without_comment(line: &str) -> &str {
    let bytes = line.as_bytes();
    let comment =
        (0..bytes.len()).find(|&at| bytes[at] == b'!' && bytes.get(at + 1) != Some(&b'='));
    match comment {
        Some(at) => &line[..at],
        None => line,
    }
}

/// Refuses what the grammar must not see, before any recursive parser runs:
/// a tree deeper than [`MAX_NESTING`], and the control characters `\x0E` to
/// `\x1F`, which the grammar's `blank` (one range from tab to space) would
/// otherwise take for blanks; they are explained as unexpected characters.
///
/// Depth is what the parser and every later stage recurse on: each open
/// parenthesis adds a level, and so does each sign before an operand and
/// each `**` (`- -x` and `a**b**c` nest). A run of `+ -` or `* /` is one
/// node of the tree whatever its length ([`crate::syntax::ast::ExprKind::Chain`]),
/// so a binary operator adds nothing.
pub fn precheck(text: &str) -> Result<(), ParseError> {
    let is_stray = |byte: u8| (0x0E..=0x1F).contains(&byte);
    // A pass with no early exit, which the compiler makes wide; the offset
    // is looked for only when there is one.
    if text
        .bytes()
        .fold(false, |found, byte| found | is_stray(byte))
    {
        let offset = text.bytes().position(is_stray).unwrap_or_default();
        return Err(diagnose(text, offset));
    }
    // Each level takes a byte at least (a parenthesis or an operator).
    if text.len() <= MAX_NESTING || nesting_bound(text) <= MAX_NESTING {
        return Ok(());
    }
    // `run` counts the signs and powers the current operand nests in;
    // `saved` keeps the run of each enclosing group; `depth` is their total
    // with the parentheses.
    let mut depth = 0usize;
    let mut run = 0usize;
    let mut saved = Vec::new();
    let mut previous = None;
    for token in Tokens::new(text) {
        match token.kind {
            Kind::Open => {
                depth += 1 + run;
                saved.push(run);
                run = 0;
            }
            Kind::Close => {
                if let Some(outer) = saved.pop() {
                    depth -= 1 + outer;
                    run = outer;
                }
            }
            Kind::Operator if !ends_operand(previous) || token.span.len() == 2 => run += 1,
            Kind::Operator | Kind::Comma | Kind::Colon => run = 0,
            _ => {}
        }
        if depth + run > MAX_NESTING {
            return Err(ParseError::TooDeep {
                limit: MAX_NESTING,
                span: token.span,
            });
        }
        previous = Some(token.kind);
    }
    Ok(())
}

/// A bound on the nesting [`precheck`] measures, from the bytes alone:
/// the deepest run of open parentheses plus every byte that could be an
/// operator (`**` and the sign of an exponent count too, so this is never
/// less). Nearly every real expression is far below the limit by this count,
/// and then the token scan is not needed.
fn nesting_bound(text: &str) -> usize {
    let (mut open, mut deepest, mut operators) = (0usize, 0usize, 0usize);
    for byte in text.bytes() {
        match byte {
            b'(' => {
                open += 1;
                deepest = deepest.max(open);
            }
            b')' => open = open.saturating_sub(1),
            b'+' | b'-' | b'*' | b'/' => operators += 1,
            _ => {}
        }
    }
    deepest + operators
}

/// An open parenthesis on the scanner's stack.
struct Opener {
    /// The function name when the parenthesis opens a call.
    function: Option<String>,
    span: Span,
}

/// Explains a failed parse. The scanner walks the tokens as the grammar
/// would and reports the first one that cannot stand where it is; pest's
/// `offset` (where its furthest rule attempt failed) is only the fallback for
/// input whose tokens are in order.
pub fn diagnose(text: &str, offset: usize) -> ParseError {
    let mut openers: Vec<Opener> = Vec::new();
    let mut previous: Option<Token> = None;
    for token in Tokens::new(text) {
        let expects_operand = !ends_operand(previous.map(|token| token.kind));
        let found = &text[token.span.range()];
        let fits = match token.kind {
            Kind::Number | Kind::Name => expects_operand,
            Kind::Open => expects_operand || previous.is_some_and(|token| token.kind == Kind::Name),
            Kind::Close => !expects_operand && !openers.is_empty(),
            Kind::Comma | Kind::Colon => {
                !expects_operand
                    && openers
                        .last()
                        .is_some_and(|opener| opener.function.is_some())
            }
            Kind::Operator => !expects_operand || found == "+" || found == "-",
            Kind::Other => false,
        };
        if !fits {
            return misplaced(text, token, previous, &openers, expects_operand);
        }
        match token.kind {
            Kind::Open => openers.push(Opener {
                function: previous
                    .filter(|token| token.kind == Kind::Name && !expects_operand)
                    .map(|token| text[token.span.range()].to_uppercase()),
                span: token.span,
            }),
            Kind::Close => {
                openers.pop();
            }
            _ => {}
        }
        previous = Some(token);
    }
    let expects_operand = !ends_operand(previous.map(|token| token.kind));
    if expects_operand || !openers.is_empty() {
        return end_of_input(text, previous, openers.last(), expects_operand);
    }
    // The tokens are in order; pest stopped for a reason of its own.
    let rest = text[offset.min(text.len())..].trim_start();
    let at = text.len() - rest.len();
    match Tokens::new(&text[at..]).next() {
        Some(token) => {
            let token = Token {
                kind: token.kind,
                span: token.span.shifted(at),
            };
            misplaced(text, token, None, &[], false)
        }
        None => end_of_input(text, previous, None, true),
    }
}

/// The error for `token`, which cannot stand where it is.
fn misplaced(
    text: &str,
    token: Token,
    previous: Option<Token>,
    openers: &[Opener],
    expects_operand: bool,
) -> ParseError {
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
        Kind::Comma | Kind::Colon if openers.iter().all(|opener| opener.function.is_none()) => {
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

/// A called name as messages show it: as written when it is a plain name
/// (`STEP`), in backticks when it has other characters (`` `.m.AZ.` ``), so
/// that a message never ends on a name's dot.
fn call_name(name: &str) -> String {
    if name
        .chars()
        .all(|character| character.is_ascii_alphanumeric() || character == '_')
    {
        name.to_string()
    } else {
        format!("`{name}`")
    }
}

fn opener_description(opener: &Opener) -> String {
    match &opener.function {
        Some(function) => format!("the call of {}", call_name(function)),
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
        }) => (
            "an operator, `,` or `)`",
            format!(" in the call of {}", call_name(function)),
        ),
        Some(_) => ("an operator or `)`", String::new()),
        None => ("an operator or the end of the expression", String::new()),
    }
}
