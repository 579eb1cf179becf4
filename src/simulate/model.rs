//! What a simulation integrates, whichever file it came from: the scene
//! (bodies at their initial states, markers, the data of VARIABLE, ARRAY,
//! SPLINE and DIFF statements), the bodies' masses, the force elements and
//! DIFF equations with their expressions, gravity, and the output columns.

use nalgebra::{Matrix3, Vector3};

use crate::check::Checked;
use crate::laws::contact::Stops;
use crate::model::Embedded;
use crate::scene::{Scene, Target};
use crate::simulate::curve::Curve;
use crate::span::Span;

/// A model ready to simulate (see [`crate::simulate::from_dataset`] and
/// [`crate::simulate::from_scene`]).
#[derive(Clone, Debug)]
pub struct Model {
    /// The world the expressions are evaluated in, at time 0.
    pub scene: Scene,
    /// The mass of each of the scene's bodies, in the same order.
    pub masses: Vec<MassProperties>,
    /// The differential states, in the order of their output columns.
    pub diffs: Vec<Diff>,
    /// The force elements.
    pub forces: Vec<Force>,
    /// The statement (`SFORCE`, `VFORCE`, `VTORQUE`, `GFORCE`, `BUSHING`,
    /// `SPRINGDAMPER`, `CONTACT`) and id of each force element, in the order of
    /// [`Model::forces`]; empty for a scene, whose forces have no id.
    pub force_statements: Vec<(&'static str, u64)>,
    /// The joints, held by Lagrange multipliers
    /// ([`crate::simulate::Joint`]).
    pub joints: Vec<Joint>,
    /// The motions imposed on joints.
    pub motions: Vec<Motion>,
    /// The motions imposed between two markers (their equations and
    /// FUNCTIONs after those of [`Model::motions`]).
    pub marker_motions: Vec<MarkerMotion>,
    /// The couplers between joints' displacements (their equations after
    /// the motions').
    pub couplers: Vec<Coupler>,
    /// The general constraints (`GCON`), their equations after the
    /// couplers'.
    pub general_constraints: Vec<GeneralConstraint>,
    /// The joints' initial conditions (`IC`, `ICTRAN`, `ICROT`), held in
    /// the initial-conditions analysis only.
    pub joint_initials: Vec<JointInitial>,
    /// The parts whose coordinates the initial-conditions analysis keeps
    /// (`EXACT`).
    pub exact: Vec<ExactPart>,
    /// The parts' velocities the dataset gives (`VX ... WZ`), held in the
    /// initial-conditions analysis of the velocities where the joints
    /// leave them free; those it leaves out are free.
    pub given_velocities: Vec<GivenVelocity>,
    /// The sensors, watched after every accepted step.
    pub sensors: Vec<Sensor>,
    /// The acceleration of gravity, in ground.
    pub gravity: Vector3<f64>,
    /// Every expression of the model: the DIFF functions, the force
    /// components, the outputs. Forces, DIFFs and outputs refer to them by
    /// index.
    pub expressions: Vec<Expression>,
    /// Named output columns after the states (REQUESTs, named expressions).
    pub outputs: Vec<Output>,
    /// What the model's file says that the simulation leaves aside (a
    /// REQUEST kind it does not compute, solver settings), each with its place.
    pub notes: Vec<(String, Span)>,
    /// The end time and number of output steps the file gives (a
    /// `SIMULATE/DYNAMIC` command), when it gives them.
    pub run: Option<(f64, usize)>,
    /// Whether the file asks for a static equilibrium before the dynamics
    /// (`SIMULATE/STATICS` first in the `.acf`).
    pub statics: bool,
    /// Whether the `.acf` asks Radau5 to step onto each output time
    /// (`INTEGRATOR/INTERPOLATE = OFF`): [`crate::simulate::Settings::land_on_outputs`].
    pub land_on_outputs: bool,
}

impl Model {
    /// Whether anything holds the bodies by multipliers: a joint, a
    /// primitive or a motion between markers (a motion on a joint comes
    /// with its joint).
    pub(crate) fn is_constrained(&self) -> bool {
        !self.joints.is_empty()
            || !self.marker_motions.is_empty()
            || !self.couplers.is_empty()
            || !self.general_constraints.is_empty()
    }

