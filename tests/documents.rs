//! The documents say what the program does: the function reference of
//! `docs/language.md` is the catalog's (written by `mbexpr::help`), and
//! every `$ mbexpr ...` session printed in the README is what the binary
//! prints (issue 27, items 11 and 14). `MBEXPR_UPDATE_DOCS=1 cargo test
//! documents::` rewrites both from the program.

use std::path::{Path, PathBuf};
use std::process::Command;

use mbexpr::catalog::Function;

const BEGIN: &str = "<!-- functions: generated from src/catalog.rs";
const END: &str = "<!-- end of functions -->";

fn file(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// Compares `text` with the file at `path`; when they differ, rewrites the
/// file under `MBEXPR_UPDATE_DOCS`, else fails saying how to.
fn same_or_update(path: &Path, text: &str) {
    let written = std::fs::read_to_string(path).unwrap();
    if written == text {
        return;
    }
    if std::env::var_os("MBEXPR_UPDATE_DOCS").is_some() {
        std::fs::write(path, text).unwrap();
        return;
    }
    let line = written
        .lines()
        .zip(text.lines())
        .position(|(old, new)| old != new)
        .unwrap_or_else(|| written.lines().count().min(text.lines().count()));
    panic!(
        "{} differs from what the program says, from line {}:\n  written: {:?}\n  program: {:?}\n(MBEXPR_UPDATE_DOCS=1 cargo test documents:: rewrites it)",
        path.display(),
        line + 1,
        written.lines().nth(line).unwrap_or_default(),
        text.lines().nth(line).unwrap_or_default()
    );
}

#[test]
fn the_language_reference_is_the_catalogs() {
    let path = file("docs/language.md");
    let page = std::fs::read_to_string(&path).unwrap();
    let begin = page
        .find(BEGIN)
        .expect("docs/language.md marks its generated part");
    let begin = begin + page[begin..].find('\n').unwrap() + 1;
    let end = page
        .find(END)
        .expect("docs/language.md marks the end of its generated part");
    let reference = mbexpr::help::functions_reference();
    let text = format!("{}{reference}{}", &page[..begin], &page[end..]);
    same_or_update(&path, &text);
    for function in Function::ALL {
        let heading = format!("#### `{}(", function.name());
        assert!(
            text.contains(&heading),
            "{} is not documented",
            function.name()
        );
        assert!(mbexpr::help::topic(function.name()).is_some());
    }
    let readme = std::fs::read_to_string(file("README.md")).unwrap();
    assert!(
        readme.contains("(docs/language.md)"),
        "the README links the reference"
    );
}

/// The words of a command line: blanks separate them, double quotes hold
/// blanks in one word.
fn words(line: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word: Option<String> = None;
    let mut quoted = false;
    for character in line.chars() {
        match character {
            '"' => {
                quoted = !quoted;
                word.get_or_insert_with(String::new);
            }
            ' ' if !quoted => words.extend(word.take()),
            _ => word.get_or_insert_with(String::new).push(character),
        }
    }
    words.extend(word);
    words
}

/// What `mbexpr ARGS` prints (standard output, then standard error).
fn session(line: &str) -> String {
    let args = words(line);
    let output = Command::new(env!("CARGO_BIN_EXE_mbexpr"))
        .args(&args[1..])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    String::from_utf8_lossy(&output.stdout).into_owned() + &String::from_utf8_lossy(&output.stderr)
}

/// Every ```` ```text ```` block of `markdown` that starts with `$ mbexpr`,
/// with each command's output as the program prints it now.
fn with_sessions(markdown: &str) -> String {
    let mut text = String::new();
    let mut lines = markdown.lines().peekable();
    while let Some(line) = lines.next() {
        text += line;
        text.push('\n');
        if line.trim() != "```text"
            || !lines
                .peek()
                .is_some_and(|next| next.starts_with("$ mbexpr"))
        {
            continue;
        }
        // The block's commands; their outputs are written anew.
        for line in lines.by_ref() {
            if line.trim() == "```" {
                text += "```\n";
                break;
            }
            if let Some(command) = line.strip_prefix("$ ") {
                text += &format!("{line}\n{}", session(command));
            }
        }
    }
    text
}

#[test]
fn the_readmes_sessions_are_what_the_program_prints() {
    let path = file("README.md");
    let markdown = std::fs::read_to_string(&path).unwrap();
    assert!(
        markdown.contains("```text\n$ mbexpr"),
        "the README shows sessions"
    );
    same_or_update(&path, &with_sessions(&markdown));
}
