//! Adams View's command language, carried out as View carries out a
//! command file: `variable create` and `variable set` give values, `for`
//! and `while` loops repeat their commands, an `if` whose conditions can
//! be evaluated keeps the branch they choose, and every value in
//! parentheses that can be evaluated (numbers, arithmetic, comparisons,
//! variables and loop counters, strings joined with `//`, `EVAL`, `RTOI`
//! and View's other numeric functions) is replaced by its value. So a
//! file that builds a chain of parts in a loop, naming each
//! `(eval(".chain.link_" // RTOI(i)))`, is read as the commands View
//! would carry out.
//!
//! What cannot be evaluated is left as written: a value with a unit
//! (`(20g)`), a function of the model View computes
//! (`(LOC_RELATIVE_TO({0, 0, 0}, .m.ground.A))`), an `if` whose
//! condition reads the model (`db_exists`), whose branches the readers
//! then all see; a loop whose bounds cannot be evaluated stays a `for`
//! command, which the readers refuse.

use std::collections::HashMap;

use super::{Argument, LARGEST_ID, ReadError, Statement, Value, ValueItem, view_key as key};
use crate::span::Span;

/// The most commands the loops of one file may write, and the most times
/// one `while` loop may go round (against a loop that never ends): five
/// times the largest models users have, and a bound on the memory the
/// copies take.
const MOST_COMMANDS: usize = 250_000;

/// How many times the loops of one file may go round in all (loops
/// inside loops that write nothing still take time).
const MOST_ROUNDS: usize = 1_000_000;

/// How deep loops and `if` blocks may nest, and `EVAL` may evaluate the
/// strings it is given.
const MOST_NESTED: usize = 64;

/// The longest string `//` may make (a string doubled in a loop grows as
/// 2^n): a longer one is not evaluated.
const LONGEST_TEXT: usize = 65_536;

/// A value of View's language.
#[derive(Clone, Debug, PartialEq)]
enum Datum {
    Real(f64),
    Integer(i64),
    Text(String),
}

impl Datum {
    fn number(&self) -> Option<f64> {
        match self {
            Datum::Real(value) => Some(*value),
            Datum::Integer(value) => Some(*value as f64),
            // View coerces a string that reads as a number.
            Datum::Text(text) => text.trim().parse().ok(),
        }
    }

    /// The text View puts in a string or a parameter for the value.
    fn text(&self) -> String {
        match self {
            Datum::Real(value) => real_text(*value),
            Datum::Integer(value) => value.to_string(),
            Datum::Text(text) => text.clone(),
        }
    }
}

/// A real as parameter text that reads back as the same double (a whole
/// number without a fraction).
fn real_text(value: f64) -> String {
    if value.fract() == 0.0 && value.abs() < 1e15 {
        format!("{value:.0}")
    } else {
        format!("{value:?}")
    }
}

/// How a block of commands ended: at its end, or at a `break` or
/// `continue` of the loop around it.
#[derive(Clone, Copy, PartialEq)]
enum Flow {
    Next,
    Break,
    Continue,
}

/// The blocks of the file: for each `for`, `while` and `if` command, its
/// matching `end`, and for an `if` the places of its `elseif` and `else`.
struct Blocks {
    end: HashMap<usize, usize>,
    branches: HashMap<usize, Vec<usize>>,
}

fn blocks(statements: &[Statement]) -> Blocks {
    let mut end = HashMap::new();
    let mut branches: HashMap<usize, Vec<usize>> = HashMap::new();
    let mut open: Vec<usize> = Vec::new();
    for (index, statement) in statements.iter().enumerate() {
        match statement.name.as_str() {
            "FOR" | "WHILE" | "IF" => open.push(index),
            "ELSEIF" | "ELSE" => {
                if let Some(&opener) = open.last()
                    && statements[opener].name == "IF"
                {
                    branches.entry(opener).or_default().push(index);
                }
            }
            "END" => {
                if let Some(opener) = open.pop() {
                    end.insert(opener, index);
                }
            }
            _ => {}
        }
    }
    Blocks { end, branches }
}

