//! The move of a bristle in a layer that only softens as it heats: its local temperature solved on the law's branch as a scalar function of T (Eq. 4.3, 4.7, 4.29, 4.35).
//!
//! The general move ([`Contact::update_bristle`]) solves T = t_hist + self_c q(T) by
//! evaluating the whole bristle law at trial temperatures, 2.5-2.8 times per move. Where
//! the layer only softens as it heats ([`crate::engine::FastPath::Softening`] with
//! [`crate::material::Resolved::monotone_softening`]: every preset with temperature) and the move's branch of the law cannot change on the way
//! up ([`SofteningPath`]: elastic below tau_c1, hardening while loading, sliding at
//! tau_c2), the law is a scalar function of T with an analytic derivative: Newton's method
//! on it needs about one exponential per move, and the new state follows from the root.
//! Elsewhere (unloading from the plastic branch, a trial that crosses the yield surface,
//! heat that rises with T faster than the solve can bound) the general solve runs.
//! Formula and custom effects that depend on the operating point only scale the strengths
//! by constants and keep the layer softening; effects on the local bristle state (p, T,
//! |u|, slip) take the general solve. Results agree with the general solve within its
//! tolerance (1e-4 relative change of the softening factors; tested in `tests/physics`).

use super::advance::Kin;
use super::Contact;
use crate::bristle::{BristleState, Material, Move, Regime, SofteningPath};
use crate::material::{exp_fast, NodeP};
use crate::thermal::{self, StepFactors, N_KERNEL};

impl Contact {
    /// [`Contact::update_bristle`] on the scalar path (see the module): advances one bristle
    /// by one sub-step with heat flow and returns its heat density q (W/m^2), or None with
    /// the bristle untouched where the general solve must run. `du` is the move's rigid slip
    /// (m) and `t_hist` the temperature of its heat history (degC, Eq. 4.35), both from
    /// [`Contact::update_bristle`].
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn update_softening<const W: bool>(
        &self,
        k: &Kin,
        np: &NodeP,
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
        let t0 = mv.t0().max(1.0);
        let gain = self_c * t0 * t0 * (k.lx.max(k.ly) + np.le) * self.r.cmax_t() / k.h;
        let theta = if gain > 0.8 { 0.8 / gain } else { 1.0 };
        // the material at t_hist (with the operating point's formula and custom factors)
        let m_h = self.material_static(np, t_hist);
        // flexibilities L + L_e and the elastic increment (Eq. 4.21); L_e does not depend on T
        let (lxe, lye, dtau) = k.flex(m_h.le, [x, y]);
        let path = mv.softening_path(&old, dtau, &m_h)?;
        // a weighted start stress (long continuous sub-steps) in its own instance, so that
        // the common moves run the unweighted code
        let (mut ns, q) = self.solve_on_path::<W>(
            k,
            np,
            &m_h,
            &old,
            &mv,
            [lxe, lye],
            dtau,
            path,
            theta,
            t_hist,
            self_c,
        )?;
        ns.temp = t_hist + self_c * q;
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
        let m = self.material_static(np, t);
        m.tc2 - m.tc1 <= 1e-12 * m.tc2
    }

