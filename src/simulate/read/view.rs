//! An Adams View command file (`.cmd`) read as the solver dataset Adams
//! View writes for it (File > Export > Adams Solver Dataset), so that the
//! dataset reader simulates it: parts, markers, joints, motions, forces and
//! data elements become the statements they stand for, each at the place of
//! its command in the `.cmd`.
//!
//! What View does on the way is done here too:
//! - **Places.** A `location` and `orientation` (body 3-1-3 angles) are
//!   relative to `relative_to`, else to the `defaults coordinate_system`
//!   in force (a part, a marker or the model); a marker is then placed on
//!   its part by its origin and axes (`QP`, `ZP`, `XP`).
//! - **Units.** `defaults units` become `UNITS`. Angles are in the angle
//!   unit (degrees unless `angle = rad`; a `d` suffix is always degrees)
//!   and so are the angular parts of stiffness, damping and velocities.
//! - **Names.** A name is full (`.model.PART_2.MARKER_1`) or any tail of
//!   one (`PART_2.MARKER_1`); each object takes its `adams_id`, or the next
//!   free id of its kind. Function expressions name markers and objects:
//!   each name becomes its id.
//! - **Mass from geometry.** A part whose mass properties are a
//!   `material_type` or a `density` takes its mass, centre of mass and
//!   inertia from its solids (block, cylinder, frustum, ellipsoid, torus,
//!   link) at that density.
//! - **Later commands.** `modify` commands change what a `create` made
//!   (View writes every function after the objects it reads), and
//!   `attributes ... active = off` leaves an element out.
//! - **Elements.** Joints and primitives, motions, single-component
//!   forces, force and torque vectors, general forces, spring-dampers,
//!   bushings, beams, contacts (their solids written as GRAPHICS), gravity,
//!   variables, differential equations, function requests and sensors.
//! - **The run.** The last `simulation single_run transient` (alone or in
//!   a `simulation script`) gives the end time and output steps.
//!
//! A command that would change the motion and is not read is refused at its
//! place; commands that only draw or arrange (colours, icons, views,
//! groups, points) are passed over.

use std::collections::{HashMap, HashSet};
use std::f64::consts::PI;

use compact_str::CompactString;
use nalgebra::{Matrix3, Vector3};

use super::commands::RunCommands;
use crate::check::{Argument as TreeArgument, Checked, NodeKind, Reference, visit};
use crate::model::{
    Argument, Dataset, Embedded, FileKind, ModelCheck, Statement, Value, ValueItem,
};
use crate::scene::euler_313;
use crate::simulate::error::SimulateError;
use crate::span::Span;

/// A View command file as a solver dataset, with its run.
pub struct ViewDataset {
    /// The statements, each at the place of the command it comes from.
    pub dataset: Dataset,
    /// The end time and output steps of its last transient simulation.
    pub run: Option<RunCommands>,
    /// What the reading passed over that a user may want to know.
    pub notes: Vec<(String, Span)>,
}

/// Commands that only draw, arrange or describe: passed over.
const PASSED_OVER: [&str; 32] = [
    "IF",
    "ELSE",
    "END",
    "MEASURE_DISPLAY",
    "DEFAULTS",
    "MODEL",
    "DATA_ELEMENT PLANT",
    "XY_PLOTS",
    "PLOT",
    "ANIMATION",
    "LIBRARY",
    "MACRO",
    "LIST_INFO",
    "ENTITY",
    "GRAPHIC_INTERFACE",
    "VIEW",
    "PLUGIN",
    "UNDO",
    "UDE",
    "VARIABLE",
    "POINT",
    "GEOMETRY ATTRIBUTES",
    "GEOMETRY CREATE CURVE",
    "GEOMETRY CREATE SHAPE FORCE",
    "GEOMETRY CREATE SHAPE SPRING_DAMPER",
    "GEOMETRY CREATE SHAPE GCONTACT",
    "GROUP",
    "MEASURE",
    "COLOR",
    "INTERFACE",
    "EXECUTIVE_CONTROL SET",
    "OUTPUT_CONTROL SET",
];

/// Commands passed over with a note: they may matter, but not to a run
/// of the model as the file leaves it.
const NOTED: [(&str, &str); 2] = [
    (
        "SIMULATION",
        "a simulation command other than a transient run: not carried out",
    ),
    ("FILE", "a file command: mbexpr reads this file alone"),
];

/// Shapes without volume: they add no mass.
const WIRES: [&str; 10] = [
    "ARC",
    "CIRCLE",
    "POLYLINE",
    "OUTLINE",
    "SPLINE",
    "POINT",
    "FORCE",
    "SPRING_DAMPER",
    "GCONTACT",
    "PLANE",
];

