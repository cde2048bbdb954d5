//! Flash temperature of a bristle from its own heat history (seed Eq. 4.30-4.35), with a sum-of-exponentials kernel.
//!
//! Eq. 4.34: T(t) = T_B + sqrt(kappa_w)/(lambda_w sqrt(pi)) * int q_w(t') / sqrt(t - t') dt'.
//! With q piecewise constant over sub-steps, the newest interval [t_{n-1}, t_n] of length h
//! contributes exactly 2 q_n sqrt(h) (Eq. 4.35's first term). The older history is a
//! convolution with the kernel 1/sqrt(s); it is evaluated with
//! 1/sqrt(s) = (1/sqrt(pi)) int exp(sigma/2) exp(-e^sigma s) d sigma, discretised by the
//! trapezoidal rule in sigma with step `H_SIGMA` from rate `S_MIN` up (29 rates, to 1.5e9 1/s),
//! plus a constant tail term for rates below `S_MIN`. Each bristle then carries one
//! accumulator per rate, updated exactly for piecewise-constant heat:
//! A_k(t_n) = exp(-s_k h) A_k(t_{n-1}) + q_n (1 - exp(-s_k h)) / s_k.
//! The relative error of the kernel is below 0.15 % for 1e-8 s <= s <= 2 s (unit test; a
//! bristle crosses a 15 mm contact in 0.15 s at 0.1 m/s, the Péclet limit), so
//! any sub-step size and any history length cost the same: O(N_KERNEL) per bristle and step.

use std::f64::consts::PI;
use wide::f64x2;

mod predictor;
pub use predictor::{pc_miss, solve_predictor_corrector, TemperatureSolve, PC_MISS_REL};

/// Smallest decay rate of the kernel, 1/s.
pub const S_MIN: f64 = 1e-3;
/// Spacing of the rates in ln(s).
pub const H_SIGMA: f64 = 1.0;
/// Number of exponential terms (plus one constant tail term, index 0).
pub const N_KERNEL: usize = 30;
const _: () = assert!(
    N_KERNEL.is_multiple_of(2),
    "StepFactors::accumulate takes two lanes at a time"
);

/// The sum-of-exponentials approximation of 1/sqrt(s).
#[derive(Clone, Debug)]
pub struct Kernel {
    /// Rates s_k (1/s); `rates[0] = 0` is the constant tail term.
    pub rates: [f64; N_KERNEL],
    /// Weights w_k (1/sqrt(s) units).
    pub weights: [f64; N_KERNEL],
}

impl Default for Kernel {
    fn default() -> Self {
        let mut rates = [0.0; N_KERNEL];
        let mut weights = [0.0; N_KERNEL];
        let s0 = S_MIN.ln();
        for k in 1..N_KERNEL {
            let sigma = s0 + (k - 1) as f64 * H_SIGMA;
            rates[k] = sigma.exp();
            weights[k] = H_SIGMA * (0.5 * sigma).exp() / PI.sqrt();
        }
        // The trapezoid's first node carries half weight; the rest of the integral below
        // S_MIN (where exp(-s t) ~ 1) is int_{-inf}^{sigma0} e^{sigma/2} = 2 e^{sigma0/2}.
        weights[1] *= 0.5;
        weights[0] = 2.0 * (0.5 * s0).exp() / PI.sqrt();
        Kernel { rates, weights }
    }
}

impl Kernel {
    /// Approximation of 1/sqrt(s).
    pub fn eval(&self, s: f64) -> f64 {
        self.rates
            .iter()
            .zip(self.weights.iter())
            .map(|(r, w)| w * (-r * s).exp())
            .sum()
    }

    /// The factors of a sub-step of length `h`.
    pub fn factors(&self, h: f64) -> StepFactors {
        let (decay, gain) = self.step_factors(h);
        let mut wdecay = [0.0; N_KERNEL];
        for ((x, w), d) in wdecay.iter_mut().zip(self.weights.iter()).zip(decay.iter()) {
            *x = w * d;
        }
        StepFactors {
            decay,
            gain,
            wdecay,
        }
    }

