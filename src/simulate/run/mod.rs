//! The run: the integrator steps the equations with every piecewise
//! function held on its branch; after each accepted step the switching
//! values are looked at on the step's continuous output, a sign change is
//! located to about 1e-13 in time, the step is cut there, the branches
//! switch and the method starts afresh.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

mod estimate;
mod sink;
mod statics;
mod switch;

pub use estimate::ErrorEstimate;
pub use sink::{MethodChange, Sink};
pub use statics::Equilibrium;

use super::constraints::{
    Drives, JOINTS, MOTIONS, Residuals, Tolerance, Unassembled, body_quaternion,
    disagreeing_redundant, first_repeated, owner_of_row, project, why_unmet,
};
use super::equations::{BODY_STATES, Mechanics, RunValue, body_offset};
use super::error::{Place, SimulateError};
use super::initial::initial_state;
use super::model::{Contact, Sensor, SensorAction};
use super::{Model, Simulation};
use crate::Shown;
use crate::compile::{Program, SiteKind};
use crate::eval::OutputError;
use crate::integrate::{
    AbsoluteTolerance, CAP_SLACK, IntegrateError, Method, Options, Rejection, Stats, Stepper,
    smallest_step,
};
use crate::laws::branch::{self, Code};
use crate::laws::contact::{ContactBranch, Piece};
use sink::RowsOnly;
use switch::{Held, Switch, find_switch, switching_slope};

/// How to run a simulation.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// The integration method ([`Method::Auto`] by default).
    pub method: Method,
    /// The end time (positive); the run starts at 0.
    pub end: f64,
    /// The number of output steps: `steps + 1` rows at equally spaced
    /// times from 0 to `end`.
    pub steps: usize,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// The largest step (infinity for none).
    pub h_max: f64,
    /// The most integration steps, accepted and rejected, the run may take
    /// (past them it stops with an error rather than run on for hours).
    pub max_steps: usize,
    /// Start from a static equilibrium (`SIMULATE/STATICS` before the
    /// dynamics): the parts at rest where the forces balance, found from
    /// the initial conditions.
    pub statics: bool,
    /// Radau5 steps onto each output time (Adams'
    /// `INTEGRATOR/INTERPOLATE = OFF`). By default (`false`) every row
    /// comes from a step's continuous output, so the output times change
    /// neither the steps nor the rows; but Radau5's continuous output is
    /// of order 3 inside a step where its steps are of order 5, and a row
    /// between steps can be a few times the tolerance off where a step's
    /// end is not (measured in BENCHMARKS.md). DOP853's continuous output
    /// is of the order of its steps, so it never lands.
    pub land_on_outputs: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            method: Method::Auto,
            end: 1.0,
            steps: 100,
            rtol: 1e-6,
            atol: 1e-9,
            h_max: f64::INFINITY,
            max_steps: DEFAULT_MAX_STEPS,
            statics: false,
            land_on_outputs: false,
        }
    }
}

/// [`Settings::max_steps`] by default: about ten seconds of DOP853 on a
/// two-state model here, and 1.5 times what the stiffest scene of the
/// simulation study takes with it at rtol 1e-12.
pub const DEFAULT_MAX_STEPS: usize = 10_000_000;

/// How many samples of the DELAYs' expressions the run records inside each
/// accepted step, besides its end: with the record's eight samples
/// per polynomial, the record reads the past to the order of the steps.
const SAMPLES_INSIDE: u32 = 7;

/// The shortest step a DELAY holds the steps to, as a fraction of the run:
/// below it a DELAY reads the straight line from its record's last sample
/// to its expression now.
const DELAY_CAP_FLOOR: f64 = 1e-4;

/// The times of a run's rows after the first (at 0): `steps` equally
/// spaced up to the end, until a sensor's DT spaces them anew after its
/// trip (the last row still at the end).
struct OutputTimes {
    /// The time the rows are counted from: 0, or the last row before a
    /// trip with a DT.
    origin: f64,
    /// The time between rows, when a DT gives it (`None`: the run's
    /// `steps` rows share the time from the origin to the end).
    step: Option<f64>,
    /// How many rows from the origin to the end.
    count: usize,
    /// The index of the next row from the origin (from 1).
    index: usize,
    /// The run's end time.
    end: f64,
    /// The time of the last row written.
    last: f64,
}

impl OutputTimes {
    /// `steps` rows after 0, equally spaced up to `end`.
    fn new(end: f64, steps: usize) -> OutputTimes {
        OutputTimes {
            origin: 0.0,
            step: None,
            count: steps,
            index: 1,
            end,
            last: 0.0,
        }
    }

    /// The time of the next row, if one is left.
    fn next(&self) -> Option<f64> {
        if self.index > self.count {
            return None;
        }
        Some(match self.step {
            Some(_) if self.index == self.count => self.end,
            Some(step) => self.origin + step * self.index as f64,
            None => self.origin + (self.end - self.origin) * self.index as f64 / self.count as f64,
        })
    }

    /// The next row, at `time`, is written.
    fn written(&mut self, time: f64) {
        self.index += 1;
        self.last = time;
    }

    /// The time of the last row written.
    fn last(&self) -> f64 {
        self.last
    }

    /// Whether `time` is after the last row written and not the next
    /// row's: where a row of its own (a PRINT sensor's) goes.
    fn between_rows(&self, time: f64) -> bool {
        self.last < time && self.next() != Some(time)
    }

    /// After a trip at `from`, rows `step` apart on the grid from the last
    /// row (so that they stay at round times), the first after the trip,
    /// the last at the end.
    fn respace(&mut self, from: f64, step: f64) {
        let span = self.end - self.last;
        if span <= 0.0 {
            return;
        }
        // A DT small against the run still ends: at most as many rows as a
        // command file's DTOUT may ask for.
        let count = (span / step * (1.0 - 1e-9))
            .ceil()
            .clamp(1.0, super::read::MOST_OUTPUT_STEPS as f64);
        let step = step.max(span / count);
        let first = ((from - self.last) / step).floor() + 1.0;
        self.origin = self.last;
        self.step = Some(step);
        self.count = count as usize;
        self.index = (first.max(1.0) as usize).min(self.count);
    }
}

/// How near, relative to the time, a DELAY's kink is to a step's end for
/// the step to have landed on it (rounding puts the sum of steps of a
/// delay's length a few ulps off the kink the delay carries forward).
const KINK_GAP: f64 = 1e-9;

/// [`KINK_GAP`] at time `t`.
fn kink_gap(t: f64) -> f64 {
    KINK_GAP * t.abs().max(1.0)
}

/// Radau5 keeps its Jacobian while Newton's iteration contracts by at most
/// this ([`Options::jacobian_reuse`]; Hairer's default is 0.001, for a
/// Jacobian that costs a few right-hand sides). A model's Jacobian is
/// evaluated over dual numbers of a direction per state colour, and a
/// sparse system's LU follows each new one: at 0.01 the stack of 32 balls
/// evaluates 4.6 times fewer Jacobians in 0.6 of the time, the jointed
/// examples run in 0.7 to 0.8 of it, and the study scenes take 0.1 to 1.7
/// % fewer instructions (0.1 took up to 2 % more there: more Newton
/// iterations and rejected steps); the rows unchanged within their spread
/// (BENCHMARKS.md, "Radau5's Jacobian kept").
const JACOBIAN_REUSE: f64 = 0.01;

/// An evaluation that failed during a run, with the program it ran.
#[derive(Debug)]
enum Failed {
    /// The forces' and DIFFs' program (a state's rates, the values of the
    /// running solver the outputs read).
    Dynamics(OutputError),
    /// The output columns' and sensors' program.
    Outputs(OutputError),
}

impl From<OutputError> for Failed {
    fn from(error: OutputError) -> Failed {
        Failed::Dynamics(error)
    }
}

/// The least [`Settings::rtol`]: ten rounding units of a double, as in
/// Hairer's codes.
pub const SMALLEST_RTOL: f64 = 10.0 * f64::EPSILON;

impl Settings {
    /// Refuses settings no run can take, so that a caller can check them
    /// before anything else: the end time, then
    /// [`Settings::check_but_end`]. [`Settings::check_for`] adds what
    /// depends on the model.
    pub fn check(&self) -> Result<(), SimulateError> {
        let problem = if !(self.end > 0.0 && self.end.is_finite()) {
            Some(format!(
                "the end time must be a positive number, not {}",
                Shown(self.end)
            ))
        } else if self.steps > 0 && self.end / (self.steps as f64) < f64::MIN_POSITIVE {
            Some(format!(
                "the time between rows, the end time over the steps ({} / {}), is below the least normal number of a double ({}): the rows' times would round together; give a later end time or fewer steps",
                Shown(self.end),
                self.steps,
                Shown(f64::MIN_POSITIVE)
            ))
        } else {
            self.problem_but_end()
        };
        refused(problem)
    }

    /// Refuses settings `model`'s run cannot take (what
    /// [`Simulation::run`] checks first): [`Settings::check`], then,
    /// unless a SENSOR of the model may end the run sooner (HALT or
    /// RETURN), the largest step against the end time: it must reach the
    /// end within [`Settings::max_steps`] steps and be no shorter than a
    /// step the integrator can take there.
    pub fn check_for(&self, model: &Model) -> Result<(), SimulateError> {
        self.check()?;
        if model.sensors.iter().any(|sensor| sensor.action.halts()) {
            return Ok(());
        }
        refused(self.reach_problem())
    }

