//! Checking a model file: every expression parsed and checked, errors placed
//! at their line and column in the file, and the references of solver
//! datasets to other statements verified (markers, variables, arrays,
//! differential states, elements), with loops among VARIABLEs found.

use std::cell::OnceCell;
use std::collections::{HashMap, HashSet};

use compact_str::CompactString;
use thiserror::Error;

use super::initial::{ConfigurationError, not_finite};
use super::variables::Reads;
use super::{
    Dataset, Embedded, FileKind, ReadError, Statement, Value, is_kind, is_statement, vocabulary,
};
use crate::ParseError;
use crate::catalog::{ArgKind, Function};
use crate::check::{Argument, Checked, NodeKind, Reference, visit};
use crate::span::{LineIndex, Span};

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
    /// `ARYVAL(id, i)` (or `PINVAL`, `POUVAL`) beyond the end of the list.
    #[error("{function}({id}, {index}) asks for entry {index}, but {kind}/{id} has {count}")]
    ArrayTooShort {
        /// The function: ARYVAL, PINVAL or POUVAL.
        function: &'static str,
        /// The statement kind it reads: ARRAY, PINPUT or POUTPUT.
        kind: &'static str,
        /// The array id.
        id: u64,
        /// The entry asked for.
        index: i64,
        /// The entries the array has.
        count: usize,
        /// The call in the file.
        span: Span,
    },
    /// A bare name in a solver dataset, which knows only its system
    /// variables and constants.
    #[error(
        "{name} is not defined: a dataset expression knows only TIME, MODE, PI, DTOR and RTOD{suggestions}"
    )]
    UnknownName {
        /// The name as written.
        name: String,
        /// " (did you mean TIME?)" or nothing.
        suggestions: String,
        /// The name in the file.
        span: Span,
    },
    /// A statement name the solver does not know.
    #[error("{name} is not a statement of a solver {file}{suggestions}")]
    UnknownStatement {
        /// The name as written, upper case.
        name: String,
        /// "dataset" or "command file".
        file: &'static str,
        /// " (did you mean MARKER?)" or nothing.
        suggestions: String,
        /// The name in the file.
        span: Span,
    },
    /// A keyword its dataset statement does not have (an expression after it
    /// is not read).
    #[error("{keyword} is not a keyword of {statement}{suggestions}")]
    UnknownKeyword {
        /// The keyword as written, upper case.
        keyword: String,
        /// `VARIABLE/4`.
        statement: String,
        /// " (did you mean FUNCTION?)" or nothing.
        suggestions: String,
        /// The keyword in the file.
        span: Span,
    },
    /// Two statements of one kind with one id.
    #[error("{label} is defined twice: here and at line {other_line}")]
    Duplicate {
        /// `VARIABLE/7`.
        label: String,
        /// The line of the other definition.
        other_line: usize,
        /// The statement's name and id.
        span: Span,
    },
    /// A keyword given twice in one statement.
    #[error("{statement}: {keyword} is given twice (first at line {first_line}): give it once")]
    KeywordTwice {
        /// The keyword, as its statement spells it in full.
        keyword: String,
        /// `REQUEST/4`.
        statement: String,
        /// The line of its first value.
        first_line: usize,
        /// The second keyword in the file.
        span: Span,
    },
    /// A statement after the dataset's `END`, which ends it: Adams Solver
    /// reads nothing after END.
    #[error(
        "{label} comes after END (line {end_line}), which ends the dataset: move END to the end of the file, or delete what follows it"
    )]
    AfterEnd {
        /// `DIFF/2`, the first statement after END.
        label: String,
        /// The line of END.
        end_line: usize,
        /// The statement's name.
        span: Span,
    },
    /// A statement named, not numbered, in a solver dataset's expression.
    #[error(
        "{name} is not an id: a solver dataset refers to a {kind} by its number, as {function}(3) does"
    )]
    NamedReference {
        /// The name as written.
        name: String,
        /// `MARKER`, `DIFF`.
        kind: &'static str,
        /// The function called.
        function: &'static str,
        /// The name in the file.
        span: Span,
    },
    /// A command file's commands that ask for a run `mbexpr simulate` does
    /// not make (its reader's message, added by the callers that read the
    /// run: the model checker does not simulate).
    #[error("{message}")]
    Run {
        /// What the run's reader said.
        message: String,
        /// The command.
        span: Span,
    },
    /// A second `PART/id, GROUND`.
    #[error(
        "{label}: a model has one ground part, and {first} is ground already: give this part a MASS, or join it to ground with a FIXED JOINT"
    )]
    SecondGround {
        /// `PART/5`.
        label: String,
        /// `PART/1`.
        first: String,
        /// The GROUND keyword in the file.
        span: Span,
    },
    /// A name in a View command file that no command of the file creates.
    #[error("{what} {name} is not created in this file{suggestions}")]
    NotCreated {
        /// "marker", "object" or "variable".
        what: &'static str,
        /// The name as written.
        name: String,
        /// " (did you mean ...?)" or nothing.
        suggestions: String,
        /// The reference in the file.
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
    /// Statement data that makes no configuration: a value list of the
    /// wrong length, a PART that does not exist, a spline that cannot be
    /// fitted (what `eval --model` and the simulator would refuse).
    #[error("{error}")]
    Configuration {
        /// What the configuration's reader said.
        error: ConfigurationError,
    },
}

