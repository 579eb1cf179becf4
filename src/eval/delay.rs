//! The record a run keeps of each `DELAY`'s expression, and the value read
//! back from it at an earlier time.
//!
//! The run samples every DELAY's expression at its accepted states and at
//! seven points inside each accepted step (on the step's continuous output)
//! ([`DelayRecord::record`]). A value at an earlier time `s` is the
//! polynomial through the [`STENCIL`] samples nearest `s` (Newton's divided
//! differences), with its first two derivatives in `s` for the dual numbers
//! a state-dependent delay carries. A located switch begins a new piece: no
//! polynomial reaches across one, so a kink in the expression stays a kink.
//! The DELAY is itself a switch, from its history to its record, located
//! where the time looked back to passes 0 (where the delayed expression
//! jumps from the history to its value at the start). Between the last
//! sample and the evaluation under way (a delay shorter than the step) the
//! value is the straight line from the last sample to the expression's
//! value now.

use std::sync::{Arc, RwLock};

use crate::laws::branch::Code;
use crate::number::Number;

/// How many samples the polynomial at an earlier time passes through
/// (degree 7: the run samples eight points a step).
pub const STENCIL: usize = 8;

/// How many times a kink is followed on: a DELAY's expression read across
/// a kink of level `k` has one of level `k + 1` (a jump in a derivative one
/// order higher), and levels from this one on are smooth enough for the
/// methods' orders to pass over.
pub const KINK_LEVELS: u8 = 8;

/// The least spacing of a new sample from the last, as a fraction of the
/// spacing before it ([`DelayRecord::record`]).
pub const CLOSEST: f64 = 0.2;

/// How near a sample may be to the start of a piece, relative to the time,
/// before it is the start again ([`DelayRecord::record`]).
const ROUNDING: f64 = 1e-12;

/// The samples of every DELAY of one program, shared by the evaluators of
/// the program in a run (the values' and the Jacobian's).
#[derive(Clone, Debug, Default)]
pub struct DelayRecord {
    /// The times of the samples, increasing.
    times: Vec<f64>,
    /// Per sample, whether it begins a piece (the sample is also the end of
    /// the piece before) and the level of the kink there: 0 for the start
    /// and a located switch, one more than the kink looked back across for
    /// a step landed on a DELAY's kink ([`DelayRecord::next_kink`]).
    starts: Vec<Option<u8>>,
    /// The indices of the samples that begin pieces, increasing (the
    /// lookups' binary searches).
    breaks: Vec<usize>,
    /// Per DELAY, its expression's value at each sample.
    values: Vec<Vec<f64>>,
    /// Per DELAY, its delay at the last sample.
    delays: Vec<f64>,
}

/// A record shared between evaluators.
pub type SharedRecord = Arc<RwLock<DelayRecord>>;

/// What the record says of a time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Looked {
    /// No sample yet.
    Empty,
    /// Within the samples: the value and its first two derivatives in time.
    Within(f64, f64, f64),
    /// After the last sample, which is at `time` with `value`.
    After {
        /// The last sample's time.
        time: f64,
        /// Its value.
        value: f64,
    },
}

impl DelayRecord {
    /// An empty record for `count` DELAYs.
    pub fn new(count: usize) -> DelayRecord {
        DelayRecord {
            values: vec![Vec::new(); count],
            delays: vec![0.0; count],
            ..DelayRecord::default()
        }
    }

    /// Adds the samples `values` (one per DELAY) at `time`, with the DELAYs'
    /// delays there; samples at `time` or after it (of a step that a switch
    /// cut short) are dropped first. `starts` begins a new piece, with its
    /// kink's level.
    ///
    /// A sample nearer the last than `CLOSEST` of the spacing before is
    /// not kept, or, when it begins a piece, the last goes instead (two
    /// starts at once are one): the polynomials' nodes stay spread, where a
    /// short step (landing on a kink, cut at a switch) would crowd them and
    /// its rounding error grow, and a piece begins where its kink is. After
    /// the start of a piece the spacing before is the last piece's, which
    /// says nothing of this one's: there only a sample within rounding of
    /// the start is crowded, so that two kinks close together (delays of
    /// 0.1 and 0.2001 read across 0.3 and 0.3001) make a short piece of
    /// their own, each kink its start.
    pub fn record(&mut self, time: f64, values: &[f64], delays: &[f64], starts: Option<u8>) {
        let keep = self.times.partition_point(|&at| at < time);
        self.times.truncate(keep);
        self.starts.truncate(keep);
        let breaks = self.breaks.partition_point(|&index| index < keep);
        self.breaks.truncate(breaks);
        for record in &mut self.values {
            record.truncate(keep);
        }
        self.delays.copy_from_slice(delays);
        let crowded = |before: f64, last: f64, starts: Option<u8>| match starts {
            Some(_) => time - last <= ROUNDING * time.abs().max(1.0),
            None => time - last < CLOSEST * (last - before),
        };
        if let [.., before, last] = self.times[..]
            && crowded(before, last, self.starts[keep - 1])
        {
            match (self.starts[keep - 1], starts) {
                // Two starts at once (a step landed on a kink, and a switch
                // right after it): one, of the lower level.
                (Some(old), Some(new)) => {
                    self.starts[keep - 1] = Some(old.min(new));
                    return;
                }
                // A start stays where it is: the sample before goes.
                (None, Some(_)) => {
                    self.times.pop();
                    self.starts.pop();
                    for record in &mut self.values {
                        record.pop();
                    }
                }
                (_, None) => return,
            }
        }
        for (record, &value) in self.values.iter_mut().zip(values) {
            record.push(value);
        }
        let starts = if self.times.is_empty() {
            starts.or(Some(0))
        } else {
            starts
        };
        if starts.is_some() {
            self.breaks.push(self.times.len());
        }
        self.times.push(time);
        self.starts.push(starts);
    }