    /// The factors of `N` graded sub-steps of one step `h`: sub-step i (1-based) lasts
    /// (2i - 1) h / N^2, so that they end at (i/N)^2 of the step. One exp and one expm1
    /// per kernel term instead of N of each: with d = exp(-s_k h / N^2) and
    /// g = (1 - d)/s_k, sub-step i decays by d^(2i-1) and gains g (1 + d + ... + d^(2i-2))
    /// (the identity 1 - d^m = (1 - d)(1 + d + ... + d^(m-1)), free of cancellation). Agrees
    /// with [`Self::factors`] of each sub-step to a few units of rounding.
    pub fn graded_factors<const N: usize>(&self, h: f64) -> [StepFactors; N] {
        let base = self.factors(h / (N * N) as f64);
        let mut out = [base; N];
        for k in 0..N_KERNEL {
            let (d, g) = (base.decay[k], base.gain[k]);
            let d2 = d * d;
            // d^(2i-1) and 1 + d + ... + d^(2i-2), built up from i = 1
            let (mut dp, mut sum) = (d, 1.0);
            for (i, f) in out.iter_mut().enumerate() {
                if i > 0 {
                    sum += dp + dp * d;
                    dp *= d2;
                }
                f.decay[k] = dp;
                f.gain[k] = g * sum;
                f.wdecay[k] = self.weights[k] * dp;
            }
        }
        out
    }

    /// Decay factors exp(-s_k h) and increments (1 - exp(-s_k h))/s_k for a sub-step `h`.
    /// Two terms at a time by [`crate::fastexp::exp_m1_pair`] (exp and exp_m1 within 1e-15
    /// of the C library's, inlined).
    pub fn step_factors(&self, h: f64) -> ([f64; N_KERNEL], [f64; N_KERNEL]) {
        let mut decay = [1.0; N_KERNEL];
        let mut gain = [h; N_KERNEL];
        // rates[0] = 0: decay 1, gain h
        let mut k = 1;
        while k < N_KERNEL {
            let k2 = (k + 1).min(N_KERNEL - 1);
            let (x1, x2) = (self.rates[k] * h, self.rates[k2] * h);
            let ((d1, m1), (d2, m2)) = crate::fastexp::exp_m1_pair(-x1, -x2);
            decay[k] = d1;
            gain[k] = -m1 / self.rates[k];
            decay[k2] = d2;
            gain[k2] = -m2 / self.rates[k2];
            k += 2;
        }
        (decay, gain)
    }
}

/// The kernel's factors for one sub-step length h: decay exp(-s_k h), gain
/// (1 - exp(-s_k h))/s_k, and weighted decay w_k exp(-s_k h) for the history sum.
#[derive(Clone, Copy, Debug)]
pub struct StepFactors {
    /// Decay factors exp(-s_k h).
    pub decay: [f64; N_KERNEL],
    /// Gains (1 - exp(-s_k h))/s_k, s.
    pub gain: [f64; N_KERNEL],
    /// Weighted decays w_k exp(-s_k h).
    pub wdecay: [f64; N_KERNEL],
}

impl StepFactors {
    /// Factors of a sub-step without heat flow: the accumulators keep their values.
    pub fn identity(h: f64) -> Self {
        StepFactors {
            decay: [1.0; N_KERNEL],
            gain: [h; N_KERNEL],
            wdecay: [0.0; N_KERNEL],
        }
    }

    /// History sum sum_k w_k exp(-s_k h) A_k of Eq. 4.35 (all but the newest interval).
    #[inline]
    pub fn history(&self, acc: &[f64; N_KERNEL]) -> f64 {
        // four partial sums in two two-lane registers (sums 0, 1 and 2, 3)
        let (mut p01, mut p23) = (f64x2::ZERO, f64x2::ZERO);
        let (w4, a4) = (self.wdecay.chunks_exact(4), acc.chunks_exact(4));
        let (wr, ar) = (w4.remainder(), a4.remainder());
        for (w, a) in w4.zip(a4) {
            p01 += f64x2::new([w[0], w[1]]) * f64x2::new([a[0], a[1]]);
            p23 += f64x2::new([w[2], w[3]]) * f64x2::new([a[2], a[3]]);
        }
        let [mut p0, p1] = p01.to_array();
        let [p2, p3] = p23.to_array();
        for (w, a) in wr.iter().zip(ar) {
            p0 += w * a;
        }
        (p0 + p1) + (p2 + p3)
    }

