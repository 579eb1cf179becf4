//! SENSOR: a function watched after every accepted step; when it becomes
//! active (its comparison with VALUE within ERROR) the run halts there or
//! reports the time, located on the step's continuous output, or spaces
//! the rows anew (DT). Checked against the closed-form times of a falling
//! part and of an oscillator.

use mbexpr::simulate::Settings;

use super::simulate::{run, settings};

/// A part falling from height 10 under gravity 9.81, halted where its
/// height comes within ERROR 1e-6 of 5: `t = √(2 (5 − 1e-6) / 9.81)`, and
/// the last row is there.
#[test]
fn a_falling_part_halts_where_the_sensor_says() {
    let text = "falling
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, QG = 0, 10, 0
MARKER/20, PART = 2
ACCGRAV/JGRAV = -9.81
SENSOR/1, LE, VALUE = 5, ERROR = 1e-6, HALT, FUNCTION = DY(20, 1)
REQUEST/1, F1 = DY(20, 1)
END
";
    let run = run(text, &settings(3.0, 10, 1e-8)).expect("it falls");
    let expected = (2.0 * (5.0 - 1e-6) / 9.81_f64).sqrt();
    let trip = run.summary.sensor_trips[0];
    let last = run.rows.last().unwrap();
    println!("halted at {} against {expected}", trip.time);
    assert!(trip.halted && run.summary.stopped);
    assert!((trip.time - expected).abs() < 1e-12, "{}", trip.time);
    assert!((last[0] - expected).abs() < 1e-12 && (last[14] - (5.0 + 1e-6)).abs() < 1e-9);
    // The rows before it are the output times 0, 0.3, ..., 0.9.
    assert_eq!(run.rows.len(), 5);
}

/// An oscillator `x = cos t` (two DIFFs) with a PRINT sensor `x ≥ 0.5`
/// (ERROR 1e-6): active from the start, then again each time `x` climbs
/// back through 0.5 − 1e-6, at `2πk − acos(0.5 − 1e-6)`; the run goes on,
/// and each trip after the start writes a row of its own (Adams writes
/// its output files when a PRINT sensor becomes active), `x` there
/// 0.5 − 1e-6, between the rows of the output grid.
#[test]
fn a_print_sensor_reports_each_time_it_becomes_active() {
    let text = "oscillator
DIFF/1, IC = 1, FUNCTION = DIF(2)
DIFF/2, IC = 0, FUNCTION = -DIF(1)
SENSOR/1, GE, VALUE = 0.5, ERROR = 1e-6, PRINT, FUNCTION = DIF(1)
END
";
    let settings = Settings {
        end: 13.0,
        steps: 13,
        rtol: 1e-10,
        atol: 1e-13,
        ..Settings::default()
    };
    let run = run(text, &settings).expect("it oscillates");
    let times: Vec<f64> = run
        .summary
        .sensor_trips
        .iter()
        .map(|trip| trip.time)
        .collect();
    let back = (0.5_f64 - 1e-6).acos();
    let expected = [
        0.0,
        std::f64::consts::TAU - back,
        2.0 * std::f64::consts::TAU - back,
    ];
    println!("{times:?} against {expected:?}");
    assert_eq!(times.len(), 3, "{times:?}");
    for (time, expected) in times.iter().zip(expected) {
        assert!((time - expected).abs() < 1e-8, "{time} {expected}");
    }
    assert!(!run.summary.stopped && run.rows.len() == 14 + 2);
    let times: Vec<f64> = run.rows.iter().map(|row| row[0]).collect();
    assert!(times.windows(2).all(|pair| pair[0] < pair[1]), "{times:?}");
    for expected in &expected[1..] {
        let row = run
            .rows
            .iter()
            .find(|row| (row[0] - expected).abs() < 1e-8)
            .unwrap_or_else(|| panic!("no row at {expected}: {times:?}"));
        assert!((row[1] - (0.5 - 1e-6)).abs() < 1e-8, "{row:?}");
    }
}

/// What a sensor statement that cannot be watched reports.
fn check(sensor: &str) -> String {
    let text = format!("sensor\nDIFF/1, IC = 1, FUNCTION = -DIF(1)\n{sensor}\nEND\n");
    match run(&text, &settings(1.0, 1, 1e-6)) {
        Ok(run) => {
            let notes = super::simulate::model_of(&text).expect("it reads").notes;
            let mut shown = format!("ran: {} trips", run.summary.sensor_trips.len());
            for (note, _) in notes {
                shown += &format!("; note: {note}");
            }
            shown
        }
        Err(error) => error.trim_end().to_string(),
    }
}

