//! The View commands the reader knows: the element commands and the
//! solver statements they write, and the commands it passes over.

/// Commands that only draw, arrange or describe: passed over.
pub(super) const PASSED_OVER: [&str; 33] = [
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
    "COLORS",
    "FUNCTION",
    "INTERFACE",
    "EXECUTIVE_CONTROL SET",
    "OUTPUT_CONTROL SET",
];

/// Commands passed over with a note: they may matter, but not to a run
/// of the model as the file leaves it.
pub(super) const NOTED: [(&str, &str); 2] = [
    (
        "SIMULATION",
        "a simulation command other than a transient run: not carried out",
    ),
    ("FILE", "a file command: mbexpr reads this file alone"),
];

/// Shapes without volume: they add no mass.
pub(super) const WIRES: [&str; 10] = [
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
pub(super) enum Becomes {
    /// A marker's id.
    Marker(&'static str),
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
    /// A function expression that may be left empty (`evaluate = ""`, as
    /// View writes a sensor's when it has none): then nothing.
    OptionalFunction(&'static str),
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
    /// A joint's initial condition: of its rotation (else its
    /// translation), its velocity (else its displacement); a joint's IC,
    /// ICROT or ICTRAN.
    JointInitial {
        /// The rotation's, in the angle unit.
        rotation: bool,
        /// The velocity's.
        velocity: bool,
    },
    /// A word, the value of the keyword it is among those listed (View's
    /// word, the solver's).
    Named(&'static str, &'static [(&'static str, &'static str)]),
    /// `on` or `yes` gives the keyword with the value; `off` or `no`,
    /// nothing.
    SwitchTo(&'static str, &'static str),
    /// A load a joint's friction reads, `on` or `off`: one of INPUTS.
    Input(&'static str),
    /// Read elsewhere, or without effect on the motion.
    Nothing,
}

/// An element command: its words after the verb, the solver statement it
/// writes, the keyword a word of its own gives (a joint's type), and its
/// parameters.
pub(super) struct ElementKind {
    /// The command's words, `CREATE` or `MODIFY` taken out.
    pub(super) words: &'static str,
    /// The solver statement.
    pub(super) statement: &'static str,
    /// The keywords of the statement the command's words give.
    pub(super) flags: &'static [&'static str],
    /// The parameter that names the element.
    pub(super) name: &'static str,
    /// The other parameters, in groups.
    pub(super) parameters: &'static [&'static [(&'static str, Becomes)]],
}

pub(super) const TWO_MARKERS: [(&str, Becomes); 2] = [
    ("I_MARKER_NAME", Becomes::Marker("I")),
    ("J_MARKER_NAME", Becomes::Marker("J")),
];

/// A vector force's I marker, its J (a floating marker, or one made on a
/// part) and the marker its components are in.
const ON_FLOATING_J: [(&str, Becomes); 4] = [
    ("I_MARKER_NAME", Becomes::Marker("I")),
    ("J_FLOATING_MARKER_NAME", Becomes::Marker("JFLOAT")),
    ("J_PART_NAME", Becomes::FloatingOn("JFLOAT")),
    ("REF_MARKER_NAME", Becomes::Marker("RM")),
];

const FORCE_FUNCTIONS: [(&str, Becomes); 3] = [
    ("X_FORCE_FUNCTION", Becomes::Function("FX")),
    ("Y_FORCE_FUNCTION", Becomes::Function("FY")),
    ("Z_FORCE_FUNCTION", Becomes::Function("FZ")),
];

const TORQUE_FUNCTIONS: [(&str, Becomes); 3] = [
    ("X_TORQUE_FUNCTION", Becomes::Function("TX")),
    ("Y_TORQUE_FUNCTION", Becomes::Function("TY")),
    ("Z_TORQUE_FUNCTION", Becomes::Function("TZ")),
];

pub(super) const FREEDOM: &[(&str, &str)] =
    &[("TRANSLATIONAL", "TRANSLATION"), ("ROTATIONAL", "ROTATION")];

/// Joints by their View word and solver keyword.
pub(super) const JOINT_TYPES: [(&str, &str); 11] = [
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

/// Joint primitives by their View word and solver keyword (View writes
/// `parallel_axis` for the solver's PARALLEL_AXES).
pub(super) const PRIMITIVES: [(&str, &str); 7] = [
    ("ATPOINT", "ATPOINT"),
    ("INLINE", "INLINE"),
    ("INPLANE", "INPLANE"),
    ("ORIENTATION", "ORIENTATION"),
    ("PARALLEL_AXIS", "PARALLEL_AXES"),
    ("PARALLEL_AXES", "PARALLEL_AXES"),
    ("PERPENDICULAR", "PERPENDICULAR"),
];

pub(super) const JOINT_PARAMETERS: &[&[(&str, Becomes)]] = &[
    &TWO_MARKERS,
    &[
        ("DIAMETER_OF_PITCH", Becomes::Numbers("PD")),
        ("PITCH", Becomes::Numbers("PITCH")),
        ("FRICTION_ENABLED", Becomes::Nothing),
        (
            "TRANSLATIONAL_IC",
            Becomes::JointInitial {
                rotation: false,
                velocity: false,
            },
        ),
        (
            "VELOCITY_IC",
            Becomes::JointInitial {
                rotation: false,
                velocity: true,
            },
        ),
        (
            "ROTATIONAL_IC",
            Becomes::JointInitial {
                rotation: true,
                velocity: false,
            },
        ),
        (
            "ANGULAR_VELOCITY_IC",
            Becomes::JointInitial {
                rotation: true,
                velocity: true,
            },
        ),
    ],
];

/// A joint's friction: the FRICTION statement's numbers, words and inputs.
const FRICTION_PARAMETERS: [(&str, Becomes); 26] = [
    ("JOINT_NAME", Becomes::Object("JOINT")),
    (
        "YOKE",
        Becomes::Choice(&[("I_YOKE", "I_YOKE"), ("J_YOKE", "J_YOKE")]),
    ),
    (
        "FORMULATION",
        Becomes::Named(
            "FRICTION_MODEL",
            &[("ORIGINAL", "DEFAULT"), ("LUGRE", "LUGRE")],
        ),
    ),
    ("MU_STATIC", Becomes::Numbers("MU_STATIC")),
    ("MU_DYNAMIC", Becomes::Numbers("MU_DYNAMIC")),
    ("REACTION_ARM", Becomes::Numbers("REACTION_ARM")),
    ("FRICTION_ARM", Becomes::Numbers("FRICTION_ARM")),
    (
        "BENDING_REACTION_ARM",
        Becomes::Numbers("BENDING_REACTION_ARM"),
    ),
    ("INITIAL_OVERLAP", Becomes::Numbers("INITIAL_OVERLAP")),
    ("PIN_RADIUS", Becomes::Numbers("PIN_RADIUS")),
    ("BALL_RADIUS", Becomes::Numbers("BALL_RADIUS")),
    (
        "STICTION_TRANSITION_VELOCITY",
        Becomes::Numbers("STICTION_TRANSITION_VELOCITY"),
    ),
    (
        "TRANSITION_VELOCITY_COEFFICIENT",
        Becomes::Numbers("TRANSITION_VELOCITY_COEFFICIENT"),
    ),
    (
        "MAX_STICTION_DEFORMATION",
        Becomes::Numbers("MAX_STICTION_DEFORMATION"),
    ),
    (
        "FRICTION_FORCE_PRELOAD",
        Becomes::Numbers("FRICTION_FORCE_PRELOAD"),
    ),
    (
        "FRICTION_TORQUE_PRELOAD",
        Becomes::Numbers("FRICTION_TORQUE_PRELOAD"),
    ),
    ("MAX_FRICTION_FORCE", Becomes::Numbers("MAX_FRICTION_FORCE")),
    (
        "MAX_FRICTION_TORQUE",
        Becomes::Numbers("MAX_FRICTION_TORQUE"),
    ),
    ("OVERLAP_DELTA", Becomes::Word("OVERLAP_DELTA")),
    ("EFFECT", Becomes::Word("EFFECT")),
    (
        "BRISTLE_STIFFNESS_COEFFICIENT",
        Becomes::Numbers("STIFFNESS_COEFFICIENT"),
    ),
    (
        "DAMPING_COEFFICIENT",
        Becomes::Numbers("DAMPING_COEFFICIENT"),
    ),
    (
        "VISCOUS_FRICTION_COEFFICIENT",
        Becomes::Numbers("VISCOUS_COEFFICIENT"),
    ),
    (
        "INACTIVE_DURING_STATIC",
        Becomes::SwitchTo("INACTIVE", "STATIC"),
    ),
    ("PRELOAD", Becomes::Input("PRELOAD")),
    ("REACTION_FORCE", Becomes::Input("REACTION_FORCE")),
];

/// The loads a friction reads beside the preload and the reaction force.
const FRICTION_MOMENTS: [(&str, Becomes); 2] = [
    ("BENDING_MOMENT", Becomes::Input("BENDING_MOMENT")),
    ("TORSIONAL_MOMENT", Becomes::Input("TORSIONAL_MOMENT")),
];

/// The parameters of a measure of kinematics or loads (`pt2pt`, `point`,
/// `object`, `orient`, `angle`): read where a function reads the measure
/// ([`MEASURE`]).
const KINEMATIC_MEASURE: [(&str, Becomes); 16] = [
    ("FROM_POINT", Becomes::Nothing),
    ("TO_POINT", Becomes::Nothing),
    ("POINT", Becomes::Nothing),
    ("OBJECT", Becomes::Nothing),
    ("FROM_FIRST", Becomes::Nothing),
    ("TO_FRAME", Becomes::Nothing),
    ("FROM_FRAME", Becomes::Nothing),
    ("FIRST_POINT", Becomes::Nothing),
    ("MIDDLE_POINT", Becomes::Nothing),
    ("LAST_POINT", Becomes::Nothing),
    ("CHARACTERISTIC", Becomes::Nothing),
    ("COMPONENT", Becomes::Nothing),
    ("MOTION_RFRAME", Becomes::Nothing),
    ("COORDINATE_RFRAME", Becomes::Nothing),
    ("CREATE_MEASURE_DISPLAY", Becomes::Nothing),
    ("LEGEND", Becomes::Nothing),
];

pub(super) const ELEMENTS: [ElementKind; 26] = [
    ElementKind {
        words: "CONSTRAINT GENERAL_CONSTRAINT",
        statement: "GCON",
        flags: &[],
        name: "GENERAL_CONSTRAINT_NAME",
        parameters: &[&[
            ("I_MARKER_NAME", Becomes::Marker("I")),
            ("FUNCTION", Becomes::Function("FUNCTION")),
        ]],
    },
    ElementKind {
        words: "CONSTRAINT COMPLEX_JOINT GEAR",
        statement: "GEAR",
        flags: &[],
        name: "GEAR_NAME",
        parameters: &[&[
            ("JOINT_NAME", Becomes::Joints("JOINTS")),
            ("COMMON_VELOCITY_MARKER", Becomes::Marker("CV")),
        ]],
    },
    ElementKind {
        words: "MEASURE PT2PT",
        statement: MEASURE,
        flags: &["PT2PT"],
        name: "MEASURE_NAME",
        parameters: &[&KINEMATIC_MEASURE],
    },
    ElementKind {
        words: "MEASURE POINT",
        statement: MEASURE,
        flags: &["POINT"],
        name: "MEASURE_NAME",
        parameters: &[&KINEMATIC_MEASURE],
    },
    ElementKind {
        words: "MEASURE OBJECT",
        statement: MEASURE,
        flags: &["OBJECT"],
        name: "MEASURE_NAME",
        parameters: &[&KINEMATIC_MEASURE],
    },
    ElementKind {
        words: "MEASURE ORIENT",
        statement: MEASURE,
        flags: &["ORIENT"],
        name: "MEASURE_NAME",
        parameters: &[&KINEMATIC_MEASURE],
    },
    ElementKind {
        words: "MEASURE ANGLE",
        statement: MEASURE,
        flags: &["ANGLE"],
        name: "MEASURE_NAME",
        parameters: &[&KINEMATIC_MEASURE],
    },
    ElementKind {
        words: "FORCE ELEMENT_LIKE FRICTION",
        statement: "FRICTION",
        flags: &[],
        name: "FRICTION_NAME",
        parameters: &[&FRICTION_PARAMETERS, &FRICTION_MOMENTS],
    },
    ElementKind {
        words: "CONSTRAINT COMPLEX_JOINT COUPLER",
        statement: "COUPLER",
        flags: &[],
        name: "COUPLER_NAME",
        parameters: &[&[
            ("JOINT_NAME", Becomes::Joints("JOINTS")),
            ("TYPE_OF_FREEDOM", Becomes::Freedoms("TYPE")),
            ("MOTION_MULTIPLIERS", Becomes::Numbers("SCALES")),
        ]],
    },
    ElementKind {
        words: "DATA_ELEMENT SPLINE",
        statement: "SPLINE",
        flags: &[],
        name: "SPLINE_NAME",
        parameters: &[&[
            ("X", Becomes::Numbers("X")),
            ("Y", Becomes::Numbers("Y")),
            ("LINEAR_EXTRAPOLATE", Becomes::Switch("LINEAR_EXTRAPOLATE")),
            ("UNITS", Becomes::Nothing),
        ]],
    },
    // A function measure is its function: a function that names it reads
    // it in brackets; nothing is written for it.
    ElementKind {
        words: "MEASURE FUNCTION",
        statement: MEASURE,
        flags: &[],
        name: "MEASURE_NAME",
        parameters: &[&[
            ("FUNCTION", Becomes::Function("FUNCTION")),
            ("UNITS", Becomes::Nothing),
            ("CREATE_MEASURE_DISPLAY", Becomes::Nothing),
        ]],
    },
    ElementKind {
        words: "FORCE ELEMENT_LIKE BEAM",
        statement: "BEAM",
        flags: &[],
        name: "BEAM_NAME",
        parameters: &[
            &TWO_MARKERS,
            &[
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
        ],
    },
    ElementKind {
        words: "CONTACT",
        statement: "CONTACT",
        flags: &["IMPACT"],
        name: "CONTACT_NAME",
        parameters: &[&[
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
        ]],
    },
    ElementKind {
        words: "CONSTRAINT MOTION_GENERATOR",
        statement: "MOTION",
        flags: &[],
        name: "MOTION_NAME",
        parameters: &[
            &TWO_MARKERS,
            &[
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
        ],
    },
    ElementKind {
        words: "FORCE DIRECT SINGLE_COMPONENT_FORCE",
        statement: "SFORCE",
        flags: &[],
        name: "SINGLE_COMPONENT_FORCE_NAME",
        parameters: &[
            &TWO_MARKERS,
            &[
                ("TYPE_OF_FREEDOM", Becomes::Choice(FREEDOM)),
                ("ACTION_ONLY", Becomes::Switch("ACTIONONLY")),
                ("FUNCTION", Becomes::Function("FUNCTION")),
            ],
        ],
    },
    ElementKind {
        words: "FORCE ELEMENT_LIKE TRANSLATIONAL_SPRING_DAMPER",
        statement: "SPRINGDAMPER",
        flags: &["TRANSLATION"],
        name: "SPRING_DAMPER_NAME",
        parameters: &[
            &TWO_MARKERS,
            &[
                ("STIFFNESS", Becomes::Numbers("K")),
                ("DAMPING", Becomes::Numbers("C")),
                ("PRELOAD", Becomes::Numbers("FORCE")),
                ("DISPLACEMENT_AT_PRELOAD", Becomes::Numbers("LENGTH")),
            ],
        ],
    },
    ElementKind {
        words: "FORCE ELEMENT_LIKE ROTATIONAL_SPRING_DAMPER",
        statement: "SPRINGDAMPER",
        flags: &["ROTATION"],
        name: "SPRING_DAMPER_NAME",
        parameters: &[
            &TWO_MARKERS,
            &[
                ("STIFFNESS", Becomes::PerAngle("KT")),
                ("DAMPING", Becomes::PerAngle("CT")),
                ("PRELOAD", Becomes::Numbers("TORQUE")),
                ("DISPLACEMENT_AT_PRELOAD", Becomes::Angles("ANGLE")),
            ],
        ],
    },
    ElementKind {
        words: "FORCE ELEMENT_LIKE BUSHING",
        statement: "BUSHING",
        flags: &[],
        name: "BUSHING_NAME",
        parameters: &[
            &TWO_MARKERS,
            &[
                ("STIFFNESS", Becomes::Numbers("K")),
                ("DAMPING", Becomes::Numbers("C")),
                ("TSTIFFNESS", Becomes::PerAngle("KT")),
                ("TDAMPING", Becomes::PerAngle("CT")),
                ("FORCE_PRELOAD", Becomes::Numbers("FORCE")),
                ("TORQUE_PRELOAD", Becomes::Numbers("TORQUE")),
            ],
        ],
    },
    ElementKind {
        words: "FORCE DIRECT FORCE_VECTOR",
        statement: "VFORCE",
        flags: &[],
        name: "FORCE_VECTOR_NAME",
        parameters: &[&ON_FLOATING_J, &FORCE_FUNCTIONS],
    },
    ElementKind {
        words: "FORCE DIRECT TORQUE_VECTOR",
        statement: "VTORQUE",
        flags: &[],
        name: "TORQUE_VECTOR_NAME",
        parameters: &[&ON_FLOATING_J, &TORQUE_FUNCTIONS],
    },
    ElementKind {
        words: "FORCE DIRECT GENERAL_FORCE",
        statement: "GFORCE",
        flags: &[],
        name: "GENERAL_FORCE_NAME",
        parameters: &[&ON_FLOATING_J, &FORCE_FUNCTIONS, &TORQUE_FUNCTIONS],
    },
    ElementKind {
        words: "DATA_ELEMENT VARIABLE",
        statement: "VARIABLE",
        flags: &[],
        name: "VARIABLE_NAME",
        parameters: &[&[
            ("FUNCTION", Becomes::Function("FUNCTION")),
            ("INITIAL_CONDITION", Becomes::Numbers("IC")),
        ]],
    },
    ElementKind {
        words: "PART EQUATION DIFFERENTIAL_EQUATION",
        statement: "DIFF",
        flags: &[],
        name: "DIFFERENTIAL_EQUATION_NAME",
        parameters: &[&[
            ("FUNCTION", Becomes::Function("FUNCTION")),
            ("INITIAL_CONDITION", Becomes::Numbers("IC")),
            ("IMPLICIT", Becomes::Switch("IMPLICIT")),
            ("STATIC_HOLD", Becomes::Switch("STATIC_HOLD")),
        ]],
    },
    ElementKind {
        words: "OUTPUT_CONTROL REQUEST",
        statement: "REQUEST",
        flags: &[],
        name: "REQUEST_NAME",
        parameters: &[&[
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
            ("COMMENT", Becomes::Nothing),
        ]],
    },
    ElementKind {
        words: "EXECUTIVE_CONTROL SENSOR",
        statement: "SENSOR",
        flags: &[],
        name: "SENSOR_NAME",
        parameters: &[&[
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
            ("CODGEN", Becomes::Switch("CODGEN")),
            ("RESTART", Becomes::Switch("RESTART")),
            ("YYDUMP", Becomes::Switch("YYDUMP")),
            ("DT", Becomes::Numbers("DT")),
            ("STEPSIZE", Becomes::Numbers("STEPSIZE")),
            ("BISECTION", Becomes::Nothing),
            ("TIME_ERROR", Becomes::Nothing),
            ("EVALUATE", Becomes::OptionalFunction("EVALUATE")),
        ]],
    },
    ElementKind {
        words: "FORCE BODY GRAVITATIONAL",
        statement: "ACCGRAV",
        flags: &[],
        name: "GRAVITY_FIELD_NAME",
        parameters: &[&[
            ("X_COMPONENT_GRAVITY", Becomes::Numbers("IGRAV")),
            ("Y_COMPONENT_GRAVITY", Becomes::Numbers("JGRAV")),
            ("Z_COMPONENT_GRAVITY", Becomes::Numbers("KGRAV")),
        ]],
    },
];

/// The kind of a measure's element, which is not written: a function
/// reads its function (a function measure's) or the function of the
/// kinematics it measures.
pub(super) const MEASURE: &str = "MEASURE";

/// The joint and primitive commands: their kind by the last word.
pub(super) fn constraint_kind(words: &str) -> Option<(&'static str, &'static str)> {
    if let Some(kind) = words.strip_prefix("CONSTRAINT JOINT ") {
        return JOINT_TYPES
            .iter()
            .find(|(view, _)| *view == kind)
            .map(|&(_, solver)| ("JOINT", solver));
    }
    let kind = words.strip_prefix("CONSTRAINT PRIMITIVE_JOINT ")?;
    PRIMITIVES
        .iter()
        .find(|(view, _)| *view == kind)
        .map(|&(_, solver)| ("JPRIM", solver))
}

/// What parameter `keyword` of an element becomes, when it has one.
pub(super) fn becomes(parameters: &[&[(&'static str, Becomes)]], keyword: &str) -> Option<Becomes> {
    parameters
        .iter()
        .flat_map(|group| group.iter())
        .find(|(view, _)| *view == keyword)
        .map(|&(_, becomes)| becomes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::view_vocabulary::{self, Meaning};

    /// The commands and parameters the reading knows, checked against
    /// View's own: an abbreviation is read in full, so each must be View's
    /// name in full, or a command written as View writes it would be read
    /// as another.
    #[test]
    fn the_reading_knows_views_own_names() {
        let mut kinds: Vec<(String, Vec<&str>)> = ELEMENTS
            .iter()
            .map(|kind| {
                let parameters = std::iter::once(kind.name)
                    .chain(
                        kind.parameters
                            .iter()
                            .flat_map(|g| g.iter().map(|(p, _)| *p)),
                    )
                    .collect();
                (kind.words.to_string(), parameters)
            })
            .collect();
        let joint: Vec<&str> = std::iter::once("JOINT_NAME")
            .chain(
                JOINT_PARAMETERS
                    .iter()
                    .flat_map(|g| g.iter().map(|(p, _)| *p)),
            )
            .collect();
        for (view, _) in JOINT_TYPES {
            kinds.push((format!("CONSTRAINT JOINT {view}"), joint.clone()));
        }
        let primitive: Vec<&str> = std::iter::once("JPRIM_NAME")
            .chain(TWO_MARKERS.iter().map(|(p, _)| *p))
            .collect();
        for (view, _) in PRIMITIVES {
            kinds.push((
                format!("CONSTRAINT PRIMITIVE_JOINT {view}"),
                primitive.clone(),
            ));
        }
        let mut unknown = Vec::new();
        for (words, parameters) in &kinds {
            let mut written: Vec<&str> = words.split(' ').collect();
            written.insert(1.min(written.len()), "CREATE");
            let (full, command) = view_vocabulary::command(&written);
            assert_eq!(full.join(" "), written.join(" "), "{words}");
            let Some(command) = command else {
                continue;
            };
            for parameter in parameters {
                // A parameter View's command does not have is kept as
                // written; one it has must be read as itself.
                match command.parameter(parameter) {
                    Meaning::Unknown => {}
                    Meaning::One(name) if name.eq_ignore_ascii_case(parameter) => {}
                    other => unknown.push(format!("{words}: {parameter} is read as {other:?}")),
                }
            }
        }
        assert!(unknown.is_empty(), "{unknown:#?}");
    }

    /// The commands passed over, as View's names read them: a word
    /// written short (`color`) is read in full (`colors`).
    #[test]
    fn the_commands_passed_over_are_views_own() {
        for over in PASSED_OVER.iter().chain(NOTED.iter().map(|(over, _)| over)) {
            let written: Vec<&str> = over.split(' ').collect();
            let (full, _) = view_vocabulary::command(&written);
            assert_eq!(full.join(" "), *over);
        }
    }
}
