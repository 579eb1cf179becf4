//! `mbexpr repl`: type an expression, see its value and derivatives; change a
//! parameter, plot a curve. With standard input from a file or a pipe it runs
//! as a batch: no prompt, one result line per input line, errors on standard
//! error with their line number.

use std::io::{self, BufRead, IsTerminal, Write};

use mbexpr::catalog::{ArgKind, Constant, Function, SystemVariable};
use mbexpr::syntax::ast::{Expr, ExprKind};
use mbexpr::{Counted, Order, Scene};
use rustyline::completion::{Completer, Pair};
use rustyline::{Context, Helper, Highlighter, Hinter, Validator};

use crate::support::files::read_scene;
use crate::support::render::{diagnostic, diagnostics};
use crate::support::values::show;
use crate::{Fatal, Outcome};

#[derive(clap::Args)]
pub struct Args {
    /// A scene (TOML) to evaluate measures in.
    #[arg(long, value_name = "FILE.toml")]
    scene: Option<String>,
}

const COMMANDS: [&str; 9] = [
    ":set", ":wrt", ":order", ":scene", ":vars", ":help", ":plot", ":quit", ":q",
];

const HELP: &str = "\
expressions: type one, e.g. STEP(TIME, 0, 0, 1, 10) or BISTOP(x, v, -1, 1, 1e4, 1.5, 50, 0.1)
:set NAME = VALUE     give a variable a value (VALUE may be an expression)
:wrt NAME, NAME       derivative directions (:wrt alone: none)
:order 0|1|2          value, gradient, or gradient and Hessian
:scene FILE.toml      evaluate measures in a scene
:vars                 what is bound
:help NAME            the signature and meaning of a function
:plot EXPR --over NAME=A..B -o FILE.svg [--derivatives] [--samples N]
NAME                  a named expression of the scene, in any expression
:quit                 leave (also Ctrl-D)";

/// What the REPL knows between lines.
#[derive(Default)]
pub struct Session {
    bindings: Vec<(String, f64)>,
    wrt: Vec<String>,
    order: Option<u8>,
    scene: Option<Scene>,
}

/// The answer to one input.
pub enum Reply {
    /// Text to show (may be empty).
    Text(String),
    /// Leave the REPL.
    Quit,
}

/// Whether `text` visibly goes on in the next line: it ends (before a
/// trailing `! comment`) with `(`, `,`, `:` or an operator, where an
/// expression cannot end. Any other line is a whole input, so in a batch
/// or a pasted block one unclosed parenthesis is an error on its own line,
/// not a hold on the lines after it.
fn continues(text: &str) -> bool {
    let line = text.lines().last().unwrap_or_default();
    if line.trim_start().starts_with(':') {
        return false;
    }
    mbexpr::syntax::without_comment(line)
        .trim_end()
        .ends_with(['(', ',', ':', '+', '-', '*', '/'])
}

/// Whether `text` (an expression, not a command) leaves a parenthesis open:
/// on a terminal, the line typed last then waits for the rest under the
/// continuation prompt.
fn unclosed(text: &str) -> bool {
    if text.trim_start().starts_with(':') {
        return false;
    }
    let depth = text.lines().fold(0i64, |depth, line| {
        mbexpr::syntax::without_comment(line)
            .chars()
            .fold(depth, |depth, c| match c {
                '(' => depth + 1,
                ')' => depth - 1,
                _ => depth,
            })
    });
    depth > 0
}

/// Gathers lines into inputs: a line is an input of its own unless it
/// visibly continues ([`continues`]), when the next line joins it.
#[derive(Default)]
struct Inputs {
    pending: String,
    first_line: usize,
}

impl Inputs {
    /// Takes line `number`; returns the input it completes, with the
    /// number of its first line. When `hold_open` (the last line typed on
    /// a terminal), an unclosed parenthesis waits for the next line too;
    /// an empty line ends the input whatever it holds.
    fn push(&mut self, number: usize, line: &str, hold_open: bool) -> Option<(usize, String)> {
        if self.pending.is_empty() {
            self.first_line = number;
        } else if line.trim().is_empty() {
            return Some((self.first_line, std::mem::take(&mut self.pending)));
        } else {
            self.pending.push(' ');
        }
        self.pending.push_str(line);
        if continues(&self.pending) || (hold_open && unclosed(&self.pending)) {
            return None;
        }
        Some((self.first_line, std::mem::take(&mut self.pending)))
    }

