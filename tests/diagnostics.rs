//! Errors as the command line shows them: the same problem at many places
//! once with its count, long lines as a window around the place, and the
//! small words the command line owes its user. One case per line.

/// `[TEXT*N]` in a case stands for TEXT written N times.
fn expand(case: &str) -> String {
    let mut text = String::new();
    let mut rest = case;
    while let Some((before, after)) = rest.split_once('[') {
        let (repeated, after) = after.split_once(']').expect("a closed [TEXT*N]");
        let (unit, count) = repeated.rsplit_once('*').expect("[TEXT*N]");
        text.push_str(before);
        text.push_str(&unit.repeat(count.parse().expect("a count")));
        rest = after;
    }
    text + rest
}

/// What `eval` says of the expression, then what `check -` says of it on
/// the second line of a file; and how many bytes each wrote, which stays
/// near the size of one window per distinct problem however many there are.
fn check(case: &str) -> String {
    let text = expand(case);
    let (_, eval, eval_code) = crate::cli::mbexpr(&["eval", &text], "");
    let file = format!("! the second line\n{text}\n");
    let (checked, check_errors, check_code) = crate::cli::mbexpr(&["check", "-"], &file);
    format!(
        "eval [exit {eval_code}, {} bytes]\n{eval}check [exit {check_code}, {} bytes]\n{checked}{check_errors}",
        eval.len(),
        checked.len() + check_errors.len()
    )
}

#[test]
fn a_problem_at_many_places_is_shown_once_with_its_count() {
    insta::assert_snapshot!(crate::table(
        r"
        MAX([x, *30000]x)
        [x+*30000]x
        [FOO(1)+*3]y+z+y
        x + STPE(y) + x*STPE(2)
        [FOO(x)+*15000]1
        ",
        check
    ));
}

#[test]
fn a_long_line_is_shown_as_a_window_around_the_place() {
    insta::assert_snapshot!(crate::table(
        r"
        [a*b+*200]SIN(c
        [SIN(1)+*30]LOG(-1)+[1+*100]1
        LOG(-1)+[1+*100]1
        [y+*45]FOO(1)[+y*100]
        [é+*60]1
        	STEP(x, 0, 0, 1, 1)	+ ^2
        ",
        check
    ));
}

/// `eval ARG|ARG|...` as the command line gets it: the output and status.
fn command(case: &str) -> String {
    let args: Vec<&str> = case.split('|').collect();
    let (stdout, stderr, code) = crate::cli::mbexpr(&args, "");
    format!("{stdout}{stderr}[exit {code}]")
}

#[test]
fn time_defaults_to_zero_and_empty_derivative_requests_say_why() {
    let Some(model) = crate::corpus::corpus_path("models/alex-marinov__mbdyn__ant.adm") else {
        return;
    };
    let model = model.to_str().unwrap();
    let cases = format!(
        "
        eval|STEP(TIME, 0, 0, 1, 10)
        eval|STEP(TIME, 0, 0, 1, 10)|--set|TIME=0.5
        eval|x*v|--set|x=2|--set|v=3|--wrt| x , v
        eval|x|--set|x=2|--wrt|x,,
        eval|2*3|--order|1
        eval|2*x|--set|x=1|--order|2
        eval|2*TIME|--order|1
        eval|2*TIME|--wrt|TIME
        eval|--model|{model}|--wrt|PART/3.x
        eval|--model|{model}|--wrt|PART/13.q
        eval|--model|{model}|--wrt|speed
        "
    );
    insta::assert_snapshot!(crate::table(&cases, command).replace(model, "MODEL"));
}
