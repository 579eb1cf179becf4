//! `mbexpr plot`: the break points found along any input, the gaps where
//! evaluation fails, the tick labels at every magnitude, and refusals.
//! One case per line: the arguments after `plot`, separated by `|`.

/// What `plot` says, and for a written SVG its texts (title, tick labels,
/// axis names) and how many stretches are shaded as not evaluated.
fn check(case: &str) -> String {
    let file = std::env::temp_dir().join(format!(
        "mbexpr-plot-{}-{:x}.svg",
        std::process::id(),
        case.len() * 31 + case.bytes().map(usize::from).sum::<usize>()
    ));
    let root = env!("CARGO_MANIFEST_DIR");
    let case = case.replace("ROOT", root);
    let mut args: Vec<&str> = vec!["plot"];
    args.extend(case.split('|'));
    let output = file.to_str().unwrap().to_string();
    if !case.contains("--samples") {
        args.extend(["--samples", "11"]);
    }
    if !case.contains("-o|") {
        args.extend(["-o", &output]);
    }
    let (stdout, stderr, code) = crate::cli::mbexpr(&args, "");
    let mut shown = format!("{stdout}{stderr}[exit {code}]").replace(&output, "FILE.svg");
    if let Ok(svg) = std::fs::read_to_string(&file) {
        let document = roxmltree::Document::parse(&svg).expect("well-formed SVG");
        let texts: Vec<&str> = document
            .descendants()
            .filter(|node| node.has_tag_name("text"))
            .filter_map(|node| node.text())
            .map(str::trim)
            .collect();
        let gaps = document
            .descendants()
            .filter(|node| node.has_tag_name("rect"))
            .filter(|node| node.attribute("opacity") == Some("0.08"))
            .count();
        shown += &format!("\n  texts: {}\n  shaded: {gaps}", texts.join(" "));
        std::fs::remove_file(&file).unwrap();
    }
    shown
}

#[test]
fn plots_mark_kinks_along_any_input_and_gaps_where_evaluation_fails() {
    insta::assert_snapshot!(crate::table(
        r"
        STEP(x, 0.5, 0, 1.5, 1)|--over|x=0..2
        STEP(TIME, 0.5, 0, 1.5, 1)|--over|TIME=0..2
        STEP(2*TIME**2, 0.5, 0, 1.5, 1)|--over|TIME=0..2
        IF(TIME - 0.25: 0, 1, 2)|--over|TIME=0..1
        BISTOP(DX(ball, wall, wall), VX(ball, wall, wall, wall), -0.5, 0.5, 1e5, 2.2, 100, 0.05)|--over|ball.x=0..1|--scene|ROOT/examples/scenes/ball_between_walls.toml
        LOG(x)|--over|x=-1..1
        SQRT(x)|--over|x=-1..1|--derivatives
        1/(x-0.5)|--over|x=0..1
        LOG(x)|--over|x=-2..-1
        BISTOP(x, v, -1, 1, 1e4, 1.5, 50, 0.2)|--over|x=-1.5..1.5|--set|v=0.3|--derivatives|--samples|400
        1/(x-0.5)|--over|x=0..1|--samples|400
        BISTOP(DIF(1), DIF(2), -1, 1, 1e5, 1.5, 50, 0.01)|--over|DIF(1)=0.9..1.1|--model|ROOT/examples/simulate/a1_ball.adm|--derivatives
        DIF(2)*TIME|--over|TIME=0..2|--model|ROOT/examples/simulate/a1_ball.adm
        DIF(2)|--over|PART/9.x=0..2|--model|ROOT/examples/simulate/a1_ball.adm
        ",
        check
    ));
}

#[test]
fn tick_labels_at_tiny_and_huge_magnitudes() {
    insta::assert_snapshot!(crate::table(
        r"
        1e-12*x|--over|x=0..1e-9
        1e300*x|--over|x=-1e8..1e8
        x|--over|x=1000000..1000001
        x*1e307|--over|x=-10..10
        1e-300*SIN(x)|--over|x=-1e-10..1e-10
        ",
        check
    ));
}

#[test]
fn a_file_that_cannot_be_written_is_refused_with_its_reason() {
    insta::assert_snapshot!(crate::table(
        r"
        x|--over|x=0..1|-o|/no/such/folder/plot.svg
        x|--over|x=0..1|-o|plot.png
        x|--over|x=-1e308..1e308|-o|/dev/null
        ",
        check
    ));
}