    /// The first time more than `gap` after `time` at which a DELAY, with
    /// the delay it had at the last sample, looks back across the start of
    /// a piece whose kink is below [`KINK_LEVELS`] (where its expression's
    /// derivatives jump: the run's start, a located switch, a kink landed
    /// on before), with that kink's level: the run lands a step there, so
    /// that no step carries the kink inside it, and begins a piece there
    /// one level up. A kink within `gap` of `time` is not a step away: it
    /// is at `time` ([`DelayRecord::kink_at`]).
    pub fn next_kink(&self, time: f64, gap: f64) -> Option<(f64, u8)> {
        self.kinks_after(time + gap)
            .min_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// The lowest level of the kinks within `gap` of `time` (either side):
    /// a step that ends there has landed on them, though rounding put its
    /// end a little off (steps of a delay's length add up to a time a few
    /// ulps from the kink the delay carries forward).
    pub fn kink_at(&self, time: f64, gap: f64) -> Option<u8> {
        self.kinks_after(time - gap)
            .filter(|&(kink, _)| kink <= time + gap)
            .map(|(_, level)| level)
            .min()
    }

    /// Per DELAY, the first kink after `time` it reads across, with its
    /// level.
    fn kinks_after(&self, time: f64) -> impl Iterator<Item = (f64, u8)> + '_ {
        self.delays
            .iter()
            .filter(|&&delay| delay > 0.0)
            .filter_map(move |&delay| {
                let at = time - delay;
                let after = self.times.partition_point(|&sample| sample <= at);
                let from = self.breaks.partition_point(|&index| index < after);
                self.breaks[from..].iter().find_map(|&index| {
                    self.starts[index]
                        .filter(|&level| level < KINK_LEVELS)
                        .map(|level| (self.times[index] + delay, level))
                })
            })
    }

    /// The smallest positive delay at the last sample (infinity for none).
    pub fn smallest_delay(&self) -> f64 {
        self.delays
            .iter()
            .copied()
            .filter(|&delay| delay > 0.0)
            .fold(f64::INFINITY, f64::min)
    }

    /// DELAY `site`'s expression at time `at`.
    pub(crate) fn look(&self, site: usize, at: f64) -> Looked {
        let (Some(&last), Some(values)) = (self.times.last(), self.values.get(site)) else {
            return Looked::Empty;
        };
        if at > last {
            return Looked::After {
                time: last,
                value: values[values.len() - 1],
            };
        }
        // The sample at or after `at`, and the piece around the two samples
        // that enclose it.
        let right = self.times.partition_point(|&time| time < at);
        let left = right.saturating_sub(1);
        let above = self.breaks.partition_point(|&index| index <= left);
        let first = above.checked_sub(1).map_or(0, |below| self.breaks[below]);
        let end = self
            .breaks
            .get(above)
            .copied()
            .unwrap_or(self.times.len() - 1);
        let piece = end + 1 - first;
        let count = STENCIL.min(piece);
        let start = left
            .saturating_sub(count / 2 - 1)
            .clamp(first, end + 1 - count);
        let (value, first_derivative, second) = newton(
            &self.times[start..start + count],
            &values[start..start + count],
            at,
        );
        Looked::Within(value, first_derivative, second)
    }
}

/// The polynomial through `(times, values)` at `at`, with its first two
/// derivatives.
fn newton(times: &[f64], values: &[f64], at: f64) -> (f64, f64, f64) {
    let mut coefficients = [0.0; STENCIL];
    let count = times.len();
    coefficients[..count].copy_from_slice(values);
    for order in 1..count {
        for index in (order..count).rev() {
            coefficients[index] = (coefficients[index] - coefficients[index - 1])
                / (times[index] - times[index - order]);
        }
    }
    let (mut value, mut first, mut second) = (coefficients[count - 1], 0.0, 0.0);
    for index in (0..count - 1).rev() {
        let offset = at - times[index];
        second = second * offset + 2.0 * first;
        first = first * offset + value;
        value = value * offset + coefficients[index];
    }
    (value, first, second)
}

/// Whether a DELAY looking back to `at` reads its record (1) or its
/// history (0, before time 0): the branch a run holds it on through a step,
/// so that the jump from the history to the record is located, and the
/// record begins a piece there.
pub(crate) fn natural_branch(at: f64) -> Code {
    Code::from(at >= 0.0)
}