    /// The FUNCTION of every motion: those on joints, then those between
    /// markers (the order of the drives and of the motions' equations).
    pub(crate) fn motion_functions(&self) -> impl Iterator<Item = usize> + '_ {
        self.motions
            .iter()
            .map(|motion| motion.function)
            .chain(self.marker_motions.iter().map(|motion| motion.function))
    }

    /// What the FUNCTION of every motion gives, in the same order.
    pub(crate) fn motion_givens(&self) -> impl Iterator<Item = Given> + '_ {
        self.motions
            .iter()
            .map(|motion| motion.given)
            .chain(self.marker_motions.iter().map(|motion| motion.given))
    }

    /// The id and statement of every motion, in the same order.
    pub(crate) fn motion_statements(&self) -> impl Iterator<Item = (u64, Span)> + '_ {
        self.motions
            .iter()
            .map(|motion| (motion.id, motion.span))
            .chain(
                self.marker_motions
                    .iter()
                    .map(|motion| (motion.id, motion.span)),
            )
    }

    /// The inverse inertia of each body, in its own axes.
    pub(crate) fn inverse_inertia(&self) -> Vec<Matrix3<f64>> {
        self.masses
            .iter()
            .map(|mass| mass.inertia.try_inverse().unwrap_or_else(Matrix3::zeros))
            .collect()
    }
}

/// The mass, centre of mass and inertia of a body.
#[derive(Clone, Debug, PartialEq)]
pub struct MassProperties {
    /// The mass: positive, or 0 for a massless part (which the joints
    /// hold: its accelerations come with the reactions).
    pub mass: f64,
    /// The centre of mass in the body frame.
    pub centre: Vector3<f64>,
    /// The inertia tensor about the centre of mass, in the body's axes
    /// (symmetric, positive definite).
    pub inertia: Matrix3<f64>,
    /// Where the body is defined (for messages).
    pub span: Span,
}

impl MassProperties {
    /// Whether it is a POINT_MASS's: a mass without inertia, which no
    /// torque turns.
    pub fn is_point_mass(&self) -> bool {
        self.mass > 0.0 && self.inertia == Matrix3::zeros()
    }

    /// A massless part: no mass, no inertia.
    pub fn is_massless(&self) -> bool {
        self.mass == 0.0
    }
}

/// A differential state `DIFF/id`: `d DIF(id)/dt = FUNCTION`.
#[derive(Clone, Debug, PartialEq)]
pub struct Diff {
    /// The statement id (0 for a linear system's state).
    pub id: u64,
    /// The initial value.
    pub initial: f64,
    /// Its FUNCTION, an index into [`Model::expressions`].
    pub function: usize,
    /// The linear system (TFSISO, LSE) whose state it is, `None` for a
    /// DIFF.
    pub linear: Option<LinearState>,
    /// `STATIC_HOLD`: a static equilibrium (`--statics`) keeps it at its
    /// value instead of making its rate zero.
    pub static_hold: bool,
    /// `IMPLICIT`: FUNCTION = 0 defines the rate, with the rate to start
    /// the search from (the IC's second value, 0 when not given); `None`
    /// for an explicit DIFF, whose FUNCTION is the rate.
    pub implicit: Option<f64>,
    /// The `FRICTION` whose stiction creep it is (its input a `DIF` of an
    /// id past the dataset's DIFFs) and the direction of the slip it is
    /// along (0 when the slip has one, else from 1), `None` for the
    /// others.
    pub creep: Option<(u64, usize)>,
}

/// A state of a control element's linear system: entry `entry` (from 1)
/// of its X array.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearState {
    /// `TFSISO/3`.
    pub statement: String,
    /// The X array.
    pub array: u64,
    /// The entry, from 1.
    pub entry: usize,
}

impl Diff {
    /// The name of the input that holds it: `DIF(3)`, `ARYVAL(4, 2)`.
    pub fn input(&self) -> String {
        match &self.linear {
            None => crate::scene::diff_input(self.id),
            Some(state) => crate::scene::array_state_input(state.array, state.entry),
        }
    }

    /// Its column in a run's rows: `DIF(3)`, `TFSISO/2.x1`,
    /// `FRICTION/4.creep`, `FRICTION/4.creep2` (no comma, so that a CSV
    /// header needs no quoting).
    pub fn column(&self) -> String {
        if let Some((friction, direction)) = self.creep {
            return match direction {
                0 => format!("FRICTION/{friction}.creep"),
                _ => format!("FRICTION/{friction}.creep{direction}"),
            };
        }
        match &self.linear {
            None => crate::scene::diff_input(self.id),
            Some(state) => format!("{}.x{}", state.statement, state.entry),
        }
    }

