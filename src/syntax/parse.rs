//! Text to syntax tree, with pest and its Pratt parser. No pest type leaves
//! this file.

use std::ops::Range;
use std::sync::LazyLock;

use compact_str::CompactString;
use pest::Parser;
use pest::iterators::{Pair, Pairs};
use pest::pratt_parser::{Assoc, Op, PrattParser};
use pest_derive::Parser;

use super::ast::{BinaryOp, Call, Expr, ExprKind, If, Number, UnaryOp};
use super::error::ParseError;
use super::scan::{additive_cuts, diagnose, precheck};
use crate::span::Span;

#[derive(Parser)]
#[grammar = "../grammar/expression.pest"]
struct ExpressionParser;

/// Operator precedence, loosest first (SPEC section 1): `**` binds tighter
/// than a unary sign, so `-2**2` is `-(2**2)`.
static PRATT: LazyLock<PrattParser<Rule>> = LazyLock::new(|| {
    PrattParser::new()
        .op(Op::infix(Rule::add, Assoc::Left) | Op::infix(Rule::sub, Assoc::Left))
        .op(Op::infix(Rule::mul, Assoc::Left) | Op::infix(Rule::div, Assoc::Left))
        .op(Op::prefix(Rule::neg) | Op::prefix(Rule::plus))
        .op(Op::infix(Rule::pow, Assoc::Right))
});

/// Parses the text of one expression into its syntax tree.
///
/// ```
/// let tree = mbexpr::parse("-2**2 + STEP(TIME, 0, 0, 1, 90D)").unwrap();
/// assert_eq!(tree.to_string(), "(+ (neg (** 2 2)) (STEP TIME 0 0 1 90D))");
/// ```
pub fn parse(text: &str) -> Result<Expr, ParseError> {
    precheck(text)?;
    if text.len() <= PIECE_BYTES {
        return parse_piece(text, 0..text.len());
    }
    // pest's queue takes about 80 bytes per byte of a flat sum: a long
    // expression is parsed a piece at a time, cut at its loosest operators.
    let cuts = additive_cuts(text, PIECE_BYTES);
    let first_end = cuts.first().copied().unwrap_or(text.len());
    let mut tree = parse_piece(text, 0..first_end)?;
    let ends = cuts.iter().skip(1).copied().chain([text.len()]);
    for (cut, end) in cuts.iter().zip(ends) {
        let op = if text.as_bytes()[*cut] == b'+' {
            BinaryOp::Add
        } else {
            BinaryOp::Sub
        };
        tree = append_terms(tree, op, parse_piece(text, cut + 1..end)?);
    }
    Ok(tree)
}

/// Expressions longer than this are parsed in pieces of about this size.
const PIECE_BYTES: usize = 1 << 16;

/// The tree of `text[range]`, a whole expression, with its spans in `text`.
fn parse_piece(text: &str, range: Range<usize>) -> Result<Expr, ParseError> {
    let piece = &text[range.clone()];
    let pairs = ExpressionParser::parse(Rule::expression, piece).map_err(|error| {
        let offset = match error.location {
            pest::error::InputLocation::Pos(offset) => offset,
            pest::error::InputLocation::Span((start, _)) => start,
        };
        diagnose(text, range.start + offset)
    })?;
    let expr = { pairs }
        .next()
        .and_then(|expression| expression.into_inner().next())
        .expect("the grammar's top rule holds one `expr`");
    let mut tree = build_expr(expr.into_inner()).map_err(|error| error.shifted(range.start))?;
    if range.start > 0 {
        shift(&mut tree, range.start);
    }
    Ok(tree)
}

/// `tree op piece`, where `piece` (a sum's next terms) is chained onto
/// `tree` term by term: the tree one parse of the whole text would give.
fn append_terms(tree: Expr, op: BinaryOp, piece: Expr) -> Expr {
    match piece.kind {
        ExprKind::Chain(first, rest) if additive(rest[0].0) => {
            let mut tree = chained(tree, op, *first);
            for (op, term) in rest {
                tree = chained(tree, op, term);
            }
            tree
        }
        kind => chained(
            tree,
            op,
            Expr {
                kind,
                span: piece.span,
            },
        ),
    }
}

/// Moves every span of `tree` `offset` bytes on.
fn shift(tree: &mut Expr, offset: usize) {
    tree.span = tree.span.shifted(offset);
    match &mut tree.kind {
        ExprKind::Number(_) | ExprKind::Name(_) => {}
        ExprKind::Unary(_, operand) => shift(operand, offset),
        ExprKind::Chain(first, rest) => {
            shift(first, offset);
            for (_, term) in rest {
                shift(term, offset);
            }
        }
        ExprKind::Power(base, exponent) => {
            shift(base, offset);
            shift(exponent, offset);
        }
        ExprKind::Call(call) => {
            call.name_span = call.name_span.shifted(offset);
            for arg in &mut call.args {
                shift(arg, offset);
            }
        }
        ExprKind::If(branches) => {
            for branch in [
                &mut branches.condition,
                &mut branches.negative,
                &mut branches.zero,
                &mut branches.positive,
            ] {
                shift(branch, offset);
            }
        }
    }
}

