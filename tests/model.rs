//! Model files: the reader rules, cross-references and loops, errors at their
//! line and column, the real models of the corpus, and robustness.

use mbexpr::model::{self, FileKind, Value};
use mbexpr::{Location, Span};
use proptest::prelude::*;

/// Every expression found (statement, keyword, joined text) and every
/// problem as `LINE:COL: message` with the line and a caret.
fn check(text: &str, kind: FileKind) -> String {
    let dataset = model::read(text, kind);
    let report = model::check_model(text, &dataset);
    let mut out = String::new();
    for found in &report.expressions {
        let statement = &dataset.statements[found.statement];
        out += &format!("{} {} = {}\n", statement.label(), found.keyword, found.text);
    }
    for problem in &report.problems {
        let span = problem.error.span();
        let at = Location::of(text, span.start);
        let line = text.lines().nth(at.line - 1).unwrap_or_default();
        out += &format!(
            "{at}: {}\n    {line}\n    {}{}\n",
            problem.error,
            " ".repeat(at.column - 1),
            "^".repeat(span.len().max(1))
        );
    }
    out + &format!(
        "{} statements, {} expressions, {} errors\n",
        dataset.statements.len(),
        report.expressions.len(),
        report.problems.len()
    )
}

const READER_RULES: &str = r"Title line: anything at all, even = and ,
! a comment line
UNITS/FORCE = NEWTON, MASS = KILOGRAM
PART/1, GROUND
PART/2, QG = 1, 2, 3, REULER = 270D, 90D, 180D ! comment after arguments
, VX = 0.5
MARKER/11, PART = 2, QP = 0, 0, 0
MARKER/12, PART = 1, FLOATING
MARKER/13
, PART = 1
, QP = 12, 0, 0
SFORCE/1, TRANSLATIONAL, I = 11, J = 13, FUNCTION = -1E4*(DM(11,13)-50)
,-10*VR(11,13)
SFORCE/2, TRANSLATIONAL, I = 11, J = 13
, FUNCTION =
, -STEP(TIME, 0, 0, 1, 10)
SFORCE/3, I = 11, J = 13, FUNC = IMPACT(DZ(11,13,13),
,VZ(11,13,13,13), 1.0, 100, 1.5, 25, 0.1)
SFORCE/4, I = 11, J = 13, FU = MOD(ATAN2(DX(11,13),
, DY(11,13))+2*PI,
, 2*PI)*RTOD\
, ROUTINE = none
GFORCE/1, I = 11, JFLOAT = 12, RM = 13, FX = 1\FY = 2\FZ = STEP(TIME,0,0,1,1)\
, TX = 0, TY = 0, TZ = 0
REQUEST/1, F2=ORIENT(27,1,11,13)\F3=DX(11)
, F8=JOINT(1,0,8,0),C=RForce
VARIABLE/1, FUNCTION = USER(1, 2, 3)\
, ROUTINE = lib::sub
VARIABLE/2, IC = 0.5, FUNCTION = VARVAL(1)*2;
ARRAY/1, NUMBERS = 1, 2, 3
JOINT/1, REVOLUTE, I = 11, J = 13
END
";

#[test]
fn reader_rules() {
    insta::assert_snapshot!(check(READER_RULES, FileKind::Adm));
}

#[test]
fn command_file_rules() {
    let acf = "file/model=pendulum\nVARIABLE/1, FUNC = IF(TIME-4.0: 0, 0, &\n -PI*IF(TIME-5: 1, 2, 3))\nsimulate/dynamic, end=10, steps=100\nDEACTIVATE/SFORCE, ID=3\nstop\n";
    insta::assert_snapshot!(check(acf, FileKind::Acf));
}

/// A command file's expressions read the statements of the dataset it
/// runs (adamspy's drill-string commands: `VARIABLE/1102, FUNCTION =
/// VARVAL(11021) * ...`, `-STEP5(SENVAL(2001), ...)`), which is not read
/// with it: an id the command file does not define is no error, as Adams
/// takes it; a loop among its own VARIABLEs still is.
#[test]
fn a_command_file_reads_the_statements_of_its_dataset() {
    let acf = "file/model=drill
VARIABLE/1102, FUNCTION = VARVAL(11021) * STEP(TIME, 0, 0, 15, 500) + DX(3, 1)
VARIABLE/1001, FUNC = -STEP5(SENVAL(2001), 2.0, 0, 4, 20*PI) + ARYVAL(5, 9)
VARIABLE/1, FUNCTION = VARVAL(2)
VARIABLE/2, FUNCTION = VARVAL(1)
simulate/dynamic, end = 1, steps = 10
";
    let report = check(acf, FileKind::Acf);
    assert!(!report.contains("not defined"), "{report}");
    assert!(
        report.ends_with("6 statements, 4 expressions, 1 errors\n")
            && report.contains("VARIABLE/1 depends on itself"),
        "{report}"
    );
}

