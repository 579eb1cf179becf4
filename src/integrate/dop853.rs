//! DOP853: Dormand and Prince's explicit Runge–Kutta pair of order 8 with
//! error estimators of orders 5 and 3 and a dense output of order 7
//! (Hairer, Nørsett, Wanner I; coefficients as in `dop853.f`).
//!
//! Stages are numbered from 0: `k[0] = f(t, y)`, `k[1..12]` the method's
//! other eleven stages, `k[12] = f(t + h, y_new)` (the next step's first),
//! `k[13..16]` the three stages that only the dense output uses.

use super::core::{Core, evaluate};
use super::spectral::SpectralRadius;
use super::{IntegrateError, Rejection, System};

/// The order of the local error the step size control works with.
pub(super) const ORDER: i32 = 8;

/// Safety factor of the step size control.
const SAFETY: f64 = 0.9;
/// Bounds of `h / h_new`: the step grows at most 6-fold, shrinks at most
/// 3-fold after an accepted step.
const SHRINK_MOST: f64 = 1.0 / 0.333;
const GROW_MOST: f64 = 1.0 / 6.0;
/// Step factor after a trial state the system refuses.
const FAILURE_SHRINK: f64 = 0.5;

/// `h |λ|` near the edge of DOP853's stability region along the negative
/// real axis (Hairer's 6.1).
pub(super) const STABILITY_EDGE: f64 = 6.1;

/// `h |λ|` within which the dense output follows the stiffest mode. For
/// `y' = λ y` its polynomial in `z = h λ` is off `e^(θz)` inside the step
/// by at most 0.003 of the mode at `|z| = 3` on the negative real axis
/// (0.014 on the imaginary), 0.05 at 4, 0.9 at 5, and 10 to 30 times the
/// mode at the edge of stability (6.1), where the error control holds a
/// stiff run's steps while their ends stay right: a sensor lag, `λ = −50`,
/// gave rows 2 000 × rtol off; held to 4.5, lags excited by a set point's
/// ramp were still 60 to 160 × rtol off at rtol 1e-9, held to 3 under 6.
const DENSE_EDGE: f64 = 3.0;
/// `h |λ|` beyond which `|λ|` is estimated at every step; within it, every
/// [`ESTIMATE_EVERY`] steps.
const WATCH_EDGE: f64 = 2.0;
/// Power iterations at most at a start, before the first step.
const START_ITERATIONS: usize = 6;
/// Accepted steps between two estimates of `|λ|` while `h |λ|` is within
/// [`WATCH_EDGE`].
const ESTIMATE_EVERY: usize = 8;

/// How the stiffness test runs: how often, against which `h |λ|`, and how
/// many tests beyond it make a problem stiff.
#[derive(Clone, Copy)]
pub(super) struct StiffnessTest {
    /// The test runs every this many accepted steps, and at every step
    /// while the last test found `h |λ|` beyond the edge.
    pub every: usize,
    /// `h |λ|` beyond which a test counts as stiff.
    pub edge: f64,
    /// Tests beyond the edge, with fewer than [`NONSTIFF_RESET`] tests
    /// within it between them, that make a problem stiff.
    pub tests: u32,
}

/// Hairer's stiffness test (`dop853.f`, `NSTIFF`): every 1000 accepted
/// steps, against the edge of the stability region, 15 tests.
pub(super) const HAIRER_TEST: StiffnessTest = StiffnessTest {
    every: 1000,
    edge: STABILITY_EDGE,
    tests: 15,
};
/// Tests within the edge in a row that forget the ones beyond it (6).
const NONSTIFF_RESET: u32 = 6;

/// A stage: its node and its coefficients on earlier stages (stage, a).
struct Stage {
    c: f64,
    a: &'static [(usize, f64)],
}

