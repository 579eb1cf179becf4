//! Checking a model file: every expression parsed and checked, errors placed
//! at their line and column in the file, and the references of solver
//! datasets to other statements verified (markers, variables, arrays,
//! differential states, elements), with loops among VARIABLEs found.

use std::collections::{HashMap, HashSet};

use thiserror::Error;

use super::{Dataset, Embedded, FileKind, ReadError, Statement, Value, is_kind};
use crate::ParseError;
use crate::catalog::{ArgKind, Function};
use crate::check::{Argument, Checked, NodeKind, Reference, visit};
use crate::span::Location;
use crate::span::Span;

/// A problem found in a model file.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ModelError {
    /// A line the reader could not read.
    #[error("{error}")]
    Read {
        /// What the reader said.
        error: ReadError,
    },
    /// A syntax or name problem inside an expression (the message of the
    /// parser or checker; the span is in the file).
    #[error("{message}")]
    Expression {
        /// The message.
        message: String,
        /// The place in the file.
        span: Span,
    },
    /// A measure's marker with no MARKER statement.
    #[error("marker {id} is not defined: there is no MARKER/{id} statement")]
    UnknownMarker {
        /// The marker id.
        id: u64,
        /// The reference in the file.
        span: Span,
    },
    /// A reference to a statement that is not in the file.
    #[error("{function}({id}) refers to {kind}/{id}, which is not defined")]
    MissingStatement {
        /// The function.
        function: &'static str,
        /// The statement kind it needs.
        kind: &'static str,
        /// The id referred to.
        id: u64,
        /// The reference in the file.
        span: Span,
    },
    /// `ARYVAL(id, i)` beyond the end of the array.
    #[error("ARYVAL({id}, {index}) asks for entry {index}, but ARRAY/{id} has {count}")]
    ArrayTooShort {
        /// The array id.
        id: u64,
        /// The entry asked for.
        index: i64,
        /// The entries the array has.
        count: usize,
        /// The call in the file.
        span: Span,
    },
    /// VARIABLEs whose functions depend on each other in a loop.
    #[error("VARIABLE/{id} depends on itself: {cycle}")]
    VariableLoop {
        /// The first variable of the loop.
        id: u64,
        /// `VARIABLE/3 -> VARIABLE/5 -> VARIABLE/3`.
        cycle: String,
        /// The reference that closes the loop.
        span: Span,
    },
}

impl ModelError {
    /// The place in the file.
    pub fn span(&self) -> Span {
        match self {
            ModelError::Read { error } => error.span(),
            ModelError::Expression { span, .. }
            | ModelError::UnknownMarker { span, .. }
            | ModelError::MissingStatement { span, .. }
            | ModelError::ArrayTooShort { span, .. }
            | ModelError::VariableLoop { span, .. } => *span,
        }
    }
}

/// An expression found in a model file.
#[derive(Clone, Debug)]
pub struct FoundExpression {
    /// Index of its statement in [`Dataset::statements`].
    pub statement: usize,
    /// The keyword it is the value of (`FUNCTION`, `F3`, `x_force_function`).
    pub keyword: String,
    /// The joined expression text.
    pub text: String,
    /// Where it stands in the file.
    pub span: Span,
    /// The checked expression, when it parsed and checked.
    pub checked: Option<Checked>,
}

/// A problem, with the statement and expression it belongs to.
#[derive(Clone, Debug)]
pub struct Problem {
    /// What is wrong.
    pub error: ModelError,
    /// Index of the statement, when the problem is inside one.
    pub statement: Option<usize>,
    /// Index into [`ModelCheck::expressions`], when the problem is in one.
    pub expression: Option<usize>,
}

/// Everything found in a model file.
#[derive(Clone, Debug)]
pub struct ModelCheck {
    /// Every expression, in file order.
    pub expressions: Vec<FoundExpression>,
    /// Every problem, in file order.
    pub problems: Vec<Problem>,
}

/// A parse error's message, with a column inside the joined expression
/// turned into the line and column in the file.
fn file_message(error: &ParseError, embedded: &Embedded, text: &str) -> String {
    match error {
        ParseError::Unclosed { opener, opened, .. } => {
            let at = Location::of(text, embedded.file_offset(opened.start));
            format!(
                "expected `)` to close {opener} opened at line {}, column {}",
                at.line, at.column
            )
        }
        _ => error.to_string(),
    }
}

