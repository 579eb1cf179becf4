//! What can be wrong with the text of an expression.

use thiserror::Error;

use crate::span::Span;

/// A syntax error: the text is not an expression of the language.
///
/// Every variant carries the span it speaks of; the message says in plain
/// words what was found and what to write instead.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ParseError {
    /// Nothing but blanks.
    #[error("the expression is empty")]
    Empty {
        /// Where the expression should have been.
        span: Span,
    },
    /// An operand was needed (after an operator, `(`, `,` or at the start).
    #[error("expected a number, a name, a sign or `(` {after}, found {found}")]
    ExpectedOperand {
        /// "after `*`", "at the start", ...
        after: String,
        /// What stands there instead, in words.
        found: String,
        /// Where the operand should start.
        span: Span,
    },
    /// Two operands with nothing between them.
    #[error("expected {expected} before {found}{inside}")]
    ExpectedOperator {
        /// What may stand here ("an operator, `,` or `)`").
        expected: String,
        /// What stands there instead.
        found: String,
        /// " in the call of STEP", or nothing at the top level.
        inside: String,
        /// The unexpected token.
        span: Span,
    },
    /// The input ended inside a call or parenthesis.
    #[error("expected `)` to close {opener} opened at column {column}")]
    Unclosed {
        /// "the call of STEP" or "the `(`".
        opener: String,
        /// Column of the opening parenthesis.
        column: usize,
        /// The end of the input.
        span: Span,
        /// The opening parenthesis.
        opened: Span,
    },
    /// A `)` with no open parenthesis.
    #[error("unmatched `)`: no parenthesis is open here; remove it or add the `(` it closes")]
    UnmatchedClose {
        /// The stray parenthesis.
        span: Span,
    },
    /// A `,` or `:` outside any call.
    #[error("`{separator}` outside a call: arguments are separated only inside `NAME( ... )`")]
    SeparatorOutsideCall {
        /// The separator found.
        separator: char,
        /// Where it stands.
        span: Span,
    },
    /// `^` used as a power.
    #[error("`^` is not an operator in this language: write `**` for a power")]
    Caret {
        /// The caret.
        span: Span,
    },
    /// A comparison or logical operator.
    #[error(
        "`{operator}` is not an operator: the language has no comparisons; choose by sign with IF(e1: e2, e3, e4) or blend with STEP"
    )]
    Comparison {
        /// The operator as written.
        operator: String,
        /// Where it stands.
        span: Span,
    },
    /// A `{...}` template placeholder.
    #[error(
        "`{brace}` cannot stand in an expression: `{{...}}` is a template placeholder that must be expanded before the solver reads the expression"
    )]
    TemplatePlaceholder {
        /// The brace found.
        brace: char,
        /// Where it stands.
        span: Span,
    },
    /// Any other character that cannot start a token.
    #[error("unexpected character `{character}`")]
    UnexpectedCharacter {
        /// The character.
        character: char,
        /// Where it stands.
        span: Span,
    },
    /// `1.0D3`: FORTRAN exponent or degrees? Refused as ambiguous.
    #[error(
        "`{text}` is ambiguous: `D` after a number means degrees here, not a FORTRAN exponent; write `{suggestion}` for the power of ten, or put an operator after the `D` for degrees"
    )]
    FortranExponent {
        /// The number with its `D...` tail as written.
        text: String,
        /// The same number written with `E`.
        suggestion: String,
        /// The whole literal.
        span: Span,
    },
    /// A literal beyond the range of a double.
    #[error("the number `{text}` is too large for a double (the largest is about 1.8E+308)")]
    NumberTooLarge {
        /// The literal as written.
        text: String,
        /// Where it stands.
        span: Span,
    },
    /// `IF(a, b, c, d)`: commas only.
    #[error(
        "IF needs a colon after its condition: write IF(e1: e2, e3, e4), not IF(e1, e2, e3, e4)"
    )]
    IfWithoutColon {
        /// The separator that should be a colon.
        span: Span,
    },
    /// An IF with the wrong number of branches.
    #[error(
        "IF takes a condition and three branches, IF(e1: e2, e3, e4) (negative, zero, positive), but {found} were given"
    )]
    IfArity {
        /// How many arguments the IF had, in words.
        found: String,
        /// The whole IF.
        span: Span,
    },
    /// A colon anywhere but after the first argument of IF.
    #[error(
        "a colon belongs only after the condition of IF(e1: e2, e3, e4); separate the arguments of {function} with `,`"
    )]
    MisplacedColon {
        /// The function whose argument list holds the colon.
        function: String,
        /// The colon.
        span: Span,
    },
    /// Parentheses, signs or powers nested deeper than the evaluator allows.
    #[error(
        "the expression nests deeper than {limit} levels (each parenthesis, call, sign before an operand and `**` adds a level; a long run of `+` or `*` does not); split it into smaller expressions"
    )]
    TooDeep {
        /// The limit.
        limit: usize,
        /// The token where the limit was passed.
        span: Span,
    },
}

impl ParseError {
    /// The error with its places moved `offset` bytes on (an error in a
    /// piece of a longer text, placed in that text).
    pub(crate) fn shifted(mut self, offset: usize) -> ParseError {
        if let ParseError::Unclosed { opened, .. } = &mut self {
            *opened = opened.shifted(offset);
        }
        let span = self.span_mut();
        *span = span.shifted(offset);
        self
    }

    /// The place in the text the error speaks of.
    pub fn span(&self) -> Span {
        *self.clone().span_mut()
    }

    fn span_mut(&mut self) -> &mut Span {
        match self {
            ParseError::Empty { span }
            | ParseError::ExpectedOperand { span, .. }
            | ParseError::ExpectedOperator { span, .. }
            | ParseError::Unclosed { span, .. }
            | ParseError::UnmatchedClose { span }
            | ParseError::SeparatorOutsideCall { span, .. }
            | ParseError::Caret { span }
            | ParseError::Comparison { span, .. }
            | ParseError::TemplatePlaceholder { span, .. }
            | ParseError::UnexpectedCharacter { span, .. }
            | ParseError::FortranExponent { span, .. }
            | ParseError::NumberTooLarge { span, .. }
            | ParseError::IfWithoutColon { span }
            | ParseError::IfArity { span, .. }
            | ParseError::MisplacedColon { span, .. }
            | ParseError::TooDeep { span, .. } => span,
        }
    }
}
