//! The move of a bristle in a layer that only softens as it heats: its local temperature solved on the law's branch as a scalar function of T (Eq. 4.3, 4.7, 4.29, 4.35).
//!
//! The general move ([`Mover::update_bristle`]) solves T = t_hist + self_c q(T) by
//! evaluating the whole bristle law at trial temperatures, 2.5-2.8 times per move. Where
//! the layer only softens as it heats ([`crate::engine::FastPath::Softening`] with
//! [`crate::material::Resolved::monotone_softening`]: every preset with temperature) and the move's branch of the law cannot change on the way
//! up ([`SofteningPath`]: elastic below tau_c1, hardening while loading, sliding at
//! tau_c2), the law is a scalar function of T with an analytic derivative: Newton's method
//! on it needs about one exponential per move, and the new state follows from the root.
//! Elsewhere (unloading from the plastic branch, a trial that crosses the yield surface,
//! heat that rises with T faster than the solve can bound, a plastic bristle below tau_c1
//! at t_hist that may ride on it, and, outside the higher-order rules, a damped release of a
//! bristle that heated, whose reference is at its predictor: docs/model.md section 6) the
//! general solve runs.
//! Formula and custom effects that depend on the operating point only scale the strengths
//! by constants and keep the layer softening; effects on the local bristle state (p, T,
//! |u|, slip) take the general solve. Results agree with the general solve within its
//! tolerance (1e-4 relative change of the softening factors; tested in `tests/physics`).

use super::kin::Kin;
use super::law::Mover;
use crate::bristle::{BristleState, Material, Move, Regime, Rule, SofteningPath};
use crate::fastexp::{exp_fast, exp_pair};
use crate::material::NodeP;
use crate::thermal::{self, StepFactors, TemperatureSolve, N_KERNEL};