impl ModelError {
    /// The place in the file.
    pub fn span(&self) -> Span {
        match self {
            ModelError::Read { error } => error.span(),
            ModelError::Configuration { error } => error.span(),
            ModelError::Expression { span, .. }
            | ModelError::UnknownMarker { span, .. }
            | ModelError::MissingStatement { span, .. }
            | ModelError::ArrayTooShort { span, .. }
            | ModelError::UnknownName { span, .. }
            | ModelError::UnknownStatement { span, .. }
            | ModelError::UnknownKeyword { span, .. }
            | ModelError::Duplicate { span, .. }
            | ModelError::KeywordTwice { span, .. }
            | ModelError::AfterEnd { span, .. }
            | ModelError::Run { span, .. }
            | ModelError::NamedReference { span, .. }
            | ModelError::SecondGround { span, .. }
            | ModelError::NotCreated { span, .. }
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
    pub keyword: CompactString,
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
fn file_message(error: &ParseError, embedded: &Embedded, lines: &LineIndex<'_>) -> String {
    match error {
        ParseError::Unclosed { opener, opened, .. } => {
            let at = lines.location(embedded.file_offset(opened.start));
            format!(
                "expected `)` to close {opener} opened at line {}, column {}",
                at.line, at.column
            )
        }
        _ => error.to_string(),
    }
}

/// The problems found so far, and the file's line index, built the first
/// time a message needs a line number.
struct Findings<'t> {
    text: &'t str,
    lines: OnceCell<LineIndex<'t>>,
    problems: Vec<Problem>,
}

impl<'t> Findings<'t> {
    fn lines(&self) -> &LineIndex<'t> {
        self.lines.get_or_init(|| LineIndex::new(self.text))
    }

    fn push(&mut self, error: ModelError, statement: Option<usize>, expression: Option<usize>) {
        self.problems.push(Problem {
            error,
            statement,
            expression,
        });
    }
}

/// Finds and checks every expression of the model file `text`, read into
/// `dataset` by [`super::read`]: syntax, names, constant arguments, the
/// statement names and keywords of a dataset, and the references between
/// statements (datasets and command files by id, View command files by name).
pub fn check_model(text: &str, dataset: &Dataset) -> ModelCheck {
    let mut findings = Findings {
        text,
        lines: OnceCell::new(),
        problems: Vec::new(),
    };
    for error in &dataset.problems {
        findings.push(
            ModelError::Read {
                error: error.clone(),
            },
            None,
            None,
        );
    }
    let solver_file = dataset.kind != FileKind::Cmd;
    if solver_file {
        check_words(dataset, &mut findings);
    }
    let mut expressions = Vec::new();
    // The tree of every expression that parsed, errors or not, for its references.
    let mut trees: Vec<Option<Checked>> = Vec::new();
    let mut cleanly: Vec<bool> = Vec::new();
    for (index, statement) in dataset.statements.iter().enumerate() {
        for (argument, embedded) in statement.expressions() {
            // A View command's `function = ""` is its "no function yet"
            // (View writes one at each element's creation and the function
            // later, when every name it reads exists).
            if !solver_file && embedded.text.trim().is_empty() {
                continue;
            }
            let expression = expressions.len();
            let report = |findings: &mut Findings<'_>, message: String, span: Span| {
                let span = embedded.file_span(span);
                findings.push(
                    ModelError::Expression { message, span },
                    Some(index),
                    Some(expression),
                );
            };
            let (clean, tree) = match crate::parse(&embedded.text) {
                Err(error) => {
                    let message = file_message(&error, embedded, findings.lines());
                    report(&mut findings, message, error.span());
                    (false, None)
                }
                Ok(tree) => {
                    let (tree, errors) = crate::check::check_partial(&tree);
                    for error in &errors {
                        report(&mut findings, error.to_string(), error.span());
                    }
                    (errors.is_empty(), Some(tree))
                }
            };
            if solver_file && let Some(tree) = &tree {
                for (name, span) in tree.variable_uses() {
                    findings.push(
                        ModelError::UnknownName {
                            name: name.to_string(),
                            suggestions: vocabulary::suggestions(name, DATASET_NAMES),
                            span: embedded.file_span(span),
                        },
                        Some(index),
                        Some(expression),
                    );
                }
            }
            let span = match &argument.value {
                Value::Expression { span, .. } => *span,
                _ => argument.span,
            };
            expressions.push(FoundExpression {
                statement: index,
                keyword: argument.keyword.clone(),
                text: embedded.text.clone(),
                span,
                checked: None,
            });
            trees.push(tree);
            cleanly.push(clean);
        }
    }
    if solver_file {
        References::of(dataset, &mut findings).check(dataset, &expressions, &trees, &mut findings);
    } else {
        super::view::check_names(dataset, &expressions, &trees, &mut findings.problems);
    }
    // The trees of the expressions that checked cleanly are the report's.
    for ((found, tree), clean) in expressions.iter_mut().zip(trees).zip(cleanly) {
        if clean {
            found.checked = tree;
        }
    }
    let mut check = ModelCheck {
        expressions,
        problems: findings.problems,
    };
    // The statements' data, read as `eval --model` and the simulator read
    // it into the initial configuration.
    if solver_file && let Err(errors) = super::initial_scene(dataset, &check) {
        check
            .problems
            .extend(errors.into_iter().map(|error| Problem {
                error: ModelError::Configuration { error },
                statement: None,
                expression: None,
            }));
    }
    check
        .problems
        .sort_by_key(|problem| problem.error.span().start);
    // A number beyond a double's range is found both in every statement's
    // data and where the initial configuration reads it.
    check.problems.dedup_by(|later, earlier| {
        later.error.span() == earlier.error.span()
            && later.error.to_string() == earlier.error.to_string()
    });
    check
}