/// The file's commands as View carries them out (see the module's
/// account); a problem where the loops write more than
/// [`MOST_COMMANDS`] commands, go round more than [`MOST_ROUNDS`] times
/// or nest deeper than [`MOST_NESTED`].
pub(super) fn carry_out(statements: Vec<Statement>) -> (Vec<Statement>, Option<ReadError>) {
    let scripted = statements.iter().any(|statement| {
        matches!(statement.name.as_str(), "FOR" | "WHILE" | "IF")
            || statement.name.starts_with("VARIABLE")
            || statement.arguments.iter().any(|argument| {
                matches!(&argument.value, Value::List(items)
                    if items.iter().any(|item| item.text.trim_start().starts_with('(')))
            })
    });
    if !scripted {
        return (statements, None);
    }
    let blocks = blocks(&statements);
    let mut script = Script {
        statements: &statements,
        blocks,
        variables: HashMap::new(),
        by_last: HashMap::new(),
        out: Vec::new(),
        problem: None,
        depth: 0,
        loops: 0,
        rounds: 0,
    };
    script.block(0, statements.len());
    let (out, problem) = (script.out, script.problem);
    match problem {
        // The file as read, with the problem that stops it.
        Some(problem) => (statements, Some(problem)),
        None => (out, None),
    }
}

struct Script<'s> {
    statements: &'s [Statement],
    blocks: Blocks,
    /// The variables by key (upper case, no leading dot).
    variables: HashMap<String, Datum>,
    /// The variables' keys by their last part (after the last dot), so
    /// that a name read by its tail is found without a search of all.
    by_last: HashMap<String, Vec<String>>,
    out: Vec<Statement>,
    problem: Option<ReadError>,
    /// How deep the blocks being carried out nest.
    depth: usize,
    /// How many loops are going round.
    loops: usize,
    /// How many times the loops have gone round.
    rounds: usize,
}