impl Mover<'_> {
    /// [`Mover::update_bristle`] on the scalar path (see the module): advances one bristle
    /// by one sub-step with heat flow and returns its heat density q (W/m^2), or None with
    /// the bristle untouched where the general solve must run. `du` is the move's rigid slip
    /// (m) and `t_hist` the temperature of its heat history (degC, Eq. 4.35), both from
    /// [`Mover::update_bristle`].
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn update_softening(
        &self,
        k: &Kin,
        np: &NodeP,
        np0: Option<&NodeP>,
        [x, y]: [f64; 2],
        du: [f64; 2],
        t_hist: f64,
        s: &mut BristleState,
        acc: &mut [f64; N_KERNEL],
        fac: &StepFactors,
    ) -> Option<f64> {
        let warm = acc[0] != 0.0;
        let self_c = k.self_c;
        if self_c.is_nan() || self_c <= 0.0 {
            return None;
        }
        let old = *s;
        let mv = Move::new(&old, du);
        // the release weight theta of the general move (docs/model.md, section 6)
        let theta = self.release_weight(k, np, old.tau, false);
        // the damped release of a bristle that heated takes its reference at the predictor
        // in the general move (outside the higher-order rules); here it would be at t_hist
        if theta < 1.0
            && old.q > 0.0
            && np0.is_none()
            && self.law.r.on.rule == Rule::SameCharacteristic
        {
            return None;
        }
        // the material at t_hist (with the operating point's formula and custom factors)
        let m_h = self.law.material_static(np, t_hist);
        // flexibilities L + L_e and the elastic increment (Eq. 4.21); L_e does not depend on T
        let (lxe, lye, dtau) = k.flex(m_h.le, [x, y]);
        let path = mv.softening_path(&old, dtau, &m_h)?;
        // a plastic bristle elastic at t_hist may ride on tau_c1 (the release weight then
        // counts tau_c1's coefficient, `riding` in the general move)
        if old.regime == Regime::Plastic && path == SofteningPath::Elastic {
            return None;
        }
        // The higher-order rules (docs/model.md section 3.3): the heat weighs the end
        // stress by 1/2 + QLIN; a hardening bristle's law takes tau_c2 linear along the move
        // from the start material's and the mean 1/L_p along the temperature profile
        // ([`crate::bristle::lp_mean`]), with the start material at the bristle's start
        // temperature (fixed for the solve). The sliding branch (t0 >= tau_c2 at t_hist,
        // hence at every T above) and the elastic one keep their laws.
        let ho = np0.is_some();
        let start = match (np0, path) {
            (Some(np0), SofteningPath::Hardening { t0, .. }) if t0 < m_h.tc2 => {
                // an elastic bristle on a hardening path takes the cold crossing's law in the
                // general move
                if old.regime == Regime::Elastic {
                    return None;
                }
                let m0 = self.law.material_static(np0, old.temp);
                Some(MoveStart {
                    tc2_0: m0.tc2,
                    lp0: m0.lp,
                    lp_sqrt: self.lp_sqrt(k, self_c, &old, du),
                })
            }
            _ => None,
        };
        let pm = PathMove {
            kq_h: self.law.r.kq / k.h,
            np,
            m_h: &m_h,
            old: &old,
            mv: &mv,
            l: [lxe, lye],
            dtau,
            theta,
            t_hist,
            self_c,
            ho,
            start,
            t_h: std::cell::Cell::new(f64::NAN),
        };
        let (mut ns, q) = self.solve_on_path(&pm, path)?;
        ns.temp = t_hist + self_c * q;
        // the higher-order rules: the temperature from the end-weighted heat, the
        // accumulators (and the friction power) from the move's mean heat; where the general
        // move would clamp the start or end rate, it runs
        let q = if ho && q > 0.0 {
            let (qbar, q1, q0) = pm.heat_parts(ns.tau, pm.release_of(&ns));
            if q1 < 0.0 || q0 < 0.0 {
                return None;
            }
            qbar
        } else {
            q
        };
        ns.q = q;
        *s = ns;
        if warm || q > 0.0 {
            fac.accumulate(acc, q); // alpha is folded into alpha_c
        }
        Some(q)
    }

    /// True if the hardening span tau_c2 - tau_c1 is closed at temperature `t` (the law
    /// perfectly plastic there; see [`crate::material::Resolved::span_may_close`]).
    #[cold]
    #[inline(never)]
    fn span_closed(&self, np: &NodeP, t: f64) -> bool {
        let m = self.law.material_static(np, t);
        m.tc2 - m.tc1 <= 1e-12 * m.tc2
    }

    /// The new state and heat density of a move on a [`SofteningPath`] (see
    /// [`Mover::update_softening`]): the root of T = t_hist + self_c q(T) with q(T) the move's
    /// heat density as a scalar function of T (L_e independent of T), from the material `m_h`
    /// at t_hist, and the law's branch evaluated there (see [`PathMove`]). None if q does not
    /// fall with T and the scalar search fails, if an elastic bristle would yield at the
    /// root, or if the residual at the root is not within the tolerance: the caller then runs
    /// the general solve.
    fn solve_on_path(&self, pm: &PathMove, path: SofteningPath) -> Option<(BristleState, f64)> {
        let (tau, regime, q, t) = match path {
            SofteningPath::Elastic => self.elastic_on_path(pm)?,
            SofteningPath::Hardening { t0, dn, dir } => self.hardening_on_path(pm, t0, dn, dir)?,
        };
        // the predictor-corrector's root is within the square of the predictor's miss: its
        // residual is bounded relative to the move's flash rise instead (a failed search
        // stays far outside either)
        let tol = match self.law.t_solve {
            TemperatureSolve::Exact => self.law.t_tol,
            TemperatureSolve::PredictorCorrector => {
                self.law.t_tol.max(PC_RESIDUAL * (t - pm.t_hist))
            }
        };
        if (pm.t_hist + pm.self_c * q - t).abs() >= tol {
            return None;
        }
        let ns = BristleState {
            u: pm.mv.u1(),
            tau,
            regime,
            ..*pm.old
        };
        Some((ns, q))
    }

    /// An elastic move: the stress does not depend on T, so q is constant and the root one
    /// step away; None if the bristle would no longer be elastic there. Returns (tau,
    /// regime, q, T).
    fn elastic_on_path(&self, pm: &PathMove) -> Option<OnPath> {
        let (old, dtau) = (pm.old, pm.dtau);
        let tr = [old.tau[0] + dtau[0], old.tau[1] + dtau[1]];
        let q = pm.heat(tr, tr);
        let t = pm.t_hist + pm.self_c * q;
        let m = self.law.material_static(pm.np, t);
        let ntr = (tr[0] * tr[0] + tr[1] * tr[1]).sqrt();
        if !(pm.mv.t0() < m.tc1 && ntr <= m.tc1) {
            return None;
        }
        Some((tr, Regime::Elastic, q, t))
    }

    /// A hardening or sliding move along `dir` from the stress `t0` over the plastic slip
    /// `dn`: the root temperature of the heat of the law's stress t(T), and the stress,
    /// regime and heat density there; None where the general solve must run. Returns (tau,
    /// regime, q, T).
    fn hardening_on_path(&self, pm: &PathMove, t0: f64, dn: f64, dir: [f64; 2]) -> Option<OnPath> {
        let law = HardeningLaw::new(self, pm.m_h, t0, dn, pm.start);
        // the predictor-corrector where the release is not damped (theta = 1): neither the
        // release reference, the law's stress at t_hist, nor the exact search is needed
        let pc = (self.law.t_solve == TemperatureSolve::PredictorCorrector
            && pm.theta == 1.0
            && pm.old.q > 0.0)
            .then(|| predictor_corrector_root(pm, &law, pm.heat_along(dir, 0.0), self.law.pc_miss))
            .flatten();
        let (root, sliding, t, t_h) = match pc {
            Some((root, sliding, t)) => (root, sliding, t, None),
            None => {
                let (t_h, dt_h) = law.at_hist();
                pm.t_h.set(t_h);
                let coef = pm.heat_along(dir, t_h);
                let (root, sliding, t) = self.hardening_root(pm, &law, coef, (t_h, dt_h))?;
                (root, sliding, t, Some(t_h))
            }
        };
        // the span closes at one temperature and stays closed above it: open at the
        // root means open on the whole path from t_hist
        if self.law.r.span_may_close() && self.span_closed(pm.np, root) {
            return None;
        }
        let theta = pm.theta;
        let tau = [t * dir[0], t * dir[1]];
        let tau_r = match t_h {
            Some(t_h) => {
                let r = [t_h * dir[0], t_h * dir[1]];
                [
                    r[0] + theta * (tau[0] - r[0]),
                    r[1] + theta * (tau[1] - r[1]),
                ]
            }
            None => tau,
        };
        let regime = if sliding {
            Regime::Sliding
        } else {
            Regime::Plastic
        };
        Some((tau, regime, pm.heat(tau, tau_r), root))
    }

    /// The root T of t_hist + self_c q(T) = T for the heat q = a t - b t^2 + c (`coef`) of the
    /// law's stress t(T), from t and dt/dT at t_hist (`at_hist`); returns (T, sliding, t at
    /// T), or None if the scalar search fails.
    fn hardening_root(
        &self,
        pm: &PathMove,
        law: &HardeningLaw,
        (a, b, c): (f64, f64, f64),
        (t_h, dt_h): (f64, f64),
    ) -> Option<(f64, bool, f64)> {
        let (t_hist, self_c, t0) = (pm.t_hist, pm.self_c, law.t0);
        // the higher-order hardening law is not monotone in T in general (tau_c2 rising
        // along the move can put t0 above its start value; the L_p mean along the profile
        // moves either way): the general search for the smallest root, on the scalar law
        let general = law.start.is_some() && t0 < law.m_h.tc2;
        let m_h = law.m_h;
        // the last temperature evaluated and the law there: (T, t, dt/dT, sliding, tau_c2)
        let last = std::cell::Cell::new((t_hist, t_h, dt_h, t0 >= m_h.tc2, m_h.tc2));
        let q_of = |t_k: f64| {
            let (t, dt, sl, tc2) = law.stress(t_k - t_hist);
            last.set((t_k, t, dt, sl, tc2));
            let q = a * t - b * t * t;
            let q = q + c;
            if q <= 0.0 {
                (0.0, 0.0)
            } else {
                (q, (a - 2.0 * b * t) * dt)
            }
        };
        let q_h = a * t_h - b * t_h * t_h;
        let q_h = q_h + c;
        let (q_h, dq_h) = if q_h <= 0.0 {
            (0.0, 0.0)
        } else {
            (q_h, (a - 2.0 * b * t_h) * dt_h)
        };
        // g(T) = t_hist + self_c q(T) - T falls on the whole bracket if q does, or, with
        // L_p independent of T, if self_c dq/dT < 1/2 at t_hist: there
        // |dq/dT| = c2 t |a - 2 b t| (sliding) or c2 tau_c2 (1 - e) |a - 2 b t|
        // (hardening) is largest, both factors falling with T
        if !general && (dq_h <= 0.0 || (law.cp == 0.0 && self_c * dq_h < 0.5)) {
            let q_max = if dq_h <= 0.0 || b <= 0.0 {
                q_h
            } else {
                // the vertex of a t - b t^2 + c bounds q where it rises
                a * a / (4.0 * b) + c
            };
            let (root, _) =
                thermal::solve_monotone(t_hist, self_c, (q_h, dq_h), q_max, self.law.t_tol, q_of)?;
            // the stress at the root: extrapolated over the last step (shorter than
            // the tolerance: tau_c2 changes by less than 1e-10 of itself over it)
            // unless the bristle may cross tau_c2 = t0 on it
            let (tl, t_l, dt_l, sl, tc2_l) = last.get();
            if (t0 - tc2_l).abs() > 2e-4 * tc2_l {
                Some((root, sl, t_l + dt_l * (root - tl)))
            } else {
                let (t, _, sl, _) = law.stress(root - t_hist);
                Some((root, sl, t))
            }
        } else {
            // q rises with T (the softening's elastic release heats more than the lower
            // stress saves) and no bound proves a single root: the general search for
            // the smallest root, on the scalar law
            let ((), q) = thermal::solve_self_heating(
                t_hist,
                self_c,
                q_h,
                (),
                pm.old.q,
                self.law.t_tol,
                |t| ((), q_of(t).0),
                |_, _, _| Some(()),
            );
            let root = t_hist + self_c * q;
            let (t, _, sl, _) = law.stress(root - t_hist);
            Some((root, sl, t))
        }
    }
}

