//! The real corpus in `../shared/corpus` (third-party text: read in place,
//! never copied here): every expression checks, and the suspect ones that are
//! wrong in syntax or names are refused.

use std::io::Write;
use std::path::{Path, PathBuf};

/// `../shared/corpus/NAME`, when it is there.
pub(crate) fn corpus_path(name: &str) -> Option<PathBuf> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/corpus")
        .join(name);
    if path.exists() {
        Some(path)
    } else {
        missing(&path);
        None
    }
}

/// Says that `path` is missing where the run shows it (standard error
/// written directly, which the test harness does not capture), and fails
/// the test when `MBEXPR_REQUIRE_CORPUS` is set, as `.ci/run` sets it: there
/// the corpus must be present.
pub(crate) fn missing(path: &Path) {
    let message = format!("{} not found; corpus test skipped", path.display());
    if std::env::var_os("MBEXPR_REQUIRE_CORPUS").is_some() {
        panic!("{message}, and MBEXPR_REQUIRE_CORPUS is set");
    }
    let _ = writeln!(std::io::stderr(), "note: {message}");
}

fn corpus_file(name: &str) -> Option<String> {
    let path = corpus_path(name)?;
    Some(
        std::fs::read_to_string(&path)
            .unwrap_or_else(|error| panic!("{}: {error}", path.display())),
    )
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