impl Script<'_> {
    /// Carries out commands `from..to`.
    fn block(&mut self, from: usize, to: usize) -> Flow {
        let mut index = from;
        while index < to && self.problem.is_none() {
            let statement = &self.statements[index];
            let end = self.blocks.end.get(&index).copied().filter(|&end| end < to);
            match (statement.name.as_str(), end) {
                (kind @ ("FOR" | "WHILE"), Some(end)) => {
                    let carried = if kind == "FOR" {
                        self.repeat(index, end)
                    } else {
                        self.repeat_while(index, end)
                    };
                    if !carried {
                        self.copy(index, end + 1);
                    }
                    index = end + 1;
                }
                ("IF", Some(end)) => {
                    let flow = self.choose(index, end);
                    if flow != Flow::Next {
                        return flow;
                    }
                    index = end + 1;
                }
                ("BREAK", _) if self.loops > 0 => return Flow::Break,
                ("CONTINUE", _) if self.loops > 0 => return Flow::Continue,
                _ => {
                    let statement = self.evaluated(statement);
                    if statement.name.starts_with("VARIABLE") {
                        self.assign(&statement);
                    }
                    self.emit(statement);
                    index += 1;
                }
            }
        }
        Flow::Next
    }

    fn emit(&mut self, statement: Statement) {
        if self.out.len() >= MOST_COMMANDS {
            self.problem = Some(ReadError::TooManyCommands {
                limit: MOST_COMMANDS,
                span: statement.span,
            });
            return;
        }
        self.out.push(statement);
    }

    /// Copies commands `from..to` as they are written, a block the script
    /// cannot carry out (the readers refuse its `for` or `while`).
    fn copy(&mut self, from: usize, to: usize) {
        for index in from..to {
            self.emit(self.statements[index].clone());
        }
    }

    /// Counts a loop's round: false (with the problem) past
    /// [`MOST_ROUNDS`].
    fn round(&mut self, span: Span) -> bool {
        self.rounds += 1;
        if self.rounds > MOST_ROUNDS {
            self.problem = Some(ReadError::TooManyRounds {
                limit: MOST_ROUNDS,
                span,
            });
            return false;
        }
        true
    }

    /// Enters a nested block: false (with the problem) past
    /// [`MOST_NESTED`].
    fn enter(&mut self, span: Span) -> bool {
        if self.depth >= MOST_NESTED {
            self.problem = Some(ReadError::NestedTooDeep {
                limit: MOST_NESTED,
                span,
            });
            return false;
        }
        self.depth += 1;
        true
    }

    /// A `for` loop over `variable_name` from `start_value` to `end_value`
    /// by `increment_value` (1 when left out), or over the names of
    /// `object_names`; false when its values cannot be evaluated.
    fn repeat(&mut self, opener: usize, end: usize) -> bool {
        let statement = &self.statements[opener];
        let Some(name) = self.word(statement, "VARIABLE_NAME") else {
            return false;
        };
        let values: Vec<Datum> = if let Some(objects) = items(statement, "OBJECT_NAMES") {
            objects
                .iter()
                .map(|item| Datum::Text(self.item_value(item).text()))
                .collect()
        } else {
            let bound = |keyword: &str| {
                items(statement, keyword)
                    .and_then(|items| match items {
                        [item] => self.item_value(item).number(),
                        _ => None,
                    })
                    .filter(|value| value.is_finite())
            };
            let (Some(start), Some(last)) = (bound("START_VALUE"), bound("END_VALUE")) else {
                return false;
            };
            let step = match items(statement, "INCREMENT_VALUE") {
                Some(_) => match bound("INCREMENT_VALUE") {
                    Some(step) if step != 0.0 => step,
                    _ => return false,
                },
                None => 1.0,
            };
            let count = ((last - start) / step + 1e-9).floor() + 1.0;
            // More rounds than all loops may go: refused before the
            // counter's values are made.
            if count > MOST_ROUNDS as f64 {
                self.problem = Some(ReadError::TooManyRounds {
                    limit: MOST_ROUNDS,
                    span: statement.span,
                });
                return true;
            }
            let whole = [start, step].iter().all(|value| value.fract() == 0.0);
            (0..count.max(0.0) as usize)
                .map(|k| {
                    let value = start + k as f64 * step;
                    if whole {
                        Datum::Integer(value as i64)
                    } else {
                        Datum::Real(value)
                    }
                })
                .collect()
        };
        if !self.enter(statement.span) {
            return true;
        }
        self.loops += 1;
        for value in values {
            if !self.round(statement.span) {
                break;
            }
            self.set(name.clone(), value);
            if self.block(opener + 1, end) == Flow::Break || self.problem.is_some() {
                break;
            }
        }
        self.loops -= 1;
        self.depth -= 1;
        true
    }

    /// A `while` loop: its body again while `condition` is true; false
    /// when the condition cannot be evaluated the first time.
    fn repeat_while(&mut self, opener: usize, end: usize) -> bool {
        let statement = &self.statements[opener];
        let span = statement.span;
        let Some(mut going) = self.condition(statement) else {
            return false;
        };
        if !self.enter(span) {
            return true;
        }
        self.loops += 1;
        while going && self.problem.is_none() && self.round(span) {
            if self.block(opener + 1, end) == Flow::Break {
                break;
            }
            going = self.condition(&self.statements[opener]).unwrap_or(false);
        }
        self.loops -= 1;
        self.depth -= 1;
        true
    }

    /// An `if` block: the branch its conditions choose, or, when one
    /// cannot be evaluated before one is true, every command as written
    /// (the readers pass over `if`, `else` and `end`).
    fn choose(&mut self, opener: usize, end: usize) -> Flow {
        let mut starts = vec![opener];
        starts.extend(
            self.blocks
                .branches
                .get(&opener)
                .into_iter()
                .flatten()
                .copied()
                .filter(|&at| at < end),
        );
        if !self.enter(self.statements[opener].span) {
            return Flow::Next;
        }
        let flow = self.choose_branch(&starts, end);
        self.depth -= 1;
        flow
    }

    /// The branch of an `if` block (its commands start after each of
    /// `starts`, the block ends at `end`) its conditions choose.
    fn choose_branch(&mut self, starts: &[usize], end: usize) -> Flow {
        let mut chosen = None;
        for (k, &start) in starts.iter().enumerate() {
            let statement = &self.statements[start];
            let taken = match statement.name.as_str() {
                "ELSE" => Some(true),
                _ => self.condition(statement),
            };
            match taken {
                Some(true) => {
                    chosen = Some((start + 1, starts.get(k + 1).copied().unwrap_or(end)));
                    break;
                }
                Some(false) => {}
                None => {
                    // Every branch as written, each carried out.
                    for (k, &start) in starts.iter().enumerate() {
                        self.emit(self.statements[start].clone());
                        let stop = starts.get(k + 1).copied().unwrap_or(end);
                        let flow = self.block(start + 1, stop);
                        if flow != Flow::Next {
                            return flow;
                        }
                    }
                    self.emit(self.statements[end].clone());
                    return Flow::Next;
                }
            }
        }
        match chosen {
            Some((from, to)) => self.block(from, to),
            None => Flow::Next,
        }
    }

    /// The `condition` of an `if`, `elseif` or `while`, if it evaluates
    /// to a number (true when not zero).
    fn condition(&self, statement: &Statement) -> Option<bool> {
        match items(statement, "CONDITION")? {
            [item] => self.item_value(item).number().map(|value| value != 0.0),
            _ => None,
        }
    }

    /// Records a variable's value (`real_value`, `integer_value` or
    /// `string_value`, a single one); one that is not known (a list, an
    /// expression left in brackets) is forgotten.
    fn assign(&mut self, statement: &Statement) {
        let Some(name) = self.word(statement, "VARIABLE_NAME") else {
            return;
        };
        if statement.name == "VARIABLE DELETE" {
            self.forget(&name);
            return;
        }
        let value = [("REAL_VALUE", 0), ("INTEGER_VALUE", 1), ("STRING_VALUE", 2)]
            .iter()
            .find_map(|&(keyword, kind)| {
                let items = items(statement, keyword)?;
                Some(match (items, kind) {
                    // A value still in brackets was not evaluated.
                    ([item], _) if item.text.trim_start().starts_with('(') => None,
                    ([item], 0) => item.text.trim().parse().ok().map(Datum::Real),
                    ([item], 1) => item.text.trim().parse().ok().map(Datum::Integer),
                    ([item], _) => Some(Datum::Text(item.text.to_string())),
                    _ => None,
                })
            });
        match value {
            Some(Some(value)) => self.set(name, value),
            Some(None) => self.forget(&name),
            None => {}
        }
    }

    /// The single word of a parameter, as a key, its value evaluated.
    fn word(&self, statement: &Statement, keyword: &str) -> Option<String> {
        match items(statement, keyword)? {
            [item] => Some(key(&self.item_value(item).text())),
            _ => None,
        }
    }

    /// An item's value: its expression's where it is one that evaluates,
    /// otherwise its text.
    fn item_value(&self, item: &ValueItem) -> Datum {
        self.evaluate_item(item)
            .unwrap_or_else(|| Datum::Text(item.text.to_string()))
    }

    fn evaluate_item(&self, item: &ValueItem) -> Option<Datum> {
        let text = item.text.trim();
        if !text.starts_with('(') {
            return None;
        }
        self.evaluate(text, 0)
    }

    /// `statement` with every item that evaluates replaced by its value
    /// (and its id read again from `adams_id`). In a `modify` command
    /// outside loops, only values given with `eval`: the others are the
    /// "expression definitions" View's export writes after the objects,
    /// restating as expressions the values the create commands wrote,
    /// which the readers know as such.
    fn evaluated(&self, statement: &Statement) -> Statement {
        let mut statement = statement.clone();
        let restating = self.loops == 0 && statement.name.contains(" MODIFY ");
        let mut changed = false;
        for argument in &mut statement.arguments {
            if let Value::List(items) = &mut argument.value {
                for item in items {
                    if restating && !item.text.to_ascii_uppercase().contains("EVAL(") {
                        continue;
                    }
                    if let Some(value) = self.evaluate_item(item) {
                        item.text = value.text().into();
                        changed = true;
                    }
                }
            }
        }
        if changed {
            statement.id = adams_id(&statement.arguments);
        }
        statement
    }

    /// The value of the expression `text`, if every part of it is known.
    fn evaluate(&self, text: &str, depth: usize) -> Option<Datum> {
        if depth > MOST_NESTED {
            return None;
        }
        let tokens = tokens(text)?;
        let mut parser = Parser {
            tokens: &tokens,
            at: 0,
            script: self,
            depth,
            nesting: 0,
        };
        let value = parser.either()?;
        (parser.at == tokens.len()).then_some(value)
    }

    /// Gives variable `name` (a key) `value`.
    fn set(&mut self, name: String, value: Datum) {
        if !self.variables.contains_key(&name) {
            self.by_last
                .entry(last_part(&name).to_string())
                .or_default()
                .push(name.clone());
        }
        self.variables.insert(name, value);
    }

    /// Forgets variable `name` (a key).
    fn forget(&mut self, name: &str) {
        if self.variables.remove(name).is_some()
            && let Some(names) = self.by_last.get_mut(last_part(name))
        {
            names.retain(|known| known != name);
        }
    }

    /// A variable's value: by its full name, or the one variable whose
    /// name ends with it (a loop counter `i`, a model's `.m.n` read as `n`).
    fn variable(&self, name: &str) -> Option<Datum> {
        let name = key(name);
        if let Some(value) = self.variables.get(&name) {
            return Some(value.clone());
        }
        let tail = |long: &str, short: &str| {
            long.len() > short.len()
                && long.ends_with(short)
                && long.as_bytes()[long.len() - short.len() - 1] == b'.'
        };
        // A name and its tail end in the same part.
        let mut found = self
            .by_last
            .get(last_part(&name))
            .into_iter()
            .flatten()
            .filter(|known| tail(known, &name) || tail(&name, known));
        match (found.next(), found.next()) {
            (Some(known), None) => self.variables.get(known).cloned(),
            _ => None,
        }
    }
}