/// The largest residual of a predictor-corrector root on the scalar path, relative to the
/// move's flash rise T - t_hist.
const PC_RESIDUAL: f64 = 1e-3;

/// The predictor-corrector ([`TemperatureSolve::PredictorCorrector`]) on the scalar path: the
/// root of t_hist + self_c q(T) = T for the heat q = a t - b t^2 + c (`coef`) of the law's
/// stress t(T), from the predictor t_hist + self_c q_pred (q_pred: the heat rate of the start
/// stress over the move's slip, as the general move's
/// [`Contact::predicted_heat`](super::Contact)). With the law's derivative, one evaluation
/// and a Newton step, the stress extrapolated to the root; without it (the higher-order
/// hardening law), the two evaluations of [`thermal::solve_predictor_corrector`]. Returns (T,
/// sliding, t at T), None where the exact search must run: no heat at a trial, heat that rises
/// with T, a bristle near the onset of sliding (t0 = tau_c2) or one that crosses it between
/// the trials or on the last step.
fn predictor_corrector_root(
    pm: &PathMove,
    law: &HardeningLaw,
    (a, b, c): (f64, f64, f64),
    miss: f64,
) -> Option<(f64, bool, f64)> {
    let (t_hist, self_c) = (pm.t_hist, pm.self_c);
    let heat = |t: f64| (a * t - b * t * t + c).max(0.0);
    let du = pm.mv.du();
    let q_start = (pm.kq_h * (pm.old.tau[0] * du[0] + pm.old.tau[1] * du[1])).max(0.0);
    let q_pred = if q_start > 0.0 { q_start } else { pm.old.q };
    let near_kink = |tc2: f64| (law.t0 - tc2).abs() <= 2e-4 * tc2;
    if law.start.is_some() && law.t0 < law.m_h.tc2 {
        // no derivative: the secants
        let ((t, sl, _), q) = thermal::solve_predictor_corrector(
            t_hist,
            self_c,
            q_pred,
            miss,
            |tk| {
                let (t, _, sl, tc2) = law.stress(tk - t_hist);
                ((t, sl, near_kink(tc2)), heat(t))
            },
            |x: &(f64, bool, bool), y: &(f64, bool, bool), w| {
                (x.1 == y.1).then_some((x.0 + w * (y.0 - x.0), x.1, false))
            },
            // a trial near the kink is refused
            |x| !x.2,
        )?;
        return Some((t_hist + self_c * q, sl, t));
    }
    // Newton from the predictor: g'(T) = self_c dq/dT - 1, dq/dT = (a - 2 b t) dt/dT; the
    // root and the stress extrapolated to it over the step
    let newton = |tk: f64| {
        let (t, dt, sl, tc2) = law.stress(tk - t_hist);
        let q = heat(t);
        let dq = (a - 2.0 * b * t) * dt;
        if !(q > 0.0 && dq <= 0.0) || near_kink(tc2) {
            return None;
        }
        let g = t_hist + self_c * q - tk;
        let root = tk + g / (1.0 - self_c * dq);
        // the branch at the root: sliding while t0 >= tau_c2 (falling with T, linear over
        // the step to well within the margin above)
        if (law.t0 >= tc2 * (1.0 - law.c2 * (root - tk))) != sl {
            return None;
        }
        Some((root, sl, t + dt * (root - tk), g))
    };
    let (root, sl, t, g0) = newton(t_hist + self_c * q_pred)?;
    // a second step where the predictor missed by more than `miss`, blended in between one
    // and two misses (as thermal::solve_predictor_corrector)
    let beta = (g0.abs() / miss - 1.0).clamp(0.0, 1.0);
    if beta == 0.0 {
        return Some((root, sl, t));
    }
    let (root2, sl2, t2, _) = newton(root)?;
    if sl2 != sl {
        return None;
    }
    Some((root + beta * (root2 - root), sl, t + beta * (t2 - t)))
}