/// Stages 1 to 11.
#[allow(clippy::excessive_precision)]
const STAGES: [Stage; 11] = [
    Stage {
        c: 0.526001519587677318785587544488e-1,
        a: &[(0, 5.26001519587677318785587544488e-2)],
    },
    Stage {
        c: 0.789002279381515978178381316732e-1,
        a: &[
            (0, 1.97250569845378994544595329183e-2),
            (1, 5.91751709536136983633785987549e-2),
        ],
    },
    Stage {
        c: 0.118350341907227396726757197510,
        a: &[
            (0, 2.95875854768068491816892993775e-2),
            (2, 8.87627564304205475450678981324e-2),
        ],
    },
    Stage {
        c: 0.281649658092772603273242802490,
        a: &[
            (0, 2.41365134159266685502369798665e-1),
            (2, -8.84549479328286085344864962717e-1),
            (3, 9.24834003261792003115737966543e-1),
        ],
    },
    Stage {
        c: 0.333333333333333333333333333333,
        a: &[
            (0, 3.7037037037037037037037037037e-2),
            (3, 1.70828608729473871279604482173e-1),
            (4, 1.25467687566822425016691814123e-1),
        ],
    },
    Stage {
        c: 0.25,
        a: &[
            (0, 3.7109375e-2),
            (3, 1.70252211019544039314978060272e-1),
            (4, 6.02165389804559606850219397283e-2),
            (5, -1.7578125e-2),
        ],
    },
    Stage {
        c: 0.307692307692307692307692307692,
        a: &[
            (0, 3.70920001185047927108779319836e-2),
            (3, 1.70383925712239993810214054705e-1),
            (4, 1.07262030446373284651809199168e-1),
            (5, -1.53194377486244017527936158236e-2),
            (6, 8.27378916381402288758473766002e-3),
        ],
    },
    Stage {
        c: 0.651282051282051282051282051282,
        a: &[
            (0, 6.24110958716075717114429577812e-1),
            (3, -3.36089262944694129406857109825),
            (4, -8.68219346841726006818189891453e-1),
            (5, 2.75920996994467083049415600797e1),
            (6, 2.01540675504778934086186788979e1),
            (7, -4.34898841810699588477366255144e1),
        ],
    },
    Stage {
        c: 0.6,
        a: &[
            (0, 4.77662536438264365890433908527e-1),
            (3, -2.48811461997166764192642586468),
            (4, -5.90290826836842996371446475743e-1),
            (5, 2.12300514481811942347288949897e1),
            (6, 1.52792336328824235832596922938e1),
            (7, -3.32882109689848629194453265587e1),
            (8, -2.03312017085086261358222928593e-2),
        ],
    },
    Stage {
        c: 0.857142857142857142857142857142,
        a: &[
            (0, -9.3714243008598732571704021658e-1),
            (3, 5.18637242884406370830023853209),
            (4, 1.09143734899672957818500254654),
            (5, -8.14978701074692612513997267357),
            (6, -1.85200656599969598641566180701e1),
            (7, 2.27394870993505042818970056734e1),
            (8, 2.49360555267965238987089396762),
            (9, -3.0467644718982195003823669022),
        ],
    },
    Stage {
        c: 1.0,
        a: &[
            (0, 2.27331014751653820792359768449),
            (3, -1.05344954667372501984066689879e1),
            (4, -2.00087205822486249909675718444),
            (5, -1.79589318631187989172765950534e1),
            (6, 2.79488845294199600508499808837e1),
            (7, -2.85899827713502369474065508674),
            (8, -8.87285693353062954433549289258),
            (9, 1.23605671757943030647266201528e1),
            (10, 6.43392746015763530355970484046e-1),
        ],
    },
];

/// The weights of the 8th-order solution.
#[allow(clippy::excessive_precision)]
const WEIGHTS: [(usize, f64); 8] = [
    (0, 5.42937341165687622380535766363e-2),
    (5, 4.45031289275240888144113950566),
    (6, 1.89151789931450038304281599044),
    (7, -5.8012039600105847814672114227),
    (8, 3.1116436695781989440891606237e-1),
    (9, -1.52160949662516078556178806805e-1),
    (10, 2.01365400804030348374776537501e-1),
    (11, 4.47106157277725905176885569043e-2),
];

