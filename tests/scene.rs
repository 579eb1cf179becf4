//! Scenes: every measure against hand-computed values in rotated and moving
//! frames, rates against finite differences along an analytic trajectory,
//! angle conventions, derivatives with respect to states, and errors.

use mbexpr::scene::{Body, Marker};
use mbexpr::{Order, Scene, check as check_tree, compile_in_scene, parse};
use nalgebra::{UnitQuaternion, Vector3};

/// Evaluates `text` in `scene` with derivatives in `wrt`.
fn evaluate(
    scene: &Scene,
    text: &str,
    wrt: &[&str],
    order: Order,
) -> Result<mbexpr::Evaluation, String> {
    let tree = parse(text).map_err(|error| error.to_string())?;
    let checked = check_tree(&tree).map_err(|errors| errors.to_string())?;
    let mut inputs = scene.input_names();
    inputs.extend(wrt.iter().map(|name| name.to_string()));
    let program =
        compile_in_scene(&checked, &inputs, scene).map_err(|errors| errors.to_string())?;
    let values = scene
        .values(program.inputs())
        .map_err(|error| error.to_string())?;
    let directions: Vec<usize> = wrt
        .iter()
        .map(|name| program.input_index(name).unwrap())
        .collect();
    program
        .evaluate(&values, &directions, order)
        .map_err(|error| error.to_string())
}

fn value(scene: &Scene, text: &str) -> f64 {
    evaluate(scene, text, &[], Order::Value)
        .unwrap_or_else(|error| panic!("{text}: {error}"))
        .value
}

/// The value, or the error, for the snapshot tables.
fn check(scene: &Scene, text: &str) -> String {
    match evaluate(scene, text, &[], Order::Value) {
        Ok(evaluation) => format!("{:.9}", evaluation.value + 0.0),
        Err(error) => format!("error: {error}"),
    }
}

fn rotation(axis: [f64; 3], angle: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(Vector3::from(axis)), angle)
}

/// Two bodies, turned and moving, with accelerations; markers on both and on ground.
fn two_bodies() -> Scene {
    let mut scene = Scene::default();
    let mut a = Body::new("a");
    a.position = Vector3::new(1.0, 2.0, 0.5);
    a.orientation = rotation([0.0, 0.0, 1.0], 0.5);
    a.velocity = Vector3::new(0.3, -0.2, 0.1);
    a.angular_velocity = Vector3::new(0.0, 0.0, 1.5);
    a.acceleration = Some(Vector3::new(0.0, 0.1, -9.81));
    a.angular_acceleration = Some(Vector3::new(0.2, 0.0, 0.3));
    let mut b = Body::new("b");
    b.position = Vector3::new(-1.0, 0.5, 2.0);
    b.orientation = rotation([1.0, 1.0, 0.0], 0.8);
    b.velocity = Vector3::new(-0.5, 0.0, 0.4);
    b.angular_velocity = Vector3::new(0.7, -0.3, 0.2);
    b.acceleration = Some(Vector3::new(1.0, 0.0, 0.0));
    b.angular_acceleration = Some(Vector3::new(0.0, -0.4, 0.0));
    scene.bodies = vec![a, b];
    let marker =
        |name: &str, id: u64, body: Option<usize>, position: [f64; 3], orientation| Marker {
            id: Some(id),
            name: Some(name.to_string()),
            body,
            position: Vector3::from(position),
            orientation,
        };
    scene.markers = vec![
        marker(
            "ai",
            11,
            Some(0),
            [0.2, 0.0, 0.1],
            rotation([0.0, 1.0, 0.0], 0.3),
        ),
        marker(
            "bj",
            21,
            Some(1),
            [0.0, -0.4, 0.3],
            rotation([1.0, 0.0, 0.0], -0.6),
        ),
        marker(
            "gk",
            31,
            None,
            [0.5, 0.5, 0.0],
            rotation([0.0, 0.0, 1.0], 1.0),
        ),
    ];
    scene
}