/// A move's stress, regime, heat density (W/m^2) and temperature (degC) on its path.
type OnPath = ([f64; 2], Regime, f64, f64);

/// A move on a [`SofteningPath`] as the scalar solve sees it: the bristle before it, the move,
/// and the law's data at the temperature of the heat history.
struct PathMove<'a> {
    /// kq / h of the sub-step.
    kq_h: f64,
    np: &'a NodeP,
    /// The material at t_hist (with the operating point's formula and custom factors).
    m_h: &'a Material,
    old: &'a BristleState,
    mv: &'a Move,
    /// (L_x + L_e, L_y + L_e), m/Pa.
    l: [f64; 2],
    /// The elastic stress increment (Eq. 4.21), Pa.
    dtau: [f64; 2],
    /// The release weight (its reference is the stress at t_hist, as in the general solve).
    theta: f64,
    /// Temperature of the heat history, degC, and the flash temperature per heat density of
    /// the sub-step's own interval.
    t_hist: f64,
    self_c: f64,
    /// The higher-order rules apply (the heat's end weight 1/2 + QLIN), and a hardening
    /// bristle's start material under them.
    ho: bool,
    start: Option<MoveStart>,
    /// The law's stress at t_hist (the release reference), set by the hardening path.
    t_h: std::cell::Cell<f64>,
}