/// The 5th-order error estimator: its weights minus the 8th order's.
#[allow(clippy::excessive_precision)]
const ERROR5: [(usize, f64); 8] = [
    (0, 0.1312004499419488073250102996e-1),
    (5, -0.1225156446376204440720569753e1),
    (6, -0.4957589496572501915214079952),
    (7, 0.1664377182454986536961530415e1),
    (8, -0.3503288487499736816886487290),
    (9, 0.3341791187130174790297318841),
    (10, 0.8192320648511571246570742613e-1),
    (11, -0.2235530786388629525884427845e-1),
];

/// The 3rd-order solution's weights; its error estimate is the 8th-order
/// increment minus these.
#[allow(clippy::excessive_precision)]
const WEIGHTS3: [(usize, f64); 3] = [
    (0, 0.244094488188976377952755905512),
    (8, 0.733846688281611857341361741547),
    (11, 0.220588235294117647058823529412e-1),
];

/// Stages 13 to 15, for the dense output only.
#[allow(clippy::excessive_precision)]
const DENSE_STAGES: [Stage; 3] = [
    Stage {
        c: 0.1,
        a: &[
            (0, 5.61675022830479523392909219681e-2),
            (6, 2.53500210216624811088794765333e-1),
            (7, -2.46239037470802489917441475441e-1),
            (8, -1.24191423263816360469010140626e-1),
            (9, 1.5329179827876569731206322685e-1),
            (10, 8.20105229563468988491666602057e-3),
            (11, 7.56789766054569976138603589584e-3),
            (12, -8.298e-3),
        ],
    },
    Stage {
        c: 0.2,
        a: &[
            (0, 3.18346481635021405060768473261e-2),
            (5, 2.83009096723667755288322961402e-2),
            (6, 5.35419883074385676223797384372e-2),
            (7, -5.49237485713909884646569340306e-2),
            (10, -1.08347328697249322858509316994e-4),
            (11, 3.82571090835658412954920192323e-4),
            (12, -3.40465008687404560802977114492e-4),
            (13, 1.41312443674632500278074618366e-1),
        ],
    },
    Stage {
        c: 0.777777777777777777777777777778,
        a: &[
            (0, -4.28896301583791923408573538692e-1),
            (5, -4.69762141536116384314449447206),
            (6, 7.68342119606259904184240953878),
            (7, 4.06898981839711007970213554331),
            (8, 3.56727187455281109270669543021e-1),
            (12, -1.39902416515901462129418009734e-3),
            (13, 2.9475147891527723389556272149),
            (14, -9.15095847217987001081870187138),
        ],
    },
];

/// The last four coefficients of the dense output polynomial, each `h`
/// times a combination of all 16 stages.
#[allow(clippy::excessive_precision)]
const DENSE: [[(usize, f64); 12]; 4] = [
    [
        (0, -0.84289382761090128651353491142e1),
        (5, 0.56671495351937776962531783590),
        (6, -0.30689499459498916912797304727e1),
        (7, 0.23846676565120698287728149680e1),
        (8, 0.21170345824450282767155149946e1),
        (9, -0.87139158377797299206789907490),
        (10, 0.22404374302607882758541771650e1),
        (11, 0.63157877876946881815570249290),
        (12, -0.88990336451333310820698117400e-1),
        (13, 0.18148505520854727256656404962e2),
        (14, -0.91946323924783554000451984436e1),
        (15, -0.44360363875948939664310572000e1),
    ],
    [
        (0, 0.10427508642579134603413151009e2),
        (5, 0.24228349177525818288430175319e3),
        (6, 0.16520045171727028198505394887e3),
        (7, -0.37454675472269020279518312152e3),
        (8, -0.22113666853125306036270938578e2),
        (9, 0.77334326684722638389603898808e1),
        (10, -0.30674084731089398182061213626e2),
        (11, -0.93321305264302278729567221706e1),
        (12, 0.15697238121770843886131091075e2),
        (13, -0.31139403219565177677282850411e2),
        (14, -0.93529243588444783865713862664e1),
        (15, 0.35816841486394083752465898540e2),
    ],
    [
        (0, 0.19985053242002433820987653617e2),
        (5, -0.38703730874935176555105901742e3),
        (6, -0.18917813819516756882830838328e3),
        (7, 0.52780815920542364900561016686e3),
        (8, -0.11573902539959630126141871134e2),
        (9, 0.68812326946963000169666922661e1),
        (10, -0.10006050966910838403183860980e1),
        (11, 0.77771377980534432092869265740),
        (12, -0.27782057523535084065932004339e1),
        (13, -0.60196695231264120758267380846e2),
        (14, 0.84320405506677161018159903784e2),
        (15, 0.11992291136182789328035130030e2),
    ],
    [
        (0, -0.25693933462703749003312586129e2),
        (5, -0.15418974869023643374053993627e3),
        (6, -0.23152937917604549567536039109e3),
        (7, 0.35763911791061412378285349910e3),
        (8, 0.93405324183624310003907691704e2),
        (9, -0.37458323136451633156875139351e2),
        (10, 0.10409964950896230045147246184e3),
        (11, 0.29840293426660503123344363579e2),
        (12, -0.43533456590011143754432175058e2),
        (13, 0.96324553959188282948394950600e2),
        (14, -0.39177261675615439165231486172e2),
        (15, -0.14972683625798562581422125276e3),
    ],
];

