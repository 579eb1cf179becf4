//! The displacements the motions impose, with their first two time
//! derivatives (from dual numbers seeded in time). A VELOCITY or
//! ACCELERATION motion's displacement is its FUNCTION integrated from time
//! 0 by adaptive quadrature (the FUNCTION depends on time only, so its
//! integral needs no state of the run), to rounding error, each call
//! going on from the integrals taken at an earlier time.

use std::sync::Mutex;

use num_dual::Dual2Vec;

use super::general::GeneralConstraints;
use super::quadrature::integrate;
use crate::compile::{Program, SiteKind, compile_outputs};
use crate::eval::{EvalError, OutputError};
use crate::laws::branch::Code;
use crate::number::Directional;
use crate::simulate::Model;
use crate::simulate::model::Given;

/// A motion's displacement at a time, and its first two derivatives.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Drive {
    pub(crate) value: f64,
    pub(crate) rate: f64,
    pub(crate) acceleration: f64,
}

type TimeDual = Dual2Vec<f64, nalgebra::Const<1>>;

/// What the motions and the general constraints impose at one time: each
/// motion's displacement and its derivatives, and the time the GCONs'
/// FUNCTIONs are evaluated at.
pub(crate) struct Imposed<'d> {
    /// Each motion's displacement: those on joints, then those between
    /// markers.
    pub(crate) drives: Vec<Drive>,
    /// The time.
    pub(crate) time: f64,
    /// The general constraints, compiled.
    pub(crate) general: &'d GeneralConstraints,
    /// For each joint, the pieces of its curves a PTCV or a CVCV is held
    /// on within a step (empty, or `None` for a curve, where each takes
    /// the piece of its point of contact).
    pub(crate) pieces: Vec<Pieces>,
}

impl Imposed<'_> {
    /// The pieces joint `joint`'s curves are held on, where they are.
    pub(crate) fn pieces(&self, joint: usize) -> Pieces {
        self.pieces.get(joint).copied().unwrap_or_default()
    }
}

/// The pieces a joint's curves are held on within a step, by
/// [`CurveSite::side`]: a PTCV's curve first, a CVCV's ICURVE then its
/// JCURVE (`None`: the piece of the point of contact).
pub(crate) type Pieces = [Option<usize>; 2];

/// A curve whose point of contact a run holds on one piece within a step,
/// so that it crosses its knots (where the curve's third derivative
/// jumps) as located switches: a PTCV's curve, or one of a CVCV's two.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct CurveSite {
    /// The joint, by its index among the model's joints.
    pub(crate) joint: usize,
    /// 0 for a PTCV's curve and a CVCV's ICURVE, 1 for a CVCV's JCURVE.
    pub(crate) side: usize,
}

/// The motions' FUNCTIONs compiled together, to be evaluated in time, and
/// the general constraints' FUNCTIONs.
pub(crate) struct Drives {
    program: Option<Program>,
    /// Each input's value: `None` for `TIME`, a constant otherwise.
    inputs: Vec<Option<f64>>,
    /// What each FUNCTION gives.
    givens: Vec<Given>,
    /// Integrals already taken: at increasing times `t`, `∫₀ᵗ f` then
    /// `∫₀ᵗ s·f(s) ds` of every FUNCTION, so that a call integrates only
    /// from the last one before its time (the latest [`CHECKPOINTS`]).
    checkpoints: Mutex<Vec<(f64, Vec<f64>)>>,
    /// The GCONs' FUNCTIONs.
    general: GeneralConstraints,
    /// For each piecewise site of `program`, the site of the forces'
    /// program that computes the same call ([`Drives::held_by`]): within a
    /// step a motion stays on the branch its FUNCTION holds there.
    held_sites: Vec<Option<usize>>,
    /// The first of the curves' sites among the held sites (after the
    /// forces' program's and the contacts'), one for each of
    /// `curve_sites` in order, when the drives are held on a program.
    first_curve_site: Option<usize>,
    /// The curves of the PTCVs and CVCVs.
    curve_sites: Vec<CurveSite>,
}

/// The curves of `model`'s PTCVs (one each) and CVCVs (two each) in the
/// order of the joints: each has a site after the forces' program's and
/// the contacts', in this order.
pub(crate) fn curve_sites(model: &Model) -> Vec<CurveSite> {
    model
        .joints
        .iter()
        .enumerate()
        .flat_map(|(joint, kind)| {
            let sides = if kind.curve.is_some() {
                1
            } else if kind.pair.is_some() {
                2
            } else {
                0
            };
            (0..sides).map(move |side| CurveSite { joint, side })
        })
        .collect()
}

/// How many integrals [`Drives`] keeps (a run's calls go back at most a
/// step or so; one before the oldest integrates from time 0).
const CHECKPOINTS: usize = 64;

impl Drives {
    /// The drives of `model`'s motions (none without motions). The
    /// FUNCTIONs have compiled in the model's program already.
    pub(crate) fn new(model: &Model) -> Drives {
        Drives::built(model, None)
    }

