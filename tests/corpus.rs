//! The real corpus in `../shared/corpus` (third-party text: read in place,
//! never copied here): every expression checks, and the suspect ones that are
//! wrong in syntax or names are refused.

use std::path::PathBuf;

fn corpus_file(name: &str) -> Option<String> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/corpus")
        .join(name);
    match std::fs::read_to_string(&path) {
        Ok(text) => Some(text),
        Err(_) => {
            eprintln!("note: {} not found; corpus test skipped", path.display());
            None
        }
    }
}

/// The `expression` column of a corpus TSV (the last but `skip_last` columns).
fn expressions(text: &str, column: usize) -> Vec<String> {
    text.lines()
        .skip(1)
        .filter_map(|line| line.split('\t').nth(column).map(str::to_string))
        .collect()
}

/// `ok`, or the first error.
fn check(input: &str) -> String {
    match mbexpr::parse(input) {
        Err(error) => format!("syntax: {error}"),
        Ok(tree) => match mbexpr::check(&tree) {
            Ok(_) => "ok".to_string(),
            Err(errors) => format!("check: {}", errors[0]),
        },
    }
}

#[test]
fn every_corpus_expression_checks_cleanly() {
    let Some(text) = corpus_file("expressions.tsv") else {
        return;
    };
    let all = expressions(&text, 2);
    assert_eq!(all.len(), 702);
    let failures: Vec<String> = all
        .iter()
        .filter(|expression| check(expression) != "ok")
        .map(|expression| format!("{expression}: {}", check(expression)))
        .collect();
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn the_suspect_expressions_are_refused_or_explained() {
    let Some(text) = corpus_file("expressions_suspect.tsv") else {
        return;
    };
    let report: String = expressions(&text, 2)
        .iter()
        .map(|expression| format!("{expression}\n  => {}\n", check(expression)))
        .collect();
    insta::assert_snapshot!(report);
}
