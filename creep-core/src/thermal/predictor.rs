//! The local temperature of a bristle move (Eq. 4.35) by a predictor-corrector with a count of law evaluations fixed by the predictor's miss: the cheaper alternative to the exact solve ([`super::solve_self_heating`]).

/// How the local temperature of a bristle move (Eq. 4.35) is solved (configuration key
/// `temperature_solve`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TemperatureSolve {
    /// The implicit solve of T = t_hist + self_c q(T) to the tolerance
    /// [`temperature_tolerance`] (the reference): 2-5 evaluations of the law per move.
    Exact,
    /// A predictor-corrector with a count of evaluations fixed by the predictor's miss: the
    /// law at the predictor t_hist + self_c q0 (q0 the heat of the move's start stress over its
    /// rigid slip) and at the fixed-point step from it,
    /// the root of the secant through both and the state interpolated there
    /// ([`solve_predictor_corrector`]); on the scalar path with a derivative, one evaluation
    /// and a Newton step. Where the two evaluations do not bracket a root on one branch of the
    /// law, the exact solve runs. The default: within 0.025 % of the exact solve in F_x,
    /// P_fric and the T_max rise on the accuracy benchmark, at 70-85 % of its cost.
    #[default]
    PredictorCorrector,
}

impl TemperatureSolve {
    /// Every solve, in the order of [`Self::NAMES`].
    pub const ALL: [TemperatureSolve; 2] = [Self::Exact, Self::PredictorCorrector];
    /// The accepted names, for messages.
    pub const NAMES: &'static str = "exact, predictor";

    /// The solve's name in configurations, the CLI and the FMU.
    pub fn name(self) -> &'static str {
        match self {
            Self::Exact => "exact",
            Self::PredictorCorrector => "predictor",
        }
    }

    /// The solve of a name, None for an unknown name.
    pub fn by_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }
}

/// The predictor's miss of the predictor-corrector ([`solve_predictor_corrector`]) above
/// which it takes a third evaluation, relative to the largest temperature coefficient's
/// scale 1 / cmax: 0.01, a change of the softening factors exp(-c T) by 1 %. On the accuracy
/// benchmark's cases (docs/model.md section 9) the largest difference from the exact solve
/// was 0.15 % in F_x with two evaluations always, 0.014 % with this; the third evaluation
/// then runs in few moves (the instructions of a table4.1 step on 20x3 grow by 0.7 %).
pub const PC_MISS_REL: f64 = 0.01;

/// The largest slope self_c dq/dT of the heat's rise with T between the predictor-corrector's
/// first two trials: beyond it the exact solve runs (it searches for the smallest root). Below
/// it g(T) = t_hist + self_c q(T) - T falls with a slope of at least 1/2 and the secant's root
/// lies within twice the predictor's miss.
const PC_SLOPE_MAX: f64 = 0.5;

/// The predictor's miss (K) above which the predictor-corrector
/// ([`solve_predictor_corrector`]) takes its third evaluation, for a largest temperature
/// coefficient `cmax` (1/degC) of the material laws: [`PC_MISS_REL`] / cmax (infinite without
/// one).
pub fn pc_miss(cmax: f64) -> f64 {
    if cmax > 0.0 {
        PC_MISS_REL / cmax
    } else {
        f64::INFINITY
    }
}