/// Finds and checks every expression of the model file `text`, read into
/// `dataset` by [`super::read`].
pub fn check_model(text: &str, dataset: &Dataset) -> ModelCheck {
    let mut problems: Vec<Problem> = dataset
        .problems
        .iter()
        .map(|error| Problem {
            error: ModelError::Read {
                error: error.clone(),
            },
            statement: None,
            expression: None,
        })
        .collect();
    let mut expressions = Vec::new();
    for (index, statement) in dataset.statements.iter().enumerate() {
        for (argument, embedded) in statement.expressions() {
            let expression = expressions.len();
            let mut report = |message: String, span: Span| {
                problems.push(Problem {
                    error: ModelError::Expression {
                        message,
                        span: embedded.file_span(span),
                    },
                    statement: Some(index),
                    expression: Some(expression),
                });
            };
            let checked = match crate::parse(&embedded.text) {
                Err(error) => {
                    report(file_message(&error, embedded, text), error.span());
                    None
                }
                Ok(tree) => match crate::check(&tree) {
                    Err(errors) => {
                        for error in errors {
                            report(error.to_string(), error.span());
                        }
                        None
                    }
                    Ok(checked) => Some(checked),
                },
            };
            let span = match &argument.value {
                Value::Expression { span, .. } => *span,
                _ => argument.span,
            };
            expressions.push(FoundExpression {
                statement: index,
                keyword: argument.keyword.clone(),
                text: embedded.text.clone(),
                span,
                checked,
            });
        }
    }
    if dataset.kind != FileKind::Cmd {
        References::of(dataset).check(dataset, &expressions, &mut problems);
    }
    problems.sort_by_key(|problem| problem.error.span().start);
    ModelCheck {
        expressions,
        problems,
    }
}

/// The statements other statements can refer to, by kind and id.
struct References {
    ids: HashMap<String, HashSet<u64>>,
    array_sizes: HashMap<u64, usize>,
}

/// The statement kind a model-data or element function refers to.
fn statement_kind(function: Function) -> Option<&'static str> {
    use Function as F;
    Some(match function {
        F::Varval => "VARIABLE",
        F::Aryval => "ARRAY",
        F::Dif | F::Dif1 => "DIFF",
        F::Pinval => "PINPUT",
        F::Pouval => "POUTPUT",
        F::Senval => "SENSOR",
        F::Akispl | F::Cubspl => "SPLINE",
        F::Curve => "CURVE",
        F::Sforce => "SFORCE",
        F::Gforce => "GFORCE",
        F::Vforce => "VFORCE",
        F::Vtorq => "VTORQUE",
        F::Joint => "JOINT",
        F::Jprim => "JPRIM",
        F::Motion => "MOTION",
        F::Beam => "BEAM",
        F::Bush => "BUSHING",
        F::Field => "FIELD",
        F::Nforce => "NFORCE",
        F::Contact => "CONTACT",
        F::Ptcv => "PTCV",
        F::Cvcv => "CVCV",
        _ => return None,
    })
}

impl References {
    fn of(dataset: &Dataset) -> References {
        let mut ids: HashMap<String, HashSet<u64>> = HashMap::new();
        let mut array_sizes = HashMap::new();
        for statement in &dataset.statements {
            let Some(id) = statement.id else { continue };
            ids.entry(statement.name.clone()).or_default().insert(id);
            if is_kind(&statement.name, "ARRAY") {
                let count = statement
                    .argument("NUMBERS", 2)
                    .and_then(|argument| match &argument.value {
                        Value::List(items) => Some(items.len()),
                        _ => None,
                    })
                    .or_else(|| {
                        statement
                            .argument("SIZE", 2)
                            .and_then(|argument| match &argument.value {
                                Value::List(items) => items.first()?.text.parse().ok(),
                                _ => None,
                            })
                    });
                if let Some(count) = count {
                    array_sizes.insert(id, count);
                }
            }
        }
        References { ids, array_sizes }
    }

    fn has(&self, kind: &str, id: u64) -> bool {
        self.ids
            .iter()
            .any(|(name, ids)| is_kind(name, kind) && ids.contains(&id))
    }