/// The items of parameter `keyword`, when it is a list.
fn items<'a>(statement: &'a Statement, keyword: &str) -> Option<&'a [ValueItem]> {
    let argument = statement
        .arguments
        .iter()
        .find(|argument| argument.keyword == keyword)?;
    match &argument.value {
        Value::List(items) => Some(items),
        _ => None,
    }
}

/// The part of a key after its last dot (all of it when it has none).
fn last_part(key: &str) -> &str {
    key.rsplit('.').next().unwrap_or(key)
}

/// The id `adams_id` gives, as the command reader reads it.
fn adams_id(arguments: &[Argument]) -> Option<u64> {
    let argument = arguments
        .iter()
        .find(|argument| argument.keyword == "ADAMS_ID")?;
    match &argument.value {
        Value::List(items) => items
            .first()
            .and_then(|item| item.text.trim().parse().ok())
            .filter(|&id| id <= LARGEST_ID),
        _ => None,
    }
}

#[derive(Clone, Debug, PartialEq)]
enum Token {
    Number(f64),
    Text(String),
    Name(String),
    Symbol(&'static str),
}

/// The tokens of an expression; `None` at a character View's language
/// has that the script does not evaluate (a unit after a number, `$`,
/// braces).
fn tokens(text: &str) -> Option<Vec<Token>> {
    const SYMBOLS: [&str; 19] = [
        "**", "//", "==", "!=", "<>", "<=", ">=", "&&", "||", "+", "-", "*", "/", "(", ")", ",",
        "<", ">", "!",
    ];
    let bytes = text.as_bytes();
    let mut tokens = Vec::new();
    let mut at = 0;
    while at < bytes.len() {
        let c = bytes[at];
        if c.is_ascii_whitespace() {
            at += 1;
        } else if c.is_ascii_digit()
            || (c == b'.' && bytes.get(at + 1).is_some_and(u8::is_ascii_digit))
        {
            let start = at;
            while at < bytes.len() && (bytes[at].is_ascii_digit() || bytes[at] == b'.') {
                at += 1;
            }
            if at < bytes.len() && matches!(bytes[at], b'e' | b'E') {
                let mut next = at + 1;
                if next < bytes.len() && matches!(bytes[next], b'+' | b'-') {
                    next += 1;
                }
                if next < bytes.len() && bytes[next].is_ascii_digit() {
                    at = next;
                    while at < bytes.len() && bytes[at].is_ascii_digit() {
                        at += 1;
                    }
                }
            }
            // A unit or a `d` after the number: not evaluated here.
            if at < bytes.len() && (bytes[at].is_ascii_alphabetic() || bytes[at] == b'_') {
                return None;
            }
            tokens.push(Token::Number(text[start..at].parse().ok()?));
        } else if c == b'"' {
            let close = text[at + 1..].find('"')? + at + 1;
            tokens.push(Token::Text(text[at + 1..close].to_string()));
            at = close + 1;
        } else if c.is_ascii_alphabetic() || c == b'_' || c == b'.' {
            let start = at;
            while at < bytes.len()
                && (bytes[at].is_ascii_alphanumeric() || bytes[at] == b'_' || bytes[at] == b'.')
            {
                at += 1;
            }
            tokens.push(Token::Name(text[start..at].to_string()));
        } else {
            let symbol = SYMBOLS
                .iter()
                .find(|symbol| text[at..].starts_with(**symbol))?;
            tokens.push(Token::Symbol(symbol));
            at += symbol.len();
        }
    }
    Some(tokens)
}

/// A recursive-descent reading of an expression, evaluated as it is read
/// (Fortran's precedence: `||`, `&&`, comparisons, `//`, `+ -`, `* /`,
/// signs and `!`, `**`).
struct Parser<'t, 's> {
    tokens: &'t [Token],
    at: usize,
    script: &'t Script<'s>,
    /// How deep `EVAL` of a string has gone.
    depth: usize,
    /// How deep the brackets and signs nest.
    nesting: usize,
}

impl Parser<'_, '_> {
    fn eat(&mut self, symbol: &str) -> bool {
        if matches!(self.tokens.get(self.at), Some(Token::Symbol(known)) if *known == symbol) {
            self.at += 1;
            true
        } else {
            false
        }
    }