/// The names a dataset expression may use bare.
const DATASET_NAMES: &[&str] = &["TIME", "MODE", "PI", "DTOR", "RTOD"];

/// Statement names and (in datasets) keywords the solver does not know.
fn check_words(dataset: &Dataset, findings: &mut Findings<'_>) {
    let (known, file) = match dataset.kind {
        FileKind::Acf => (vocabulary::COMMANDS, "command file"),
        _ => (vocabulary::DATASET_STATEMENTS.as_slice(), "dataset"),
    };
    let mut end_line = None;
    for (index, statement) in dataset.statements.iter().enumerate() {
        if dataset.kind == FileKind::Adm {
            let end = is_statement(statement, "END");
            // A second END ends nothing more.
            if let Some(end_line) = end_line.filter(|_| !end) {
                let span = name_span(findings.text, statement.span, &statement.name)
                    .unwrap_or(statement.span);
                findings.push(
                    ModelError::AfterEnd {
                        label: statement.label(),
                        end_line,
                        span,
                    },
                    Some(index),
                    None,
                );
                break;
            }
            if end {
                end_line = Some(findings.lines().location(statement.span.start).line);
            }
        }
        // A command file starts with the names of its dataset and output
        // files, one word a line.
        let file_name = dataset.kind == FileKind::Acf
            && statement.id.is_none()
            && statement.arguments.is_empty()
            && findings.lines().location(statement.span.start).line <= 2;
        if vocabulary::statement_name(&statement.name, known).is_none() && !file_name {
            let span = Span::new(
                statement.span.start,
                statement.span.start + statement.name.len(),
            );
            let span = name_span(findings.text, statement.span, &statement.name).unwrap_or(span);
            findings.push(
                ModelError::UnknownStatement {
                    name: as_written(&statement.name),
                    file,
                    suggestions: suggestions(&statement.name, known),
                    span,
                },
                Some(index),
                None,
            );
            continue;
        }
        if dataset.kind == FileKind::Acf {
            // The commands' keywords are not listed: a keyword counts as
            // written, so an abbreviation and its full form are not matched.
            keywords_once(statement, index, findings, |argument| {
                Some(argument.keyword.to_string())
            });
        }
        if dataset.kind != FileKind::Adm {
            continue;
        }
        let Some(keywords) = vocabulary::keywords_of(&statement.name) else {
            continue;
        };
        // A 3-D SPLINE gives one Y list for each value of its second
        // variable.
        let spline = is_statement(statement, "SPLINE");
        keywords_once(statement, index, findings, |argument| {
            let repeats = spline && argument.keyword.as_str() == "Y";
            full_keyword(&argument.keyword, keywords)
                .filter(|_| !repeats)
                .map(str::to_string)
        });
        for argument in &statement.arguments {
            if !vocabulary::is_keyword(&argument.keyword, keywords) {
                findings.push(
                    ModelError::UnknownKeyword {
                        keyword: as_written(&argument.keyword),
                        statement: statement.label(),
                        suggestions: suggestions(&argument.keyword, keywords),
                        span: argument.keyword_span,
                    },
                    Some(index),
                    None,
                );
                continue;
            }
            if let Some(error) = not_finite(statement, argument) {
                findings.push(ModelError::Configuration { error }, Some(index), None);
            }
        }
        if is_statement(statement, "ARRAY")
            && let Some(error) = array_size(statement)
        {
            findings.push(ModelError::Configuration { error }, Some(index), None);
        }
    }
    check_grounds(dataset, findings);
}