    /// [`Settings::check`] less what depends on the end time (the end
    /// time itself, and the largest step against it): for the settings of
    /// runs whose end time comes with each model, checked once before any
    /// of them starts.
    pub fn check_but_end(&self) -> Result<(), SimulateError> {
        refused(self.problem_but_end())
    }

    /// What [`Settings::check_but_end`] refuses.
    fn problem_but_end(&self) -> Option<String> {
        if self.steps == 0 {
            Some("the number of output steps must be at least 1".to_string())
        } else if self.steps > crate::simulate::read::MOST_OUTPUT_STEPS {
            Some(format!(
                "the number of output steps must be at most {} (a row each; the run would not end), not {}",
                crate::simulate::read::MOST_OUTPUT_STEPS,
                self.steps
            ))
        } else if !(self.rtol >= SMALLEST_RTOL && self.rtol < 1.0) {
            Some(format!(
                "the relative tolerance must be at least {} (ten rounding units: below it a step's error cannot be told from rounding) and less than 1, not {}",
                Shown(SMALLEST_RTOL),
                Shown(self.rtol)
            ))
        } else if !(self.atol > 0.0 && self.atol.is_finite()) {
            Some(format!(
                "the absolute tolerance must be a positive number, not {}",
                Shown(self.atol)
            ))
        } else if self.max_steps == 0 {
            Some("the most steps must be at least 1".to_string())
        } else if self.h_max.is_nan() || self.h_max <= 0.0 {
            Some(format!(
                "the largest step must be positive, not {}",
                Shown(self.h_max)
            ))
        } else {
            None
        }
    }

    /// A largest step too short to reach the end time (`end` positive and
    /// finite, `h_max` positive): the run needs at least `end / h_max`
    /// accepted steps (each at most `h_max`, a landing one a rounding
    /// unit more), more than [`Settings::max_steps`] allows; or, where
    /// the run needs more than one step, `h_max` is below
    /// [`smallest_step`] at the end time, the shortest step the
    /// integrator takes before it gives up (a step that short is lost in
    /// the rounding of the time).
    fn reach_problem(&self) -> Option<String> {
        let least_steps = self.end / self.h_max;
        if least_steps > self.max_steps as f64 * (1.0 + CAP_SLACK) {
            Some(format!(
                "the largest step must be at least {} (the end time {} over the most steps the settings allow, {}: with shorter steps the run cannot reach its end), not {}",
                Shown(self.end / self.max_steps as f64),
                Shown(self.end),
                self.max_steps,
                Shown(self.h_max)
            ))
        } else if least_steps > 1.0 + CAP_SLACK && self.h_max < smallest_step(self.end) {
            Some(format!(
                "the largest step must be at least {} (the shortest step the integrator takes at the end time {}: a shorter one is lost in the rounding of the time), not {}",
                Shown(smallest_step(self.end)),
                Shown(self.end),
                Shown(self.h_max)
            ))
        } else {
            None
        }
    }
}

/// A settings error of `problem`, if there is one.
fn refused(problem: Option<String>) -> Result<(), SimulateError> {
    problem.map_or(Ok(()), |message| {
        Err(SimulateError::Settings {
            message,
            span: None,
        })
    })
}

/// How many times a step is looked at for a sensor becoming active.
const SENSOR_LOOKS: usize = 4;

/// A located branch switch.
#[derive(Clone, Debug, PartialEq)]
pub struct Event {
    /// When.
    pub time: f64,
    /// The function (`BISTOP`), `IF`, or `CONTACT` for a contact's law.
    pub function: String,
    /// Where it is written: a call's span in an expression of
    /// [`Model::expressions`], or a CONTACT statement's in the file.
    pub place: Place,
    /// What it is in: the expression's label (`SFORCE/3 FUNCTION`) or the
    /// statement's (`CONTACT/1`).
    pub label: String,
    /// The branch it leaves.
    pub from: String,
    /// The branch it takes.
    pub to: String,
    /// The values of the columns after `time` ([`crate::simulate::columns`])
    /// at the switch, on the branches it takes.
    pub values: Vec<f64>,
    /// In a model with constraints, how far the state located at the
    /// switch was off the joints before it was assembled again (the
    /// consistent state the run goes on from); `None` without constraints.
    pub residuals: Option<Residuals>,
}

/// What a run cost and found.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// The integrator's counts: steps, rejected steps, right-hand sides,
    /// Jacobians, LU decompositions (over every restart).
    pub stats: Stats,
    /// Every branch switch, in time order.
    pub events: Vec<Event>,
    /// The wall time of the run.
    pub wall_time: Duration,
    /// Whether the sink stopped the run before the end (its answer to a
    /// row or an event, or [`Sink::stop_requested`]).
    pub stopped: bool,
    /// Under [`Method::Auto`], every change of method, in time order.
    pub method_changes: Vec<MethodChange>,
    /// DOP853: the time from which Hairer's stiffness test found the run
    /// stiff (steps held by stability, not accuracy; Radau5 takes far
    /// fewer there).
    pub stiff_from: Option<f64>,
    /// With joints: the largest constraint residuals an accepted step
    /// left (before its projection), over the run after the initial
    /// assembly.
    pub residuals: Residuals,
    /// With joints: the initial state's residuals, before the assembly
    /// that put it on the constraints.
    pub initial_residuals: Residuals,
    /// With joints: how many times a state was projected back onto the
    /// constraints (a residual past the absolute tolerance).
    pub projections: usize,
    /// With [`Settings::statics`]: how the static equilibrium the run
    /// starts from was found.
    pub equilibrium: Option<Equilibrium>,
    /// Every time a SENSOR became active, in time order; a HALT or RETURN
    /// one ends the run there.
    pub sensor_trips: Vec<SensorTrip>,
}

/// A SENSOR that became active.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorTrip {
    /// The statement id.
    pub sensor: u64,
    /// The time it became active (located on the step's continuous output).
    pub time: f64,
    /// Whether it ended the run (HALT or RETURN).
    pub halted: bool,
}

/// Records that sensor `watched` tripped at `time`: the trip joins
/// `trips`, and the sensor's DT, when it has one, spaces the output rows
/// after it anew. Returns whether the trip ends the run (HALT or RETURN);
/// the rest of what a trip does (the last row of a halted run, SENVAL) is
/// the caller's.
fn note_trip(
    watched: &Sensor,
    time: f64,
    trips: &mut Vec<SensorTrip>,
    outputs: &mut OutputTimes,
) -> bool {
    let halts = watched.action.halts();
    trips.push(SensorTrip {
        sensor: watched.id,
        time,
        halted: halts,
    });
    if let Some(step) = watched.output_step {
        outputs.respace(time, step);
    }
    halts
}

/// Looks at the sensors at `(time, state)` and records those newly active
/// (`active`, updated) as trips there, in order. Each EVALUATE stores its
/// SENVAL, and the sensors that the new value makes active trip at the
/// same time (each sensor at most once at one instant, so that sensors
/// reading one another's SENVAL cannot loop). Says whether a trip ends
/// the run (the trips after it are not recorded), whether a SENVAL
/// changed and whether a PRINT sensor asks for a row there.
fn trips_at(
    model: &Model,
    (rows, mechanics): (&mut Rows<'_>, &mut Mechanics<'_>),
    (time, state): (f64, &[f64]),
    active: &mut [bool],
    (trips, outputs): (&mut Vec<SensorTrip>, &mut OutputTimes),
) -> Result<TripsAt, Failed> {
    let mut pending: VecDeque<usize> = rows.tripped(time, state, active)?.into();
    let mut tripped = vec![false; model.sensors.len()];
    let mut found = TripsAt::default();
    while let Some(sensor) = pending.pop_front() {
        if std::mem::replace(&mut tripped[sensor], true) {
            continue;
        }
        let watched = &model.sensors[sensor];
        if note_trip(watched, time, trips, outputs) {
            found.halted = true;
            return Ok(found);
        }
        found.printed |= watched.action == SensorAction::Print;
        if watched.evaluate.is_some() {
            rows.store(sensor, (time, state), mechanics)?;
            found.evaluated = true;
            pending.extend(rows.tripped(time, state, active)?);
        }
    }
    Ok(found)
}

/// The state at `time` inside the stepper's last step: its end state
/// there, else its continuous output (written into `dense` either way).
fn state_at<'a>(stepper: &'a Stepper, time: f64, dense: &'a mut [f64]) -> &'a [f64] {
    stepper.dense(time, dense);
    if time == stepper.t() {
        stepper.y()
    } else {
        dense
    }
}

/// What the sensors that trip at one time ask of the run.
#[derive(Default)]
struct TripsAt {
    /// A HALT or RETURN ends the run there.
    halted: bool,
    /// An EVALUATE changed a SENVAL.
    evaluated: bool,
    /// A PRINT writes a row there (Adams writes its output files at the
    /// trip).
    printed: bool,
}