#[test]
fn view_command_rules() {
    let cmd = r#"! Adams View command file
model create model_name = model_1
marker create marker_name = .model_1.PART_2.MARKER_1 adams_id = 1
force create direct single_component_force  &
   single_component_force_name = .model_1.SFORCE_1  &
   adams_id = 1  &
   type_of_freedom = translational  &
   i_marker_name = .model_1.PART_2.MARKER_1  &
   j_marker_name = .model_1.ground.MARKER_2  &
   function = "-1E4*(DM(.model_1.PART_2.MARKER_1, .model_1.ground.MARKER_2)",  &
              " - 50)/117.85",  &
              " + STEP(time, 0, 0, 1, .model_1.DV_1)"
force create direct general_force  &
   general_force_name = .model_1.GFORCE_1  &
   x_force_function = "0"  &
   y_force_function = "STPE(time, 0, 0, 1, 1)"  &
   location = (LOC_RELATIVE_TO({0, 0, 0}, .model_1.ground))
output_control create request request_name = .model_1.REQ_1 f1 = "DX(.model_1.PART_2.MARKER_1)" f2 = "IF(time, 1, 2, 3)"
"#;
    insta::assert_snapshot!(check(cmd, FileKind::Cmd));
}

#[test]
fn cross_references_and_loops() {
    let adm = r"cross references
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1
VARIABLE/1, FUNCTION = VARVAL(2) + DX(1, 2) + DX(1, 99)
VARIABLE/2, FUNCTION = VARVAL(3)
VARIABLE/3, FUNCTION = VARVAL(1)
VARIABLE/4, FUNCTION = VARVAL(4)
VARIABLE/5, FUNCTION = VARVAL(42) + ARYVAL(1, 4) + ARYVAL(1, 3) + ARYVAL(7, 1)
ARRAY/1, NUMBERS = 1, 2, 3
DIFF/1, IC = 0, FUNCTION = DIF(1) + DIF1(2)
SFORCE/1, I = 1, J = 2, FUNCTION = SFORCE(1, 0, 2, 0) + JOINT(3, 0, 2, 0) + FX(1, 2)
SFORCE/2, I = 1, J = 2, FUNCTION = STPE(TIME, 0, 0, 1, 1) + AKISPL(TIME, 0, 5)
PINPUT/1, VARIABLES = 1, 2
POUTPUT/1, VARIABLES = 3
VARIABLE/6, FUNCTION = PINVAL(1, 2) + PINVAL(1, 3) + POUVAL(1, 2) + POUVAL(2, 1)
";
    insta::assert_snapshot!(check(adm, FileKind::Adm));
}

#[test]
fn errors_inside_continued_expressions_point_at_their_line() {
    let adm = "errors\nPART/1, GROUND\nMARKER/1, PART = 1\nSFORCE/1, I = 1, J = 1, FUNCTION = 2*STEP(TIME,\n, 0, 0, 1, 1) + 3*STPE(TIME,\n,0,0,1,1)\n, + BISTOP(DX(1), VX(1), 5, -5,\n, 1e5, 2.2, 100, 0.1) + (1\nthis is not a statement\nVARIABLE/1, FUNCTION = 1.0D3\n";
    insta::assert_snapshot!(check(adm, FileKind::Adm));
}

/// A dataset without its title line: its first statement is read as the
/// title (Adams' rule), and a continuation of it says so, where it was "not
/// a statement"; a title that only looks like a statement, or a
/// continuation after a statement, is as before.
#[test]
fn a_continuation_of_the_title_says_the_first_line_is_the_title() {
    let cases = [
        "PART/1, GROUND\n, DENSITY = 1\nMARKER/1, PART = 1\nEND\n",
        "part/ 12 , mass = 1\n! a comment\n, CM = 3\nEND\n",
        "PART/1 of a test\n, DENSITY = 1\nEND\n",
        "title\nPART/1, GROUND\n, DENSITY = 1\nEND\n",
        "title\n, DENSITY = 1\nEND\n",
    ];
    let table: String = cases
        .iter()
        .map(|text| format!("{text:?}\n{}\n", check(text, FileKind::Adm)))
        .collect();
    insta::assert_snapshot!(table);
}

