//! The vocabulary of the language: every function, constant and system
//! variable, with the number and kind of its arguments, a one-line meaning,
//! and the rules its constant arguments must obey (SPEC sections 2 to 4).
//!
//! Later stages match on [`Function`], never on strings.

use std::cmp::Ordering;
use std::fmt;

use crate::Shown;

/// What an argument position holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArgKind {
    /// Any expression.
    Value,
    /// A marker: an id (`0` is ground) or a name.
    Marker,
    /// A model statement: an id or a name (`VARVAL(3)`, `SFORCE(.model.SF_1, ...)`).
    Object,
    /// A constant whole number (a component code, a flag, an index).
    Flag,
}

/// How a function gets its value, which decides where it can be evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    /// FORTRAN intrinsics and `AINT`, `DIM`, `MAX`, ... (SPEC 3.1).
    Intrinsic,
    /// `STEP`, `STEP5`, `HAVSIN` (SPEC 3.2).
    Step,
    /// `IMPACT`, `BISTOP` (SPEC 3.3).
    Contact,
    /// `SHF`, `POLY`, `CHEBY`, `FORCOS`, `FORSIN`, `SWEEP` (SPEC 3.4).
    Series,
    /// Kinematic measures between markers (SPEC 4), evaluated in a scene.
    Measure,
    /// Data of a model's statements: variables, arrays, splines, states (SPEC 3.6, 3.7).
    ModelData,
    /// Results of a running solver: element forces, delays (SPEC 3.7).
    Solver,
    /// `USER(...)`: constants for a user subroutine.
    User,
}

/// A rule that constant (or evaluated) arguments must obey; indices are
/// argument positions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// Argument `.0` must be less than argument `.1`.
    Less(usize, usize),
    /// The argument must be greater than zero.
    Positive(usize),
    /// The argument must not be negative.
    NonNegative(usize),
    /// The argument must not be zero.
    NonZero(usize),
}

/// An argument rule broken by the given values.
#[derive(Clone, Debug, PartialEq)]
pub struct RuleViolation {
    /// The function whose rule was broken.
    pub function: Function,
    /// The rule.
    pub rule: Rule,
    /// The argument values the rule speaks of, in the rule's order.
    pub values: Vec<f64>,
}

impl Rule {
    /// The argument positions the rule speaks of.
    pub fn positions(self) -> Vec<usize> {
        match self {
            Rule::Less(a, b) => vec![a, b],
            Rule::Positive(a) | Rule::NonNegative(a) | Rule::NonZero(a) => vec![a],
        }
    }
}

impl fmt::Display for RuleViolation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = self.function.name();
        let param = |position: usize| self.function.param_name(position);
        let value = Shown(self.values[0]);
        match self.rule {
            Rule::Less(a, b) => write!(
                f,
                "{name}: {} ({value}) must be less than {} ({})",
                param(a),
                param(b),
                Shown(self.values[1])
            ),
            Rule::Positive(a) => write!(f, "{name}: {} ({value}) must be positive", param(a)),
            Rule::NonNegative(a) => {
                write!(f, "{name}: {} ({value}) must not be negative", param(a))
            }
            Rule::NonZero(a) => write!(f, "{name}: {} ({value}) must not be zero", param(a)),
        }
    }
}

/// Checks `function`'s argument rules against the values that are known
/// (`None` for an argument that is not a constant yet).
pub fn check_rules(function: Function, values: &[Option<f64>]) -> Result<(), RuleViolation> {
    check_rules_with(function, |position| values.get(position).copied().flatten())
}

/// [`check_rules`] with the argument values given by `value(position)`.
pub fn check_rules_with(
    function: Function,
    value: impl Fn(usize) -> Option<f64>,
) -> Result<(), RuleViolation> {
    for &rule in function.rules() {
        let broken = match rule {
            Rule::Less(a, b) => match (value(a), value(b)) {
                // Written so that a NaN breaks every rule.
                (Some(lower), Some(upper)) => {
                    (lower.partial_cmp(&upper) != Some(Ordering::Less)).then(|| vec![lower, upper])
                }
                _ => None,
            },
            Rule::Positive(a) => value(a)
                .filter(|v| v.partial_cmp(&0.0) != Some(Ordering::Greater))
                .map(|v| vec![v]),
            Rule::NonNegative(a) => value(a)
                .filter(|v| {
                    !matches!(
                        v.partial_cmp(&0.0),
                        Some(Ordering::Greater | Ordering::Equal)
                    )
                })
                .map(|v| vec![v]),
            Rule::NonZero(a) => value(a).filter(|v| *v == 0.0).map(|v| vec![v]),
        };
        if let Some(values) = broken {
            return Err(RuleViolation {
                function,
                rule,
                values,
            });
        }
    }
    Ok(())
}

