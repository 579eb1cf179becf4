//! Places in a text: the line index gives each offset's line and column
//! (columns in characters) after one pass over the text (issue 19.1).

use mbexpr::LineIndex;

/// `LINE:COL` of the offset marked `|` in `case` (`\n` and `\r` written as
/// escapes), by the index, and the line it is on.
fn check(case: &str) -> String {
    let case = case.replace("\\n", "\n").replace("\\r", "\r");
    let offset = case.find('|').expect("a marked offset");
    let text = case.replacen('|', "", 1);
    let index = LineIndex::new(&text);
    let at = index.location(offset);
    format!("{at} {:?}", index.line(at.line))
}

#[test]
fn lines_and_columns() {
    insta::assert_snapshot!(crate::table(
        r"
        |abc
        ab|c
        abc|
        abc\n|def
        abc\nd|ef\nghi
        abc\r\nde|f
        abc\n\n|\n
        é|x
        ab\n°°|x
        ’’’\n’|’’\n
        \n\n\n|
        ",
        check
    ));
}

#[test]
fn offsets_inside_a_character_or_past_the_end_are_clamped() {
    let text = "aé\nb";
    let index = LineIndex::new(text);
    assert_eq!(index.location(2).to_string(), "1:2"); // inside `é`
    assert_eq!(index.location(99).to_string(), "2:2");
    assert_eq!(index.line(3), "");
    assert_eq!(index.line(0), "");
}