/// A keyword statement `index` gives twice (`SIMULATE/DYNAMIC, END = 1,
/// END = 2`), each argument's keyword named by `name` (`None`: not
/// counted), reported at its second place.
fn keywords_once(
    statement: &Statement,
    index: usize,
    findings: &mut Findings<'_>,
    name: impl Fn(&super::Argument) -> Option<String>,
) {
    let mut given: HashMap<String, Span> = HashMap::new();
    for argument in &statement.arguments {
        let Some(keyword) = name(argument) else {
            continue;
        };
        if let Some(first) = given.insert(keyword.clone(), argument.keyword_span) {
            let first_line = findings.lines().location(first.start).line;
            findings.push(
                ModelError::KeywordTwice {
                    keyword,
                    statement: statement.label(),
                    first_line,
                    span: argument.keyword_span,
                },
                Some(index),
                None,
            );
        }
    }
}

/// What is wrong with an ARRAY's SIZE: not a whole number of at least 1,
/// or fewer than the NUMBERS it lists.
fn array_size(statement: &Statement) -> Option<ConfigurationError> {
    let argument = statement.argument("SIZE", 2)?;
    let Value::List(items) = &argument.value else {
        return None;
    };
    let text = items.first()?.text.trim();
    let reason = match text.parse::<f64>() {
        Ok(size) if size >= 1.0 && size.fract() == 0.0 && size <= 1e9 => {
            let listed =
                statement
                    .argument("NUMBERS", 2)
                    .and_then(|numbers| match &numbers.value {
                        Value::List(items) => Some(items.len()),
                        _ => None,
                    })?;
            if listed as f64 <= size {
                return None;
            }
            format!("it lists {listed} NUMBERS, more than its SIZE = {text}")
        }
        _ => format!("SIZE must be a whole number from 1 to 10^9, not {text}"),
    };
    Some(ConfigurationError::Control {
        statement: statement.label(),
        reason,
        span: argument.span,
    })
}