    /// What it is in messages: `DIFF/3`, `TFSISO/2's state 1`,
    /// `FRICTION/4's creep`, `FRICTION/4's creep 2`.
    pub fn label(&self) -> String {
        if let Some((friction, direction)) = self.creep {
            return match direction {
                0 => format!("FRICTION/{friction}'s creep"),
                _ => format!("FRICTION/{friction}'s creep {direction}"),
            };
        }
        match &self.linear {
            None => format!("DIFF/{}", self.id),
            Some(state) => format!("{}'s state {}", state.statement, state.entry),
        }
    }
}

/// A force element: its geometry, and the expressions of its components.
#[derive(Clone, Debug, PartialEq)]
pub enum Force {
    /// `SFORCE, TRANSLATIONAL`: a force of the given magnitude along the
    /// line from J to I, on I's body at I (positive pushes them apart) and
    /// the opposite on J's body at J; with `action_only`, along the z axis
    /// of J, on I's body only.
    Translational {
        /// The marker the force acts at.
        i: Target,
        /// The marker it reacts at (or whose z axis it acts along).
        j: Target,
        /// The magnitude, an index into [`Model::expressions`].
        magnitude: usize,
        /// Along J's z axis, on I's body only.
        action_only: bool,
    },
    /// `SFORCE, ROTATIONAL`: a torque about the z axis of J, on I's body and
    /// the opposite on J's body (not with `action_only`).
    Rotational {
        /// The marker on the body the torque acts on.
        i: Target,
        /// The marker whose z axis the torque is about.
        j: Target,
        /// The magnitude, an index into [`Model::expressions`].
        magnitude: usize,
        /// On I's body only.
        action_only: bool,
    },
    /// `VFORCE`, `VTORQUE`, `GFORCE`: force and torque components along the
    /// axes of marker RM, on I's body at I, and the opposite on the body of
    /// the floating marker JFLOAT (at the same point), when it is not ground.
    Vector {
        /// The marker the force acts at.
        i: Target,
        /// The body that takes the reaction (`None`: ground).
        reaction: Option<usize>,
        /// The marker whose axes the components are along.
        axes: Target,
        /// Force components, indices into [`Model::expressions`].
        force: [Option<usize>; 3],
        /// Torque components, indices into [`Model::expressions`].
        torque: [Option<usize>; 3],
    },
    /// `CONTACT`: a force where two solids overlap (see [`Contact`]).
    Contact(Box<Contact>),
}

/// A `CONTACT` between one solid of each of two parts: where they overlap,
/// a normal force by the `IMPACT` law of the depth and its rate, and
/// optionally Coulomb friction against the slip, on I's part at the
/// contact point and the opposite on J's.
#[derive(Clone, Debug, PartialEq)]
pub struct Contact {
    /// The solid of the I part (`IGEOM`).
    pub i: Solid,
    /// The solid of the J part (`JGEOM`).
    pub j: Solid,
    /// `STIFFNESS`: the normal force is `STIFFNESS·depth^EXPONENT`.
    pub stiffness: f64,
    /// `EXPONENT` of the depth.
    pub exponent: f64,
    /// `DAMPING`: the damping coefficient at full depth.
    pub damping: f64,
    /// `DMAX`: the depth at which the damping is full (a cubic step from
    /// none at first touch).
    pub damping_depth: f64,
    /// Coulomb friction, when it is on.
    pub friction: Option<Friction>,
    /// The statement id.
    pub id: u64,
    /// The statement (for messages and events).
    pub span: Span,
}

impl Contact {
    /// The normal force's law: `IMPACT(x, v, 0, k, e, c, d)` of the
    /// separation `x = -depth` and its rate.
    pub(crate) fn law(&self) -> Stops {
        Stops::new(
            0.0,
            None,
            [
                self.stiffness,
                self.exponent,
                self.damping,
                self.damping_depth,
            ],
        )
    }
}