    fn check(
        &self,
        dataset: &Dataset,
        expressions: &[FoundExpression],
        problems: &mut Vec<Problem>,
    ) {
        // VARIABLE id -> the VARIABLEs its function reads, with where.
        let mut reads: HashMap<u64, Vec<(u64, Span)>> = HashMap::new();
        for (index, found) in expressions.iter().enumerate() {
            let Some(checked) = &found.checked else {
                continue;
            };
            let statement: &Statement = &dataset.statements[found.statement];
            let Some((_, embedded)) = statement
                .expressions()
                .find(|(argument, _)| argument.keyword == found.keyword)
            else {
                continue;
            };
            let mut report = |error: ModelError| {
                problems.push(Problem {
                    error,
                    statement: Some(found.statement),
                    expression: Some(index),
                });
            };
            visit(&checked.root, &mut |node| {
                let NodeKind::Call(function, args) = &node.kind else {
                    return;
                };
                for (position, arg) in args.iter().enumerate() {
                    match (arg, function.signature().kind(position)) {
                        (Argument::Marker(Reference::Id(id), span), ArgKind::Marker)
                            if *id != 0 && !self.has("MARKER", *id) =>
                        {
                            report(ModelError::UnknownMarker {
                                id: *id,
                                span: embedded.file_span(*span),
                            });
                        }
                        (Argument::Object(Reference::Id(id), span), ArgKind::Object) => {
                            let Some(kind) = statement_kind(*function) else {
                                continue;
                            };
                            if !self.has(kind, *id) {
                                report(ModelError::MissingStatement {
                                    function: function.name(),
                                    kind,
                                    id: *id,
                                    span: embedded.file_span(*span),
                                });
                                continue;
                            }
                            if *function == Function::Aryval
                                && let (Some(Argument::Flag(entry, _)), Some(&count)) =
                                    (args.get(1), self.array_sizes.get(id))
                                && (*entry < 1 || *entry as usize > count)
                            {
                                report(ModelError::ArrayTooShort {
                                    id: *id,
                                    index: *entry,
                                    count,
                                    span: embedded.file_span(node.span),
                                });
                            }
                            if *function == Function::Varval
                                && is_kind(&statement.name, "VARIABLE")
                                && let Some(variable) = statement.id
                            {
                                reads
                                    .entry(variable)
                                    .or_default()
                                    .push((*id, embedded.file_span(node.span)));
                            }
                        }
                        _ => {}
                    }
                }
            });
        }
        report_loops(&reads, dataset, problems);
    }
}

/// Reports each loop among VARIABLE functions once, at the reference that closes it.
fn report_loops(
    reads: &HashMap<u64, Vec<(u64, Span)>>,
    dataset: &Dataset,
    problems: &mut Vec<Problem>,
) {
    let mut ids: Vec<u64> = reads.keys().copied().collect();
    ids.sort_unstable();
    let mut in_loop: HashSet<u64> = HashSet::new();
    for &start in &ids {
        if in_loop.contains(&start) {
            continue;
        }
        // Depth-first search for a path from `start` back to itself.
        let mut stack: Vec<(u64, usize)> = vec![(start, 0)];
        let mut on_path: Vec<u64> = vec![start];
        let mut seen: HashSet<u64> = HashSet::from([start]);
        while let Some((node, next)) = stack.last_mut() {
            let edges = reads.get(node).map_or(&[][..], Vec::as_slice);
            let Some(&(target, span)) = edges.get(*next) else {
                stack.pop();
                on_path.pop();
                continue;
            };
            *next += 1;
            if target == start {
                let mut cycle: Vec<String> =
                    on_path.iter().map(|id| format!("VARIABLE/{id}")).collect();
                cycle.push(format!("VARIABLE/{start}"));
                in_loop.extend(on_path.iter().copied());
                let statement = dataset.statements.iter().position(|statement| {
                    is_kind(&statement.name, "VARIABLE")
                        && statement.id == Some(*on_path.last().expect("a path"))
                });
                problems.push(Problem {
                    error: ModelError::VariableLoop {
                        id: start,
                        cycle: cycle.join(" -> "),
                        span,
                    },
                    statement,
                    expression: None,
                });
                break;
            }
            if seen.insert(target) {
                stack.push((target, 0));
                on_path.push(target);
            }
        }
    }
}
