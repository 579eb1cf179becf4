//! A dataset's expressions evaluated at its initial configuration: each
//! VARIABLE once, after the VARIABLEs it reads, `VARVAL` passing its value
//! on with its derivatives; the inputs a user sets (TIME, MODE, `DIF(id)`,
//! a part's state). For `eval --model` and `plot --model`.

use std::collections::HashMap;

use mbexpr::model::{self, FileKind};
use mbexpr::number::{Directional, Number};
use mbexpr::{Checked, Evaluation, Order, Scene};
use num_dual::{Dual2DVec64, DualDVec64};

use super::files;
use super::plotting::{Plot, Sampling, trace};
use super::render::diagnostics;
use super::values::parse_assignment;
use crate::Fatal;

/// Why a row has no value.
#[derive(Clone)]
pub struct NoValue {
    pub message: String,
    pub kind: Missing,
}

/// What keeps a row from a value.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Missing {
    /// Something is wrong with the expression or the model.
    Error,
    /// Nothing is wrong: only a running solver has the value (a result, a
    /// solver state).
    Solver,
    /// Nothing is wrong: mbexpr does not evaluate the function (CURVE,
    /// INTERP, a user subroutine).
    NotEvaluated,
}

impl NoValue {
    pub fn error(message: impl ToString) -> NoValue {
        NoValue {
            message: message.to_string(),
            kind: Missing::Error,
        }
    }
}

/// What keeps an expression that compiles with `errors` from a value: the
/// least harmless of them.
pub fn missing(errors: &[mbexpr::CompileError]) -> Missing {
    use mbexpr::CompileError;
    let kind = |error: &CompileError| match error {
        CompileError::NeedsSolver { .. } | CompileError::NeedsSolverState { .. } => Missing::Solver,
        CompileError::NotInScene { .. } | CompileError::UserSubroutine { .. } => {
            Missing::NotEvaluated
        }
        _ => Missing::Error,
    };
    if errors.iter().any(|error| kind(error) == Missing::Error) {
        Missing::Error
    } else if errors
        .iter()
        .any(|error| kind(error) == Missing::NotEvaluated)
    {
        Missing::NotEvaluated
    } else {
        Missing::Solver
    }
}

/// What every evaluation of one run shares: the scene, its input names,
/// the derivative directions and how to make and read numbers of type `T`.
pub struct Context<'a, T> {
    scene: &'a Scene,
    inputs: Vec<String>,
    wrt: &'a [String],
    /// A value as a number of type `T`, seeded as direction `Some(j)`.
    seed: fn(f64, Option<usize>, usize) -> T,
    /// The values of the VARIABLEs evaluated so far.
    variables: HashMap<u64, Result<T, NoValue>>,
}

impl<T: Number> Context<'_, T> {
    /// The value of `checked` with the VARIABLEs it reads from
    /// [`Context::variables`].
    fn evaluate(&self, checked: &Checked) -> Result<T, NoValue> {
        let program =
            mbexpr::compile_in_model(checked, &self.inputs, self.scene).map_err(|errors| {
                NoValue {
                    message: errors[0].to_string(),
                    kind: missing(&errors),
                }
            })?;
        let count = self.wrt.len();
        let values = program
            .inputs()
            .iter()
            .map(|name| match variable_id(name) {
                Some(id) => match self.variables.get(&id) {
                    Some(Ok(value)) => Ok(value.clone()),
                    Some(Err(no_value)) => Err(NoValue {
                        message: format!("VARVAL({id}) has no value: {}", no_value.message),
                        kind: no_value.kind,
                    }),
                    None => Err(NoValue::error(format!("VARIABLE/{id} depends on itself"))),
                },
                None => {
                    let value = self.scene.value_of(name).map_err(NoValue::error)?;
                    let direction = self
                        .wrt
                        .iter()
                        .position(|known| known.eq_ignore_ascii_case(name));
                    Ok((self.seed)(value, direction, count))
                }
            })
            .collect::<Result<Vec<T>, NoValue>>()?;
        program
            .evaluator::<T>()
            .evaluate_numbers(&values)
            .map_err(NoValue::error)
    }
}

/// The VARIABLE id of an input named `VARVAL(id)` by `compile_in_model`.
pub fn variable_id(name: &str) -> Option<u64> {
    name.strip_prefix("VARVAL(")?
        .strip_suffix(')')?
        .parse()
        .ok()
}