    /// The drives of `model`'s motions, held within a step on the branches
    /// of `forces`, the forces' program, which computes the expressions
    /// `computed` (the motions' FUNCTIONs among them, so that their
    /// switches are located as events): a step that ends before a STEP's
    /// start sees the motion continue smoothly, as the forces do, and the
    /// switch is located after it.
    pub(crate) fn held_by(model: &Model, forces: &Program, computed: &[usize]) -> Drives {
        Drives::built(model, Some((forces, computed)))
    }

    fn built(model: &Model, forces: Option<(&Program, &[usize])>) -> Drives {
        let trees: Vec<&crate::Checked> = model
            .motion_functions()
            .map(|function| &model.expressions[function].checked)
            .collect();
        let mut names = vec!["TIME".to_string()];
        names.extend(model.scene.variables.iter().map(|(name, _)| name.clone()));
        let program = (!trees.is_empty())
            .then(|| compile_outputs(&trees, &names, Some(&model.scene)).ok())
            .flatten();
        let inputs = program.as_ref().map_or_else(Vec::new, |program| {
            program
                .inputs()
                .iter()
                .map(|name| {
                    (!name.eq_ignore_ascii_case("TIME"))
                        .then(|| model.scene.value_of(name).unwrap_or(0.0))
                })
                .collect()
        });
        let held_sites = match (&program, forces) {
            (Some(program), Some((forces, computed))) => site_map(model, program, forces, computed),
            _ => Vec::new(),
        };
        let contacts = model
            .forces
            .iter()
            .filter(|force| matches!(force, crate::simulate::Force::Contact(_)))
            .count();
        Drives {
            program,
            inputs,
            givens: model.motion_givens().collect(),
            checkpoints: Mutex::new(Vec::new()),
            general: GeneralConstraints::new(model),
            held_sites,
            first_curve_site: forces.map(|(forces, _)| forces.sites().len() + contacts),
            curve_sites: curve_sites(model),
        }
    }

    /// The names a motion's FUNCTION reads besides time and constants
    /// (a FUNCTION must be a function of time only).
    pub(crate) fn states_read(model: &Model) -> Vec<String> {
        let drives = Drives::new(model);
        drives.program.as_ref().map_or_else(Vec::new, |program| {
            program
                .inputs()
                .iter()
                .filter(|name| {
                    model.scene.parse_state_name(name).is_some()
                        || crate::scene::is_run_state_input(name)
                        || crate::scene::parse_sensor_input(name).is_some()
                })
                .cloned()
                .collect()
        })
    }