/// What a hardening bristle's law needs from the start of its move under the higher-order
/// rules.
#[derive(Clone, Copy)]
struct MoveStart {
    /// tau_c2 (Pa) and L_p (m) of the start material (start node, start temperature).
    tc2_0: f64,
    lp0: f64,
    /// The temperature profile's sqrt(s) part in L_p ([`crate::bristle::Along::lp_sqrt`]).
    lp_sqrt: f64,
}

impl PathMove<'_> {
    /// The start stress's weight in the heat: 1/2 (the trapezoid), 1/2 - QLIN under the
    /// higher-order rules.
    #[inline]
    fn w(&self) -> f64 {
        if self.ho {
            0.5 - super::bristle_move::QLIN
        } else {
            0.5
        }
    }

    /// The release stress of the end state `ns` (its reference: the law's stress at t_hist
    /// along the end stress's direction; the end stress itself off the hardening path).
    fn release_of(&self, ns: &BristleState) -> [f64; 2] {
        let t_h = self.t_h.get();
        if t_h.is_nan() {
            return ns.tau;
        }
        let t = (ns.tau[0] * ns.tau[0] + ns.tau[1] * ns.tau[1]).sqrt();
        let d = if t > 0.0 {
            [ns.tau[0] / t, ns.tau[1] / t]
        } else {
            [0.0, 0.0]
        };
        let r = [t_h * d[0], t_h * d[1]];
        [
            r[0] + self.theta * (ns.tau[0] - r[0]),
            r[1] + self.theta * (ns.tau[1] - r[1]),
        ]
    }

    /// (qbar, q1, q0) of the general move: the trapezoid's heat (at least 0) and the end and
    /// start stresses' heat rates over the plastic slip.
    fn heat_parts(&self, tau: [f64; 2], tau_r: [f64; 2]) -> (f64, f64, f64) {
        let (du, l, old) = (self.mv.du(), self.l, self.old);
        let dux = du[0] - l[0] * (tau_r[0] - old.tau[0]);
        let duy = du[1] - l[1] * (tau_r[1] - old.tau[1]);
        let tw = super::kin::trapezoid_stress(tau, old.tau);
        let qbar = (self.kq_h * (tw[0] * dux + tw[1] * duy)).max(0.0);
        let q1 = self.kq_h * (tau[0] * dux + tau[1] * duy);
        let q0 = self.kq_h * (old.tau[0] * dux + old.tau[1] * duy);
        (qbar, q1, q0)
    }

    /// q of Eq. 4.29 as in the law's evaluation: tau_w . (du - L (tau_r - tau_old)) kq / h,
    /// tau_r the release stress, tau_w = (tau + tau_old) / 2 (the trapezoid).
    #[inline]
    fn heat(&self, tau: [f64; 2], tau_r: [f64; 2]) -> f64 {
        if self.ho {
            // as the general move: the end-weighted heat from the parts, each at least 0
            let (qbar, q1, q0) = self.heat_parts(tau, tau_r);
            return super::bristle_move::end_weighted_heat(qbar, q1, q0);
        }
        let (du, l, old) = (self.mv.du(), self.l, self.old);
        let dux = du[0] - l[0] * (tau_r[0] - old.tau[0]);
        let duy = du[1] - l[1] * (tau_r[1] - old.tau[1]);
        let tw = super::kin::trapezoid_stress(tau, old.tau);
        (self.kq_h * (tw[0] * dux + tw[1] * duy)).max(0.0)
    }

    /// The heat density along `dir` as q = a t - b t^2 + c in the stress t, with the release
    /// stress tau_r = t_h + theta (t - t_h): returns (a, b, c). The dissipating stress is the
    /// trapezoid tau_w = (t dir + tau_old) / 2 ([`super::kin::trapezoid_stress`]): it halves
    /// the terms of the end stress and adds tau_old . slip / 2.
    fn heat_along(&self, dir: [f64; 2], t_h: f64) -> (f64, f64, f64) {
        let (kq_h, l, du, old, theta) = (self.kq_h, self.l, self.mv.du(), self.old, self.theta);
        let w = self.w();
        let bb = kq_h * (l[0] * dir[0] * dir[0] + l[1] * dir[1] * dir[1]);
        let a = kq_h
            * (dir[0] * (du[0] + l[0] * old.tau[0]) + dir[1] * (du[1] + l[1] * old.tau[1]))
            - bb * t_h * (1.0 - theta);
        let b = bb * theta;
        let o = old.tau;
        let dd = kq_h * (l[0] * o[0] * dir[0] + l[1] * o[1] * dir[1]);
        let c0 = kq_h * (o[0] * (du[0] + l[0] * o[0]) + o[1] * (du[1] + l[1] * o[1]))
            - dd * t_h * (1.0 - theta);
        ((1.0 - w) * a - w * dd * theta, (1.0 - w) * b, w * c0)
    }
}