/// A contact's Coulomb friction: its coefficient a function of the slip
/// speed `v` at the contact point, `STEP(v, -vs, -μs, vs, μs)` below the
/// stiction transition velocity `vs`, `STEP(v, vs, μs, vd, μd)` up to the
/// friction transition velocity `vd`, and `μd` beyond.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    /// `MU_STATIC` (`μs`).
    pub static_coefficient: f64,
    /// `MU_DYNAMIC` (`μd`).
    pub dynamic_coefficient: f64,
    /// `STICTION_TRANSITION_VELOCITY` (`vs`).
    pub stiction_velocity: f64,
    /// `FRICTION_TRANSITION_VELOCITY` (`vd`).
    pub friction_velocity: f64,
}

/// A solid a contact meets: its shape in the axes of a marker.
#[derive(Clone, Debug, PartialEq)]
pub struct Solid {
    /// The marker whose origin and axes place the shape.
    pub marker: Target,
    /// The shape.
    pub shape: Shape,
}

/// The sine of the largest angle between two cylinders' axes that a
/// contact takes for parallel where the model is drawn; in a run, the
/// joints that keep them so hold them to the integration's accuracy, and
/// a run whose cylinders turn further apart (beyond a thousandth of a
/// radian) stops at the contact.
pub(crate) const PARALLEL_AXES: f64 = 1e-6;

/// The shapes a contact meets (GRAPHICS statements).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// `ELLIPSOID` with equal scales: a sphere about the marker's origin.
    Sphere {
        /// Half the scale (Adams' scales are diameters).
        radius: f64,
    },
    /// `BOX`: the block between the marker's origin and the corner
    /// `(X, Y, Z)` in its axes (each length of either sign).
    Block {
        /// The least corner, in the marker's axes.
        lower: Vector3<f64>,
        /// The greatest corner, in the marker's axes.
        upper: Vector3<f64>,
    },
    /// `CYLINDER` or `FRUSTUM`: a round solid about the marker's z axis,
    /// from its origin to `LENGTH` along z (either sign), its radius
    /// changing linearly along the axis (a cylinder's is constant; a
    /// cone's is 0 at its tip).
    Frustum {
        /// The radii at `bottom` and at `top`.
        radii: [f64; 2],
        /// The least z.
        bottom: f64,
        /// The greatest z.
        top: f64,
    },
    /// `PLANE`: the half-space below the marker's x-y plane (its z axis is
    /// the outward normal), unbounded.
    HalfSpace,
}

impl Force {
    /// An `SFORCE` of one component: a torque about J's z axis when
    /// `rotational`, a force along the line from J to I otherwise.
    pub(crate) fn single(
        rotational: bool,
        i: Target,
        j: Target,
        magnitude: usize,
        action_only: bool,
    ) -> Force {
        if rotational {
            Force::Rotational {
                i,
                j,
                magnitude,
                action_only,
            }
        } else {
            Force::Translational {
                i,
                j,
                magnitude,
                action_only,
            }
        }
    }
}

/// An expression of the model, with its text and how to find it in the file.
#[derive(Clone, Debug, PartialEq)]
pub struct Expression {
    /// What it is: `SFORCE/3 FUNCTION`, `force contact`.
    pub label: String,
    /// The checked expression.
    pub checked: Checked,
    /// The text and the way from each of its bytes back to the file.
    pub text: Embedded,
}

impl Expression {
    /// The span in the file of `span` in the expression's text.
    pub fn file_span(&self, span: Span) -> Span {
        self.text.file_span(span)
    }
}

/// A named output column, computed at every output time.
#[derive(Clone, Debug, PartialEq)]
pub struct Output {
    /// The column name: `REQUEST/4.F2`, `gap`.
    pub name: String,
    /// An index into [`Model::expressions`].
    pub expression: usize,
}