#[test]
fn every_measure_in_rotated_and_moving_frames() {
    let scene = two_bodies();
    let measures = [
        "DX(ai)",
        "DY(ai, bj)",
        "DZ(ai, bj, gk)",
        "DM(ai, bj)",
        "DM(11, 0)",
        "VX(ai, bj, gk)",
        "VY(ai, bj, gk, bj)",
        "VZ(ai, bj, bj, ai)",
        "VM(ai, bj)",
        "VM(ai, bj, bj)",
        "VR(ai, bj)",
        "VR(ai, bj, bj)",
        "ACCX(ai, bj, gk)",
        "ACCY(ai, bj, gk, bj)",
        "ACCZ(ai, 0, 0, ai)",
        "ACCM(ai, bj)",
        "ACCM(ai, bj, bj)",
        "WX(ai, bj, gk)",
        "WY(ai)",
        "WZ(ai, bj, bj)",
        "WM(ai, bj)",
        "WDTX(ai, bj, gk, bj)",
        "WDTY(ai, bj)",
        "WDTZ(ai, bj, bj, ai)",
        "WDTM(ai, bj, bj)",
        "AX(ai, bj)",
        "AY(ai, bj)",
        "AZ(ai, gk)",
        "PSI(ai, bj)",
        "THETA(ai, bj)",
        "PHI(ai, bj)",
        "YAW(ai, bj)",
        "PITCH(ai, bj)",
        "ROLL(ai, bj)",
        "DX(bj, ai, ai) - DX(ai, bj, ai)",
    ];
    let table: String = measures
        .iter()
        .map(|text| format!("{text:<32} {}\n", check(&scene, text)))
        .collect();
    insta::assert_snapshot!(table);
}

#[test]
fn hand_computed_values() {
    // Body turned 90 degrees about z, at (1, 2, 0), spinning at 2 rad/s about z,
    // moving at (0.5, 0, 0); a marker 1 along its x axis, i.e. at (1, 3, 0).
    let mut scene = Scene::default();
    let mut body = Body::new("arm");
    body.position = Vector3::new(1.0, 2.0, 0.0);
    body.orientation = rotation([0.0, 0.0, 1.0], std::f64::consts::FRAC_PI_2);
    body.velocity = Vector3::new(0.5, 0.0, 0.0);
    body.angular_velocity = Vector3::new(0.0, 0.0, 2.0);
    body.acceleration = Some(Vector3::zeros());
    body.angular_acceleration = Some(Vector3::zeros());
    scene.bodies.push(body);
    let mut tip = Marker::new(Some(0));
    tip.name = Some("tip".into());
    tip.position = Vector3::new(1.0, 0.0, 0.0);
    let mut base = Marker::new(Some(0));
    base.name = Some("base".into());
    scene.markers = vec![tip, base];
    let close = |text: &str, want: f64| {
        let got = value(&scene, text);
        assert!((got - want).abs() < 1e-12, "{text}: got {got}, want {want}");
    };
    close("DX(tip)", 1.0);
    close("DY(tip)", 3.0);
    close("DX(tip, base, base)", 1.0); // along the arm's x axis
    close("DY(tip, base)", 1.0); // along ground y
    close("DM(tip)", 10f64.sqrt());
    // Velocity of the tip in ground: v + w x r = (0.5, 0, 0) + 2 z x (0, 1, 0) = (-1.5, 0, 0).
    close("VX(tip)", -1.5);
    close("VY(tip)", 0.0);
    // Seen from the arm (l = base) the tip does not move.
    close("VX(tip, base, 0, base)", 0.0);
    close("VM(tip, base, base)", 0.0);
    // In ground, relative to the base: only the rotation, 2 z x (0, 1, 0).
    close("VX(tip, base)", -2.0);
    close("VR(tip, base)", 0.0);
    // Centripetal acceleration of the tip: -w^2 r = -4 (0, 1, 0).
    close("ACCY(tip, base)", -4.0);
    close("ACCY(tip, base, 0, base)", 0.0);
    close("WZ(tip)", 2.0);
    close("AZ(tip)", std::f64::consts::FRAC_PI_2);
    close("YAW(tip)", std::f64::consts::FRAC_PI_2);
    close("PSI(tip) + PHI(tip)", std::f64::consts::FRAC_PI_2);
}