/// The longest name a message repeats whole.
const LONGEST_NAME: usize = 60;

/// A name as written, cut after [`LONGEST_NAME`] characters (a line of
/// a megabyte is not repeated in its message).
fn as_written(name: &str) -> String {
    match name.char_indices().nth(LONGEST_NAME) {
        Some((end, _)) => format!("{}…", &name[..end]),
        None => name.to_string(),
    }
}

/// The vocabulary's names close to `written` (" (did you mean ...?)"), not
/// looked for when it is longer than any name could be.
fn suggestions(written: &str, known: &[&str]) -> String {
    if written.len() > LONGEST_NAME {
        String::new()
    } else {
        vocabulary::suggestions(written, known)
    }
}

/// The keyword of `keywords` that `written` is or abbreviates, when it
/// names one only.
fn full_keyword<'k>(written: &str, keywords: &[&'k str]) -> Option<&'k str> {
    if let Some(exact) = keywords.iter().find(|known| **known == written) {
        return Some(exact);
    }
    let mut starting = keywords.iter().filter(|known| known.starts_with(written));
    match (starting.next(), starting.next()) {
        (Some(only), None) => Some(only),
        _ => None,
    }
}

/// A second ground part, at its GROUND keyword.
fn check_grounds(dataset: &Dataset, findings: &mut Findings<'_>) {
    let mut ground = None;
    for (index, statement) in dataset.statements.iter().enumerate() {
        if !is_statement(statement, "PART") {
            continue;
        }
        let Some(argument) = statement.argument("GROUND", 3) else {
            continue;
        };
        match &ground {
            None => ground = Some(statement.label()),
            Some(first) => findings.push(
                ModelError::SecondGround {
                    label: statement.label(),
                    first: first.clone(),
                    span: argument.keyword_span,
                },
                Some(index),
                None,
            ),
        }
    }
}

/// Where the name `name` stands in the statement `span` of `text` (after
/// any leading blanks).
fn name_span(text: &str, span: Span, name: &str) -> Option<Span> {
    let statement = text.get(span.range())?;
    let start = span.start + (statement.len() - statement.trim_start().len());
    Some(Span::new(start, start + name.len()))
}

/// The statements other statements can refer to, by kind and id.
struct References {
    /// `(kind, id)` of every statement with an id, the kind as the
    /// vocabulary spells it (`VARI/3` is `VARIABLE`).
    ids: HashSet<(String, u64)>,
    /// The entries of each ARRAY, PINPUT and POUTPUT, by kind and id.
    list_sizes: HashMap<(&'static str, u64), usize>,
    /// A command file's: its expressions read the markers, VARIABLEs,
    /// SENSORs ... of the dataset it runs, which is not read with it, so an
    /// id it does not define itself is not an error.
    open: bool,
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
        F::Spdp => "SPRINGDAMPER",
        F::Friction => "FRICTION",
        _ => return None,
    })
}