/// The `max` of a function that takes any number of arguments.
pub const MANY: usize = usize::MAX;

/// The fixed facts of one function.
#[derive(Debug)]
pub struct Signature {
    /// The canonical (upper-case) name.
    pub name: &'static str,
    /// How its value is obtained.
    pub family: Family,
    /// Parameter names for messages and help; `...` marks a repeated tail.
    pub params: &'static [&'static str],
    /// Kinds of the leading arguments; later ones are `rest`.
    pub kinds: &'static [ArgKind],
    /// Kind of every argument past `kinds`.
    pub rest: ArgKind,
    /// Fewest arguments.
    pub min: usize,
    /// Most arguments.
    pub max: usize,
    /// One line: what the function computes.
    pub summary: &'static str,
}

impl Signature {
    /// The kind of argument at `position`.
    pub fn kind(&self, position: usize) -> ArgKind {
        self.kinds.get(position).copied().unwrap_or(self.rest)
    }
}

macro_rules! functions {
    ($( $variant:ident $name:literal $family:ident [$($kind:ident),*] $rest:ident
        $min:literal..=$max:tt ($($param:literal),*) $summary:literal; )*) => {
        /// Every function of the language (SPEC sections 3 and 4).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Function {
            $( #[doc = $summary] $variant, )*
        }

        impl Function {
            /// All functions, in catalog order.
            pub const ALL: &'static [Function] = &[$(Function::$variant),*];

            /// The function named `name`, in any case.
            pub fn lookup(name: &str) -> Option<Function> {
                // The name in capitals, on the stack (no name is longer).
                let mut buffer = [0u8; 32];
                let upper = buffer.get_mut(..name.len())?;
                upper.copy_from_slice(name.as_bytes());
                upper.make_ascii_uppercase();
                match std::str::from_utf8(upper).ok()? {
                    $($name => Some(Function::$variant),)*
                    _ => None,
                }
            }

            /// The function's signature.
            pub fn signature(self) -> &'static Signature {
                match self {
                    $(Function::$variant => &Signature {
                        name: $name,
                        family: Family::$family,
                        params: &[$($param),*],
                        kinds: &[$(ArgKind::$kind),*],
                        rest: ArgKind::$rest,
                        min: $min,
                        max: $max,
                        summary: $summary,
                    },)*
                }
            }
        }
    };
}