#[test]
fn angle_conventions() {
    let (psi, theta, phi) = (0.4, 0.9, -1.1);
    let mut scene = Scene::default();
    let mut euler = Body::new("euler");
    euler.orientation = mbexpr::scene::euler_313(psi, theta, phi);
    let mut cardan = Body::new("cardan");
    let (yaw, pitch, roll) = (0.3, 0.5, -0.7);
    cardan.orientation = rotation([0.0, 0.0, 1.0], yaw)
        * rotation([0.0, 1.0, 0.0], pitch)
        * rotation([1.0, 0.0, 0.0], roll);
    let mut about_x = Body::new("about_x");
    about_x.orientation = rotation([1.0, 0.0, 0.0], 0.6);
    let mut about_y = Body::new("about_y");
    about_y.orientation = rotation([0.0, 1.0, 0.0], -0.6);
    scene.bodies = vec![euler, cardan, about_x, about_y];
    scene.markers = (0..4)
        .map(|body| {
            let mut marker = Marker::new(Some(body));
            marker.id = Some(body as u64 + 1);
            marker
        })
        .collect();
    let close = |text: &str, want: f64| {
        let got = value(&scene, text);
        assert!((got - want).abs() < 1e-12, "{text}: got {got}, want {want}");
    };
    close("PSI(1)", psi);
    close("THETA(1)", theta);
    close("PHI(1)", phi);
    close("YAW(2)", yaw);
    close("PITCH(2)", -pitch); // the automotive sign
    close("ROLL(2)", roll);
    close("AX(3)", 0.6);
    close("AY(4)", -0.6);
    close("AX(1, 1) + AY(2, 2) + AZ(3, 3)", 0.0);
    // Turned about several axes, each is Adams' projection (its AX, AY and
    // AZ pages): AX = ATAN2(-zi.yj, zi.zj), AY = ATAN2(zi.xj, zi.zj),
    // AZ = ATAN2(xi.yj, xi.xj), with zi = (sin psi sin theta, -cos psi sin
    // theta, cos theta) and xi = (cos psi cos phi - sin psi cos theta sin
    // phi, sin psi cos phi + cos psi cos theta sin phi, ...) for 3-1-3 angles.
    let (zx, zy, zz) = (
        psi.sin() * theta.sin(),
        -psi.cos() * theta.sin(),
        theta.cos(),
    );
    let xx = psi.cos() * phi.cos() - psi.sin() * theta.cos() * phi.sin();
    let xy = psi.sin() * phi.cos() + psi.cos() * theta.cos() * phi.sin();
    close("AX(1)", (-zy).atan2(zz));
    close("AY(1)", zx.atan2(zz));
    close("AZ(1)", xy.atan2(xx));
}

/// A body on an analytic trajectory: position, a rotation about a fixed axis,
/// and their first and second time derivatives, at time `t`.
fn on_trajectory(t: f64) -> Scene {
    let axis = Vector3::new(1.0, 2.0, 2.0) / 3.0;
    let angle = |t: f64| 0.3 * t + 0.2 * t * t;
    let mut a = Body::new("a");
    a.position = Vector3::new(t.cos(), (2.0 * t).sin(), 0.5 * t * t);
    a.velocity = Vector3::new(-t.sin(), 2.0 * (2.0 * t).cos(), t);
    a.acceleration = Some(Vector3::new(-t.cos(), -4.0 * (2.0 * t).sin(), 1.0));
    a.orientation = UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle(t));
    a.angular_velocity = axis * (0.3 + 0.4 * t);
    a.angular_acceleration = Some(axis * 0.4);
    let mut b = Body::new("b");
    b.position = Vector3::new(0.2 * t, -0.5, t.sin());
    b.velocity = Vector3::new(0.2, 0.0, t.cos());
    b.acceleration = Some(Vector3::new(0.0, 0.0, -t.sin()));
    b.orientation = rotation([0.0, 0.0, 1.0], 1.5 * t);
    b.angular_velocity = Vector3::new(0.0, 0.0, 1.5);
    b.angular_acceleration = Some(Vector3::zeros());
    let mut scene = Scene {
        time: t,
        bodies: vec![a, b],
        ..Scene::default()
    };
    let mut i = Marker::new(Some(0));
    i.name = Some("i".into());
    i.position = Vector3::new(0.3, -0.1, 0.2);
    i.orientation = rotation([0.0, 1.0, 0.0], 0.4);
    let mut j = Marker::new(Some(1));
    j.name = Some("j".into());
    j.position = Vector3::new(0.0, 0.5, 0.0);
    scene.markers = vec![i, j];
    scene
}