impl References {
    /// The statements of `dataset`; a kind and id given twice in a dataset
    /// is reported at both places.
    fn of(dataset: &Dataset, findings: &mut Findings<'_>) -> References {
        let mut first: HashMap<(String, u64), usize> = HashMap::new();
        let mut list_sizes = HashMap::new();
        for (index, statement) in dataset.statements.iter().enumerate() {
            let Some(id) = statement.id else { continue };
            let kind = canonical(&statement.name);
            if let Some(list) = ["ARRAY", "PINPUT", "POUTPUT"]
                .into_iter()
                .find(|list| is_kind(&kind, list))
                && let Some(count) = list_size(statement)
            {
                list_sizes.insert((list, id), count);
            }
            let Some(&other) = first.get(&(kind.clone(), id)) else {
                first.insert((kind, id), index);
                continue;
            };
            // A command file changes statements again and again.
            if dataset.kind != FileKind::Adm {
                continue;
            }
            let label = format!("{kind}/{id}");
            let at = |index: usize| dataset.statements[index].span;
            let line_of = |index: usize| findings.lines().location(at(index).start).line;
            let (line, other_line) = (line_of(index), line_of(other));
            let place = |index: usize| {
                name_span(findings.text, at(index), &dataset.statements[index].name)
                    .unwrap_or(at(index))
            };
            let (first_place, own_place) = (place(other), place(index));
            findings.push(
                ModelError::Duplicate {
                    label: label.clone(),
                    other_line: line,
                    span: first_place,
                },
                Some(other),
                None,
            );
            findings.push(
                ModelError::Duplicate {
                    label,
                    other_line,
                    span: own_place,
                },
                Some(index),
                None,
            );
        }
        References {
            ids: first.into_keys().collect(),
            list_sizes,
            open: dataset.kind == FileKind::Acf,
        }
    }

    fn has(&self, kind: &str, id: u64) -> bool {
        self.open || self.ids.contains(&(kind.to_string(), id))
    }

    fn check(
        &self,
        dataset: &Dataset,
        expressions: &[FoundExpression],
        trees: &[Option<Checked>],
        findings: &mut Findings<'_>,
    ) {
        let mut reads = Reads::default();
        for (index, found) in expressions.iter().enumerate() {
            let Some(checked) = &trees[index] else {
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
                findings.push(error, Some(found.statement), Some(index));
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
                        (Argument::Marker(Reference::Name(name), span), ArgKind::Marker) => {
                            report(ModelError::NamedReference {
                                name: name.clone(),
                                kind: "MARKER",
                                function: function.name(),
                                span: embedded.file_span(*span),
                            });
                        }
                        (Argument::Object(Reference::Name(name), span), ArgKind::Object) => {
                            report(ModelError::NamedReference {
                                name: name.clone(),
                                kind: statement_kind(*function).unwrap_or("statement"),
                                function: function.name(),
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
                            if matches!(
                                function,
                                Function::Aryval | Function::Pinval | Function::Pouval
                            ) && let (Some(Argument::Flag(entry, _)), Some(&count)) =
                                (args.get(1), self.list_sizes.get(&(kind, *id)))
                                && (*entry < 1 || *entry as usize > count)
                            {
                                report(ModelError::ArrayTooShort {
                                    function: function.name(),
                                    kind,
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
                                reads.add(variable, *id, embedded.file_span(node.span), index);
                            }
                        }
                        _ => {}
                    }
                }
            });
        }
        for found in reads.loops() {
            let statement = expressions[found.expression].statement;
            findings.push(
                ModelError::VariableLoop {
                    id: found.first,
                    cycle: found.cycle,
                    span: found.span,
                },
                Some(statement),
                Some(found.expression),
            );
        }
    }
}

/// The number of entries of an ARRAY, PINPUT or POUTPUT statement: its
/// `NUMBERS` (the `VARIABLES` of a U array, a PINPUT or a POUTPUT), else
/// its `SIZE`.
fn list_size(statement: &Statement) -> Option<usize> {
    statement
        .argument("NUMBERS", 2)
        .or_else(|| {
            let listed = statement.argument("U", 1).is_some() || !is_kind(&statement.name, "ARRAY");
            listed.then(|| statement.argument("VARIABLES", 3)).flatten()
        })
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
        })
}

/// A statement name as the vocabulary spells it (an abbreviation in full),
/// or as written when the vocabulary does not know it.
fn canonical(name: &str) -> String {
    vocabulary::statement_name(name, &vocabulary::DATASET_STATEMENTS)
        .or_else(|| vocabulary::statement_name(name, vocabulary::COMMANDS))
        .map_or_else(|| name.to_string(), str::to_string)
}
