//! Adaptive Gauss–Kronrod quadrature (7-point Gauss inside 15-point
//! Kronrod) of a vector of functions over an interval: the integrals a
//! VELOCITY or ACCELERATION motion needs from time 0 to now, to rounding
//! error wherever the functions are smooth between panel ends.

/// The Kronrod abscissae on [-1, 1] (non-negative half, descending; the odd
/// ones are Gauss's).
pub(crate) const NODES: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];

/// The Kronrod weights of [`NODES`].
pub(crate) const KRONROD: [f64; 8] = [
    0.022_935_322_010_529_225,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_18,
    0.140_653_259_715_525_92,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_83,
];

/// The 7-point Gauss weights, of [`NODES`] 1, 3, 5 and 7.
const GAUSS: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// Halvings of one panel before its estimate is taken as it is.
const DEPTH: usize = 48;

/// The integrals over `[a, b]` of the `n` functions `f` writes at a point
/// (`f(s, values)`, false where they cannot be evaluated), each to about
/// `1e-14` of the integral of the largest's magnitude (a panel is also
/// taken once its error is at rounding level); `None` where `f` fails.
pub(crate) fn integrate(
    a: f64,
    b: f64,
    n: usize,
    f: &mut dyn FnMut(f64, &mut [f64]) -> bool,
) -> Option<Vec<f64>> {
    let mut total = vec![0.0; n];
    if b == a {
        return Some(total);
    }
    let whole = panel(a, b, n, f)?;
    let tolerance = 1e-14 * whole.magnitude;
    let mut pending = vec![(a, b, whole, 0usize)];
    while let Some((left, right, estimate, depth)) = pending.pop() {
        let share = tolerance * ((right - left) / (b - a)).abs();
        let middle = 0.5 * (left + right);
        if estimate.error <= share.max(1e-14 * estimate.magnitude)
            || depth >= DEPTH
            || middle == left
            || middle == right
        {
            for (sum, value) in total.iter_mut().zip(&estimate.integrals) {
                *sum += value;
            }
            continue;
        }
        pending.push((left, middle, panel(left, middle, n, f)?, depth + 1));
        pending.push((middle, right, panel(middle, right, n, f)?, depth + 1));
    }
    Some(total)
}

/// One panel's Kronrod estimates, the largest difference from Gauss's,
/// and the largest integral of a function's magnitude.
struct Panel {
    integrals: Vec<f64>,
    error: f64,
    magnitude: f64,
}

/// The estimates over the panel `[a, b]`.
fn panel(a: f64, b: f64, n: usize, f: &mut dyn FnMut(f64, &mut [f64]) -> bool) -> Option<Panel> {
    let centre = 0.5 * (a + b);
    let half = 0.5 * (b - a);
    let mut kronrod = vec![0.0; n];
    let mut gauss = vec![0.0; n];
    let mut magnitudes = vec![0.0; n];
    let mut values = vec![0.0; n];
    for (k, (&node, &weight)) in NODES.iter().zip(&KRONROD).enumerate() {
        let points: &[f64] = if node == 0.0 {
            &[centre]
        } else {
            &[centre - half * node, centre + half * node]
        };
        for &point in points {
            if !f(point, &mut values) {
                return None;
            }
            for (((k_sum, g_sum), m_sum), value) in kronrod
                .iter_mut()
                .zip(&mut gauss)
                .zip(&mut magnitudes)
                .zip(&values)
            {
                *k_sum += weight * value;
                *m_sum += weight * value.abs();
                if k % 2 == 1 {
                    *g_sum += GAUSS[k / 2] * value;
                }
            }
        }
    }
    let mut error: f64 = 0.0;
    for (k_sum, g_sum) in kronrod.iter_mut().zip(&gauss) {
        *k_sum *= half;
        error = error.max((*k_sum - half * g_sum).abs());
    }
    let magnitude = magnitudes
        .iter()
        .fold(0.0, |largest: f64, m| largest.max((half * m).abs()));
    Some(Panel {
        integrals: kronrod,
        error,
        magnitude,
    })
}