    /// Accumulator update A_k <- exp(-s_k h) A_k + q (1 - exp(-s_k h))/s_k.
    #[inline]
    pub fn accumulate(&self, acc: &mut [f64; N_KERNEL], q: f64) {
        // two lanes at a time (N_KERNEL is even)
        let qq = f64x2::splat(q);
        for ((a, d), g) in acc
            .chunks_exact_mut(2)
            .zip(self.decay.chunks_exact(2))
            .zip(self.gain.chunks_exact(2))
        {
            let r =
                f64x2::new([d[0], d[1]]) * f64x2::new([a[0], a[1]]) + qq * f64x2::new([g[0], g[1]]);
            a.copy_from_slice(&r.to_array());
        }
    }
}

/// beta = lambda_r sqrt(kappa_w)/(lambda_w sqrt(kappa_r)) of Eq. 4.31 (the thermal
/// effusivities' ratio, rail over wheel).
fn partition_beta(lambda_w: f64, kappa_w: f64, lambda_r: f64, kappa_r: f64) -> f64 {
    lambda_r * kappa_w.sqrt() / (lambda_w * kappa_r.sqrt())
}

/// Heat partition factor alpha into the wheel (Eq. 4.30, 4.31):
/// alpha = sqrt(v_w)/(sqrt(v_w) + beta sqrt(v)), beta = lambda_r sqrt(kappa_w)/(lambda_w sqrt(kappa_r)). `v_w` is the
/// circumferential wheel speed, `v` the vehicle speed (m/s). Returns 0.5 when both are 0.
pub fn heat_partition(
    v_w: f64,
    v: f64,
    lambda_w: f64,
    kappa_w: f64,
    lambda_r: f64,
    kappa_r: f64,
) -> f64 {
    let beta = partition_beta(lambda_w, kappa_w, lambda_r, kappa_r);
    let num = v_w.max(0.0).sqrt();
    let den = num + beta * v.max(0.0).sqrt();
    if den <= 0.0 {
        1.0 / (1.0 + beta)
    } else {
        num / den
    }
}

/// The partition factor of [`heat_partition`] times sqrt(v / v_w): with it, Eq. 4.34
/// evaluated in the layer's time x / v gives the wheel surface's flash temperature over its
/// own time in the contact, x / v_w (effect `surface_time_flash`):
/// sqrt(v) / (sqrt(v_w) + beta sqrt(v)). Equal to alpha at v_w = v, 1/beta at v_w = 0 (the
/// rail side's formula with all heat into the rail). Returns alpha's limit 1/(1 + beta) when
/// v = 0.
pub fn surface_time_partition(
    v_w: f64,
    v: f64,
    lambda_w: f64,
    kappa_w: f64,
    lambda_r: f64,
    kappa_r: f64,
) -> f64 {
    let beta = partition_beta(lambda_w, kappa_w, lambda_r, kappa_r);
    let sv = v.max(0.0).sqrt();
    if sv <= 0.0 {
        return 1.0 / (1.0 + beta);
    }
    sv / (v_w.max(0.0).sqrt() + beta * sv)
}

/// Factor sqrt(kappa_w)/(lambda_w sqrt(pi)) of Eq. 4.34, K m^2 s^-1/2 / W.
pub fn flash_factor(lambda_w: f64, kappa_w: f64) -> f64 {
    kappa_w.sqrt() / (lambda_w * PI.sqrt())
}

/// Péclet condition of Eq. 4.33: a (v + v_w) > 20 (kappa_r + kappa_w).
pub fn peclet_ok(a: f64, v: f64, v_w: f64, kappa_w: f64, kappa_r: f64) -> bool {
    a * (v + v_w) > 20.0 * (kappa_r + kappa_w)
}

/// Relative change of the softening factors (exp(-c T), c the largest temperature
/// coefficient) that the local temperature solves resolve: 1e-10. The forces follow the
/// temperature through these factors, so a solve that stops anywhere within its tolerance
/// moves them by about this much relative: with 1e-10 a finite-difference derivative with a
/// relative increment of 1e-6 is still right to about 1e-4 relative. The earlier
/// 1e-4 made the outputs jump by 1e-6..1e-5 relative where an input moved by one ulp changed
/// an iteration count; it cost about a fifth fewer instructions per transient step
/// (docs/model.md, "Tolerance of the temperature solve").
pub const T_TOL_REL: f64 = 1e-10;