    /// Whether a line has been taken that waits for more.
    fn waiting(&self) -> bool {
        !self.pending.is_empty()
    }

    /// What is left when the input ends (a line that said it went on).
    fn finish(self) -> Option<(usize, String)> {
        (!self.pending.trim().is_empty()).then_some((self.first_line, self.pending))
    }
}

impl Session {
    fn order(&self) -> Order {
        match self.order {
            Some(order) => Order::from_number(order).unwrap_or(Order::Value),
            None if self.wrt.is_empty() => Order::Value,
            None => Order::Gradient,
        }
    }

    /// Evaluates `text` with the session's bindings: its value, or rendered errors.
    fn evaluate(&self, text: &str, compact: bool) -> Result<String, String> {
        let tree = mbexpr::parse(text)
            .map_err(|error| diagnostic("", text, error.span(), &error.to_string()))?;
        let checked = mbexpr::check(&tree).map_err(|errors| {
            let problems = errors.iter().map(|error| (error.span(), error.to_string()));
            diagnostics("", text, problems)
        })?;
        let bound =
            crate::support::binding::bind(&checked, self.scene.as_ref(), &self.bindings, &self.wrt)
                .map_err(|errors| {
                    crate::support::binding::render(&errors, "", text, |name| {
                        format!(":set {name} = VALUE")
                    })
                })?;
        let directions: Vec<usize> = self
            .wrt
            .iter()
            .filter_map(|name| bound.program.input_index(name))
            .collect();
        let evaluation = bound
            .program
            .evaluate(&bound.values, &directions, self.order())
            .map_err(|error| diagnostic("", text, error.span(), &error.to_string()))?;
        let mut result = format_result(&evaluation, &self.wrt, compact);
        if self.order() > Order::Value && self.wrt.is_empty() {
            let program = &bound.program;
            result += &crate::support::binding::no_directions(program, ":wrt NAME, NAME");
        }
        Ok(result)
    }

    /// Handles one complete input.
    pub fn handle(&mut self, input: &str, compact: bool) -> Result<Reply, String> {
        let input = if input.trim_start().starts_with(':') {
            input.trim()
        } else {
            mbexpr::syntax::without_comment(input).trim()
        };
        let Some(command) = input.strip_prefix(':') else {
            if input.is_empty() {
                return Ok(Reply::Text(String::new()));
            }
            return self.evaluate(&self.expand(input), compact).map(Reply::Text);
        };
        let (word, rest) = command
            .split_once(char::is_whitespace)
            .unwrap_or((command, ""));
        let rest = rest.trim();
        match word {
            "quit" | "q" | "exit" => Ok(Reply::Quit),
            "set" => {
                let (name, value) = rest
                    .split_once('=')
                    .ok_or_else(|| "error: write :set NAME = VALUE".to_string())?;
                let name = name.trim();
                if name.is_empty()
                    || !name
                        .chars()
                        .all(|c| c.is_ascii_alphanumeric() || "_./".contains(c))
                {
                    return Err(format!("error: `{name}` is not a variable name"));
                }
                if let Some(reason) = reserved(name) {
                    return Err(format!("error: {reason}"));
                }
                let value = self.constant(value.trim())?;
                if SystemVariable::lookup(name) == Some(SystemVariable::Mode)
                    && let Some(message) = SystemVariable::mode_error(value)
                {
                    return Err(format!("error: {message}"));
                }
                self.bindings
                    .retain(|(known, _)| !known.eq_ignore_ascii_case(name));
                self.bindings.push((name.to_string(), value));
                Ok(Reply::Text(format!("{name} = {}", show(value))))
            }
            "wrt" => {
                self.wrt = rest
                    .split(',')
                    .map(str::trim)
                    .filter(|name| !name.is_empty())
                    .map(str::to_string)
                    .collect();
                Ok(Reply::Text(if self.wrt.is_empty() {
                    "no derivative directions".to_string()
                } else {
                    format!("derivatives in {}", self.wrt.join(", "))
                }))
            }
            "order" => match rest {
                "0" | "1" | "2" => {
                    self.order = rest.parse().ok();
                    Ok(Reply::Text(format!("order {rest}")))
                }
                _ => Err("error: write :order 0, :order 1 or :order 2".to_string()),
            },
            "scene" => {
                let scene =
                    read_scene(rest).map_err(|fatal| fatal.message().trim_end().to_string())?;
                let summary = format!(
                    "scene {rest}: {}, {}, {}",
                    Counted(scene.bodies.len(), "body"),
                    Counted(scene.markers.len(), "marker"),
                    Counted(scene.expressions.len(), "expression")
                );
                self.scene = Some(scene);
                Ok(Reply::Text(summary))
            }
            "vars" => Ok(Reply::Text(self.vars())),
            "help" => Ok(Reply::Text(help(rest))),
            "plot" => self.plot(rest).map(Reply::Text),
            _ => Err(format!("error: unknown command :{word} (try :help)")),
        }
    }