#[test]
fn rates_agree_with_finite_differences_of_positions() {
    let t = 0.7;
    let h = 1e-4;
    let at = |text: &str, time: f64| value(&on_trajectory(time), text);
    // Central differences: first derivative O(h^2), second O(h^2).
    let rate = |text: &str| (at(text, t + h) - at(text, t - h)) / (2.0 * h);
    let curvature = |text: &str| (at(text, t + h) - 2.0 * at(text, t) + at(text, t - h)) / (h * h);
    let scene = on_trajectory(t);
    let pairs = [
        ("VX(i, j, j, j)", rate("DX(i, j, j)"), 1e-7),
        ("VY(i, j, j, j)", rate("DY(i, j, j)"), 1e-7),
        ("VZ(i, j, i, i)", rate("DZ(i, j, i)"), 1e-7),
        ("VX(i, 0, 0, 0)", rate("DX(i)"), 1e-7),
        ("VR(i, j)", rate("DM(i, j)"), 1e-7),
        ("ACCX(i, j, j, j)", curvature("DX(i, j, j)"), 1e-5),
        ("ACCZ(i, j, i, i)", curvature("DZ(i, j, i)"), 1e-5),
        ("ACCY(i, 0, 0, 0)", curvature("DY(i)"), 1e-5),
        ("WDTX(i, j, j, j)", rate("WX(i, j, j)"), 1e-7),
        ("WDTZ(i, j, i, i)", rate("WZ(i, j, i)"), 1e-7),
        ("WZ(j)", rate("AZ(j)"), 1e-7),
    ];
    for (text, want, tolerance) in pairs {
        let got = value(&scene, text);
        assert!(
            (got - want).abs() < tolerance,
            "{text}: got {got}, finite difference {want}"
        );
    }
}

#[test]
fn derivatives_with_respect_to_states_agree_with_finite_differences() {
    let expression = "BISTOP(DX(i, j, j), VX(i, j, j, j), -0.5, 0.5, 1e3, 1.5, 10, 0.2) + DM(i, j)**2 + WZ(i, j, j)";
    let mut scene = on_trajectory(0.7);
    // Put the gap variable inside the lower stop's damping ramp.
    let dx = value(&scene, "DX(i, j, j)");
    scene.bodies[0].position.x -= dx + 0.6;
    let components = [
        "a.x", "a.y", "a.z", "a.rx", "a.ry", "a.rz", "a.vx", "a.vy", "a.wz", "b.x", "b.rz", "b.wz",
    ];
    let result = evaluate(&scene, expression, &components, Order::Gradient).unwrap();
    let gradient = result.gradient.unwrap();
    let h = 1e-6;
    for (index, component) in components.iter().enumerate() {
        let shifted = |step: f64| {
            let mut moved = scene.clone();
            let (body, suffix) = component.split_once('.').unwrap();
            let body = &mut moved.bodies[usize::from(body == "b")];
            let axis = match &suffix[suffix.len() - 1..] {
                "x" => 0,
                "y" => 1,
                _ => 2,
            };
            match &suffix[..suffix.len() - 1] {
                "" => body.position[axis] += step,
                "v" => body.velocity[axis] += step,
                "w" => body.angular_velocity[axis] += step,
                _ => {
                    let mut turn = Vector3::zeros();
                    turn[axis] = step;
                    body.orientation = UnitQuaternion::from_scaled_axis(turn) * body.orientation;
                }
            }
            value(&moved, expression)
        };
        let difference = (shifted(h) - shifted(-h)) / (2.0 * h);
        let got = gradient[index];
        assert!(
            (got - difference).abs() <= 1e-5 * (1.0 + difference.abs()),
            "d/d{component}: dual {got}, finite difference {difference}"
        );
    }
}