/// What a View parameter becomes in the solver statement.
#[derive(Clone, Copy)]
enum Becomes {
    /// A marker's id.
    Marker(&'static str),
    /// A floating marker's id.
    Floating(&'static str),
    /// A part, held by a floating marker made on it.
    FloatingOn(&'static str),
    /// An element's id (a motion's joint).
    Object(&'static str),
    /// Numbers as written.
    Numbers(&'static str),
    /// Angles, in the angle unit.
    Angles(&'static str),
    /// Numbers per angle (a torsional stiffness), in the angle unit.
    PerAngle(&'static str),
    /// A function expression.
    Function(&'static str),
    /// One of several words, each a keyword of the statement.
    Choice(&'static [(&'static str, &'static str)]),
    /// A word, the value of the keyword (`COULOMB_FRICTION = ON`).
    Word(&'static str),
    /// Solids (geometry names): the ids of the GRAPHICS written for them.
    Solids(&'static str),
    /// Joints (names): their ids.
    Joints(&'static str),
    /// A coupler's freedoms (`rot_rot`, `trans_rot`): its TYPE (`R:R`, `T:R`).
    Freedoms(&'static str),
    /// `on` or `yes` gives the keyword; `off` or `no`, nothing.
    Switch(&'static str),
    /// An angle or a number, as the element turns or moves.
    Initial(&'static str),
    /// Read elsewhere, or without effect on the motion.
    Nothing,
}

/// An element command: its words after the verb, the solver statement it
/// writes, the keyword a word of its own gives (a joint's type), and its
/// parameters.
struct ElementKind {
    /// The command's words, `CREATE` or `MODIFY` taken out.
    words: &'static str,
    /// The solver statement.
    statement: &'static str,
    /// The keywords of the statement the command's words give.
    flags: &'static [&'static str],
    /// The parameter that names the element.
    name: &'static str,
    /// The other parameters.
    parameters: &'static [(&'static str, Becomes)],
}

const TWO_MARKERS: [(&str, Becomes); 2] = [
    ("I_MARKER_NAME", Becomes::Marker("I")),
    ("J_MARKER_NAME", Becomes::Marker("J")),
];

const FREEDOM: &[(&str, &str)] = &[("TRANSLATIONAL", "TRANSLATION"), ("ROTATIONAL", "ROTATION")];

/// Joints by their View word and solver keyword.
const JOINT_TYPES: [(&str, &str); 11] = [
    ("REVOLUTE", "REVOLUTE"),
    ("TRANSLATIONAL", "TRANSLATIONAL"),
    ("SPHERICAL", "SPHERICAL"),
    ("FIXED", "FIXED"),
    ("CYLINDRICAL", "CYLINDRICAL"),
    ("UNIVERSAL", "UNIVERSAL"),
    ("HOOKE", "HOOKE"),
    ("PLANAR", "PLANAR"),
    ("CONSTANT_VELOCITY", "CONVEL"),
    ("RACKPIN", "RACKPIN"),
    ("SCREW", "SCREW"),
];

/// Joint primitives by their View word.
const PRIMITIVES: [&str; 6] = [
    "ATPOINT",
    "INLINE",
    "INPLANE",
    "ORIENTATION",
    "PARALLEL_AXES",
    "PERPENDICULAR",
];

const JOINT_PARAMETERS: &[(&str, Becomes)] = &[
    TWO_MARKERS[0],
    TWO_MARKERS[1],
    ("DIAMETER_OF_PITCH", Becomes::Numbers("PD")),
    ("PITCH", Becomes::Numbers("PITCH")),
    ("FRICTION_ENABLED", Becomes::Nothing),
];

const ELEMENTS: [ElementKind; 18] = [
    ElementKind {
        words: "CONSTRAINT COMPLEX_JOINT COUPLER",
        statement: "COUPLER",
        flags: &[],
        name: "COUPLER_NAME",
        parameters: &[
            ("JOINT_NAME", Becomes::Joints("JOINTS")),
            ("TYPE_OF_FREEDOM", Becomes::Freedoms("TYPE")),
            ("MOTION_MULTIPLIERS", Becomes::Numbers("SCALES")),
        ],
    },
    ElementKind {
        words: "DATA_ELEMENT SPLINE",
        statement: "SPLINE",
        flags: &[],
        name: "SPLINE_NAME",
        parameters: &[
            ("X", Becomes::Numbers("X")),
            ("Y", Becomes::Numbers("Y")),
            ("LINEAR_EXTRAPOLATE", Becomes::Switch("LINEAR_EXTRAPOLATE")),
            ("UNITS", Becomes::Nothing),
        ],
    },
    // A function measure is its function: a function that names it reads
    // it in brackets; nothing is written for it.
    ElementKind {
        words: "MEASURE FUNCTION",
        statement: MEASURE,
        flags: &[],
        name: "MEASURE_NAME",
        parameters: &[
            ("FUNCTION", Becomes::Function("FUNCTION")),
            ("UNITS", Becomes::Nothing),
            ("CREATE_MEASURE_DISPLAY", Becomes::Nothing),
        ],
    },
    ElementKind {
        words: "FORCE ELEMENT_LIKE BEAM",
        statement: "BEAM",
        flags: &[],
        name: "BEAM_NAME",
        parameters: &[
            TWO_MARKERS[0],
            TWO_MARKERS[1],
            ("LENGTH", Becomes::Numbers("LENGTH")),
            ("AREA_OF_CROSS_SECTION", Becomes::Numbers("AREA")),
            ("Y_SHEAR_AREA_RATIO", Becomes::Numbers("ASY")),
            ("Z_SHEAR_AREA_RATIO", Becomes::Numbers("ASZ")),
            ("YOUNGS_MODULUS", Becomes::Numbers("EMODULUS")),
            ("SHEAR_MODULUS", Becomes::Numbers("GMODULUS")),
            ("IXX", Becomes::Numbers("IXX")),
            ("IYY", Becomes::Numbers("IYY")),
            ("IZZ", Becomes::Numbers("IZZ")),
            ("DAMPING_RATIO", Becomes::Numbers("CRATIO")),
        ],
    },
    ElementKind {
        words: "CONTACT",
        statement: "CONTACT",
        flags: &["IMPACT"],
        name: "CONTACT_NAME",
        parameters: &[
            ("I_GEOMETRY_NAME", Becomes::Solids("IGEOM")),
            ("J_GEOMETRY_NAME", Becomes::Solids("JGEOM")),
            ("STIFFNESS", Becomes::Numbers("STIFFNESS")),
            ("DAMPING", Becomes::Numbers("DAMPING")),
            ("DMAX", Becomes::Numbers("DMAX")),
            ("EXPONENT", Becomes::Numbers("EXPONENT")),
            ("COULOMB_FRICTION", Becomes::Word("COULOMB_FRICTION")),
            ("MU_STATIC", Becomes::Numbers("MU_STATIC")),
            ("MU_DYNAMIC", Becomes::Numbers("MU_DYNAMIC")),
            (
                "STICTION_TRANSITION_VELOCITY",
                Becomes::Numbers("STICTION_TRANSITION_VELOCITY"),
            ),
            (
                "FRICTION_TRANSITION_VELOCITY",
                Becomes::Numbers("FRICTION_TRANSITION_VELOCITY"),
            ),
            ("TYPE", Becomes::Word("TYPE")),
            ("NO_FRICTION", Becomes::Nothing),
            ("AUGMENTED_LAGRANGIAN_FORMULATION", Becomes::Nothing),
            // View writes the restitution law's numbers beside the impact
            // law's; they count only without STIFFNESS (refused then).
            ("PENALTY", Becomes::Nothing),
            ("RESTITUTION_COEFFICIENT", Becomes::Nothing),
        ],
    },
    ElementKind {
        words: "CONSTRAINT MOTION_GENERATOR",
        statement: "MOTION",
        flags: &[],
        name: "MOTION_NAME",
        parameters: &[
            TWO_MARKERS[0],
            TWO_MARKERS[1],
            ("JOINT_NAME", Becomes::Object("JOINT")),
            ("TYPE_OF_FREEDOM", Becomes::Choice(FREEDOM)),
            (
                "AXIS",
                Becomes::Choice(&[
                    ("X", "X"),
                    ("Y", "Y"),
                    ("Z", "Z"),
                    ("B1", "B1"),
                    ("B2", "B2"),
                    ("B3", "B3"),
                ]),
            ),
            (
                "TIME_DERIVATIVE",
                Becomes::Choice(&[
                    ("DISPLACEMENT", "DISPLACEMENT"),
                    ("VELOCITY", "VELOCITY"),
                    ("ACCELERATION", "ACCELERATION"),
                ]),
            ),
            ("FUNCTION", Becomes::Function("FUNCTION")),
            ("DISPLACEMENT_IC", Becomes::Initial("ICDISP")),
            ("VELOCITY_IC", Becomes::Initial("ICVEL")),
        ],
    },
    ElementKind {
        words: "FORCE DIRECT SINGLE_COMPONENT_FORCE",
        statement: "SFORCE",
        flags: &[],
        name: "SINGLE_COMPONENT_FORCE_NAME",
        parameters: &[
            TWO_MARKERS[0],
            TWO_MARKERS[1],
            ("TYPE_OF_FREEDOM", Becomes::Choice(FREEDOM)),
            ("ACTION_ONLY", Becomes::Switch("ACTIONONLY")),
            ("FUNCTION", Becomes::Function("FUNCTION")),
        ],
    },
    ElementKind {
        words: "FORCE ELEMENT_LIKE TRANSLATIONAL_SPRING_DAMPER",
        statement: "SPRINGDAMPER",
        flags: &["TRANSLATION"],
        name: "SPRING_DAMPER_NAME",
        parameters: &[
            TWO_MARKERS[0],
            TWO_MARKERS[1],
            ("STIFFNESS", Becomes::Numbers("K")),
            ("DAMPING", Becomes::Numbers("C")),
            ("PRELOAD", Becomes::Numbers("FORCE")),
            ("DISPLACEMENT_AT_PRELOAD", Becomes::Numbers("LENGTH")),
        ],
    },
    ElementKind {
        words: "FORCE ELEMENT_LIKE ROTATIONAL_SPRING_DAMPER",
        statement: "SPRINGDAMPER",
        flags: &["ROTATION"],
        name: "SPRING_DAMPER_NAME",
        parameters: &[
            TWO_MARKERS[0],
            TWO_MARKERS[1],
            ("STIFFNESS", Becomes::PerAngle("KT")),
            ("DAMPING", Becomes::PerAngle("CT")),
            ("PRELOAD", Becomes::Numbers("TORQUE")),
            ("DISPLACEMENT_AT_PRELOAD", Becomes::Angles("ANGLE")),
        ],
    },
    ElementKind {
        words: "FORCE ELEMENT_LIKE BUSHING",
        statement: "BUSHING",
        flags: &[],
        name: "BUSHING_NAME",
        parameters: &[
            TWO_MARKERS[0],
            TWO_MARKERS[1],
            ("STIFFNESS", Becomes::Numbers("K")),
            ("DAMPING", Becomes::Numbers("C")),
            ("TSTIFFNESS", Becomes::PerAngle("KT")),
            ("TDAMPING", Becomes::PerAngle("CT")),
            ("FORCE_PRELOAD", Becomes::Numbers("FORCE")),
            ("TORQUE_PRELOAD", Becomes::Numbers("TORQUE")),
        ],
    },
    ElementKind {
        words: "FORCE DIRECT FORCE_VECTOR",
        statement: "VFORCE",
        flags: &[],
        name: "FORCE_VECTOR_NAME",
        parameters: &[
            ("I_MARKER_NAME", Becomes::Marker("I")),
            ("J_FLOATING_MARKER_NAME", Becomes::Floating("JFLOAT")),
            ("J_PART_NAME", Becomes::FloatingOn("JFLOAT")),
            ("REF_MARKER_NAME", Becomes::Marker("RM")),
            ("X_FORCE_FUNCTION", Becomes::Function("FX")),
            ("Y_FORCE_FUNCTION", Becomes::Function("FY")),
            ("Z_FORCE_FUNCTION", Becomes::Function("FZ")),
        ],
    },
    ElementKind {
        words: "FORCE DIRECT TORQUE_VECTOR",
        statement: "VTORQUE",
        flags: &[],
        name: "TORQUE_VECTOR_NAME",
        parameters: &[
            ("I_MARKER_NAME", Becomes::Marker("I")),
            ("J_FLOATING_MARKER_NAME", Becomes::Floating("JFLOAT")),
            ("J_PART_NAME", Becomes::FloatingOn("JFLOAT")),
            ("REF_MARKER_NAME", Becomes::Marker("RM")),
            ("X_TORQUE_FUNCTION", Becomes::Function("TX")),
            ("Y_TORQUE_FUNCTION", Becomes::Function("TY")),
            ("Z_TORQUE_FUNCTION", Becomes::Function("TZ")),
        ],
    },
    ElementKind {
        words: "FORCE DIRECT GENERAL_FORCE",
        statement: "GFORCE",
        flags: &[],
        name: "GENERAL_FORCE_NAME",
        parameters: &[
            ("I_MARKER_NAME", Becomes::Marker("I")),
            ("J_FLOATING_MARKER_NAME", Becomes::Floating("JFLOAT")),
            ("J_PART_NAME", Becomes::FloatingOn("JFLOAT")),
            ("REF_MARKER_NAME", Becomes::Marker("RM")),
            ("X_FORCE_FUNCTION", Becomes::Function("FX")),
            ("Y_FORCE_FUNCTION", Becomes::Function("FY")),
            ("Z_FORCE_FUNCTION", Becomes::Function("FZ")),
            ("X_TORQUE_FUNCTION", Becomes::Function("TX")),
            ("Y_TORQUE_FUNCTION", Becomes::Function("TY")),
            ("Z_TORQUE_FUNCTION", Becomes::Function("TZ")),
        ],
    },
    ElementKind {
        words: "DATA_ELEMENT VARIABLE",
        statement: "VARIABLE",
        flags: &[],
        name: "VARIABLE_NAME",
        parameters: &[
            ("FUNCTION", Becomes::Function("FUNCTION")),
            ("INITIAL_CONDITION", Becomes::Numbers("IC")),
        ],
    },
    ElementKind {
        words: "PART EQUATION DIFFERENTIAL_EQUATION",
        statement: "DIFF",
        flags: &[],
        name: "DIFFERENTIAL_EQUATION_NAME",
        parameters: &[
            ("FUNCTION", Becomes::Function("FUNCTION")),
            ("INITIAL_CONDITION", Becomes::Numbers("IC")),
            ("IMPLICIT", Becomes::Switch("IMPLICIT")),
            ("STATIC_HOLD", Becomes::Switch("STATIC_HOLD")),
        ],
    },
    ElementKind {
        words: "OUTPUT_CONTROL REQUEST",
        statement: "REQUEST",
        flags: &[],
        name: "REQUEST_NAME",
        parameters: &[
            ("F1", Becomes::Function("F1")),
            ("F2", Becomes::Function("F2")),
            ("F3", Becomes::Function("F3")),
            ("F4", Becomes::Function("F4")),
            ("F5", Becomes::Function("F5")),
            ("F6", Becomes::Function("F6")),
            ("F7", Becomes::Function("F7")),
            ("F8", Becomes::Function("F8")),
            ("COMPONENT_NAMES", Becomes::Nothing),
            ("COMPONENT_UNITS", Becomes::Nothing),
            ("COMPONENT_LABELS", Becomes::Nothing),
            ("RESULTS_NAME", Becomes::Nothing),
        ],
    },
    ElementKind {
        words: "EXECUTIVE_CONTROL SENSOR",
        statement: "SENSOR",
        flags: &[],
        name: "SENSOR_NAME",
        parameters: &[
            ("FUNCTION", Becomes::Function("FUNCTION")),
            (
                "COMPARE",
                Becomes::Choice(&[("EQ", "EQ"), ("GE", "GE"), ("LE", "LE")]),
            ),
            ("VALUE", Becomes::Numbers("VALUE")),
            ("ERROR", Becomes::Numbers("ERROR")),
            ("HALT", Becomes::Switch("HALT")),
            ("PRINT", Becomes::Switch("PRINT")),
            ("RETURN", Becomes::Switch("RETURN")),
            ("BISECTION", Becomes::Nothing),
            ("TIME_ERROR", Becomes::Nothing),
        ],
    },
    ElementKind {
        words: "FORCE BODY GRAVITATIONAL",
        statement: "ACCGRAV",
        flags: &[],
        name: "GRAVITY_FIELD_NAME",
        parameters: &[
            ("X_COMPONENT_GRAVITY", Becomes::Numbers("IGRAV")),
            ("Y_COMPONENT_GRAVITY", Becomes::Numbers("JGRAV")),
            ("Z_COMPONENT_GRAVITY", Becomes::Numbers("KGRAV")),
        ],
    },
];

/// The kind of a function measure's element, which is not written.
const MEASURE: &str = "MEASURE";

/// The joint and primitive commands: their kind by the last word.
fn constraint_kind(words: &str) -> Option<(&'static str, &'static str)> {
    if let Some(kind) = words.strip_prefix("CONSTRAINT JOINT ") {
        return JOINT_TYPES
            .iter()
            .find(|(view, _)| *view == kind)
            .map(|&(_, solver)| ("JOINT", solver));
    }
    let kind = words.strip_prefix("CONSTRAINT PRIMITIVE_JOINT ")?;
    PRIMITIVES
        .iter()
        .find(|primitive| **primitive == kind)
        .map(|&primitive| ("JPRIM", primitive))
}

/// A frame: its origin and axes (columns) in the ground's.
#[derive(Clone, Copy, Debug)]
struct Frame {
    origin: Vector3<f64>,
    axes: Matrix3<f64>,
}

impl Frame {
    const GROUND: Frame = Frame {
        origin: Vector3::new(0.0, 0.0, 0.0),
        axes: Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
    };

    /// The frame `local` gives in this one.
    fn then(&self, local: &Frame) -> Frame {
        Frame {
            origin: self.origin + self.axes * local.origin,
            axes: self.axes * local.axes,
        }
    }

    /// `global` seen from this frame.
    fn seen(&self, global: &Frame) -> Frame {
        Frame {
            origin: self.axes.transpose() * (global.origin - self.origin),
            axes: self.axes.transpose() * global.axes,
        }
    }
}

/// What a name stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Entity {
    Part(usize),
    Marker(usize),
    Element(usize),
    Material(usize),
    Geometry(usize),
    /// A design variable's value (`variable create ... real_value = v`).
    Design(usize),
    Model,
}

/// A geometry (`geometry create shape ...`): its command and shape, its
/// id, and whether a contact meets it (then a GRAPHICS is written for it).
struct Geometry {
    command: usize,
    shape: String,
    id: Option<u64>,
    met: bool,
}

/// A rigid part.
struct Part {
    name: String,
    id: Option<u64>,
    span: Span,
    frame: Frame,
    ground: bool,
    /// The `mass_properties` command.
    mass: Option<usize>,
    /// The `initial_velocity` command.
    velocity: Option<usize>,
    /// The solids (`geometry create shape` commands) on it.
    solids: Vec<usize>,
    /// Not made inactive (`part attributes ... active = off`).
    active: bool,
}

/// A marker (or floating marker) on a part.
struct Marker {
    id: Option<u64>,
    span: Span,
    part: usize,
    frame: Frame,
    floating: bool,
}

/// An element: its kind, the commands that made and changed it.
struct Element {
    /// The solver statement, and the keywords its words give.
    statement: &'static str,
    flags: Vec<&'static str>,
    parameters: &'static [(&'static str, Becomes)],
    id: Option<u64>,
    span: Span,
    /// `(command, argument)` of each parameter given, the last for each.
    given: Vec<(CompactString, usize, usize)>,
    active: bool,
}

/// The reader's state.
struct Reader<'d> {
    view: &'d Dataset,
    trees: HashMap<(usize, CompactString), &'d Checked>,
    names: HashMap<String, Entity>,
    /// Every tail of every full name, with what it stands for.
    tails: HashMap<String, Vec<Entity>>,
    model: Option<String>,
    parts: Vec<Part>,
    markers: Vec<Marker>,
    elements: Vec<Element>,
    geometries: Vec<Geometry>,
    densities: Vec<f64>,
    designs: Vec<f64>,
    /// The function measures being read into a function (against loops).
    reading: Vec<usize>,
    /// The user-defined force instances (`ude create instance` of a
    /// force): refused unless made inactive.
    user_forces: Vec<(String, usize, bool)>,
    /// The frame locations are given in by default.
    coordinates: Frame,
    degrees: bool,
    units: [(&'static str, &'static str); 4],
    units_span: Span,
    run: Option<RunCommands>,
    errors: Vec<SimulateError>,
    notes: Vec<(String, Span)>,
}

/// A name as the reader keys it: upper case, without the leading dot and
/// quotes.
fn key(name: &str) -> String {
    name.trim()
        .trim_matches('"')
        .trim_start_matches('.')
        .to_ascii_uppercase()
}

/// The words of `statement` without its verb (`CREATE`, `MODIFY`), and the verb.
fn words_and_verb(statement: &Statement) -> (String, Option<&str>) {
    let words: Vec<&str> = statement.name.split(' ').collect();
    match words
        .iter()
        .position(|word| matches!(*word, "CREATE" | "MODIFY"))
    {
        Some(at) => {
            let mut rest = words[..at].to_vec();
            rest.extend(&words[at + 1..]);
            (rest.join(" "), Some(words[at]))
        }
        None => (words.join(" "), None),
    }
}

/// The label of a View command for messages: its words, lower case.
fn label(statement: &Statement) -> String {
    statement.name.to_ascii_lowercase().to_string()
}

/// A View unit name, or the solver's, as the solver's.
fn solver_unit(kind: &str, name: &str) -> Option<&'static str> {
    let name = name.trim_matches('"').to_ascii_uppercase();
    let table: &[(&[&str], &str)] = match kind {
        "LENGTH" => &[
            (&["MM", "MILLIMETER", "MILLIMETERS"], "MILLIMETER"),
            (&["CM", "CENTIMETER", "CENTIMETERS"], "CENTIMETER"),
            (&["METER", "METERS", "M"], "METER"),
            (&["KM", "KILOMETER", "KILOMETERS"], "KILOMETER"),
            (&["INCH", "INCHES", "IN"], "INCH"),
            (&["FOOT", "FEET", "FT"], "FOOT"),
            (&["MILE", "MILES"], "MILE"),
            (&["MICRON", "MICROMETER"], "MICROMETER"),
        ],
        "MASS" => &[
            (&["KG", "KILOGRAM", "KILOGRAMS"], "KILOGRAM"),
            (&["GRAM", "GRAMS", "G"], "GRAM"),
            (&["POUND_MASS", "LBM"], "POUND_MASS"),
            (&["KPOUND_MASS"], "KPOUND_MASS"),
            (&["SLUG", "SLUGS"], "SLUG"),
            (&["OUNCE_MASS"], "OUNCE_MASS"),
            (&["TONNE", "MEGAGRAM"], "TONNE"),
        ],
        "FORCE" => &[
            (&["NEWTON", "NEWTONS", "N"], "NEWTON"),
            (&["KNEWTON", "KILONEWTON"], "KNEWTON"),
            (&["MILLINEWTON"], "MILLINEWTON"),
            (&["MEGANEWTON"], "MEGANEWTON"),
            (&["DYNE", "DYNES"], "DYNE"),
            (&["POUND_FORCE", "LBF"], "POUND_FORCE"),
            (&["KPOUND_FORCE"], "KPOUND_FORCE"),
            (&["KG_FORCE", "KILOGRAM_FORCE"], "KILOGRAM_FORCE"),
            (&["OUNCE_FORCE"], "OUNCE_FORCE"),
        ],
        _ => &[
            (&["SEC", "SECOND", "SECONDS", "S"], "SECOND"),
            (
                &["MILLISEC", "MILLISECOND", "MILLISECONDS", "MS"],
                "MILLISECOND",
            ),
            (&["MINUTE", "MINUTES", "MIN"], "MINUTE"),
            (&["HOUR", "HOURS", "HR"], "HOUR"),
        ],
    };
    table
        .iter()
        .find(|(names, _)| names.contains(&name.as_str()))
        .map(|&(_, solver)| solver)
}

/// Reads the View command file `view` (checked: `check`) as a solver
/// dataset. Every command that would change the motion and is not read is
/// refused at its place.
pub fn solver_dataset(
    view: &Dataset,
    check: &ModelCheck,
) -> Result<ViewDataset, Vec<SimulateError>> {
    let mut trees = HashMap::new();
    for found in &check.expressions {
        if let Some(tree) = &found.checked {
            trees.insert((found.statement, found.keyword.clone()), tree);
        }
    }
    let mut reader = Reader {
        view,
        trees,
        names: HashMap::new(),
        tails: HashMap::new(),
        model: None,
        parts: Vec::new(),
        markers: Vec::new(),
        elements: Vec::new(),
        geometries: Vec::new(),
        densities: Vec::new(),
        designs: Vec::new(),
        reading: Vec::new(),
        user_forces: Vec::new(),
        coordinates: Frame::GROUND,
        degrees: true,
        units: [
            ("FORCE", "NEWTON"),
            ("MASS", "KILOGRAM"),
            ("LENGTH", "MILLIMETER"),
            ("TIME", "SECOND"),
        ],
        units_span: Span::at(0),
        run: None,
        errors: Vec::new(),
        notes: Vec::new(),
    };
    reader.ground(None, Span::at(0));
    for index in 0..view.statements.len() {
        reader.command(index);
    }
    let statements = reader.write();
    if !reader.errors.is_empty() {
        return Err(SimulateError::grouped(reader.errors));
    }
    Ok(ViewDataset {
        dataset: Dataset {
            kind: FileKind::Adm,
            title: None,
            statements,
            problems: Vec::new(),
        },
        run: reader.run,
        notes: reader.notes,
    })
}

impl<'d> Reader<'d> {
    fn refuse(&mut self, statement: &Statement, reason: String, span: Span) {
        self.errors.push(SimulateError::Unsupported {
            statement: format!("`{}`", label(statement)),
            reason,
            span,
        });
    }

    fn wrong(&mut self, message: String, span: Span) {
        self.errors.push(SimulateError::Model { message, span });
    }

    /// Enters `name` (full, upper case) for `entity`, with its tails.
    fn name(&mut self, name: String, entity: Entity) {
        let mut rest = name.as_str();
        while let Some((_, tail)) = rest.split_once('.') {
            self.tails.entry(tail.to_string()).or_default().push(entity);
            rest = tail;
        }
        self.names.insert(name, entity);
    }

    /// What `name` (full or a tail) stands for.
    fn find(&self, name: &str) -> Option<Entity> {
        let name = key(name);
        if let Some(entity) = self.names.get(&name) {
            return Some(*entity);
        }
        match self.tails.get(&name).map(Vec::as_slice) {
            Some([entity]) => Some(*entity),
            _ => None,
        }
    }

    /// The full name of a new object named `name` in the model.
    fn full(&self, name: &str) -> String {
        let name = key(name);
        match &self.model {
            Some(model) if !name.contains('.') => format!("{model}.{name}"),
            _ => name,
        }
    }

    /// The ground part, created with the model.
    fn ground(&mut self, model: Option<&str>, span: Span) {
        let name = match model {
            Some(model) => format!("{model}.GROUND"),
            None => "GROUND".to_string(),
        };
        if self.find(&name).is_some() {
            return;
        }
        self.parts.push(Part {
            name: name.clone(),
            id: None,
            span,
            frame: Frame::GROUND,
            ground: true,
            mass: None,
            velocity: None,
            solids: Vec::new(),
            active: true,
        });
        self.name(name, Entity::Part(self.parts.len() - 1));
    }

    /// Gives `part` the full name `new`; the names under its old one (its
    /// markers') are entered under the new one too.
    fn rename_part(&mut self, part: usize, new: String) {
        let old = self.parts[part].name.clone();
        self.names.remove(&old);
        for tails in self.tails.values_mut() {
            tails.retain(|entity| *entity != Entity::Part(part));
        }
        let renamed: Vec<(String, Entity)> = self
            .names
            .iter()
            .filter(|(name, _)| name.starts_with(&format!("{old}.")))
            .map(|(name, entity)| (format!("{new}{}", &name[old.len()..]), *entity))
            .collect();
        for (name, entity) in renamed {
            self.name(name, entity);
        }
        self.parts[part].name = new.clone();
        self.name(new, Entity::Part(part));
    }

    /// The argument `keyword` of command `index`, with its index.
    fn argument(&self, index: usize, keyword: &str) -> Option<(usize, &'d Argument)> {
        self.view.statements[index]
            .arguments
            .iter()
            .enumerate()
            .find(|(_, argument)| argument.keyword == keyword)
    }

    /// The items of a list argument.
    fn items(&self, index: usize, keyword: &str) -> Option<&'d [ValueItem]> {
        match &self.argument(index, keyword)?.1.value {
            Value::List(items) => Some(items),
            _ => None,
        }
    }

    /// The single word of a list argument, upper case.
    fn word(&self, index: usize, keyword: &str) -> Option<String> {
        self.items(index, keyword)
            .and_then(|items| items.first())
            .map(|item| key(&item.text))
    }

    /// The numbers of a list argument; angles (`angle`) in radians.
    fn numbers(&mut self, index: usize, keyword: &str, angle: bool) -> Option<Vec<f64>> {
        let (_, argument) = self.argument(index, keyword)?;
        let Value::List(items) = &argument.value else {
            return None;
        };
        let mut values = Vec::new();
        for item in items {
            let degrees = item.text.trim().ends_with(['d', 'D']);
            match item.number() {
                Some(value) if angle && !degrees && self.degrees => values.push(value * PI / 180.0),
                Some(value) => values.push(value),
                None => {
                    self.wrong(
                        format!(
                            "{}: `{}` is not a number mbexpr reads (a View expression in parentheses, or a value with its unit, is evaluated by View: give the number)",
                            keyword.to_ascii_lowercase(),
                            item.text
                        ),
                        item.span,
                    );
                    return None;
                }
            }
        }
        Some(values)
    }

    /// `location` and `orientation` of command `index`, relative to
    /// `relative_to` or the default coordinate system.
    fn placed(&mut self, index: usize) -> Frame {
        let statement = &self.view.statements[index];
        let reference = match self.argument(index, "RELATIVE_TO") {
            Some((_, argument)) => match self.frame_of(index, "RELATIVE_TO") {
                Some(frame) => frame,
                None => {
                    self.wrong(
                        "relative_to names no model, part or marker the file creates before".into(),
                        argument.span,
                    );
                    Frame::GROUND
                }
            },
            None => self.coordinates,
        };
        let location = self.numbers(index, "LOCATION", false).unwrap_or_default();
        let orientation = self.numbers(index, "ORIENTATION", true).unwrap_or_default();
        for (keyword, values) in [("LOCATION", &location), ("ORIENTATION", &orientation)] {
            if !values.is_empty() && values.len() != 3 {
                let span = statement.place_of(keyword, keyword.len());
                self.wrong(
                    format!("{} takes three numbers", keyword.to_ascii_lowercase()),
                    span,
                );
            }
        }
        let three = |values: &[f64]| match values {
            [a, b, c] => [*a, *b, *c],
            _ => [0.0; 3],
        };
        let [x, y, z] = three(&location);
        let [psi, theta, phi] = three(&orientation);
        reference.then(&Frame {
            origin: Vector3::new(x, y, z),
            axes: euler_313(psi, theta, phi).to_rotation_matrix().into_inner(),
        })
    }

    /// Whether a modify command `index` places its object anew: it gives
    /// a location or orientation, and none of its placing arguments is a
    /// View expression (those restate the place the create command wrote:
    /// `(LOC_RELATIVE_TO({0, 0, 0}, .model.ground.A))`).
    fn moves(&self, index: usize) -> bool {
        let placing = ["LOCATION", "ORIENTATION", "RELATIVE_TO"]
            .map(|keyword| self.argument(index, keyword).map(|(_, argument)| argument));
        placing[..2].iter().any(Option::is_some)
            && !placing
                .iter()
                .flatten()
                .any(|argument| view_expression(argument))
    }

    /// A design variable: its single real value, which functions read.
    fn design_variable(&mut self, index: usize) {
        let Some(name) = self.word(index, "VARIABLE_NAME") else {
            return;
        };
        let Some((_, argument)) = self.argument(index, "REAL_VALUE") else {
            return;
        };
        if view_expression(argument) {
            return;
        }
        let Some([value]) = self
            .numbers(index, "REAL_VALUE", false)
            .as_deref()
            .map(|values| match values {
                [value] => [*value],
                _ => [f64::NAN],
            })
        else {
            return;
        };
        match self.find(&name) {
            Some(Entity::Design(design)) => self.designs[design] = value,
            _ => {
                self.designs.push(value);
                let full = self.full(&name);
                self.name(full, Entity::Design(self.designs.len() - 1));
            }
        }
    }

    /// A user-defined element's instance: a force's is refused (unless
    /// made inactive later); other instances (a controls plant's
    /// inputs and outputs) are passed over.
    fn user_defined(&mut self, index: usize) {
        let definition = self.word(index, "DEFINITION_NAME").unwrap_or_default();
        let Some(name) = self.word(index, "INSTANCE_NAME") else {
            return;
        };
        if definition.contains(".FORCES.") && self.view.statements[index].name.contains(" CREATE ")
        {
            self.user_forces.push((self.full(&name), index, true));
        }
    }

    /// The frame of the model, part or marker argument `keyword` names.
    fn frame_of(&self, index: usize, keyword: &str) -> Option<Frame> {
        let name = self.word(index, keyword)?;
        match self.find(&name)? {
            Entity::Model => Some(Frame::GROUND),
            Entity::Part(part) => Some(self.parts[part].frame),
            Entity::Marker(marker) => Some(self.markers[marker].frame),
            _ => None,
        }
    }

    /// The id of argument `keyword` when it is a whole number.
    fn id(&mut self, index: usize, keyword: &str) -> Option<u64> {
        let items = self.items(index, keyword)?;
        let item = items.first()?;
        match item.text.trim().parse::<u64>() {
            Ok(id) if id > 0 && id <= crate::model::LARGEST_ID => Some(id),
            _ => {
                self.wrong("adams_id must be a positive whole number".into(), item.span);
                None
            }
        }
    }

    fn command(&mut self, index: usize) {
        let statement = &self.view.statements[index];
        let (words, verb) = words_and_verb(statement);
        let words = words.as_str();
        match (words, verb) {
            ("MODEL", Some("CREATE")) => {
                if let Some(name) = self.word(index, "MODEL_NAME") {
                    let name = key(&name);
                    self.model = Some(name.clone());
                    self.name(name.clone(), Entity::Model);
                    // The ground made before any model takes the model's name.
                    match self.names.get("GROUND") {
                        Some(&Entity::Part(ground)) => {
                            self.rename_part(ground, format!("{name}.GROUND"));
                            self.parts[ground].span = statement.span;
                        }
                        _ => self.ground(Some(&name), statement.span),
                    }
                }
            }
            ("DEFAULTS UNITS", None) => self.default_units(index),
            ("DEFAULTS COORDINATE_SYSTEM", None) => {
                match self.frame_of(index, "DEFAULT_COORDINATE_SYSTEM") {
                    Some(frame) => self.coordinates = frame,
                    None => {
                        let span = statement.place_of("DEFAULT_COORDINATE_SYSTEM", 7);
                        self.wrong(
                            "default_coordinate_system names no model, part or marker the file creates before".into(),
                            span,
                        );
                    }
                }
            }
            ("VARIABLE", Some(_)) => self.design_variable(index),
            ("UDE INSTANCE", Some(_)) => self.user_defined(index),
            ("MATERIAL", Some("MODIFY")) => {
                // A density given again as a View expression keeps the
                // value the create command wrote (see `view_expression`).
                if let Some(name) = self.word(index, "MATERIAL_NAME")
                    && let Some(Entity::Material(material)) = self.find(&name)
                    && self
                        .argument(index, "DENSITY")
                        .is_some_and(|(_, argument)| !view_expression(argument))
                    && let Some(density) = self
                        .numbers(index, "DENSITY", false)
                        .and_then(|values| values.first().copied())
                {
                    self.densities[material] = density;
                }
            }
            ("MATERIAL", Some("CREATE")) => {
                if let Some(name) = self.word(index, "MATERIAL_NAME") {
                    let density = self
                        .numbers(index, "DENSITY", false)
                        .and_then(|values| values.first().copied());
                    self.densities.push(density.unwrap_or(f64::NAN));
                    let entity = Entity::Material(self.densities.len() - 1);
                    let name = self.full(&name);
                    self.name(name, entity);
                }
            }
            ("PART RIGID_BODY NAME_AND_POSITION", Some(verb)) => self.part(index, verb),
            ("PART RIGID_BODY MASS_PROPERTIES", Some(verb)) => {
                if let Some(part) = self.part_named(index, "PART_NAME") {
                    // View's expression definitions state again, as View
                    // expressions, what the create command wrote evaluated.
                    let restated = verb == "MODIFY"
                        && self.parts[part].mass.is_some()
                        && statement.arguments.iter().any(view_expression);
                    if !restated {
                        self.parts[part].mass = Some(index);
                    }
                }
            }
            ("PART RIGID_BODY INITIAL_VELOCITY", Some(_)) => {
                if let Some(part) = self.part_named(index, "PART_NAME") {
                    self.parts[part].velocity = Some(index);
                }
            }
            ("MARKER", Some(verb)) => self.marker(index, verb == "MODIFY", false),
            ("FLOATING_MARKER", Some("CREATE")) => self.marker(index, false, true),
            ("SIMULATION SINGLE_RUN TRANSIENT", None) => {
                let parameters: Vec<(String, String)> = statement
                    .arguments
                    .iter()
                    .filter_map(|argument| match &argument.value {
                        Value::List(items) => items
                            .first()
                            .map(|item| (argument.keyword.to_string(), key(&item.text))),
                        _ => None,
                    })
                    .collect();
                self.transient(&parameters, statement.span);
            }
            ("SIMULATION SCRIPT", Some(_)) => self.script(index),
            _ if words.starts_with("GEOMETRY SHAPE ") => self.solid(index, &words[15..]),
            _ if words.split(' ').nth(1) == Some("ATTRIBUTES") => self.attributes(index),
            _ => self.element(index, words, verb),
        }
    }

    fn default_units(&mut self, index: usize) {
        let statement = &self.view.statements[index];
        for argument in &statement.arguments {
            let Value::List(items) = &argument.value else {
                continue;
            };
            let Some(item) = items.first() else { continue };
            let value = key(&item.text);
            match argument.keyword.as_str() {
                "ANGLE" => match value.as_str() {
                    "DEG" | "DEGREE" | "DEGREES" => self.degrees = true,
                    "RAD" | "RADIAN" | "RADIANS" => self.degrees = false,
                    _ => self.wrong(
                        format!("angle = {}: mbexpr reads deg and rad", item.text),
                        item.span,
                    ),
                },
                kind @ ("LENGTH" | "MASS" | "FORCE" | "TIME") => match solver_unit(kind, &value) {
                    Some(unit) => {
                        for slot in &mut self.units {
                            if slot.0 == kind {
                                slot.1 = unit;
                            }
                        }
                        self.units_span = statement.span;
                    }
                    None => self.wrong(
                        format!(
                            "{} = {}: not a unit of {} mbexpr knows",
                            kind.to_ascii_lowercase(),
                            item.text,
                            kind.to_ascii_lowercase()
                        ),
                        item.span,
                    ),
                },
                "ORIENTATION_TYPE" if value != "BODY313" => self.refuse(
                    statement,
                    format!(
                        "orients by {}: mbexpr reads body313 angles, View's default",
                        item.text
                    ),
                    argument.span,
                ),
                "COORDINATE_SYSTEM_TYPE" if value != "CARTESIAN" => self.refuse(
                    statement,
                    format!(
                        "places by {} coordinates: mbexpr reads cartesian ones, View's default",
                        item.text
                    ),
                    argument.span,
                ),
                _ => {}
            }
        }
    }

    /// The part argument `keyword` of command `index` names.
    fn part_named(&mut self, index: usize, keyword: &str) -> Option<usize> {
        let name = self.word(index, keyword)?;
        match self.find(&name) {
            Some(Entity::Part(part)) => Some(part),
            _ => {
                let span = self.view.statements[index].place_of(keyword, keyword.len());
                self.wrong(
                    format!(
                        "{} names no part the file creates before",
                        keyword.to_ascii_lowercase()
                    ),
                    span,
                );
                None
            }
        }
    }

    fn part(&mut self, index: usize, verb: &str) {
        let statement = &self.view.statements[index];
        let Some(name) = self.word(index, "PART_NAME") else {
            return;
        };
        for argument in &statement.arguments {
            match argument.keyword.as_str() {
                "PART_NAME" | "NEW_PART_NAME" | "ADAMS_ID" | "LOCATION" | "ORIENTATION"
                | "RELATIVE_TO" | "COMMENTS" | "GROUND_PART" => {}
                "PLANAR" if self.word(index, "PLANAR").as_deref() == Some("NO") => {}
                "PLANAR_AXES" => {}
                _ => self.refuse(
                    statement,
                    format!(
                        "sets {}, which mbexpr does not read",
                        argument.keyword.to_ascii_lowercase()
                    ),
                    argument.span,
                ),
            }
        }
        let id = self.id(index, "ADAMS_ID");
        let part = if verb == "CREATE" {
            let name = self.full(&name);
            self.parts.push(Part {
                name: name.clone(),
                id: None,
                span: statement.span,
                frame: Frame::GROUND,
                ground: false,
                mass: None,
                velocity: None,
                solids: Vec::new(),
                active: true,
            });
            let part = self.parts.len() - 1;
            self.name(name, Entity::Part(part));
            part
        } else {
            match self.part_named(index, "PART_NAME") {
                Some(part) => part,
                None => return,
            }
        };
        if let Some(id) = id {
            self.parts[part].id = Some(id);
        }
        if let Some(new_name) = self.word(index, "NEW_PART_NAME") {
            // The markers keep their part: their names are re-entered under
            // the new one.
            let old = self.parts[part].name.clone();
            let new = match old.rsplit_once('.') {
                Some((model, _)) if !new_name.contains('.') => format!("{model}.{new_name}"),
                _ => key(&new_name),
            };
            self.rename_part(part, new);
        }
        if verb == "CREATE" || self.moves(index) {
            if self.parts[part].ground {
                self.refuse(
                    statement,
                    "moves the ground part, which stays at the origin".into(),
                    statement.span,
                );
            } else {
                self.parts[part].frame = self.placed(index);
            }
        }
    }

    fn marker(&mut self, index: usize, modify: bool, floating: bool) {
        let statement = &self.view.statements[index];
        let keyword = if floating {
            "FLOATING_MARKER_NAME"
        } else {
            "MARKER_NAME"
        };
        let Some(name) = self.word(index, keyword) else {
            return;
        };
        for argument in &statement.arguments {
            match argument.keyword.as_str() {
                "MARKER_NAME"
                | "FLOATING_MARKER_NAME"
                | "ADAMS_ID"
                | "LOCATION"
                | "ORIENTATION"
                | "RELATIVE_TO"
                | "COMMENTS" => {}
                _ => self.refuse(
                    statement,
                    format!(
                        "sets {}, which mbexpr does not read",
                        argument.keyword.to_ascii_lowercase()
                    ),
                    argument.span,
                ),
            }
        }
        let id = self.id(index, "ADAMS_ID");
        let frame = if modify && !self.moves(index) {
            Frame::GROUND
        } else {
            self.placed(index)
        };
        if modify {
            match self.find(&name) {
                Some(Entity::Marker(marker)) => {
                    if id.is_some() {
                        self.markers[marker].id = id;
                    }
                    if self.moves(index) {
                        self.markers[marker].frame = frame;
                    }
                }
                _ => {
                    let span = statement.place_of(keyword, keyword.len());
                    self.wrong(
                        "marker_name names no marker the file creates before".into(),
                        span,
                    );
                }
            }
            return;
        }
        let full = self.full(&name);
        let Some((owner, _)) = full.rsplit_once('.') else {
            let span = statement.place_of(keyword, keyword.len());
            self.wrong(
                "a marker's name starts with its part's: .model.part.marker".into(),
                span,
            );
            return;
        };
        let part = match self.find(owner) {
            Some(Entity::Part(part)) => part,
            _ => {
                let span = statement.place_of(keyword, keyword.len());
                self.wrong(
                    format!("the marker's part {owner} is not created before it"),
                    span,
                );
                return;
            }
        };
        self.markers.push(Marker {
            id,
            span: statement.span,
            part,
            frame,
            floating,
        });
        self.name(full, Entity::Marker(self.markers.len() - 1));
    }

    fn transient(&mut self, parameters: &[(String, String)], span: Span) {
        let value = |name: &str| {
            parameters
                .iter()
                .find(|(keyword, _)| keyword.eq_ignore_ascii_case(name))
                .map(|(_, value)| value.as_str())
        };
        let number = |name: &str| value(name).and_then(|text| text.parse::<f64>().ok());
        let end = number("END_TIME").or_else(|| number("DURATION"));
        let steps = number("NUMBER_OF_STEPS")
            .or_else(|| Some(end? / number("STEP_SIZE")?))
            .filter(|steps| steps.is_finite() && *steps >= 1.0);
        match (end, steps) {
            (Some(end), Some(steps)) if end > 0.0 => {
                self.run = Some(RunCommands {
                    end,
                    steps: steps.round() as usize,
                    statics: value("INITIAL_STATIC").is_some_and(|value| value == "YES"),
                    land_on_outputs: false,
                    span,
                });
            }
            _ => self.notes.push((
                "this simulation gives no end time and steps mbexpr reads (end_time and number_of_steps or step_size): give --end and --steps".into(),
                span,
            )),
        }
    }

    /// A `simulation script`'s transient commands, as if given alone.
    fn script(&mut self, index: usize) {
        let Some(items) = self.items(index, "COMMANDS") else {
            return;
        };
        for item in items {
            let text = item.text.replace(" =", "=").replace("= ", "=");
            let mut tokens = text.split_whitespace();
            let words: Vec<String> = tokens
                .by_ref()
                .take(3)
                .map(str::to_ascii_uppercase)
                .collect();
            let transient = ["SIMULATION", "SINGLE_RUN", "TRANSIENT"]
                .iter()
                .zip(&words)
                .all(|(full, word)| word.len() >= 3 && full.starts_with(word.as_str()));
            if words.len() < 3 || !transient {
                continue;
            }
            let parameters: Vec<(String, String)> = tokens
                .filter_map(|token| token.split_once('='))
                .map(|(name, value)| (name.to_ascii_uppercase(), key(value)))
                .collect();
            self.transient(&parameters, item.span);
        }
    }

    fn solid(&mut self, index: usize, shape: &str) {
        let statement = &self.view.statements[index];
        let Some(name) = statement
            .arguments
            .iter()
            .find(|argument| argument.keyword.ends_with("_NAME"))
            .and_then(|argument| match &argument.value {
                Value::List(items) => items.first().map(|item| self.full(&item.text)),
                _ => None,
            })
        else {
            return;
        };
        let restated = statement
            .arguments
            .iter()
            .filter(|argument| !argument.keyword.ends_with("_NAME"))
            .all(view_expression);
        if statement.name.contains(" MODIFY ") && restated {
            return;
        }
        if statement.name.contains(" CREATE ") {
            let id = self.id(index, "ADAMS_ID");
            self.geometries.push(Geometry {
                command: index,
                shape: shape.to_string(),
                id,
                met: false,
            });
            self.name(name.clone(), Entity::Geometry(self.geometries.len() - 1));
        }
        // Shapes without volume add no mass; every other is a solid of its
        // part (refused where the part's mass comes from its geometry and
        // mbexpr does not compute the shape's: see `solid_moments`).
        if WIRES.contains(&shape) {
            return;
        }
        if let Some((owner, _)) = name.rsplit_once('.')
            && let Some(Entity::Part(part)) = self.find(owner)
        {
            self.parts[part].solids.push(index);
        }
    }

    fn attributes(&mut self, index: usize) {
        let statement = &self.view.statements[index];
        let Some(active) = self.word(index, "ACTIVE") else {
            return;
        };
        if !matches!(active.as_str(), "OFF" | "NO") {
            return;
        }
        let Some(name) = statement
            .arguments
            .iter()
            .find(|argument| argument.keyword.ends_with("_NAME"))
            .and_then(|argument| match &argument.value {
                Value::List(items) => items.first().map(|item| item.text.clone()),
                _ => None,
            })
        else {
            return;
        };
        match self.find(&name) {
            Some(Entity::Element(element)) => {
                self.elements[element].active = false;
                self.notes.push((
                    format!("{} is inactive (active = off): left out", key(&name)),
                    statement.span,
                ));
            }
            Some(Entity::Part(part)) => {
                if self.parts[part].ground {
                    self.refuse(
                        statement,
                        "deactivates the ground part".into(),
                        statement.span,
                    );
                } else {
                    self.parts[part].active = false;
                    self.notes.push((
                        format!(
                            "{} is inactive (active = off): left out, with its markers and the elements on them",
                            name.trim_matches('"')
                        ),
                        statement.span,
                    ));
                }
            }
            Some(Entity::Marker(_)) => self.refuse(
                statement,
                "deactivates a marker, which mbexpr does not: make the elements on it inactive"
                    .into(),
                statement.span,
            ),
            // What the reading passes over (a measure, a graphic, a solid
            // from a file) stays out; a user-defined force made inactive
            // is not refused.
            _ => {
                let name = key(&name);
                for (force, _, active) in &mut self.user_forces {
                    if *force == name {
                        *active = false;
                    }
                }
            }
        }
    }

    fn element(&mut self, index: usize, words: &str, verb: Option<&str>) {
        let statement = &self.view.statements[index];
        let read =
            ELEMENTS.iter().any(|kind| kind.words == words) || constraint_kind(words).is_some();
        let passed_over = PASSED_OVER.iter().any(|over| {
            let spaced = format!("{over} ");
            words == *over || words.starts_with(&spaced) || statement.name.starts_with(&spaced)
        });
        if passed_over && !read {
            return;
        }
        if let Some((_, note)) = NOTED
            .iter()
            .find(|(over, _)| words == *over || words.starts_with(&format!("{over} ")))
        {
            self.notes.push((note.to_string(), statement.span));
            return;
        }
        let found = ELEMENTS
            .iter()
            .find(|kind| kind.words == words)
            .map(|kind| {
                (
                    kind.statement,
                    kind.flags.to_vec(),
                    kind.name,
                    kind.parameters,
                )
            })
            .or_else(|| {
                let (statement, flag) = constraint_kind(words)?;
                let name = if statement == "JOINT" {
                    "JOINT_NAME"
                } else {
                    "JPRIM_NAME"
                };
                let parameters: &'static [(&'static str, Becomes)] = if statement == "JOINT" {
                    JOINT_PARAMETERS
                } else {
                    &TWO_MARKERS
                };
                Some((statement, vec![flag], name, parameters))
            });
        let Some((solver, flags, name_keyword, parameters)) = found else {
            self.refuse(
                statement,
                "is not read: mbexpr simulates a View file's parts, markers, joints, joint primitives, motions, single-component forces, force and torque vectors, general forces, spring-dampers, bushings, beams, contacts, gravity, variables, differential equations, function requests and sensors".into(),
                statement.span,
            );
            return;
        };
        let Some(verb) = verb else {
            self.refuse(statement, "is not read".into(), statement.span);
            return;
        };
        let Some(name) = self.word(index, name_keyword) else {
            let span = statement.span;
            self.wrong(
                format!("{} is missing", name_keyword.to_ascii_lowercase()),
                span,
            );
            return;
        };
        let element = if verb == "CREATE" {
            self.elements.push(Element {
                statement: solver,
                flags,
                parameters,
                id: None,
                span: statement.span,
                given: Vec::new(),
                active: true,
            });
            let element = self.elements.len() - 1;
            let full = self.full(&name);
            self.name(full, Entity::Element(element));
            element
        } else {
            match self.find(&name) {
                Some(Entity::Element(element)) if self.elements[element].statement == solver => {
                    element
                }
                _ => {
                    let span = statement.place_of(name_keyword, name_keyword.len());
                    self.wrong(
                        format!(
                            "{} names no {} the file creates before",
                            name_keyword.to_ascii_lowercase(),
                            words.to_ascii_lowercase()
                        ),
                        span,
                    );
                    return;
                }
            }
        };
        if let Some(id) = self.id(index, "ADAMS_ID") {
            self.elements[element].id = Some(id);
        }
        for (position, argument) in statement.arguments.iter().enumerate() {
            let keyword = argument.keyword.as_str();
            if keyword == name_keyword || matches!(keyword, "ADAMS_ID" | "COMMENTS" | "NEW_NAME") {
                continue;
            }
            if !parameters.iter().any(|(view, _)| *view == keyword) {
                self.refuse(
                    statement,
                    format!(
                        "sets {}, which mbexpr does not read",
                        keyword.to_ascii_lowercase()
                    ),
                    argument.span,
                );
                continue;
            }
            let known = self.elements[element]
                .given
                .iter()
                .any(|(name, _, _)| name == keyword);
            if view_expression(argument) {
                // A View expression restates the value the create command
                // wrote evaluated; one with nothing before cannot be read.
                if !known {
                    self.wrong(
                        format!(
                            "{}: a View expression mbexpr does not evaluate, and no command before gives the value: give the number",
                            keyword.to_ascii_lowercase()
                        ),
                        argument.span,
                    );
                }
                continue;
            }
            let given = &mut self.elements[element].given;
            given.retain(|(name, _, _)| name != keyword);
            given.push((argument.keyword.clone(), index, position));
        }
    }

    /// The ids of every object, given or the next free of its kind.
    fn assign_ids(&mut self) {
        let mut taken: HashMap<&'static str, HashSet<u64>> = HashMap::new();
        for part in &self.parts {
            taken.entry("PART").or_default().extend(part.id);
        }
        for marker in &self.markers {
            taken.entry("MARKER").or_default().extend(marker.id);
        }
        for element in &self.elements {
            taken
                .entry(element.statement)
                .or_default()
                .extend(element.id);
        }
        for geometry in &self.geometries {
            taken.entry("GRAPHICS").or_default().extend(geometry.id);
        }
        let mut next = |kind: &'static str| {
            let ids = taken.entry(kind).or_default();
            let id = (1..).find(|id| !ids.contains(id)).unwrap_or(1);
            ids.insert(id);
            id
        };
        // The ground first, so that it takes 1 when it is free.
        let mut order: Vec<usize> = (0..self.parts.len()).collect();
        order.sort_by_key(|&part| !self.parts[part].ground);
        for part in order {
            if self.parts[part].id.is_none() {
                self.parts[part].id = Some(next("PART"));
            }
        }
        for marker in &mut self.markers {
            if marker.id.is_none() {
                marker.id = Some(next("MARKER"));
            }
        }
        for element in &mut self.elements {
            if element.id.is_none() {
                element.id = Some(next(element.statement));
            }
        }
        for geometry in &mut self.geometries {
            if geometry.id.is_none() {
                geometry.id = Some(next("GRAPHICS"));
            }
        }
    }

    /// Makes inactive every element that names a marker or solid on an
    /// inactive part, or a joint made inactive so (in file order), as View
    /// does with what depends on an inactive part.
    fn leave_out_on_inactive_parts(&mut self) {
        if self.parts.iter().all(|part| part.active) {
            return;
        }
        for element in 0..self.elements.len() {
            if !self.elements[element].active {
                continue;
            }
            let parameters = self.elements[element].parameters;
            let mut on_inactive = false;
            for (keyword, index, _) in &self.elements[element].given {
                let Some(&(_, becomes)) = parameters.iter().find(|(view, _)| view == keyword)
                else {
                    continue;
                };
                let names: Vec<String> = self
                    .items(*index, keyword)
                    .unwrap_or_default()
                    .iter()
                    .map(|item| item.text.to_string())
                    .collect();
                for name in names {
                    on_inactive |= match (becomes, self.find(&name)) {
                        (
                            Becomes::Marker(_) | Becomes::Floating(_),
                            Some(Entity::Marker(marker)),
                        ) => !self.parts[self.markers[marker].part].active,
                        (Becomes::FloatingOn(_), Some(Entity::Part(part))) => {
                            !self.parts[part].active
                        }
                        (Becomes::Solids(_), Some(Entity::Geometry(geometry))) => {
                            let owner = self.full(&name);
                            owner.rsplit_once('.').is_some_and(|(owner, _)| {
                                matches!(self.find(owner), Some(Entity::Part(part)) if !self.parts[part].active)
                            }) && geometry < self.geometries.len()
                        }
                        (Becomes::Object(_) | Becomes::Joints(_), Some(Entity::Element(joint))) => {
                            !self.elements[joint].active
                        }
                        _ => false,
                    };
                }
            }
            if on_inactive {
                self.elements[element].active = false;
                let span = self.elements[element].span;
                self.notes
                    .push(("left out: it acts on an inactive part".into(), span));
            }
        }
    }

    /// A new marker on `part` at `frame`, with the next free id.
    fn new_marker(&mut self, part: usize, frame: Frame, floating: bool, span: Span) -> u64 {
        let id = self
            .markers
            .iter()
            .filter_map(|marker| marker.id)
            .max()
            .unwrap_or(0)
            + 1;
        self.markers.push(Marker {
            id: Some(id),
            span,
            part,
            frame,
            floating,
        });
        id
    }

    /// The solver statements.
    fn write(&mut self) -> Vec<Statement> {
        for (_, index, active) in self.user_forces.clone() {
            if active {
                let command = &self.view.statements[index];
                self.refuse(
                    command,
                    "is a user-defined force (a View library element), which mbexpr does not read: write it as a force element".into(),
                    command.span,
                );
            }
        }
        self.assign_ids();
        let mut statements = Vec::new();
        let mut units = new_statement("UNITS", None, self.units_span);
        for (kind, unit) in self.units {
            words_argument(&mut units, kind, &[unit], self.units_span);
        }
        statements.push(units);
        self.leave_out_on_inactive_parts();
        let mut parts = Vec::new();
        for part in 0..self.parts.len() {
            if !self.parts[part].active {
                continue;
            }
            if let Some(statement) = self.write_part(part) {
                parts.push(statement);
            }
        }
        statements.extend(parts);
        let mut elements = Vec::new();
        for element in 0..self.elements.len() {
            if self.elements[element].active
                && self.elements[element].statement != MEASURE
                && let Some(statement) = self.write_element(element)
            {
                elements.push(statement);
            }
        }
        for geometry in 0..self.geometries.len() {
            if self.geometries[geometry].met
                && let Some(statement) = self.write_graphic(geometry)
            {
                elements.push(statement);
            }
        }
        // Markers last: writing the parts and elements makes some.
        for marker in &self.markers {
            let part = &self.parts[marker.part];
            if !part.active {
                continue;
            }
            let mut statement = new_statement("MARKER", marker.id, marker.span);
            ids_argument(&mut statement, "PART", part.id.unwrap_or(0), marker.span);
            if marker.floating {
                flag_argument(&mut statement, "FLOATING", marker.span);
            } else {
                let local = part.frame.seen(&marker.frame);
                place_arguments(&mut statement, ["QP", "ZP", "XP"], &local, marker.span);
            }
            statements.push(statement);
        }
        statements.extend(elements);
        statements
    }

    fn write_part(&mut self, part: usize) -> Option<Statement> {
        let span = self.parts[part].span;
        let mut statement = new_statement("PART", self.parts[part].id, span);
        if self.parts[part].ground {
            flag_argument(&mut statement, "GROUND", span);
            return Some(statement);
        }
        let frame = self.parts[part].frame;
        place_arguments(&mut statement, ["QG", "ZG", "XG"], &frame, span);
        if let Some(index) = self.parts[part].mass {
            self.mass_properties(part, index, &mut statement);
        }
        if let Some(index) = self.parts[part].velocity {
            self.velocities(index, &mut statement);
        }
        Some(statement)
    }

    fn marker_id(&mut self, index: usize, keyword: &str) -> Option<u64> {
        let name = self.word(index, keyword)?;
        match self.find(&name) {
            Some(Entity::Marker(marker)) => self.markers[marker].id,
            _ => {
                let span = self.view.statements[index].place_of(keyword, keyword.len());
                self.wrong(
                    format!(
                        "{} names no marker the file creates",
                        keyword.to_ascii_lowercase()
                    ),
                    span,
                );
                None
            }
        }
    }

    fn mass_properties(&mut self, part: usize, index: usize, statement: &mut Statement) {
        let command = &self.view.statements[index];
        let span = command.span;
        let density = if let Some(material) = self.word(index, "MATERIAL_TYPE") {
            match self.find(&material) {
                Some(Entity::Material(material)) => Some(self.densities[material]),
                _ => {
                    let span = command.place_of("MATERIAL_TYPE", 13);
                    self.wrong(
                        "material_type names no material the file creates (material create material_name = ... density = ...)".into(),
                        span,
                    );
                    return;
                }
            }
        } else {
            self.numbers(index, "DENSITY", false)
                .and_then(|values| values.first().copied())
        };
        if let Some(density) = density {
            if !(density.is_finite() && density > 0.0) {
                self.wrong(
                    "the part's material has no positive density: mbexpr computes its mass from its geometry".into(),
                    span,
                );
                return;
            }
            self.mass_from_solids(part, density, statement, span);
            return;
        }
        for argument in &command.arguments {
            let keyword = argument.keyword.as_str();
            if !matches!(
                keyword,
                "PART_NAME"
                    | "MASS"
                    | "CENTER_OF_MASS_MARKER"
                    | "INERTIA_MARKER"
                    | "IXX"
                    | "IYY"
                    | "IZZ"
                    | "IXY"
                    | "IZX"
                    | "IYZ"
            ) {
                let reason = format!(
                    "sets {}, which mbexpr does not read",
                    keyword.to_ascii_lowercase()
                );
                self.refuse(command, reason, argument.span);
            }
        }
        let value = |reader: &mut Self, keyword: &str| {
            reader
                .numbers(index, keyword, false)
                .and_then(|values| values.first().copied())
                .unwrap_or(0.0)
        };
        let mass = value(self, "MASS");
        let moments =
            ["IXX", "IYY", "IZZ", "IXY", "IZX", "IYZ"].map(|keyword| value(self, keyword));
        numbers_argument(statement, "MASS", &[mass], span);
        if let Some(id) = self.marker_id(index, "CENTER_OF_MASS_MARKER") {
            ids_argument(statement, "CM", id, span);
        }
        if let Some(id) = self.marker_id(index, "INERTIA_MARKER") {
            ids_argument(statement, "IM", id, span);
        }
        numbers_argument(statement, "IP", &moments, span);
    }

    /// MASS, CM (a marker made at the centre of mass, with the part's
    /// axes) and IP of `part` from its solids at `density`.
    fn mass_from_solids(
        &mut self,
        part: usize,
        density: f64,
        statement: &mut Statement,
        span: Span,
    ) {
        let mut total = Moments::default();
        let mut refused = false;
        for index in self.parts[part].solids.clone() {
            let (words, _) = words_and_verb(&self.view.statements[index]);
            let shape = words.trim_start_matches("GEOMETRY SHAPE ").to_string();
            match self.solid_moments(index, &shape) {
                Ok(Some(moments)) => total.add(&moments),
                Ok(None) => {}
                Err(reason) => {
                    let command = &self.view.statements[index];
                    self.refuse(command, reason, command.span);
                    refused = true;
                }
            }
        }
        if refused {
            return;
        }
        if total.volume <= 0.0 {
            self.wrong(
                "the part's mass comes from its geometry (material_type or density), but it has no solid whose volume mbexpr computes (block, cylinder, frustum, ellipsoid, torus, link)".into(),
                span,
            );
            return;
        }
        let mass = density * total.volume;
        let centre = total.first / total.volume;
        // ∫ r rᵀ dV about the centre, then the inertia tensor.
        let second = total.second - centre * centre.transpose() * total.volume;
        let tensor = (Matrix3::identity() * second.trace() - second) * density;
        let frame = self.parts[part].frame;
        let in_part = frame.axes.transpose() * tensor * frame.axes;
        let at = Frame {
            origin: centre,
            axes: frame.axes,
        };
        let id = self.new_marker(part, at, false, span);
        numbers_argument(statement, "MASS", &[mass], span);
        ids_argument(statement, "CM", id, span);
        // Adams' products are the positive integrals (Ixy = ∫xy dm).
        numbers_argument(
            statement,
            "IP",
            &[
                in_part[(0, 0)],
                in_part[(1, 1)],
                in_part[(2, 2)],
                -in_part[(0, 1)],
                -in_part[(0, 2)],
                -in_part[(1, 2)],
            ],
            span,
        );
    }

    /// The volume moments of the solid command `index` in the ground's
    /// axes; `None` for a shape that has no volume.
    fn solid_moments(&mut self, index: usize, shape: &str) -> Result<Option<Moments>, String> {
        let marker_frame = |reader: &mut Self, keyword: &str| -> Result<Frame, String> {
            let name = reader
                .word(index, keyword)
                .ok_or_else(|| format!("has no {}", keyword.to_ascii_lowercase()))?;
            match reader.find(&name) {
                Some(Entity::Marker(marker)) => Ok(reader.markers[marker].frame),
                _ => Err(format!(
                    "{} names no marker the file creates",
                    keyword.to_ascii_lowercase()
                )),
            }
        };
        let number = |reader: &mut Self, keyword: &str, angle: bool| -> Result<f64, String> {
            reader
                .numbers(index, keyword, angle)
                .and_then(|values| values.first().copied())
                .ok_or_else(|| format!("has no {}", keyword.to_ascii_lowercase()))
        };
        let whole_turn = |reader: &mut Self| -> Result<(), String> {
            if reader.argument(index, "ANGLE_EXTENT").is_none() {
                return Ok(());
            }
            let extent = number(reader, "ANGLE_EXTENT", true)?;
            if (extent.abs() - 2.0 * PI).abs() > 1e-9 {
                return Err(
                    "is a part of a turn (angle_extent): mbexpr computes the mass of whole solids of revolution".into(),
                );
            }
            Ok(())
        };
        if self.view.statements[index].name.contains(" MODIFY ") {
            return Err(
                "changes a solid after its creation: mbexpr reads a part's solids as created"
                    .into(),
            );
        }
        let local = match shape {
            "BLOCK" => {
                let frame = marker_frame(self, "CORNER_MARKER")?;
                let corner = self
                    .numbers(index, "DIAG_CORNER_COORDS", false)
                    .filter(|values| values.len() == 3)
                    .ok_or("has no diag_corner_coords")?;
                (
                    frame,
                    Moments::block(Vector3::new(corner[0], corner[1], corner[2])),
                )
            }
            "CYLINDER" => {
                whole_turn(self)?;
                let frame = marker_frame(self, "CENTER_MARKER")?;
                let (length, radius) = (
                    number(self, "LENGTH", false)?,
                    number(self, "RADIUS", false)?,
                );
                (frame, Moments::frustum(length, radius, radius))
            }
            "FRUSTUM" => {
                whole_turn(self)?;
                let frame = marker_frame(self, "CENTER_MARKER")?;
                let length = number(self, "LENGTH", false)?;
                let bottom = number(self, "BOTTOM_RADIUS", false)?;
                let top = number(self, "TOP_RADIUS", false)?;
                (frame, Moments::frustum(length, bottom, top))
            }
            "ELLIPSOID" => {
                let frame = marker_frame(self, "CENTER_MARKER")?;
                let scales = ["X_SCALE_FACTOR", "Y_SCALE_FACTOR", "Z_SCALE_FACTOR"]
                    .map(|keyword| number(self, keyword, false));
                let [x, y, z] = [&scales[0], &scales[1], &scales[2]].map(|scale| scale.clone());
                (frame, Moments::ellipsoid(x? / 2.0, y? / 2.0, z? / 2.0))
            }
            "TORUS" => {
                whole_turn(self)?;
                let frame = marker_frame(self, "CENTER_MARKER")?;
                let major = number(self, "MAJOR_RADIUS", false)?;
                let minor = number(self, "MINOR_RADIUS", false)?;
                (frame, Moments::torus(major, minor))
            }
            "LINK" => {
                let start = marker_frame(self, "I_MARKER")?;
                let end = marker_frame(self, "J_MARKER")?;
                let width = number(self, "WIDTH", false)?;
                let depth = number(self, "DEPTH", false)?;
                let along = end.origin - start.origin;
                let length = along.norm();
                let x = along
                    .try_normalize(1e-12 * start.origin.amax().max(1.0))
                    .ok_or("has its I and J markers at one point")?;
                let z = start.axes.column(2) - x * x.dot(&start.axes.column(2));
                let z = z
                    .try_normalize(1e-9)
                    .ok_or("has its J marker off the I marker's xy plane")?;
                let frame = Frame {
                    origin: start.origin,
                    axes: Matrix3::from_columns(&[x, z.cross(&x), z]),
                };
                (frame, Moments::link(length, width, depth))
            }
            _ => {
                return Err(
                    "is a shape whose volume mbexpr does not compute: give the part's mass, centre of mass and inertia (mass_properties with mass, center_of_mass_marker, ixx ...)".into(),
                );
            }
        };
        let (frame, moments) = local;
        if !(moments.volume.is_finite() && moments.volume > 0.0) {
            return Err("has no volume: its sizes must be positive".into());
        }
        Ok(Some(moments.moved(&frame)))
    }

    fn velocities(&mut self, index: usize, statement: &mut Statement) {
        let command = &self.view.statements[index];
        let span = command.span;
        for argument in &command.arguments {
            let keyword = argument.keyword.as_str();
            match keyword {
                "PART_NAME" => {}
                "VX" | "VY" | "VZ" | "WX" | "WY" | "WZ" => {
                    let angular = keyword.starts_with('W');
                    if let Some(values) = self.numbers(index, keyword, angular) {
                        numbers_argument(statement, keyword, &values, argument.span);
                    }
                }
                "VM" | "WM" => {
                    if let Some(id) = self.marker_id(index, keyword) {
                        ids_argument(statement, keyword, id, argument.span);
                    }
                }
                "GROUND" | "VX_GROUND" => {}
                _ => {
                    let reason = format!(
                        "sets {}, which mbexpr does not read",
                        keyword.to_ascii_lowercase()
                    );
                    self.refuse(command, reason, argument.span);
                }
            }
        }
        let _ = span;
    }

    fn write_element(&mut self, element: usize) -> Option<Statement> {
        let (solver, span, id) = {
            let element = &self.elements[element];
            (element.statement, element.span, element.id)
        };
        let id = if solver == "ACCGRAV" { None } else { id };
        let mut statement = new_statement(solver, id, span);
        for flag in self.elements[element].flags.clone() {
            flag_argument(&mut statement, flag, span);
        }
        let rotational = self.elements[element]
            .given
            .iter()
            .any(|(keyword, index, _)| {
                matches!(keyword.as_str(), "TYPE_OF_FREEDOM" | "AXIS")
                    && matches!(
                        self.word(*index, keyword).as_deref(),
                        Some("ROTATIONAL" | "B1" | "B2" | "B3")
                    )
            });
        let given = |name: &str| {
            self.elements[element]
                .given
                .iter()
                .any(|(keyword, _, _)| keyword == name)
        };
        if solver == "CONTACT" && !given("STIFFNESS") && given("RESTITUTION_COEFFICIENT") {
            self.refuse(
                &self.view.statements[self.elements[element].given[0].1],
                "is a restitution (POISSON) contact, which mbexpr does not simulate: give the impact law's stiffness, damping, exponent and dmax".into(),
                span,
            );
            return None;
        }
        let parameters = self.elements[element].parameters;
        for (keyword, index, position) in self.elements[element].given.clone() {
            let argument = &self.view.statements[index].arguments[position];
            let Some(&(_, becomes)) = parameters.iter().find(|(view, _)| *view == keyword) else {
                continue;
            };
            let argument_span = argument.span;
            match becomes {
                Becomes::Marker(solver_keyword) | Becomes::Floating(solver_keyword) => {
                    if let Some(id) = self.marker_id(index, &keyword) {
                        ids_argument(&mut statement, solver_keyword, id, argument_span);
                    }
                }
                Becomes::FloatingOn(solver_keyword) => {
                    if let Some(part) = self.part_named(index, &keyword) {
                        let frame = self.parts[part].frame;
                        let id = self.new_marker(part, frame, true, argument_span);
                        ids_argument(&mut statement, solver_keyword, id, argument_span);
                    }
                }
                Becomes::Object(solver_keyword) => {
                    let name = self.word(index, &keyword).unwrap_or_default();
                    match self.find(&name) {
                        Some(Entity::Element(target))
                            if self.elements[target].statement == solver_keyword =>
                        {
                            let target_id = self.elements[target].id.unwrap_or(0);
                            ids_argument(&mut statement, solver_keyword, target_id, argument_span);
                        }
                        _ => self.wrong(
                            format!(
                                "{} names no {} the file creates",
                                keyword.to_ascii_lowercase(),
                                solver_keyword.to_ascii_lowercase()
                            ),
                            argument_span,
                        ),
                    }
                }
                Becomes::Numbers(solver_keyword) => {
                    if let Some(values) = self.numbers(index, &keyword, false) {
                        numbers_argument(&mut statement, solver_keyword, &values, argument_span);
                    }
                }
                Becomes::Angles(solver_keyword) => {
                    if let Some(values) = self.numbers(index, &keyword, true) {
                        numbers_argument(&mut statement, solver_keyword, &values, argument_span);
                    }
                }
                Becomes::Initial(solver_keyword) => {
                    if let Some(values) = self.numbers(index, &keyword, rotational) {
                        numbers_argument(&mut statement, solver_keyword, &values, argument_span);
                    }
                }
                Becomes::PerAngle(solver_keyword) => {
                    if let Some(values) = self.numbers(index, &keyword, false) {
                        let scale = if self.degrees { 180.0 / PI } else { 1.0 };
                        let values: Vec<f64> = values.iter().map(|value| value * scale).collect();
                        numbers_argument(&mut statement, solver_keyword, &values, argument_span);
                    }
                }
                Becomes::Function(solver_keyword) => {
                    if let Some(text) = self.function(index, position) {
                        statement.arguments.push(Argument {
                            keyword: solver_keyword.into(),
                            keyword_span: argument.keyword_span,
                            span: argument_span,
                            value: Value::Expression {
                                text,
                                span: argument_span,
                            },
                        });
                    }
                }
                Becomes::Choice(choices) => {
                    let word = self.word(index, &keyword).unwrap_or_default();
                    match choices.iter().find(|(view, _)| *view == word) {
                        Some(&(_, solver_keyword)) => {
                            flag_argument(&mut statement, solver_keyword, argument_span);
                        }
                        None => self.wrong(
                            format!(
                                "{} is one of {}",
                                keyword.to_ascii_lowercase(),
                                choices
                                    .iter()
                                    .map(|(view, _)| view.to_ascii_lowercase())
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            ),
                            argument_span,
                        ),
                    }
                }
                Becomes::Word(solver_keyword) => {
                    let word = self.word(index, &keyword).unwrap_or_default();
                    words_argument(&mut statement, solver_keyword, &[&word], argument_span);
                }
                Becomes::Solids(solver_keyword) => {
                    let names: Vec<String> = self
                        .items(index, &keyword)
                        .unwrap_or_default()
                        .iter()
                        .map(|item| item.text.to_string())
                        .collect();
                    let mut ids = Vec::new();
                    for name in names {
                        match self.find(&name) {
                            Some(Entity::Geometry(geometry)) => {
                                self.geometries[geometry].met = true;
                                ids.push(self.geometries[geometry].id.unwrap_or(0).to_string());
                            }
                            _ => self.refuse(
                                &self.view.statements[index],
                                format!(
                                    "meets {name}, which is no solid this file creates (solids read from a file by `file parasolid read` are not read)"
                                ),
                                argument_span,
                            ),
                        }
                    }
                    let ids: Vec<&str> = ids.iter().map(String::as_str).collect();
                    words_argument(&mut statement, solver_keyword, &ids, argument_span);
                }
                Becomes::Joints(solver_keyword) => {
                    let names: Vec<String> = self
                        .items(index, &keyword)
                        .unwrap_or_default()
                        .iter()
                        .map(|item| item.text.to_string())
                        .collect();
                    let mut ids = Vec::new();
                    for name in names {
                        match self.find(&name) {
                            Some(Entity::Element(joint))
                                if self.elements[joint].statement == "JOINT" =>
                            {
                                ids.push(self.elements[joint].id.unwrap_or(0).to_string());
                            }
                            _ => self.wrong(
                                format!("{name} is no joint the file creates"),
                                argument_span,
                            ),
                        }
                    }
                    let ids: Vec<&str> = ids.iter().map(String::as_str).collect();
                    words_argument(&mut statement, solver_keyword, &ids, argument_span);
                }
                Becomes::Freedoms(solver_keyword) => {
                    let word = self.word(index, &keyword).unwrap_or_default();
                    let freedoms: Option<Vec<&str>> = word
                        .split('_')
                        .map(|freedom| match freedom {
                            "TRANS" | "TRANSLATIONAL" => Some("T"),
                            "ROT" | "ROTATIONAL" => Some("R"),
                            _ => None,
                        })
                        .collect();
                    match freedoms {
                        Some(freedoms) => {
                            let value = freedoms.join(":");
                            words_argument(
                                &mut statement,
                                solver_keyword,
                                &[&value],
                                argument_span,
                            );
                        }
                        None => self.wrong(
                            format!(
                                "{} is the joints' freedoms joined by _ (rot_rot, trans_rot ...)",
                                keyword.to_ascii_lowercase()
                            ),
                            argument_span,
                        ),
                    }
                }
                Becomes::Switch(solver_keyword) => {
                    let word = self.word(index, &keyword).unwrap_or_default();
                    match word.as_str() {
                        "ON" | "YES" | "TRUE" => {
                            flag_argument(&mut statement, solver_keyword, argument_span);
                        }
                        "OFF" | "NO" | "FALSE" => {}
                        _ => self.wrong(
                            format!("{} is on or off", keyword.to_ascii_lowercase()),
                            argument_span,
                        ),
                    }
                }
                Becomes::Nothing => {}
            }
        }
        Some(statement)
    }

    /// The GRAPHICS statement of a geometry a contact meets: the solids a
    /// CONTACT reads (a sphere, a block, a cylinder, a frustum, a plane);
    /// another shape is refused at its command.
    fn write_graphic(&mut self, geometry: usize) -> Option<Statement> {
        let index = self.geometries[geometry].command;
        let shape = self.geometries[geometry].shape.clone();
        let span = self.view.statements[index].span;
        let mut statement = new_statement("GRAPHICS", self.geometries[geometry].id, span);
        let marker = |reader: &mut Self, view: &str, solver: &str, statement: &mut Statement| {
            if let Some(id) = reader.marker_id(index, view) {
                ids_argument(statement, solver, id, span);
            }
        };
        let numbers = |reader: &mut Self, view: &str, solver: &str, statement: &mut Statement| {
            if let Some(values) = reader.numbers(index, view, false) {
                numbers_argument(statement, solver, &values, span);
            }
        };
        match shape.as_str() {
            "ELLIPSOID" => {
                flag_argument(&mut statement, "ELLIPSOID", span);
                marker(self, "CENTER_MARKER", "CM", &mut statement);
                for (view, solver) in [
                    ("X_SCALE_FACTOR", "XSCALE"),
                    ("Y_SCALE_FACTOR", "YSCALE"),
                    ("Z_SCALE_FACTOR", "ZSCALE"),
                ] {
                    numbers(self, view, solver, &mut statement);
                }
            }
            "BLOCK" => {
                flag_argument(&mut statement, "BOX", span);
                marker(self, "CORNER_MARKER", "CORNER", &mut statement);
                if let Some(corner) = self.numbers(index, "DIAG_CORNER_COORDS", false)
                    && let [x, y, z] = corner[..]
                {
                    for (keyword, value) in [("X", x), ("Y", y), ("Z", z)] {
                        numbers_argument(&mut statement, keyword, &[value], span);
                    }
                }
            }
            "CYLINDER" | "FRUSTUM" => {
                flag_argument(&mut statement, &shape, span);
                marker(self, "CENTER_MARKER", "CM", &mut statement);
                numbers(self, "LENGTH", "LENGTH", &mut statement);
                if shape == "CYLINDER" {
                    numbers(self, "RADIUS", "RADIUS", &mut statement);
                } else {
                    numbers(self, "TOP_RADIUS", "TOP", &mut statement);
                    numbers(self, "BOTTOM_RADIUS", "BOTTOM", &mut statement);
                }
                let extent = self
                    .numbers(index, "ANGLE_EXTENT", true)
                    .and_then(|values| values.first().copied())
                    .unwrap_or(2.0 * PI);
                if (extent.abs() - 2.0 * PI).abs() > 1e-9 {
                    numbers_argument(&mut statement, "RANGLE", &[extent], span);
                }
            }
            "PLANE" => {
                flag_argument(&mut statement, "PLANE", span);
                marker(self, "REF_MARKER", "RM", &mut statement);
            }
            _ => {
                let command = &self.view.statements[index];
                self.refuse(
                    command,
                    "is a solid a contact meets that mbexpr does not: it meets spheres (ellipsoids of equal scales), blocks, cylinders, frustums and planes".into(),
                    span,
                );
                return None;
            }
        }
        Some(statement)
    }

    /// The function of argument `position` of command `index`, its names
    /// turned into ids; `None` (with the reason) when it cannot be.
    fn function(&mut self, index: usize, position: usize) -> Option<Embedded> {
        let statement = &self.view.statements[index];
        let argument = &statement.arguments[position];
        let Value::Expression { text, span } = &argument.value else {
            return None;
        };
        if text.text.trim().is_empty() {
            // View's "no function yet": the element is refused if no later
            // command gives one.
            self.wrong(
                format!(
                    "{} is empty, and no later command gives it: an element needs its function",
                    argument.keyword.to_ascii_lowercase()
                ),
                *span,
            );
            return None;
        }
        let tree = *self.trees.get(&(index, argument.keyword.clone()))?;
        let mut replacements = Vec::new();
        let mut unknown = Vec::new();
        visit(&tree.root, &mut |node| match &node.kind {
            NodeKind::Variable(name) => unknown.push((name.to_string(), node.span)),
            NodeKind::Call(_, arguments) => {
                for argument in arguments {
                    if let TreeArgument::Marker(Reference::Name(name), span)
                    | TreeArgument::Object(Reference::Name(name), span) = argument
                    {
                        replacements.push((*span, name.clone()));
                    }
                }
            }
            _ => {}
        });
        let mut ids = Vec::new();
        for (name, at) in unknown {
            match self.find(&name) {
                Some(Entity::Design(design)) => {
                    ids.push((at, format!("({:?})", self.designs[design])));
                }
                Some(Entity::Element(measure))
                    if self.elements[measure].statement == MEASURE
                        && !self.reading.contains(&measure) =>
                {
                    let function = self.elements[measure]
                        .given
                        .iter()
                        .find(|(keyword, _, _)| keyword == "FUNCTION")
                        .map(|&(_, command, position)| (command, position));
                    self.reading.push(measure);
                    let measured =
                        function.and_then(|(command, position)| self.function(command, position));
                    self.reading.pop();
                    match measured {
                        Some(measured) => ids.push((at, format!("({})", measured.text))),
                        None => self.wrong(
                            format!("{name}: the measure has no function mbexpr reads"),
                            text.file_span(at),
                        ),
                    }
                }
                _ => self.wrong(
                    format!(
                        "{name} is a View object mbexpr does not evaluate in a function (it reads design variables and function measures): give its value"
                    ),
                    text.file_span(at),
                ),
            }
        }
        for (at, name) in replacements {
            let id = match self.find(&name) {
                Some(Entity::Marker(marker)) => self.markers[marker].id,
                Some(Entity::Part(part)) => self.parts[part].id,
                Some(Entity::Element(element)) => self.elements[element].id,
                _ => None,
            };
            match id {
                Some(id) => ids.push((at, id.to_string())),
                None => self.wrong(
                    format!("{name} is no marker, part or element the file creates"),
                    text.file_span(at),
                ),
            }
        }
        ids.sort_by_key(|(at, _)| at.start);
        Some(text.replaced(&ids))
    }
}

/// A solid's volume and its first and second volume moments (`∫ r dV`,
/// `∫ r rᵀ dV`) about a point.
#[derive(Clone, Copy, Default)]
struct Moments {
    volume: f64,
    first: Vector3<f64>,
    second: Matrix3<f64>,
}

impl Moments {
    fn add(&mut self, other: &Moments) {
        self.volume += other.volume;
        self.first += other.first;
        self.second += other.second;
    }

    /// These moments (about `frame`'s origin, in its axes) about the
    /// ground's origin in its axes.
    fn moved(&self, frame: &Frame) -> Moments {
        let axes = frame.axes;
        let first = axes * self.first;
        let second = axes * self.second * axes.transpose();
        let origin = frame.origin;
        Moments {
            volume: self.volume,
            first: first + origin * self.volume,
            second: second
                + first * origin.transpose()
                + origin * first.transpose()
                + origin * origin.transpose() * self.volume,
        }
    }

    /// A box from the origin to the corner `d`.
    fn block(d: Vector3<f64>) -> Moments {
        let volume = (d.x * d.y * d.z).abs();
        let mut second = d * d.transpose() * (volume / 4.0);
        for axis in 0..3 {
            second[(axis, axis)] = volume * d[axis] * d[axis] / 3.0;
        }
        Moments {
            volume,
            first: d * (volume / 2.0),
            second,
        }
    }

    /// A frustum along z from the origin (radius `bottom`) to `length`
    /// (radius `top`): a cylinder when they are equal. Gauss–Legendre with
    /// three points is exact for the polynomials of degree 4 in z.
    fn frustum(length: f64, bottom: f64, top: f64) -> Moments {
        let nodes = [
            (-(0.6_f64.sqrt()), 5.0 / 9.0),
            (0.0, 8.0 / 9.0),
            (0.6_f64.sqrt(), 5.0 / 9.0),
        ];
        let mut moments = Moments::default();
        for (node, weight) in nodes {
            let t = 0.5 * (node + 1.0);
            let z = t * length;
            let radius = bottom + (top - bottom) * t;
            let dz = 0.5 * weight * length.abs();
            let area = PI * radius * radius;
            moments.volume += area * dz;
            moments.first.z += z * area * dz;
            let across = area * radius * radius / 4.0 * dz;
            moments.second[(0, 0)] += across;
            moments.second[(1, 1)] += across;
            moments.second[(2, 2)] += z * z * area * dz;
        }
        moments
    }

    /// An ellipsoid about the origin with semi-axes `a`, `b`, `c`.
    fn ellipsoid(a: f64, b: f64, c: f64) -> Moments {
        let volume = 4.0 / 3.0 * PI * (a * b * c).abs();
        Moments {
            volume,
            first: Vector3::zeros(),
            second: Matrix3::from_diagonal(&Vector3::new(a * a, b * b, c * c)) * (volume / 5.0),
        }
    }

    /// A torus about the z axis: its tube of radius `minor` around the
    /// circle of radius `major`.
    fn torus(major: f64, minor: f64) -> Moments {
        let volume = 2.0 * PI * PI * major * minor * minor;
        let across = volume * (major * major / 2.0 + 3.0 * minor * minor / 8.0);
        Moments {
            volume,
            first: Vector3::zeros(),
            second: Matrix3::from_diagonal(&Vector3::new(
                across,
                across,
                volume * minor * minor / 4.0,
            )),
        }
    }

    /// View's link: a bar from the origin along x of `length`, `width`
    /// across (y) with semicircular ends, and `depth` thick (z), centred on
    /// the xy plane.
    fn link(length: f64, width: f64, depth: f64) -> Moments {
        let radius = width / 2.0;
        let bar = length * width * depth;
        let half_disc = PI * radius * radius * depth / 2.0;
        // Each half disc's centroid lies 4r/3π beyond its end.
        let out = 4.0 * radius / (3.0 * PI);
        let xx = bar * length * length / 3.0
            + half_disc * radius * radius / 4.0
            + half_disc * (radius * radius / 4.0 + 2.0 * length * out + length * length);
        let yy = bar * width * width / 12.0 + 2.0 * half_disc * radius * radius / 4.0;
        let zz = (bar + 2.0 * half_disc) * depth * depth / 12.0;
        let volume = bar + 2.0 * half_disc;
        Moments {
            volume,
            first: Vector3::new(volume * length / 2.0, 0.0, 0.0),
            second: Matrix3::from_diagonal(&Vector3::new(xx, yy, zz)),
        }
    }
}

/// Whether an argument holds a View expression: a value in brackets
/// (`(20g)`, `(.model.DV_1)`, `(LOC_RELATIVE_TO({0, 0, 0}, .model.ground))`),
/// which View evaluates and mbexpr does not.
fn view_expression(argument: &Argument) -> bool {
    match &argument.value {
        Value::List(items) => items
            .iter()
            .any(|item| item.text.trim_start().starts_with('(')),
        Value::Flag | Value::Expression { .. } => false,
    }
}

fn new_statement(name: &str, id: Option<u64>, span: Span) -> Statement {
    Statement {
        name: name.into(),
        id,
        span,
        arguments: Vec::new(),
    }
}

fn list_argument(statement: &mut Statement, keyword: &str, texts: Vec<String>, span: Span) {
    statement.arguments.push(Argument {
        keyword: keyword.into(),
        keyword_span: span,
        span,
        value: Value::List(
            texts
                .into_iter()
                .map(|text| ValueItem {
                    text: text.into(),
                    span,
                })
                .collect(),
        ),
    });
}

fn numbers_argument(statement: &mut Statement, keyword: &str, values: &[f64], span: Span) {
    let texts = values.iter().map(|value| format!("{value:?}")).collect();
    list_argument(statement, keyword, texts, span);
}

fn ids_argument(statement: &mut Statement, keyword: &str, id: u64, span: Span) {
    list_argument(statement, keyword, vec![id.to_string()], span);
}

fn words_argument(statement: &mut Statement, keyword: &str, words: &[&str], span: Span) {
    let texts = words.iter().map(|word| word.to_string()).collect();
    list_argument(statement, keyword, texts, span);
}

fn flag_argument(statement: &mut Statement, keyword: &str, span: Span) {
    statement.arguments.push(Argument {
        keyword: keyword.into(),
        keyword_span: span,
        span,
        value: Value::Flag,
    });
}

/// `origin`, a point on the z axis and one on the x axis of `frame`.
fn place_arguments(statement: &mut Statement, keywords: [&str; 3], frame: &Frame, span: Span) {
    let origin = frame.origin;
    let points = [
        origin,
        origin + frame.axes.column(2),
        origin + frame.axes.column(0),
    ];
    for (keyword, point) in keywords.into_iter().zip(points) {
        numbers_argument(statement, keyword, &[point.x, point.y, point.z], span);
    }
}