    /// `input` with each name of a scene's named expression (where a value
    /// goes, and unless `:set` gave that name a value) replaced by the
    /// expression's text in parentheses: `2*gap` is `2*(DX(ball, wall,
    /// wall))`. An input that does not parse is left as it is, for its
    /// error.
    fn expand<'a>(&self, input: &'a str) -> std::borrow::Cow<'a, str> {
        let Some(scene) = self
            .scene
            .as_ref()
            .filter(|scene| !scene.expressions.is_empty())
        else {
            return input.into();
        };
        let Ok(tree) = mbexpr::parse(input) else {
            return input.into();
        };
        let mut places = Vec::new();
        self.named_places(scene, &tree, &mut places);
        if places.is_empty() {
            return input.into();
        }
        places.sort_by_key(|(span, _)| span.start);
        let (mut text, mut done) = (String::new(), 0);
        for (span, expression) in places {
            text += &input[done..span.start];
            text += &format!("({expression})");
            done = span.end;
        }
        text += &input[done..];
        text.into()
    }

    /// The places in `expression` where a name stands for one of the
    /// scene's named expressions, with that expression's text.
    fn named_places<'s>(
        &self,
        scene: &'s Scene,
        expression: &Expr,
        places: &mut Vec<(mbexpr::Span, &'s str)>,
    ) {
        let mut walk = |inner: &Expr| self.named_places(scene, inner, places);
        match &expression.kind {
            ExprKind::Number(_) => {}
            ExprKind::Name(name) => {
                let bound = self
                    .bindings
                    .iter()
                    .any(|(known, _)| known.eq_ignore_ascii_case(name));
                let named = scene
                    .expressions
                    .iter()
                    .find(|(known, _)| known.eq_ignore_ascii_case(name));
                if let Some((_, text)) = named.filter(|_| !bound) {
                    places.push((expression.span, text));
                }
            }
            ExprKind::Unary(_, operand) => walk(operand),
            ExprKind::Chain(first, rest) => {
                walk(first);
                rest.iter().for_each(|(_, operand)| walk(operand));
            }
            ExprKind::Power(base, exponent) => {
                walk(base);
                walk(exponent);
            }
            ExprKind::Call(call) => {
                let function = Function::lookup(&call.name);
                for (position, argument) in call.args.iter().enumerate() {
                    // A marker or a statement is named, never computed.
                    if function.is_none_or(|function| {
                        function.signature().kind(position) == ArgKind::Value
                    }) {
                        walk(argument);
                    }
                }
            }
            ExprKind::If(branches) => {
                for branch in [
                    &branches.condition,
                    &branches.negative,
                    &branches.zero,
                    &branches.positive,
                ] {
                    walk(branch);
                }
            }
        }
    }

    /// The value of a constant expression (or one over bound variables).
    fn constant(&self, text: &str) -> Result<f64, String> {
        let tree = mbexpr::parse(text)
            .map_err(|error| diagnostic("", text, error.span(), &error.to_string()))?;
        let checked = mbexpr::check(&tree)
            .map_err(|errors| diagnostic("", text, errors[0].span(), &errors[0].to_string()))?;
        let bound =
            crate::support::binding::bind(&checked, self.scene.as_ref(), &self.bindings, &[])
                .map_err(|errors| {
                    crate::support::binding::render(&errors, "", text, |name| {
                        format!(":set {name} = VALUE")
                    })
                })?;
        let evaluation = bound
            .program
            .evaluate(&bound.values, &[], Order::Value)
            .map_err(|error| diagnostic("", text, error.span(), &error.to_string()))?;
        Ok(evaluation.value)
    }

    fn vars(&self) -> String {
        let mut lines: Vec<String> = self
            .bindings
            .iter()
            .map(|(name, value)| format!("{name} = {}", show(*value)))
            .collect();
        let time_bound = self
            .bindings
            .iter()
            .any(|(name, _)| name.eq_ignore_ascii_case("TIME"));
        if !time_bound && self.scene.is_none() {
            lines.push("TIME = 0 (until set)".to_string());
        }
        if let Some(scene) = &self.scene {
            lines.push(format!("TIME = {} (scene)", show(scene.time)));
            for (name, value) in &scene.variables {
                lines.push(format!("{name} = {} (scene)", show(*value)));
            }
            let markers: Vec<String> = scene
                .markers
                .iter()
                .map(mbexpr::scene::Marker::label)
                .collect();
            lines.push(format!("markers: {}", markers.join(", ")));
            let bodies: Vec<&str> = scene.bodies.iter().map(|body| body.name.as_str()).collect();
            lines.push(format!(
                "bodies: {} (state components BODY.x ... BODY.wz)",
                bodies.join(", ")
            ));
        }
        lines.push(match self.wrt.as_slice() {
            [] => "no derivative directions".to_string(),
            wrt => format!("derivatives in {}", wrt.join(", ")),
        });
        lines.push(format!("order {}", self.order() as u8));
        lines.join("\n")
    }

    /// `:plot EXPR --over NAME=A..B -o FILE.svg`, as on the command line
    /// (`--derivatives` and `--samples N` too), or `:plot EXPR over NAME in
    /// A..B to FILE.svg`.
    fn plot(&self, rest: &str) -> Result<String, String> {
        let command = PlotCommand::parse(rest)?;
        let (over, start, end) = crate::support::plotting::parse_range(&command.range)
            .map_err(|message| format!("error: {message}"))?;
        let expression = &*self.expand(command.expression.trim());
        let file = command.file.as_str();
        let tree = mbexpr::parse(expression)
            .map_err(|error| diagnostic("", expression, error.span(), &error.to_string()))?;
        let checked = mbexpr::check(&tree).map_err(|errors| {
            diagnostic("", expression, errors[0].span(), &errors[0].to_string())
        })?;
        let request = crate::support::plotting::PlotRequest {
            text: expression,
            checked: &checked,
            scene: self.scene.as_ref(),
            bindings: &self.bindings,
            over: &over,
            range: (start, end),
            samples: command.samples,
            derivatives: command.derivatives || self.order() > Order::Value,
        };
        let plot = crate::support::plotting::curves(&request)
            .map_err(|message| format!("error: {message}"))?;
        crate::support::plotting::render_svg(file, &over, &plot)
            .map_err(|message| format!("error: cannot write {file}: {message}"))?;
        Ok(plot.summary(file, &over))
    }

    /// The words a name at the cursor may complete to.
    pub fn candidates(&self, line: &str, pos: usize) -> (usize, Vec<String>) {
        let before = &line[..pos];
        let start = before
            .rfind(|c: char| !(c.is_ascii_alphanumeric() || "_.:/".contains(c)))
            .map_or(0, |index| index + 1);
        let prefix = &before[start..];
        let mut words: Vec<String> = Vec::new();
        if let Some(path) = before.strip_prefix(":scene ") {
            return (pos - path.trim_start().len(), file_names(path.trim_start()));
        }
        if start == 0 && prefix.starts_with(':') {
            words.extend(COMMANDS.iter().map(|command| command.to_string()));
        } else if argument_kind(&before[..start]) == Some(ArgKind::Marker) {
            // Inside a call, where a marker goes: the scene's markers only.
            if let Some(scene) = &self.scene {
                words.extend(
                    scene
                        .markers
                        .iter()
                        .filter_map(|marker| marker.name.clone()),
                );
            }
        } else {
            words.extend(
                Function::ALL
                    .iter()
                    .map(|function| function.name().to_string()),
            );
            words.extend(
                Constant::ALL
                    .iter()
                    .map(|constant| constant.name().to_string()),
            );
            words.extend(["TIME", "MODE"].map(str::to_string));
            words.extend(self.bindings.iter().map(|(name, _)| name.clone()));
            if let Some(scene) = &self.scene {
                words.extend(scene.variables.iter().map(|(name, _)| name.clone()));
                words.extend(
                    scene
                        .markers
                        .iter()
                        .filter_map(|marker| marker.name.clone()),
                );
                words.extend(scene.expressions.iter().map(|(name, _)| name.clone()));
                for (index, _) in scene.bodies.iter().enumerate() {
                    words.extend(
                        mbexpr::scene::StateComponent::ALL
                            .map(|component| scene.state_name(index, component)),
                    );
                }
            }
        }
        let upper = prefix.to_uppercase();
        let mut matches: Vec<String> = words
            .into_iter()
            .filter(|word| word.to_uppercase().starts_with(&upper))
            .collect();
        matches.sort();
        matches.dedup();
        (start, matches)
    }
}

