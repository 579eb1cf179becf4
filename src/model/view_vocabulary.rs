//! Adams View's commands and their parameters, and View's abbreviations of
//! them: a command word may be cut to any beginning that is one word's
//! alone among those that can stand there (`part cre rig name_and_pos`),
//! and a parameter to any beginning that is one parameter's alone among
//! its command's (`loc = 0, 0, 0`, `len = meter`); a word written in full
//! is that word even where it begins another (`color` is View's `colors`,
//! `for` stays `for` beside `force`). The commands and parameters are
//! those of View's command reference (`view_commands.txt`, written by
//! `scripts/view_vocabulary.py`).

use std::sync::LazyLock;

/// Every View command, a line each: `words: parameters`.
const TABLE: &str = include_str!("view_commands.txt");

/// One place in the tree of command words: the words that can follow it,
/// and the parameters when the words so far are a whole command.
#[derive(Default)]
struct Node {
    words: Vec<(&'static str, usize)>,
    parameters: Option<Vec<&'static str>>,
}

/// The tree of View's command words, its root at index 0.
struct Vocabulary {
    nodes: Vec<Node>,
}

static VOCABULARY: LazyLock<Vocabulary> = LazyLock::new(|| {
    let mut nodes = vec![Node::default()];
    for line in TABLE.lines().filter(|line| !line.starts_with('#')) {
        let Some((words, parameters)) = line.split_once(':') else {
            continue;
        };
        let mut at = 0;
        for word in words.split_whitespace() {
            at = match nodes[at].words.iter().find(|(known, _)| *known == word) {
                Some(&(_, next)) => next,
                None => {
                    nodes.push(Node::default());
                    let next = nodes.len() - 1;
                    nodes[at].words.push((word, next));
                    next
                }
            };
        }
        nodes[at].parameters = Some(parameters.split_whitespace().collect());
    }
    Vocabulary { nodes }
});

/// What a written word or parameter stands for among the names that can
/// stand there.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Meaning {
    /// The name it is, or the one name it begins.
    One(&'static str),
    /// The names it begins, more than one: View would ask for more letters.
    Several(Vec<&'static str>),
    /// No name there is or begins with it.
    Unknown,
}

/// What `written` stands for among `names`: a name it is (in any case)
/// before the names it begins.
fn meaning<'n>(names: impl Iterator<Item = &'n &'static str> + Clone, written: &str) -> Meaning {
    if let Some(name) = names
        .clone()
        .find(|name| name.eq_ignore_ascii_case(written))
    {
        return Meaning::One(name);
    }
    let begun: Vec<&'static str> = names
        .filter(|name| {
            !written.is_empty()
                && name.len() > written.len()
                && name.as_bytes()[..written.len()].eq_ignore_ascii_case(written.as_bytes())
        })
        .copied()
        .collect();
    match begun.as_slice() {
        [] => Meaning::Unknown,
        [only] => Meaning::One(only),
        _ => Meaning::Several(begun),
    }
}

/// A whole View command found in the vocabulary: its parameters.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Command {
    node: usize,
}

impl Command {
    /// What the written parameter `written` stands for among the command's.
    pub(crate) fn parameter(self, written: &str) -> Meaning {
        let parameters = VOCABULARY.nodes[self.node]
            .parameters
            .as_deref()
            .unwrap_or_default();
        meaning(parameters.iter(), written)
    }
}

/// The word `written` stands for among those that can follow `node`: its
/// name and the node it leads to, or what it is instead.
fn next_word(node: usize, written: &str) -> Result<(&'static str, usize), Meaning> {
    let children = &VOCABULARY.nodes[node].words;
    match meaning(children.iter().map(|(name, _)| name), written) {
        Meaning::One(name) => Ok(*children
            .iter()
            .find(|(known, _)| *known == name)
            .expect("a name found among the children is one of them")),
        other => Err(other),
    }
}

/// The command words `written` stand for, in full and upper case, each as
/// far as each is one word's alone (the rest as written), and the command
/// when they all are and make a whole command.
pub(crate) fn command<S: AsRef<str>>(written: &[S]) -> (Vec<String>, Option<Command>) {
    let mut words = Vec::with_capacity(written.len());
    let mut at = Some(0);
    for word in written {
        let word = word.as_ref();
        match at.map(|node| next_word(node, word)) {
            Some(Ok((name, next))) => {
                words.push(name.to_ascii_uppercase());
                at = Some(next);
            }
            _ => {
                words.push(word.to_ascii_uppercase());
                at = None;
            }
        }
    }
    let command = at
        .filter(|&node| VOCABULARY.nodes[node].parameters.is_some())
        .map(|node| Command { node });
    (words, command)
}

/// Why a written command or parameter that the reading does not know may
/// not be what its writer meant: a word or parameter written short that
/// begins more than one of View's, named; `None` when none is.
pub(crate) fn ambiguity(command_name: &str, parameter: Option<&str>) -> Option<String> {
    let mut at = 0;
    for word in command_name.split_whitespace() {
        match next_word(at, word) {
            Ok((_, next)) => at = next,
            Err(Meaning::Several(names)) => {
                return Some(several(&word.to_ascii_lowercase(), "command word", &names));
            }
            Err(_) => return None,
        }
    }
    let parameter = parameter?;
    match (Command { node: at }).parameter(parameter) {
        Meaning::Several(names) => Some(several(
            &parameter.to_ascii_lowercase(),
            "parameter of this command",
            &names,
        )),
        _ => None,
    }
}

/// "writes `m`, which begins more than one parameter ... (mass, ...) ...".
fn several(written: &str, what: &str, names: &[&str]) -> String {
    format!(
        "writes `{written}`, which begins more than one {what} ({}), so View would not know which is meant: write more of it",
        names.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn expand(command_text: &str) -> String {
        let written: Vec<&str> = command_text.split_whitespace().collect();
        let (words, found) = command(&written);
        format!("{} {}", words.join(" "), found.is_some())
    }

    #[test]
    fn words_and_parameters_are_read_as_view_reads_them() {
        assert_eq!(
            expand("par cre rig name_and_pos"),
            "PART CREATE RIGID_BODY NAME_AND_POSITION true"
        );
        assert_eq!(expand("color create"), "COLORS CREATE true");
        assert_eq!(expand("default units"), "DEFAULTS UNITS true");
        assert_eq!(expand("my_macro run"), "MY_MACRO RUN false");
        // `fo` begins `for` and `force`; `for` is `for`.
        assert_eq!(expand("fo cre"), "FO CRE false");
        assert_eq!(expand("for"), "FOR true");
        let (_, units) = command(&["defaults", "units"]);
        let units = units.expect("a whole command");
        assert_eq!(units.parameter("LEN"), Meaning::One("length"));
        assert_eq!(units.parameter("length"), Meaning::One("length"));
        assert_eq!(units.parameter("weight"), Meaning::Unknown);
        assert!(matches!(units.parameter("f"), Meaning::Several(_)));
        assert!(ambiguity("DEFAULTS UNITS", Some("F")).is_some());
        assert!(ambiguity("DEFAULTS UNITS", Some("MASS")).is_none());
    }
}