/// The kinds of joint simulated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// Origins and axes together: no relative motion (6 equations).
    Fixed,
    /// Origins together, z axes parallel: a rotation about z (5).
    Revolute,
    /// Axes parallel, I's origin on J's z axis: a translation along z (5).
    Translational,
    /// Origins together: any rotation (3).
    Spherical,
    /// z axes parallel, I's origin on J's z axis: a rotation about and a
    /// translation along z (4).
    Cylindrical,
    /// z axes parallel, I's origin in J's x-y plane: a rotation about z
    /// and a translation in the plane (3).
    Planar,
    /// Origins together, I's z axis perpendicular to J's (the two arms of
    /// the cross): a rotation about each (4).
    Universal,
    /// Origins together, I's x axis perpendicular to J's y axis (the two
    /// arms of the cross), the z axes down the shafts (4).
    Hooke,
    /// Origins together, the z axes down the shafts away from the centre,
    /// the rotation of I about its z axis equal and opposite to J's about
    /// its own: `x_i · y_j + y_i · x_j = 0` (4).
    Convel,
    /// The translation of I's origin along J's z axis (the rack) is the
    /// pitch radius times I's rotation about its own z axis (the pinion;
    /// [`Joint::pitch`] its pitch diameter), the rack on the side
    /// `z_i × z_j` of the pinion (1).
    RackPin,
    /// The translation of I's origin along J's z axis is [`Joint::pitch`]
    /// per turn of I's x axis about J's z axis (1).
    Screw,
    /// `JPRIM`, ATPOINT: origins together (3).
    AtPoint,
    /// `JPRIM`, INLINE: I's origin on J's z axis (2).
    InLine,
    /// `JPRIM`, INPLANE: I's origin in J's x-y plane (1).
    InPlane,
    /// `JPRIM`, ORIENTATION: the axes parallel (3).
    Orientation,
    /// `JPRIM`, PARALLEL_AXES: the z axes parallel (2).
    ParallelAxes,
    /// `JPRIM`, PERPENDICULAR: I's z axis perpendicular to J's (1).
    Perpendicular,
    /// `PTCV`: I's origin on a curve drawn in the axes of a marker of J's
    /// part ([`Joint::curve`]), J the floating marker at the point of
    /// contact (2).
    PointCurve,
    /// `CVCV`: a curve drawn in the axes of I's marker kept in contact with,
    /// and tangent to, a curve drawn in the axes of J's, in I's x-y plane
    /// ([`Joint::pair`]) (2).
    CurveCurve,
}

impl JointKind {
    /// Every kind with its keyword.
    pub const ALL: [(JointKind, &'static str); 11] = [
        (JointKind::Fixed, "FIXED"),
        (JointKind::Revolute, "REVOLUTE"),
        (JointKind::Translational, "TRANSLATIONAL"),
        (JointKind::Spherical, "SPHERICAL"),
        (JointKind::Cylindrical, "CYLINDRICAL"),
        (JointKind::Planar, "PLANAR"),
        (JointKind::Universal, "UNIVERSAL"),
        (JointKind::Hooke, "HOOKE"),
        (JointKind::Convel, "CONVEL"),
        (JointKind::RackPin, "RACKPIN"),
        (JointKind::Screw, "SCREW"),
    ];

    /// Every kind of joint primitive (`JPRIM`) with its keyword.
    pub const PRIMITIVES: [(JointKind, &'static str); 6] = [
        (JointKind::AtPoint, "ATPOINT"),
        (JointKind::InLine, "INLINE"),
        (JointKind::InPlane, "INPLANE"),
        (JointKind::Orientation, "ORIENTATION"),
        (JointKind::ParallelAxes, "PARALLEL_AXES"),
        (JointKind::Perpendicular, "PERPENDICULAR"),
    ];

    /// The number of scalar equations.
    pub fn equations(self) -> usize {
        match self {
            JointKind::Fixed => 6,
            JointKind::Revolute | JointKind::Translational => 5,
            JointKind::Cylindrical
            | JointKind::Universal
            | JointKind::Hooke
            | JointKind::Convel => 4,
            JointKind::Spherical
            | JointKind::Planar
            | JointKind::AtPoint
            | JointKind::Orientation => 3,
            JointKind::InLine
            | JointKind::ParallelAxes
            | JointKind::PointCurve
            | JointKind::CurveCurve => 2,
            JointKind::InPlane
            | JointKind::Perpendicular
            | JointKind::RackPin
            | JointKind::Screw => 1,
        }
    }

    /// Whether it is a joint primitive (`JPRIM`), which a MOTION cannot
    /// name.
    pub fn is_primitive(self) -> bool {
        JointKind::PRIMITIVES.iter().any(|(kind, _)| *kind == self)
    }

    /// The statement that gives it: `JOINT`, `JPRIM`, `PTCV` or `CVCV`.
    pub fn statement(self) -> &'static str {
        if self == JointKind::PointCurve {
            "PTCV"
        } else if self == JointKind::CurveCurve {
            "CVCV"
        } else if self.is_primitive() {
            "JPRIM"
        } else {
            "JOINT"
        }
    }
}

/// A `JOINT` statement.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// The statement id.
    pub id: u64,
    /// What it holds.
    pub kind: JointKind,
    /// The I marker (on the moving body, by Adams' convention).
    pub i: Target,
    /// The J marker.
    pub j: Target,
    /// The length its kind needs: a SCREW's PITCH (the translation per
    /// turn), a RACKPIN's PD (the pinion's pitch diameter); 0 for the
    /// others.
    pub pitch: f64,
    /// A PTCV's curve and the marker it is drawn in; `None` for the other
    /// kinds.
    pub curve: Option<OnCurve>,
    /// A CVCV's two curves; `None` for the other kinds.
    pub pair: Option<Box<CurvePair>>,
    /// Its equations (indices below [`JointKind::equations`]) that repeat
    /// other joints' at the initial state, left out of the run.
    pub redundant: Vec<usize>,
    /// The statement.
    pub span: Span,
}