/// Every row (and the user's expression, last) evaluated over numbers of
/// type `T`, read into [`Evaluation`]s by `finish`.
pub fn evaluate_all<T: Number>(
    mut context: Context<'_, T>,
    rows: &[Option<&Checked>],
    finish: impl Fn(&T) -> Evaluation,
) -> Vec<Result<Evaluation, NoValue>> {
    let (order, looped) = model::evaluation_order(&context.scene.statements.variables);
    for id in looped {
        let message = format!("VARIABLE/{id} depends on itself (see mbexpr check)");
        context.variables.insert(id, Err(NoValue::error(message)));
    }
    for id in order {
        let value = context.evaluate(&context.scene.statements.variables[&id]);
        context.variables.insert(id, value);
    }
    rows.iter()
        .map(|row| match row {
            Some(checked) => context.evaluate(checked).map(|value| finish(&value)),
            None => Err(NoValue::error(
                "the expression does not check (see mbexpr check)",
            )),
        })
        .collect()
}

/// [`evaluate_all`] over the number type `order` needs.
pub fn evaluate_rows(
    scene: &Scene,
    inputs: Vec<String>,
    wrt: &[String],
    order: Order,
    rows: &[Option<&Checked>],
) -> Vec<Result<Evaluation, NoValue>> {
    fn context<'a, T: Directional>(
        scene: &'a Scene,
        inputs: Vec<String>,
        wrt: &'a [String],
    ) -> Context<'a, T> {
        Context {
            scene,
            inputs,
            wrt,
            seed: |value, direction, count| match direction {
                Some(direction) => T::variable(value, direction, count),
                None => T::from(value),
            },
            variables: HashMap::new(),
        }
    }
    let count = wrt.len();
    match order {
        Order::Value => {
            let context = Context::<f64> {
                scene,
                inputs,
                wrt,
                seed: |value, _, _| value,
                variables: HashMap::new(),
            };
            evaluate_all(context, rows, |value| Evaluation {
                value: *value,
                gradient: None,
                hessian: None,
            })
        }
        Order::Gradient => evaluate_all(context::<DualDVec64>(scene, inputs, wrt), rows, |value| {
            Evaluation {
                value: value.value(),
                gradient: Some(value.gradient(count)),
                hessian: None,
            }
        }),
        Order::Hessian => evaluate_all(context::<Dual2DVec64>(scene, inputs, wrt), rows, |value| {
            Evaluation {
                value: value.value(),
                gradient: Some(value.gradient(count)),
                hessian: value.hessian(count),
            }
        }),
    }
}

/// The text of the model file and its statements.
pub fn read_model(path: &str) -> Result<(String, model::Dataset), Fatal> {
    let text = files::read(path).map_err(|message| Fatal::usage(format!("error: {message}")))?;
    let kind = match FileKind::detect(path, &text) {
        Some(kind @ (FileKind::Adm | FileKind::Acf)) => kind,
        _ => {
            return Err(Fatal::usage(format!(
                "error: --model {path}: give a solver dataset (.adm, or a file whose first lines are a dataset's) or command file (.acf)"
            )));
        }
    };
    let dataset = model::read(&text, kind);
    Ok((text, dataset))
}

/// A model read for evaluation: its text, statements, check report and
/// the scene of its initial configuration, with the inputs `sets` gives
/// (TIME, MODE, `DIF(id)`, a part's state) set.
pub struct Model {
    pub text: String,
    pub dataset: model::Dataset,
    pub report: model::ModelCheck,
    pub scene: Scene,
}

pub fn read_in(path: &str, sets: &[String]) -> Result<Model, Fatal> {
    let (text, dataset) = read_model(path)?;
    let report = model::check_model(&text, &dataset);
    let mut scene = model::initial_scene(&dataset, &report).map_err(|errors| {
        let problems = errors.iter().map(|error| (error.span(), error.to_string()));
        Fatal::input(diagnostics(path, &text, problems))
    })?;
    for assignment in sets {
        let (name, value) = parse_assignment(assignment)?;
        set_input(&mut scene, &name, value)
            .map_err(|message| Fatal::usage(format!("error: --set {assignment}: {message}")))?;
    }
    Ok(Model {
        text,
        dataset,
        report,
        scene,
    })
}

