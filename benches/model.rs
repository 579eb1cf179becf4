//! Checking a whole model file: the largest corpus model (368 kB, 1 601
//! markers, about 200 force statements) is read, every expression found,
//! parsed, checked and its references verified.

use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use mbexpr::model::{self, FileKind};

const LARGEST: &str = "../shared/corpus/models/bthornton191__adamspy__FRS5_doe_8_LAUL_analysis.adm";

fn models(c: &mut Criterion) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(LARGEST);
    let Ok(text) = std::fs::read_to_string(&path) else {
        eprintln!(
            "note: {} not found; model benchmark skipped",
            path.display()
        );
        return;
    };
    let mut group = c.benchmark_group("model");
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(20)
        .throughput(Throughput::Bytes(text.len() as u64));
    group.bench_function("read", |b| b.iter(|| model::read(&text, FileKind::Adm)));
    group.bench_function("read and check", |b| {
        b.iter(|| {
            let dataset = model::read(&text, FileKind::Adm);
            model::check_model(&text, &dataset)
        })
    });
    group.finish();
}

criterion_group!(benches, models);
criterion_main!(benches);