    fn peek_symbol(&self) -> Option<&'static str> {
        match self.tokens.get(self.at) {
            Some(Token::Symbol(symbol)) => Some(symbol),
            _ => None,
        }
    }

    fn either(&mut self) -> Option<Datum> {
        let mut value = self.both()?;
        while self.eat("||") {
            let right = self.both()?;
            value = truth(value.number()? != 0.0 || right.number()? != 0.0);
        }
        Some(value)
    }

    fn both(&mut self) -> Option<Datum> {
        let mut value = self.comparison()?;
        while self.eat("&&") {
            let right = self.comparison()?;
            value = truth(value.number()? != 0.0 && right.number()? != 0.0);
        }
        Some(value)
    }

    fn comparison(&mut self) -> Option<Datum> {
        let mut value = self.joined()?;
        while let Some(symbol @ ("==" | "!=" | "<>" | "<" | ">" | "<=" | ">=")) = self.peek_symbol()
        {
            self.at += 1;
            let right = self.joined()?;
            let order = match (&value, &right) {
                (Datum::Text(a), Datum::Text(b)) => a.cmp(b),
                _ => value.number()?.partial_cmp(&right.number()?)?,
            };
            use std::cmp::Ordering::{Equal, Greater, Less};
            value = truth(match symbol {
                "==" => order == Equal,
                "!=" | "<>" => order != Equal,
                "<" => order == Less,
                ">" => order == Greater,
                "<=" => order != Greater,
                _ => order != Less,
            });
        }
        Some(value)
    }