#[test]
fn sensors_that_cannot_be_watched_are_refused_at_their_place() {
    let cases = "
        SENSOR/1, VALUE = 0.5, ERROR = 0.1, HALT, FUNCTION = DIF(1)
        SENSOR/1, VALUE = 0.5, CODGEN, FUNCTION = DIF(1)
        SENSOR/1, VALUE = 0.5, STEPSIZE = 0.1, HALT, FUNCTION = DIF(1)
        SENSOR/1, VALUE = 0.5, ERROR = 0.01, RESTART, YYDUMP, FUNCTION = DIF(1)
        SENSOR/1, VALUE = 0.5, DT = 0.01, PRINT, FUNCTION = DIF(1)
        SENSOR/1, VALUE = 0.5, HALT, FUNCTION = DIF(1)\\, EVALUATE = TIME
        SENSOR/1, VALUE = 0.5, HALT, FUNCTION = DIF(1)\\, EVALUATE_ROUTINE = SEV
        SENSOR/2, VALUE = 0.5, HALT, FUNCTION = SENVAL(1)
        SENSOR/2, VALUE = 0.5, HALT, FUNCTION = SENVAL(2)
        SENSOR/1, GE, VALUE = 0, ERROR = 0, FUNCTION = SENVAL(1) - DIF(1) + 1\\, EVALUATE = DIF(1) - 1 - 1e-13
        SENSOR/1, VALUE = 0.5, FUNCTION = DIF(1)
        SENSOR/1, HALT, FUNCTION = DIF(1)
        SENSOR/1, VALUE = 0.5, HALT
        SENSOR/1, VALUE = 0.5, ERROR = -1, HALT, FUNCTION = DIF(1)
        SENSOR/1, VALUE = 0.5, HALT, FUNCTION = USER(1, 2)
        SENSOR/1, GE, LE, VALUE = 0.5, HALT, FUNCTION = DIF(1)
        SENSOR/1, VALUE = 0.5, DT = 0, PRINT, FUNCTION = DIF(1)
        SENSOR/1, VALUE = 0.5, DT = -0.1, FUNCTION = DIF(1)
        SENSOR/1, VALUE = 0.5, DT = 1e400, FUNCTION = DIF(1)
        SENSOR/1, VALUE = 0.5, DT = 0.25, FUNCTION = DIF(1)
    ";
    insta::assert_snapshot!(super::table(cases, check));
}

/// An EQ sensor whose band (VALUE ± ERROR, here as narrow as 0) lies
/// between two of the four looks a step gets trips where its function
/// passes its value: a falling part passes DY = 5 at `sqrt(2 (10 − 5 −
/// ERROR) / g)` (before, it fell through unseen).
#[test]
fn an_eq_sensor_stepped_over_trips_where_its_function_passes_the_value() {
    for error in [0.0, 1e-6, 1e-3] {
        let text = format!(
            "falling
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, QG = 0, 10, 0
MARKER/20, PART = 2
ACCGRAV/JGRAV = -9.81
SENSOR/1, EQ, VALUE = 5, ERROR = {error}, HALT, FUNCTION = DY(20, 1)
END
"
        );
        let run = run(&text, &settings(3.0, 3, 1e-10)).expect("it falls");
        let expected = (2.0 * (5.0 - error) / 9.81_f64).sqrt();
        let trip = run.summary.sensor_trips.first().expect("the sensor trips");
        println!("ERROR {error}: halted at {} against {expected}", trip.time);
        assert!(trip.halted, "ERROR {error}");
        assert!(
            (trip.time - expected).abs() < 1e-9,
            "ERROR {error}: {}",
            trip.time
        );
    }
}