#[test]
fn numbers_in_messages_are_short() {
    let adm = "numbers\nPART/1, GROUND\nMARKER/1, PART = 1\nSFORCE/1, I = 1, J = 1, FUNCTION = IMPACT(DX(1), VX(1), 0, 1E300, 1.5, 10, -1E-300)\n";
    insta::assert_snapshot!(check(adm, FileKind::Adm));
}

/// The real models in `../shared/corpus/models` (read in place, never copied).
fn corpus_models() -> Vec<(String, String)> {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/corpus/models");
    let Ok(entries) = std::fs::read_dir(&folder) else {
        crate::corpus::missing(&folder);
        return Vec::new();
    };
    let mut models: Vec<(String, String)> = entries
        .filter_map(Result::ok)
        .map(|entry| entry.path())
        .filter(|path| path.extension().is_some_and(|extension| extension == "adm"))
        .map(|path| {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            (name, std::fs::read_to_string(&path).unwrap())
        })
        .collect();
    models.sort();
    models
}

/// Expression arguments counted the simple way: `KEY =` at a line start, after
/// a comma or a `\`, outside comments.
fn expression_keys(text: &str) -> usize {
    let keys = [
        "FUNCTION",
        "FUNC",
        "FU",
        "FX",
        "FY",
        "FZ",
        "TX",
        "TY",
        "TZ",
        "CRATIO",
        "EVALUATE",
        "SAMPLE_PERIOD",
        "SAMPLE_OFFSET",
    ];
    text.lines()
        .filter(|line| !line.trim_start().starts_with('!'))
        .map(|line| {
            let upper = line.to_uppercase();
            upper
                .split([',', '\\', ';'])
                .filter(|piece| {
                    let piece = piece.trim();
                    let Some((key, _)) = piece.split_once('=') else {
                        return false;
                    };
                    let key = key.trim();
                    keys.contains(&key)
                        || (key.len() == 2
                            && key.starts_with('F')
                            && key.as_bytes()[1].is_ascii_digit())
                })
                .count()
        })
        .sum()
}

#[test]
fn the_real_models_check_cleanly_and_every_expression_is_found() {
    for (name, text) in corpus_models() {
        let dataset = model::read(&text, FileKind::Adm);
        let report = model::check_model(&text, &dataset);
        let problems: Vec<String> = report
            .problems
            .iter()
            .map(|problem| {
                format!(
                    "{}: {}",
                    Location::of(&text, problem.error.span().start),
                    problem.error
                )
            })
            .collect();
        assert!(problems.is_empty(), "{name}: {problems:#?}");
        assert_eq!(report.expressions.len(), expression_keys(&text), "{name}");
        assert!(
            report
                .expressions
                .iter()
                .all(|found| found.checked.is_some())
        );
    }
}

