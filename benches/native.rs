//! The hand-written laws the evaluation benchmarks compare against, shared
//! by `eval.rs` and `counts.rs`.

use num_dual::DualNum;

/// BISTOP written out by hand for these parameters (SPEC 3.3), generic so
/// that num-dual gives its derivatives: what a hand-coded force would be.
pub fn native_bistop<D: DualNum<Primitive = f64> + Copy>(x: D, v: D) -> D {
    let (x1, x2, k, e, cmax, d) = (-10.0, 10.0, 1e5, 2.2, 100.0, 0.1);
    let damping = |p: D| {
        if p.re() >= d {
            D::from(cmax)
        } else {
            let w = p / d;
            w * w * (w * -2.0 + 3.0) * cmax
        }
    };
    if x.re() < x1 {
        let p = -x + x1;
        let raw = p.powf(e) * k - damping(p) * v;
        if raw.re() > 0.0 { raw } else { D::zero() }
    } else if x.re() > x2 {
        let p = x - x2;
        let raw = -(p.powf(e) * k) - damping(p) * v;
        if raw.re() < 0.0 { raw } else { D::zero() }
    } else {
        D::zero()
    }
}

/// `-1E4*(x-50)-10*v + 3*sin(2*pi*t)` by hand.
pub fn native_linear(x: f64, v: f64, t: f64) -> f64 {
    -1e4 * (x - 50.0) - 10.0 * v + 3.0 * (2.0 * std::f64::consts::PI * t).sin()
}