/// The oscillator `x = cos t` with a sensor `x ≤ 0` (ERROR 1e-12) whose
/// only action is `EVALUATE = TIME`: `SENVAL(1)` is 0 until `x` first
/// reaches 0 at `π/2`, then `π/2` until it does again at `5π/2`, then
/// `5π/2`. A DIFF integrates it, so its value at `t = 9` is
/// `π/2 (5π/2 − π/2) + 5π/2 (9 − 5π/2)`, and a REQUEST shows it; the same
/// with PRINT beside EVALUATE. Without the step cut at each trip the
/// DIFF would take the new value from the step's end, not the trip.
#[test]
fn a_sensor_evaluate_stores_its_value_at_each_trip_for_senval() {
    use std::f64::consts::PI;
    for action in ["", ", PRINT"] {
        let text = format!(
            "oscillator
DIFF/1, IC = 1, FUNCTION = DIF(2)
DIFF/2, IC = 0, FUNCTION = -DIF(1)
DIFF/3, IC = 0, FUNCTION = SENVAL(1)
SENSOR/1, LE, VALUE = 0, ERROR = 1e-12{action}, FUNCTION = DIF(1)\\
, EVALUATE = TIME
REQUEST/1, F2 = SENVAL(1)
END
"
        );
        let settings = Settings {
            end: 9.0,
            steps: 9,
            rtol: 1e-10,
            atol: 1e-12,
            ..Settings::default()
        };
        let run = run(&text, &settings).expect("it oscillates");
        let times: Vec<f64> = run
            .summary
            .sensor_trips
            .iter()
            .map(|trip| trip.time)
            .collect();
        println!("{action:?}: trips {times:?}");
        assert_eq!(times.len(), 2, "{times:?}");
        assert!((times[0] - PI / 2.0).abs() < 1e-9 && (times[1] - 2.5 * PI).abs() < 1e-9);
        let last = run.rows.last().expect("rows");
        let expected = PI / 2.0 * (2.5 * PI - PI / 2.0) + 2.5 * PI * (9.0 - 2.5 * PI);
        println!("DIF(3)(9) = {} against {expected}", last[3]);
        assert!((last[3] - expected).abs() < 1e-7, "{}", last[3]);
        // The REQUEST's column: SENVAL at the rows t = 1 (0), 2 (π/2), 8
        // (5π/2).
        let column = last.len() - 1;
        let senval_at = |t: f64| run.rows.iter().find(|row| row[0] == t).expect("a row")[column];
        assert_eq!(senval_at(1.0), 0.0);
        assert!((senval_at(2.0) - PI / 2.0).abs() < 1e-9);
        assert!((senval_at(8.0) - 2.5 * PI).abs() < 1e-9);
    }
}

/// A sensor's DT spaces the rows anew after each trip: `x = t² / 2`
/// (two DIFFs) passes 0.125 at `t = 0.5`; the rows before it are the run's
/// (0, 0.25, 0.5 at `--steps 4` to 1), then every 0.05 on the grid from
/// the last row, the last at the end, each on the closed form. A second
/// sensor's trip at `x = 0.32` (`t = 0.8`), in the same step while the
/// first stays active (it was once not looked for after the first trip),
/// spaces them 0.1 apart on the grid from the last row (0.75).
#[test]
fn a_sensor_dt_spaces_the_rows_after_its_trip() {
    let text = "a cart pushed from rest
DIFF/1, IC = 0, FUNCTION = DIF(2)
DIFF/2, IC = 0, FUNCTION = 1
SENSOR/1, GE, VALUE = 0.125, ERROR = 1e-9, DT = 0.05, FUNCTION = DIF(1)
SENSOR/2, GE, VALUE = 0.32, ERROR = 1e-9, DT = 0.1, FUNCTION = DIF(1)
END
";
    let run = run(text, &settings(1.0, 4, 1e-10)).expect("it runs");
    let times: Vec<f64> = run.rows.iter().map(|row| row[0]).collect();
    let expected = [0.0, 0.25, 0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.85, 0.95, 1.0];
    println!("{times:?}");
    assert_eq!(times.len(), expected.len(), "{times:?}");
    for (time, expected) in times.iter().zip(expected) {
        assert!((time - expected).abs() < 1e-12, "{times:?}");
    }
    for row in &run.rows {
        let t = row[0];
        assert!(
            (row[1] - t * t / 2.0).abs() < 1e-9 && (row[2] - t).abs() < 1e-9,
            "{row:?}"
        );
    }
    let trips: Vec<f64> = run
        .summary
        .sensor_trips
        .iter()
        .map(|trip| trip.time)
        .collect();
    assert_eq!(trips.len(), 2, "{trips:?}");
    for (trip, expected) in trips.iter().zip([0.25_f64, 0.64]) {
        assert!((trip - (expected - 2e-9).sqrt()).abs() < 1e-8, "{trips:?}");
    }
}