fn span_of(pair: &Pair<'_, Rule>) -> Span {
    let span = pair.as_span();
    Span::new(span.start(), span.end())
}

/// Folds an `expr`'s flat run of operands and operators by precedence.
fn build_expr(mut pairs: Pairs<'_, Rule>) -> Result<Expr, ParseError> {
    // Most arguments are a single operand: nothing to fold.
    if pairs.len() == 1 {
        return build_primary(pairs.next().expect("one pair"));
    }
    PRATT
        .map_primary(build_primary)
        .map_prefix(|sign, operand| Ok(signed(&sign, operand?)))
        .map_infix(|lhs, op, rhs| {
            let (lhs, rhs) = (lhs?, rhs?);
            let binary = match op.as_rule() {
                Rule::add => BinaryOp::Add,
                Rule::sub => BinaryOp::Sub,
                Rule::mul => BinaryOp::Mul,
                Rule::div => BinaryOp::Div,
                _ => {
                    return Ok(Expr {
                        span: lhs.span.to(rhs.span),
                        kind: ExprKind::Power(Box::new(lhs), Box::new(rhs)),
                    });
                }
            };
            Ok(chained(lhs, binary, rhs))
        })
        .parse(pairs)
}

/// Whether `op` is of the loosest level, `+ -`.
fn additive(op: BinaryOp) -> bool {
    matches!(op, BinaryOp::Add | BinaryOp::Sub)
}

/// `lhs op rhs`, added to the end of `lhs` when it is a chain of the same
/// precedence level (the Pratt parser folds from the left, so a flat run
/// arrives one operator at a time).
fn chained(lhs: Expr, op: BinaryOp, rhs: Expr) -> Expr {
    let span = lhs.span.to(rhs.span);
    match lhs.kind {
        ExprKind::Chain(first, mut rest) if additive(rest[0].0) == additive(op) => {
            rest.push((op, rhs));
            Expr {
                kind: ExprKind::Chain(first, rest),
                span,
            }
        }
        kind => Expr {
            kind: ExprKind::Chain(
                Box::new(Expr {
                    kind,
                    span: lhs.span,
                }),
                vec![(op, rhs)],
            ),
            span,
        },
    }
}

/// `operand` with the sign `sign` (a `neg` or `plus` pair) before it.
fn signed(sign: &Pair<'_, Rule>, operand: Expr) -> Expr {
    let unary = match sign.as_rule() {
        Rule::neg => UnaryOp::Neg,
        _ => UnaryOp::Plus,
    };
    Expr {
        span: span_of(sign).to(operand.span),
        kind: ExprKind::Unary(unary, Box::new(operand)),
    }
}

/// A call's argument that starts with `first`: an `expr`, or a lone number
/// or name after any signs, whose pairs follow in `rest`.
fn build_argument(first: Pair<'_, Rule>, rest: &mut Pairs<'_, Rule>) -> Result<Expr, ParseError> {
    match first.as_rule() {
        Rule::neg | Rule::plus => {
            let operand = rest
                .next()
                .expect("the grammar puts an operand after a sign");
            Ok(signed(&first, build_argument(operand, rest)?))
        }
        Rule::name => Ok(Expr {
            span: span_of(&first),
            kind: ExprKind::Name(CompactString::new(first.as_str())),
        }),
        _ => build_primary(first),
    }
}

fn build_primary(pair: Pair<'_, Rule>) -> Result<Expr, ParseError> {
    let span = span_of(&pair);
    let kind = match pair.as_rule() {
        Rule::number => ExprKind::Number(build_number(pair)?),
        Rule::named => return build_named(pair),
        // A parenthesised `expr`: the parentheses leave no node of their own.
        _ => return build_expr(pair.into_inner()),
    };
    Ok(Expr { kind, span })
}

fn build_number(pair: Pair<'_, Rule>) -> Result<Number, ParseError> {
    let text = pair.as_str();
    let span = span_of(&pair);
    let degrees = text.ends_with(['d', 'D']);
    let digits = if degrees {
        &text[..text.len() - 1]
    } else {
        text
    };
    // Whole numbers up to 2^53 are exact as integers, and most literals are
    // such ids and counts: they skip the float parser. Otherwise the grammar
    // admits only what Rust's float syntax reads (`1.`, `.5`, `1E+07`).
    let value = match digits.parse::<u64>() {
        Ok(whole) if whole <= 1 << f64::MANTISSA_DIGITS => whole as f64,
        _ => digits.parse().unwrap_or(f64::INFINITY),
    };
    if !value.is_finite() {
        return Err(ParseError::NumberTooLarge {
            text: text.to_string(),
            span,
        });
    }
    Ok(Number {
        value: if degrees { value.to_radians() } else { value },
        text: CompactString::new(text),
    })
}