/// The predictor-corrector solve of T = t_hist + self_c q(T) (Eq. 4.35) in two or three
/// evaluations of the law, with no tolerance:
/// 1. the law at the predictor t0 = t_hist + self_c `q_pred`;
/// 2. the law at the fixed-point step t1 = t_hist + self_c q(t0): with g(T) = t_hist + self_c
///    q(T) - T, g(t1) = self_c (q(t1) - q(t0)) = L g(t0), L the secant's slope of self_c q;
///    where L < [`PC_SLOPE_MAX`] (the heat falls with T, or rises slowly), the secant's root
///    t2 = t0 + w (t1 - t0), w = 1 / (1 - L) (between t0 and t1 where the heat falls), gives
///    the temperature and `lerp` the state there;
/// 3. where the heat rises with T (0 < L), or where the predictor misses by more than `miss`
///    (K), the law at t2, and the secant through t2 and the end of the first two on the root's
///    side; between one and two `miss` the result is blended linearly from the two-evaluation
///    one to this, so that it stays continuous in the inputs.
///
/// The two-evaluation result misses the root by about g''/g' (t1 - t0)^2, and the state the
/// state at the root by about its curvature in T times (t1 - t0)^2: an error of the order of
/// the square of the predictor's miss |t1 - t0|, which the third evaluation squares again.
/// A count of evaluations fixed by the miss, not by a tolerance, makes the result a smooth
/// function of the inputs wherever the states lie on one branch of the law.
///
/// None (the caller then runs the exact solve) where a trial has no heat, where `unique(state)`
/// refuses a state (one the exact solve must search from t_hist for), where the heat rises
/// with T faster than [`PC_SLOPE_MAX`] between the first two, or where `lerp` refuses a pair
/// (a change of the law's branch between them).
pub fn solve_predictor_corrector<S: Copy>(
    t_hist: f64,
    self_c: f64,
    q_pred: f64,
    miss: f64,
    eval: impl Fn(f64) -> (S, f64),
    lerp: impl Fn(&S, &S, f64) -> Option<S>,
    unique: impl Fn(&S) -> bool,
) -> Option<(S, f64)> {
    let t0 = t_hist + self_c * q_pred;
    let (s0, q0) = eval(t0);
    if !(q0 > 0.0 && unique(&s0)) {
        return None;
    }
    let t1 = t_hist + self_c * q0;
    let g0 = t1 - t0;
    if g0 == 0.0 {
        return Some((s0, q0));
    }
    let (s1, q1) = eval(t1);
    if !(q1 > 0.0 && unique(&s1)) {
        return None;
    }
    // g(t1) = self_c (q1 - q0) = L g0 with L the secant's slope of self_c q(T): of g0's
    // opposite sign where the heat falls with T; where it rises, the secant's root lies beyond
    // t1 and is the only one near while L < 1/2 (as the exact scalar solve's bound)
    let g1 = self_c * (q1 - q0);
    let slope = g1 / g0;
    if slope.is_nan() || slope >= PC_SLOPE_MAX {
        return None;
    }
    let w = g0 / (g0 - g1);
    let s = lerp(&s0, &s1, w)?;
    let q = q0 + w * (q1 - q0);
    // the blend's weight of the three-evaluation result: 0 up to one miss, 1 from two; 1
    // where the heat rises with T (there the secant extrapolates, and two evaluations missed
    // P_fric by up to 0.3 % on the dry sine; at L = 0 both results are the state at t1)
    let beta = if slope > 0.0 {
        1.0
    } else {
        (g0.abs() / miss - 1.0).clamp(0.0, 1.0)
    };
    if beta == 0.0 {
        return Some((s, q));
    }
    let t2 = t0 + w * g0;
    let (s2, q2) = eval(t2);
    if !(q2 > 0.0 && unique(&s2)) {
        return None;
    }
    let g2 = t_hist + self_c * q2 - t2;
    // the end of the bracket on the root's side of t2: t1 where g2 has g0's sign
    let (se, qe, ge) = if (g2 > 0.0) == (g0 > 0.0) {
        (s1, q1, g1)
    } else {
        (s0, q0, g0)
    };
    let (s3, q3) = if ge == g2 {
        (s2, q2)
    } else {
        let w3 = g2 / (g2 - ge);
        (lerp(&s2, &se, w3)?, q2 + w3 * (qe - q2))
    };
    if beta == 1.0 {
        return Some((s3, q3));
    }
    Some((lerp(&s, &s3, beta)?, q + beta * (q3 - q)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The predictor-corrector on a softening heat q = q0 exp(-c (T - t_hist)) (state: the
    /// heat itself): its error falls with the square of the predictor's miss below one
    /// `miss`, with about its fourth power from two misses (the third evaluation), and the
    /// result is continuous where the blend between them starts and ends.
    #[test]
    fn the_predictor_corrector_converges_with_the_misses_square_and_is_continuous() {
        let (t_hist, self_c, q0, c) = (40.0, 2e-6, 2e7, 0.01);
        let q_of = |t: f64| q0 * (-c * (t - t_hist)).exp();
        let g = |t: f64| t_hist + self_c * q_of(t) - t;
        let (mut lo, mut hi) = (t_hist, t_hist + self_c * q0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if g(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let q_root = q_of(lo);
        let lerp = |a: &f64, b: &f64, w: f64| Some(a + w * (b - a));
        let solve = |q_pred: f64, miss: f64| {
            solve_predictor_corrector(
                t_hist,
                self_c,
                q_pred,
                miss,
                |t| (q_of(t), q_of(t)),
                lerp,
                |_| true,
            )
            .expect("a root")
            .1
        };
        // relative errors of the heat for predictors off by 1, 2, 4 % (misses about 0.4-1.6
        // K): two evaluations (miss infinite) and three (miss 0)
        let two: Vec<f64> = [1.01, 1.02, 1.04]
            .iter()
            .map(|f| (solve(q_root * f, f64::INFINITY) / q_root - 1.0).abs())
            .collect();
        let three: Vec<f64> = [1.01, 1.02, 1.04]
            .iter()
            .map(|f| (solve(q_root * f, 0.0) / q_root - 1.0).abs())
            .collect();
        for k in 0..2 {
            let (r2, r3) = (two[k + 1] / two[k], three[k + 1] / three[k].max(1e-300));
            assert!((3.0..5.0).contains(&r2), "two evaluations: errors {two:?}");
            assert!(
                three[k + 1] < 1e-3 * two[k + 1] || three[k + 1] < 1e-13,
                "three: {three:?}, two: {two:?}, ratio {r3}"
            );
        }
        assert!(two[2] > 1e-7 && two[2] < 1e-4, "errors {two:?}");
        // continuity: the predictor's miss |t1 - t0| crossing `miss` and 2 `miss`
        let q_pred = q_root * 1.03;
        let t0 = t_hist + self_c * q_pred;
        let m = (t_hist + self_c * q_of(t0) - t0).abs();
        for edge in [m, 0.5 * m] {
            let below = solve(q_pred, edge * (1.0 + 1e-12));
            let above = solve(q_pred, edge * (1.0 - 1e-12));
            assert!(
                (below - above).abs() <= 1e-9 * q_root,
                "{below} vs {above} at miss {edge}"
            );
        }
    }
}