/// What `:plot` was asked for.
struct PlotCommand {
    expression: String,
    /// `NAME=A..B`.
    range: String,
    file: String,
    samples: usize,
    derivatives: bool,
}

impl PlotCommand {
    const USAGE: &str = "error: write :plot EXPR --over NAME=A..B -o FILE.svg [--derivatives] [--samples N] (or :plot EXPR over NAME in A..B to FILE.svg)";
    const OPTIONS: [&str; 5] = ["--over", "-o", "--output", "--derivatives", "--samples"];

    fn parse(text: &str) -> Result<PlotCommand, String> {
        let usage = || PlotCommand::USAGE.to_string();
        // The command line's form: the options follow the expression.
        let first_option = text
            .match_indices(" -")
            .map(|(index, _)| index)
            .find(|&index| {
                let word = text[index + 1..]
                    .split([' ', '='])
                    .next()
                    .unwrap_or_default();
                PlotCommand::OPTIONS.contains(&word)
            });
        let Some(first_option) = first_option else {
            let (expression, rest) = text.rsplit_once(" over ").ok_or_else(usage)?;
            let (name, rest) = rest.split_once(" in ").ok_or_else(usage)?;
            let (range, file) = rest.split_once(" to ").ok_or_else(usage)?;
            return Ok(PlotCommand {
                expression: expression.to_string(),
                range: format!("{}={}", name.trim(), range.trim()),
                file: file.trim().to_string(),
                samples: 400,
                derivatives: false,
            });
        };
        let mut command = PlotCommand {
            expression: text[..first_option].to_string(),
            range: String::new(),
            file: String::new(),
            samples: 400,
            derivatives: false,
        };
        let mut words = text[first_option..].split_whitespace();
        while let Some(word) = words.next() {
            let (option, attached) = match word.split_once('=') {
                Some((option, value)) if option.starts_with("--") && option != "--over" => {
                    (option, Some(value))
                }
                _ => (word, None),
            };
            let mut value = || {
                attached
                    .map(str::to_string)
                    .or_else(|| words.next().map(str::to_string))
                    .ok_or_else(|| format!("error: {option} needs a value"))
            };
            match option {
                "--over" => command.range = value()?,
                "-o" | "--output" => command.file = value()?,
                "--derivatives" => command.derivatives = true,
                "--samples" => {
                    let text = value()?;
                    command.samples = text
                        .parse()
                        .ok()
                        .filter(|samples| (2..=1_000_000).contains(samples))
                        .ok_or_else(|| {
                            format!(
                                "error: --samples {text}: give a whole number from 2 to 1000000"
                            )
                        })?;
                }
                _ => {
                    return Err(format!(
                        "error: `{word}` is not an option of :plot (--over, -o, --derivatives, --samples)"
                    ));
                }
            }
        }
        if command.range.is_empty() || command.file.is_empty() {
            return Err(usage());
        }
        Ok(command)
    }
}