/// Smallest temperature tolerance, K: well above the rounding of g(T) = t_hist + self_c q - T
/// at flash temperatures up to 10^4 degC (about 1e-12 K), so a solve never waits for a
/// residual that rounding does not let it reach.
pub const T_TOL_MIN: f64 = 1e-11;

/// Largest temperature tolerance, K, where no material law depends on T (the solve then
/// only sets the reported temperatures, and converges in one step anyway).
pub const T_TOL_MAX: f64 = 1e-8;

/// Temperature tolerance (K) of the local solves for a largest temperature coefficient
/// `cmax` (1/degC) of the material laws: [`T_TOL_REL`] / cmax within
/// [[`T_TOL_MIN`], [`T_TOL_MAX`]].
pub fn temperature_tolerance(cmax: f64) -> f64 {
    if cmax > 0.0 {
        (T_TOL_REL / cmax).clamp(T_TOL_MIN, T_TOL_MAX)
    } else {
        T_TOL_MAX
    }
}

/// Solves the local flash temperature of a bristle move, T = t_hist + self_c q(T) (Eq. 4.35:
/// history part `t_hist`, the sub-step's own heat `self_c q`), for the smallest root above
/// `t_hist`: the temperature the bristle reaches first while heating up (q(T) may rise with T
/// where softening turns an elastic bristle plastic). `eval(T)` returns the bristle's new state
/// and its heat density q at temperature T; `first` is that pair at `t_hist`, `q_prev` the
/// bristle's heat density of its previous sub-step (the predictor), `tol` the tolerance in K,
/// `lerp(a, b, w)` the state a + w (b - a) where that is a valid state (None where it is not,
/// e.g. across a change of regime). Returns the state and q at the root.
#[allow(clippy::too_many_arguments)]
pub fn solve_self_heating<S: Copy>(
    t_hist: f64,
    self_c: f64,
    q: f64,
    first: S,
    q_prev: f64,
    tol: f64,
    eval: impl Fn(f64) -> (S, f64),
    lerp: impl Fn(&S, &S, f64) -> Option<S>,
) -> (S, f64) {
    let (mut ns, mut q) = (first, q);
    // states and true residuals at the bracket's ends, for the final interpolation
    let (mut sa, mut qa) = (first, q);
    let (mut sb, mut qb) = (first, q);
    let old_q = q_prev;
    // Solve T = t_hist + self_c q(T) for the smallest root above t_hist (the temperature
    // the bristle reaches first while heating up; q(T) may rise with T where softening
    // turns an elastic bristle plastic): secant steps upward (fixed-point steps where the
    // secant does not point up) while g(T) = t_hist + self_c q(T) - T > 0, then Illinois
    // regula falsi once bracketed;
    // tolerance `tol` (K): see [`temperature_tolerance`].
    let g_of = |q: f64, t: f64| t_hist + self_c * q - t;
    let (mut ta, mut ga) = (t_hist, self_c * q);
    // predictor: this bristle's heat of its previous sub-step, when it lies inside
    // [t_hist, t_hist + self_c q(t_hist)]; else the fixed-point step from t_hist
    let mut tb = ta + ga;
    if ga < tol {
        // the move's own heat warms it by less than the tolerance (e.g. an adhering bristle
        // whose q is a rounding residue): t_hist is the root
        return (ns, q);
    }
    let mut bracketed = false;
    let mut gb = 0.0;
    if old_q > 0.0 && self_c * old_q < ga {
        let tp = t_hist + self_c * old_q;
        let (sp, qp) = eval(tp);
        let gp = g_of(qp, tp);
        if gp.abs() < tol {
            ns = sp;
            q = qp;
            tb = tp;
            ta = tp;
        } else if gp > 0.0 {
            tb = secant_up(ta, ga, tp, gp);
            ta = tp;
            ga = gp;
            (sa, qa) = (sp, qp);
        } else {
            // the root lies between t_hist and the predictor
            ns = sp;
            q = qp;
            tb = tp;
            gb = gp;
            (sb, qb) = (sp, qp);
            bracketed = true;
        }
    }
    for _ in 0..60 {
        if bracketed || tb == ta {
            break;
        }
        let (s_new, q_new) = eval(tb);
        ns = s_new;
        q = q_new;
        gb = g_of(q_new, tb);
        if gb.abs() < tol {
            break;
        }
        if gb > 0.0 {
            let next = secant_up(ta, ga, tb, gb);
            ta = tb;
            ga = gb;
            (sa, qa) = (s_new, q_new);
            tb = next;
        } else {
            (sb, qb) = (ns, q);
            bracketed = true;
            break;
        }
    }
    if bracketed {
        let mut side = 0;
        let (mut ga_true, mut gb_true) = (ga, gb);
        for _ in 0..60 {
            let tc = tb - gb * (tb - ta) / (gb - ga);
            if (tb - ta).abs() < LERP_TOLS * tol {
                // a narrow bracket: g is linear on it to well within the tolerance, so the
                // state at the secant root is the interpolation of the ends' states
                let w = ga_true / (ga_true - gb_true);
                if let Some(st) = lerp(&sa, &sb, w) {
                    return (st, qa + w * (qb - qa));
                }
            }
            let (sc, qc) = eval(tc);
            let gc = g_of(qc, tc);
            ns = sc;
            q = qc;
            // a bracket a few ulps wide: the secant root tc is as close as rounding allows
            if gc.abs() < tol || (tb - ta).abs() <= 8.0 * f64::EPSILON * tb.abs() {
                break;
            }
            if gc < 0.0 {
                tb = tc;
                gb = gc;
                (sb, qb, gb_true) = (sc, qc, gc);
                if side == -1 {
                    ga *= 0.5;
                }
                side = -1;
            } else {
                ta = tc;
                ga = gc;
                (sa, qa, ga_true) = (sc, qc, gc);
                if side == 1 {
                    gb *= 0.5;
                }
                side = 1;
            }
        }
    }
    (ns, q)
}