#[test]
fn second_derivatives_through_the_kinematics_are_symmetric_and_match_gradients() {
    let scene = on_trajectory(0.3);
    let expression = "DM(i, j)**3 + VX(i, j, j, j)*DY(i, j, j)";
    let wrt = ["a.x", "a.rz", "b.wz", "a.vx"];
    let hessian = evaluate(&scene, expression, &wrt, Order::Hessian)
        .unwrap()
        .hessian
        .unwrap();
    assert!((hessian.clone() - hessian.transpose()).abs().max() < 1e-9);
    // Column a.x of the Hessian against a finite difference of the gradient.
    let gradient_at = |step: f64| {
        let mut moved = scene.clone();
        moved.bodies[0].position.x += step;
        evaluate(&moved, expression, &wrt, Order::Gradient)
            .unwrap()
            .gradient
            .unwrap()
    };
    let h = 1e-6;
    let column = (gradient_at(h) - gradient_at(-h)) / (2.0 * h);
    for row in 0..wrt.len() {
        let (got, want) = (hessian[(row, 0)], column[row]);
        assert!(
            (got - want).abs() <= 1e-5 * (1.0 + want.abs()),
            "row {row}: {got} vs {want}"
        );
    }
}

#[test]
fn errors_name_what_is_missing() {
    let mut scene = two_bodies();
    scene.bodies[0].acceleration = None;
    let report: String = [
        "DX(aj, bj)",
        "DX(99)",
        "ACCX(ai)",
        "WDTZ(bj, ai)",
        "DM(ai, ai)",
        "VR(ai, ai)",
        "DX(ai) + x",
    ]
    .iter()
    .map(|text| format!("{text}\n  => {}\n", check(&scene, text)))
    .collect();
    insta::assert_snapshot!(report);
}

#[test]
fn only_the_markers_and_bodies_used_are_kept() {
    let mut scene = two_bodies();
    for index in 0..1000 {
        scene.bodies.push(Body::new(format!("extra{index}")));
        let mut marker = Marker::new(Some(scene.bodies.len() - 1));
        marker.id = Some(1000 + index as u64);
        scene.markers.push(marker);
    }
    let checked = check_tree(&parse("DX(ai, gk)").unwrap()).unwrap();
    let program = compile_in_scene(&checked, &scene.input_names(), &scene).unwrap();
    let states: Vec<&String> = program
        .inputs()
        .iter()
        .filter(|name| name.contains('.'))
        .collect();
    assert_eq!(states.len(), 12, "{states:?}");
    assert!(states.iter().all(|name| name.starts_with("a.")));
}

#[test]
fn scene_files_read_and_refuse_with_reasons() {
    let examples = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
    for file in ["ball_between_walls.toml", "slider_in_slot.toml"] {
        let text = std::fs::read_to_string(examples.join(file)).unwrap();
        let scene = Scene::from_toml(&text).unwrap_or_else(|error| panic!("{file}: {error}"));
        for (name, expression) in &scene.expressions {
            evaluate(&scene, expression, &[], Order::Value)
                .unwrap_or_else(|error| panic!("{file} {name}: {error}"));
        }
    }
    let refusals: String = [
        "[[body]]\nname = \"a\"\nposition = [1, 2]",
        "[[body]]\nname = \"a\"\nquaternion = [0, 0, 0, 0]",
        "[[body]]\nname = \"a\"\neuler = [1, 2, 3]\nangles = \"grads\"",
        "[[marker]]\nname = \"m\"\nbody = \"nobody\"",
        "[[marker]]\nid = 0",
        "speed = 3",
        "[variables]\nk = \"stiff\"",
        "time = 1\n[variables]\nc = 2\nk = nan",
        "[variables]\nk = -inf",
        "time = +inf",
        "[[body]]\nname = \"a\"\nvelocity = [0, nan, 0]",
        "[[marker]]\nname = \"m\"\neuler = [0, 0, inf]",
        "mode = 99",
        "mode = -1",
        "mode = 1.5",
        "mode = 2",
        "mode = 7\n[variables]\nk = 1_000.5",
        "[[body]]\nname = \"ball\"\n[[marker]]\nname = \"m\"\nbody = \"bal\"\n[[marker]]\nid = 0\n[variables]\nk = \"stiff\"\nc = inf",
        "[expressions]\ngap = \"DX(m, 0) - \"\nforce = \"STPE(TIME, 0, 0, 1, 1) + LOG(0)\"",
    ]
    .iter()
    .map(|text| match Scene::from_toml(text) {
        Ok(_) => format!("{text:?}\n  => accepted\n"),
        Err(errors) => {
            let mut found = format!("{text:?}\n");
            for error in &errors {
                let at = error.file_span().map_or(String::new(), |span| {
                    format!("{}: ", mbexpr::Location::of(text, span.start))
                });
                found += &format!("  => {at}{error}\n");
            }
            found
        }
    })
    .collect();
    insta::assert_snapshot!(refusals);
}

