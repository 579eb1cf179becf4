//! The displacements the motions impose, with their first two time
//! derivatives (from dual numbers seeded in time).

use num_dual::Dual2Vec;

use crate::compile::{Program, compile_outputs};
use crate::number::Directional;
use crate::simulate::Model;

/// A motion's displacement at a time, and its first two derivatives.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Drive {
    pub(crate) value: f64,
    pub(crate) rate: f64,
    pub(crate) acceleration: f64,
}

type TimeDual = Dual2Vec<f64, nalgebra::Const<1>>;

/// The motions' FUNCTIONs compiled together, to be evaluated in time.
pub(crate) struct Drives {
    program: Option<Program>,
    /// Each input's value: `None` for `TIME`, a constant otherwise.
    inputs: Vec<Option<f64>>,
}

impl Drives {
    /// The drives of `model`'s motions (none without motions). The
    /// FUNCTIONs have compiled in the model's program already.
    pub(crate) fn new(model: &Model) -> Drives {
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
        Drives { program, inputs }
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
                        || crate::scene::parse_diff_input(name).is_some()
                })
                .cloned()
                .collect()
        })
    }

    /// Each motion's displacement and its derivatives at time `t` (an
    /// empty list without motions; `None` where a FUNCTION fails).
    pub(crate) fn at(&self, t: f64) -> Option<Vec<Drive>> {
        let Some(program) = &self.program else {
            return Some(Vec::new());
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
        program
            .evaluator::<TimeDual>()
            .outputs(&inputs, None, &mut outputs)
            .ok()?;
        Some(
            outputs
                .iter()
                .map(|output| Drive {
                    value: output.re,
                    rate: output.gradient(1)[0],
                    acceleration: output.hessian(1).map_or(0.0, |hessian| hessian[(0, 0)]),
                })
                .collect(),
        )
    }
}