functions! {
    Abs "ABS" Intrinsic [] Value 1..=1 ("a") "absolute value";
    Sin "SIN" Intrinsic [] Value 1..=1 ("a") "sine of an angle in radians";
    Cos "COS" Intrinsic [] Value 1..=1 ("a") "cosine of an angle in radians";
    Tan "TAN" Intrinsic [] Value 1..=1 ("a") "tangent of an angle in radians";
    Asin "ASIN" Intrinsic [] Value 1..=1 ("a") "arc sine, for -1 <= a <= 1";
    Acos "ACOS" Intrinsic [] Value 1..=1 ("a") "arc cosine, for -1 <= a <= 1";
    Atan "ATAN" Intrinsic [] Value 1..=1 ("a") "arc tangent";
    Atan2 "ATAN2" Intrinsic [] Value 2..=2 ("y", "x") "angle of the point (x, y), in (-pi, pi] (-pi for y = -0 and x < 0, as C's atan2 that Adams calls); ATAN2(0, 0) = 0";
    Sinh "SINH" Intrinsic [] Value 1..=1 ("a") "hyperbolic sine";
    Cosh "COSH" Intrinsic [] Value 1..=1 ("a") "hyperbolic cosine";
    Tanh "TANH" Intrinsic [] Value 1..=1 ("a") "hyperbolic tangent";
    Exp "EXP" Intrinsic [] Value 1..=1 ("a") "e to the power a";
    Log "LOG" Intrinsic [] Value 1..=1 ("a") "natural logarithm, for a > 0";
    Log10 "LOG10" Intrinsic [] Value 1..=1 ("a") "base-10 logarithm, for a > 0";
    Sqrt "SQRT" Intrinsic [] Value 1..=1 ("a") "square root, for a >= 0";
    Aint "AINT" Intrinsic [] Value 1..=1 ("a") "truncation toward zero (derivative 0)";
    Anint "ANINT" Intrinsic [] Value 1..=1 ("a") "nearest whole number, halves away from zero (derivative 0)";
    Dim "DIM" Intrinsic [] Value 2..=2 ("a", "b") "positive difference: a - b if a > b, else 0";
    Max "MAX" Intrinsic [] Value 2..=MANY ("a", "b", "...") "largest of two or more values";
    Min "MIN" Intrinsic [] Value 2..=MANY ("a", "b", "...") "smallest of two or more values";
    Mod "MOD" Intrinsic [] Value 2..=2 ("a", "b") "remainder a - AINT(a/b)*b, with the sign of a";
    Sign "SIGN" Intrinsic [] Value 2..=2 ("a", "b") "ABS(a) if b >= 0, else -ABS(a)";
    Step "STEP" Step [] Value 5..=5 ("x", "x0", "h0", "x1", "h1") "cubic step from h0 at x0 to h1 at x1";
    Step5 "STEP5" Step [] Value 5..=5 ("x", "x0", "h0", "x1", "h1") "quintic step from h0 at x0 to h1 at x1 (continuous second derivative)";
    Havsin "HAVSIN" Step [] Value 5..=5 ("x", "x0", "h0", "x1", "h1") "haversine step from h0 at x0 to h1 at x1";
    Impact "IMPACT" Contact [] Value 7..=7 ("x", "x'", "x1", "k", "e", "cmax", "d") "one-sided contact force: pushes x back above x1";
    Bistop "BISTOP" Contact [] Value 8..=8 ("x", "x'", "x1", "x2", "k", "e", "cmax", "d") "two-sided gap contact force: free in [x1, x2], pushed back outside";
    Shf "SHF" Series [] Value 6..=6 ("x", "x0", "a", "w", "phi", "b") "simple harmonic a*sin(w*(x - x0) - phi) + b";
    Poly "POLY" Series [] Value 3..=33 ("x", "x0", "a0", "...") "polynomial sum a_j (x - x0)^j";
    Cheby "CHEBY" Series [] Value 3..=33 ("x", "x0", "a0", "...") "Chebyshev series sum a_j T_j(x - x0)";
    Forcos "FORCOS" Series [] Value 4..=34 ("x", "x0", "w", "a0", "...") "Fourier cosine series a0 + sum a_j cos(j w (x - x0))";
    Forsin "FORSIN" Series [] Value 4..=34 ("x", "x0", "w", "a0", "...") "Fourier sine series a0 + sum a_j sin(j w (x - x0))";
    Sweep "SWEEP" Series [] Value 7..=7 ("x", "a", "x0", "f0", "x1", "f1", "dx") "sine of amplitude a, frequency rising from f0 at x0 to f1 at x1, faded in over dx";
    Dx "DX" Measure [] Marker 1..=3 ("i", "j", "k") "x distance from marker j to i, along x of k";
    Dy "DY" Measure [] Marker 1..=3 ("i", "j", "k") "y distance from marker j to i, along y of k";
    Dz "DZ" Measure [] Marker 1..=3 ("i", "j", "k") "z distance from marker j to i, along z of k";
    Dm "DM" Measure [] Marker 1..=2 ("i", "j") "distance between markers i and j";
    Vx "VX" Measure [] Marker 1..=4 ("i", "j", "k", "l") "x velocity of i relative to j, derivative in frame l, along x of k";
    Vy "VY" Measure [] Marker 1..=4 ("i", "j", "k", "l") "y velocity of i relative to j, derivative in frame l, along y of k";
    Vz "VZ" Measure [] Marker 1..=4 ("i", "j", "k", "l") "z velocity of i relative to j, derivative in frame l, along z of k";
    Vm "VM" Measure [] Marker 1..=3 ("i", "j", "l") "magnitude of the velocity of i relative to j in frame l";
    Vr "VR" Measure [] Marker 1..=3 ("i", "j", "l") "radial velocity d(DM)/dt, positive when separating";
    Accx "ACCX" Measure [] Marker 1..=4 ("i", "j", "k", "l") "x acceleration of i relative to j, derivatives in l, along x of k";
    Accy "ACCY" Measure [] Marker 1..=4 ("i", "j", "k", "l") "y acceleration of i relative to j, derivatives in l, along y of k";
    Accz "ACCZ" Measure [] Marker 1..=4 ("i", "j", "k", "l") "z acceleration of i relative to j, derivatives in l, along z of k";
    Accm "ACCM" Measure [] Marker 1..=3 ("i", "j", "l") "magnitude of the acceleration of i relative to j in frame l";
    Wx "WX" Measure [] Marker 1..=3 ("i", "j", "k") "x angular velocity of i relative to j, along x of k";
    Wy "WY" Measure [] Marker 1..=3 ("i", "j", "k") "y angular velocity of i relative to j, along y of k";
    Wz "WZ" Measure [] Marker 1..=3 ("i", "j", "k") "z angular velocity of i relative to j, along z of k";
    Wm "WM" Measure [] Marker 1..=2 ("i", "j") "magnitude of the angular velocity of i relative to j";
    Wdtx "WDTX" Measure [] Marker 1..=4 ("i", "j", "k", "l") "x angular acceleration of i relative to j, derivative in l, along x of k";
    Wdty "WDTY" Measure [] Marker 1..=4 ("i", "j", "k", "l") "y angular acceleration of i relative to j, derivative in l, along y of k";
    Wdtz "WDTZ" Measure [] Marker 1..=4 ("i", "j", "k", "l") "z angular acceleration of i relative to j, derivative in l, along z of k";
    Wdtm "WDTM" Measure [] Marker 1..=3 ("i", "j", "l") "magnitude of the angular acceleration of i relative to j in frame l";
    Ax "AX" Measure [] Marker 1..=2 ("i", "j") "rotation of i about the x axis of j: i's z axis in j's y-z plane, ATAN2(-zi.yj, zi.zj), continuous over a run";
    Ay "AY" Measure [] Marker 1..=2 ("i", "j") "rotation of i about the y axis of j: i's z axis in j's z-x plane, ATAN2(zi.xj, zi.zj), continuous over a run";
    Az "AZ" Measure [] Marker 1..=2 ("i", "j") "rotation of i about the z axis of j: i's x axis in j's x-y plane, ATAN2(xi.yj, xi.xj), continuous over a run";
    Psi "PSI" Measure [] Marker 1..=2 ("i", "j") "first body-fixed 3-1-3 Euler angle of i relative to j";
    Theta "THETA" Measure [] Marker 1..=2 ("i", "j") "second body-fixed 3-1-3 Euler angle of i relative to j";
    Phi "PHI" Measure [] Marker 1..=2 ("i", "j") "third body-fixed 3-1-3 Euler angle of i relative to j";
    Yaw "YAW" Measure [] Marker 1..=2 ("i", "j") "first body-fixed 3-2-1 angle of i relative to j";
    Pitch "PITCH" Measure [] Marker 1..=2 ("i", "j") "negative second body-fixed 3-2-1 angle of i relative to j";
    Roll "ROLL" Measure [] Marker 1..=2 ("i", "j") "third body-fixed 3-2-1 angle of i relative to j";
    Incang "INCANG" Measure [] Marker 3..=4 ("i", "j", "k", "l") "included angle between the lines j-i and k-l (or j-k), about their normal as the model is drawn";
    Orient "ORIENT" Measure [Flag, Flag, Marker, Marker] Marker 3..=4 ("type", "component", "i", "j") "a component of the orientation of i relative to j: Euler angles of the body-fixed (1-12) or space-fixed (13-24) sequences 123 231 312 132 213 321 121 131 212 232 313 323, Euler parameters (27), Rodriguez parameters (28), direction cosines (29, by columns)";
    Fx "FX" Solver [] Marker 1..=3 ("i", "j", "k") "x force between markers i and j, along x of k";
    Fy "FY" Solver [] Marker 1..=3 ("i", "j", "k") "y force between markers i and j, along y of k";
    Fz "FZ" Solver [] Marker 1..=3 ("i", "j", "k") "z force between markers i and j, along z of k";
    Fm "FM" Solver [] Marker 1..=2 ("i", "j") "magnitude of the force between markers i and j";
    Tx "TX" Solver [] Marker 1..=3 ("i", "j", "k") "x torque between markers i and j, along x of k";
    Ty "TY" Solver [] Marker 1..=3 ("i", "j", "k") "y torque between markers i and j, along y of k";
    Tz "TZ" Solver [] Marker 1..=3 ("i", "j", "k") "z torque between markers i and j, along z of k";
    Tm "TM" Solver [] Marker 1..=2 ("i", "j") "magnitude of the torque between markers i and j";
    Sforce "SFORCE" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a force component of SFORCE id";
    Gforce "GFORCE" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a force component of GFORCE id";
    Vforce "VFORCE" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a force component of VFORCE id";
    Vtorq "VTORQ" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a torque component of VTORQUE id";
    Joint "JOINT" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a reaction component of JOINT id";
    Jprim "JPRIM" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a reaction component of JPRIM id";
    Motion "MOTION" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a reaction component of MOTION id";
    Beam "BEAM" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a force component of BEAM id";
    Bush "BUSH" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a force component of BUSHING id";
    Field "FIELD" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a force component of FIELD id";
    Nforce "NFORCE" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "at_marker", "comp", "rm") "a force component of NFORCE id at marker at_marker (one of its I markers, or its J)";
    Contact "CONTACT" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a force component of CONTACT id";
    Spdp "SPDP" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a force component of SPRINGDAMPER id";
    Ptcv "PTCV" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a reaction component of point-to-curve constraint id";
    Cvcv "CVCV" Solver [Object, Flag, Flag, Marker] Marker 4..=4 ("id", "jflag", "comp", "rm") "a reaction component of curve-to-curve constraint id";
    Delay "DELAY" Solver [Value, Value, Value, Flag] Flag 3..=4 ("e", "delay", "e_history", "id") "value e had a time `delay` ago in a run (a negative delay is 0); before time 0, e_history (a constant or a function of TIME) at that time; id, an ARRAY of Adams' interpolation settings, 0 or left out";
    Varval "VARVAL" ModelData [Object] Object 1..=1 ("id") "value of VARIABLE id";
    Aryval "ARYVAL" ModelData [Object, Flag] Flag 2..=2 ("id", "i") "entry i of ARRAY id";
    Dif "DIF" ModelData [Object] Object 1..=1 ("id") "value of the differential state DIFF id";
    Dif1 "DIF1" ModelData [Object] Object 1..=1 ("id") "time derivative of the differential state DIFF id";
    Pinval "PINVAL" ModelData [Object, Flag] Flag 2..=2 ("id", "i") "entry i of the inputs of PINPUT id";
    Pouval "POUVAL" ModelData [Object, Flag] Flag 2..=2 ("id", "i") "entry i of the outputs of POUTPUT id";
    Senval "SENVAL" ModelData [Object] Object 1..=1 ("id") "value of SENSOR id";
    Friction "FRICTION" ModelData [Object, Flag] Flag 2..=2 ("id", "index") "output index of FRICTION id, along or about its joint's J axes: 1-6 the force and torque on I, 7-12 the coefficients, 13 the static coefficient (0 when sliding), 14-19 the joint's velocities, 20-22 the creep";
    Akispl "AKISPL" ModelData [Value, Value, Object, Flag] Flag 3..=4 ("x", "z", "id", "iord") "Akima spline of SPLINE id at x (z for a surface), or its derivative of order iord";
    Cubspl "CUBSPL" ModelData [Value, Value, Object, Flag] Flag 3..=4 ("x", "z", "id", "iord") "cubic spline of SPLINE id at x (z for a surface), or its derivative of order iord";
    Curve "CURVE" ModelData [Value, Flag, Flag, Object] Object 4..=4 ("alpha", "iord", "comp", "id") "a coordinate of CURVE id at parameter alpha";
    Interp "INTERP" ModelData [Value, Flag, Object, Flag] Flag 3..=4 ("x", "method", "id", "iord") "interpolated value of a data table at x";
    User "USER" User [] Value 1..=30 ("r1", "...") "constants passed to a user subroutine";
}