/// Gives input `name` of a model's expressions the value `value` in
/// `scene`: `TIME`, `MODE`, a DIFF's state `DIF(id)`, or a part's state
/// component (`PART/3.x`; a rotation `rz` turns the part from its initial
/// orientation about ground z).
pub fn set_input(scene: &mut Scene, name: &str, value: f64) -> Result<(), String> {
    use mbexpr::catalog::SystemVariable;
    use mbexpr::scene::StateComponent;
    match SystemVariable::lookup(name) {
        Some(SystemVariable::Time) => scene.time = value,
        Some(SystemVariable::Mode) => match SystemVariable::mode_error(value) {
            Some(message) => return Err(message),
            None => scene.mode = Some(value),
        },
        None => {
            let diff = mbexpr::scene::parse_diff_input(name)
                .and_then(|id| scene.statements.diffs.get_mut(&id));
            if let Some(diff) = diff {
                diff.initial = value;
                return Ok(());
            }
            let linear_state =
                mbexpr::scene::parse_array_state_input(name).and_then(|(array, entry)| {
                    let system = scene
                        .statements
                        .linear_systems
                        .iter_mut()
                        .find(|system| system.states == array)?;
                    system.initial.get_mut(entry.checked_sub(1)?)
                });
            if let Some(initial) = linear_state {
                *initial = value;
                return Ok(());
            }
            let (index, component) = scene
                .parse_state_name(name)
                .ok_or_else(|| not_a_state(scene, name))?;
            let body = &mut scene.bodies[index];
            match component {
                StateComponent::Position(axis) => body.position[axis] = value,
                StateComponent::Rotation(axis) => {
                    let turn = nalgebra::Vector3::ith(axis, value);
                    body.orientation =
                        nalgebra::UnitQuaternion::from_scaled_axis(turn) * body.orientation;
                }
                StateComponent::Velocity(axis) => body.velocity[axis] = value,
                StateComponent::AngularVelocity(axis) => body.angular_velocity[axis] = value,
            }
        }
    }
    Ok(())
}

/// `plot --model`: `checked` evaluated in the model at each sample of the
/// input `sampling.over` (TIME, `DIF(id)` or a part's state component), the
/// other inputs at the initial configuration. Its break points are not
/// looked for (each VARIABLE is its own program): the samples are even.
pub fn curves(
    path: &str,
    sets: &[String],
    checked: &Checked,
    sampling: &Sampling<'_>,
    samples: usize,
) -> Result<Plot, Fatal> {
    let scene = read_in(path, sets)?.scene;
    let over = sampling.over;
    set_input(&mut scene.clone(), over, sampling.range.0)
        .map_err(|message| Fatal::usage(format!("error: --over {over}: {message}")))?;
    let (wrt, order) = if sampling.derivatives {
        (vec![over.to_string()], Order::Hessian)
    } else {
        (Vec::new(), Order::Value)
    };
    let mut inputs = scene.input_names();
    inputs.extend(wrt.iter().cloned());
    let (low, high) = sampling.range;
    let xs = mbexpr::kinks::samples(low, high, samples, &[]);
    trace(sampling, &xs, Vec::new(), |x| {
        let mut at = scene.clone();
        set_input(&mut at, over, x)?;
        let mut results = evaluate_rows(&at, inputs.clone(), &wrt, order, &[Some(checked)]);
        results.remove(0).map_err(|no_value| no_value.message)
    })
    .map_err(|message| Fatal::input(format!("error: {message}")))
}

/// Why `name` is neither TIME nor a state component of a part of `scene`:
/// no part of that name (with the close ones), or no such component.
pub fn not_a_state(scene: &Scene, name: &str) -> String {
    const COMPONENTS: &str = "x y z rx ry rz vx vy vz wx wy wz";
    let Some((part, component)) = name.rsplit_once('.') else {
        return format!(
            "name TIME, a DIFF's state DIF(id), a TFSISO's or LSE's state ARYVAL(x, k) (k-th of its X array x) or a part's state component, such as PART/3.x ({COMPONENTS})"
        );
    };
    if scene.find_body(part).is_none() {
        let parts = scene.bodies.iter().map(|body| body.name.as_str());
        let close = mbexpr::catalog::closest(part, parts);
        return format!(
            "{part} does not exist in this model{}",
            mbexpr::catalog::did_you_mean(&close)
        );
    }
    format!("`{component}` is not a state component of {part}: write one of {COMPONENTS}")
}
