//! Parse and check: the headline BISTOP call, side by side with fasteval
//! and evalexpr (the two references the issue names) parsing a call of the
//! same shape, and the throughput over the real corpus.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};

const BISTOP: &str = "BISTOP(DX(2,1,1), VX(2,1,1,1), -10, 10, 1e5, 2.2, 100, 0.1)";
/// The same shape for fasteval and evalexpr, which have no markers: a call
/// of 8 arguments, two of them calls.
const FASTEVAL_CALL: &str = "bistop(dx(2,1,1), vx(2,1,1,1), -10, 10, 1e5, 2.2, 100, 0.1)";

/// The corpus's expressions, read in place (third-party text, not copied here).
fn corpus() -> Option<Vec<String>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../shared/corpus/expressions.tsv"
    );
    let text = std::fs::read_to_string(path).ok()?;
    Some(
        text.lines()
            .skip(1)
            .filter_map(|line| line.split('\t').nth(2).map(str::to_string))
            .collect(),
    )
}

fn parse(c: &mut Criterion) {
    let mut group = c.benchmark_group("parse");
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    group.bench_function("mbexpr parse + check BISTOP", |b| {
        b.iter(|| mbexpr::check(&mbexpr::parse(black_box(BISTOP)).unwrap()).unwrap())
    });
    group.bench_function("mbexpr parse BISTOP", |b| {
        b.iter(|| mbexpr::parse(black_box(BISTOP)).unwrap())
    });
    group.bench_function("fasteval parse 8-argument call", |b| {
        let parser = fasteval::Parser::new();
        let mut slab = fasteval::Slab::new();
        b.iter(|| {
            parser
                .parse(black_box(FASTEVAL_CALL), &mut slab.ps)
                .unwrap()
        })
    });
    group.bench_function("evalexpr parse 8-argument call", |b| {
        b.iter(|| {
            evalexpr::build_operator_tree::<evalexpr::DefaultNumericTypes>(black_box(FASTEVAL_CALL))
                .unwrap()
        })
    });
    match corpus() {
        Some(expressions) => {
            let bytes: usize = expressions.iter().map(String::len).sum();
            group.throughput(Throughput::Bytes(bytes as u64));
            group.bench_function("mbexpr parse + check the corpus (702 expressions)", |b| {
                b.iter(|| {
                    for expression in &expressions {
                        let tree = mbexpr::parse(expression).unwrap();
                        black_box(mbexpr::check(&tree).unwrap());
                    }
                })
            });
        }
        None => eprintln!("note: ../shared/corpus not found; corpus throughput skipped"),
    }
    group.finish();
}

criterion_group!(benches, parse);
criterion_main!(benches);