impl Function {
    /// The canonical (upper-case) name.
    pub fn name(self) -> &'static str {
        self.signature().name
    }

    /// How the function gets its value.
    pub fn family(self) -> Family {
        self.signature().family
    }

    /// The name of parameter `position` (`a3` for positions in a repeated tail).
    pub fn param_name(self, position: usize) -> String {
        let params = self.signature().params;
        match params.get(position) {
            Some(&"...") | None => format!("argument {}", position + 1),
            Some(name) => (*name).to_string(),
        }
    }

    /// `STEP(x, x0, h0, x1, h1)`, for help and messages.
    pub fn usage(self) -> String {
        format!("{}({})", self.name(), self.signature().params.join(", "))
    }

    /// The rules its arguments must obey (SPEC 3.1 to 3.4).
    pub fn rules(self) -> &'static [Rule] {
        use Rule::{Less, NonNegative, NonZero, Positive};
        match self {
            Function::Mod => &[NonZero(1)],
            Function::Step | Function::Step5 | Function::Havsin => &[Less(1, 3)],
            Function::Impact => &[NonNegative(3), Positive(4), NonNegative(5), Positive(6)],
            Function::Bistop => &[
                Less(2, 3),
                NonNegative(4),
                Positive(5),
                NonNegative(6),
                Positive(7),
            ],
            Function::Sweep => &[Less(2, 4), Positive(6)],
            _ => &[],
        }
    }
}

