//! A dataset written as the text of a solver dataset (`.adm`): what mbexpr
//! made of an Adams View command file, as View's File > Export > Adams
//! Solver Dataset would write it.

use super::{Dataset, Statement, Value};

impl Dataset {
    /// The dataset as solver-dataset text: its title line, one statement
    /// after another (each argument on a line of its own, a function
    /// expression last on its line and continued with `\` where a request
    /// lists several), and `END`.
    pub fn to_text(&self) -> String {
        let mut text = String::new();
        text.push_str(self.title.as_deref().unwrap_or("mbexpr"));
        text.push('\n');
        for statement in &self.statements {
            write_statement(&mut text, statement);
        }
        text.push_str("END\n");
        text
    }
}

fn write_statement(text: &mut String, statement: &Statement) {
    text.push_str(&statement.name);
    match statement.id {
        Some(id) => text.push_str(&format!("/{id}\n")),
        None => text.push_str("/\n"),
    }
    // Values first, expressions after them (an expression runs to the end
    // of its line, or to a backslash where another follows).
    let expressions = statement
        .arguments
        .iter()
        .filter(|argument| matches!(argument.value, Value::Expression { .. }))
        .count();
    let mut written = 0;
    for argument in &statement.arguments {
        match &argument.value {
            Value::Flag => text.push_str(&format!(", {}\n", argument.keyword)),
            Value::List(items) => {
                let items: Vec<&str> = items.iter().map(|item| item.text.as_str()).collect();
                text.push_str(&format!(", {} = {}\n", argument.keyword, items.join(", ")));
            }
            Value::Expression { .. } => {}
        }
    }
    for argument in &statement.arguments {
        if let Value::Expression { text: function, .. } = &argument.value {
            written += 1;
            let more = if written < expressions { "\\" } else { "" };
            let function = function
                .text
                .split_whitespace()
                .collect::<Vec<_>>()
                .join(" ");
            text.push_str(&format!(", {} = {function}{more}\n", argument.keyword));
        }
    }
}
