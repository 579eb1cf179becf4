//! Results of a running solver as program inputs: a call such as
//! `JOINT(1, 0, 4, 0)` compiled by [`super::compile_run_outputs`] becomes
//! the input of that name, whose value the simulation gives at each
//! evaluation; so does a measure of accelerations, `ACCY(3, 1)`
//! ([`MarkerCall`]).

use crate::catalog::Function;
use crate::check::{Argument, Reference};
use crate::scene::{Scene, Target};

/// A reaction or a force a running solver computes: `JOINT`, `JPRIM` or
/// `MOTION`, `SFORCE`, `VFORCE`, `VTORQ`, `GFORCE`, `BUSH`, `BEAM` or
/// `FIELD`, with its
/// statement id, `jflag` (0: on the I marker, 1: on the J marker),
/// component (1 `|F|`, 2–4 `Fx Fy Fz`, 5 `|T|`, 6–8 `Tx Ty Tz`) and the
/// marker `rm` whose axes the components are along.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct SolverCall {
    /// `JOINT`, `JPRIM`, `MOTION` or a force element's function.
    pub function: Function,
    /// The statement id.
    pub id: u64,
    /// 0: the reaction on the I marker; 1: on the J marker (NFORCE: the
    /// id of the marker, one of its I markers or its J).
    pub jflag: i64,
    /// The component, 1 to 8.
    pub component: i64,
    /// The marker whose axes the components are along, as written.
    pub rm: Reference,
}

impl SolverCall {
    /// The functions whose calls become inputs.
    pub const FUNCTIONS: [Function; 15] = [
        Function::Joint,
        Function::Jprim,
        Function::Ptcv,
        Function::Cvcv,
        Function::Motion,
        Function::Sforce,
        Function::Vforce,
        Function::Vtorq,
        Function::Gforce,
        Function::Bush,
        Function::Beam,
        Function::Field,
        Function::Nforce,
        Function::Contact,
        Function::Spdp,
    ];

    /// The call of `function` with `args`, when it is one of
    /// [`SolverCall::FUNCTIONS`] with an id, two flags and a marker.
    pub(crate) fn of(function: Function, args: &[Argument]) -> Option<SolverCall> {
        if !SolverCall::FUNCTIONS.contains(&function) {
            return None;
        }
        match args {
            [
                Argument::Object(Reference::Id(id), _),
                Argument::Flag(jflag, _),
                Argument::Flag(component, _),
                Argument::Marker(rm, _),
            ] => Some(SolverCall {
                function,
                id: *id,
                jflag: *jflag,
                component: *component,
                rm: rm.clone(),
            }),
            _ => None,
        }
    }

    /// The input's name: the call as written, `JOINT(1,0,4,0)` (no name of
    /// the language has a parenthesis).
    pub fn input_name(&self) -> String {
        format!(
            "{}({},{},{},{})",
            self.function.name(),
            self.id,
            self.jflag,
            self.component,
            self.rm
        )
    }

    /// The call an input named by [`SolverCall::input_name`] stands for.
    pub fn parse(name: &str) -> Option<SolverCall> {
        let (function, rest) = name.split_once('(')?;
        let function = Function::lookup(function)?;
        if !SolverCall::FUNCTIONS.contains(&function) {
            return None;
        }
        let mut parts = rest.strip_suffix(')')?.split(',');
        let id = parts.next()?.parse().ok()?;
        let jflag = parts.next()?.parse().ok()?;
        let component = parts.next()?.parse().ok()?;
        let rm = parts.next()?;
        let rm = rm
            .parse()
            .map_or_else(|_| Reference::Name(rm.to_string()), Reference::Id);
        parts.next().is_none().then_some(SolverCall {
            function,
            id,
            jflag,
            component,
            rm,
        })
    }

    /// The marker `rm` in `scene`.
    pub fn rm_in(&self, scene: &Scene) -> Option<Target> {
        scene.find_marker(&self.rm).ok()
    }
}