impl fmt::Display for Function {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Named constants (SPEC section 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Constant {
    /// pi
    Pi,
    /// pi/180: degrees to radians
    Dtor,
    /// 180/pi: radians to degrees
    Rtod,
}

impl Constant {
    /// All constants.
    pub const ALL: &'static [Constant] = &[Constant::Pi, Constant::Dtor, Constant::Rtod];

    /// The canonical name.
    pub fn name(self) -> &'static str {
        match self {
            Constant::Pi => "PI",
            Constant::Dtor => "DTOR",
            Constant::Rtod => "RTOD",
        }
    }

    /// The value.
    pub fn value(self) -> f64 {
        match self {
            Constant::Pi => std::f64::consts::PI,
            Constant::Dtor => std::f64::consts::PI / 180.0,
            Constant::Rtod => 180.0 / std::f64::consts::PI,
        }
    }

    /// The constant named `name`, in any case.
    pub fn lookup(name: &str) -> Option<Constant> {
        Constant::ALL
            .iter()
            .copied()
            .find(|constant| constant.name().eq_ignore_ascii_case(name))
    }
}

/// System variables set by the host (SPEC section 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SystemVariable {
    /// The current time; a variable like any other.
    Time,
    /// The analysis mode; 4 (dynamics) unless the host sets it.
    Mode,
}