    fn joined(&mut self) -> Option<Datum> {
        let mut value = self.sum()?;
        while self.eat("//") {
            let right = self.sum()?;
            let (left, right) = (value.text(), right.text());
            if left.len() + right.len() > LONGEST_TEXT {
                return None;
            }
            value = Datum::Text(left + &right);
        }
        Some(value)
    }

    fn sum(&mut self) -> Option<Datum> {
        let mut value = self.product()?;
        while let Some(symbol @ ("+" | "-")) = self.peek_symbol() {
            self.at += 1;
            let right = self.product()?;
            value = arithmetic(symbol, &value, &right)?;
        }
        Some(value)
    }

    fn product(&mut self) -> Option<Datum> {
        let mut value = self.signed()?;
        while let Some(symbol @ ("*" | "/")) = self.peek_symbol() {
            self.at += 1;
            let right = self.signed()?;
            value = arithmetic(symbol, &value, &right)?;
        }
        Some(value)
    }

    fn signed(&mut self) -> Option<Datum> {
        self.nesting += 1;
        if self.nesting > MOST_NESTED * 2 {
            return None;
        }
        let value = if self.eat("-") {
            arithmetic("-", &Datum::Integer(0), &self.signed()?)
        } else if self.eat("+") {
            self.signed()
        } else if self.eat("!") {
            Some(truth(self.signed()?.number()? == 0.0))
        } else {
            self.power()
        };
        self.nesting -= 1;
        value
    }

