//! The calls of the other benchmarks in a plain loop, for counting
//! instructions under cachegrind: a figure that, unlike time on a shared
//! machine, does not move with the load.
//!
//! ```sh
//! cargo bench --bench counts --no-run
//! valgrind --tool=cachegrind --cache-sim=no target/release/deps/counts-* CASE
//! ```
//!
//! then subtract the count of the case `none` (the set-up every case shares)
//! and divide by the case's repetitions (printed). `CASE` is one of the
//! names in `CASES`; with none, every case runs once (the smoke test
//! `cargo bench` makes of it).
//!
//! A second argument sets the repetitions. On a shared machine, the least
//! wall-clock time of many runs of `CASE 1000000`, less that of `none`, is
//! a steadier time per call than a criterion run (BENCHMARKS.md uses both).

use std::hint::black_box;

use num_dual::{Dual2SVec64, DualSVec64};

#[path = "native.rs"]
mod native;
use native::{BareTape, fasteval_linear, fasteval_linear_value, native_bistop, native_linear};

const PARSE_TEXT: &str = "BISTOP(DX(2,1,1), VX(2,1,1,1), -10, 10, 1e5, 2.2, 100, 0.1)";
/// The same shape for fasteval and evalexpr, as in `benches/parse.rs`.
const FASTEVAL_TEXT: &str = "bistop(dx(2,1,1), vx(2,1,1,1), -10, 10, 1e5, 2.2, 100, 0.1)";
const LARGEST_MODEL: &str =
    "../shared/corpus/models/bthornton191__adamspy__FRS5_doe_8_LAUL_analysis.adm";
const POINT: [f64; 2] = [10.05, 0.7];
const LINEAR_POINT: [f64; 3] = [10.05, 0.7, 0.3];

/// Each case and how many times it runs.
const CASES: [(&str, u32); 16] = [
    ("parse+check", 20_000),
    ("fasteval-parse", 20_000),
    ("evalexpr-parse", 20_000),
    ("native-value", 100_000),
    ("value", 100_000),
    ("native-gradient", 100_000),
    ("gradient", 100_000),
    ("native-hessian", 100_000),
    ("hessian", 100_000),
    ("native-linear", 100_000),
    ("linear", 100_000),
    ("fasteval-linear", 100_000),
    ("bare-tape-linear", 100_000),
    ("model-read", 3),
    ("model-read+check", 3),
    ("none", 1),
];

fn program(text: &str, inputs: &[&str]) -> mbexpr::Program {
    let checked = mbexpr::check(&mbexpr::parse(text).unwrap()).unwrap();
    mbexpr::compile(&checked, inputs).unwrap()
}