/// The solve of [`solve_self_heating`] started at the predictor t_hist + self_c q_prev (the
/// bristle's heat of its previous move) instead of at t_hist: a fixed-point step, then secant
/// steps, and the interpolation of [`solve_self_heating`] once the root is bracketed within a
/// few kelvin. Valid only where the root is unique, which `unique(state)` tells for each
/// evaluated state (a bristle whose heat falls with T); returns None wherever that or the
/// convergence is in doubt, and the caller then runs the full solve from t_hist.
pub fn solve_from_predictor<S: Copy>(
    t_hist: f64,
    self_c: f64,
    q_prev: f64,
    tol: f64,
    eval: impl Fn(f64) -> (S, f64),
    lerp: impl Fn(&S, &S, f64) -> Option<S>,
    unique: impl Fn(&S) -> bool,
) -> Option<(S, f64)> {
    let g_of = |q: f64, t: f64| t_hist + self_c * q - t;
    let mut t0 = t_hist + self_c * q_prev;
    let (mut s0, mut q0) = eval(t0);
    if q0 <= 0.0 || !unique(&s0) {
        return None;
    }
    let mut g0 = g_of(q0, t0);
    if g0.abs() < tol {
        return Some((s0, q0));
    }
    let mut t1 = t0 + g0;
    for _ in 0..20 {
        let (s1, q1) = eval(t1);
        if q1 <= 0.0 || !unique(&s1) {
            return None;
        }
        if (q1 - q0) * (t1 - t0) > 0.0 {
            // the heat rises with T here: the root may not be unique
            return None;
        }
        let g1 = g_of(q1, t1);
        if g1.abs() < tol {
            return Some((s1, q1));
        }
        if (g0 > 0.0) != (g1 > 0.0) && (t1 - t0).abs() < LERP_TOLS * tol {
            let w = g0 / (g0 - g1);
            if let Some(st) = lerp(&s0, &s1, w) {
                return Some((st, q0 + w * (q1 - q0)));
            }
        }
        let t2 = if g1 != g0 {
            t1 - g1 * (t1 - t0) / (g1 - g0)
        } else {
            t1 + g1
        };
        if !(t2.is_finite() && t2 >= t_hist) {
            return None;
        }
        (t0, s0, q0, g0) = (t1, s1, q1, g1);
        t1 = t2;
    }
    None
}