    fn power(&mut self) -> Option<Datum> {
        let base = self.atom()?;
        if self.eat("**") {
            // Right to left, binding tighter than a sign after it.
            let exponent = self.signed()?;
            return finite(match (&base, &exponent) {
                (Datum::Integer(b), Datum::Integer(e)) if (0..=62).contains(e) => {
                    match b.checked_pow(*e as u32) {
                        Some(value) => Datum::Integer(value),
                        None => Datum::Real((*b as f64).powi(*e as i32)),
                    }
                }
                _ => Datum::Real(base.number()?.powf(exponent.number()?)),
            });
        }
        Some(base)
    }

    fn atom(&mut self) -> Option<Datum> {
        let token = self.tokens.get(self.at)?.clone();
        self.at += 1;
        match token {
            Token::Number(value) => Some(Datum::Real(value)),
            Token::Text(text) => Some(Datum::Text(text)),
            Token::Symbol("(") => {
                let value = self.either()?;
                self.eat(")").then_some(value)
            }
            Token::Symbol(_) => None,
            Token::Name(name) => {
                if self.eat("(") {
                    let mut arguments = Vec::new();
                    if !self.eat(")") {
                        loop {
                            arguments.push(self.either()?);
                            if self.eat(")") {
                                break;
                            }
                            if !self.eat(",") {
                                return None;
                            }
                        }
                    }
                    self.call(&name, &arguments)
                } else {
                    self.script
                        .variable(&name)
                        .or_else(|| constant(&name).map(Datum::Real))
                }
            }
        }
    }

