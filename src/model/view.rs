//! The references of an Adams View command file (`.cmd`): the markers, the
//! objects (`VARVAL(.model_1.VARIABLE_1)`) and the bare names (design
//! variables such as `.model_1.DV_1`) its expressions use must be created by
//! a command of the file (`marker create marker_name = ...`). A name may be
//! written in full or relative to the model (`PART_2.MARKER_1`).

use std::collections::HashSet;

use super::{Dataset, FoundExpression, ModelError, Problem, Value};
use crate::catalog::{ArgKind, closest, did_you_mean};
use crate::check::{Argument, Checked, NodeKind, Reference, visit};
use crate::span::Span;

/// View's general motion: its definition, as a name key, and its
/// components, the prefixes of its variables (`t1_type`, `t1_func` ...)
/// and of the motions it makes (`.m.general_motion_1.motion_t1`).
pub(crate) const GENERAL_MOTION: &str = "MDI.CONSTRAINTS.GENERAL_MOTION";
/// See [`GENERAL_MOTION`].
pub(crate) const GENERAL_MOTION_COMPONENTS: [&str; 6] = ["T1", "T2", "T3", "R1", "R2", "R3"];

/// The names the file creates, full and by every tail after a dot.
#[derive(Default)]
struct Created {
    /// Every created name as written (for "did you mean").
    names: Vec<String>,
    /// Upper case, full and every tail after a dot.
    forms: HashSet<String>,
}

impl Created {
    fn add(&mut self, name: &str) {
        self.names.push(name.to_string());
        let upper = name.trim_start_matches('.').to_ascii_uppercase();
        let mut rest = upper.as_str();
        loop {
            self.forms.insert(rest.to_string());
            match rest.split_once('.') {
                Some((_, tail)) => rest = tail,
                None => break,
            }
        }
    }

    fn has(&self, name: &str) -> bool {
        self.forms
            .contains(&name.trim_start_matches('.').to_ascii_uppercase())
    }

    fn suggestions(&self, name: &str) -> String {
        did_you_mean(&closest(name, self.names.iter().map(String::as_str)))
    }
}

/// Reports every name the expressions use that no command creates.
pub(crate) fn check_names(
    dataset: &Dataset,
    expressions: &[FoundExpression],
    trees: &[Option<Checked>],
    problems: &mut Vec<Problem>,
) {
    let (mut markers, mut objects) = (Created::default(), Created::default());
    for statement in &dataset.statements {
        // `variable set` makes the variable when there is none yet.
        if !statement.name.split(' ').any(|word| word == "CREATE")
            && statement.name != "VARIABLE SET"
        {
            continue;
        }
        for argument in &statement.arguments {
            let Value::List(items) = &argument.value else {
                continue;
            };
            let Some(name) = argument.keyword.strip_suffix("_NAME") else {
                continue;
            };
            for item in items {
                if name == "MARKER" {
                    markers.add(&item.text);
                }
                objects.add(&item.text);
            }
        }
        // View's general motion makes a motion for each component, named
        // in the instance (`.m.general_motion_1.motion_t3`).
        let first_of = |keyword: &str| {
            statement
                .arguments
                .iter()
                .find_map(|argument| match &argument.value {
                    Value::List(items) if argument.keyword == keyword => items.first(),
                    _ => None,
                })
        };
        let (definition, instance) = (first_of("DEFINITION_NAME"), first_of("INSTANCE_NAME"));
        if let (Some(definition), Some(instance)) = (definition, instance)
            && super::view_key(&definition.text) == GENERAL_MOTION
        {
            for component in GENERAL_MOTION_COMPONENTS {
                objects.add(&format!("{}.MOTION_{component}", instance.text));
            }
        }
    }
    for (index, found) in expressions.iter().enumerate() {
        let Some(tree) = &trees[index] else { continue };
        let Some((_, embedded)) = dataset.statements[found.statement]
            .expressions()
            .find(|(argument, _)| argument.keyword == found.keyword)
        else {
            continue;
        };
        let mut report = |what: &'static str, name: &str, created: &Created, span: Span| {
            problems.push(Problem {
                error: ModelError::NotCreated {
                    what,
                    name: name.to_string(),
                    suggestions: created.suggestions(name),
                    span: embedded.file_span(span),
                },
                statement: Some(found.statement),
                expression: Some(index),
            });
        };
        visit(&tree.root, &mut |node| match &node.kind {
            NodeKind::Variable(name) if !objects.has(name) => {
                report("variable", name, &objects, node.span);
            }
            NodeKind::Call(function, args) => {
                for (position, arg) in args.iter().enumerate() {
                    match (arg, function.signature().kind(position)) {
                        (Argument::Marker(Reference::Name(name), span), ArgKind::Marker)
                            if !markers.has(name) =>
                        {
                            report("marker", name, &markers, *span);
                        }
                        (Argument::Object(Reference::Name(name), span), ArgKind::Object)
                            if !objects.has(name) =>
                        {
                            report("object", name, &objects, *span);
                        }
                        _ => {}
                    }
                }
            }
            _ => {}
        });
    }
}