/// The kind of argument that `before` (an input up to the word being
/// typed) is inside: the innermost call left open, at the argument its
/// commas have reached; `None` outside a call or in an unknown function.
fn argument_kind(before: &str) -> Option<ArgKind> {
    let (mut depth, mut position) = (0usize, 0usize);
    for (index, c) in before.char_indices().rev() {
        match c {
            ')' => depth += 1,
            '(' if depth > 0 => depth -= 1,
            '(' => {
                let name = before[..index].trim_end();
                let start = name
                    .rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                    .map_or(0, |at| at + 1);
                let function = Function::lookup(&name[start..])?;
                return Some(function.signature().kind(position));
            }
            ',' if depth == 0 => position += 1,
            _ => {}
        }
    }
    None
}

/// The files and folders that `typed` (a path being typed) may complete
/// to, folders with a `/`, sorted; files that start with a dot only when
/// the name typed does.
fn file_names(typed: &str) -> Vec<String> {
    let (folder, name) = match typed.rfind('/') {
        Some(at) => typed.split_at(at + 1),
        None => ("", typed),
    };
    let Ok(entries) = std::fs::read_dir(if folder.is_empty() { "." } else { folder }) else {
        return Vec::new();
    };
    let mut names: Vec<String> = entries
        .filter_map(Result::ok)
        .filter_map(|entry| {
            let file = entry.file_name().into_string().ok()?;
            if !file.starts_with(name) || (file.starts_with('.') && !name.starts_with('.')) {
                return None;
            }
            let slash = if entry.path().is_dir() { "/" } else { "" };
            Some(format!("{folder}{file}{slash}"))
        })
        .collect();
    names.sort();
    names
}