    /// View's function `name` of `arguments`.
    fn call(&self, name: &str, arguments: &[Datum]) -> Option<Datum> {
        let name = name.to_ascii_uppercase();
        if name == "EVAL" {
            return match arguments {
                // A string that reads as an expression is evaluated (`eval("2
                // + 2")`); any other stays the string, evaluated now rather
                // than kept as a reference (`eval(".m.link_" // RTOI(i))`).
                [Datum::Text(text)] => Some(
                    self.script
                        .evaluate(text, self.depth + 1)
                        .unwrap_or_else(|| Datum::Text(text.clone())),
                ),
                [value] => Some(value.clone()),
                _ => None,
            };
        }
        if let ("STOI" | "STOR", [Datum::Text(text)]) = (name.as_str(), arguments) {
            let value: f64 = text.trim().parse().ok()?;
            return finite(if name == "STOI" {
                Datum::Integer(value.trunc() as i64)
            } else {
                Datum::Real(value)
            });
        }
        let numbers: Vec<f64> = arguments.iter().map(Datum::number).collect::<Option<_>>()?;
        let one = |f: fn(f64) -> f64| match numbers.as_slice() {
            [x] => Some(Datum::Real(f(*x))),
            _ => None,
        };
        let whole = |value: f64| {
            (value.is_finite() && value.abs() < 9e18).then_some(Datum::Integer(value as i64))
        };
        let value = match name.as_str() {
            "RTOI" | "STOI" => whole(single(&numbers)?.trunc())?,
            "NINT" => whole(single(&numbers)?.round())?,
            "INT" | "AINT" => one(f64::trunc)?,
            "ANINT" => one(f64::round)?,
            "CEIL" => one(f64::ceil)?,
            "FLOOR" => one(f64::floor)?,
            "ABS" => one(f64::abs)?,
            "SQRT" => one(f64::sqrt)?,
            "EXP" => one(f64::exp)?,
            "LOG" => one(f64::ln)?,
            "LOG10" => one(f64::log10)?,
            "SIN" => one(f64::sin)?,
            "COS" => one(f64::cos)?,
            "TAN" => one(f64::tan)?,
            "ASIN" => one(f64::asin)?,
            "ACOS" => one(f64::acos)?,
            "ATAN" => one(f64::atan)?,
            "SINH" => one(f64::sinh)?,
            "COSH" => one(f64::cosh)?,
            "TANH" => one(f64::tanh)?,
            "STOR" => Datum::Real(single(&numbers)?),
            "ATAN2" => match numbers.as_slice() {
                [y, x] => Datum::Real(y.atan2(*x)),
                _ => return None,
            },
            "MOD" => match numbers.as_slice() {
                // Fortran's: the sign of the dividend.
                [a, b] if *b != 0.0 => Datum::Real(a - (a / b).trunc() * b),
                _ => return None,
            },
            "SIGN" => match numbers.as_slice() {
                [a, b] => Datum::Real(if *b >= 0.0 { a.abs() } else { -a.abs() }),
                _ => return None,
            },
            "MIN" if !numbers.is_empty() => {
                Datum::Real(numbers.iter().copied().fold(f64::INFINITY, f64::min))
            }
            "MAX" if !numbers.is_empty() => {
                Datum::Real(numbers.iter().copied().fold(f64::NEG_INFINITY, f64::max))
            }
            _ => return None,
        };
        finite(value)
    }
}

fn single(numbers: &[f64]) -> Option<f64> {
    match numbers {
        [x] => Some(*x),
        _ => None,
    }
}

/// A comparison's or a logical operator's value: 1 or 0.
fn truth(value: bool) -> Datum {
    Datum::Integer(i64::from(value))
}

/// `value` if it is a finite number (or a string): an expression that
/// overflows or leaves a function's domain is not evaluated.
fn finite(value: Datum) -> Option<Datum> {
    match value {
        Datum::Real(x) if !x.is_finite() => None,
        value => Some(value),
    }
}

/// `a symbol b` for `+ - * /`: integers stay integers under `+ - *`
/// while they fit.
fn arithmetic(symbol: &str, a: &Datum, b: &Datum) -> Option<Datum> {
    if let (Datum::Integer(x), Datum::Integer(y)) = (a, b) {
        let exact = match symbol {
            "+" => x.checked_add(*y),
            "-" => x.checked_sub(*y),
            "*" => x.checked_mul(*y),
            _ => None,
        };
        if let Some(value) = exact {
            return Some(Datum::Integer(value));
        }
    }
    let (x, y) = (a.number()?, b.number()?);
    finite(Datum::Real(match symbol {
        "+" => x + y,
        "-" => x - y,
        "*" => x * y,
        _ => x / y,
    }))
}

/// View's constants.
fn constant(name: &str) -> Option<f64> {
    use std::f64::consts::PI;
    match name.to_ascii_uppercase().as_str() {
        "PI" => Some(PI),
        "RTOD" => Some(180.0 / PI),
        "DTOR" => Some(PI / 180.0),
        _ => None,
    }
}