/// The event of `contact`'s law switching from `from` to `to` at `time`.
fn contact_event(contact: &Contact, time: f64, from: Code, to: Code) -> Event {
    // The law's stop is where the solids touch.
    let describe = |code| {
        match ContactBranch::from_code(code) {
            ContactBranch::Lower(Piece::Ramp) => "touching, damping ramp",
            ContactBranch::Lower(Piece::Full) => "touching, full damping",
            ContactBranch::LowerClamped => "touching, clamped",
            _ => "apart",
        }
        .to_string()
    };
    Event {
        time,
        function: "CONTACT".to_string(),
        place: Place::File(contact.span),
        label: format!("CONTACT/{}", contact.id),
        from: describe(from),
        to: describe(to),
        values: Vec::new(),
        residuals: None,
    }
}

/// The event of PTCV or CVCV `joint`'s point of contact crossing, on
/// its curve of side `side`
/// ([`CurveSite::side`](crate::simulate::constraints::CurveSite::side)),
/// from piece `from` to piece `to` at `time` (a knot, where the curve's
/// third derivative changes).
fn curve_event(
    joint: &crate::simulate::Joint,
    side: usize,
    time: f64,
    from: Code,
    to: Code,
) -> Event {
    let (function, curve) = match (&joint.curve, &joint.pair) {
        (Some(on), _) => ("PTCV", on.curve.id),
        (None, Some(pair)) if side == 0 => ("CVCV", pair.i.curve.id),
        (None, Some(pair)) => ("CVCV", pair.j.curve.id),
        (None, None) => ("JOINT", 0),
    };
    let describe = |code: Code| format!("on piece {} of CURVE/{curve}", code + 1);
    Event {
        time,
        function: function.to_string(),
        place: Place::File(joint.span),
        label: format!("{function}/{}", joint.id),
        from: describe(from),
        to: describe(to),
        values: Vec::new(),
        residuals: None,
    }
}

/// A step limit of the sites, raised to what the integrator can take at
/// time `t` (a hundred times its smallest step).
fn floor(limit: f64, t: f64) -> f64 {
    limit.max(100.0 * crate::integrate::smallest_step(t))
}

/// The tolerance a state `y` is held on the joints to after a step of
/// size `h`: the run's, tightened where the joints' reactions make a drift
/// of that size matter. A joint that has drifted by a small angle turns
/// its reaction `R` with it, which pushes its part along the path the
/// joint leaves free by up to `R/m` times the angle, and over the step
/// moves the part's velocity by `R/m · angle · h`: a drift the tolerance
/// allows is harmless beside loads of the motion's size, but not beside a
/// reaction of 1e9 N on a part of 2 kg (a hinge loaded along its axis ran
/// its pendulum 0.2 % off at rtol 1e-6). `push` holds each part's
/// reactions per unit of mass and of inertia
/// ([`Mechanics::reaction_push`]); each part's drift allowed keeps its
/// push over the step within its velocities' tolerance (`atol + rtol |v|`,
/// and `atol + rtol |ω|`) where the tolerance on its orientation (`atol +
/// rtol`) would not.
fn drift_tolerance(
    tolerance: Tolerance,
    (push, y): (&[[f64; 2]], &[f64]),
    offsets: &[usize],
    h: f64,
) -> Tolerance {
    let orientation = tolerance.atol + tolerance.rtol;
    let mut factor: f64 = 1.0;
    for (push, &offset) in push.iter().zip(offsets) {
        // The linear velocities from 7, the angular ones from 10.
        for (push, first) in push.iter().zip([offset + 7, offset + 10]) {
            let speed = y[first..first + 3]
                .iter()
                .fold(0.0_f64, |most, v| most.max(v.abs()));
            let allowed = tolerance.atol + tolerance.rtol * speed;
            let moved = h * push * orientation;
            if moved > allowed {
                factor = factor.min(allowed / moved);
            }
        }
    }
    Tolerance {
        rtol: tolerance.rtol * factor,
        atol: tolerance.atol * factor,
    }
}

/// The counts of two runs of the integrator together.
fn add(a: Stats, b: Stats) -> Stats {
    Stats {
        steps: a.steps + b.steps,
        rejected: a.rejected + b.rejected,
        rhs_evaluations: a.rhs_evaluations + b.rhs_evaluations,
        rhs_failures: a.rhs_failures + b.rhs_failures,
        jacobian_evaluations: a.jacobian_evaluations + b.jacobian_evaluations,
        lu_decompositions: a.lu_decompositions + b.lu_decompositions,
        rounding_limited: a.rounding_limited + b.rounding_limited,
        rounding_limited_from: a.rounding_limited_from.or(b.rounding_limited_from),
    }
}

/// Switches closer together than this, relative to the time, in a row of
/// [`CHATTER_COUNT`], are chattering.
const CHATTER_WINDOW: f64 = 1e-9;
const CHATTER_COUNT: usize = 100;

/// Adds a switch at `time` to the `recent` ones, and gives how long the
/// last [`CHATTER_COUNT`] of them took when that is within
/// [`CHATTER_WINDOW`] of the time: the run chatters.
fn chatters(recent: &mut VecDeque<f64>, time: f64) -> Option<f64> {
    recent.push_back(time);
    if recent.len() > CHATTER_COUNT {
        recent.pop_front();
    }
    let (first, last) = (*recent.front()?, *recent.back()?);
    (recent.len() == CHATTER_COUNT && last - first <= CHATTER_WINDOW * last.abs().max(1.0))
        .then_some(last - first)
}

/// The rows' values at state `y` (everything but the time).
struct Rows<'m> {
    model: &'m Model,
    outputs: Mechanics<'m>,
    /// The equations of motion and the values of the running solver the
    /// outputs read, when they read any.
    reactions: Option<(Mechanics<'m>, Vec<RunValue>)>,
    values: Vec<f64>,
    /// The sensors' functions at the last look for a trip (NaN before the
    /// first): an EQ sensor whose function passes its value between two
    /// looks, stepping over the band of its ERROR, trips there.
    sensed_before: Vec<f64>,
}

impl Rows<'_> {
    /// `(t, y)` is an accepted state: the AX, AY, AZ the outputs (and the
    /// forces whose values they read) evaluate settle their turns there.
    fn accept(&mut self, t: f64, y: &[f64], starts_piece: bool) -> Result<(), Failed> {
        let reactions = self
            .reactions
            .as_ref()
            .is_some_and(|(dynamics, _)| dynamics.continues_angles());
        if reactions || self.outputs.continues_angles() {
            self.at(t, y)?;
            self.outputs.accept_angles(t, starts_piece);
            if let Some((dynamics, _)) = &mut self.reactions {
                dynamics.accept_angles(t, starts_piece);
            }
        }
        Ok(())
    }

    /// Whether the outputs (or the forces whose values they read) have
    /// DELAYs, whose expressions the run records.
    fn has_delays(&self) -> bool {
        self.outputs.has_delays()
            || self
                .reactions
                .as_ref()
                .is_some_and(|(dynamics, _)| dynamics.has_delays())
    }

    /// Records the outputs' DELAYs' expressions at `(t, y)`
    /// ([`Mechanics::record_delays`]).
    fn record_delays(&mut self, t: f64, y: &[f64], starts: Option<u8>) -> Result<(), Failed> {
        if !self.has_delays() {
            return Ok(());
        }
        if let Some((dynamics, _)) = &mut self.reactions {
            dynamics.record_delays(t, y, None, starts)?;
        }
        // The outputs are evaluated only for their own DELAYs.
        if self.outputs.has_delays() {
            self.at(t, y)?;
            self.outputs.sample_delays(t, starts);
        }
        Ok(())
    }

    fn at(&mut self, t: f64, y: &[f64]) -> Result<&[f64], Failed> {
        let model = self.model;
        self.values.clear();
        self.values.extend_from_slice(&y[..model.diffs.len()]);
        for (body, mass) in model.masses.iter().enumerate() {
            let offset = body_offset(model, body);
            let state = &y[offset..offset + BODY_STATES];
            let q = body_quaternion(state);
            let arm = q * mass.centre;
            let omega = q * nalgebra::Vector3::new(state[10], state[11], state[12]);
            let velocity = nalgebra::Vector3::new(state[7], state[8], state[9]) - omega.cross(&arm);
            self.values
                .extend([state[0] - arm.x, state[1] - arm.y, state[2] - arm.z]);
            self.values.extend([q.w, q.i, q.j, q.k]);
            self.values.extend(velocity.iter());
            self.values.extend(omega.iter());
        }
        let start = self.values.len();
        let columns = start + model.outputs.len();
        let end = columns + model.sensors.len() + self.evaluated();
        self.values.resize(end, 0.0);
        if end > start {
            let solved: Vec<f64> = match &mut self.reactions {
                None => Vec::new(),
                Some((dynamics, values)) => dynamics.run_values(t, y, values)?,
            };
            self.outputs
                .outputs(t, y, &solved, &mut self.values[start..])
                .map_err(Failed::Outputs)?;
        }
        Ok(&self.values[..columns])
    }

    /// The sensors' functions at the state [`Rows::at`] last looked at.
    fn sensed(&self) -> &[f64] {
        let first = self.sensed_from();
        &self.values[first..first + self.model.sensors.len()]
    }

    /// Where the sensors' functions begin among the values (after the
    /// output columns, before the EVALUATEs).
    fn sensed_from(&self) -> usize {
        self.values.len() - self.evaluated() - self.model.sensors.len()
    }

    /// How many sensors have an EVALUATE (its values last among the
    /// outputs).
    fn evaluated(&self) -> usize {
        let sensors = &self.model.sensors;
        sensors.iter().filter(|s| s.evaluate.is_some()).count()
    }

    /// Sensor `sensor`'s trip at `(t, y)`: the value of its EVALUATE
    /// there, when it has one, becomes its `SENVAL` for the equations of
    /// motion `dynamics` and the outputs.
    fn store(
        &mut self,
        sensor: usize,
        (t, y): (f64, &[f64]),
        dynamics: &mut Mechanics<'_>,
    ) -> Result<(), Failed> {
        let sensors = &self.model.sensors;
        if sensors[sensor].evaluate.is_none() {
            return Ok(());
        }
        let slot = sensors[..sensor]
            .iter()
            .filter(|s| s.evaluate.is_some())
            .count();
        self.at(t, y)?;
        let value = self.values[self.values.len() - self.evaluated() + slot];
        dynamics.store_sensor_value(sensor, value);
        self.outputs.store_sensor_value(sensor, value);
        if let Some((reactions, _)) = &mut self.reactions {
            reactions.store_sensor_value(sensor, value);
        }
        Ok(())
    }

    /// The sensors that are active at `(t, y)` and were not at the last
    /// look (`active`, updated), in the model's order.
    fn tripped(&mut self, t: f64, y: &[f64], active: &mut [bool]) -> Result<Vec<usize>, Failed> {
        if self.model.sensors.is_empty() {
            return Ok(Vec::new());
        }
        self.at(t, y)?;
        let from = self.sensed_from();
        let mut newly = Vec::new();
        for (k, ((sensor, &value), before)) in self
            .model
            .sensors
            .iter()
            .zip(&self.values[from..])
            .zip(&mut self.sensed_before)
            .enumerate()
        {
            let now = sensor.is_active(value) || sensor.passes(*before, value);
            if now && !active[k] {
                newly.push(k);
            }
            active[k] = now;
            *before = value;
        }
        Ok(newly)
    }
}

