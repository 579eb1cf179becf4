//! The built binary, driven as a user would: arguments, piped input, exit codes.

use std::io::Write;
use std::process::{Command, Stdio};

/// Runs `mbexpr args...` with `stdin`, returning stdout, stderr and the exit code.
pub(crate) fn mbexpr(args: &[&str], stdin: &str) -> (String, String, i32) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_mbexpr"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    // A run that ends before reading its input (a usage error) closes the
    // pipe: that is not the test's failure.
    let _ = child
        .stdin
        .take()
        .expect("piped")
        .write_all(stdin.as_bytes());
    let output = child.wait_with_output().expect("the binary ends");
    (
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
        output.status.code().unwrap_or(-1),
    )
}

/// `$ mbexpr args` then what it printed and its exit code.
pub(crate) fn check(args: &[&str], stdin: &str) -> String {
    let (stdout, stderr, code) = mbexpr(args, stdin);
    format!(
        "$ mbexpr {}\n{stdout}{stderr}[exit {code}]\n",
        args.join(" ")
    )
}

const EXPRESSIONS: &str = "STEP(TIME, 0, 0, 1, 10)
! a comment line

BISTOP(DX(2,1,1), VX(2,1,1,1), -5, 5, 1e5, 2.2, 100, 0.1)
2*STPE(TIME, 0, 0, 1, 1)
IF(TIME-1, 0, 0, 1)
BISTOP(x, v, 5, -5, 1e5, 2.2, 100, 0)
x^2 + (y
";

#[test]
fn check_reports_every_error_with_its_place() {
    insta::assert_snapshot!(
        check(&["check", "-"], EXPRESSIONS)
            + &check(&["check", "--format", "jsonl", "-"], EXPRESSIONS)
    );
}

#[test]
fn check_exit_codes() {
    assert_eq!(mbexpr(&["check", "-"], "STEP(TIME,0,0,1,1)\n").2, 0);
    assert_eq!(mbexpr(&["check", "-"], "STPE(TIME,0,0,1,1)\n").2, 1);
    assert_eq!(mbexpr(&["check", "/no/such/file"], "").2, 2);
    assert_eq!(mbexpr(&["check"], "").2, 2);
    assert_eq!(mbexpr(&["check", "--format", "yaml", "-"], "").2, 2);
}

#[test]
fn parse_prints_the_tree() {
    insta::assert_snapshot!(
        check(&["parse", "-2**2 + step(time, 0, 0, 1, 90D)"], "") + &check(&["parse", "1.0D3"], "")
    );
}

#[test]
fn eval_prints_value_gradient_and_hessian() {
    let bistop = "BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1)";
    insta::assert_snapshot!(
        check(&["eval", bistop, "--set", "x=10.05", "--set", "v=0.7"], "")
            + &check(
                &[
                    "eval", bistop, "--set", "X=10.05", "--set", "v=0.7", "--wrt", "x,v"
                ],
                ""
            )
            + &check(
                &[
                    "eval", bistop, "--set", "x=10.05", "--set", "v=0.7", "--wrt", "x,v",
                    "--order", "2"
                ],
                ""
            )
            + &check(
                &[
                    "eval", bistop, "--set", "x=10.05", "--set", "v=0.7", "--wrt", "x,v",
                    "--order", "2", "--format", "json"
                ],
                ""
            )
            + &check(
                &[
                    "eval", bistop, "--set", "x=10.05", "--set", "v=0.7", "--wrt", "v", "--format",
                    "jsonl"
                ],
                ""
            )
            + &check(
                &[
                    "eval",
                    "STEP(TIME, 0, 0, 1, 10)",
                    "--set",
                    "time=0.5",
                    "--wrt",
                    "TIME"
                ],
                ""
            )
    );
}

#[test]
fn eval_errors() {
    let bistop = "BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1)";
    insta::assert_snapshot!(
        check(&["eval", bistop, "--set", "x=1"], "")
            + &check(
                &["eval", bistop, "--set", "x=1", "--set", "v=1", "--wrt", "y"],
                ""
            )
            + &check(&["eval", bistop, "--set", "x=one"], "")
            + &check(&["eval", "LOG(x)", "--set", "x=0"], "")
            + &check(&["eval", "STPE(x)", "--set", "x=0"], "")
            + &check(&["eval", "x", "--order", "3"], "")
    );
}

#[test]
fn eval_points_gives_one_line_per_row_and_goes_on_after_errors() {
    let dir = std::env::temp_dir().join(format!("mbexpr-points-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("points.csv");
    std::fs::write(&csv, "x,v\n10.05,0.7\n0,1\nbad,1\n-10.5,2\n1,2,3\n").unwrap();
    let path = csv.to_str().unwrap();
    let bistop = "BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1)";
    let report = check(
        &[
            "eval", bistop, "--wrt", "x,v", "--points", path, "--format", "jsonl",
        ],
        "",
    ) + &check(
        &["eval", "LOG(x)", "--points", path, "--format", "json"],
        "",
    ) + &check(
        &["eval", "TIME * 2 + x", "--points", "-"],
        "TIME,x\n1,1\n2.5,0\n",
    );
    std::fs::remove_dir_all(&dir).unwrap();
    insta::assert_snapshot!(report.replace(path, "points.csv"));
}

#[test]
fn a_closed_pipe_ends_the_run_quietly() {
    let many = "x + 1\n".repeat(200_000);
    let mut child = Command::new(env!("CARGO_BIN_EXE_mbexpr"))
        .args(["check", "--format", "jsonl", "-"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(many.as_bytes())
        .unwrap();
    // Read a little, then close our end of the pipe.
    let mut stdout = child.stdout.take().unwrap();
    let mut first = [0u8; 64];
    std::io::Read::read_exact(&mut stdout, &mut first).unwrap();
    drop(stdout);
    let output = child.wait_with_output().unwrap();
    assert_eq!(output.status.code(), Some(0));
    assert!(
        output.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

#[test]
fn eval_in_a_scene() {
    let root = env!("CARGO_MANIFEST_DIR");
    let ball = format!("{root}/examples/scenes/ball_between_walls.toml");
    let slider = format!("{root}/examples/scenes/slider_in_slot.toml");
    let dir = std::env::temp_dir().join(format!("mbexpr-scene-points-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("points.csv");
    std::fs::write(&csv, "ball.x,ball.vx\n0.0,1\n0.52,0.7\n-0.6,-2\n").unwrap();
    let points = csv.to_str().unwrap();
    let report = check(
        &[
            "eval",
            "--scene",
            &ball,
            "--wrt",
            "ball.x,ball.vx",
            "--order",
            "2",
        ],
        "",
    ) + &check(&["eval", "--scene", &slider, "--format", "jsonl"], "")
        + &check(
            &[
                "eval",
                "DM(ball, wall)",
                "--scene",
                &ball,
                "--wrt",
                "ball.y",
            ],
            "",
        )
        + &check(&["eval", "DX(ball, wal)", "--scene", &ball], "")
        + &check(
            &[
                "eval",
                "BISTOP(DX(ball, wall, wall), VX(ball, wall, wall, wall), -0.5, 0.5, 1e5, 2.2, 100, 0.05)",
                "--scene",
                &ball,
                "--points",
                points,
                "--wrt",
                "ball.x",
                "--format",
                "jsonl",
            ],
            "",
        );
    std::fs::remove_dir_all(&dir).unwrap();
    insta::assert_snapshot!(report.replace(root, "ROOT").replace(points, "points.csv"));
}

const SMALL_MODEL: &str = "initial configuration
PART/1, GROUND
PART/2, QG = 1, 2, 3, REULER = 90D, 0, 0, VX = 0.5
MARKER/10, PART = 2, QP = 1, 0, 0
MARKER/20, PART = 1
VARIABLE/1, FUNCTION = DX(10, 20)
VARIABLE/2, FUNCTION = 2*VARVAL(1)
ARRAY/1, NUMBERS = 5, 6
SFORCE/1, I = 10, J = 20, FUNCTION = VARVAL(2) + ARYVAL(1, 2) + VX(10, 20)
SFORCE/2, I = 10, J = 20, FUNCTION = SFORCE(1, 0, 2, 0) + DIF(3)
SFORCE/3, I = 10, J = 20, FUNCTION = LOG(DX(10, 20) - 2)
REQUEST/1, F2 = DY(10, 20)\\F3 = DZ(10)
";

#[test]
fn check_and_eval_a_model_file() {
    let dir = std::env::temp_dir().join(format!("mbexpr-model-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("small.adm");
    std::fs::write(&path, SMALL_MODEL).unwrap();
    let broken = dir.join("broken.adm");
    std::fs::write(
        &broken,
        SMALL_MODEL
            .replace("DX(10, 20)\n", "DX(10, 21)\n")
            .replace("VARVAL(2)", "VARVL(2)"),
    )
    .unwrap();
    let (small, broken_path) = (path.to_str().unwrap(), broken.to_str().unwrap());
    let report = check(&["check", small], "")
        + &check(&["check", broken_path], "")
        + &check(&["check", "--format", "jsonl", broken_path], "")
        + &check(
            &["eval", "--model", small, "--wrt", "PART/2.x,PART/2.rz"],
            "",
        )
        + &check(&["eval", "--model", small, "--format", "jsonl"], "")
        + &check(&["eval", "--model", small, "--wrt", "x"], "")
        + &check(&["eval", "--model", small, "ORIENT(1, 1, 10, 20)"], "")
        + &check(
            &[
                "eval",
                "--model",
                small,
                "--set",
                "PART/2.x=3",
                "DX(10, 20)",
            ],
            "",
        )
        + &check(
            &["eval", "--model", small, "--points", "-", "DX(10, 20)"],
            "TIME,PART/2.x,PART/2.rz\n0,1,0\n1,3,0.5\n2,x,0\n",
        )
        + &check(
            &[
                "eval", "--model", small, "--points", "-", "--format", "jsonl",
            ],
            "PART/2.vx\n2\n",
        )
        + &check(&["eval", "--model", small, "--points", "-"], "k\n1\n");
    std::fs::remove_dir_all(&dir).unwrap();
    let folder = dir.to_str().unwrap();
    insta::assert_snapshot!(report.replace(folder, "DIR"));
}

#[test]
fn repl_session_from_a_pipe() {
    let session = "\
:set k = 1e4
:set v = 0.3
BISTOP(x, v, -1, 1, k, 1.5, 50, 0.1)
:set x = 1.05
BISTOP(x, v, -1, 1, k,
  1.5, 50, 0.1)
:wrt x, v
:order 2
BISTOP(x, v, -1, 1, k, 1.5, 50, 0.1)
:help bistop
:help pi
STPE(x)
LOG(x - 2)
:vars
:bogus
:order 7
:quit
x
";
    insta::assert_snapshot!(check(&["repl"], session));
    let root = env!("CARGO_MANIFEST_DIR");
    let scene = format!("{root}/examples/scenes/slider_in_slot.toml");
    let in_scene = ":wrt slider.x\nVX(slider, slot, slot, slot)\n:scene /no/such/file.toml\n";
    insta::assert_snapshot!(check(&["repl", "--scene", &scene], in_scene).replace(root, "ROOT"));
}

#[test]
fn plot_writes_a_well_formed_svg_holding_the_curve() {
    let dir = std::env::temp_dir().join(format!("mbexpr-plot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("bistop.svg");
    let path = svg.to_str().unwrap();
    let (stdout, stderr, code) = mbexpr(
        &[
            "plot",
            "BISTOP(x, v, -1, 1, 1e4, 1.5, 50, 0.2)",
            "--over",
            "x=-1.5..1.5",
            "--set",
            "v=0.3",
            "--derivatives",
            "--samples",
            "101",
            "-o",
            path,
        ],
        "",
    );
    assert_eq!(code, 0, "{stderr}");
    // 101 samples and the break points -1.2, -1, 1, 1.2, each with the
    // double below it (one may fall on a sample).
    let points: usize = stdout
        .split(" (")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|count| count.parse().ok())
        .unwrap_or_default();
    assert!((108..=109).contains(&points), "{stdout}");
    let text = std::fs::read_to_string(&svg).unwrap();
    let document = roxmltree::Document::parse(&text).expect("well-formed SVG");
    let lines: Vec<_> = document
        .descendants()
        .filter(|node| node.has_tag_name("polyline"))
        .filter_map(|node| node.attribute("points"))
        .filter(|points| points.split_whitespace().count() >= 100)
        .collect();
    assert_eq!(lines.len(), 3, "value, first and second derivative");
    let texts: Vec<&str> = document
        .descendants()
        .filter_map(|node| node.text())
        .map(str::trim)
        .collect();
    assert!(texts.contains(&"x") && texts.contains(&"d/dx"), "{texts:?}");
    std::fs::remove_dir_all(&dir).unwrap();
    insta::assert_snapshot!(
        check(
            &["plot", "LOG(x)", "--over", "x=-2..-1", "-o", "/dev/null"],
            ""
        ) + &check(&["plot", "x", "--over", "x=1..1", "-o", "/dev/null"], "")
            + &check(&["plot", "x", "--over", "y", "-o", "/dev/null"], "")
    );
}

/// `args` split at ` | `, run; the exit code and the first line it printed.
fn run_line(case: &str) -> String {
    let args: Vec<&str> = case.split(" | ").collect();
    let (stdout, stderr, code) = mbexpr(&args, "");
    let first = stdout
        .lines()
        .chain(stderr.lines())
        .next()
        .unwrap_or_default();
    format!("[exit {code}] {first}")
}

#[test]
fn an_expression_may_start_with_a_minus() {
    insta::assert_snapshot!(crate::table(
        "
        eval | -2**2
        eval | - -8.3E-03*RTOD
        eval | -1E4*(x-50)-10*v | --set | x=51 | --set | v=-1
        eval | --set | x=3 | -x | --wrt | x
        eval | -x | --set | x=3 | --wrt | x | --format | jsonl
        eval | --scene | examples/scenes/ball_between_walls.toml | --format | jsonl | -DX(ball, wall)
        eval | -x | --bogus
        eval | -h*2 | --set | h=1
        eval | -V | --set | V=1
        eval | --set | x=1 | -- | -x
        eval | -h
        parse | -1E4*(DM(3,4)-50)-10*VR(3,4)
        parse | -x
        plot | -x | --over | x=0..1 | -o | /dev/null
        plot | -o | /dev/null | --over | x=0..1 | -x**2
        plot | -o | /dev/null | -x**2 | --over | x=0..1
        plot | -omega | --over | omega=0..1 | -o | /dev/null
        ",
        run_line
    ));
}

/// A points file and an `eval` on it: `CSV || ARGS`, the CSV with `\n`,
/// `\r`, `\t` and `\u{feff}` written out, the arguments split at ` | `,
/// `points.csv` standing for the file (`-`: the CSV is standard input). JSON output is parsed and said to be valid or not.
fn points_case(case: &str) -> String {
    let (csv, args) = case.split_once(" || ").expect("CSV || ARGS");
    let csv = csv
        .replace("\\n", "\n")
        .replace("\\r", "\r")
        .replace("\\t", "\t")
        .replace("\\u{feff}", "\u{feff}");
    // One folder per call: tests run in parallel, and cases of two tests
    // may have the same length.
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir =
        std::env::temp_dir().join(format!("mbexpr-points-case-{}-{call}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("points.csv");
    std::fs::write(&file, &csv).unwrap();
    let path = file.to_str().unwrap();
    let args: Vec<&str> = std::iter::once("eval")
        .chain(
            args.split(" | ")
                .map(|arg| if arg == "points.csv" { path } else { arg }),
        )
        .collect();
    let stdin = if args.contains(&"-") {
        csv.as_str()
    } else {
        ""
    };
    let (stdout, stderr, code) = mbexpr(&args, stdin);
    std::fs::remove_dir_all(&dir).unwrap();
    let validity = json_validity(&args, &stdout);
    format!("{stdout}{stderr}[exit {code}]{validity}")
        .replace(path, "points.csv")
        .replace('\n', "\n     ")
}

/// ` [one JSON document]`, ` [N JSON lines]` or what is wrong with them,
/// when `args` ask for JSON.
fn json_validity(args: &[&str], stdout: &str) -> String {
    let format = args
        .iter()
        .position(|arg| *arg == "--format")
        .map(|index| args[index + 1]);
    let parses = |text: &str| serde_json::from_str::<serde_json::Value>(text).is_ok();
    match format {
        Some("json") if parses(stdout) => " [one JSON document]".to_string(),
        Some("json") => " [NOT ONE JSON DOCUMENT]".to_string(),
        Some("jsonl") if stdout.lines().all(parses) => {
            format!(" [{} JSON lines]", stdout.lines().count())
        }
        Some("jsonl") => " [A LINE IS NOT JSON]".to_string(),
        _ => String::new(),
    }
}

#[test]
fn points_rows_are_known_by_their_line() {
    insta::assert_snapshot!(crate::table(
        r"
        x\n1\n\n2\n   \n3\n || LOG(x) | --points | points.csv
        x\n1\n\n2\n,\n-1\n || LOG(x) | --points | points.csv | --format | jsonl
        x\n1\n\n0\n || LOG(x) | --points | points.csv | --format | json
        \u{feff}x,v\n1,2\n || x+v | --points | points.csv
        x,v,\n1,2,\n3,4\n || x+v | --points | points.csv
        x,v\r1,2\r\r3,4\r || x+v | --points | points.csv | --format | jsonl
        x,v\r\n1,2\r\n\r\n3,4\r\n || x+v | --points | points.csv | --format | jsonl
        x,v\n1,2\r3,4\r\n5,6\n || x*v | --points | points.csv | --format | jsonl
        # a comment\nx,v\n# another\n1,2\n || x+v | --points | points.csv | --format | jsonl
        x\tv\n1\t2\n || x+v | --points | points.csv
        x\nnan\ninf\n1e999\n-0\n0x10\n\n || x | --points | points.csv
        x,v\n1\n1,2,3\n1,2,,\n || x+v | --points | points.csv
        x\n2\n || x | --points | - | --wrt | x | --format | jsonl
        x\n || x | --points | points.csv | --format | json
        x\n || x | --points | points.csv
        ",
        points_case
    ));
}

#[test]
fn points_headers_are_read_as_csv_readers_do() {
    insta::assert_snapshot!(crate::table(
        r#"
        "x","v"\n1,2\n || x+v | --points | points.csv
        x;v\n1;2\n1,5;2\n || x+v | --points | points.csv
        # x,v\n1,2\n || x+v | --points | points.csv
        1,2\n3,4\n || x+v | --points | points.csv
        X1,V1\n1,2\n || x+v | --points | points.csv
        X1,V1\n1,2\n || x+v | --points | points.csv | --format | json
        x,v,X\n1,2,3\n || x+v | --points | points.csv
        x,,v\n1,2,3\n || x+v | --points | points.csv
        x\n2\n || x | --set | x=1 | --set | y=3 | --points | points.csv
        x,y,z,w\n1,2,3,4\n || x+w | --points | points.csv
        # only a comment\n\n || x | --points | points.csv
        x\n1\n || x | --points | no-such.csv
        x\n1\n || x | --points | no-such.csv | --format | jsonl
        "#,
        points_case
    ));
}

#[test]
fn json_output_is_one_document_and_errors_are_json_too() {
    insta::assert_snapshot!(crate::table(
        r"
        x\n1\n || x**2 | --set | x=3 | --wrt | x | --order | 2 | --format | json
        x\n1\n || STPE(x) + FOOO(x) | --format | json
        x\n1\n || STPE(x) + FOOO(x) | --format | jsonl
        x\n1\n || LOG(x) | --set | x=0 | --format | json
        x\n1\n || x | --set | x=1 | --wrt | y | --format | json
        x\n1\n || x | --set | x=one | --format | jsonl
        x\n1\n || x | --scene | no-such.toml | --format | json
        x\n1\n || STPE(x) | --points | points.csv | --format | json
        x\n1\n2\n || x*y | --set | y=2 | --wrt | x,y | --points | points.csv | --format | json
        slider.x\n1\n2\n || --scene | examples/scenes/slider_in_slot.toml | --format | json
        slider.x\n1\n2\n || --scene | examples/scenes/slider_in_slot.toml | --points | points.csv | --format | json
        slider.x\n1\n2\n || --scene | examples/scenes/slider_in_slot.toml | --points | points.csv | --format | jsonl
        slider.x\n1\n2\n || --scene | examples/scenes/slider_in_slot.toml | --points | - | --format | jsonl
        ",
        points_case
    ));
}

/// Runs `eval EXPR --format jsonl --points -` on `csv` and returns, per
/// output line, its row and its value or first error message.
fn stream(expression: &str, extra: &[&str], csv: &str) -> Vec<(u64, Result<f64, String>)> {
    let mut args = vec!["eval", expression, "--format", "jsonl", "--points", "-"];
    args.extend(extra);
    let (stdout, stderr, _) = mbexpr(&args, csv);
    assert!(!stdout.is_empty(), "{stderr}");
    stdout
        .lines()
        .map(|line| {
            let record: serde_json::Value = serde_json::from_str(line).unwrap();
            let result = match record["value"].as_f64() {
                Some(value) => Ok(value),
                None => Err(record["errors"][0]["message"].to_string()),
            };
            (record["row"].as_u64().unwrap(), result)
        })
        .collect()
}

#[test]
fn many_points_stream_out_in_order_and_a_bad_row_does_not_stop_them() {
    // More rows than a batch, every 997th bad: each row's result comes out
    // in the order of the file, with its line.
    let rows = 20_000;
    let mut csv = String::from("x\n");
    for row in 0..rows {
        if row % 997 == 0 {
            csv += "oops\n";
        } else {
            csv += &format!("{row}\n");
        }
    }
    let results = stream("x*2", &[], &csv);
    assert_eq!(results.len(), rows);
    for (row, (line, result)) in results.into_iter().enumerate() {
        assert_eq!(line, row as u64 + 2);
        match result {
            Ok(value) => assert_eq!(value, row as f64 * 2.0, "row {row}"),
            Err(message) => assert!(row % 997 == 0 && message.contains("oops"), "{message}"),
        }
    }
}

#[test]
fn angles_continue_from_row_to_row_across_batches() {
    // The slot turns four times over 10 000 rows: AZ goes on past ±π in
    // the order of the rows, as a run does, however the rows are batched.
    let scene = format!(
        "{}/examples/scenes/slider_in_slot.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let rows = 10_000;
    let turn = 8.0 * std::f64::consts::PI / rows as f64;
    let mut csv = String::from("slot.rz\n");
    for row in 0..rows {
        csv += &format!("{}\n", row as f64 * turn);
    }
    let results = stream("AZ(slot) - slot.rz", &["--scene", &scene], &csv);
    let offset = results[0].1.clone().unwrap();
    for (line, result) in results {
        let value = result.unwrap();
        assert!((value - offset).abs() < 1e-9, "row {line}: {value}");
    }
}

#[test]
fn completions_and_manual_pages() {
    // `ARGS ? TEXT`: the exit code, and whether the output holds TEXT.
    insta::assert_snapshot!(crate::table(
        r"
        completions | bash ? --points
        completions | zsh ? --points
        completions | fish ? points
        completions | powershell ? --points
        completions | tcsh ? points
        man ? .TH mbexpr 1
        man | eval ? .TH mbexpr-eval 1
        man | eval ? points
        man | plot ? over
        man | bogus ? points
        ",
        |case| {
            let (args, text) = case.split_once(" ? ").unwrap();
            let args: Vec<&str> = args.split(" | ").collect();
            let (stdout, stderr, code) = mbexpr(&args, "");
            let holds = if stdout.contains(text) {
                "holds"
            } else {
                "lacks"
            };
            let error = stderr.lines().next().unwrap_or_default();
            format!("[exit {code}] {holds} {text} {error}")
                .trim_end()
                .to_string()
        }
    ));
}

/// Issue 18, items 4 to 8, as a user meets them: `eval --model` at the time
/// given, on an expression of the user's, with a DIFF's IC and the Hessian
/// in text; `check` with every error of an expression in jsonl, names it is
/// told exist, a dataset known by its first line whatever its extension, a
/// missing file among others, and a file saved in Windows-1252.
#[test]
fn model_files_as_an_engineer_meets_them() {
    let dir = std::env::temp_dir().join(format!("mbexpr-engineer-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = "Adams View model name: timed\nPART/1, GROUND\nPART/2, QG = 1, 0, 0\nMARKER/10, PART = 2\nMARKER/20, PART = 1\nDIFF/3, IC = 0.25, FUNCTION = 1\nVARIABLE/1, FUNCTION = STEP(TIME, 1, 0, 2, 10) + DIF(3)\nSFORCE/1, I = 10, J = 20, FUNCTION = VARVAL(1)*DM(10, 20)**2\n";
    let dat = dir.join("timed.dat");
    std::fs::write(&dat, model).unwrap();
    let mut latin = b"Adams View model name: caf\xe9\n! r\xe9glage \xb0C\nPART/1, GROUND\nVARIABLE/1, FUNCTION = STPE(TIME, 0, 0, 1, 1) + LOG(0)\n".to_vec();
    latin.extend_from_slice(b"VARIABLE/2, FUNCTION = 2 \xb0\n");
    let cp1252 = dir.join("windows.adm");
    std::fs::write(&cp1252, latin).unwrap();
    let expressions = dir.join("expressions.txt");
    std::fs::write(
        &expressions,
        "STPE(x)+FOOO(y)+STEP(x,1,0,0,1)\nk*x + TIME\n",
    )
    .unwrap();
    let (dat, cp1252, expressions) = (
        dat.to_str().unwrap(),
        cp1252.to_str().unwrap(),
        expressions.to_str().unwrap(),
    );
    // The lift's TFSISO states, ARYVAL(10, 1) and ARYVAL(20, 1).
    let lift = |args: &[&str]| {
        let model = ["eval", "--model", "examples/simulate/l_controlled_lift.adm"];
        check(&[&model[..], args].concat(), "")
    };
    let report = check(&["eval", "--model", dat, "--set", "TIME=1.5"], "")
        + &check(
            &["eval", "--model", dat, "--wrt", "DIF(3)", "DIF(3)**2"],
            "",
        )
        + &lift(&[
            "3*ARYVAL(10, 1)**2 + ARYVAL(20,1)",
            "--wrt",
            "aryval(10,1), ARYVAL(20, 1)",
            "--set",
            "ARYVAL(10,1)=2",
            "--order",
            "2",
        ])
        + &lift(&["ARYVAL(10, 1)", "--wrt", "ARYVAL(10,5)"])
        + &check(
            &[
                "eval",
                "--model",
                dat,
                "DM(10, 20) + DIF(3)",
                "--wrt",
                "PART/2.x",
                "--order",
                "2",
            ],
            "",
        )
        + &check(
            &[
                "eval",
                "--model",
                dat,
                "--wrt",
                "PART/2.x,TIME",
                "--order",
                "2",
                "--set",
                "time=1.5",
            ],
            "",
        )
        + &check(&["eval", "--model", dat, "--set", "k=1"], "")
        + &check(&["eval", "--model", dat, "DM(10, 99)"], "")
        + &check(&["check", dat, "/no/such/file.adm", cp1252], "")
        + &check(&["check", "--format", "jsonl", expressions], "")
        + &check(&["check", "--names", "x,y", expressions], "")
        + &check(&["check", "--kind", "expressions", dat], "");
    std::fs::remove_dir_all(&dir).unwrap();
    insta::assert_snapshot!(report.replace(dir.to_str().unwrap(), "DIR"));
}

/// `check`, with the wall time in the statistics line (which varies from
/// run to run) replaced.
fn check_run(args: &[&str], stdin: &str) -> String {
    let text = check(args, stdin);
    text.lines()
        .map(|line| match line.rsplit_once(" events, ") {
            Some((head, _)) => format!("{head} events, <wall time>\n"),
            None => format!("{line}\n"),
        })
        .collect()
}

const BALL_DATASET: &str = "A1: a ball between two walls
DIFF/1, IC = 0, FUNCTION = DIF(2)
DIFF/2, IC = 5, FUNCTION = BISTOP(DIF(1), DIF(2), -1, 1, 1e5, 1.5, 50, 0.01)
";

#[test]
fn simulate_writes_rows_statistics_and_events() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "simulate", "-", "--end", "0.4", "--steps", "4", "--rtol", "1e-8",
        ];
        args.extend_from_slice(extra);
        check_run(&args, BALL_DATASET)
    };
    insta::assert_snapshot!(
        run(&[])
            + &run(&["--format", "jsonl"])
            + &run(&["--format", "csv", "--events"])
            + &run(&["--method", "dop853", "--format", "csv"])
    );
}

/// Issue 17.3 in the simulator's rows and statistics: numbers as the
/// shortest text that reads back, in exponent form when large or small.
#[test]
fn simulate_rows_show_large_and_small_numbers_short() {
    let model = "extremes\nDIFF/1, IC = 1E-300, FUNCTION = 0\nDIFF/2, IC = 1E300, FUNCTION = 0\nDIFF/3, IC = 0, FUNCTION = 1E-7\n";
    let run = |format: &str| {
        check_run(
            &[
                "simulate", "-", "--end", "2", "--steps", "2", "--format", format,
            ],
            model,
        )
    };
    insta::assert_snapshot!(run("csv") + &run("text"));
}

/// A stiff run with DOP853: the run goes on, and says so at the end.
#[test]
fn simulate_warns_of_a_stiff_run() {
    let dropped = include_str!("../examples/simulate/a4_dropped_ball.adm");
    let args = [
        "simulate", "-", "--end", "0.6", "--steps", "2", "--method", "dop853",
    ];
    insta::assert_snapshot!(check_run(&args, dropped));
}

#[test]
fn simulate_refuses_what_it_cannot_run() {
    let joint = "joint\nPART/1, GROUND\nMARKER/1, PART = 1\nPART/2, MASS = 1, CM = 3, IP = 1, 1, 1\nMARKER/3, PART = 2\nJOINT/1, SCREW, I = 3, J = 1\n";
    let typo = "typo\nDIFF/1, IC = 0, FUNCTION = STPE(TIME, 0, 0, 1, 1)\n";
    insta::assert_snapshot!(
        check_run(&["simulate", "-"], BALL_DATASET)
            + &check_run(&["simulate", "-", "--end", "1", "--steps", "2"], joint)
            + &check_run(&["simulate", "-", "--end", "1", "--steps", "2"], typo)
            + &check_run(
                &["simulate", "-", "--end", "-1", "--steps", "2"],
                BALL_DATASET
            )
            + &check_run(
                &[
                    "simulate", "-", "--end", "1", "--steps", "2", "--method", "euler"
                ],
                BALL_DATASET
            )
            + &check_run(
                &["simulate", "-", "--end", "1e-323", "--steps", "4"],
                BALL_DATASET
            )
            + &check_run(
                &[
                    "simulate",
                    "/no/such/model.adm",
                    "--end",
                    "1",
                    "--steps",
                    "2"
                ],
                ""
            )
    );
}

#[test]
fn simulate_reads_scene_files_and_plots() {
    let folder = std::env::temp_dir().join(format!("mbexpr-simulate-{}", std::process::id()));
    std::fs::create_dir_all(&folder).expect("a temporary folder");
    let svg = folder.join("slider.svg");
    let svg = svg.to_str().expect("a UTF-8 path");
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/slider_simulation.toml"
    );
    let (stdout, stderr, code) = mbexpr(
        &[
            "simulate", scene, "--steps", "2", "--format", "csv", "--plot", svg,
        ],
        "",
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stdout.starts_with("time,DIF(1),DIF(2)\n0,0.1,0\n"),
        "{stdout}"
    );
    assert_eq!(stdout.lines().count(), 4, "{stdout}");
    let drawing = std::fs::read_to_string(svg).expect("the plot is written");
    assert!(drawing.starts_with("<svg") && drawing.contains("DIF(1)"));
    // A run where no state changes draws its states flat, and succeeds.
    let flat = folder.join("flat.svg");
    let flat = flat.to_str().expect("a UTF-8 path");
    let still = "still\nDIFF/1, IC = 1, FUNCTION = 0\nEND\n";
    let (stdout, stderr, code) = mbexpr(
        &[
            "simulate", "-", "--end", "1", "--steps", "2", "--plot", flat,
        ],
        still,
    );
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(stdout.matches("time,").count(), 1, "{stdout}");
    let drawing = std::fs::read_to_string(flat).expect("the flat plot is written");
    assert!(drawing.contains("DIF(1)"));
    std::fs::remove_dir_all(&folder).ok();
}

/// Every command, its standard output a pipe already closed (`mbexpr ... |
/// (exec 0<&-; true)`), ends quietly with exit 0: no panic, no message
/// (issue 27.4). `ARGS` split at ` | `.
#[test]
fn every_command_ends_quietly_on_a_closed_pipe() {
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/ball_between_walls.toml"
    );
    let model = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/simulate/a1_ball.adm");
    let cases = format!(
        "
        completions | bash
        completions | zsh
        completions | fish
        man
        man | simulate
        --help
        --version
        parse | STEP(TIME, 0, 0, 1, 10)
        check | -
        eval | SIN(x) | --set | x=1 | --wrt | x
        eval | DX(ball, wall) | --scene | {scene}
        eval | --model | {model}
        simulate | {model} | --end | 0.1 | --steps | 2
        repl
        "
    );
    insta::assert_snapshot!(
        crate::table(&cases, |case| {
            let args: Vec<&str> = case.split(" | ").collect();
            let (reader, writer) = std::io::pipe().unwrap();
            drop(reader);
            let output = Command::new(env!("CARGO_BIN_EXE_mbexpr"))
                .args(&args)
                .stdin(Stdio::null())
                .stdout(writer)
                .stderr(Stdio::piped())
                .output()
                .unwrap();
            let stderr = String::from_utf8_lossy(&output.stderr);
            format!("[exit {:?}] {}", output.status.code(), stderr.trim())
                .trim_end()
                .to_string()
        })
        .replace(env!("CARGO_MANIFEST_DIR"), ".")
    );
}

/// A `--set` value is a constant expression of the language, as `:set`
/// takes it in the REPL (issue 27.5); what is no constant is an error with
/// its place.
#[test]
fn set_takes_a_constant_expression() {
    insta::assert_snapshot!(crate::table(
        r"
        x=30D
        x=1D3
        x=2*PI
        x = -1.5e-3
        x=STEP(0.5, 0, 0, 1, 1)
        x=RTOD*0.1
        x=2*y
        x=LOG(0)
        x=1/0
        x=
        x=SIN(
        x
        ",
        |case| {
            let (stdout, stderr, code) = mbexpr(&["eval", "x", "--set", case], "");
            format!("[exit {code}] {}{}", stdout, stderr)
                .trim_end()
                .to_string()
        }
    ));
}

/// A binary file (a library, NUL bytes, mostly control bytes) is one error,
/// "not a text file", not a message per line it happens to have (issue
/// 27.6), for `check`, `eval --model` and `simulate` alike.
#[test]
fn a_binary_file_is_one_error() {
    let dir = std::env::temp_dir().join(format!("mbexpr-binary-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut library = b"\x7fELF\x02\x01\x01\0\0\0\0\0\0\0\0\0".to_vec();
    for index in 0..20_000u32 {
        library.extend_from_slice(&index.to_le_bytes());
        library.extend_from_slice(b"PART/1, MASS = 1\n");
    }
    let controls: Vec<u8> = (0..4000u32).map(|index| (index % 32) as u8 | 1).collect();
    let latin = "Titel: Gr\u{f6}\u{df}e\nPART/1, GROUND\n"
        .as_bytes()
        .to_vec();
    let files = [
        ("library.so", library),
        ("controls.adm", controls),
        ("text.adm", latin),
    ];
    for (name, bytes) in &files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    let cases = "
        check | library.so
        check | controls.adm
        check | text.adm
        eval | --model | library.so
        simulate | library.so
    ";
    let report = crate::table(cases, |case| {
        let args: Vec<String> = case
            .split(" | ")
            .map(|arg| match dir.join(arg) {
                path if path.exists() => path.display().to_string(),
                _ => arg.to_string(),
            })
            .collect();
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (stdout, stderr, code) = mbexpr(&args, "");
        format!("[exit {code}] {stdout}{stderr}")
            .trim_end()
            .to_string()
    });
    std::fs::remove_dir_all(&dir).unwrap();
    insta::assert_snapshot!(report.replace(&dir.display().to_string(), "DIR"));
}

/// Issue 22.5: every output and option is checked before the first step:
/// nothing is written, and the run is not started.
#[test]
fn simulate_checks_every_output_before_the_first_step() {
    let run = |extra: &[&str]| {
        let mut args = vec!["simulate", "-", "--end", "1", "--steps", "2"];
        args.extend_from_slice(extra);
        check_run(&args, BALL_DATASET)
    };
    insta::assert_snapshot!(
        run(&["--plot", "/nonexistent/x.svg"])
            + &run(&["--plot", "ball.png"])
            + &run(&["--events-file", "/nonexistent/events.jsonl"])
            + &run(&["--rtol", "0"])
            + &run(&["--max-steps", "0"])
            + &run(&["--hmax", "-1"])
            + &run(&["--hmax", "1e-300"])
    );
}

/// Issue 22.6: events as JSON objects (on standard error under `--format
/// jsonl`, and in `--events-file`), the end statistics as one JSON object.
#[test]
fn simulate_writes_events_and_statistics_as_json() {
    let folder = std::env::temp_dir().join(format!("mbexpr-events-{}", std::process::id()));
    std::fs::create_dir_all(&folder).expect("a temporary folder");
    let file = folder.join("events.jsonl");
    let file = file.to_str().expect("a UTF-8 path");
    let dropped = include_str!("../examples/simulate/a4_dropped_ball.adm");
    let (stdout, stderr, code) = mbexpr(
        &[
            "simulate",
            "-",
            "--end",
            "1",
            "--steps",
            "2",
            "--format",
            "jsonl",
            "--events",
            "--events-file",
            file,
            "--stats",
            "json",
        ],
        dropped,
    );
    assert_eq!(code, 0, "{stderr}");
    let mut objects: Vec<serde_json::Value> = stderr
        .lines()
        .map(|line| serde_json::from_str(line).expect(line))
        .collect();
    // The statistics: the wall time varies from run to run.
    let stats = objects.last_mut().expect("the statistics");
    stats["wall_time"] = serde_json::Value::Null;
    let written = std::fs::read_to_string(file).expect("the events file");
    std::fs::remove_dir_all(&folder).ok();
    let events: Vec<&serde_json::Value> = objects[..objects.len() - 1].iter().collect();
    let in_file: Vec<serde_json::Value> = written
        .lines()
        .map(|line| serde_json::from_str(line).expect(line))
        .collect();
    assert_eq!(events, in_file.iter().collect::<Vec<_>>());
    let report: String = std::iter::once(stdout)
        .chain(objects.iter().map(|object| format!("{object:#}\n")))
        .collect();
    insta::assert_snapshot!(report);
}

/// Issue 22.5: SIGINT and SIGTERM end a long run at its next step, every
/// row computed already written (each flushed as it comes), the
/// statistics printed, exit status 128 + the signal.
#[cfg(unix)]
#[test]
fn a_signal_ends_a_run_with_every_row_written() {
    use std::io::{BufRead, BufReader, Read};
    for (signal, status) in [("INT", 130), ("TERM", 143)] {
        // DOP853 on the stiff stop: millions of steps after t = 0.45.
        let mut child = Command::new(env!("CARGO_BIN_EXE_mbexpr"))
            .args([
                "simulate",
                concat!(
                    env!("CARGO_MANIFEST_DIR"),
                    "/examples/simulate/a4_dropped_ball.adm"
                ),
                "--method",
                "dop853",
                "--rtol",
                "1e-12",
                "--end",
                "10",
                "--steps",
                "100000",
                "--format",
                "csv",
            ])
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("the binary runs");
        let mut rows = BufReader::new(child.stdout.take().expect("piped"));
        let mut lines = Vec::new();
        // The header and the rows of the free fall come at once.
        while lines.len() < 50 {
            let mut line = String::new();
            assert!(rows.read_line(&mut line).expect("a row") > 0, "{lines:?}");
            lines.push(line);
        }
        let killed = Command::new("kill")
            .args([&format!("-{signal}"), &child.id().to_string()])
            .status()
            .expect("kill runs");
        assert!(killed.success());
        let mut rest = String::new();
        rows.read_to_string(&mut rest)
            .expect("the rest of the rows");
        lines.extend(rest.lines().map(|line| format!("{line}\n")));
        let mut stderr = String::new();
        child
            .stderr
            .take()
            .expect("piped")
            .read_to_string(&mut stderr)
            .expect("standard error");
        let code = child.wait().expect("the run ends").code();
        assert_eq!(code, Some(status), "SIG{signal}: {stderr}");
        assert_eq!(lines[0], "time,DIF(1),DIF(2)\n");
        let rows = &lines[1..];
        for (index, row) in rows.iter().enumerate() {
            let cells: Vec<f64> = row
                .trim_end_matches('\n')
                .split(',')
                .map(|cell| cell.parse().expect(row))
                .collect();
            assert!(row.ends_with('\n') && cells.len() == 3, "{row:?}");
            assert_eq!(cells[0], 10.0 * index as f64 / 100_000.0, "row {index}");
        }
        assert!(
            stderr.contains(" steps (")
                && stderr.contains(&format!(
                    "interrupted by SIG{signal}: {} rows written",
                    rows.len()
                )),
            "{stderr}"
        );
    }
}

/// A run that fails keeps what it computed in the plot too: the rows up to
/// the stop are drawn (before, the SVG was written only for a run that
/// reached its end).
#[test]
fn a_failed_run_still_plots_its_rows() {
    let dir = std::env::temp_dir().join(format!("mbexpr-failed-plot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("ball.svg");
    let path = svg.to_str().unwrap();
    let model = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/simulate/a1_ball.adm");
    let (stdout, stderr, code) = mbexpr(
        &[
            "simulate",
            model,
            "--end",
            "1000",
            "--steps",
            "1000",
            "--max-steps",
            "500",
            "--plot",
            path,
        ],
        "",
    );
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("more than 500 steps"), "{stderr}");
    let rows = stdout.lines().count() - 1;
    let drawn = std::fs::read_to_string(&svg).expect("the plot is written");
    assert!(
        drawn.starts_with("<svg") && drawn.contains(&format!("{rows} output rows")),
        "{rows}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A MARKER's axes from the points ZP (on its z axis) and XP (in its xz
/// plane), a PART's from ZG and XG, as Adams reads them (before, the
/// points were ignored and the axes were ground's): the distances measured
/// along them by hand.
#[test]
fn axes_given_by_points_are_the_axes_the_points_say() {
    let dir = std::env::temp_dir().join(format!("mbexpr-axes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("axes.adm");
    std::fs::write(
        &model,
        "axes by points
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 2, 1, 0
MARKER/3, PART = 1, QP = 5, 5, 5, ZP = 6, 5, 5, XP = 5, 6, 5
PART/2, MASS = 1, IP = 1, 1, 1, CM = 20, QG = 1, 0, 0, ZG = 1, 0, 1, XG = 1, -1, 0
MARKER/20, PART = 2
MARKER/21, PART = 2, QP = 1, 0, 0
VARIABLE/1, FUNCTION = DX(2, 1, 3)
VARIABLE/2, FUNCTION = DY(2, 1, 3)
VARIABLE/3, FUNCTION = DZ(2, 1, 3)
VARIABLE/4, FUNCTION = DX(21, 1)
VARIABLE/5, FUNCTION = DY(21, 1)
MARKER/4, PART = 1, ZP = 0, 0, 0
",
    )
    .unwrap();
    let path = model.to_str().unwrap();
    let (_, stderr, code) = mbexpr(&["eval", "--model", path], "");
    assert_eq!(code, 1);
    assert!(stderr.contains("MARKER/4: ZP is the origin QP"), "{stderr}");
    let text = std::fs::read_to_string(&model).unwrap();
    std::fs::write(
        &model,
        text.replace("MARKER/4, PART = 1, ZP = 0, 0, 0\n", ""),
    )
    .unwrap();
    let (stdout, stderr, code) = mbexpr(&["eval", "--model", path], "");
    assert_eq!(code, 0, "{stderr}");
    let values: Vec<f64> = stdout
        .lines()
        .filter(|line| line.starts_with("VARIABLE/"))
        .map(|line| line.split_whitespace().last().unwrap().parse().unwrap())
        .collect();
    let expected = [1.0, 0.0, 2.0, 1.0, -1.0];
    assert_eq!(values.len(), expected.len(), "{stdout}");
    for (value, expected) in values.iter().zip(expected) {
        assert!((value - expected).abs() < 1e-12, "{stdout}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A command file beside a dataset that does not check (a command the
/// solver does not know) or asks for a run mbexpr does not make stops
/// `simulate` with the command's line and a caret, and `check` of the
/// command file finds the same.
#[test]
fn a_command_file_that_gives_no_run_is_refused_at_its_place() {
    let folder = std::env::temp_dir().join(format!("mbexpr-commands-{}", std::process::id()));
    std::fs::create_dir_all(&folder).expect("a temporary folder");
    let ball = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/simulate/a1_ball.adm"
    ))
    .expect("the example");
    let mut shown = String::new();
    for (name, commands) in [
        (
            "unknown",
            "ball\nball\nfrobnicate/all\nsimulate/dynamic, end = 1, steps = 4\nstop\n",
        ),
        (
            "end0",
            "ball\nball\nsimulate/dynamic, end = 0, steps = 10\nstop\n",
        ),
        (
            "dtout",
            "ball\nball\nsimulate/dynamic, end = 1, dtout = 0.3\nstop\n",
        ),
    ] {
        let dataset = folder.join(format!("{name}.adm"));
        let command_file = folder.join(format!("{name}.acf"));
        std::fs::write(&dataset, &ball).expect("written");
        std::fs::write(&command_file, commands).expect("written");
        for args in [
            vec!["simulate", dataset.to_str().expect("UTF-8")],
            vec!["check", command_file.to_str().expect("UTF-8")],
        ] {
            shown += &check(&args, "").replace(folder.to_str().expect("UTF-8"), "DIR");
        }
    }
    std::fs::remove_dir_all(&folder).ok();
    insta::assert_snapshot!(shown);
}

/// `simulate --dataset` prints the solver dataset a View command file is
/// read as, which runs as the View file does; another file is a usage
/// error.
#[test]
fn simulate_prints_the_dataset_a_view_file_is_read_as() {
    let view = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/simulate/n_view_four_bar.cmd"
    );
    let (dataset, _, code) = mbexpr(&["simulate", "--dataset", view], "");
    assert_eq!(code, 0);
    assert!(dataset.starts_with("mbexpr\nUNITS/\n"), "{dataset}");
    assert!(dataset.ends_with("END\n"), "{dataset}");
    let run = ["--end", "0.5", "--steps", "5", "--format", "csv"];
    let (from_view, _, _) = mbexpr(&[&["simulate", view][..], &run[..]].concat(), "");
    let (from_dataset, _, code) = mbexpr(&[&["simulate", "-"][..], &run[..]].concat(), &dataset);
    assert_eq!(code, 0);
    assert_eq!(from_view, from_dataset);
    let adm = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/simulate/c_pendulum.adm"
    );
    let (_, refused, code) = mbexpr(&["simulate", "--dataset", adm], "");
    assert_eq!(code, 2);
    assert!(
        refused.contains("an Adams View command file (.cmd)"),
        "{refused}"
    );
}
