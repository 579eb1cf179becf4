//! A contact force over two markers costs the same in a scene of 1 000 bodies
//! as in a scene of 2: compiling against a scene keeps only what the
//! expression uses.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use mbexpr::scene::{Body, Marker};
use mbexpr::{Order, Scene};
use nalgebra::Vector3;

const CONTACT: &str =
    "BISTOP(DX(ball, wall, wall), VX(ball, wall, wall, wall), -0.5, 0.5, 1e5, 2.2, 100, 0.05)";

/// The ball and the wall, and `extra` more bodies with a marker each.
fn scene(extra: usize) -> Scene {
    let mut scene = Scene::default();
    let mut ball = Body::new("ball");
    ball.position = Vector3::new(0.52, 0.0, 0.0);
    ball.velocity = Vector3::new(0.7, 0.0, 0.0);
    scene.bodies.push(ball);
    scene.bodies.push(Body::new("wall_body"));
    for (name, body) in [("ball", 0), ("wall", 1)] {
        let mut marker = Marker::new(Some(body));
        marker.name = Some(name.to_string());
        scene.markers.push(marker);
    }
    for index in 0..extra {
        let mut body = Body::new(format!("part{index}"));
        body.position = Vector3::new(index as f64, 1.0, 2.0);
        scene.bodies.push(body);
        let mut marker = Marker::new(Some(scene.bodies.len() - 1));
        marker.id = Some(1000 + index as u64);
        scene.markers.push(marker);
    }
    scene
}

fn scenes(c: &mut Criterion) {
    let checked = mbexpr::check(&mbexpr::parse(CONTACT).unwrap()).unwrap();
    let mut group = c.benchmark_group("scene");
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for (label, extra) in [("2 bodies", 0), ("1000 bodies", 998)] {
        let scene = scene(extra);
        let program = mbexpr::compile_in_scene(&checked, &scene.input_names(), &scene).unwrap();
        let values = scene.values(program.inputs()).unwrap();
        let wrt: Vec<usize> = ["ball.x", "ball.vx"]
            .iter()
            .map(|name| program.input_index(name).unwrap())
            .collect();
        group.bench_function(format!("value, {label}"), |b| {
            let mut evaluator = program.evaluator::<f64>();
            b.iter(|| evaluator.value(black_box(&values)).unwrap())
        });
        group.bench_function(format!("Hessian in ball.x, ball.vx, {label}"), |b| {
            b.iter(|| {
                program
                    .evaluate(black_box(&values), &wrt, Order::Hessian)
                    .unwrap()
            })
        });
        group.bench_function(format!("compile, {label}"), |b| {
            b.iter(|| {
                mbexpr::compile_in_scene(&checked, &scene.input_names(), black_box(&scene)).unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, scenes);
criterion_main!(benches);