/// The curve a `PTCV` holds its I marker's origin on, or one of a `CVCV`'s
/// two curves.
#[derive(Clone, Debug, PartialEq)]
pub struct OnCurve {
    /// The curve, in the RM marker's axes from its origin.
    pub curve: Curve,
    /// The RM marker (on the part of the joint's J marker).
    pub frame: Target,
    /// The parameter of the curve's point nearest `DISP` (a CVCV's IDISP
    /// or JDISP), where the initial analysis places the point of contact,
    /// when it is given.
    pub start: Option<f64>,
    /// The speed of the point of contact along the curve at time 0 (`VEL`,
    /// a CVCV's IVEL or JVEL: relative to the curve, positive towards its
    /// greater parameters), which the initial analysis of the velocities
    /// gives it, when it is given.
    pub speed: Option<f64>,
}

/// The two curves a `CVCV` keeps in contact: each drawn in the axes of its
/// reference marker (IRM, JRM), with the parameter its IDISP or JDISP sets
/// at the start and the speed its IVEL or JVEL gives.
#[derive(Clone, Debug, PartialEq)]
pub struct CurvePair {
    /// ICURVE, in IRM's axes (IRM is also the joint's I marker).
    pub i: OnCurve,
    /// JCURVE, in JRM's axes (JRM is also the joint's J marker).
    pub j: OnCurve,
}

impl Joint {
    /// How many of its equations the run holds (its redundant ones left
    /// out).
    pub(crate) fn held_equations(&self) -> usize {
        self.kind.equations() - self.redundant.len()
    }
}

/// A `MOTION` on a joint: the joint's displacement along (translation) or
/// about (rotation) its J marker's z axis, a function of time.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    /// The statement id.
    pub id: u64,
    /// The joint, an index into [`Model::joints`].
    pub joint: usize,
    /// About the z axis (the angle of I's x axis from J's, towards J's y
    /// axis) rather than along it (I's origin from J's).
    pub rotation: bool,
    /// Its FUNCTION, an index into [`Model::expressions`].
    pub function: usize,
    /// What the FUNCTION gives: the displacement or one of its derivatives.
    pub given: Given,
    /// The statement.
    pub span: Span,
}

/// What a motion's FUNCTION gives (Adams' `DISPLACEMENT`, `VELOCITY`,
/// `ACCELERATION`): a velocity or an acceleration is integrated in time to
/// the displacement, from `ICDISP` (and `ICVEL`) at time 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Given {
    /// The displacement itself.
    Displacement,
    /// Its rate: the displacement is `icdisp + ∫₀ᵗ f`.
    Velocity {
        /// The displacement at time 0 (`ICDISP`).
        icdisp: f64,
    },
    /// Its second derivative: the displacement is
    /// `icdisp + icvel·t + ∫₀ᵗ (t - s)·f(s) ds`.
    Acceleration {
        /// The displacement at time 0 (`ICDISP`).
        icdisp: f64,
        /// The rate at time 0 (`ICVEL`).
        icvel: f64,
    },
}