/// Why `name` cannot be given a value with `:set`: it is a constant or a
/// function of the language (which an expression never reads as a variable).
fn reserved(name: &str) -> Option<String> {
    if let Some(constant) = Constant::lookup(name) {
        return Some(format!(
            "{} is a constant ({}): it cannot be set; choose another name",
            constant.name(),
            show(constant.value())
        ));
    }
    Function::lookup(name).map(|function| {
        format!(
            "{} is a function, {}: it cannot be set; choose another name",
            function.name(),
            function.usage()
        )
    })
}

/// `:help NAME`: the function's (constant's, system variable's) entry of
/// the language reference (`docs/language.md`); `:help` alone: the commands.
fn help(name: &str) -> String {
    if name.is_empty() {
        return HELP.to_string();
    }
    mbexpr::help::topic(name).unwrap_or_else(|| {
        let known = Function::ALL.iter().map(|function| function.name());
        format!(
            "no function, constant or system variable {name}{}",
            mbexpr::catalog::did_you_mean(&mbexpr::catalog::closest(name, known))
        )
    })
}

/// The value and labelled derivatives: on one line (`compact`) or as a table.
fn format_result(evaluation: &mbexpr::Evaluation, wrt: &[String], compact: bool) -> String {
    let mut text = show(evaluation.value);
    let Some(gradient) = evaluation.gradient.as_ref().filter(|_| !wrt.is_empty()) else {
        return text;
    };
    let entries: Vec<String> = wrt
        .iter()
        .zip(gradient.iter())
        .map(|(name, entry)| format!("d/d{name} = {}", show(*entry)))
        .collect();
    if compact {
        text += &format!("  gradient [{}]", entries.join(", "));
    } else {
        for entry in &entries {
            text += &format!("\n  {entry}");
        }
    }
    if let Some(hessian) = &evaluation.hessian {
        let rows: Vec<String> = hessian
            .row_iter()
            .map(|row| {
                row.iter()
                    .map(|entry| show(*entry))
                    .collect::<Vec<_>>()
                    .join(", ")
            })
            .collect();
        if compact {
            text += &format!("  hessian [[{}]]", rows.join("], ["));
        } else {
            text += &format!("\n  hessian ({})", wrt.join(", "));
            for (name, row) in wrt.iter().zip(&rows) {
                text += &format!("\n    {name}: [{row}]");
            }
        }
    }
    text
}

