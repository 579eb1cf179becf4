//! The scalar equations `Φ(q) = 0` a joint puts on its I and J markers,
//! each with what the multiplier method needs of it, over any [`Number`]
//! (over dual numbers the reactions carry their exact derivatives):
//!
//! - its value `Φ` (the position residual);
//! - its rate `Φ' = G u`, with the row of `G` on each body's generalised
//!   velocity `u = (v, ω)` (the centre of mass's velocity and the angular
//!   velocity, both in ground);
//! - its bias `Φ'' − G u'`, the part of its second derivative that the
//!   accelerations do not reach (`ω × (ω × r)` and its kin), so that the
//!   accelerations satisfy `G u' = −bias`.
//!
//! A marker's origin and axes are [`Moving`] vectors; each row is a
//! component or a dot product of them, and the product rule gives its rate,
//! bias and `G` row, so no derivative is written by hand per joint.

use nalgebra::{Matrix3, Vector3};

use crate::number::Number;

/// A body's motion as the constraint rows see it: the centre of mass, the
/// rotation from body to ground axes, the centre's velocity and the
/// angular velocity, in ground.
pub(crate) struct BodyMotion<T: Number> {
    /// The centre of mass in ground.
    pub(crate) centre: Vector3<T>,
    /// The rotation from the body's axes to ground's.
    pub(crate) rotation: Matrix3<T>,
    /// The velocity of the centre of mass, in ground.
    pub(crate) velocity: Vector3<T>,
    /// The angular velocity, in ground.
    pub(crate) omega: Vector3<T>,
}

/// A vector fixed in a body (or in ground), moving with it: its value, its
/// rate, the bias of its second derivative, and the linear map from each
/// body's generalised velocity to its rate (`[linear | angular]`, 3 × 6).
pub(crate) struct Moving<T: Number> {
    value: Vector3<T>,
    rate: Vector3<T>,
    bias: Vector3<T>,
    map: Vec<(usize, [Vector3<T>; 6])>,
}

impl<T: Number> Moving<T> {
    /// A constant vector (on ground).
    fn fixed(value: Vector3<T>) -> Moving<T> {
        Moving {
            value,
            rate: Vector3::zeros(),
            bias: Vector3::zeros(),
            map: Vec::new(),
        }
    }

    /// The point at `offset` from the centre of mass of `body` (in its own
    /// axes; on ground, the point `ground`): `p = c + r` with `r = R s`,
    /// `p' = v + ω × r`.
    pub(crate) fn point(
        body: Option<(usize, &BodyMotion<T>)>,
        offset: &Vector3<f64>,
        ground: &Vector3<f64>,
    ) -> Moving<T> {
        let Some((index, motion)) = body else {
            return Moving::fixed(ground.map(T::from));
        };
        let mut point = Moving::turning(index, motion, offset);
        point.value += &motion.centre;
        point.rate += &motion.velocity;
        for (_, columns) in &mut point.map {
            columns[0] = Vector3::x();
            columns[1] = Vector3::y();
            columns[2] = Vector3::z();
        }
        point
    }

    /// The direction `axis` (in the body's axes) of `body`: `a = R a_b`,
    /// `a' = ω × a`.
    pub(crate) fn axis(
        body: Option<(usize, &BodyMotion<T>)>,
        axis_in_body: &Vector3<f64>,
    ) -> Moving<T> {
        match body {
            Some((index, motion)) => Moving::turning(index, motion, axis_in_body),
            None => Moving::fixed(axis_in_body.map(T::from)),
        }
    }

    /// The vector `a = R a_b` turning with body `index`: rate `ω × a`, bias
    /// `ω × (ω × a)`; column `k` of its angular map is `e_k × a`.
    fn turning(index: usize, motion: &BodyMotion<T>, in_body: &Vector3<f64>) -> Moving<T> {
        let value = &motion.rotation * in_body.map(T::from);
        let omega = &motion.omega;
        let turn = |component: usize| {
            let mut unit = Vector3::zeros();
            unit[component] = T::one();
            unit.cross(&value)
        };
        let columns = [
            Vector3::zeros(),
            Vector3::zeros(),
            Vector3::zeros(),
            turn(0),
            turn(1),
            turn(2),
        ];
        Moving {
            rate: omega.cross(&value),
            bias: omega.cross(&omega.cross(&value)),
            value,
            map: vec![(index, columns)],
        }
    }

    /// `self − other`.
    pub(crate) fn minus(&self, other: &Moving<T>) -> Moving<T> {
        let mut map = self.map.clone();
        for (body, columns) in &other.map {
            let negated = columns.clone().map(|column| -column);
            add_columns(&mut map, *body, &negated);
        }
        Moving {
            value: &self.value - &other.value,
            rate: &self.rate - &other.rate,
            bias: &self.bias - &other.bias,
            map,
        }
    }

    /// The row of component `axis` (0, 1, 2: x, y, z of ground).
    pub(crate) fn component(&self, axis: usize) -> Row<T> {
        Row {
            value: self.value[axis].clone(),
            rate: self.rate[axis].clone(),
            bias: self.bias[axis].clone(),
            coefficients: self
                .map
                .iter()
                .map(|(body, columns)| (*body, columns.clone().map(|column| column[axis].clone())))
                .collect(),
        }
    }