/// DOP853's working storage and its dense output over the last step.
pub(super) struct Dop853 {
    n: usize,
    /// The 16 stages, one after another.
    k: Vec<f64>,
    /// A stage's argument.
    stage_y: Vec<f64>,
    /// The 8th-order solution at the end of the trial step.
    y_new: Vec<f64>,
    /// The eight coefficient vectors of the dense output polynomial.
    dense: Vec<f64>,
    /// The length of the last accepted step.
    h_dense: f64,
    /// The last trial step was rejected: the next accepted one may not
    /// propose a larger step.
    after_rejection: bool,
    /// Hairer's stiffness test over the accepted steps.
    stiffness: Stiffness,
    /// How the stiffness test runs.
    test: StiffnessTest,
    /// Power iteration for the largest `|λ|` of the Jacobian.
    spectral: SpectralRadius,
    /// Its last estimate.
    lambda: Option<f64>,
    /// Accepted steps since that estimate.
    since_estimate: usize,
}

/// The state of Hairer's stiffness test: `h |λ|` estimated on the last
/// stage and the step's end, `h |f(t+h, y_new) - f(t+h, y_12)| / |y_new -
/// y_12|`, counted against the edge of the stability region; a step held
/// to [`DENSE_EDGE`] whose proposal passed the edge of stability counts
/// beyond it (Hairer's estimate misses a stiff mode barely excited).
#[derive(Clone, Default)]
struct Stiffness {
    /// The estimate of the step being finished, when a test is due.
    pending: Option<f64>,
    /// Tests beyond the edge since the last run of tests within it.
    beyond: u32,
    /// Tests within the edge in a row.
    within: u32,
    /// The start of the step at which the test found the problem stiff.
    found_at: Option<f64>,
}

impl Stiffness {
    /// Counts the estimate of the step from `t` that was just accepted.
    fn count(&mut self, t: f64, test: &StiffnessTest) {
        let Some(h_lambda) = self.pending.take() else {
            return;
        };
        if h_lambda > test.edge {
            self.within = 0;
            self.beyond += 1;
            if self.beyond == test.tests && self.found_at.is_none() {
                self.found_at = Some(t);
            }
        } else {
            self.within += 1;
            if self.within == NONSTIFF_RESET {
                self.beyond = 0;
            }
        }
    }
}

impl Dop853 {
    /// Working storage for `n` components, the stiffness test run as
    /// `test` says ([`HAIRER_TEST`] for DOP853 alone).
    pub fn new(n: usize, test: StiffnessTest) -> Self {
        Dop853 {
            n,
            k: vec![0.0; 16 * n],
            stage_y: vec![0.0; n],
            y_new: vec![0.0; n],
            dense: vec![0.0; 8 * n],
            h_dense: 0.0,
            after_rejection: false,
            stiffness: Stiffness::default(),
            test: StiffnessTest {
                every: test.every.max(1),
                ..test
            },
            spectral: SpectralRadius::new(n),
            lambda: None,
            since_estimate: 0,
        }
    }