/// rustyline's helper: completion (an input that goes on is held by the
/// session's loop, under its own prompt, not by the editor).
#[derive(Helper, Highlighter, Hinter, Validator)]
struct Editor {
    session: std::rc::Rc<std::cell::RefCell<Session>>,
}

impl Completer for Editor {
    type Candidate = Pair;

    fn complete(
        &self,
        line: &str,
        pos: usize,
        _: &Context<'_>,
    ) -> rustyline::Result<(usize, Vec<Pair>)> {
        let (start, words) = self.session.borrow().candidates(line, pos);
        let pairs = words
            .into_iter()
            .map(|word| Pair {
                display: word.clone(),
                replacement: word,
            })
            .collect();
        Ok((start, pairs))
    }
}

fn history_path() -> Option<std::path::PathBuf> {
    std::env::var_os("HOME").map(|home| std::path::PathBuf::from(home).join(".mbexpr_history"))
}

pub fn run(args: &Args, out: &mut impl Write) -> Result<Outcome, Fatal> {
    let mut session = Session::default();
    if let Some(path) = &args.scene {
        session.scene = Some(read_scene(path)?);
    }
    if io::stdin().is_terminal() {
        interactive(session)
    } else {
        batch(session, out)
    }
}

/// Standard input is a file or a pipe: one result line per complete input.
fn batch(mut session: Session, out: &mut impl Write) -> Result<Outcome, Fatal> {
    let mut failures = 0;
    let mut inputs = Inputs::default();
    for (index, line) in io::stdin().lock().lines().enumerate() {
        let line = line
            .map_err(|error| Fatal::usage(format!("error: cannot read standard input: {error}")))?;
        let Some((first_line, input)) = inputs.push(index + 1, &line, false) else {
            continue;
        };
        match answer(&mut session, first_line, &input, out)? {
            Some(Reply::Quit) => return Ok(outcome(failures)),
            Some(Reply::Text(_)) => {}
            None => failures += 1,
        }
    }
    if let Some((first_line, input)) = inputs.finish()
        && answer(&mut session, first_line, &input, out)?.is_none()
    {
        failures += 1;
    }
    Ok(outcome(failures))
}

fn outcome(failures: usize) -> Outcome {
    if failures == 0 {
        Outcome::Success
    } else {
        Outcome::Failure
    }
}

/// Handles one input of a batch: its result line on `out`, or its error on
/// standard error under its line number (`None`).
fn answer(
    session: &mut Session,
    first_line: usize,
    input: &str,
    out: &mut impl Write,
) -> Result<Option<Reply>, Fatal> {
    let trimmed = input.trim_start();
    if trimmed.is_empty() || trimmed.starts_with('!') {
        return Ok(Some(Reply::Text(String::new())));
    }
    match session.handle(input, true) {
        Ok(Reply::Text(text)) => {
            if !text.is_empty() {
                writeln!(out, "{text}")?;
            }
            Ok(Some(Reply::Text(text)))
        }
        Ok(Reply::Quit) => Ok(Some(Reply::Quit)),
        Err(message) => {
            out.flush()?;
            eprint!("line {first_line}: {message}");
            if !message.ends_with('\n') {
                eprintln!();
            }
            Ok(None)
        }
    }
}