/// What a [`MarkerMotion`] sets of its I marker relative to its J marker.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Along {
    /// `X`, `Y`, `Z`: I's origin from J's, along J's axis 0, 1 or 2.
    Axis(usize),
    /// `B1`, `B2`, `B3`: the body 1-2-3 angle 1, 2 or 3 of I's axes
    /// from J's (the rotation from J's axes to I's is `Rx(b1) Ry(b2)
    /// Rz(b3)` in J's; B2 is held through its sine, so within a quarter
    /// turn).
    Angle(usize),
}

/// A `MOTION` between markers (`I =`, `J =`): one of I's displacements
/// from J, a function of time.
#[derive(Clone, Debug, PartialEq)]
pub struct MarkerMotion {
    /// The statement id.
    pub id: u64,
    /// The I marker.
    pub i: Target,
    /// The J marker.
    pub j: Target,
    /// The displacement it sets.
    pub along: Along,
    /// Its FUNCTION, an index into [`Model::expressions`].
    pub function: usize,
    /// What the FUNCTION gives: the displacement or one of its derivatives.
    pub given: Given,
    /// The statement.
    pub span: Span,
}

/// A joint's initial conditions: `IC` of a REVOLUTE (its rotation) or a
/// TRANSLATIONAL joint (its translation), `ICROT` or `ICTRAN` of a
/// CYLINDRICAL one. The initial-conditions analysis puts the joint at the
/// displacement, when one is given, and gives it the velocity, when one is
/// given (an Adams View file may give the velocity alone); the run then
/// leaves the joint free.
#[derive(Clone, Debug, PartialEq)]
pub struct JointInitial {
    /// The joint, an index into [`Model::joints`].
    pub joint: usize,
    /// The rotation about J's z axis rather than the translation along it
    /// (measured as a MOTION on the joint measures it).
    pub rotation: bool,
    /// The displacement at time 0, when given.
    pub displacement: Option<f64>,
    /// The velocity at time 0, when given.
    pub velocity: Option<f64>,
    /// The argument's place in the file.
    pub span: Span,
}

/// A PART's `EXACT`: the coordinates of the part (its centre of mass's
/// X, Y, Z in ground and its CM marker's body 3-1-3 angles PSI, THETA,
/// PHI) that the initial-conditions analysis keeps at their drawn values.
#[derive(Clone, Debug, PartialEq)]
pub struct ExactPart {
    /// The part's body, an index into the scene's bodies.
    pub body: usize,
    /// Which of X, Y, Z, PSI, THETA, PHI are kept.
    pub coordinates: [bool; 6],
    /// The centre of mass as drawn, in ground.
    pub centre: Vector3<f64>,
    /// The CM marker's axes as drawn (columns in ground).
    pub axes: Matrix3<f64>,
    /// The CM marker's axes in the body's.
    pub cm_axes: Matrix3<f64>,
    /// The argument's place in the file.
    pub span: Span,
}

/// A part's initial velocity components as the dataset gives them (`VX,
/// VY, VZ` of its VM marker's origin along ground's axes, `WX, WY, WZ`
/// about its WM marker's axes): each one given is held in the velocities'
/// initial-conditions analysis where the joints leave it free, as Adams
/// changes a given velocity only where it disagrees with a joint or a
/// motion; one left out is "inexact 0", free.
#[derive(Clone, Debug, PartialEq)]
pub struct GivenVelocity {
    /// The part's body, an index into the scene's bodies.
    pub body: usize,
    /// The VM marker's origin in the body's frame.
    pub point: Vector3<f64>,
    /// The WM marker's axes in the body's (columns).
    pub axes: Matrix3<f64>,
    /// `VX, VY, VZ, WX, WY, WZ`, each when given.
    pub values: [Option<f64>; 6],
}

/// A `COUPLER`: two or three joints' displacements tied, `Σ scale·q = 0`.
#[derive(Clone, Debug, PartialEq)]
pub struct Coupler {
    /// The statement's kind: `COUPLER`, or `GEAR` (a coupler whose scales
    /// its CV marker's place gives).
    pub statement: &'static str,
    /// The statement id.
    pub id: u64,
    /// Each coupled joint (an index into [`Model::joints`]), whether its
    /// rotation (about J's z) or its translation (along J's z) is coupled,
    /// and its scale.
    pub joints: Vec<(usize, bool, f64)>,
    /// A GEAR's CV marker, on the carrier at the teeth's contact, its z
    /// axis along their motion: the teeth push each other there, along
    /// it (`None` for a COUPLER).
    pub contact: Option<Target>,
    /// The statement's place in the file.
    pub span: Span,
}

