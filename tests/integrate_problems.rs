//! Test problems for the integrators, with published or closed-form
//! answers.

use mbexpr::integrate::{System, finite_difference_jacobian};
use nalgebra::DMatrix;

/// A test system's refusal of a state.
#[derive(Debug, PartialEq)]
pub struct Refused(pub &'static str);

impl std::fmt::Display for Refused {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.0)
    }
}

type Rhs = fn(f64, &[f64], &mut [f64]) -> Result<(), Refused>;
type Jacobian = fn(&[f64], &mut DMatrix<f64>) -> Result<(), Refused>;

/// A system given by its functions; without a Jacobian, finite differences.
pub struct Equations {
    dimension: usize,
    rhs: Rhs,
    jacobian: Option<Jacobian>,
}

impl System for Equations {
    type Error = Refused;

    fn dimension(&self) -> usize {
        self.dimension
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Refused> {
        (self.rhs)(t, y, dy)
    }

    fn jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        dy: &[f64],
        jac: &mut DMatrix<f64>,
    ) -> Result<(), Refused> {
        match self.jacobian {
            Some(jacobian) => jacobian(y, jac),
            None => finite_difference_jacobian(self, t, y, dy, jac),
        }
    }
}

/// An initial value problem and the solution at its end.
pub struct Problem {
    pub system: Equations,
    pub y0: Vec<f64>,
    pub t_end: f64,
    /// `y(t_end)`.
    pub reference: Vec<f64>,
    /// Errors are measured as `|y_i - reference_i| / scale_i`.
    pub scale: Vec<f64>,
    /// The solution at any time, when known in closed form.
    pub exact: Option<fn(f64) -> Vec<f64>>,
}

impl Problem {
    /// A problem whose solution is known in closed form, over `[0, t_end]`.
    fn closed_form(system: Equations, exact: fn(f64) -> Vec<f64>, t_end: f64) -> Self {
        Problem {
            scale: vec![1.0; system.dimension],
            system,
            y0: exact(0.0),
            t_end,
            reference: exact(t_end),
            exact: Some(exact),
        }
    }
}

/// The problem called `name`.
pub fn problem(name: &str) -> Problem {
    let equations = |dimension, rhs, jacobian| Equations {
        dimension,
        rhs,
        jacobian,
    };
    match name {
        // Hairer, Nørsett, Wanner I, p. 129: the restricted three-body orbit
        // closes after one period.
        "arenstorf" => Problem {
            system: equations(4, arenstorf, None),
            y0: ARENSTORF_START.to_vec(),
            t_end: ARENSTORF_PERIOD,
            reference: ARENSTORF_START.to_vec(),
            scale: vec![1.0; 4],
            exact: None,
        },
        // Test Set for IVP Solvers (Mazzia, Magherini), VDPOL: eps = 1e-6.
        "van-der-pol" => Problem {
            system: equations(2, van_der_pol, Some(van_der_pol_jacobian)),
            y0: vec![2.0, 0.0],
            t_end: 2.0,
            reference: vec![0.170_616_773_217_048_3e1, -0.892_809_701_024_797_5],
            scale: vec![1.0; 2],
            exact: None,
        },
        // Test Set for IVP Solvers, ROBER at t = 1e11 (relative errors).
        "robertson" => {
            let reference = vec![
                0.208_334_014_970_125_5e-7,
                0.833_336_077_033_471_3e-13,
                0.999_999_979_166_505,
            ];
            Problem {
                system: equations(3, robertson, Some(robertson_jacobian)),
                y0: vec![1.0, 0.0, 0.0],
                t_end: 1e11,
                scale: reference.clone(),
                reference,
                exact: None,
            }
        }
        // r' = r (1 - r^2), angle' = 1 in Cartesian form, from r = 1/2.
        "limit-cycle" => Problem::closed_form(
            equations(2, limit_cycle, Some(limit_cycle_jacobian)),
            limit_cycle_solution,
            2.0,
        ),
        // Torricelli's tank, y' = -sqrt(y): a trial step that overshoots
        // the empty tank asks for the root of a negative level.
        "draining-tank" => Problem::closed_form(
            equations(1, draining_tank, Some(draining_tank_jacobian)),
            |t| vec![(1.0 - t / 2.0).powi(2)],
            1.9,
        ),
        // y' = -100 y^(3/2): slow algebraic decay, refused below zero,
        // where a long explicit step overshoots.
        "decay" => Problem::closed_form(
            equations(1, decay, Some(decay_jacobian)),
            |t| vec![(1.0 + 50.0 * t).powi(-2)],
            10.0,
        ),
        // The limit cycle refused beyond t = 1.
        "refused-after-1" => Problem {
            system: equations(2, refused_after_1, Some(limit_cycle_jacobian)),
            ..problem("limit-cycle")
        },
        // The limit cycle with a NaN rate once the second component passes
        // 0.6.
        "nan-beyond" => Problem {
            system: equations(2, nan_beyond, Some(limit_cycle_jacobian)),
            ..problem("limit-cycle")
        },
        // The limit cycle with a Jacobian that always fails.
        "no-jacobian" => Problem {
            system: equations(
                2,
                limit_cycle,
                Some(|_, _| Err(Refused("no jacobian here"))),
            ),
            ..problem("limit-cycle")
        },
        // No state at all: time passes.
        "empty" => Problem {
            system: equations(0, |_, _, _| Ok(()), None),
            y0: Vec::new(),
            t_end: 1.0,
            reference: Vec::new(),
            scale: Vec::new(),
            exact: None,
        },
        _ => panic!("no problem called {name}"),
    }
}