fn interactive(session: Session) -> Result<Outcome, Fatal> {
    const PROMPT: &str = "mbexpr> ";
    const CONTINUATION_PROMPT: &str = "   ...> ";
    let session = std::rc::Rc::new(std::cell::RefCell::new(session));
    let mut editor = rustyline::Editor::<Editor, rustyline::history::DefaultHistory>::new()
        .map_err(|error| Fatal::usage(format!("error: cannot start the line editor: {error}")))?;
    editor.set_helper(Some(Editor {
        session: session.clone(),
    }));
    let history = history_path();
    if let Some(path) = &history {
        // A missing history file is the first run, not an error.
        let _ = editor.load_history(path);
    }
    // Written through a handle, not `println!`, so that a closed standard
    // output ends the session quietly rather than in a panic.
    let mut stdout = io::stdout();
    writeln!(
        stdout,
        "mbexpr {} — :help for commands, :quit to leave",
        env!("CARGO_PKG_VERSION")
    )?;
    // An input that goes on waits under the continuation prompt; Ctrl-C
    // drops it, an empty line or Ctrl-D ends it.
    let mut inputs = Inputs::default();
    'session: loop {
        let prompt = if inputs.waiting() {
            CONTINUATION_PROMPT
        } else {
            PROMPT
        };
        let read = editor.readline(prompt);
        let text = match read {
            Ok(text) => text,
            Err(rustyline::error::ReadlineError::Interrupted) => {
                inputs = Inputs::default();
                continue;
            }
            Err(rustyline::error::ReadlineError::Eof) if inputs.waiting() => String::new(),
            Err(rustyline::error::ReadlineError::Eof) => break,
            Err(error) => return Err(Fatal::usage(format!("error: {error}"))),
        };
        if !text.trim().is_empty() {
            let _ = editor.add_history_entry(text.as_str());
        }
        // A pasted block arrives whole: each of its lines is an input of
        // its own unless it visibly continues, as in a batch; its last
        // line (or the one line typed) may also wait for a parenthesis.
        let mut complete: Vec<(usize, String)> = Vec::new();
        let lines: Vec<&str> = if text.is_empty() {
            vec![""]
        } else {
            text.lines().collect()
        };
        for (index, line) in lines.iter().enumerate() {
            let last = index + 1 == lines.len();
            complete.extend(inputs.push(index + 1, line, last));
        }
        for (_, input) in complete {
            let reply = session.borrow_mut().handle(&input, false);
            match reply {
                Ok(Reply::Quit) => break 'session,
                Ok(Reply::Text(text)) if text.is_empty() => {}
                Ok(Reply::Text(text)) => writeln!(stdout, "{text}")?,
                Err(message) => eprint!(
                    "{}",
                    if message.ends_with('\n') {
                        message
                    } else {
                        message + "\n"
                    }
                ),
            }
        }
    }
    if let Some(path) = &history {
        let _ = editor.save_history(path);
    }
    Ok(Outcome::Success)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(session: &Session, line: &str) -> Vec<String> {
        session.candidates(line, line.len()).1
    }

    #[test]
    fn completion_offers_functions_constants_variables_commands_and_markers() {
        let mut session = Session::default();
        assert_eq!(names(&session, "2*BIS"), ["BISTOP"]);
        assert_eq!(names(&session, "ste"), ["STEP", "STEP5"]);
        assert_eq!(
            names(&session, "x + P"),
            [
                "PHI", "PI", "PINVAL", "PITCH", "POLY", "POUVAL", "PSI", "PTCV"
            ]
        );
        assert_eq!(names(&session, ":s"), [":scene", ":set"]);
        session.bindings.push(("stiffness".to_string(), 1e5));
        assert_eq!(names(&session, "IMPACT(x, v, 1, stif"), ["stiffness"]);
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/examples/scenes/ball_between_walls.toml"
        ))
        .unwrap();
        session.scene = Some(Scene::from_toml(&text).unwrap());
        assert_eq!(names(&session, "DX(wa"), ["wall"]);
        assert_eq!(names(&session, "DM(ball, w"), ["wall"]);
        assert_eq!(
            names(&session, "DM(ball, MAX(w"),
            [
                "WDTM", "WDTX", "WDTY", "WDTZ", "WM", "WX", "WY", "WZ", "wall"
            ]
        );
        assert_eq!(names(&session, "2*con"), ["CONTACT", "contact"]);
        let scenes = ":scene examples/scenes/ball_b";
        assert_eq!(
            session.candidates(scenes, scenes.len()),
            (
                7,
                vec!["examples/scenes/ball_between_walls.toml".to_string()]
            )
        );
        assert_eq!(names(&session, ":scene examples/sc"), ["examples/scenes/"]);
        assert_eq!(names(&session, "ball.v"), ["ball.vx", "ball.vy", "ball.vz"]);
        assert_eq!(session.candidates("DX(ba", 5).0, 3);
    }
}