/// A model's equations `dy/dt = f(t, y)` as an integration
/// [`System`](crate::integrate::System), every piecewise function on the
/// branch the state decides, with the exact Jacobian from dual numbers: for
/// a driver of one's own ([`Simulation::equations`]). The state is laid out
/// as the simulation's (see [`Simulation::initial_state`]).
pub struct Equations<'m> {
    mechanics: Mechanics<'m>,
}

impl crate::integrate::System for Equations<'_> {
    type Error = OutputError;

    fn dimension(&self) -> usize {
        self.mechanics.dimension()
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), OutputError> {
        self.mechanics.rates(t, y, None, dy)
    }

    fn jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        _dy: &[f64],
        jacobian: &mut nalgebra::DMatrix<f64>,
    ) -> Result<(), OutputError> {
        self.mechanics.jacobian(t, y, None, jacobian)
    }

    fn jacobian_pattern(&mut self) -> Option<crate::integrate::linalg::Pattern> {
        Some(self.mechanics.pattern().clone())
    }

    fn rounding_floor(
        &mut self,
        t: f64,
        y: &[f64],
        floor: &mut [f64],
        carried: &mut [f64],
    ) -> Result<(), OutputError> {
        self.mechanics.rounding_floor(t, y, None, floor, carried)
    }

    fn norm_groups(&mut self) -> Vec<std::ops::Range<usize>> {
        self.mechanics.norm_groups()
    }

    fn sparse_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        _dy: &[f64],
        _pattern: &crate::integrate::linalg::Pattern,
        values: &mut [f64],
    ) -> Result<(), OutputError> {
        self.mechanics.sparse_jacobian(t, y, None, values)
    }
}