    /// The start of the step at which the stiffness test first found the
    /// problem stiff: `h |λ|` beyond its edge (Hairer's: 6.1, the edge of
    /// DOP853's stability region) in its number of tests (Hairer's: 15),
    /// with fewer than 6 within it in a row between them. The steps are
    /// then held near that edge by stability, not accuracy.
    pub fn stiff_from(&self) -> Option<f64> {
        self.stiffness.found_at
    }

    /// Takes over `other`'s stiffness test where it stands and its estimate
    /// of `|λ|`: a fresh start at an event goes on counting (a run whose
    /// every step crosses a branch boundary is still found stiff), and its
    /// first step, chosen anew, is held by the stiffest mode as the last,
    /// which the end of that step estimates again (the event may have
    /// changed it: a contact's spring met).
    pub fn continue_from(&mut self, other: &Dop853) {
        self.stiffness = other.stiffness.clone();
        self.spectral = other.spectral.clone();
        self.lambda = other.lambda;
        self.since_estimate = ESTIMATE_EVERY;
    }

    /// Forgets the last step.
    pub fn restart(&mut self) {
        self.after_rejection = false;
    }

    /// One accepted step that does not pass `t_end`.
    pub fn step<S: System + ?Sized>(
        &mut self,
        core: &mut Core,
        system: &mut S,
        t_end: f64,
    ) -> Result<(), IntegrateError<S::Error>> {
        let mut cause = None;
        if self.lambda.is_none() {
            // The first step, as any, is held by the stiffest mode: its
            // size is only a guess from the rates.
            for _ in 0..START_ITERATIONS {
                let estimate =
                    self.spectral
                        .iterate(system, &mut core.stats, core.t, &core.y, &core.dy);
                self.lambda = estimate.or(self.lambda);
                if estimate.is_none() || self.spectral.settled() {
                    break;
                }
            }
        }
        if let Some(lambda) = self.lambda {
            core.h = core.h.min(DENSE_EDGE / lambda);
        }
        loop {
            if core.floor_due(self.after_rejection) {
                core.update_floor(system);
            }
            let (h, lands) = core.trial(t_end, &mut cause)?;
            let (err, plain) = match self.stages(core, system, h) {
                Ok(err) => err,
                Err(why) => {
                    core.reject(h * FAILURE_SHRINK, why, &mut cause);
                    self.after_rejection = true;
                    continue;
                }
            };
            let shrink = err.powf(1.0 / f64::from(ORDER)) / SAFETY;
            if err > 1.0 {
                core.reject(
                    h / shrink.min(SHRINK_MOST),
                    Rejection::Tolerance,
                    &mut cause,
                );
                self.after_rejection = true;
                continue;
            }
            if let Err(why) = self.finish(core, system, h) {
                core.reject(h * FAILURE_SHRINK, why, &mut cause);
                self.after_rejection = true;
                continue;
            }
            core.count_rounding_limited(plain);
            let mut h_new = h / shrink.clamp(GROW_MOST, SHRINK_MOST);
            if self.after_rejection {
                h_new = h_new.min(h);
            }
            self.after_rejection = false;
            // A step shortened to land keeps the longer step it replaced.
            h_new = if lands { h_new.max(core.h) } else { h_new };
            // Held by the stiffest mode, not by accuracy; a stiff step where
            // accuracy alone would pass the edge of stability.
            if let Some(lambda) = self.lambda
                && h_new * lambda > DENSE_EDGE
            {
                if h_new * lambda > STABILITY_EDGE {
                    self.stiffness.pending = self.stiffness.pending.map(|_| f64::INFINITY);
                }
                h_new = DENSE_EDGE / lambda;
            }
            core.h = h_new;
            self.h_dense = h;
            self.stiffness.count(core.t, &self.test);
            std::mem::swap(&mut core.y, &mut self.y_new);
            core.dy.copy_from_slice(&self.k[12 * self.n..13 * self.n]);
            core.advance(h, lands, t_end);
            return Ok(());
        }
    }