/// The root of T = t_hist + self_c q(T) (Eq. 4.35) where g(T) = t_hist + self_c q(T) - T
/// falls strictly, as for a bristle that softens as it heats
/// ([`crate::bristle::SofteningPath`]) and whose heat falls with T or rises more slowly than
/// 1 / self_c: then the root is unique, below t_hist + self_c q_max. `q_of(T)` returns
/// (q, dq/dT) of the law as a scalar function of T (cheap: no bristle state); (`q0`, `dq0`)
/// are its values at t_hist, `q_max` a bound of q over the bracket. The caller must know that
/// g falls on the whole bracket. Safeguarded Newton (bisection where a step
/// leaves the bracket) until a Newton step is shorter than `tol`; that step is taken without
/// a further evaluation (the residual after it is of the order of the step squared times
/// g'').
///
/// Returns the root and the temperature at which `q_of` was last evaluated (t_hist if it was
/// not): the caller extrapolates its own state from there over the last step. None if
/// self_c dq/dT >= 1 where it is evaluated, or after 50 iterations.
pub fn solve_monotone(
    t_hist: f64,
    self_c: f64,
    (q0, dq0): (f64, f64),
    q_max: f64,
    tol: f64,
    q_of: impl Fn(f64) -> (f64, f64),
) -> Option<(f64, f64)> {
    let g0 = self_c * q0;
    if self_c * dq0 >= 1.0 {
        return None;
    }
    if g0 < tol {
        return Some((t_hist, t_hist));
    }
    let (mut lo, mut hi) = (t_hist, t_hist + self_c * q_max.max(q0));
    // the first step from t_hist needs no evaluation: (q0, dq0) are known there
    let (mut t, mut g, mut dq) = (t_hist, g0, dq0);
    for _ in 0..50 {
        if self_c * dq >= 1.0 {
            return None;
        }
        if g > 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let step = -g / (self_c * dq - 1.0);
        let next = t + step;
        if step.abs() < tol && next >= lo && next <= hi {
            return Some((next, t));
        }
        t = if next > lo && next < hi {
            next
        } else {
            0.5 * (lo + hi)
        };
        let (q, d) = q_of(t);
        g = t_hist + self_c * q - t;
        dq = d;
        if hi - lo < tol && g.abs() < tol {
            return Some((t, t));
        }
    }
    None
}

/// Width of a bracket, in tolerances, below which the root's state is interpolated between
/// the bracket's ends instead of evaluated. The residual and the state are smooth in T
/// within one regime, so the interpolation's error is of the order of the width squared
/// times their curvature: with the tolerance of [`temperature_tolerance`] the width is
/// 5e-7 / cmax K, over which the softening factors change by 5e-7 relative, and the error is
/// about 1e-13 relative. (With the earlier tolerance of 1e-4 relative this width was 15 K on
/// the dry preset, and the interpolation moved F_x by 0.37 % from the converged value.)
const LERP_TOLS: f64 = 5000.0;

/// The next trial temperature above `tb` while g > 0 at both `ta` < `tb`: the secant's zero
/// where g falls, else the fixed-point step tb + g(tb).
#[inline]
fn secant_up(ta: f64, ga: f64, tb: f64, gb: f64) -> f64 {
    if gb < ga && tb > ta {
        tb + gb * (tb - ta) / (ga - gb)
    } else {
        tb + gb
    }
}