/// Sensors are looked at before the first step: `x = exp(−0.654 t)` with
/// a GE sensor active at the start trips at 0, and an EQ sensor whose
/// value it passes inside DOP853's long first step trips at
/// `ln(1 / 0.995) / 0.654` (both were once missed: the first look was a
/// quarter into the first step, past the GE sensor's band, and the EQ
/// sensor had no value before it to pass from).
#[test]
fn sensors_are_looked_at_before_the_first_step() {
    let text = "decay
DIFF/1, IC = 1, FUNCTION = -0.654 * DIF(1)
SENSOR/1, GE, VALUE = 0.99999, ERROR = 0, PRINT, FUNCTION = DIF(1)
SENSOR/2, EQ, VALUE = 0.995, ERROR = 0, PRINT, FUNCTION = DIF(1)
END
";
    for method in [
        mbexpr::integrate::Method::Dop853,
        mbexpr::integrate::Method::Radau5,
    ] {
        let settings = Settings {
            method,
            ..settings(6.0, 4, 1e-9)
        };
        let run = run(text, &settings).expect("it decays");
        let trips: Vec<(u64, f64)> = run
            .summary
            .sensor_trips
            .iter()
            .map(|trip| (trip.sensor, trip.time))
            .collect();
        let crossing = (1.0_f64 / 0.995).ln() / 0.654;
        assert_eq!(trips.len(), 2, "{method:?}: {trips:?}");
        assert_eq!(trips[0], (1, 0.0), "{method:?}: {trips:?}");
        assert!(
            trips[1].0 == 2 && (trips[1].1 - crossing).abs() < 1e-8,
            "{method:?}: {trips:?}"
        );
    }
}

/// A HALT sensor that becomes active only because another sensor's
/// EVALUATE sets its SENVAL trips at that same time, whether the first trip
/// is at the start, inside a step or at a located switch; and a HALT sensor
/// tripping at exactly the time of an EVALUATE one (the same function) is
/// not lost. `x = t`: SENSOR/1 (`x ≥ 0.3`, or `x ≥ 0` at the start)
/// stores 1 into its SENVAL, which SENSOR/2 (`SENVAL(1) ≥ 0.2`, HALT)
/// watches.
#[test]
fn a_sensor_made_active_by_another_sensors_senval_trips_at_the_same_time() {
    let check = |first_value: f64, switch: bool, second: &str| {
        let switching = if switch {
            "DIFF/2, IC = 0, FUNCTION = IF(DIF(1) - 0.3: 0, 0, 1)\n"
        } else {
            ""
        };
        let text = format!(
            "senval
DIFF/1, IC = 0, FUNCTION = 1
{switching}SENSOR/1, GE, VALUE = {first_value}, ERROR = 1e-9, FUNCTION = DIF(1)\\
, EVALUATE = 1
SENSOR/2, GE, VALUE = 0.2, ERROR = 1e-9, HALT, FUNCTION = {second}
END
"
        );
        let settings = Settings {
            end: 1.0,
            steps: 4,
            rtol: 1e-10,
            atol: 1e-12,
            ..Settings::default()
        };
        let run = run(&text, &settings).expect("it runs");
        let trips: Vec<(u64, f64, bool)> = run
            .summary
            .sensor_trips
            .iter()
            .map(|trip| (trip.sensor, trip.time, trip.halted))
            .collect();
        assert!(run.summary.stopped, "{text}: {trips:?}");
        trips
    };
    for (value, switch) in [(0.0, false), (0.3, false), (0.3, true)] {
        let trips = check(value, switch, "SENVAL(1)");
        assert_eq!(trips.len(), 2, "{trips:?}");
        assert!(
            trips[0].0 == 1 && trips[1].0 == 2 && trips[1].2,
            "{trips:?}"
        );
        assert!((trips[0].1 - value).abs() < 1e-8, "{trips:?}");
        assert_eq!(trips[0].1, trips[1].1, "{trips:?}");
    }
    // Tied: both watch DIF(1) against 0.3.
    let tied = |value| {
        let trips = check(value, false, "DIF(1) - 0.1");
        assert!(
            trips
                .iter()
                .any(|&(sensor, _, halted)| sensor == 2 && halted),
            "{trips:?}"
        );
        assert!((trips.last().unwrap().1 - 0.3).abs() < 1e-8, "{trips:?}");
    };
    tied(0.3);
}