/// A `GCON`: the equation `FUNCTION = 0`, its FUNCTION an expression of
/// the parts' positions and orientations and of time.
#[derive(Clone, Debug, PartialEq)]
pub struct GeneralConstraint {
    /// The statement id.
    pub id: u64,
    /// The marker its reaction is reported on.
    pub i: Target,
    /// The FUNCTION (an index into [`Model::expressions`]).
    pub function: usize,
    /// The FUNCTION argument's place in the file.
    pub function_span: Span,
    /// The statement's place in the file.
    pub span: Span,
}

/// A `SENSOR`: a function of the run watched after every accepted step;
/// when it becomes active (`relation` to `value` within `error`), the run
/// does what `action` says at the located time.
#[derive(Clone, Debug, PartialEq)]
pub struct Sensor {
    /// The statement id.
    pub id: u64,
    /// Its FUNCTION (or `VARVAL` of its VARIABLE), an index into
    /// [`Model::expressions`].
    pub function: usize,
    /// How the function is compared with `value`.
    pub relation: Relation,
    /// The value it is compared with.
    pub value: f64,
    /// The tolerance of the comparison (Adams' ERROR, 1e-3 by default).
    pub error: f64,
    /// What the run does when the sensor becomes active.
    pub action: SensorAction,
    /// Its EVALUATE, an index into [`Model::expressions`]: the value of
    /// `SENVAL(id)` from each trip on is this expression's there.
    pub evaluate: Option<usize>,
    /// Its DT: after each trip, the output steps are this far apart, on
    /// the grid from the last row before the trip (the last at the end).
    pub output_step: Option<f64>,
    /// The statement's place in the file.
    pub span: Span,
}

/// A sensor's comparison.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Relation {
    /// `EQ`: active within `error` of the value.
    Equal,
    /// `GE`: active at or above the value, less `error`.
    AtLeast,
    /// `LE`: active at or below the value, plus `error`.
    AtMost,
}

/// What a sensor does when it becomes active.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SensorAction {
    /// `HALT`: the run ends there.
    Halt,
    /// `RETURN`: the run ends there (an Adams solver returns to its
    /// commands).
    Return,
    /// `PRINT`: the time is reported and the run goes on.
    Print,
    /// Only EVALUATE (the value stored) or actions that steer Adams'
    /// integrator (CODGEN, RESTART, STEPSIZE, YYDUMP), which leave the
    /// answer as it is: the trip is counted and the run goes on.
    Watch,
}

impl SensorAction {
    /// Whether the run ends at a trip.
    pub fn halts(self) -> bool {
        matches!(self, SensorAction::Halt | SensorAction::Return)
    }
}

impl Sensor {
    /// Whether the sensor is active with its function at `value`.
    pub fn is_active(&self, value: f64) -> bool {
        let off = value - self.value;
        match self.relation {
            Relation::Equal => off.abs() <= self.error,
            Relation::AtLeast => off >= -self.error,
            Relation::AtMost => off <= self.error,
        }
    }

    /// Whether an EQ sensor's function went from `before` to `value` past
    /// its value (from one side of it to the other): it was within its
    /// band between them, however narrow the band.
    pub fn passes(&self, before: f64, value: f64) -> bool {
        self.relation == Relation::Equal
            && (before - self.value).signum() * (value - self.value).signum() < 0.0
    }
}

/// The groups of two or more of `count` items that `links` join, directly
/// or through other items (union-find), each in increasing order.
pub(crate) fn linked_groups(
    count: usize,
    links: impl IntoIterator<Item = (usize, usize)>,
) -> Vec<Vec<usize>> {
    let mut root: Vec<usize> = (0..count).collect();
    fn find(root: &mut [usize], mut item: usize) -> usize {
        while root[item] != item {
            root[item] = root[root[item]];
            item = root[item];
        }
        item
    }
    for (a, b) in links {
        let (a, b) = (find(&mut root, a), find(&mut root, b));
        root[a] = b;
    }
    let mut groups: Vec<Vec<usize>> = vec![Vec::new(); count];
    for item in 0..count {
        let top = find(&mut root, item);
        groups[top].push(item);
    }
    groups.retain(|group| group.len() > 1);
    groups
}