impl Simulation<'_> {
    /// The model's equations, for a driver of one's own.
    pub fn equations(&self) -> Equations<'_> {
        Equations {
            mechanics: Mechanics::new(self.model, &self.dynamics, &self.computed),
        }
    }

    /// The state at time 0: the value of each DIFF, then for each body its
    /// centre of mass in ground, its orientation as a quaternion `w x y z`,
    /// the velocity of its centre of mass and its angular velocity in its
    /// own axes (13 numbers).
    pub fn initial_state(&self) -> Vec<f64> {
        initial_state(self.model)
    }

    /// Runs from time 0 to `settings.end`, calling `row` with the time and
    /// the values of the columns after `time` ([`crate::simulate::columns`])
    /// at each output time; `row` returns `false` to stop the run there.
    /// [`run_into`](Self::run_into) with a sink of rows only.
    pub fn run(
        &self,
        settings: &Settings,
        row: impl FnMut(f64, &[f64]) -> bool,
    ) -> Result<Summary, SimulateError> {
        self.run_into(settings, &mut RowsOnly(row))
    }

    /// Runs from time 0 to `settings.end`, handing `sink` each row (the
    /// time and the values of the columns after `time`,
    /// [`crate::simulate::columns`]) at each output time as soon as the
    /// step that reaches it is taken, each located switch and each change
    /// of method; the sink may stop the run at any of them or before any
    /// step. The rows come from each step's continuous output: the steps
    /// do not depend on the output times. Rows handed over before an error
    /// stay the caller's.
    pub fn run_into(
        &self,
        settings: &Settings,
        sink: &mut impl Sink,
    ) -> Result<Summary, SimulateError> {
        settings.check_for(self.model)?;
        let started = Instant::now();
        let model = self.model;
        let program = &self.dynamics;
        let mut system = Held {
            mechanics: Mechanics::new(model, program, &self.computed),
            held: Vec::new(),
            tolerance: settings.atol,
            before_end: None,
        };
        let outputs = Mechanics::new(model, &self.outputs, &self.output_expressions);
        let components: Vec<RunValue> = outputs
            .solver_calls()
            .iter()
            .map(|call| RunValue::of(model, call).expect("checked when compiled"))
            .collect();
        let reactions = (!components.is_empty())
            .then(|| (Mechanics::new(model, program, &self.computed), components));
        let mut rows = Rows {
            sensed_before: vec![f64::NAN; model.sensors.len()],
            model,
            outputs,
            reactions,
            values: Vec::new(),
        };
        let mut y0 = initial_state(model);
        let offsets = body_offsets(model);
        let inverse_inertia = model.inverse_inertia();
        let drives = Drives::new(model);
        let assemble = |y: &mut [f64], time: f64, tolerance: Tolerance, initial: bool| {
            let at = drives
                .at(time, None)
                .map_err(|error| self.failure(time, error))?;
            project(model, y, &offsets, &at, &inverse_inertia, tolerance, initial).map_err(|error| {
                let unmet = |row: Option<usize>| {
                    why_unmet(model, y, &offsets, row).map(|(span, reason)| {
                        (format!("the joints cannot be assembled: {reason}"), Some(span))
                    })
                };
                let (message, owner) = match error {
                    Unassembled::Singular { row } if initial && !(model.joint_initials.is_empty() && model.exact.is_empty()) => ("the joints cannot be assembled: their equations and the initial conditions (the joints' IC, ICTRAN, ICROT, the parts' EXACT) are dependent at this state (an initial condition may set a coordinate the joints, motions or other initial conditions already set, or the configuration is singular)".to_string(), row.and_then(|row| owner_of_row(model, row).1)),
                    Unassembled::Singular { row } if let Some(unmet) = unmet(row) => unmet,
                    Unassembled::Singular { row: Some(row) } => {
                        let (owner, span) = owner_of_row(model, row);
                        (format!("the joints cannot be assembled: their equations are dependent at this state: an equation of {owner} repeats those before it, or does not move with the parts (two motions or constraints set one freedom, a FUNCTION that reads no part's place, or a singular configuration)"), span)
                    }
                    Unassembled::Singular { row: None } => ("the joints cannot be assembled: their equations are dependent at this state (a singular configuration)".to_string(), None),
                    Unassembled::Apart { row, residual } => {
                        let (owner, span) = owner_of_row(model, row);
                        let message = if let Some((message, _)) = unmet(Some(row)) {
                            message
                        } else if residual.is_nan() {
                            format!("the joints cannot be assembled: the equation of {owner} cannot be evaluated at this state (its FUNCTION leaves its domain)")
                        } else {
                            format!("the joints cannot be assembled: {owner} stays off by {residual:.3e} after Newton's iterations (the parts cannot be placed as the joints and motions ask: check the markers' places and axes and the motions' values at this time)")
                        };
                        (message, span)
                    }
                };
                SimulateError::Integration {
                    time,
                    message,
                    place: owner.map_or(Place::None, Place::File),
                }
            })
        };
        let tolerance = Tolerance {
            rtol: settings.rtol,
            atol: settings.atol,
        };
        // The motions at the start, for the repeated-equation test and the
        // static equilibrium.
        let at = drives
            .at(0.0, None)
            .map_err(|error| self.failure(0.0, error))?;
        let initial_residuals = if !model.is_constrained() {
            Residuals::default()
        } else {
            let found = assemble(
                &mut y0,
                0.0,
                Tolerance {
                    rtol: 0.0,
                    atol: 0.0,
                },
                true,
            )?;
            if let Some((joint, residual)) = disagreeing_redundant(model, &y0, &offsets) {
                let joint = &model.joints[joint];
                return Err(SimulateError::Integration {
                    time: 0.0,
                    message: format!(
                        "the joints cannot be assembled: {}/{} repeats other joints' equations but disagrees with them by {residual:.3e} once they hold (its markers are not where the other joints put them)",
                        joint.kind.statement(),
                        joint.id
                    ),
                    place: Place::File(joint.span),
                });
            }
            if let Some(row) = first_repeated(model, &y0, &offsets, &at) {
                let (owner, span) = owner_of_row(model, row);
                return Err(SimulateError::Integration {
                    time: 0.0,
                    message: format!(
                        "{owner} sets a freedom the joints and the equations before it set already (its equation repeats theirs at the start): the mechanism has more motions and constraints than freedoms, and only a joint's repeated equations are left out (remove one of them, or free a joint)"
                    ),
                    place: span.map_or(Place::None, Place::File),
                });
            }
            found
        };
        let equilibrium = if settings.statics {
            let mut put_back = |y: &mut [f64]| {
                if model.is_constrained() {
                    assemble(
                        y,
                        0.0,
                        Tolerance {
                            rtol: 0.0,
                            atol: 0.0,
                        },
                        false,
                    )
                    .map(|_| ())
                } else {
                    Ok(())
                }
            };
            let found = statics::settle(
                model,
                &mut system.mechanics,
                &mut y0,
                &offsets,
                &at,
                &mut put_back,
            )
            .map_err(|unsettled| self.unsettled(unsettled))?;
            // Motions moving at time 0 set their joints' velocities.
            put_back(&mut y0)?;
            Some(found)
        } else {
            None
        };
        system.held = vec![None; system.mechanics.site_count()];
        let mut natural = vec![None; system.mechanics.site_count()];
        let mut switching = vec![0.0; system.mechanics.switch_count()];
        let limit = system
            .mechanics
            .observe(
                0.0,
                &y0,
                None,
                (&mut natural, &mut switching),
                Some(settings.atol),
            )
            .map_err(|error| self.failure(0.0, error))?;
        system.held.clone_from(&natural);
        // `starts`: the state begins a new piece of the DELAYs' records, at
        // a kink of this level (0: the start, a switch).
        let accept =
            |system: &mut Held<'_>, rows: &mut Rows<'_>, t: f64, y: &[f64], starts: Option<u8>| {
                let piece = starts == Some(0);
                system.mechanics.accept(t, y, Some(&system.held), piece)?;
                system
                    .mechanics
                    .record_delays(t, y, Some(&system.held), starts)?;
                rows.accept(t, y, piece)?;
                rows.record_delays(t, y, starts)
            };
        accept(&mut system, &mut rows, 0.0, &y0, Some(0))
            .map_err(|error| self.failure(0.0, error))?;
        let delays = system.mechanics.has_delays() || rows.has_delays();
        // The DELAYs' expressions inside an accepted step that ends at
        // `end`, on its continuous output: SAMPLES_INSIDE samples equally
        // spaced, for the record's polynomials.
        let sample_inside = |system: &mut Held<'_>,
                             rows: &mut Rows<'_>,
                             stepper: &Stepper,
                             end: f64,
                             state: &mut [f64]|
         -> Result<(), (f64, Failed)> {
            let start = stepper.t_previous();
            for sample in 1..=SAMPLES_INSIDE {
                let t = start + (end - start) * f64::from(sample) / f64::from(SAMPLES_INSIDE + 1);
                stepper.dense(t, state);
                system
                    .mechanics
                    .record_delays(t, state, Some(&system.held), None)
                    .map_err(|error| (t, error.into()))?;
                rows.record_delays(t, state, None)
                    .map_err(|error| (t, error))?;
            }
            Ok(())
        };
        // The largest step the DELAYs allow: their shortest delay, so that
        // what they read lies in the record (no less than 1e-4 of the run:
        // a shorter delay reads the line from the last record to now).
        let delay_cap = |system: &Held<'_>| {
            system
                .mechanics
                .smallest_delay()
                .max(DELAY_CAP_FLOOR * settings.end)
        };
        // A stepper's budget: what the steppers before it left.
        let options = |limit: f64, spent: Stats, cap: f64| Options {
            rtol: settings.rtol,
            atol: AbsoluteTolerance::All(settings.atol),
            h_max: settings.h_max.min(floor(limit, 0.0)).min(cap),
            // A finite limit: a weak singularity near (contact::step_limit).
            smooth: limit.is_infinite(),
            max_steps: settings
                .max_steps
                .saturating_sub(spent.steps + spent.rejected)
                .max(1),
            jacobian_reuse: JACOBIAN_REUSE,
            ..Options::default()
        };
        self.start_is_finite(&mut system, &y0)?;
        let mut stepper = Stepper::new(
            settings.method,
            options(limit, Stats::default(), delay_cap(&system)),
            0.0,
            &y0,
            &mut system,
        )
        .map_err(|error| self.integration_error(error))?;
        let mut summary = Summary {
            stats: Stats::default(),
            events: Vec::new(),
            wall_time: Duration::ZERO,
            stopped: false,
            method_changes: Vec::new(),
            stiff_from: None,
            residuals: Residuals::default(),
            initial_residuals,
            projections: 0,
            equilibrium,
            sensor_trips: Vec::new(),
        };
        let mut active = vec![false; model.sensors.len()];
        let mut outputs = OutputTimes::new(settings.end, settings.steps);
        let values = rows
            .at(0.0, &y0)
            .map_err(|error| self.failure(0.0, error))?;
        summary.stopped = sink.row(0.0, values).is_break();
        // The sensors active at the start trip there, before any step (and
        // an EQ sensor's last value is then the start's, so that a crossing
        // inside the first step is seen).
        let at_start = trips_at(
            model,
            (&mut rows, &mut system.mechanics),
            (0.0, &y0),
            &mut active,
            (&mut summary.sensor_trips, &mut outputs),
        )
        .map_err(|error| self.failure(0.0, error))?;
        summary.stopped |= at_start.halted;
        if at_start.evaluated {
            // SENVAL takes its value before the first step, which
            // evaluates the rates again.
            stepper.restart(0.0, &y0);
        }
        let mut dense = vec![0.0; y0.len()];
        let mut recent = VecDeque::new();
        // The counts of the steppers before the last restart.
        let mut before = Stats::default();
        // The state at the start of the step, and the switching values there.
        let mut step_start = y0.clone();
        let mut start_values = switching.clone();
        let mut method = stepper.method();
        while !summary.stopped && stepper.t() < settings.end {
            if sink.stop_requested() {
                summary.stopped = true;
                break;
            }
            step_start.copy_from_slice(stepper.y());
            // Radau5 steps onto the next output time (its continuous output
            // is of lower order than its steps).
            let next_output = outputs.next().filter(|&time| time > stepper.t());
            let mut target = match next_output {
                Some(time) if settings.land_on_outputs && stepper.method() == Method::Radau5 => {
                    time.min(settings.end)
                }
                _ => settings.end,
            };
            // A step lands where a DELAY reads across a kink in its record
            // (its expression's derivatives jump there: the method's error
            // estimate would not see it inside a step).
            if delays {
                let now = stepper.t();
                if let Some((time, _)) = system.mechanics.next_delay_kink(now, kink_gap(now))
                    && time <= target
                {
                    target = time;
                }
            }
            if let Err(error) = stepper.step_to(&mut system, target) {
                let stiff_from = summary.stiff_from.or(stepper.stiff_from());
                return Err(self.stuck(error, (&mut system, &stepper), settings, stiff_from));
            }
            summary.stiff_from = summary.stiff_from.or(stepper.stiff_from());
            if stepper.method() != method {
                let change = MethodChange {
                    time: stepper.t_previous(),
                    from: method,
                    to: stepper.method(),
                };
                method = change.to;
                sink.method_changed(&change);
                summary.method_changes.push(change);
            }
            let (t0, t1) = (stepper.t_previous(), stepper.t());
            let switch = find_switch(
                &mut system,
                &stepper,
                t0,
                t1,
                &start_values,
                &mut natural,
                &mut switching,
            )
            .map_err(|(time, error)| self.failure(time, error))?;
            let mut reached = switch.map_or(t1, |located| located.right);
            // The sensors that become active in a step without a switch,
            // each at the time located on the step's continuous output, in
            // time order; the step is cut at the first that halts the run
            // or sets SENVAL. Looked at four times in the step, so that a
            // sensor active only inside it is seen.
            let cuts = |sensor: usize| {
                let watched = &model.sensors[sensor];
                watched.action.halts() || watched.evaluate.is_some()
            };
            let mut trips: Vec<(usize, f64)> = Vec::new();
            if switch.is_err() && !model.sensors.is_empty() {
                let mut before = t0;
                for look in 1..=SENSOR_LOOKS {
                    let time = if look == SENSOR_LOOKS {
                        t1
                    } else {
                        t0 + (t1 - t0) * look as f64 / SENSOR_LOOKS as f64
                    };
                    stepper.dense(time, &mut dense);
                    let state = if time == t1 { stepper.y() } else { &dense };
                    let newly = rows
                        .tripped(time, state, &mut active)
                        .map_err(|error| self.failure(time, error))?;
                    for sensor in newly {
                        let at = self
                            .locate_trip(&mut rows, &stepper, sensor, before, time, &mut dense)
                            .map_err(|(time, error)| self.failure(time, error))?;
                        trips.push((sensor, at));
                    }
                    if trips.iter().any(|&(sensor, _)| cuts(sensor)) {
                        break;
                    }
                    before = time;
                }
                trips.sort_by(|a, b| a.1.total_cmp(&b.1));
                if let Some(first) = trips.iter().position(|&(sensor, _)| cuts(sensor)) {
                    // The trips at the cut's time all happen there.
                    let cut = trips[first].1;
                    trips.retain(|&(_, time)| time <= cut);
                    reached = cut;
                }
            }
            // The rows up to each trip, the trip (a DT spacing the rows
            // after it anew), then the rows up to the step's end.
            let mut evaluated = Vec::new();
            for &(sensor, time) in &trips {
                if self.write_rows(&mut outputs, time, (&stepper, &mut rows), sink, &mut dense)? {
                    summary.stopped = true;
                    break;
                }
                let watched = &model.sensors[sensor];
                if note_trip(watched, time, &mut summary.sensor_trips, &mut outputs) {
                    // The run ends at the sensor: its last row is there.
                    let state = state_at(&stepper, time, &mut dense);
                    self.last_row(&outputs, time, state, &mut rows, sink)?;
                    summary.stopped = true;
                    break;
                }
                if watched.action == SensorAction::Print && outputs.between_rows(time) {
                    let state = state_at(&stepper, time, &mut dense);
                    if self.row_at(time, state, &mut rows, sink)? {
                        summary.stopped = true;
                        break;
                    }
                }
                if watched.evaluate.is_some() {
                    evaluated.push(sensor);
                }
            }
            if summary.stopped {
                break;
            }
            if self.write_rows(
                &mut outputs,
                reached,
                (&stepper, &mut rows),
                sink,
                &mut dense,
            )? {
                summary.stopped = true;
            }
            if let Some(&sensor) = evaluated.first() {
                let time = reached;
                // SENVAL takes its EVALUATE's value at the trip: the run
                // starts again from there, as after a switch.
                if delays {
                    sample_inside(&mut system, &mut rows, &stepper, time, &mut dense)
                        .map_err(|(time, error)| self.failure(time, error))?;
                }
                if time == t1 {
                    dense.copy_from_slice(stepper.y());
                } else {
                    stepper.dense(time, &mut dense);
                }
                if model.is_constrained() {
                    let found = assemble(&mut dense, time, tolerance, false)?;
                    summary.residuals = summary.residuals.max(found);
                }
                let watched = &model.sensors[sensor];
                if let Some(window) = chatters(&mut recent, time) {
                    return Err(SimulateError::Chattering {
                        time,
                        function: format!("SENSOR/{} (its EVALUATE setting SENVAL)", watched.id),
                        count: CHATTER_COUNT,
                        window,
                        place: Place::File(watched.span),
                    });
                }
                let at = |error: Failed| self.failure(time, error);
                for &sensor in &evaluated {
                    rows.store(sensor, (time, &dense), &mut system.mechanics)
                        .map_err(at)?;
                }
                // The sensors' states at the trip, not at the look after
                // it: those the new values make active trip there too.
                let trips = trips_at(
                    model,
                    (&mut rows, &mut system.mechanics),
                    (time, &dense),
                    &mut active,
                    (&mut summary.sensor_trips, &mut outputs),
                )
                .map_err(at)?;
                if trips.halted {
                    self.last_row(&outputs, time, &dense, &mut rows, sink)?;
                    summary.stopped = true;
                    break;
                }
                if trips.printed && outputs.between_rows(time) {
                    summary.stopped |= self.row_at(time, &dense, &mut rows, sink)?;
                }
                accept(&mut system, &mut rows, time, &dense, Some(0)).map_err(at)?;
                let limit = system
                    .look_and_limit(time, &dense, &mut natural, &mut start_values)
                    .map_err(|error| at(error.into()))?;
                before = add(before, stepper.stats());
                stepper = stepper
                    .fresh_start(
                        options(limit, before, delay_cap(&system)),
                        time,
                        &dense,
                        &mut system,
                    )
                    .map_err(|error| self.integration_error(error))?;
                continue;
            }
            let located = match switch {
                Ok(located) => located,
                Err(limit) => {
                    // The last look was at t1.
                    start_values.copy_from_slice(&switching);
                    if delays {
                        sample_inside(&mut system, &mut rows, &stepper, t1, &mut dense)
                            .map_err(|(time, error)| self.failure(time, error))?;
                    }
                    stepper.set_h_max(settings.h_max.min(floor(limit, t1)).min(delay_cap(&system)));
                    stepper.set_smooth(limit.is_infinite());
                    if model.is_constrained() {
                        dense.copy_from_slice(stepper.y());
                        let tolerance = drift_tolerance(
                            tolerance,
                            (system.mechanics.reaction_push(), &dense),
                            &offsets,
                            t1 - t0,
                        );
                        let found = assemble(&mut dense, t1, tolerance, false)?;
                        summary.residuals = summary.residuals.max(found);
                        if dense != stepper.y() {
                            summary.projections += 1;
                            stepper.nudge(t1, &dense);
                        }
                    }
                    dense.copy_from_slice(stepper.y());
                    // A step landed on a kink begins a piece one level up
                    // (a step that ends within rounding of one has landed
                    // on it too).
                    let starts = system
                        .mechanics
                        .delay_kink_at(t1, kink_gap(t1))
                        .map(|level| level + 1);
                    accept(&mut system, &mut rows, t1, &dense, starts)
                        .map_err(|error| self.failure(t1, error))?;
                    continue;
                }
            };
            let slope =
                switching_slope(&mut system, &stepper, located, &mut natural, &mut switching)
                    .map_err(|(time, error)| self.failure(time, error))?;
            if delays {
                sample_inside(&mut system, &mut rows, &stepper, located.right, &mut dense)
                    .map_err(|(time, error)| self.failure(time, error))?;
            }
            stepper.dense(located.right, &mut dense);
            let step_end = stepper.t();
            let h_before = stepper.h();
            let (right, state) = self.cut(
                &mut system,
                &mut stepper,
                (t0, &step_start, step_end),
                (located, &dense, slope),
                settings,
            )?;
            dense.copy_from_slice(&state);
            let mut residuals = None;
            if model.is_constrained() {
                let tolerance = drift_tolerance(
                    tolerance,
                    (system.mechanics.reaction_push(), &dense),
                    &offsets,
                    right - t0,
                );
                let found = assemble(&mut dense, right, tolerance, false)?;
                summary.residuals = summary.residuals.max(found);
                summary.projections += usize::from(dense != state);
                residuals = Some(found);
            }
            system
                .mechanics
                .observe(right, &dense, None, (&mut natural, &mut switching), None)
                .map_err(|error| self.failure(right, error))?;
            let first_event = summary.events.len();
            for (index, (held, now)) in system.held.iter().zip(&natural).enumerate() {
                if let (Some(from), Some(to)) = (held, now)
                    && from != to
                {
                    let mechanics = &system.mechanics;
                    let event = match (
                        mechanics.contact_of_site(index),
                        mechanics.curve_of_site(index),
                    ) {
                        (Some(contact), _) => contact_event(contact, right, *from, *to),
                        (None, Some((joint, side))) => curve_event(joint, side, right, *from, *to),
                        (None, None) => {
                            self.event(program, &program.sites()[index], right, *from, *to)
                        }
                    };
                    summary.events.push(event);
                }
            }
            system.held.clone_from(&natural);
            accept(&mut system, &mut rows, right, &dense, Some(0))
                .map_err(|error| self.failure(right, error))?;
            // SENVAL takes its EVALUATE's value; the fresh start below
            // begins with it.
            let trips = trips_at(
                model,
                (&mut rows, &mut system.mechanics),
                (right, &dense),
                &mut active,
                (&mut summary.sensor_trips, &mut outputs),
            )
            .map_err(|error| self.failure(right, error))?;
            if trips.halted {
                self.last_row(&outputs, right, &dense, &mut rows, sink)?;
                summary.stopped = true;
                break;
            }
            if trips.printed && outputs.between_rows(right) {
                summary.stopped |= self.row_at(right, &dense, &mut rows, sink)?;
            }
            let values = rows
                .at(right, &dense)
                .map_err(|error| self.failure(right, error))?;
            for event in &mut summary.events[first_event..] {
                event.values = values.to_vec();
                event.residuals = residuals;
                if sink.event(event).is_break() {
                    summary.stopped = true;
                }
            }
            let limit = system
                .look_and_limit(right, &dense, &mut natural, &mut start_values)
                .map_err(|error| self.failure(right, error))?;
            if let Some(window) = chatters(&mut recent, right)
                && let Some(event) = summary.events.last()
            {
                return Err(SimulateError::Chattering {
                    time: right,
                    function: event.function.clone(),
                    count: CHATTER_COUNT,
                    window,
                    place: event.place,
                });
            }
            // A fresh start: the first step is chosen anew for the new
            // branch (a step fit for free flight would cross a contact),
            // but after a curve's knot alone, where the motion goes on as
            // smoothly as before but for its third derivative, the step
            // goes on as it was (the error control shrinks it if need be).
            let switched = &summary.events[first_event..];
            let knots_only = !switched.is_empty()
                && switched
                    .iter()
                    .all(|event| matches!(event.function.as_str(), "PTCV" | "CVCV"));
            before = add(before, stepper.stats());
            stepper = stepper
                .fresh_start(
                    Options {
                        h_init: (knots_only && h_before.is_finite() && h_before > 0.0)
                            .then_some(h_before),
                        ..options(limit, before, delay_cap(&system))
                    },
                    right,
                    &dense,
                    &mut system,
                )
                .map_err(|error| self.integration_error(error))?;
        }
        summary.stats = add(before, stepper.stats());
        summary.wall_time = started.elapsed();
        Ok(summary)
    }

    /// The state at a switch located on a step's continuous output, from
    /// integrating again from the start `(t0, y0)` of the step that ends at
    /// `step_end` on the branches
    /// held through the step (the stepper restarted there): the continuous
    /// output may be of lower order than the steps (Radau's), so the time
    /// is refined on the integrated states, by Newton's rule with the
    /// switching value's `slope` in time, until the state lies past the
    /// switch by no more than the location's tolerance. When the integrated
    /// states never confirm the switch (a loose tolerance, where the
    /// continuous output strays), the located time and `located_state`, the
    /// continuous output's state there, are kept. The time and the state;
    /// a step budget spent in the integration is the settings' (as in a
    /// step of the run).
    fn cut(
        &self,
        system: &mut Held<'_>,
        stepper: &mut Stepper,
        (t0, y0, step_end): (f64, &[f64], f64),
        (located, located_state, slope): (Switch, &[f64], f64),
        settings: &Settings,
    ) -> Result<(f64, Vec<f64>), SimulateError> {
        let mut natural = vec![None; system.mechanics.site_count()];
        let mut switching = vec![0.0; system.mechanics.switch_count()];
        let tolerance = 1e-13 * located.right.abs().max(located.right - t0);
        let mut time = located.right;
        let mut best: Option<(f64, Vec<f64>)> = None;
        for _ in 0..4 {
            stepper.restart(t0, y0);
            while stepper.t() < time {
                if let Err(error) = stepper.step_to(system, time) {
                    return Err(self.stuck(error, (system, stepper), settings, None));
                }
            }
            let state = stepper.y().to_vec();
            system
                .look(time, &state, &mut natural, &mut switching)
                .map_err(|error| self.failure(time, error))?;
            let value = switching[located.index];
            let root = time - value / slope;
            if value < 0.0 {
                let past = time - root <= tolerance || !root.is_finite();
                best = Some((time, state));
                if past {
                    break;
                }
            }
            // Newton's rule is trusted inside the step only (a slope near
            // zero throws it far past it).
            if !(root.is_finite() && root > t0 && root <= step_end) {
                break;
            }
            // Aim just past the switch.
            time = root + 0.5 * tolerance;
        }
        Ok(best.unwrap_or_else(|| (located.right, located_state.to_vec())))
    }

    /// The error of an evaluation that failed at `time`, placed in the
    /// expression of its program's output.
    fn failure(&self, time: f64, failed: impl Into<Failed>) -> SimulateError {
        let (program, error) = match failed.into() {
            Failed::Dynamics(error) => (&self.dynamics, error),
            Failed::Outputs(error) => (&self.outputs, error),
        };
        if error.output == JOINTS {
            SimulateError::Integration {
                time,
                message: error.error.to_string(),
                place: self.joints_place(&error),
            }
        } else {
            SimulateError::Evaluation {
                time,
                expression: self.expression_of(program, error.output),
                error: error.error,
            }
        }
    }

    /// Where the joints' failure `error` is placed: at the statement it
    /// names (a PTCV that lost its curve), else at the first massless part
    /// when the model has one (the likelier cause is a freedom its joints
    /// leave it, [`crate::simulate::constraints::joints_singular_in`],
    /// whose message names them all), else nowhere in the file.
    fn joints_place(&self, error: &OutputError) -> Place {
        let span = error.error.span();
        if span != crate::span::Span::default() {
            return Place::File(span);
        }
        self.model
            .masses
            .iter()
            .find(|mass| mass.is_massless())
            .map_or(Place::None, |part| Place::File(part.span))
    }

    /// The model expression that output `output` of `program` computes
    /// (a motion's FUNCTION past [`MOTIONS`]).
    fn expression_of(&self, program: &Program, output: usize) -> usize {
        if let Some(motion) = output.checked_sub(MOTIONS) {
            self.model
                .motion_functions()
                .nth(motion)
                .unwrap_or_default()
        } else if std::ptr::eq(program, &self.dynamics) {
            self.computed[output]
        } else {
            self.output_expressions[output]
        }
    }

    /// The event of `site` switching from `from` to `to` at `time`.
    fn event(
        &self,
        program: &Program,
        site: &crate::compile::Site,
        time: f64,
        from: Code,
        to: Code,
    ) -> Event {
        let index = site.instruction as usize;
        let (function, from, to) = match program.site_kind(site) {
            SiteKind::Call(function) => (
                function.name().to_string(),
                branch::describe(function, from),
                branch::describe(function, to),
            ),
            SiteKind::If => (
                "IF".to_string(),
                branch::describe_if(from).to_string(),
                branch::describe_if(to).to_string(),
            ),
        };
        let expression = self.expression_of(program, program.origin(index));
        Event {
            time,
            function,
            place: Place::Expression {
                expression,
                span: program.span(index),
            },
            label: self.model.expressions[expression].label.clone(),
            from,
            to,
            values: Vec::new(),
            residuals: None,
        }
    }

    /// The error for a step that fails: [`Self::step_error`], with the
    /// state that changes fastest at the last state reached where the steps
    /// shrank to nothing (or why the rates fail there).
    fn stuck(
        &self,
        error: IntegrateError<OutputError>,
        (system, stepper): (&mut Held<'_>, &Stepper),
        settings: &Settings,
        stiff_from: Option<f64>,
    ) -> SimulateError {
        let stalled = matches!(
            error,
            IntegrateError::StepSizeTooSmall {
                cause: Rejection::Tolerance
                    | Rejection::NonFinite
                    | Rejection::Newton
                    | Rejection::Singular,
                ..
            } | IntegrateError::Stalled { .. }
        );
        let fastest = stalled
            .then(|| self.fastest_state(system, (stepper.t(), stepper.y()), settings))
            .flatten();
        self.step_error(error, settings, stiff_from, fastest)
    }

    /// The error for an integration that cannot go on.
    /// [`Self::integration_error`], but the step budget named as the
    /// settings' and, when DOP853 found the run stiff, the method to take.
    fn step_error(
        &self,
        error: IntegrateError<OutputError>,
        settings: &Settings,
        stiff_from: Option<f64>,
        fastest: Option<Result<(usize, f64), SimulateError>>,
    ) -> SimulateError {
        let stiff = stiff_from.map_or(String::new(), |from| {
            format!(
                "; the run is stiff from t = {} (DOP853's steps are held by stability there): Radau5 takes far fewer",
                Shown(from)
            )
        });
        let (time, mut message, mut place) = match error {
            IntegrateError::TooManySteps { t, .. } => (
                t,
                format!(
                    "more than {} steps, accepted and rejected, the most the settings allow{stiff}",
                    settings.max_steps
                ),
                Place::None,
            ),
            IntegrateError::Stalled { t, steps, advance } => (
                t,
                format!(
                    "it stalls: its last {steps} accepted steps advanced the time by only {}, so the solution is nearly singular here (a FUNCTION, a MOTION or a force that grows without bound as the time nears a pole){stiff}",
                    Shown(advance)
                ),
                Place::None,
            ),
            other => match self.integration_error(other) {
                SimulateError::Integration {
                    time,
                    message,
                    place,
                } => (time, message, place),
                other => return other,
            },
        };
        match fastest {
            Some(Ok((state, rate))) => {
                let owner;
                (owner, place) = self.state_owner(state);
                message = format!(
                    "{message}; the state that changes fastest for its tolerance is {owner} (its rate of change {}): check the initial conditions and forces that drive it",
                    Shown(rate)
                );
            }
            Some(Err(failure)) => {
                place = failure.place();
                let why = match failure {
                    SimulateError::Evaluation { error, .. } => error.to_string(),
                    SimulateError::Integration { message, .. } => message,
                    other => other.to_string(),
                };
                message = format!("{message}; at the last state it reached, {why}");
            }
            None => {}
        }
        SimulateError::Integration {
            time,
            message,
            place,
        }
    }

    /// Hands `sink` the rows due up to `limit` within the last step, from
    /// its continuous output; `true` when the sink stops the run.
    fn write_rows(
        &self,
        outputs: &mut OutputTimes,
        limit: f64,
        (stepper, rows): (&Stepper, &mut Rows<'_>),
        sink: &mut impl Sink,
        dense: &mut [f64],
    ) -> Result<bool, SimulateError> {
        while let Some(time) = outputs.next().filter(|&time| time <= limit) {
            let state = state_at(stepper, time, dense);
            let stop = self.row_at(time, state, rows, sink)?;
            outputs.written(time);
            if stop {
                return Ok(true);
            }
        }
        Ok(false)
    }

    /// Writes the row at `time`, the state there `state`; says whether the
    /// sink asks the run to stop.
    fn row_at(
        &self,
        time: f64,
        state: &[f64],
        rows: &mut Rows<'_>,
        sink: &mut impl Sink,
    ) -> Result<bool, SimulateError> {
        self.finite_row(time, state)?;
        let values = rows
            .at(time, state)
            .map_err(|error| self.failure(time, error))?;
        Ok(sink.row(time, values).is_break())
    }

    /// The last row of a run a sensor halts at `time`, the state there
    /// `state`, unless a row at `time` (or the run's end) has been written
    /// already; an error where the state is not a finite number.
    fn last_row(
        &self,
        outputs: &OutputTimes,
        time: f64,
        state: &[f64],
        rows: &mut Rows<'_>,
        sink: &mut impl Sink,
    ) -> Result<(), SimulateError> {
        if outputs.last() < time {
            // The run ends here whatever the sink says.
            let _ = self.row_at(time, state, rows, sink)?;
        }
        Ok(())
    }

    /// An error where the state of a row from a step's continuous output
    /// is not a finite number (the steps' ends were: the polynomial's
    /// coefficients overflow near the largest double), naming the state.
    fn finite_row(&self, time: f64, state: &[f64]) -> Result<(), SimulateError> {
        match state.iter().position(|value| !value.is_finite()) {
            None => Ok(()),
            Some(index) => {
                let (owner, place) = self.state_owner(index);
                Err(SimulateError::Integration {
                    time,
                    message: format!(
                        "the continuous output of the step is not a finite number for {owner} (its values near the largest double, 1e308, overflow): the model diverges, or its units make its numbers too large"
                    ),
                    place,
                })
            }
        }
    }

    /// The time in the step `(t0, t1]` at which `sensor` becomes active,
    /// bisected on the step's continuous output to rounding (it is active
    /// at `t1`; at `t0` it was not, or the run just started).
    fn locate_trip(
        &self,
        rows: &mut Rows<'_>,
        stepper: &Stepper,
        sensor: usize,
        t0: f64,
        t1: f64,
        dense: &mut [f64],
    ) -> Result<f64, (f64, Failed)> {
        let watched = &self.model.sensors[sensor];
        let index = sensor;
        let mut sensed_at = |t: f64, dense: &mut [f64]| {
            stepper.dense(t, dense);
            rows.at(t, dense).map_err(|error| (t, error))?;
            Ok::<f64, (f64, Failed)>(rows.sensed()[index])
        };
        let first = sensed_at(t0, dense)?;
        if watched.is_active(first) {
            return Ok(t0);
        }
        // Active from the first time it is within its band, or (an EQ
        // sensor stepped over) past its value.
        let mut active_at = |t: f64, dense: &mut [f64]| {
            let value = sensed_at(t, dense)?;
            Ok(watched.is_active(value) || watched.passes(first, value))
        };
        let (mut inactive, mut active) = (t0, t1);
        while active - inactive > 4.0 * f64::EPSILON * active.abs().max(1e-300) {
            let middle = 0.5 * (inactive + active);
            if middle <= inactive || middle >= active {
                break;
            }
            if active_at(middle, dense)? {
                active = middle;
            } else {
                inactive = middle;
            }
        }
        Ok(active)
    }

    /// What state `state` is, `DIFF/3` or `PART/2's angular velocity`, and
    /// the place of its DIFF's FUNCTION or its part's statement.
    fn state_owner(&self, state: usize) -> (String, Place) {
        self.state_or_rate_owner(state, false)
    }

    /// [`Self::state_owner`], or, with `rate`, what state `state`'s rate
    /// of change is: `DIFF/3's rate`, `PART/2's angular acceleration`.
    fn state_or_rate_owner(&self, state: usize, rate: bool) -> (String, Place) {
        let model = self.model;
        if let Some(diff) = model.diffs.get(state) {
            let expression = &model.expressions[diff.function];
            return (
                format!("{}{}", diff.label(), if rate { "'s rate" } else { "" }),
                Place::Expression {
                    expression: diff.function,
                    span: crate::span::Span::new(0, expression.text.text.len()),
                },
            );
        }
        let body = (state - model.diffs.len()) / BODY_STATES;
        let (quantity, its_rate) = match (state - model.diffs.len()) % BODY_STATES {
            0..3 => ("position", "velocity"),
            3..7 => ("orientation", "orientation's rate"),
            7..10 => ("velocity", "linear acceleration"),
            _ => ("angular velocity", "angular acceleration"),
        };
        let quantity = if rate { its_rate } else { quantity };
        (
            format!("{}'s {quantity}", model.scene.bodies[body].name),
            model
                .masses
                .get(body)
                .map_or(Place::None, |mass| Place::File(mass.span)),
        )
    }

    /// The state that changes fastest for the error it may have, at `(t,
    /// y)`: the largest `|dy/dt| / (atol + rtol |y|)` (where a run whose
    /// steps shrink to nothing without a failing expression is stuck), with
    /// its rate of change; where the rates cannot be evaluated there, why;
    /// `None` for a run without states.
    fn fastest_state(
        &self,
        system: &mut Held<'_>,
        (t, y): (f64, &[f64]),
        settings: &Settings,
    ) -> Option<Result<(usize, f64), SimulateError>> {
        let mut rates = vec![0.0; y.len()];
        if let Err(error) = system.mechanics.rates(t, y, Some(&system.held), &mut rates) {
            return Some(Err(self.failure(t, error)));
        }
        let scaled = |i: usize| {
            let scale = settings.atol + settings.rtol * y[i].abs();
            let value = rates[i].abs() / scale;
            if value.is_nan() { f64::INFINITY } else { value }
        };
        (0..y.len())
            .max_by(|&a, &b| scaled(a).total_cmp(&scaled(b)))
            .map(|state| Ok((state, rates[state])))
    }

    /// An error, at the statement of the part or DIFF it names, when the
    /// state at the start or its rates of change are not finite numbers
    /// (an initial velocity or force beyond the range of a double): no
    /// step can start from it.
    fn start_is_finite(&self, system: &mut Held<'_>, y0: &[f64]) -> Result<(), SimulateError> {
        let mut rates = vec![0.0; y0.len()];
        system
            .mechanics
            .rates(0.0, y0, Some(&system.held), &mut rates)
            .map_err(|error| self.failure(0.0, error))?;
        let found = |values: &[f64]| values.iter().position(|value| !value.is_finite());
        let (state, what, value) = match (found(y0), found(&rates)) {
            (Some(state), _) => (state, "value", y0[state]),
            (None, Some(state)) => (state, "rate of change", rates[state]),
            (None, None) => return Ok(()),
        };
        let (owner, place) = self.state_owner(state);
        Err(SimulateError::Integration {
            time: 0.0,
            message: format!(
                "the start is not finite: {owner} has the {what} {} (an initial condition, velocity or force beyond the range of a double: give smaller values)",
                Shown(value)
            ),
            place,
        })
    }

    /// The error of a static equilibrium that is not found.
    fn unsettled(&self, unsettled: statics::Unsettled) -> SimulateError {
        match unsettled {
            statics::Unsettled::Evaluation(error) => self.failure(0.0, Failed::Dynamics(error)),
            statics::Unsettled::Assembly(error) => error,
            statics::Unsettled::NotFinite => SimulateError::Integration {
                time: 0.0,
                message: "no static equilibrium found: the accelerations' derivatives in the parts' places are not finite numbers (a force or the gravity is beyond the floating-point range; check ACCGRAV and the forces' sizes)".to_string(),
                place: Place::None,
            },
            statics::Unsettled::Moving { state, residual } => {
                // The residual is of the state's rate of change.
                let (what, place) = self.state_or_rate_owner(state, true);
                SimulateError::Integration {
                    time: 0.0,
                    message: format!(
                        "no static equilibrium found from the initial conditions: Newton's iterations end with {what} at {residual:.3e} (the forces may have no balance near the start, or a freedom no force holds: start the dynamics from the initial conditions without SIMULATE/STATICS or --statics)"
                    ),
                    place,
                }
            }
        }
    }

    /// The simulator's error for the integrator's, with the expression
    /// whose evaluation failed when that was the cause.
    fn integration_error(&self, error: IntegrateError<OutputError>) -> SimulateError {
        let (time, cause) = match &error {
            IntegrateError::Start { t, cause }
            | IntegrateError::StepSizeTooSmall { t, cause, .. } => (*t, Some(cause)),
            IntegrateError::TooManySteps { t, .. }
            | IntegrateError::Stalled { t, .. }
            | IntegrateError::JacobianNotFinite { t }
            | IntegrateError::EndNotAhead { t, .. } => (*t, None),
            IntegrateError::Jacobian { t, error } if error.output == JOINTS => {
                return SimulateError::Integration {
                    time: *t,
                    message: format!("the Jacobian: {}", error.error),
                    place: self.joints_place(error),
                };
            }
            IntegrateError::Jacobian { t, error } => {
                return SimulateError::Evaluation {
                    time: *t,
                    expression: self.expression_of(&self.dynamics, error.output),
                    error: error.error.clone(),
                };
            }
            IntegrateError::Settings(message) => {
                return SimulateError::Settings {
                    message: message.clone(),
                    span: None,
                };
            }
        };
        let place = match cause {
            Some(Rejection::System(failure)) if failure.output != JOINTS => Place::Expression {
                expression: self.expression_of(&self.dynamics, failure.output),
                span: failure.error.span(),
            },
            Some(Rejection::System(failure)) => self.joints_place(failure),
            _ => Place::None,
        };
        SimulateError::Integration {
            time,
            message: error.to_string(),
            place,
        }
    }
}

/// The index of each body's first state in the state vector.
pub(super) fn body_offsets(model: &Model) -> Vec<usize> {
    (0..model.masses.len())
        .map(|body| body_offset(model, body))
        .collect()
}