    /// The stages of a trial step of size `h` and its error in units of the
    /// error scale, and in units of the tolerance alone.
    fn stages<S: System + ?Sized>(
        &mut self,
        core: &mut Core,
        system: &mut S,
        h: f64,
    ) -> Result<(f64, f64), Rejection<S::Error>> {
        let n = self.n;
        self.k[..n].copy_from_slice(&core.dy);
        for (index, stage) in STAGES.iter().enumerate() {
            self.evaluate_stage(core, system, h, index + 1, stage)?;
        }
        combine(&core.y, h, &self.k, n, &WEIGHTS, &mut self.y_new);
        // Hairer's blend, which the 3rd-order estimate tempers on a smooth
        // solution where the steps are small enough for the estimates'
        // orders to show; the 5th-order estimate alone near a weak
        // singularity and on the first step of a start, whose size is only
        // `hinit`'s guess (a contact crossed in two or three steps of a
        // first step too large: 380 x rtol blended, 1.4 x without).
        let blend = core.smooth && core.stats.steps > 0;
        // The largest over the norm's groups. Each state's scale is
        // `atol + rtol |y|` at the step's start, as Radau5's (and CVODE's
        // weights): not Hairer's `max(|y0|, |y1|)`, with which a trial step
        // that blows up widens its own tolerance and is accepted (a ball
        // struck on a stiff contact at rtol 0.1 left at 130 m/s).
        // Each state's scale is also widened to what rounding leaves in it
        // over the step ([`Core::error_scale`]); `plain` is the error
        // against the tolerance alone.
        let (mut err, mut plain) = (0.0_f64, 0.0_f64);
        for group in &core.groups {
            // The sums of the squared 5th- and 3rd-order estimates, against
            // the widened scale and against the tolerance.
            let (mut widened, mut tolerance) = ([0.0; 2], [0.0; 2]);
            for i in group.clone() {
                let scale = core.error_scale(i, h);
                let at = |stage: usize| self.k[stage * n + i];
                let increment: f64 = WEIGHTS.iter().map(|&(j, b)| b * at(j)).sum();
                let third = increment - WEIGHTS3.iter().map(|&(j, b)| b * at(j)).sum::<f64>();
                let fifth: f64 = ERROR5.iter().map(|&(j, e)| e * at(j)).sum();
                widened[0] += (fifth / scale.scale).powi(2);
                widened[1] += (third / scale.scale).powi(2);
                tolerance[0] += (fifth / scale.tolerance).powi(2);
                tolerance[1] += (third / scale.tolerance).powi(2);
            }
            let size = group.len() as f64;
            let group_err = |[err5, err3]: [f64; 2]| {
                if blend {
                    let denominator = if err5 + 0.01 * err3 > 0.0 {
                        err5 + 0.01 * err3
                    } else {
                        1.0
                    };
                    h * err5 / (size * denominator).sqrt()
                } else {
                    h * (err5 / size).sqrt()
                }
            };
            let group_err_widened = group_err(widened);
            if !group_err_widened.is_finite() {
                return Err(Rejection::NonFinite);
            }
            err = err.max(group_err_widened);
            plain = plain.max(group_err(tolerance));
        }
        if err.is_finite() {
            Ok((err, plain))
        } else {
            Err(Rejection::NonFinite)
        }
    }