/// The law's stress on a hardening path as a function of T: tau = t dir, t(T) from
/// tau_c2(T) = tau_c2(t_hist) exp(-c2 (T - t_hist)), L_p(T) = L_p(t_hist) exp(c_p (T -
/// t_hist)) (Eq. 4.3/4.4).
struct HardeningLaw<'a> {
    /// The material at t_hist.
    m_h: &'a Material,
    /// |tau| before the move, Pa, and the plastic slip |u1| - |u0|, m.
    t0: f64,
    dn: f64,
    /// Temperature coefficients of tau_c2 and L_p, 1/degC.
    c2: f64,
    cp: f64,
    /// exp(-dn / L_p) at t_hist.
    e_h: f64,
    /// The start material under the higher-order rules.
    start: Option<MoveStart>,
    /// Under the higher-order rules: 1/L_p of the start material (1/m), and
    /// ln(L_p(t_hist) / L_p0) (k of the profile mean at t_hist; k(T) = k_h + c_p (T -
    /// t_hist)).
    i0: f64,
    k_h: f64,
}

impl<'a> HardeningLaw<'a> {
    /// The law of the contact's layer from the material at t_hist.
    fn new(c: &Mover, m_h: &'a Material, t0: f64, dn: f64, start: Option<MoveStart>) -> Self {
        let (c2, cp) = (c.law.r.tc2_t, c.law.r.lp_t);
        let e_h = (-dn / m_h.lp).exp();
        let (i0, k_h) = match &start {
            Some(r) if r.lp0.is_finite() && r.lp0 > 0.0 => {
                let i0 = 1.0 / r.lp0;
                (i0, (i0 * m_h.lp).ln())
            }
            _ => (f64::NAN, f64::NAN),
        };
        Self {
            m_h,
            t0,
            dn,
            c2,
            cp,
            e_h,
            start,
            i0,
            k_h,
        }
    }