    /// What the motions and general constraints impose at time `t`, the
    /// forces' program's sites on `held` (`None`: every branch as the
    /// values decide), or the error of the first motion whose FUNCTION
    /// fails (its output [`motion_output`]).
    pub(crate) fn at(
        &self,
        t: f64,
        held: Option<&[Option<Code>]>,
    ) -> Result<Imposed<'_>, OutputError> {
        let mut pieces: Vec<Pieces> = Vec::new();
        if let (Some(sites), Some(first)) = (held, self.first_curve_site) {
            for (k, site) in self.curve_sites.iter().enumerate() {
                let piece = sites.get(first + k).copied().flatten();
                if let Some(piece) = piece.and_then(|code| usize::try_from(code).ok()) {
                    pieces.resize(pieces.len().max(site.joint + 1), [None; 2]);
                    pieces[site.joint][site.side] = Some(piece);
                }
            }
        }
        Ok(Imposed {
            drives: self.displacements(t, held)?,
            time: t,
            general: &self.general,
            pieces,
        })
    }

    /// Each motion's displacement and its derivatives at time `t` with the
    /// forces' sites on `held` (an empty list without motions), or the
    /// error of the first FUNCTION that fails.
    fn displacements(
        &self,
        t: f64,
        held: Option<&[Option<Code>]>,
    ) -> Result<Vec<Drive>, OutputError> {
        let Some(program) = &self.program else {
            return Ok(Vec::new());
        };
        let of_motion = |error: OutputError| OutputError {
            output: motion_output(error.output),
            error: error.error,
        };
        let inputs: Vec<TimeDual> = self
            .inputs
            .iter()
            .map(|input| match input {
                None => TimeDual::variable(t, 0, 1),
                Some(value) => TimeDual::from(*value),
            })
            .collect();
        let mut outputs = vec![TimeDual::from(0.0); program.output_count()];
        let own: Option<Vec<Option<Code>>> =
            held.filter(|_| !self.held_sites.is_empty()).map(|held| {
                self.held_sites
                    .iter()
                    .map(|site| site.and_then(|site| held.get(site).copied().flatten()))
                    .collect()
            });
        program
            .evaluator::<TimeDual>()
            .outputs(&inputs, own.as_deref(), &mut outputs)
            .map_err(of_motion)?;
        let mut drives: Vec<Drive> = outputs
            .iter()
            .map(|output| Drive {
                value: output.re,
                rate: output.gradient(1)[0],
                acceleration: output.hessian(1).map_or(0.0, |hessian| hessian[(0, 0)]),
            })
            .collect();
        if self
            .givens
            .iter()
            .any(|given| !matches!(given, Given::Displacement))
        {
            let n = drives.len();
            let mut checkpoints = self
                .checkpoints
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner);
            let from = checkpoints.partition_point(|(time, _)| *time <= t);
            let (start, mut sums) = match from.checked_sub(1) {
                Some(last) => checkpoints[last].clone(),
                None => (0.0, vec![0.0; 2 * n]),
            };
            // ∫ f and ∫ s·f from the checkpoint to t.
            let mut evaluator = program.evaluator::<f64>();
            let mut inputs: Vec<f64> = self.inputs.iter().map(|v| v.unwrap_or(0.0)).collect();
            let mut values = vec![0.0; n];
            let mut failed = None;
            let rest = integrate(start, t, 2 * n, &mut |s, out| {
                for (input, given) in inputs.iter_mut().zip(&self.inputs) {
                    if given.is_none() {
                        *input = s;
                    }
                }
                if let Err(error) = evaluator.outputs(&inputs, None, &mut values) {
                    failed = Some(error);
                    return false;
                }
                for (k, value) in values.iter().enumerate() {
                    out[k] = *value;
                    out[n + k] = s * value;
                }
                true
            })
            .ok_or_else(|| {
                of_motion(failed.take().unwrap_or_else(|| OutputError {
                    output: 0,
                    error: EvalError::NotFinite {
                        operation: "the integral of a motion's FUNCTION".to_string(),
                        value: f64::NAN,
                        span: crate::span::Span::new(0, 0),
                    },
                }))
            })?;
            for (sum, part) in sums.iter_mut().zip(&rest) {
                *sum += part;
            }
            if from == checkpoints.len() && t > start {
                if checkpoints.len() == CHECKPOINTS {
                    checkpoints.remove(0);
                }
                checkpoints.push((t, sums.clone()));
            }
            drop(checkpoints);
            for (k, (drive, given)) in drives.iter_mut().zip(&self.givens).enumerate() {
                // ∫₀ᵗ (t - s)·f(s) ds = t·∫₀ᵗ f - ∫₀ᵗ s·f(s) ds.
                let (once, twice) = (sums[k], t * sums[k] - sums[n + k]);
                *drive = match *given {
                    Given::Displacement => *drive,
                    Given::Velocity { icdisp } => Drive {
                        value: icdisp + once,
                        rate: drive.value,
                        acceleration: drive.rate,
                    },
                    Given::Acceleration { icdisp, icvel } => Drive {
                        value: icdisp + icvel * t + twice,
                        rate: icvel + once,
                        acceleration: drive.value,
                    },
                };
            }
        }
        Ok(drives)
    }
}

/// What a piecewise site computes, to find it in another program: its
/// kind, its span in its expression's text and that text.
type SiteKey<'t> = (SiteKind, crate::span::Span, Option<&'t str>);

/// For each piecewise site of `drives` (the motions' FUNCTIONs), the site
/// of `forces` (the program of the expressions `computed`) that computes
/// the same call: the one compiled from the same text of the same
/// FUNCTION, or, where the forces' program computes a call once for
/// several expressions, a call of the same function written alike;
/// `None` where there is none (that site goes as its values decide).
fn site_map(
    model: &Model,
    drives: &Program,
    forces: &Program,
    computed: &[usize],
) -> Vec<Option<usize>> {
    let functions: Vec<usize> = model.motion_functions().collect();
    let text_of = |expression: usize, span: crate::span::Span| {
        model.expressions[expression].text.text.get(span.range())
    };
    let key = |program: &Program, site: &crate::compile::Site, expression: usize| {
        let instruction = site.instruction as usize;
        let span = program.span(instruction);
        (program.site_kind(site), span, text_of(expression, span))
    };
    let forces_sites: Vec<(usize, SiteKey<'_>)> = forces
        .sites()
        .iter()
        .map(|site| {
            let expression = computed[forces.origin(site.instruction as usize)];
            (expression, key(forces, site, expression))
        })
        .collect();
    drives
        .sites()
        .iter()
        .map(|site| {
            let expression = functions[drives.origin(site.instruction as usize)];
            let (kind, span, text) = key(drives, site, expression);
            forces_sites
                .iter()
                .position(|(of, (k, s, _))| *of == expression && *k == kind && *s == span)
                .or_else(|| {
                    text.and_then(|text| {
                        forces_sites
                            .iter()
                            .position(|(_, (k, _, t))| *k == kind && *t == Some(text))
                    })
                })
        })
        .collect()
}

/// The output index an [`OutputError`] names when the FUNCTION of motion
/// `motion` (in [`Model::motion_functions`]' order) fails: past every
/// program's outputs, below [`super::JOINTS`].
pub(crate) fn motion_output(motion: usize) -> usize {
    MOTIONS + motion
}

/// The first output index of the motions' FUNCTIONs' errors.
pub(crate) const MOTIONS: usize = usize::MAX / 2;