/// A body `spin` at rest at the origin, its marker 1 at its origin.
fn spinning() -> Scene {
    let mut marker = Marker::new(Some(0));
    marker.id = Some(1);
    Scene {
        bodies: vec![Body::new("spin")],
        markers: vec![marker],
        ..Scene::default()
    }
}

#[test]
fn angles_stay_continuous_over_a_run() {
    let scene = spinning();
    let checked = check_tree(&parse("AZ(1)").unwrap()).unwrap();
    let program = compile_in_scene(&checked, &scene.input_names(), &scene).unwrap();
    let mut values = scene.values(program.inputs()).unwrap();
    let turn = program.input_index("spin.rz").unwrap();
    let mut run = program.run();
    // Three turns and a half forwards, then back past the start.
    let angles = (0..=120)
        .map(|step| f64::from(step) * 0.1)
        .chain((0..=150).map(|step| 12.0 - f64::from(step) * 0.1));
    for angle in angles {
        values[turn] = angle;
        let continued = run.evaluate(&values, &[turn], Order::Gradient).unwrap();
        let principal = program.evaluate(&values, &[turn], Order::Gradient).unwrap();
        assert!(
            (continued.value - angle).abs() < 1e-9,
            "{angle}: {}",
            continued.value
        );
        assert!(principal.value.abs() <= std::f64::consts::PI + 1e-12);
        let turns = (angle - principal.value) / std::f64::consts::TAU;
        assert!(
            (turns - turns.round()).abs() < 1e-9,
            "{angle}: {}",
            principal.value
        );
        assert_eq!(continued.gradient, principal.gradient);
    }
}

/// A body's rotation state of any size turns its markers: 1e-160 gives what
/// 0 gives (its angle's square, a subnormal, met the square root's
/// curvature: NaN), and the series below an angle of 1e-3 meets Rodrigues'
/// formula above it.
#[test]
fn rotation_states_of_every_size() {
    let scene = two_bodies();
    let text = "DY(ai, gk, gk) + AX(ai, gk)";
    let checked = check_tree(&parse(text).unwrap()).unwrap();
    let mut inputs = scene.input_names();
    inputs.push("a.rx".to_string());
    let program = compile_in_scene(&checked, &inputs, &scene).unwrap();
    let mut values = scene.values(program.inputs()).unwrap();
    let rx = program.input_index("a.rx").unwrap();
    let mut at = |angle: f64| {
        values[rx] = angle;
        program.evaluate(&values, &[rx], Order::Hessian).unwrap()
    };
    let close = |a: &mbexpr::Evaluation, b: &mbexpr::Evaluation, tolerance: f64| {
        let entries = |e: &mbexpr::Evaluation| {
            let mut all = vec![e.value];
            all.extend(e.gradient.iter().flatten());
            all.extend(e.hessian.iter().flatten());
            all
        };
        entries(a)
            .iter()
            .zip(entries(b))
            .all(|(a, b)| (a - b).abs() <= tolerance * (1.0 + b.abs()))
    };
    let zero = at(0.0);
    assert!(close(&at(1e-200), &zero, 1e-15));
    assert!(close(&at(-1e-300), &zero, 1e-15));
    assert!(close(&at(1e-160), &zero, 1e-15));
    let (below, above) = (at(1e-3 * (1.0 - 1e-12)), at(1e-3 * (1.0 + 1e-12)));
    assert!(close(&below, &above, 1e-9), "{below:?} vs {above:?}");
}