    /// [`crate::bristle::lp_mean`] over the whole move (from the start, not cold) on the
    /// scalar path: k from k_h without a logarithm, the exponentials by pairs. `lp`: the end
    /// material's L_p (m) at T = t_hist + `dtk`.
    #[inline]
    fn lp_mean(&self, r: &MoveStart, lp: f64, dtk: f64) -> f64 {
        if !self.i0.is_finite() {
            return crate::bristle::lp_mean(r.lp0, lp, r.lp_sqrt, 0.0, false);
        }
        let (i0, i1) = (self.i0, 1.0 / lp);
        let k = self.k_h + self.cp * dtk;
        let c = r.lp_sqrt;
        if c.is_finite() && c != 0.0 {
            let (x, w) = (crate::bristle::GL4_X, crate::bristle::GL4_W);
            let arg = |u: f64| -(c * u + (k - c) * u * u);
            let (e0, e1) = exp_pair(arg(x[0]), arg(x[1]));
            let (e2, e3) = exp_pair(arg(x[2]), arg(x[3]));
            let mean =
                2.0 * (w[0] * x[0] * e0 + w[1] * x[1] * e1 + w[2] * x[2] * e2 + w[3] * x[3] * e3);
            return 1.0 / (i0 * mean);
        }
        if k.abs() < 1e-9 {
            2.0 / (i0 + i1)
        } else {
            k / (i0 - i1)
        }
    }