/// DELAY's value over any number type on `branch` ([`natural_branch`]):
/// `history`, or the record at `at` (the derivatives flowing through `at`,
/// a delay that depends on the states), and after the record's last sample
/// the straight line from it to `delayed`, the expression's value `now`.
pub(crate) fn delayed_value<T: Number>(
    record: &DelayRecord,
    site: usize,
    branch: Code,
    [now, at, delayed, history]: [&T; 4],
) -> T {
    if branch == 0 {
        return history.clone();
    }
    match record.look(site, at.value()) {
        Looked::Empty => delayed.clone(),
        Looked::Within(value, first, second) => at.chain(value, || (first, second)),
        Looked::After {
            time: last,
            value: sample,
        } => {
            if now.value() <= last {
                return delayed.clone();
            }
            let last_time = T::from(last);
            let weight = (at.clone() - last_time.clone()) / (now.clone() - last_time);
            let sample = T::from(sample);
            sample.clone() + (delayed.clone() - sample) * weight
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_record_gives_a_polynomial_of_degree_seven_exactly() {
        let mut record = DelayRecord::new(1);
        let cubic = |t: f64| 1.0 - 2.0 * t + 0.5 * t.powi(3) - 0.1 * t.powi(5) + 0.01 * t.powi(7);
        for index in 0..=20 {
            let time = f64::from(index) * 0.1;
            record.record(time, &[cubic(time)], &[0.3], None);
        }
        for at in [0.0, 0.05, 0.77, 1.234, 2.0] {
            let Looked::Within(value, first, second) = record.look(0, at) else {
                panic!("within");
            };
            assert!((value - cubic(at)).abs() < 1e-12, "{at}");
            let slope = -2.0 + 1.5 * at * at - 0.5 * at.powi(4) + 0.07 * at.powi(6);
            let curvature = 3.0 * at - 2.0 * at.powi(3) + 0.42 * at.powi(5);
            assert!(
                (first - slope).abs() < 1e-9,
                "{at}: {first} against {slope}"
            );
            assert!((second - curvature).abs() < 1e-7, "{at}");
        }
        assert_eq!(
            record.look(0, 2.5),
            Looked::After {
                time: 2.0,
                value: cubic(2.0)
            }
        );
        assert_eq!(record.smallest_delay(), 0.3);
        // Over dual numbers the slope flows through the time looked back
        // to (a delay that depends on the states); the history branch and
        // the expression now carry their own.
        type Dual = num_dual::DualSVec64<1>;
        let seed = <Dual as crate::number::Directional>::variable(0.0, 0, 1);
        let slope_of = |number: &Dual| crate::number::Directional::gradient(number, 1)[0];
        let at = seed + 0.77;
        let now = Dual::from(1.07);
        let delayed = seed * 3.0 + 5.0;
        let history = seed * 0.5 - 1.0;
        let read = delayed_value(&record, 0, 1, [&now, &at, &delayed, &history]);
        let slope = -2.0 + 1.5 * 0.77f64.powi(2) - 0.5 * 0.77f64.powi(4) + 0.07 * 0.77f64.powi(6);
        assert!((read.re - cubic(0.77)).abs() < 1e-12);
        assert!(
            (slope_of(&read) - slope).abs() < 1e-9,
            "{read} against {slope}"
        );
        let before = delayed_value(&record, 0, 0, [&now, &at, &delayed, &history]);
        assert_eq!((before.re, slope_of(&before)), (-1.0, 0.5));
        // After the last sample: the line from it to the expression now.
        let (now, at) = (Dual::from(3.0), Dual::from(2.5));
        let read = delayed_value(&record, 0, 1, [&now, &at, &delayed, &history]);
        assert!((read.re - (cubic(2.0) + (5.0 - cubic(2.0)) * 0.5)).abs() < 1e-12);
        assert!(
            (slope_of(&read) - 1.5).abs() < 1e-12,
            "half the expression's slope"
        );
    }

    #[test]
    fn no_polynomial_reaches_across_a_new_piece() {
        let mut record = DelayRecord::new(1);
        // |t - 1|: a kink at the piece's start.
        for index in 0..=20 {
            let time = f64::from(index) * 0.1;
            record.record(
                time,
                &[(time - 1.0).abs()],
                &[0.0],
                (index == 10).then_some(0),
            );
        }
        for at in [0.55, 0.95, 1.05, 1.45] {
            let Looked::Within(value, ..) = record.look(0, at) else {
                panic!("within");
            };
            assert!((value - (at - 1.0).abs()).abs() < 1e-12, "{at}: {value}");
        }
        // A step cut short: its samples after the switch are dropped.
        record.record(1.5, &[7.0], &[0.0], Some(0));
        assert_eq!(
            record.look(0, 1.6),
            Looked::After {
                time: 1.5,
                value: 7.0
            }
        );
        assert_eq!(record.smallest_delay(), f64::INFINITY);
    }
}