/// The published digits, more than a double holds.
#[allow(clippy::excessive_precision)]
const ARENSTORF_PERIOD: f64 = 17.065_216_560_157_962_558_891_720_624_9;
#[allow(clippy::excessive_precision)]
const ARENSTORF_START: [f64; 4] = [0.994, 0.0, 0.0, -2.001_585_106_379_082_522_405_378_622_24];

fn arenstorf(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Refused> {
    let mu = 0.012_277_471;
    let earth = 1.0 - mu;
    let [y1, y2, v1, v2] = [y[0], y[1], y[2], y[3]];
    let d1 = ((y1 + mu).powi(2) + y2 * y2).powf(1.5);
    let d2 = ((y1 - earth).powi(2) + y2 * y2).powf(1.5);
    dy[0] = v1;
    dy[1] = v2;
    dy[2] = y1 + 2.0 * v2 - earth * (y1 + mu) / d1 - mu * (y1 - earth) / d2;
    dy[3] = y2 - 2.0 * v1 - earth * y2 / d1 - mu * y2 / d2;
    Ok(())
}

const VAN_DER_POL_EPSILON: f64 = 1e-6;

fn van_der_pol(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Refused> {
    dy[0] = y[1];
    dy[1] = ((1.0 - y[0] * y[0]) * y[1] - y[0]) / VAN_DER_POL_EPSILON;
    Ok(())
}

fn van_der_pol_jacobian(y: &[f64], jac: &mut DMatrix<f64>) -> Result<(), Refused> {
    jac[(0, 1)] = 1.0;
    jac[(1, 0)] = (-2.0 * y[0] * y[1] - 1.0) / VAN_DER_POL_EPSILON;
    jac[(1, 1)] = (1.0 - y[0] * y[0]) / VAN_DER_POL_EPSILON;
    Ok(())
}

fn robertson(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Refused> {
    dy[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
    dy[2] = 3e7 * y[1] * y[1];
    dy[1] = -dy[0] - dy[2];
    Ok(())
}

fn robertson_jacobian(y: &[f64], jac: &mut DMatrix<f64>) -> Result<(), Refused> {
    jac.copy_from(&DMatrix::from_row_slice(
        3,
        3,
        &[
            -0.04,
            1e4 * y[2],
            1e4 * y[1],
            0.04,
            -1e4 * y[2] - 6e7 * y[1],
            -1e4 * y[1],
            0.0,
            6e7 * y[1],
            0.0,
        ],
    ));
    Ok(())
}

fn limit_cycle_solution(t: f64) -> Vec<f64> {
    let r = 1.0 / (1.0 + 3.0 * (-2.0 * t).exp()).sqrt();
    vec![r * t.cos(), r * t.sin()]
}

fn limit_cycle(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Refused> {
    let growth = 1.0 - y[0] * y[0] - y[1] * y[1];
    dy[0] = y[0] * growth - y[1];
    dy[1] = y[1] * growth + y[0];
    Ok(())
}

fn limit_cycle_jacobian(y: &[f64], jac: &mut DMatrix<f64>) -> Result<(), Refused> {
    let (x, y) = (y[0], y[1]);
    jac[(0, 0)] = 1.0 - 3.0 * x * x - y * y;
    jac[(0, 1)] = -2.0 * x * y - 1.0;
    jac[(1, 0)] = -2.0 * x * y + 1.0;
    jac[(1, 1)] = 1.0 - x * x - 3.0 * y * y;
    Ok(())
}

fn draining_tank(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Refused> {
    if y[0] < 0.0 {
        return Err(Refused("the square root of a negative level"));
    }
    dy[0] = -y[0].sqrt();
    Ok(())
}

fn draining_tank_jacobian(y: &[f64], jac: &mut DMatrix<f64>) -> Result<(), Refused> {
    jac[(0, 0)] = -0.5 / y[0].sqrt();
    Ok(())
}

fn decay(_t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Refused> {
    if y[0] < 0.0 {
        return Err(Refused("the square root of a negative amount"));
    }
    dy[0] = -100.0 * y[0] * y[0].sqrt();
    Ok(())
}

fn decay_jacobian(y: &[f64], jac: &mut DMatrix<f64>) -> Result<(), Refused> {
    jac[(0, 0)] = -150.0 * y[0].sqrt();
    Ok(())
}

fn refused_after_1(t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Refused> {
    if t > 1.0 {
        return Err(Refused("refused beyond t = 1"));
    }
    limit_cycle(t, y, dy)
}

fn nan_beyond(t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Refused> {
    limit_cycle(t, y, dy)?;
    if y[1] > 0.6 {
        dy[1] = f64::NAN;
    }
    Ok(())
}
