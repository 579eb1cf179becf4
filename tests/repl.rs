//! The REPL: lines from a pipe (batch mode) and keys on a terminal, one
//! case per line (`\n` in a case is a line break).

use std::io::Write;
use std::process::{Command, Stdio};

/// A batch session: what `mbexpr repl` prints for `input` from a pipe.
fn check(input: &str) -> String {
    let (stdout, stderr, code) = crate::cli::mbexpr(&["repl"], &input.replace("\\n", "\n"));
    format!("{stdout}{stderr}[exit {code}]")
}

#[test]
fn each_line_is_an_input_unless_it_visibly_continues() {
    insta::assert_snapshot!(crate::table(
        r"
        1+1\n2+2
        SIN(x\n3+3\nSTEP(TIME, 0, 0, 1, 10
        STEP(TIME,\n0, 0, 1, 10)
        2 *\n(3 +\n4)
        IF(TIME - 1:\n-1, 0, 1)
        :set x = 2\nx + 1 ! the rest is a comment\nx ! comment with ( and ,
        x != 1
        ! a comment line\n1
        1 +
        TIME + 1\n:set TIME = 2\nTIME + 1\n:vars
        :set PI = 3\n:set pi=3\n:set STEP = 3\n:set Step5 = 1\n:set TIME = 1\nPI
        :set MODE = 99\n:set MODE = 2\n:set MODE = 3\nMODE
        :order 1\n2*3\n:wrt x\n:set x = 1\n2*x
        :scene examples/scenes/ball_between_walls.toml\ngap\ncontact\n2*gap + gap_rate\nDX(ball, wall, wall) - gap\n:set gap = 2\ngap
        :scene examples/scenes/ball_between_walls.toml\n:plot gap --over ball.x=0..1 -o /dev/null --samples 11\n:plot gap over ball.x in 0..1 to /dev/null\n:plot gap --over ball.x=0..1
        ",
        check
    ));
}

/// Runs `mbexpr repl` on a terminal (through `script`, which gives it a
/// pseudo-terminal) with `keys` sent at once, before the first prompt, as
/// keys typed ahead or pasted are; returns the result and error lines.
fn on_a_terminal(keys: &str) -> String {
    let home = std::env::temp_dir().join(format!("mbexpr-repl-{}", std::process::id()));
    std::fs::create_dir_all(&home).unwrap();
    let command = format!("{} repl", env!("CARGO_BIN_EXE_mbexpr"));
    let spawned = Command::new("script")
        .args(["-q", "-e", "-c", &command, "/dev/null"])
        .env("HOME", &home)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn();
    let Ok(mut child) = spawned else {
        eprintln!("skipped: `script` (util-linux) is not installed");
        return "skipped".to_string();
    };
    let keys = keys.replace("\\n", "\n").replace("\\e", "\u{1b}");
    let mut stdin = child.stdin.take().unwrap();
    stdin.write_all(keys.as_bytes()).unwrap();
    stdin.write_all(b":quit\n").unwrap();
    drop(stdin);
    let output = child.wait_with_output().unwrap();
    let _ = std::fs::remove_dir_all(&home);
    String::from_utf8_lossy(&output.stdout)
        .replace('\r', "")
        .lines()
        .filter(|line| line.parse::<f64>().is_ok() || line.starts_with("error"))
        .collect::<Vec<_>>()
        .join(" | ")
}

#[test]
fn keys_typed_ahead_and_pasted_blocks_are_each_answered() {
    insta::assert_snapshot!(crate::table(
        r"
        1+1\n2+2\n3+3\n
        \e[200~1+1\n2+2\nSIN(x\n4+4\e[201~\n
        \e[200~STEP(1,\n0, 0, 2, 10)\n5*5\e[201~\n
        STEP(1, 0, 0, 2\n, 10)\n
        SIN(0\n\n7*7\n
        ",
        on_a_terminal
    ));
}