    /// For an accepted trial step: `f` at its end and the dense output's
    /// three stages and coefficients.
    fn finish<S: System + ?Sized>(
        &mut self,
        core: &mut Core,
        system: &mut S,
        h: f64,
    ) -> Result<(), Rejection<S::Error>> {
        let n = self.n;
        let t_end = core.t + h;
        evaluate(
            system,
            &mut core.stats,
            t_end,
            &self.y_new,
            &mut self.k[12 * n..13 * n],
        )?;
        self.since_estimate += 1;
        let due = self
            .lambda
            .is_none_or(|lambda| h * lambda > WATCH_EDGE || self.since_estimate >= ESTIMATE_EVERY);
        if due {
            self.since_estimate = 0;
            let end_rate = &self.k[12 * n..13 * n];
            let estimate =
                self.spectral
                    .iterate(system, &mut core.stats, t_end, &self.y_new, end_rate);
            self.lambda = estimate.or(self.lambda);
        }
        let accepted = core.stats.steps + 1;
        self.stiffness.pending = (accepted.is_multiple_of(self.test.every)
            || self.stiffness.beyond > 0)
            .then(|| self.stiffness_estimate(h));
        for (index, stage) in DENSE_STAGES.iter().enumerate() {
            self.evaluate_stage(core, system, h, index + 13, stage)?;
        }
        let (y, y_new, k) = (&core.y, &self.y_new, &self.k);
        let (first, last) = (&k[..n], &k[12 * n..13 * n]);
        let (ends, high) = self.dense.split_at_mut(4 * n);
        for i in 0..n {
            let difference = y_new[i] - y[i];
            let spline = h * first[i] - difference;
            ends[i] = y[i];
            ends[n + i] = difference;
            ends[2 * n + i] = spline;
            ends[3 * n + i] = difference - h * last[i] - spline;
        }
        for (r, row) in DENSE.iter().enumerate() {
            for i in 0..n {
                high[r * n + i] = h * row.iter().map(|&(j, d)| d * k[j * n + i]).sum::<f64>();
            }
        }
        Ok(())
    }

    /// `h |λ|` of the step of size `h` being finished: the last stage (at
    /// `t + h`, its argument still in `stage_y`) against the step's end.
    fn stiffness_estimate(&self, h: f64) -> f64 {
        let n = self.n;
        let (last_rate, end_rate) = (&self.k[11 * n..12 * n], &self.k[12 * n..13 * n]);
        let squares =
            |a: &[f64], b: &[f64]| -> f64 { a.iter().zip(b).map(|(a, b)| (a - b) * (a - b)).sum() };
        let rates = squares(end_rate, last_rate);
        let states = squares(&self.y_new, &self.stage_y);
        if states > 0.0 {
            h * (rates / states).sqrt()
        } else {
            0.0
        }
    }

    /// Evaluates stage `index` of a step of size `h` from `core.y`.
    fn evaluate_stage<S: System + ?Sized>(
        &mut self,
        core: &mut Core,
        system: &mut S,
        h: f64,
        index: usize,
        stage: &Stage,
    ) -> Result<(), Rejection<S::Error>> {
        let n = self.n;
        combine(&core.y, h, &self.k, n, stage.a, &mut self.stage_y);
        let out = &mut self.k[index * n..(index + 1) * n];
        evaluate(
            system,
            &mut core.stats,
            core.t + stage.c * h,
            &self.stage_y,
            out,
        )
    }

    /// The 7th-order polynomial of the last step at `t`.
    pub fn dense(&self, core: &Core, t: f64, out: &mut [f64]) {
        let s = (t - core.t_previous) / self.h_dense;
        let r = 1.0 - s;
        let n = self.n;
        let c = |index: usize, i: usize| self.dense[index * n + i];
        for (i, value) in out.iter_mut().enumerate() {
            let high = c(4, i) + s * (c(5, i) + r * (c(6, i) + s * c(7, i)));
            *value = c(0, i) + s * (c(1, i) + r * (c(2, i) + s * (c(3, i) + r * high)));
        }
    }
}

/// `out = y + h Σ a_j k_j` over the stages `j` that `coefficients` name.
fn combine(y: &[f64], h: f64, k: &[f64], n: usize, coefficients: &[(usize, f64)], out: &mut [f64]) {
    out.copy_from_slice(y);
    for &(j, a) in coefficients {
        for (value, rate) in out.iter_mut().zip(&k[j * n..(j + 1) * n]) {
            *value += h * a * rate;
        }
    }
}