#[test]
fn joined_expressions_map_back_to_the_file() {
    let dataset = model::read(READER_RULES, FileKind::Adm);
    for statement in &dataset.statements {
        for (_, embedded) in statement.expressions() {
            // Every character of the joined text is the character at its place in the file.
            for (offset, character) in embedded.text.char_indices() {
                let at = embedded.file_offset(offset);
                assert_eq!(
                    READER_RULES[at..].chars().next(),
                    Some(character),
                    "{}",
                    embedded.text
                );
            }
        }
    }
    let values: Vec<f64> = dataset
        .statements
        .iter()
        .find(|statement| statement.label() == "PART/2")
        .unwrap()
        .argument("REULER", 2)
        .map(|argument| match &argument.value {
            Value::List(items) => items.iter().filter_map(|item| item.number()).collect(),
            _ => Vec::new(),
        })
        .unwrap();
    assert_eq!(
        values,
        [270f64.to_radians(), 90f64.to_radians(), 180f64.to_radians()]
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Truncating or mangling a dataset anywhere never panics, and every
    /// problem points at a real place in the text.
    #[test]
    fn mangled_datasets_never_panic(cut in 0usize..2000, at in 0usize..2000, junk in "[ -~\n]{0,8}") {
        let mut text = READER_RULES.to_string();
        let cut = cut.min(text.len());
        text.truncate(cut.max(1));
        let at = at.min(text.len());
        text.insert_str(at, &junk);
        for kind in [FileKind::Adm, FileKind::Acf, FileKind::Cmd] {
            let dataset = model::read(&text, kind);
            let report = model::check_model(&text, &dataset);
            for problem in &report.problems {
                let span: Span = problem.error.span();
                prop_assert!(span.start <= span.end && span.end <= text.len(), "{span:?} in {} bytes", text.len());
                prop_assert!(text.is_char_boundary(span.start));
            }
        }
    }
}

#[test]
fn brackets_nested_past_the_limit_are_refused_and_at_it_read() {
    let limit = mbexpr::syntax::MAX_NESTING;
    let nested = |depth: usize| format!("{}1{}", "(".repeat(depth), ")".repeat(depth));
    // Run where the stack is smallest: a test thread has 2 MiB.
    for (text, kind) in [
        (
            format!(
                "deep\nPART/1, GROUND\nVARIABLE/1, FUNCTION = {}\n",
                nested(limit - 1)
            ),
            FileKind::Adm,
        ),
        (
            format!(
                "variable create variable_name = .m.v &\n  function = \"1\" &\n  comments = {}\n",
                nested(limit - 1)
            ),
            FileKind::Cmd,
        ),
    ] {
        let dataset = model::read(&text, kind);
        assert!(
            dataset.problems.is_empty(),
            "{kind:?}: {:?}",
            dataset.problems
        );
        assert_eq!(
            model::check_model(&text, &dataset).problems.len(),
            0,
            "{kind:?}"
        );
    }
    let deep = format!(
        "deep\nPART/1, GROUND\n! (((\nVARIABLE/1, FUNCTION = 2*{}\n",
        nested(100_000)
    );
    let report = check(&deep, FileKind::Adm);
    assert!(report.starts_with("4:"), "{}", &report[..80]);
    assert!(report.contains("brackets nest deeper than 500 levels here"));
    let cmd = format!(
        "part create part_name = .m.p location = {}\n",
        nested(100_000)
    );
    assert!(
        model::read(&cmd, FileKind::Cmd).problems[0]
            .to_string()
            .contains("nest deeper")
    );
}

/// What the solver would refuse is an error at its place (issues 18.5,
/// 19.4, 19.5): a bare name a dataset does not know, a misspelled keyword
/// (its expression is not read), an unknown statement, an id given twice
/// (at both places), and a missing marker beside a broken argument rule.
#[test]
fn names_keywords_statements_and_duplicate_ids() {
    let adm = r"names and words
PART/1, GROUND
MARKER/1, PART = 1
MARKR/3, PART = 1
VARIABLE/4, FUNCTION = TIEM*2 + time + Pi + mode*x
VARIABLE/5, FUNCTON = STPE(TIME, 0, 0, 1, 1)
VARI/7, FUNCTION = 1
VARIABLE/7, FUNC = 2
SFORCE/1, I = 1, J = 1, FUNCTION = STEP(DX(1, 9), 1, 0, 0, 1)
SFORCE/2, I = 1, J = 1, FUNCTION = LOG(0) + DM(1, 8)
SFORCE/3, I = 1, J = 1, FUNCTION = VARVAL(7)
";
    insta::assert_snapshot!(check(adm, FileKind::Adm));
    let acf =
        "model\nresults\nsimulate/dynamic, end = 1, steps = 10\nsimulat/static\nbogus/1\nstop\n";
    insta::assert_snapshot!(check(acf, FileKind::Acf));
}

/// A keyword given twice in a statement (abbreviated or not; a 3-D
/// SPLINE's Y lists repeat), a second ground part, a number beyond a
/// double's range in any statement's data and a statement named where a
/// solver dataset wants its id are errors at their place.
#[test]
fn keywords_twice_second_grounds_and_overflowing_numbers() {
    let adm = r"twice
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1
PART/5, GROUND
PART/6, MASS = 1, CM = 7, IP = 1, 1, 1, MASS = 2
MARKER/7, PART = 6
REQUEST/1, F2 = TIME
, F2 = 2*TIME
VARIABLE/1, FUNC = 1, FUNCTION = 2
VARIABLE/2, IC = 1e309, FUNCTION = 1
SPLINE/1, X = 1, 2, 3, 4, Y = 0, 1, 2, 3, 4, Y = 1, 2, 3, 4, 5
SPRINGDAMPER/1, TRANSLATION, I = 7, J = 1, K = 1, C = 1, LENGTH = 1
DIFF/1, IC = 0, FUNCTION = DIF(FOO) + DX(BAR, 1)
";
    insta::assert_snapshot!(check(adm, FileKind::Adm));
}

/// A command file's keyword given twice (the run would read the first) and
/// a dataset's statements after its END (which ends it: Adams reads none
/// of them) are errors at their place; comments after END are not.
#[test]
fn command_keywords_twice_and_statements_after_end() {
    let acf = "model\nresults\nsimulate/dynamic, end = 1, END = 2, steps = 10, steps = 20\nstop\n";
    insta::assert_snapshot!(check(acf, FileKind::Acf));
    let adm = "after end\nDIFF/1, IC = 0, FUNCTION = 1\nEND\n! a note\nDIFF/2, IC = 0, FUNCTION = 2\nEND\n";
    insta::assert_snapshot!(check(adm, FileKind::Adm));
    let clean = "clean\nDIFF/1, IC = 0, FUNCTION = 1\nEND\n! notes after END are comments\n";
    insta::assert_snapshot!(check(clean, FileKind::Adm));
}

/// What `eval --model` and the simulator refuse in the statements' data is
/// an error of `check` too, at its statement.
#[test]
fn statement_data_that_makes_no_configuration() {
    let adm = r"configuration
PART/1, GROUND
PART/2, MASS = 1, CM = 3, IP = 1, 1, 1, QG = 1, 2
MARKER/3, PART = 2
MARKER/4, PART = 7
MARKER/5, PART = 1, QP = 1, 2
SPLINE/1, X = 1, 2, Y = 1, 2
DIFF/1, IC = 1e400
MARKER/6, PART = 1, QP = 0, -inf, 0
ARRAY/2, NUMBERS = 1, 2
VARIABLE/3, FUNCTION = ARYVAL(2, 1.5) + ARYVAL(1e30, 1) + ARYVAL(2, 3)
DIFF/123456789012345678901, IC = 1
PART/17, MASS = abc, CM = 18
MARKER/18, PART = 17
MARKER/9007199254740993, PART = 1
XXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXX/1
";
    insta::assert_snapshot!(check(adm, FileKind::Adm));
}

/// A long chain of VARIABLEs and a loop inside a larger group: each loop
/// once, from its smallest id (issue 19.2: the search is linear).
#[test]
fn loops_in_chains() {
    let mut adm = String::from("chains\n");
    for id in 1..=2000 {
        adm += &format!("VARIABLE/{id}, FUNCTION = VARVAL({})\n", id + 1);
    }
    adm += "VARIABLE/2001, FUNCTION = TIME\n";
    adm += "VARIABLE/3001, FUNCTION = VARVAL(3002) + VARVAL(3003)\nVARIABLE/3002, FUNCTION = VARVAL(3003)\nVARIABLE/3003, FUNCTION = VARVAL(3001)\n";
    let report = check(&adm, FileKind::Adm);
    let errors: Vec<&str> = report
        .lines()
        .filter(|line| line.contains(": VARIABLE"))
        .collect();
    insta::assert_snapshot!(errors.join("\n"));
}

/// A file far larger than the readers' pieces (64 KiB) reads as the same
/// statements, whatever continuation crosses where a piece could end: `,`
/// lines after comment lines, and `&` at a line's end (issue 19.3: pest's
/// tokens are those of one piece at a time).
#[test]
fn large_files_read_in_pieces_as_whole() {
    let mut adm = String::from("pieces\n");
    let mut acf = String::new();
    let mut cmd = String::new();
    for id in 1..=3000 {
        adm += &format!(
            "VARIABLE/{id}, FUNCTION = STEP(TIME, 0, 0,\n! a comment between\n\n, 1, {id})\n"
        );
        acf += &format!("VARIABLE/{id}, FUNCTION = STEP(TIME, 0, 0, &\n! note\n 1, {id})\n");
        cmd += &format!(
            "data_element create variable &\n   variable_name = .m.V{id} &\n   function = \"STEP(time, 0, 0,\", &\n   \" 1, {id})\"\n"
        );
    }
    for (text, kind, time) in [
        (&adm, FileKind::Adm, "TIME"),
        (&acf, FileKind::Acf, "TIME"),
        (&cmd, FileKind::Cmd, "time"),
    ] {
        let dataset = model::read(text, kind);
        assert!(
            dataset.problems.is_empty(),
            "{kind:?}: {:?}",
            dataset.problems.first()
        );
        assert_eq!(dataset.statements.len(), 3000, "{kind:?}");
        let report = model::check_model(text, &dataset);
        for (index, found) in report.expressions.iter().enumerate() {
            let joined = found.text.split_whitespace().collect::<Vec<_>>().join(" ");
            assert_eq!(
                joined,
                format!("STEP({time}, 0, 0, 1, {})", index + 1),
                "{kind:?}"
            );
        }
    }
}

/// A run of blanks is read whole: before, every blank of a run inside an
/// expression or a value looked past the rest of it for a separator, so
/// 100 000 blanks took minutes.
#[test]
fn long_runs_of_blanks_read_as_one() {
    let blanks = " ".repeat(200_000);
    let adm = format!(
        "blanks\nMARKER/1, QP = 1{blanks}, 2, 3\nVARIABLE/2, FUNCTION = 1 +{blanks}2{blanks}\n, + (3{blanks}+ 4)\n"
    );
    let dataset = model::read(&adm, FileKind::Adm);
    assert!(
        dataset.problems.is_empty(),
        "{:?}",
        dataset.problems.first()
    );
    assert_eq!(dataset.statements.len(), 2);
    let report = model::check_model(&adm, &dataset);
    let found = &report.expressions[0];
    let joined = found.text.split_whitespace().collect::<Vec<_>>().join(" ");
    assert_eq!(joined, "1 + 2 + (3 + 4)");
}

/// A VARIABLE read twice is compiled once (issue 19.2): sixty VARIABLEs,
/// each reading the one before twice, would be 2^59 walks otherwise.
#[test]
fn a_variable_read_twice_is_compiled_once() {
    let mut adm = String::from("doubling\nVARIABLE/1, FUNCTION = TIME\n");
    for id in 2..=60 {
        adm += &format!(
            "VARIABLE/{id}, FUNCTION = VARVAL({0}) + VARVAL({0})\n",
            id - 1
        );
    }
    let dataset = model::read(&adm, FileKind::Adm);
    let report = model::check_model(&adm, &dataset);
    let scene = model::initial_scene(&dataset, &report).unwrap();
    let last = report.expressions.last().unwrap().checked.as_ref().unwrap();
    let program = mbexpr::compile_in_scene(last, &["TIME"], &scene).unwrap();
    assert_eq!(program.len(), 59);
    assert_eq!(program.value(&[1.0]).unwrap(), 2f64.powi(59));
}

/// The bytes of a file as text (issue 18.4, docs/encoding.md): UTF-8 as
/// it is, a byte-order mark's encoding, else Windows-1252.
#[test]
fn files_that_are_not_utf8_are_read() {
    let cases: [(&str, &[u8]); 5] = [
        ("UTF-8", "PART/1 ! réglage °C".as_bytes()),
        ("Windows-1252", b"PART/1 ! r\xe9glage \xb0C \x92"),
        ("UTF-8 with a mark", b"\xef\xbb\xbfPART/1"),
        ("UTF-16LE with a mark", b"\xff\xfeP\0A\0R\0T\0"),
        ("UTF-8 cut in a character", b"PART/1 ! caf\xc3"),
    ];
    let report: String = cases
        .iter()
        .map(|(label, bytes)| {
            let (text, encoding) = model::decode_owned(bytes.to_vec());
            format!("{label}: {encoding} {text:?}\n")
        })
        .collect();
    insta::assert_snapshot!(report);
}

/// The vocabulary errors (unknown statements and keywords) of a dataset.
fn vocabulary_errors(adm: &str) -> Vec<String> {
    let dataset = model::read(adm, FileKind::Adm);
    model::check_model(adm, &dataset)
        .problems
        .iter()
        .map(|problem| problem.error.to_string())
        .filter(|message| {
            message.contains("is not a keyword") || message.contains("not a statement")
        })
        .collect()
}

/// Every statement of the reference, with each of its keywords (one line a
/// statement, every keyword given a value), is read without a word of
/// vocabulary refused: the vocabulary is the solver's, not the corpus's
/// (issue 27.1).
#[test]
fn every_statement_takes_each_of_its_keywords() {
    // The statements of the Adams Solver reference (TITLE is the dataset's
    // first line, taken whole): each is a statement of the vocabulary.
    const REFERENCE: &str = "ACCGRAV ARRAY BEAM BUSHING CLEARANCE CONTACT COUPLER CURVE CVCV DEBUG DIFF END ENVIRONMENT EQUILIBRIUM FEMDATA FIELD FLEX_BODY FRICTION GCON GEAR GFORCE GRAPHICS GSE IC INTEGRATOR JOINT JPRIM KINEMATICS LIST LSE LSOLVER MARKER MATRIX MFORCE MOTION NFORCE NOLIST OUTPUT PART PINPUT POINT_MASS POUTPUT PREFERENCES PTCV REQUEST RESULTS SENSOR SFORCE SPLINE SPRINGDAMPER STRING SURFACE TFSISO UCON UNITS VARIABLE VFORCE VTORQUE";
    for name in REFERENCE.split(' ') {
        assert!(
            model::vocabulary::STATEMENTS
                .iter()
                .any(|(known, _)| *known == name),
            "{name} is not in the vocabulary"
        );
        let adm = format!("reference\n{name}/1\n");
        assert_eq!(vocabulary_errors(&adm), Vec::<String>::new(), "{name}");
    }
    for (name, keywords) in model::vocabulary::STATEMENTS {
        let Some(keywords) = keywords else { continue };
        let mut adm = format!("every keyword of {name}\n{name}/1");
        for keyword in *keywords {
            adm += &format!("\n, {keyword} = 1");
        }
        assert_eq!(
            vocabulary_errors(&(adm + "\n")),
            Vec::<String>::new(),
            "{name}"
        );
    }
}

/// What Adams View writes is read without a false error, abbreviations
/// included; a keyword of another statement, or none at all, is refused
/// with the close names of its own statement (issue 27.1).
#[test]
fn statements_as_adams_view_writes_them() {
    insta::assert_snapshot!(crate::table(
        r"
        JOINT/03, RACKPIN, I = 1, J = 2, PD = 0.1
        JOINT/4, SCREW, I = 1, J = 2, PITCH = 0.01
        JOINT/5, CONVEL, I = 1, J = 2, IC = 0, 0
        GRAPHICS/204, SPDP, I = 1, J = 2, COILS = 8, DA = 1, DB = 2, DC = 3, LA = 1, LB = 1, LC = 4, LD = 4
        GRAPHICS/205, OUTLINE = 1, 2, 3
        GRAPHICS/206, FORCE, ETYPE = SFORCE, EID = 1, EMARKER = 2
        CONTACT/1, TYPE = SOLID_TO_SOLID, IGEOM = 1, JGEOM = 2, POISSON, PENALTY = 1E5, RESTITUTION_COEFFICIENT = 0.5
        FRICTION/1, JOINT = 3, MU_STATIC = 0.3, MU_DYNAMIC = 0.2, PIN_RADIUS = 1, BALL_RADIUS = 1
        JOINT/7, REVOLUTE, I = 1, J = 2, DELTA_V = 0.01, MAXIMUM_DEFORMATION = 0.01, MU_DYN_ROT = 0.3, MU_STAT_ROT = 0.4, MAX_FRIC_ROT = 0, PRELOAD_RADIAL = 0, PRELOAD_AXIAL = 0, INNER_RADIUS = 1, OUTER_RADIUS = 1.1
        JOINT/8, TRANSLATIONAL, I = 1, J = 2, FRICTION = ON, MU_DYN_TRANS = 0.2, MU_STAT_TRANS = 0.3, MAX_FRIC_TRANS = 0, HEIGHT = 1, WIDTH = 1, PRELOAD_X = 0, PRELOAD_Y = 0
        GSE/990, NS = 0, NO = 1, U = 991, Y = 992, SAMPLE_PERIOD = 1.0\, FUNCTION = USER(0)\, INTERFACE = lib::gse_deriv, lib::gse_output
        MARK/1, PAR = 1, QP = 0, 0, 0
        SFOR/1, TRANS, I = 1, J = 2, FUNC = 1
        REQUEST/1, F2 = 1, C = comment
        MARKER/1, PD = 0.1
        JOINT/6, RACKPINE, I = 1, J = 2
        SFORCE/2, I = 1, J = 2, FUNCTON = 1
        MATERIAL/1, ANYTHING = 1
        ",
        |line| {
            let errors = vocabulary_errors(&format!("view\n{line}\n"));
            if errors.is_empty() {
                "read".to_string()
            } else {
                errors.join("; ")
            }
        }
    ));
}
