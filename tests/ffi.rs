//! The utility subroutines through their C and FORTRAN calling sequences:
//! programs written as user subroutines would be, compiled against the
//! static library and run; and the Rust API against the expression evaluator.

use std::path::{Path, PathBuf};
use std::process::Command;

use mbexpr::{Order, Shown, utility};
use proptest::prelude::*;

/// `target/<profile>`, where the binary and `libmbexpr.a` are built.
fn build_dir() -> PathBuf {
    Path::new(env!("CARGO_BIN_EXE_mbexpr"))
        .parent()
        .expect("the binary is in a folder")
        .to_path_buf()
}

/// Compiles `sources` with `compiler` and `flags` against the static
/// library and runs the program; `None` (with a note) when the compiler is
/// not installed.
fn compile_and_run(compiler: &str, sources: &[PathBuf], flags: &[&str]) -> Option<String> {
    compile_and_run_under(&[], compiler, sources, flags)
}

/// [`compile_and_run`], the program run by the command `runner` (as
/// `valgrind ... PROGRAM`; none when empty), which must succeed too.
fn compile_and_run_under(
    runner: &[&str],
    compiler: &str,
    sources: &[PathBuf],
    flags: &[&str],
) -> Option<String> {
    if Command::new(compiler).arg("--version").output().is_err() {
        eprintln!(
            "note: {compiler} is not installed; a test of {sources:?} is skipped (.ci/run installs it)"
        );
        return None;
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    // `cargo test` builds the static library beside the test binaries.
    let library = build_dir().join("deps/libmbexpr.a");
    assert!(
        library.exists(),
        "{} is built with the library",
        library.display()
    );
    let scratch = scratch(compiler);
    let program = scratch.join("user_sub");
    let output = Command::new(compiler)
        .current_dir(&scratch)
        .args(flags)
        .args(sources)
        .arg("-I")
        .arg(root.join("include"))
        .arg(&library)
        .args(["-lpthread", "-ldl", "-lm", "-o"])
        .arg(&program)
        .output()
        .expect("the compiler runs");
    assert!(
        output.status.success(),
        "{compiler} failed on {sources:?}:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    // In the scratch folder: the programs write files of their own
    // (`broken.adm`), which must not land in the source tree.
    let mut command = match runner {
        [first, rest @ ..] => {
            let mut command = Command::new(first);
            command.args(rest).arg(&program);
            command
        }
        [] => Command::new(&program),
    };
    let output = command
        .current_dir(&scratch)
        .output()
        .expect("the program runs");
    std::fs::remove_dir_all(&scratch).unwrap();
    assert!(
        output.status.success(),
        "{sources:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    Some(String::from_utf8(output.stdout).unwrap())
}

/// A fresh folder for one compilation.
fn scratch(name: &str) -> PathBuf {
    static COUNT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let count = COUNT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let folder =
        std::env::temp_dir().join(format!("mbexpr-ffi-{}-{name}-{count}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    folder
}

/// A file of this repository.
fn file(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

#[test]
fn a_c_user_subroutine_calls_the_library() {
    if let Some(output) =
        compile_and_run("cc", &[file("tests/c/user_sub.c")], &["-Wall", "-Werror"])
    {
        insta::assert_snapshot!(output);
    }
}

#[test]
fn a_fortran_user_subroutine_calls_the_library() {
    let sources = [
        "include/mbexpr.f90",
        "tests/fortran/old_style.f",
        "tests/fortran/user_sub.f90",
    ]
    .map(file);
    if let Some(output) = compile_and_run("gfortran", &sources, &["-Wall", "-Werror"]) {
        insta::assert_snapshot!(output);
    }
}

#[test]
fn the_c_api_from_c() {
    if let Some(output) = compile_and_run(
        "cc",
        &[file("tests/c/capi.c")],
        &["-Wall", "-Werror", "-std=c11"],
    ) {
        insta::assert_snapshot!(output);
    }
}

/// One `mbexpr_error` passed to failing call after failing call without
/// being freed between them: each failure frees the message it held (under
/// valgrind no byte is lost; each earlier message was), and a success
/// leaves it as it was.
#[test]
fn an_error_passed_again_frees_its_earlier_message() {
    if Command::new("valgrind").arg("--version").output().is_err() {
        eprintln!(
            "note: valgrind is not installed; the test of a reused mbexpr_error is skipped (.ci/run installs it)"
        );
        return;
    }
    let valgrind = [
        "valgrind",
        "--quiet",
        "--leak-check=full",
        "--errors-for-leak-kinds=definite",
        "--error-exitcode=99",
    ];
    if let Some(output) = compile_and_run_under(
        &valgrind,
        "cc",
        &[file("tests/c/error_reuse.c")],
        &["-Wall", "-Werror", "-std=c11"],
    ) {
        insta::assert_snapshot!(output);
    }
}

#[test]
fn the_c_api_from_cpp_through_its_raii_header() {
    if let Some(output) = compile_and_run(
        "c++",
        &[file("tests/cpp/capi.cpp")],
        &["-Wall", "-Werror", "-std=c++17"],
    ) {
        insta::assert_snapshot!(output);
    }
}

#[test]
fn the_c_api_from_fortran_through_iso_c_binding() {
    let sources = ["include/mbexpr_c.f90", "tests/fortran/capi.f90"].map(file);
    if let Some(output) = compile_and_run("gfortran", &sources, &["-Wall", "-Werror"]) {
        insta::assert_snapshot!(output);
    }
}

/// A fenced code block of a Markdown file: its language and text.
fn fenced_blocks(markdown: &str) -> Vec<(String, String)> {
    let mut blocks = Vec::new();
    let mut open: Option<(String, String)> = None;
    for line in markdown.lines() {
        match (&mut open, line.trim_start().strip_prefix("```")) {
            (None, Some(language)) => open = Some((language.trim().to_string(), String::new())),
            (Some(_), Some(_)) => blocks.extend(open.take()),
            (Some((_, text)), None) => {
                text.push_str(line);
                text.push('\n');
            }
            (None, None) => {}
        }
    }
    blocks
}

/// Whether a FORTRAN text is in fixed form: every line a comment (C, *, !
/// in column 1), or a label field of digits and blanks before column 7.
fn fixed_form(text: &str) -> bool {
    text.lines().all(|line| {
        line.trim().is_empty()
            || line.starts_with(['C', 'c', '*', '!'])
            || line.chars().take(5).all(|c| c == ' ' || c.is_ascii_digit()) && line.len() > 6
    })
}

/// Issue 18.1: every C and FORTRAN block of the README and `docs/` compiles
/// exactly as written, with `-Wall -Werror` (fixed-form FORTRAN as fixed
/// form, where gfortran cuts lines at column 72), and runs: a block
/// without a main program with the driver in `tests/docs/` named after the
/// routine it defines.
#[test]
fn every_c_and_fortran_block_of_the_docs_compiles_and_runs() {
    let mut documents = vec![file("README.md")];
    let mut pages: Vec<PathBuf> = std::fs::read_dir(file("docs"))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|extension| extension == "md"))
        .collect();
    pages.sort();
    documents.extend(pages);
    let drivers: Vec<PathBuf> = std::fs::read_dir(file("tests/docs"))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .collect();
    let mut report = String::new();
    for document in &documents {
        let markdown = std::fs::read_to_string(document).unwrap();
        for (index, (language, text)) in fenced_blocks(&markdown).into_iter().enumerate() {
            let (compiler, extension, main) = match language.as_str() {
                "c" => ("cc", "c", "main("),
                "cpp" => ("c++", "cpp", "main("),
                "fortran" if fixed_form(&text) => ("gfortran", "f", "PROGRAM"),
                "fortran" => ("gfortran", "f90", "PROGRAM"),
                _ => continue,
            };
            let name = format!(
                "{}-{index}",
                document.file_stem().unwrap().to_string_lossy()
            );
            let folder = scratch(&name);
            let block = folder.join(format!("{name}.{extension}"));
            std::fs::write(&block, &text).unwrap();
            // A FORTRAN block of the C API comes after the module it uses.
            let mut sources = if text.to_lowercase().contains("use mbexpr_c") {
                vec![file("include/mbexpr_c.f90"), block]
            } else {
                vec![block]
            };
            if !text.to_uppercase().contains(&main.to_uppercase()) {
                // The driver whose name is a routine the block defines.
                let defined = text.to_lowercase();
                let driver = drivers
                    .iter()
                    .find(|driver| {
                        let stem = driver.file_stem().unwrap().to_string_lossy().to_lowercase();
                        let language_matches = match extension {
                            "c" | "cpp" => driver.extension().is_some_and(|e| e == extension),
                            _ => driver.extension().is_some_and(|e| e != "c"),
                        };
                        language_matches && defined.contains(&format!("{stem}("))
                    })
                    .unwrap_or_else(|| panic!("{name}: a block without a main program needs a driver in tests/docs/ named after its routine:\n{text}"));
                sources.push(driver.clone());
            }
            let Some(output) = compile_and_run(compiler, &sources, &["-Wall", "-Werror"]) else {
                continue;
            };
            std::fs::remove_dir_all(&folder).unwrap();
            report += &format!("{name} ({language}):\n{output}");
        }
    }
    insta::assert_snapshot!(report);
}

#[test]
fn vector_across_every_branch() {
    let points = [
        ("gap", 0.0, 0.7),
        ("contact", 10.0, 0.7),
        ("ramp", 10.05, 0.7),
        ("ramp end", 10.125, 0.7),
        ("beyond", 10.5, 0.7),
        ("clamped", 10.05, -100.0),
        ("lower ramp", -10.05, -0.7),
        ("lower beyond", -10.5, 0.7),
    ];
    let mut table = String::new();
    for (branch, x, v) in points {
        for iord in 0..=2 {
            let vector = utility::bistop(x, v, -10.0, 10.0, 1e5, 2.2, 100.0, 0.125, iord).unwrap();
            table += &format!(
                "BISTOP {branch:<13} iord {iord}: [{:.12e}, {:.12e}, {:.12e}]\n",
                vector[0], vector[1], vector[2]
            );
        }
    }
    for (x, v) in [(1.5, -1.0), (0.95, -1.0), (0.5, -1.0), (0.95, 1e6)] {
        for iord in 0..=2 {
            let vector = utility::impact(x, v, 1.0, 1e4, 1.5, 10.0, 0.1, iord).unwrap();
            table += &format!(
                "IMPACT x={x} v={v} iord {iord}: [{:.12e}, {:.12e}, {:.12e}]\n",
                vector[0], vector[1], vector[2]
            );
        }
    }
    for (x, iord) in [(-1.0, 0), (0.25, 0), (0.25, 1), (0.25, 2), (2.0, 1)] {
        table += &format!(
            "STEP x={x} iord {iord}: {:.12e}\n",
            utility::step(x, 0.0, 0.0, 1.0, 10.0, iord).unwrap()
        );
    }
    let errors = [
        utility::bistop(0.0, 0.0, 1.0, 1.0, 1e5, 2.2, 100.0, 0.1, 0).unwrap_err(),
        utility::bistop(0.0, 0.0, -1.0, 1.0, -1.0, 2.2, 100.0, 0.1, 0).unwrap_err(),
        utility::bistop(0.0, 0.0, -1.0, 1.0, 1e5, 0.0, 100.0, 0.1, 0).unwrap_err(),
        utility::bistop(0.0, 0.0, -1.0, 1.0, 1e5, 2.2, -1.0, 0.1, 0).unwrap_err(),
        utility::bistop(0.0, 0.0, -1.0, 1.0, 1e5, 2.2, 100.0, 0.0, 0).unwrap_err(),
        utility::bistop(0.0, 0.0, -1.0, 1.0, 1e5, 2.2, 100.0, 0.1, 3).unwrap_err(),
        utility::bistop(f64::NAN, 0.0, -1.0, 1.0, 1e5, 2.2, 100.0, 0.1, 0).unwrap_err(),
        utility::impact(0.0, f64::INFINITY, 1.0, 1e5, 2.2, 100.0, 0.1, 0).unwrap_err(),
        utility::step(0.0, 1.0, 0.0, 1.0, 1.0, 0).unwrap_err(),
    ];
    for error in errors {
        table += &format!("error: {error}\n");
    }
    insta::assert_snapshot!(table);
}

/// One utility call, `NAME ARG ... IORD` (the arguments in the calling
/// sequence's order): VECTOR (or STEP's value), or the error that sets ERRFLG.
fn call(case: &str) -> String {
    let mut words = case.split_whitespace();
    let name = words.next().unwrap();
    let numbers: Vec<f64> = words.map(|word| word.parse().unwrap()).collect();
    let (arguments, iord) = numbers.split_at(numbers.len() - 1);
    let iord = iord[0] as i32;
    let result = match (name, arguments) {
        ("bistop", &[x, xd, x1, x2, k, e, cmax, d]) => {
            utility::bistop(x, xd, x1, x2, k, e, cmax, d, iord)
        }
        ("impact", &[x, xd, x1, k, e, cmax, d]) => utility::impact(x, xd, x1, k, e, cmax, d, iord),
        ("step", &[x, x0, h0, x1, h1]) => {
            utility::step(x, x0, h0, x1, h1, iord).map(|value| [value, 0.0, 0.0])
        }
        _ => panic!("not a call: {case}"),
    };
    match result {
        Ok([a, b, c]) => format!("[{}, {}, {}]", Shown(a), Shown(b), Shown(c)),
        Err(error) => format!("ERRFLG: {error}"),
    }
}

#[test]
fn extreme_arguments_give_the_double_or_errflg() {
    insta::assert_snapshot!(crate::table(
        r"
        impact -5e-161 0 0 1 2 1 1e-160 2
        impact -2.5e-161 0 0 1 2 1 1e-160 2
        impact -1e-300 0 0 1 0.5 0 1 2
        impact -1e-300 0 0 1 0.5 0 1 1
        impact -5e-201 0 0 1 2 1 1e-200 1
        impact -5e-201 0 0 1 2 1 1e-200 0
        impact -5e-301 1 0 1 2 1 1e-300 1
        impact -1e-300 0 0 1e12 0.1 0 1e-9 2
        step 5e-201 0 0 1e-200 1 0
        step 5e-201 0 0 1e-200 1 1
        step 5e-201 0 0 1e-200 1 2
        step 2.5e-201 0 0 1e-200 1 2
        step 5e-301 0 0 1e-300 1 1
        step 0.5 0 -1e308 1 1e308 0
        step 0.5 0 -1e308 1 1e308 1
        step 0.25 0 -1e308 1 1e308 0
        step 0.5 0 -1e308 1e10 1e308 1
        step 0.5 -1e308 0 1e308 1 1
        step 2.5e-301 0 0 1e-300 1e308 0
        step 2.5e-301 0 0 1e-300 1e308 1
        bistop 12 -1e307 -10 10 1e308 3 100 0.1 0
        bistop 12 -7e306 -10 10 1e308 3 100 0.1 0
        bistop 12 -7e306 -10 10 1e308 3 100 0.1 1
        bistop 12 -1e306 -10 10 1e308 3 100 0.1 0
        bistop 12 -1e306 -10 10 1e308 3 100 0.1 2
        bistop -1e200 0 -1 1 1e12 3 0 1e-9 0
        bistop 1e200 0 -1 1 1e-300 1.5 0 1e-9 0
        bistop 1e200 0 -1 1 1e-300 1.5 0 1e-9 1
        bistop 1e10 0 -1 1 1e280 3 0 1e-9 1
        bistop 1e300 1e300 -1 1 1e12 0.1 1e6 1e-9 0
        bistop -1e300 -1e300 -1 1 1e12 0.1 1e6 1e-9 0
        ",
        call
    ));
}

#[test]
fn extreme_inputs_keep_their_digits() {
    // Gap at 1e6, d = 1e-9, penetrations of a few ulps: against the formula
    // evaluated in penetration coordinates by hand.
    let ulp = 1e6f64.next_up() - 1e6;
    for (steps, e, k) in [
        (1.0, 1.5, 1e12),
        (3.0, 0.1, 1e3),
        (5.0, 3.0, 0.0),
        (8.0, 1.0, 1e12),
    ] {
        let x = 1e6 - steps * ulp;
        let p = 1e6 - x;
        let (cmax, d, v) = (1e3, 1e-9, -2.0);
        let w = p / d;
        let c = cmax * w * w * (3.0 - 2.0 * w);
        let dc = cmax * 6.0 * w * (1.0 - w) / d;
        let want = [k * p.powf(e) - c * v, -k * e * p.powf(e - 1.0) + dc * v, -c];
        let value = utility::impact(x, v, 1e6, k, e, cmax, d, 0).unwrap()[0];
        let slopes = utility::impact(x, v, 1e6, k, e, cmax, d, 1).unwrap();
        let scale = k * p.powf(e) + c * v.abs();
        assert!(
            (value - want[0]).abs() <= 1e-12 * scale,
            "value {value} vs {}",
            want[0]
        );
        let slope_scale = (k * e * p.powf(e - 1.0)).abs() + (dc * v).abs();
        assert!(
            (slopes[0] - want[1]).abs() <= 1e-9 * slope_scale,
            "dF/dx {} vs {}",
            slopes[0],
            want[1]
        );
        assert!(
            (slopes[1] - want[2]).abs() <= 1e-12 * c.max(1e-300),
            "dF/dv {} vs {}",
            slopes[1],
            want[2]
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The utility and the expression `BISTOP(x, v, ...)` are one law.
    #[test]
    fn the_utility_agrees_with_the_expression(
        x in -3.0f64..3.0, v in -5.0f64..5.0, x1 in -1.5f64..-0.5, x2 in 0.5f64..1.5,
        k in 0.0f64..1e6, e in 0.1f64..3.0, cmax in 0.0f64..1e3, d in 1e-6f64..1.0,
    ) {
        let text = format!("BISTOP(x, v, {x1:?}, {x2:?}, {k:?}, {e:?}, {cmax:?}, {d:?})");
        let checked = mbexpr::check(&mbexpr::parse(&text).unwrap()).unwrap();
        let program = mbexpr::compile(&checked, &["x", "v"]).unwrap();
        let expression = program.evaluate(&[x, v], &[0, 1], Order::Hessian);
        let values = utility::bistop(x, v, x1, x2, k, e, cmax, d, 0).unwrap();
        let slopes = utility::bistop(x, v, x1, x2, k, e, cmax, d, 1).unwrap();
        let curvatures = utility::bistop(x, v, x1, x2, k, e, cmax, d, 2).unwrap();
        if let Ok(expression) = expression {
            let gradient = expression.gradient.unwrap();
            let hessian = expression.hessian.unwrap();
            prop_assert_eq!(values[0], expression.value + 0.0);
            prop_assert_eq!([slopes[0], slopes[1]], [gradient[0] + 0.0, gradient[1] + 0.0]);
            prop_assert_eq!([curvatures[0], curvatures[1]], [hessian[(0, 0)] + 0.0, hessian[(0, 1)] + 0.0]);
        }
    }
}

/// A seeded stream of arguments for the utilities: doubles of every
/// magnitude from 1e-300 to 1e308 of either sign, moderate ones, zeros and
/// the extremes (xorshift64*, so that a failure can be replayed).
struct Arguments(u64);

impl Arguments {
    fn bits(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.bits() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn any(&mut self) -> f64 {
        let sign = if self.bits() & 1 == 0 { 1.0 } else { -1.0 };
        let magnitude = match self.bits() % 10 {
            0..=4 => 10f64.powf(-300.0 + 608.0 * self.unit()),
            5..=7 => 10.0 * self.unit(),
            8 => 0.0,
            _ => [f64::MAX, 1e308, 5e-324, 1e-300, f64::MIN_POSITIVE][(self.bits() % 5) as usize],
        };
        sign * magnitude
    }

    /// A positive double of any magnitude.
    fn positive(&mut self) -> f64 {
        match self.any().abs() {
            0.0 => 1.0,
            value => value,
        }
    }

    /// An ordered pair (`x1 < x2`), distinct.
    fn ordered(&mut self) -> (f64, f64) {
        let (a, b) = (self.any(), self.any());
        match a.partial_cmp(&b) {
            Some(std::cmp::Ordering::Less) => (a, b),
            Some(std::cmp::Ordering::Greater) => (b, a),
            _ if a == -f64::MAX => (a, a.next_up()),
            _ => (a.next_down(), a),
        }
    }
}

/// `ln(e^a + e^b)`: the logarithm of a sum of two magnitudes given as logarithms.
fn log_sum(a: f64, b: f64) -> f64 {
    let (big, small) = (a.max(b), a.min(b));
    if big == f64::NEG_INFINITY {
        big
    } else {
        big + (small - big).exp().ln_1p()
    }
}

/// Upper bounds (as logarithms) of `|F|, |dF/dx|, |dF/dx'|, |d2F/dx2|,
/// |d2F/dx dx'|` for penetration `p`: `k p^e` and its slopes plus the
/// damping, whose ramp is at most 1 and has slope at most `1.5/d` and
/// curvature at most `6/d^2`.
fn contact_bounds(p: f64, v: f64, k: f64, e: f64, cmax: f64, d: f64) -> [f64; 5] {
    let (ln_p, ln_v, ln_c, ln_d) = (p.ln(), v.abs().ln(), cmax.ln(), d.ln());
    let stiffness = |power: f64, factor: f64| k.ln() + factor.abs().ln() + power * ln_p;
    [
        log_sum(stiffness(e, 1.0), ln_c + ln_v),
        log_sum(stiffness(e - 1.0, e), ln_c + 1.5f64.ln() - ln_d + ln_v),
        ln_c,
        log_sum(
            stiffness(e - 2.0, e * (e - 1.0)),
            ln_c + 6f64.ln() - 2.0 * ln_d + ln_v,
        ),
        ln_c + 1.5f64.ln() - ln_d,
    ]
}

/// Issue 17.6: a million argument sets per routine and IORD, across every
/// magnitude. No call returns NaN or an infinity; a call fails only on a
/// broken rule or an entry that may truly be beyond the range of a double
/// (its bound is); the force never pulls. (About 5 s in the test profile.)
#[test]
fn a_million_argument_sets_per_routine_and_order() {
    const SETS: usize = 1_000_000;
    let limit = f64::MAX.ln();
    let mut arguments = Arguments(0x9e37_79b9_7f4a_7c15);
    let mut failures = Vec::new();
    let mut counts = [0usize; 3];
    for set in 0..SETS {
        let (x, v) = (arguments.any(), arguments.any());
        let (x1, x2) = arguments.ordered();
        let (k, cmax) = (arguments.any().abs(), arguments.any().abs());
        let (e, d) = (arguments.positive(), arguments.positive());
        for iord in 0..=2 {
            let entries: [usize; 2] = [[0, 0], [1, 2], [3, 4]][iord as usize];
            for (routine, result) in [
                ("bistop", utility::bistop(x, v, x1, x2, k, e, cmax, d, iord)),
                ("impact", utility::impact(x, v, x1, k, e, cmax, d, iord)),
            ] {
                let (below, above) = (x < x1, routine == "bistop" && x > x2);
                let p = if below { x1 - x } else { x - x2 };
                let bounds = contact_bounds(p, v, k, e, cmax, d);
                let case = || {
                    format!(
                        "{routine}({x:e}, {v:e}, {x1:e}, {x2:e}, {k:e}, {e:e}, {cmax:e}, {d:e}, {iord})"
                    )
                };
                match result {
                    Ok(vector) => {
                        counts[0] += 1;
                        if !vector.iter().all(|entry| entry.is_finite()) {
                            failures.push(format!("{}: {vector:?}", case()));
                        }
                        let pulls = (below && vector[0] < 0.0) || (above && vector[0] > 0.0);
                        if iord == 0 && (pulls || (!below && !above && vector[0] != 0.0)) {
                            failures.push(format!("{}: force {}", case(), vector[0]));
                        }
                    }
                    Err(utility::UtilityError::BeyondRange { quantity, .. }) => {
                        counts[1] += 1;
                        let entry = if quantity.ends_with('\'') {
                            entries[1]
                        } else {
                            entries[0]
                        };
                        if !(p.is_finite() && bounds[entry] < limit - 1e-6) || p.is_infinite() {
                            continue;
                        }
                        failures.push(format!(
                            "{}: ERRFLG ({quantity}) where its bound is e^{}",
                            case(),
                            bounds[entry]
                        ));
                    }
                    Err(error) => failures.push(format!("{}: {error}", case())),
                }
            }
            let (x0, step_x1) = arguments.ordered();
            let (h0, h1) = (arguments.any(), arguments.any());
            // Half the points inside the ramp.
            let at = if set % 2 == 0 {
                let t = arguments.unit();
                x0 * (1.0 - t) + step_x1 * t
            } else {
                x
            };
            match utility::step(at, x0, h0, step_x1, h1, iord) {
                Ok(value) if value.is_finite() => counts[0] += 1,
                Ok(value) => failures.push(format!(
                    "step({at:e}, {x0:e}, {h0:e}, {step_x1:e}, {h1:e}, {iord}): {value}"
                )),
                Err(utility::UtilityError::BeyondRange { .. }) => {
                    counts[2] += 1;
                    // |h1 - h0| times at most 1.5/L or 6/L^2 (L in halves where it overflows).
                    let (rise, length) = (
                        (h1 * 0.5 - h0 * 0.5).abs().ln() + 2f64.ln(),
                        (step_x1 * 0.5 - x0 * 0.5).ln() + 2f64.ln(),
                    );
                    let bound = match iord {
                        0 => h0.abs().max(h1.abs()).ln(),
                        1 => rise + 1.5f64.ln() - length,
                        _ => rise + 6f64.ln() - 2.0 * length,
                    };
                    if bound < limit - 1e-6 {
                        failures.push(format!("step({at:e}, {x0:e}, {h0:e}, {step_x1:e}, {h1:e}, {iord}): ERRFLG where its bound is e^{bound}"));
                    }
                }
                Err(error) => failures.push(format!(
                    "step({at:e}, {x0:e}, {h0:e}, {step_x1:e}, {h1:e}, {iord}): {error}"
                )),
            }
        }
        if failures.len() > 20 {
            break;
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures (results {counts:?}):\n{}",
        failures.len(),
        failures.join("\n")
    );
    // The sets reach every branch: results, and errors beyond the range.
    assert!(counts.iter().all(|count| *count > 1000), "{counts:?}");
}

/// Issue 27.12: the compile commands of `docs/contact.md` (its `sh` blocks)
/// work as printed: each is run line by line in a folder laid out as the
/// repository (`include/`, `tests/docs/`, `target/release/libmbexpr.a`,
/// the last the library this test run built, so `cargo build --release`
/// is the one line not run), with the C or FORTRAN block above it saved as
/// the file the commands name (`my_sub.c`, `my_sub.f`).
#[test]
fn the_compile_commands_of_the_docs_work_as_printed() {
    let markdown = std::fs::read_to_string(file("docs/contact.md")).unwrap();
    let mut report = String::new();
    let mut source: Option<(String, String)> = None;
    for (language, text) in fenced_blocks(&markdown) {
        if language != "sh" {
            source = Some((language, text));
            continue;
        }
        let Some((source_language, source_text)) = &source else {
            continue;
        };
        let (compiler, name) = match source_language.as_str() {
            "c" => ("cc", "my_sub.c"),
            "fortran" => ("gfortran", "my_sub.f"),
            _ => continue,
        };
        assert!(text.contains(name), "the commands name {name}:\n{text}");
        if Command::new(compiler).arg("--version").output().is_err() {
            eprintln!(
                "note: {compiler} is not installed; the commands of docs/contact.md are not run (.ci/run installs it)"
            );
            continue;
        }
        let folder = scratch(compiler);
        std::fs::write(folder.join(name), source_text).unwrap();
        std::fs::create_dir_all(folder.join("target/release")).unwrap();
        std::fs::create_dir_all(folder.join("tests")).unwrap();
        std::os::unix::fs::symlink(file("include"), folder.join("include")).unwrap();
        std::os::unix::fs::symlink(file("tests/docs"), folder.join("tests/docs")).unwrap();
        std::os::unix::fs::symlink(
            build_dir().join("deps/libmbexpr.a"),
            folder.join("target/release/libmbexpr.a"),
        )
        .unwrap();
        for line in text.lines().filter(|line| !line.starts_with("cargo ")) {
            let output = Command::new("sh")
                .args(["-c", line])
                .current_dir(&folder)
                .output()
                .unwrap();
            assert!(
                output.status.success(),
                "`{line}` failed:\n{}",
                String::from_utf8_lossy(&output.stderr)
            );
            report += &format!("$ {line}\n{}", String::from_utf8_lossy(&output.stdout));
        }
        std::fs::remove_dir_all(&folder).unwrap();
    }
    insta::assert_snapshot!(report);
}

/// Bulk evaluation through the shared layer of the C API and the Python
/// package: `PROGRAMS` at random points, some outside the domain, on 1, 2
/// and every thread: each point's value, gradient and Hessian are exactly
/// those of a single evaluation there, or its status is 1 where that fails.
#[test]
fn bulk_evaluation_is_single_evaluation_at_every_point_on_any_threads() {
    use mbexpr::embed::{Bulk, Expression};
    const PROGRAMS: [&str; 6] = [
        "-k*x - c*v",
        "((((0.5*x - 1.2)*x + 3.1)*x - 0.7)*x + 2)*x - 4 + -v",
        "(x*1e154 - k) * (v*1e154) * c",
        "BISTOP(x, v, -1, 1, k, 1.5, c, 0.01) + LOG(x + 1.5)",
        "SQRT(x) * v + k ** 2 / c",
        "IF(x: STEP(v, -1, 0, 1, k), 0, IMPACT(x, v, 0.5, k, 2.2, c, 0.1))",
    ];
    let mut arguments = Arguments(0x2545_f491_4f6c_dd1d);
    let n = 5000;
    let columns: Vec<Vec<f64>> = (0..4)
        .map(|_| (0..n).map(|_| 4.0 * arguments.unit() - 2.0).collect())
        .collect();
    let columns: Vec<&[f64]> = columns.iter().map(Vec::as_slice).collect();
    for text in PROGRAMS {
        let expression = Expression::compile(text, &["x", "v", "k", "c"]).unwrap();
        for (wrt, order) in [
            (vec![], Order::Value),
            (vec![0, 1], Order::Gradient),
            (vec![2, 0, 3], Order::Hessian),
        ] {
            let k = wrt.len();
            let mut results = Vec::new();
            for threads in [1, 2, 0] {
                let (mut values, mut gradients, mut hessians, mut status) = (
                    vec![9.0; n],
                    vec![9.0; n * k],
                    vec![9.0; n * k * k],
                    vec![9; n],
                );
                let out = Bulk {
                    values: &mut values,
                    gradients: if order >= Order::Gradient {
                        &mut gradients
                    } else {
                        &mut []
                    },
                    hessians: if order >= Order::Hessian {
                        &mut hessians
                    } else {
                        &mut []
                    },
                    status: &mut status,
                };
                let failed = expression
                    .evaluate_bulk(&columns, &wrt, order, out, threads)
                    .unwrap();
                assert_eq!(failed, status.iter().filter(|&&s| s != 0).count());
                results.push((values, gradients, hessians, status));
            }
            assert!(
                results.windows(2).all(|pair| pair[0] == pair[1]),
                "{text}: threads disagree"
            );
            let (values, gradients, hessians, status) = &results[0];
            let mut failures = 0;
            for p in 0..n {
                let point: Vec<f64> = columns.iter().map(|column| column[p]).collect();
                match expression.evaluate(&point, &wrt, order) {
                    Ok(single) => {
                        assert_eq!(status[p], 0, "{text} at {point:?}");
                        assert_eq!(values[p], single.value);
                        if let Some(gradient) = single.gradient {
                            assert_eq!(&gradients[p * k..(p + 1) * k], gradient.as_slice());
                        }
                        if let Some(hessian) = single.hessian {
                            assert_eq!(&hessians[p * k * k..(p + 1) * k * k], hessian.as_slice());
                        }
                    }
                    Err(_) => {
                        failures += 1;
                        assert_eq!(status[p], 1, "{text} at {point:?}");
                        assert_eq!(values[p], 0.0);
                    }
                }
            }
            assert!(failures < n, "{text}: every point failed");
        }
    }
    /// The outputs of a bulk evaluation of values alone.
    fn values_only<'o>(values: &'o mut [f64], status: &'o mut [i32]) -> Bulk<'o> {
        Bulk {
            values,
            gradients: &mut [],
            hessians: &mut [],
            status,
        }
    }
    // Columns shorter than the points, and a direction that is not an input.
    let expression = Expression::compile("x + v", &["x", "v"]).unwrap();
    let mut values = vec![0.0; 3];
    let mut status = vec![0; 3];
    let short: [&[f64]; 2] = [&[1.0, 2.0, 3.0], &[1.0]];
    let out = values_only(&mut values, &mut status);
    let error = expression
        .evaluate_bulk(&short, &[], Order::Value, out, 1)
        .unwrap_err();
    assert_eq!(error.message, "column 1 (v) has 1 points, fewer than 3");
    let error = expression
        .evaluate(&[1.0, 2.0], &[0, 0], Order::Gradient)
        .unwrap_err();
    assert_eq!(
        error.message,
        "derivative direction 0 (x) is asked for twice"
    );
    // More threads than a bulk evaluation starts, and inputs that differ
    // only in case.
    let mut values = vec![0.0; 1];
    let mut status = vec![0; 1];
    let one: [&[f64]; 2] = [&[1.0], &[2.0]];
    let out = values_only(&mut values, &mut status);
    let error = expression
        .evaluate_bulk(&one, &[], Order::Value, out, usize::MAX)
        .unwrap_err();
    assert!(error.message.starts_with("at most "), "{}", error.message);
    let error = Expression::compile("x", &["x", "X"]).unwrap_err();
    assert_eq!(
        error.message,
        "input 2 (\"X\") repeats input 1 (\"x\"): names are read in any case, so give each input once"
    );
}