/// ORIENT recovers the angles a part was turned by in each of the twelve
/// body-fixed and twelve space-fixed sequences, relative to a turned
/// marker; its Euler parameters, Rodriguez parameters and direction cosines
/// are nalgebra's quaternion and matrix of the same rotation; its gradient
/// matches finite differences; systems and components out of range are
/// refused at the call.
#[test]
fn orient_gives_every_orientation_system() {
    let sequences = [
        [0, 1, 2],
        [1, 2, 0],
        [2, 0, 1],
        [0, 2, 1],
        [1, 0, 2],
        [2, 1, 0],
        [0, 1, 0],
        [0, 2, 0],
        [1, 0, 1],
        [1, 2, 1],
        [2, 0, 2],
        [2, 1, 2],
    ];
    let about = |axis: usize, angle: f64| {
        let mut direction = [0.0; 3];
        direction[axis] = 1.0;
        rotation(direction, angle)
    };
    let reference = rotation([0.3, -0.5, 0.8], 0.9);
    for (index, sequence) in sequences.iter().enumerate() {
        let [p, q, r] = *sequence;
        let angles = [0.4, if p == r { 0.7 } else { -0.6 }, -1.1];
        for space_fixed in [false, true] {
            let turn = if space_fixed {
                about(r, angles[2]) * about(q, angles[1]) * about(p, angles[0])
            } else {
                about(p, angles[0]) * about(q, angles[1]) * about(r, angles[2])
            };
            let mut scene = Scene::default();
            let mut body = Body::new("turned");
            body.orientation = reference * turn;
            scene.bodies.push(body);
            let mut i = Marker::new(Some(0));
            i.id = Some(1);
            let mut j = Marker::new(None);
            j.id = Some(2);
            j.orientation = reference;
            scene.markers = vec![i, j];
            let system = index + 1 + if space_fixed { 12 } else { 0 };
            for (component, angle) in angles.iter().enumerate() {
                let text = format!("ORIENT({system}, {}, 1, 2)", component + 1);
                let got = value(&scene, &text);
                assert!((got - angle).abs() < 1e-12, "{text}: {got}, want {angle}");
            }
        }
    }
    let scene = two_bodies();
    let relative = (scene.bodies[1].orientation * scene.markers[1].orientation).inverse()
        * scene.bodies[0].orientation
        * scene.markers[0].orientation;
    let sign = relative.w.signum();
    let parameters = [relative.w, relative.i, relative.j, relative.k].map(|e| e * sign);
    let matrix = relative.to_rotation_matrix().into_inner();
    let mut wanted: Vec<(String, f64)> = Vec::new();
    for (component, parameter) in parameters.iter().enumerate() {
        wanted.push((format!("ORIENT(27, {}, ai, bj)", component + 1), *parameter));
        if component > 0 {
            let rodriguez = parameter / parameters[0];
            wanted.push((format!("ORIENT(28, {component}, ai, bj)"), rodriguez));
        }
    }
    for component in 0..9 {
        let cosine = matrix[(component % 3, component / 3)];
        wanted.push((format!("ORIENT(29, {}, ai, bj)", component + 1), cosine));
    }
    for (text, want) in wanted {
        let got = value(&scene, &text);
        assert!((got - want).abs() < 1e-12, "{text}: {got}, want {want}");
    }
    // The gradient in the turning states of both parts.
    let expression = "ORIENT(5, 2, ai, bj) + ORIENT(27, 3, ai, bj) * ORIENT(9, 1, ai, bj)";
    let components = ["a.rx", "a.ry", "a.rz", "b.rx", "b.rz"];
    let gradient = evaluate(&scene, expression, &components, Order::Gradient)
        .unwrap()
        .gradient
        .unwrap();
    let h = 1e-6;
    for (index, component) in components.iter().enumerate() {
        let shifted = |step: f64| {
            let mut moved = scene.clone();
            let body = usize::from(component.starts_with('b'));
            let mut turn = Vector3::zeros();
            turn[match component.as_bytes()[3] {
                b'x' => 0,
                b'y' => 1,
                _ => 2,
            }] = step;
            moved.bodies[body].orientation =
                UnitQuaternion::from_scaled_axis(turn) * moved.bodies[body].orientation;
            value(&moved, expression)
        };
        let difference = (shifted(h) - shifted(-h)) / (2.0 * h);
        assert!(
            (gradient[index] - difference).abs() < 1e-7,
            "d/d{component}: {} vs {difference}",
            gradient[index]
        );
    }
    let refusals: String = [
        "ORIENT(25, 1, ai, bj)",
        "ORIENT(27, 5, ai)",
        "ORIENT(0, 1, ai)",
    ]
    .iter()
    .map(|text| format!("{text}\n  => {}\n", check(&scene, text)))
    .collect();
    insta::assert_snapshot!(refusals);
}

