//! The measures of accelerations, `ACCX ACCY ACCZ ACCM WDTX WDTY WDTZ
//! WDTM`, during a run: the bodies' accelerations are the right-hand
//! side's (`v'` of each centre of mass and `ω'`, after the joints' solve),
//! and the measure is [`crate::kinematics::measure`] of marker frames built
//! from them, so the derivative in a moving frame `l` is written once.
//!
//! A force, DIFF or MOTION cannot read one: the accelerations come from the
//! forces, an algebraic loop the run does not solve (refused at the call).

use nalgebra::{Matrix3, Vector3};

use super::bodies::Kinematics;
use crate::catalog::Function;
use crate::compile::MarkerCall;
use crate::kinematics::{Frame, Selector, measure};
use crate::laws::LawError;
use crate::scene::Target;
use crate::simulate::Model;

/// A measure of accelerations a model's expression asks for, its markers
/// found in the model.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Measure {
    function: Function,
    /// `i, j, k, l` as the signature orders them, omitted ones ground.
    markers: Vec<Target>,
}

impl Measure {
    /// The measure `call` asks of `model`, or why it has none.
    pub(crate) fn of(model: &Model, call: &MarkerCall) -> Result<Measure, String> {
        let markers = call
            .markers_in(&model.scene)
            .map_err(|why| format!("{}: {why}", call.input_name()))?;
        Ok(Measure {
            function: call.function,
            markers,
        })
    }
}

/// One body's motion with its accelerations, in ground.
struct Moving {
    centre: Vector3<f64>,
    rotation: Matrix3<f64>,
    velocity: Vector3<f64>,
    omega: Vector3<f64>,
    acceleration: Vector3<f64>,
    alpha: Vector3<f64>,
}

/// The bodies' accelerations at one state.
pub(crate) struct Accelerations {
    bodies: Vec<Moving>,
}

impl Accelerations {
    /// The accelerations of the bodies `kinematics` from the state's
    /// `rates` (laid out as the state: each body's `v'` at 7..10 and its
    /// `ω'` in its own axes at 10..13 of its 13 rates from `offsets`).
    pub(super) fn new(
        kinematics: &[Kinematics<f64>],
        rates: &[f64],
        offsets: impl Iterator<Item = usize>,
    ) -> Accelerations {
        let bodies = kinematics
            .iter()
            .zip(offsets)
            .map(|(state, offset)| {
                let rate = |first: usize| {
                    Vector3::new(
                        rates[offset + first],
                        rates[offset + first + 1],
                        rates[offset + first + 2],
                    )
                };
                Moving {
                    centre: state.centre,
                    rotation: state.rotation,
                    velocity: state.velocity,
                    omega: state.omega_ground,
                    acceleration: rate(7),
                    // d(R ω_body)/dt = R (ω × ω + ω') = R ω'.
                    alpha: state.rotation * rate(10),
                }
            })
            .collect();
        Accelerations { bodies }
    }

    /// The frame of marker `target` with its accelerations.
    fn frame(&self, model: &Model, target: &Target) -> Frame<f64> {
        let Target::Marker(index) = target else {
            return still(Vector3::zeros(), Matrix3::identity());
        };
        let marker = &model.scene.markers[*index];
        let axes = marker.orientation.to_rotation_matrix().into_inner();
        let Some(body) = marker.body else {
            return still(marker.position, axes);
        };
        let moving = &self.bodies[body];
        let arm = moving.rotation * (marker.position - model.masses[body].centre);
        Frame {
            origin: moving.centre + arm,
            axes: moving.rotation * axes,
            velocity: moving.velocity + moving.omega.cross(&arm),
            omega: moving.omega,
            body_acceleration: moving.acceleration,
            arm,
            alpha: moving.alpha,
        }
    }

    /// The value of `measure` of `model`.
    pub(crate) fn value(&self, model: &Model, measure_of: &Measure) -> Result<f64, LawError> {
        let frames: Vec<Frame<f64>> = measure_of
            .markers
            .iter()
            .map(|target| self.frame(model, target))
            .collect();
        let frames: Vec<&Frame<f64>> = frames.iter().collect();
        measure(measure_of.function, Selector::Plain, &frames)
    }
}

/// A frame that does not move, at `origin` with `axes`.
fn still(origin: Vector3<f64>, axes: Matrix3<f64>) -> Frame<f64> {
    Frame {
        origin,
        axes,
        velocity: Vector3::zeros(),
        omega: Vector3::zeros(),
        body_acceleration: Vector3::zeros(),
        arm: Vector3::zeros(),
        alpha: Vector3::zeros(),
    }
}