impl SystemVariable {
    /// The value of MODE when the host does not set it (dynamics).
    pub const DEFAULT_MODE: f64 = 4.0;

    /// Why `value` cannot be the analysis mode (SPEC 2), or `None` when it can.
    pub fn mode_error(value: f64) -> Option<String> {
        const MODES: [f64; 6] = [1.0, 3.0, 4.0, 5.0, 6.0, 7.0];
        (!MODES.contains(&value)).then(|| {
            format!(
                "MODE is 1 (kinematics), 3 (initial conditions), 4 (dynamics), 5 (statics), 6 (quasi-statics) or 7 (linear), not {value}"
            )
        })
    }

    /// The canonical name.
    pub fn name(self) -> &'static str {
        match self {
            SystemVariable::Time => "TIME",
            SystemVariable::Mode => "MODE",
        }
    }

    /// The system variable named `name`, in any case.
    pub fn lookup(name: &str) -> Option<SystemVariable> {
        [SystemVariable::Time, SystemVariable::Mode]
            .into_iter()
            .find(|variable| variable.name().eq_ignore_ascii_case(name))
    }
}

/// Names close to `name` among `candidates`, best first: the "did you mean"
/// of every unknown-name message.
pub fn closest<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Vec<&'a str> {
    let name = name.to_uppercase();
    let mut scored: Vec<(f64, &str)> = candidates
        .into_iter()
        .map(|candidate| {
            let upper = candidate.to_uppercase();
            let mut score = strsim::jaro_winkler(&name, &upper);
            // Short names score low however alike: one edit apart is close.
            if name.len() >= 2 && strsim::levenshtein(&name, &upper) == 1 {
                score = score.max(0.8);
            }
            (score, candidate)
        })
        .filter(|(score, _)| *score >= 0.8)
        .collect();
    scored.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(b.1)));
    scored.dedup_by(|a, b| a.1.eq_ignore_ascii_case(b.1));
    scored.into_iter().take(3).map(|(_, name)| name).collect()
}

/// " (did you mean A, B or C?)" or nothing.
pub fn did_you_mean(suggestions: &[&str]) -> String {
    match suggestions {
        [] => String::new(),
        [one] => format!(" (did you mean {one}?)"),
        [init @ .., last] => format!(" (did you mean {} or {last}?)", init.join(", ")),
    }
}