    /// The new state and heat density of a move on a [`SofteningPath`] (see
    /// [`Contact::update_softening`]): the root of T = t_hist + self_c q(T) with q(T) the move's
    /// heat density as a scalar function of T (L_e independent of T), from the material `m_h`
    /// at t_hist, and the law's branch evaluated there. `l` = (L_x + L_e, L_y + L_e), `dtau`
    /// the elastic increment, `theta` the release weight (its reference is the stress at
    /// t_hist, as in the general solve). None if q does not fall with T and the scalar
    /// search fails, if an elastic bristle would yield at the root, or if the residual at the
    /// root is not within the tolerance: the caller then runs the general solve.
    #[allow(clippy::too_many_arguments)]
    fn solve_on_path<const WEIGHTED: bool>(
        &self,
        k: &Kin,
        np: &NodeP,
        m_h: &Material,
        old: &BristleState,
        mv: &Move,
        l: [f64; 2],
        dtau: [f64; 2],
        path: SofteningPath,
        theta: f64,
        t_hist: f64,
        self_c: f64,
    ) -> Option<(BristleState, f64)> {
        let kq_h = self.r.kq / k.h;
        let du = mv.du();
        let w = k.w_old;
        // q of Eq. 4.29 as in the law's evaluation: tau_w . (du - L (tau_r - tau_old)) kq / h,
        // tau_r the release stress, tau_w = tau - w (tau - tau_old) (w = 0 but for long
        // continuous sub-steps)
        let heat = |tau: [f64; 2], tau_r: [f64; 2]| {
            let dux = du[0] - l[0] * (tau_r[0] - old.tau[0]);
            let duy = du[1] - l[1] * (tau_r[1] - old.tau[1]);
            let tw = if WEIGHTED {
                super::advance::weighted_stress(tau, old.tau, w)
            } else {
                tau
            };
            (kq_h * (tw[0] * dux + tw[1] * duy)).max(0.0)
        };
        let (tau, regime, q, t) = match path {
            SofteningPath::Elastic => {
                // the stress does not depend on T: q is constant, the root one step away;
                // the bristle must still be elastic there
                let tr = [old.tau[0] + dtau[0], old.tau[1] + dtau[1]];
                let q = heat(tr, tr);
                let t = t_hist + self_c * q;
                let m = self.material_static(np, t);
                let ntr = (tr[0] * tr[0] + tr[1] * tr[1]).sqrt();
                if !(mv.t0() < m.tc1 && ntr <= m.tc1) {
                    return None;
                }
                (tr, Regime::Elastic, q, t)
            }
            SofteningPath::Hardening { t0, dn, dir } => {
                // tau = t dir, t(T) from tau_c2(T) = tau_c2(t_hist) exp(-c2 (T - t_hist)),
                // L_p(T) = L_p(t_hist) exp(c_p (T - t_hist)) (Eq. 4.3/4.4)
                let (c2, cp) = (self.r.tc2_t, self.r.lp_t);
                let e_h = (-dn / m_h.lp).exp();
                let stress = |dtk: f64| {
                    let f = exp_fast(-c2 * dtk);
                    let tc2 = m_h.tc2 * f;
                    if t0 >= tc2 {
                        return (tc2, -c2 * tc2, true, tc2);
                    }
                    let (lp, e) = if cp == 0.0 {
                        (m_h.lp, e_h)
                    } else {
                        let lp = m_h.lp
                            * if cp == c2 {
                                1.0 / f
                            } else {
                                exp_fast(cp * dtk)
                            };
                        (lp, exp_fast(-dn / lp))
                    };
                    // d/dT of tc2 - (tc2 - t0) e, e = exp(-dn / L_p)
                    let de = e * dn * cp / lp;
                    (
                        tc2 - (tc2 - t0) * e,
                        -c2 * tc2 * (1.0 - e) - (tc2 - t0) * de,
                        false,
                        tc2,
                    )
                };
                // at t_hist (no exponential): the law's value there
                let (t_h, dt_h) = if t0 >= m_h.tc2 {
                    (m_h.tc2, -c2 * m_h.tc2)
                } else {
                    let de = e_h * dn * cp / m_h.lp;
                    (
                        m_h.tc2 - (m_h.tc2 - t0) * e_h,
                        -c2 * m_h.tc2 * (1.0 - e_h) - (m_h.tc2 - t0) * de,
                    )
                };
                // along dir: q = a t - b t^2 + c with tau_r = t_h + theta (t - t_h) (c = 0
                // unless the start stress is weighted, w > 0: then tau_w = (1 - w) t dir +
                // w tau_old scales the first two terms by 1 - w and adds w tau_old . slip)
                let bb = kq_h * (l[0] * dir[0] * dir[0] + l[1] * dir[1] * dir[1]);
                let a = kq_h
                    * (dir[0] * (du[0] + l[0] * old.tau[0]) + dir[1] * (du[1] + l[1] * old.tau[1]))
                    - bb * t_h * (1.0 - theta);
                let b = bb * theta;
                let (a, b, c) = if !WEIGHTED {
                    (a, b, 0.0)
                } else {
                    let o = old.tau;
                    let dd = kq_h * (l[0] * o[0] * dir[0] + l[1] * o[1] * dir[1]);
                    let c0 = kq_h * (o[0] * (du[0] + l[0] * o[0]) + o[1] * (du[1] + l[1] * o[1]))
                        - dd * t_h * (1.0 - theta);
                    ((1.0 - w) * a - w * dd * theta, (1.0 - w) * b, w * c0)
                };
                // the last temperature evaluated and the law there: (T, t, dt/dT, sliding, tau_c2)
                let last = std::cell::Cell::new((t_hist, t_h, dt_h, t0 >= m_h.tc2, m_h.tc2));
                let q_of = |t_k: f64| {
                    let (t, dt, sl, tc2) = stress(t_k - t_hist);
                    last.set((t_k, t, dt, sl, tc2));
                    let q = a * t - b * t * t;
                    let q = if WEIGHTED { q + c } else { q };
                    if q <= 0.0 {
                        (0.0, 0.0)
                    } else {
                        (q, (a - 2.0 * b * t) * dt)
                    }
                };
                let q_h = a * t_h - b * t_h * t_h;
                let q_h = if WEIGHTED { q_h + c } else { q_h };
                let (q_h, dq_h) = if q_h <= 0.0 {
                    (0.0, 0.0)
                } else {
                    (q_h, (a - 2.0 * b * t_h) * dt_h)
                };
                // g(T) = t_hist + self_c q(T) - T falls on the whole bracket if q does, or, with
                // L_p independent of T, if self_c dq/dT < 1/2 at t_hist: there
                // |dq/dT| = c2 t |a - 2 b t| (sliding) or c2 tau_c2 (1 - e) |a - 2 b t|
                // (hardening) is largest, both factors falling with T
                let (root, sliding, t) = if dq_h <= 0.0 || (cp == 0.0 && self_c * dq_h < 0.5) {
                    let q_max = if dq_h <= 0.0 || b <= 0.0 {
                        q_h
                    } else {
                        // the vertex of a t - b t^2 + c bounds q where it rises
                        let v = a * a / (4.0 * b);
                        if WEIGHTED {
                            v + c
                        } else {
                            v
                        }
                    };
                    let (root, _) = thermal::solve_monotone(
                        t_hist,
                        self_c,
                        (q_h, dq_h),
                        q_max,
                        self.t_tol,
                        q_of,
                    )?;
                    // the stress at the root: extrapolated over the last step (shorter than
                    // the tolerance: tau_c2 changes by less than 1e-10 of itself over it)
                    // unless the bristle may cross tau_c2 = t0 on it
                    let (tl, t_l, dt_l, sl, tc2_l) = last.get();
                    if (t0 - tc2_l).abs() > 2e-4 * tc2_l {
                        (root, sl, t_l + dt_l * (root - tl))
                    } else {
                        let (t, _, sl, _) = stress(root - t_hist);
                        (root, sl, t)
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
                        old.q,
                        self.t_tol,
                        |t| ((), q_of(t).0),
                        |_, _, _| Some(()),
                    );
                    let root = t_hist + self_c * q;
                    let (t, _, sl, _) = stress(root - t_hist);
                    (root, sl, t)
                };
                // the span closes at one temperature and stays closed above it: open at the
                // root means open on the whole path from t_hist
                if self.r.span_may_close() && self.span_closed(np, root) {
                    return None;
                }
                let tau = [t * dir[0], t * dir[1]];
                let r = [t_h * dir[0], t_h * dir[1]];
                let tau_r = [
                    r[0] + theta * (tau[0] - r[0]),
                    r[1] + theta * (tau[1] - r[1]),
                ];
                let regime = if sliding {
                    Regime::Sliding
                } else {
                    Regime::Plastic
                };
                (tau, regime, heat(tau, tau_r), root)
            }
        };
        if (t_hist + self_c * q - t).abs() >= self.t_tol {
            return None;
        }
        let ns = BristleState {
            u: mv.u1(),
            tau,
            regime,
            ..*old
        };
        Some((ns, q))
    }
}
