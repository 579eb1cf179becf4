//! Evaluation, side by side in one run so that the report is ratios:
//! a hand-written native BISTOP (the limit), the same over num-dual,
//! fasteval with BISTOP as a native function, and mbexpr; for the linear
//! expression, native code, mbexpr, fasteval and a bare tape interpreter.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use mbexpr::Order;
use num_dual::{Dual2SVec64, DualSVec64};

#[path = "native.rs"]
mod native;
use native::{BareTape, fasteval_linear, fasteval_linear_value, native_bistop, native_linear};

const BISTOP: &str = "BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1)";
const LINEAR: &str = "-1E4*(x-50)-10*v + 3*sin(2*pi*t)";
const POINT: [f64; 2] = [10.05, 0.7];

fn program(text: &str, inputs: &[&str]) -> mbexpr::Program {
    mbexpr::compile(
        &mbexpr::check(&mbexpr::parse(text).unwrap()).unwrap(),
        inputs,
    )
    .unwrap()
}

fn bistop(c: &mut Criterion) {
    let mut group = c.benchmark_group("bistop");
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    let program = program(BISTOP, &["x", "v"]);

    group.bench_function("value: native f64", |b| {
        b.iter(|| native_bistop(black_box(POINT[0]), black_box(POINT[1])))
    });
    group.bench_function("value: mbexpr", |b| {
        let mut evaluator = program.evaluator::<f64>();
        b.iter(|| evaluator.value(black_box(&POINT)).unwrap())
    });
    group.bench_function("value: fasteval with BISTOP as a native function", |b| {
        use fasteval::{Compiler, Evaler};
        let parser = fasteval::Parser::new();
        let mut slab = fasteval::Slab::new();
        let compiled = parser
            .parse("bistop(x, v)", &mut slab.ps)
            .unwrap()
            .from(&slab.ps)
            .compile(&slab.ps, &mut slab.cs);
        b.iter(|| {
            let (x, v) = (black_box(POINT[0]), black_box(POINT[1]));
            let mut namespace = |name: &str, args: Vec<f64>| match name {
                "x" => Some(x),
                "v" => Some(v),
                "bistop" => Some(native_bistop(args[0], args[1])),
                _ => None,
            };
            compiled.eval(&slab, &mut namespace).unwrap()
        })
    });
    group.bench_function("gradient: native num-dual DualSVec64<2>", |b| {
        b.iter(|| {
            let x = DualSVec64::<2>::from_re(black_box(POINT[0])).derivative(0);
            let v = DualSVec64::<2>::from_re(black_box(POINT[1])).derivative(1);
            native_bistop(x, v)
        })
    });
    group.bench_function("gradient: mbexpr DualSVec64<2>", |b| {
        let mut evaluator = program.evaluator::<DualSVec64<2>>();
        b.iter(|| evaluator.dual(black_box(&POINT), &[0, 1]).unwrap())
    });
    group.bench_function("hessian: native num-dual Dual2SVec64<2>", |b| {
        b.iter(|| {
            let x = Dual2SVec64::<2>::from_re(black_box(POINT[0])).derivative(0);
            let v = Dual2SVec64::<2>::from_re(black_box(POINT[1])).derivative(1);
            native_bistop(x, v)
        })
    });
    group.bench_function("hessian: mbexpr Dual2SVec64<2>", |b| {
        let mut evaluator = program.evaluator::<Dual2SVec64<2>>();
        b.iter(|| evaluator.dual(black_box(&POINT), &[0, 1]).unwrap())
    });
    group.bench_function(
        "hessian: mbexpr Program::evaluate (allocates the result)",
        |b| {
            b.iter(|| {
                program
                    .evaluate(black_box(&POINT), &[0, 1], Order::Hessian)
                    .unwrap()
            })
        },
    );
    group.finish();
}

fn linear(c: &mut Criterion) {
    let mut group = c.benchmark_group("linear");
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    let program = program(LINEAR, &["x", "v", "t"]);
    let point = [10.05, 0.7, 0.3];
    // Every contender computes the same number.
    let expected = native_linear(point[0], point[1], point[2]);
    assert_eq!(program.value(&point).unwrap(), expected);
    assert_eq!(BareTape::linear().value(point), expected);
    let mut slab = fasteval::Slab::new();
    let fasteval_value = fasteval_linear_value(&fasteval_linear(&mut slab), &slab, point);
    assert!((fasteval_value - expected).abs() <= 1e-12 * expected.abs());
    group.bench_function("value: native f64", |b| {
        b.iter(|| {
            native_linear(
                black_box(point[0]),
                black_box(point[1]),
                black_box(point[2]),
            )
        })
    });
    group.bench_function("value: mbexpr", |b| {
        let mut evaluator = program.evaluator::<f64>();
        b.iter(|| evaluator.value(black_box(&point)).unwrap())
    });
    group.bench_function("value: fasteval", |b| {
        let mut slab = fasteval::Slab::new();
        let compiled = fasteval_linear(&mut slab);
        b.iter(|| fasteval_linear_value(&compiled, &slab, black_box(point)))
    });
    group.bench_function("value: bare tape, no checks (the floor of a tape)", |b| {
        let mut tape = black_box(BareTape::linear());
        b.iter(|| tape.value(black_box(point)))
    });
    group.finish();
}

criterion_group!(benches, bistop, linear);
criterion_main!(benches);