/// INCANG: the angle at j between the lines to i and to k (or between i-j
/// and k-l), positive where the scene places the markers and measured about
/// the normal drawn there after, so that it passes pi without a jump in a
/// run; against the angles a marker is turned to by hand.
#[test]
fn incang_measures_about_the_drawn_normal() {
    let mut scene = Scene::default();
    let mut arm = Body::new("arm");
    arm.position = Vector3::new(1.0, 1.0, 0.0);
    scene.bodies.push(arm);
    let marker = |id: u64, body: Option<usize>, position: [f64; 3]| {
        let mut marker = Marker::new(body);
        marker.id = Some(id);
        marker.position = Vector3::from(position);
        marker
    };
    // The arm's tip at 0.3 rad from the x axis around its pivot (1, 1, 0).
    let tip = [0.3f64.cos(), 0.3f64.sin(), 0.0];
    scene.markers = vec![
        marker(1, None, [3.0, 1.0, 0.0]),
        marker(2, Some(0), [0.0, 0.0, 0.0]),
        marker(3, Some(0), tip),
        marker(4, None, [0.0, 0.0, 5.0]),
        marker(5, None, [0.0, 2.0, 5.0]),
    ];
    let close = |scene: &Scene, text: &str, want: f64| {
        let got = value(scene, text);
        assert!((got - want).abs() < 1e-12, "{text}: {got}, want {want}");
    };
    close(&scene, "INCANG(1, 2, 3)", 0.3);
    close(&scene, "INCANG(3, 2, 1)", 0.3);
    // Between the x axis and a line along y, four markers.
    close(&scene, "INCANG(1, 2, 4, 5)", std::f64::consts::FRAC_PI_2);
    // Turning the arm on: the angle grows past pi in a run.
    let checked = check_tree(&parse("INCANG(1, 2, 3)").unwrap()).unwrap();
    let program = compile_in_scene(&checked, &scene.input_names(), &scene).unwrap();
    let mut values = scene.values(program.inputs()).unwrap();
    let turn = program.input_index("arm.rz").unwrap();
    let mut run = program.run();
    for step in 0..=60 {
        let angle = f64::from(step) * 0.1;
        values[turn] = angle;
        let got = run.evaluate(&values, &[turn], Order::Gradient).unwrap();
        assert!(
            (got.value - (0.3 + angle)).abs() < 1e-9,
            "{angle}: {}",
            got.value
        );
        assert!((got.gradient.unwrap()[0] - 1.0).abs() < 1e-9);
    }
}

/// ORIENT's Euler parameters run on continuously through `e0 = 0` over a
/// run (a part turning twice about z: `e0 = cos θ/2`, `e3 = sin θ/2`, as
/// Adams gives them), where one evaluation alone gives `e0` not negative.
#[test]
fn euler_parameters_run_on_through_a_half_turn() {
    let scene = spinning();
    for component in [1, 4] {
        let text = format!("ORIENT(27, {component}, 1)");
        let checked = check_tree(&parse(&text).unwrap()).unwrap();
        let program = compile_in_scene(&checked, &scene.input_names(), &scene).unwrap();
        let mut values = scene.values(program.inputs()).unwrap();
        let turn = program.input_index("spin.rz").unwrap();
        let mut run = program.run();
        for step in 0..=130 {
            let angle = f64::from(step) * 0.1;
            values[turn] = angle;
            let want = if component == 1 {
                (angle / 2.0).cos()
            } else {
                (angle / 2.0).sin()
            };
            let continued = run.evaluate(&values, &[turn], Order::Gradient).unwrap();
            let alone = program.evaluate(&values, &[turn], Order::Value).unwrap();
            assert!(
                (continued.value - want).abs() < 1e-12,
                "{text} at {angle}: {}",
                continued.value
            );
            let slope = if component == 1 {
                -0.5 * (angle / 2.0).sin()
            } else {
                0.5 * (angle / 2.0).cos()
            };
            assert!(
                (continued.gradient.unwrap()[0] - slope).abs() < 1e-9,
                "{text} at {angle}"
            );
            let sign = if (angle / 2.0).cos() < 0.0 { -1.0 } else { 1.0 };
            assert!(
                (alone.value - sign * want).abs() < 1e-12,
                "{text} alone at {angle}"
            );
        }
    }
}