fn run(case: &str, repetitions: u32) {
    use mbexpr::model::{self, FileKind};
    let bistop = program("BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1)", &["x", "v"]);
    let linear = program("-1E4*(x-50)-10*v + 3*sin(2*pi*t)", &["x", "v", "t"]);
    let model_text = if case.starts_with("model") {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(LARGEST_MODEL);
        match std::fs::read_to_string(&path) {
            Ok(text) => text,
            Err(_) => return eprintln!("note: {} not found; {case} skipped", path.display()),
        }
    } else {
        String::new()
    };
    let mut value = bistop.evaluator::<f64>();
    let mut gradient = bistop.evaluator::<DualSVec64<2>>();
    let mut hessian = bistop.evaluator::<Dual2SVec64<2>>();
    let mut linear = linear.evaluator::<f64>();
    let (x, v) = (POINT[0], POINT[1]);
    let fasteval_parser = fasteval::Parser::new();
    let mut slab = fasteval::Slab::new();
    let mut linear_slab = fasteval::Slab::new();
    let fasteval_linear = fasteval_linear(&mut linear_slab);
    let mut bare_tape = black_box(BareTape::linear());
    // The case is chosen once, outside the loop, so that each loop holds
    // nothing but the call.
    match case {
        "parse+check" => repeat(repetitions, || {
            let tree = mbexpr::parse(black_box(PARSE_TEXT)).unwrap();
            black_box(mbexpr::check(&tree).unwrap());
        }),
        "fasteval-parse" => repeat(repetitions, || {
            black_box(
                fasteval_parser
                    .parse(black_box(FASTEVAL_TEXT), &mut slab.ps)
                    .unwrap(),
            );
        }),
        "evalexpr-parse" => repeat(repetitions, || {
            black_box(
                evalexpr::build_operator_tree::<evalexpr::DefaultNumericTypes>(black_box(
                    FASTEVAL_TEXT,
                ))
                .unwrap(),
            );
        }),
        "native-value" => repeat(repetitions, || {
            black_box(native_bistop(black_box(x), black_box(v)));
        }),
        "value" => repeat(repetitions, || {
            black_box(value.value(black_box(&POINT)).unwrap());
        }),
        "native-gradient" => repeat(repetitions, || {
            let x = DualSVec64::<2>::from_re(black_box(x)).derivative(0);
            let v = DualSVec64::<2>::from_re(black_box(v)).derivative(1);
            black_box(native_bistop(x, v));
        }),
        "gradient" => repeat(repetitions, || {
            black_box(gradient.dual(black_box(&POINT), &[0, 1]).unwrap());
        }),
        "native-hessian" => repeat(repetitions, || {
            let x = Dual2SVec64::<2>::from_re(black_box(x)).derivative(0);
            let v = Dual2SVec64::<2>::from_re(black_box(v)).derivative(1);
            black_box(native_bistop(x, v));
        }),
        "hessian" => repeat(repetitions, || {
            black_box(hessian.dual(black_box(&POINT), &[0, 1]).unwrap());
        }),
        "native-linear" => repeat(repetitions, || {
            let [x, v, t] = black_box(LINEAR_POINT);
            black_box(native_linear(x, v, t));
        }),
        "linear" => repeat(repetitions, || {
            black_box(linear.value(black_box(&LINEAR_POINT)).unwrap());
        }),
        "fasteval-linear" => repeat(repetitions, || {
            black_box(fasteval_linear_value(
                &fasteval_linear,
                &linear_slab,
                black_box(LINEAR_POINT),
            ));
        }),
        "bare-tape-linear" => repeat(repetitions, || {
            black_box(bare_tape.value(black_box(LINEAR_POINT)));
        }),
        "model-read" => repeat(repetitions, || {
            black_box(model::read(&model_text, FileKind::Adm));
        }),
        "model-read+check" => repeat(repetitions, || {
            let dataset = model::read(&model_text, FileKind::Adm);
            black_box(model::check_model(&model_text, &dataset));
        }),
        _ => {}
    }
}

/// Calls `call` `repetitions` times.
fn repeat(repetitions: u32, mut call: impl FnMut()) {
    for _ in 0..repetitions {
        call();
    }
}

fn main() {
    // `cargo bench` passes `--bench`; a case is the first other argument,
    // and the repetitions the second.
    let mut args = std::env::args()
        .skip(1)
        .filter(|arg| !arg.starts_with("--"));
    let case = args.next();
    let repetitions: Option<u32> = args.next().map(|count| {
        count.parse().unwrap_or_else(|_| {
            eprintln!("repetitions must be a whole number, not `{count}`");
            std::process::exit(2);
        })
    });
    match case {
        Some(case) => match CASES.iter().find(|(name, _)| *name == case) {
            Some(&(name, default)) => {
                let repetitions = repetitions.unwrap_or(default);
                run(name, repetitions);
                println!("{name}: {repetitions} repetitions");
            }
            None => {
                let names: Vec<&str> = CASES.iter().map(|(name, _)| *name).collect();
                eprintln!("unknown case `{case}`; one of: {}", names.join(", "));
                std::process::exit(2);
            }
        },
        None => {
            for (name, _) in CASES {
                run(name, 1);
            }
        }
    }
}