    /// The row of `self · other`: by the product rule, rate `a'·b + a·b'`,
    /// bias `a''·b + 2 a'·b' + a·b''` (of the bias parts).
    pub(crate) fn dot(&self, other: &Moving<T>) -> Row<T> {
        let mut coefficients: Vec<(usize, [T; 6])> = Vec::new();
        let mut add = |map: &[(usize, [Vector3<T>; 6])], with: &Vector3<T>| {
            for (body, columns) in map {
                add_coefficients(
                    &mut coefficients,
                    *body,
                    columns.clone().map(|column| column.dot(with)),
                );
            }
        };
        add(&self.map, &other.value);
        add(&other.map, &self.value);
        Row {
            value: self.value.dot(&other.value),
            rate: self.rate.dot(&other.value) + self.value.dot(&other.rate),
            bias: self.bias.dot(&other.value)
                + self.value.dot(&other.bias)
                + self.rate.dot(&other.rate) * T::from(2.0),
            coefficients,
        }
    }
}

/// Adds `row` to `body`'s coefficients in `coefficients`.
fn add_coefficients<T: Number>(coefficients: &mut Vec<(usize, [T; 6])>, body: usize, row: [T; 6]) {
    match coefficients.iter_mut().find(|(b, _)| *b == body) {
        Some((_, sum)) => {
            for (sum, term) in sum.iter_mut().zip(row) {
                *sum += term;
            }
        }
        None => coefficients.push((body, row)),
    }
}

/// Adds `columns` to `body`'s entry of `map`.
fn add_columns<T: Number>(
    map: &mut Vec<(usize, [Vector3<T>; 6])>,
    body: usize,
    columns: &[Vector3<T>; 6],
) {
    match map.iter_mut().find(|(b, _)| *b == body) {
        Some((_, sum)) => {
            for (sum, term) in sum.iter_mut().zip(columns) {
                *sum += term;
            }
        }
        None => map.push((body, columns.clone())),
    }
}

/// One scalar constraint equation at the current state.
pub(crate) struct Row<T: Number> {
    /// `Φ`: zero on the constraint.
    pub(crate) value: T,
    /// `Φ' = G u`.
    pub(crate) rate: T,
    /// `Φ'' − G u'`.
    pub(crate) bias: T,
    /// The row of `G` on each body it involves: `[v_x v_y v_z ω_x ω_y ω_z]`.
    pub(crate) coefficients: Vec<(usize, [T; 6])>,
}

impl<T: Number> Row<T> {
    /// The row of `self + factor · other`.
    pub(crate) fn plus_scaled(mut self, other: Row<T>, factor: f64) -> Row<T> {
        self.value += other.value * factor;
        self.rate += other.rate * factor;
        self.bias += other.bias * factor;
        for (body, columns) in other.coefficients {
            add_coefficients(
                &mut self.coefficients,
                body,
                columns.map(|entry| entry * factor),
            );
        }
        self
    }

    /// The row of `self + factor · other`, `factor` a number that does not
    /// move (its own rate left out).
    pub(crate) fn plus_times(mut self, other: &Row<T>, factor: &T) -> Row<T> {
        self.value += other.value.clone() * factor.clone();
        self.rate += other.rate.clone() * factor.clone();
        self.bias += other.bias.clone() * factor.clone();
        self.plus_coefficients(other, factor)
    }

    /// The row that is zero at every state.
    pub(crate) fn zero() -> Row<T> {
        Row {
            value: T::zero(),
            rate: T::zero(),
            bias: T::zero(),
            coefficients: Vec::new(),
        }
    }

    /// `self` with `factor` times `other`'s row of `G` added to its own
    /// (its value, rate and bias unchanged): the chain rule's part of a
    /// function of rows whose other parts are worked out on their own.
    pub(crate) fn plus_coefficients(mut self, other: &Row<T>, factor: &T) -> Row<T> {
        for (body, columns) in &other.coefficients {
            add_coefficients(
                &mut self.coefficients,
                *body,
                columns.clone().map(|entry| entry * factor.clone()),
            );
        }
        self
    }

    /// The row of `factor · self`.
    pub(crate) fn scaled(self, factor: f64) -> Row<T> {
        Row {
            value: self.value * factor,
            rate: self.rate * factor,
            bias: self.bias * factor,
            coefficients: self
                .coefficients
                .into_iter()
                .map(|(body, columns)| (body, columns.map(|entry| entry * factor)))
                .collect(),
        }
    }

    /// Its value less the whole number of `period`s that brings it nearest
    /// zero: an equation on an angle known modulo a turn (`period` the
    /// equation's change over one turn), its rate and bias unchanged.
    pub(crate) fn wrap(&mut self, period: f64) {
        let turns = (self.value.value() / period).round();
        self.value -= T::from(turns * period);
    }

    /// The row of the angle `atan2(s, c)`: rate `(c s' − s c') / r²`, bias
    /// `(c b_s − s b_c) / r² − 2 θ' (c c' + s s') / r²` (`r² = s² + c²`).
    pub(crate) fn angle(s: Row<T>, c: Row<T>) -> Row<T> {
        let r2 = s.value.clone() * s.value.clone() + c.value.clone() * c.value.clone();
        let rate =
            (c.value.clone() * s.rate.clone() - s.value.clone() * c.rate.clone()) / r2.clone();
        let bias = (c.value.clone() * s.bias.clone() - s.value.clone() * c.bias.clone())
            / r2.clone()
            - rate.clone()
                * (c.value.clone() * c.rate.clone() + s.value.clone() * s.rate.clone())
                * T::from(2.0)
                / r2.clone();
        let mut coefficients: Vec<(usize, [T; 6])> = Vec::new();
        for (row, factor) in [(&s, c.value.clone()), (&c, -s.value.clone())] {
            for (body, columns) in &row.coefficients {
                let scaled = columns
                    .clone()
                    .map(|entry| entry * factor.clone() / r2.clone());
                add_coefficients(&mut coefficients, *body, scaled);
            }
        }
        Row {
            value: s.value.clone().atan2(c.value.clone()),
            rate,
            bias,
            coefficients,
        }
    }
}