/// Exact Eq. 4.35 for a heat history `q[i]` on intervals ending at `t[i]` (t_0 = 0 implied):
/// the temperature rise at t_n divided by the flash factor. Reference for tests.
pub fn exact_history_sum(t: &[f64], q: &[f64]) -> f64 {
    let n = t.len();
    let tn = t[n - 1];
    let mut s = 0.0;
    for i in 0..n {
        let t_prev = if i == 0 { 0.0 } else { t[i - 1] };
        s += 2.0 * q[i] * ((tn - t_prev).sqrt() - (tn - t[i]).sqrt());
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kernel_approximates_inverse_sqrt() {
        let k = Kernel::default();
        let mut worst: f64 = 0.0;
        let mut s = 1e-8;
        while s <= 2.0 {
            let rel = (k.eval(s) * s.sqrt() - 1.0).abs();
            worst = worst.max(rel);
            s *= 1.07;
        }
        assert!(worst < 1.5e-3, "worst relative kernel error {worst}");
    }

    #[test]
    fn accumulators_reproduce_eq_4_35() {
        // Irregular sub-steps and a varying heat history.
        let k = Kernel::default();
        let mut acc = [0.0; N_KERNEL];
        let (mut t, mut ts, mut qs) = (0.0, vec![], vec![]);
        for i in 0..300 {
            let h = 1e-6 * (1.0 + (i % 7) as f64 * 3.0);
            let q = 1e8 * (1.0 + (i as f64 * 0.1).sin());
            t += h;
            ts.push(t);
            qs.push(q);
            let (decay, gain) = k.step_factors(h);
            // history part before this step's own contribution
            let hist: f64 = (0..N_KERNEL)
                .map(|j| k.weights[j] * decay[j] * acc[j])
                .sum();
            let approx = hist + 2.0 * q * h.sqrt();
            let exact = exact_history_sum(&ts, &qs);
            assert!(
                (approx - exact).abs() / exact < 2e-3,
                "step {i}: {approx} vs {exact}"
            );
            for j in 0..N_KERNEL {
                acc[j] = decay[j] * acc[j] + q * gain[j];
            }
        }
    }

    /// The graded sub-steps' factors from one exp and expm1 per term agree with each
    /// sub-step's own factors to rounding, over sub-steps from 1e-9 s (every term nearly
    /// constant) to 1e-2 s (the fast terms decayed).
    #[test]
    fn graded_factors_match_each_sub_step() {
        let k = Kernel::default();
        let mut worst: f64 = 0.0;
        for h in [1e-9, 3.7e-7, 1e-5, 2.5e-4, 1e-2] {
            let g = k.graded_factors::<4>(h);
            for (i, f) in g.iter().enumerate() {
                let hi = h * (2 * i + 1) as f64 / 16.0;
                let e = k.factors(hi);
                for j in 0..N_KERNEL {
                    for (a, b) in [
                        (f.decay[j], e.decay[j]),
                        (f.gain[j], e.gain[j]),
                        (f.wdecay[j], e.wdecay[j]),
                    ] {
                        // a NaN fails the comparison
                        let rel = (a - b).abs() / b.abs().max(1e-300);
                        assert!(rel < 1e-13, "h {h}, sub-step {i}, term {j}: {a} vs {b}");
                        worst = worst.max(rel);
                    }
                }
            }
        }
        assert!(worst < 1e-13, "worst relative difference {worst:e}");
    }

    /// Newton on a scalar law finds the root that bisection finds, for heat falling with T
    /// and for heat rising more slowly than 1 / self_c, within the tolerance.
    #[test]
    fn solve_monotone_finds_the_unique_root() {
        let (t_hist, self_c, tol) = (40.0, 2e-6, 1e-3);
        for (q0, c) in [
            (5e6, 0.03),
            (5e6, 0.0025),
            (2e7, 0.05),
            (5e6, -2e-3),
            (1e3, 0.03),
        ] {
            // q = q0 exp(-c (T - t_hist)); c < 0: rising, self_c dq/dT = 2e-5 at t_hist
            let q_of = |t: f64| {
                let q = q0 * (-c * (t - t_hist)).exp();
                (q, -c * q)
            };
            let g = |t: f64| t_hist + self_c * q_of(t).0 - t;
            let (root, _) = solve_monotone(
                t_hist,
                self_c,
                q_of(t_hist),
                if c < 0.0 { 10.0 * q0 } else { q0 },
                tol,
                q_of,
            )
            .expect("root");
            let (mut lo, mut hi) = (t_hist, t_hist + self_c * 10.0 * q0);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if g(mid) > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            assert!(g(root).abs() < tol, "q0 {q0} c {c}: g = {}", g(root));
            assert!((root - lo).abs() < tol, "q0 {q0} c {c}: {root} vs {lo}");
        }
        // heat that rises as fast as 1 / self_c: no unique root guaranteed, refused
        let steep = |t: f64| (1e6 + 1e6 * (t - t_hist), 1e6);
        assert!(solve_monotone(t_hist, 1e-6, steep(t_hist), 1e9, tol, steep).is_none());
    }

    #[test]
    fn partition_is_half_for_equal_bodies_and_speeds() {
        assert!((heat_partition(5.0, 5.0, 50.0, 1.4e-5, 50.0, 1.4e-5) - 0.5).abs() < 1e-12);
        assert!(heat_partition(6.0, 5.0, 50.0, 1.4e-5, 50.0, 1.4e-5) > 0.5);
    }
}
