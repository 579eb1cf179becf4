//! The built binary, driven as a user would: arguments, piped input, exit codes.

use std::io::Write;
use std::process::{Command, Stdio};

/// Runs `mbexpr args...` with `stdin`, returning stdout, stderr and the exit code.
fn mbexpr(args: &[&str], stdin: &str) -> (String, String, i32) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_mbexpr"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    child
        .stdin
        .take()
        .expect("piped")
        .write_all(stdin.as_bytes())
        .expect("stdin accepts input");
    let output = child.wait_with_output().expect("the binary ends");
    (
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
        output.status.code().unwrap_or(-1),
    )
}

/// `$ mbexpr args` then what it printed and its exit code.
fn check(args: &[&str], stdin: &str) -> String {
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
        + &check(&["eval", "--model", small, "--wrt", "x"], "");
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
    // 101 samples and the break points -1.2, -1, 1, 1.2 (one may fall on a sample).
    let points: usize = stdout
        .split(" (")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|count| count.parse().ok())
        .unwrap_or_default();
    assert!((104..=105).contains(&points), "{stdout}");
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