    /// The hardening stress under the higher-order rules at tau_c2 = `tc2` (Pa), end L_p =
    /// `lp` (m), T = t_hist + `dtk`: the general move's law ([`crate::bristle::harden_lin`]
    /// with [`crate::bristle::lp_mean`]).
    #[inline]
    fn stress_ho(&self, r: &MoveStart, tc2: f64, lp: f64, dtk: f64) -> f64 {
        let lpe = self.lp_mean(r, lp, dtk);
        let dlt = tc2 - r.tc2_0;
        let dlt = if dlt.is_finite() { dlt } else { 0.0 };
        let x = self.dn / lpe;
        let e = exp_fast(-x);
        if dlt == 0.0 && lpe == lp {
            return tc2 - (tc2 - self.t0) * e;
        }
        let base = tc2 - (tc2 - self.t0) * e;
        if x.is_nan() || x <= 0.0 {
            return base;
        }
        // phi = (1 - e)/x - e; below x = 0.1 by its series sum_n (-1)^(n+1) n x^n / (n+1)!
        // to n = 8 (truncation below 3e-15 of phi), where 1 - e cancels
        let phi = if x < 0.1 {
            x * (1.0 / 2.0
                - x * (1.0 / 3.0
                    - x * (1.0 / 8.0
                        - x * (1.0 / 30.0
                            - x * (1.0 / 144.0
                                - x * (1.0 / 840.0 - x * (1.0 / 5760.0 - x * (1.0 / 45360.0))))))))
        } else {
            (1.0 - e) / x - e
        };
        (base - dlt * phi).min(tc2)
    }

    /// (t, dt/dT, sliding, tau_c2) at T = t_hist + `dtk`.
    #[inline]
    fn stress(&self, dtk: f64) -> (f64, f64, bool, f64) {
        let (m_h, t0, dn, c2, cp) = (self.m_h, self.t0, self.dn, self.c2, self.cp);
        let f = exp_fast(-c2 * dtk);
        let tc2 = m_h.tc2 * f;
        if t0 >= tc2 {
            return (tc2, -c2 * tc2, true, tc2);
        }
        let (lp, e) = if cp == 0.0 {
            (m_h.lp, self.e_h)
        } else {
            let lp = m_h.lp
                * if cp == c2 {
                    1.0 / f
                } else {
                    exp_fast(cp * dtk)
                };
            (lp, exp_fast(-dn / lp))
        };
        if let Some(r) = &self.start {
            // no derivative: this law takes the general search
            return (self.stress_ho(r, tc2, lp, dtk), f64::NAN, false, tc2);
        }
        // d/dT of tc2 - (tc2 - t0) e, e = exp(-dn / L_p)
        let de = e * dn * cp / lp;
        (
            tc2 - (tc2 - t0) * e,
            -c2 * tc2 * (1.0 - e) - (tc2 - t0) * de,
            false,
            tc2,
        )
    }

    /// (t, dt/dT) at t_hist itself, without an exponential: the law's value there.
    fn at_hist(&self) -> (f64, f64) {
        let (m_h, t0, dn, c2, cp, e_h) = (self.m_h, self.t0, self.dn, self.c2, self.cp, self.e_h);
        if t0 >= m_h.tc2 {
            (m_h.tc2, -c2 * m_h.tc2)
        } else if let Some(r) = &self.start {
            (self.stress_ho(r, m_h.tc2, m_h.lp, 0.0), f64::NAN)
        } else {
            let de = e_h * dn * cp / m_h.lp;
            (
                m_h.tc2 - (m_h.tc2 - t0) * e_h,
                -c2 * m_h.tc2 * (1.0 - e_h) - (m_h.tc2 - t0) * de,
            )
        }
    }
}