/// A name, or a call when arguments follow it.
fn build_named(pair: Pair<'_, Rule>) -> Result<Expr, ParseError> {
    let span = span_of(&pair);
    let input = pair.get_input();
    let mut inner = pair.into_inner();
    let name_pair = inner.next().expect("`named` starts with a name");
    let name = CompactString::new(name_pair.as_str());
    let name_span = span_of(&name_pair);
    let Some(arguments) = inner.next() else {
        return Ok(Expr {
            kind: ExprKind::Name(name),
            span,
        });
    };
    let mut parts = arguments.into_inner();
    let mut args = Vec::with_capacity(parts.len());
    let mut colons = Vec::new();
    while let Some(part) = parts.next() {
        match part.as_rule() {
            Rule::colon => colons.push((args.len(), span_of(&part))),
            _ => args.push(build_argument(part, &mut parts)?),
        }
    }
    if !name.eq_ignore_ascii_case("IF") {
        if let Some(&(_, colon)) = colons.first() {
            return Err(ParseError::MisplacedColon {
                function: name.as_str().to_uppercase(),
                span: colon,
            });
        }
        let call = Call {
            name,
            name_span,
            args,
        };
        return Ok(Expr {
            kind: ExprKind::Call(Box::new(call)),
            span,
        });
    }
    if let Some(&(_, colon)) = colons.iter().find(|(position, _)| *position != 1) {
        return Err(ParseError::MisplacedColon {
            function: "IF".to_string(),
            span: colon,
        });
    }
    if args.len() != 4 {
        return Err(ParseError::IfArity {
            found: match args.len() {
                0 => "no arguments".to_string(),
                1 => "one argument".to_string(),
                count => format!("{count} arguments"),
            },
            span,
        });
    }
    if colons.is_empty() {
        // The first separator, a comma, stands between the first two arguments.
        let between = Span::new(args[0].span.end, args[1].span.start);
        let comma = input[between.range()]
            .find(',')
            .map_or(between.start, |at| between.start + at);
        return Err(ParseError::IfWithoutColon {
            span: Span::new(comma, comma + 1),
        });
    }
    let mut args = args.into_iter();
    let mut next = || args.next().expect("checked: four arguments");
    let branches = If {
        condition: next(),
        negative: next(),
        zero: next(),
        positive: next(),
    };
    Ok(Expr {
        kind: ExprKind::If(Box::new(branches)),
        span,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A long expression of `terms` terms from a fixed list, joined by the
    /// four operators in turn, with signs, exponents and brackets where the
    /// cutting must not cut.
    fn long_expression(terms: usize) -> String {
        const TERMS: [&str; 8] = [
            "x",
            "1E-3",
            "-y",
            "STEP(TIME, 0, -1, 1E+2, 2)",
            "(a - b + c)",
            "2.5D",
            "x**-2",
            "IF(x - 1: -1, 0, +1)",
        ];
        const OPERATORS: [&str; 6] = [" + ", "-", " * ", "+", "/", " - "];
        let mut text = String::new();
        for index in 0..terms {
            if index > 0 {
                text.push_str(OPERATORS[index % OPERATORS.len()]);
            }
            text.push_str(TERMS[(index * 7) % TERMS.len()]);
        }
        text
    }

    #[test]
    fn a_long_expression_parsed_in_pieces_is_the_tree_of_one_parse() {
        for terms in [40_000, 60_001] {
            let text = long_expression(terms);
            assert!(text.len() > 4 * PIECE_BYTES);
            assert!(additive_cuts(&text, PIECE_BYTES).len() >= 4);
            let whole = parse_piece(&text, 0..text.len()).unwrap();
            assert!(parse(&text).unwrap() == whole, "{terms} terms");
        }
    }

    #[test]
    fn an_error_in_a_later_piece_is_placed_in_the_whole_text() {
        let mut text = long_expression(20_000);
        text.push_str(" + 1E999 - x");
        let error = parse(&text).unwrap_err();
        let whole = parse_piece(&text, 0..text.len()).unwrap_err();
        assert_eq!(error, whole);
        assert_eq!(&text[error.span().range()], "1E999");
        let mut text = long_expression(20_000);
        text.push_str(" + * x");
        assert_eq!(
            parse(&text).unwrap_err(),
            parse_piece(&text, 0..text.len()).unwrap_err()
        );
    }
}