/// A function of markers whose value a running solver gives: a measure of
/// the bodies' accelerations, `ACCX` ... `WDTM` (from the right-hand side,
/// after the joints' solve, which no scene of a model holds), or the net
/// force between markers, `FX` ... `TM`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct MarkerCall {
    /// One of [`MarkerCall::FUNCTIONS`] or [`MarkerCall::NET_FORCES`].
    pub function: Function,
    /// The markers `i, j, k, l` as written, as many as the signature has;
    /// an omitted one is `0` (ground).
    pub markers: Vec<Reference>,
}

impl MarkerCall {
    /// The measures of accelerations whose calls become inputs.
    pub const FUNCTIONS: [Function; 8] = [
        Function::Accx,
        Function::Accy,
        Function::Accz,
        Function::Accm,
        Function::Wdtx,
        Function::Wdty,
        Function::Wdtz,
        Function::Wdtm,
    ];

    /// The net forces between markers whose calls become inputs.
    pub const NET_FORCES: [Function; 8] = [
        Function::Fx,
        Function::Fy,
        Function::Fz,
        Function::Fm,
        Function::Tx,
        Function::Ty,
        Function::Tz,
        Function::Tm,
    ];

    /// The call of `function` with marker arguments `args`, every marker
    /// of its signature (an omitted one `0`).
    pub(crate) fn of(function: Function, args: &[Argument]) -> MarkerCall {
        let markers = (0..function.signature().max)
            .map(|position| match args.get(position) {
                Some(Argument::Marker(reference, _)) => reference.clone(),
                _ => Reference::Id(0),
            })
            .collect();
        MarkerCall { function, markers }
    }

    /// The input's name: the call with every marker, `ACCY(3,1,0,0)`.
    pub fn input_name(&self) -> String {
        let markers: Vec<String> = self.markers.iter().map(ToString::to_string).collect();
        format!("{}({})", self.function.name(), markers.join(","))
    }

    /// The markers in `scene`, or the first one it does not have.
    pub fn markers_in(&self, scene: &Scene) -> Result<Vec<Target>, String> {
        self.markers
            .iter()
            .map(|marker| {
                scene
                    .find_marker(marker)
                    .map_err(|_| format!("the model has no marker {marker}"))
            })
            .collect()
    }
}

/// A value a running solver gives a program as an input.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum RunCall {
    /// A reaction or a force element's force.
    Reaction(SolverCall),
    /// A measure of accelerations.
    Acceleration(MarkerCall),
    /// A net force between markers.
    NetForce(MarkerCall),
    /// `DIF1(id)` of an implicit DIFF: the time derivative that makes its
    /// FUNCTION zero, which the solver finds.
    ImplicitRate(u64),
}

impl RunCall {
    /// The input's name (no name of the language has a parenthesis).
    pub fn input_name(&self) -> String {
        match self {
            RunCall::Reaction(call) => call.input_name(),
            RunCall::Acceleration(call) | RunCall::NetForce(call) => call.input_name(),
            RunCall::ImplicitRate(id) => crate::scene::diff_rate_input(*id),
        }
    }

    /// The call an input named by [`RunCall::input_name`] stands for.
    pub fn parse(name: &str) -> Option<RunCall> {
        if let Some(call) = SolverCall::parse(name) {
            return Some(RunCall::Reaction(call));
        }
        if let Some(id) = crate::scene::parse_diff_rate_input(name) {
            return Some(RunCall::ImplicitRate(id));
        }
        let (function, rest) = name.split_once('(')?;
        let function = Function::lookup(function)?;
        let net_force = MarkerCall::NET_FORCES.contains(&function);
        if !net_force && !MarkerCall::FUNCTIONS.contains(&function) {
            return None;
        }
        let markers = rest
            .strip_suffix(')')?
            .split(',')
            .map(|marker| {
                marker
                    .parse()
                    .map_or_else(|_| Reference::Name(marker.to_string()), Reference::Id)
            })
            .collect();
        let call = MarkerCall { function, markers };
        Some(if net_force {
            RunCall::NetForce(call)
        } else {
            RunCall::Acceleration(call)
        })
    }
}
