//! One bristle's move over a sub-step: the bristle law (Sec. 4.1) under the local temperature solve (Eq. 4.35), and where an adhering bristle yields (the cold crossing, docs/model.md section 4).

use super::kin::{trapezoid_stress, Kin};
use super::law::Mover;
use crate::bristle::{self, BristleState, Material};
use crate::material::NodeP;
use crate::thermal::{self, StepFactors, N_KERNEL};
use std::cell::Cell;

/// The end stress's extra weight in the newest interval of Eq. 4.35 under the higher-order
/// rules: for a heat rate linear over the move the exact weights of its start and end rates
/// are 1/3 and 2/3, i.e. the mean plus 1/6 of the rise.
pub(super) const QLIN: f64 = 1.0 / 6.0;

/// The heat density of the newest interval of Eq. 4.35 under the higher-order rules, W/m^2:
/// the mean `qbar` plus [`QLIN`] of the rise from the start stress's rate `q0` to the end
/// stress's `q1` (each at least 0), at least 0.
#[inline]
pub(super) fn end_weighted_heat(qbar: f64, q1: f64, q0: f64) -> f64 {
    (qbar + QLIN * (q1.max(0.0) - q0.max(0.0))).max(0.0)
}

/// The state between two trial states `a` and `b` of a temperature solve, at weight `w`;
/// only within one regime (no kink between the ends).
fn lerp(a: &BristleState, b: &BristleState, w: f64) -> Option<BristleState> {
    (a.regime == b.regime).then(|| BristleState {
        tau: [
            a.tau[0] + w * (b.tau[0] - a.tau[0]),
            a.tau[1] + w * (b.tau[1] - a.tau[1]),
        ],
        sh: a.sh + w * (b.sh - a.sh),
        ..*a
    })
}

/// A general move as its temperature solve sees it: the bristle before the move, what the
/// law takes from the move whatever the trial temperature, and the reference of the damped
/// release.
struct TrialMove<'a> {
    c: &'a Mover<'a>,
    k: &'a Kin,
    /// The pressure parts at the end of the move.
    np: &'a NodeP,
    /// The midpoint of the move in the contact frame, m.
    xy: [f64; 2],
    old: BristleState,
    /// The move's rigid slip, m.
    du: [f64; 2],
    /// |u| of the bristle before the move (m) and its slip |du| / h, the material's local
    /// state.
    u_abs: f64,
    slip: f64,
    /// The temperature of the heat history, degC, and the material there where the setup
    /// evaluated it (kept for the solve's first evaluation).
    t_hist: f64,
    m_hist: Option<Material>,
    /// The flash temperature per heat density of the move's own interval, over the plastic
    /// remainder of the move for a bristle that yields on the way.
    self_c: f64,
    /// The bristle may ride on tau_c1 in this move.
    riding: bool,
    /// The release weight theta of the move's own elastic-release heat.
    theta: f64,
    /// (L_x + L_e, L_y + L_e, dtau) where L_e does not depend on the trial temperature.
    fixed: Option<(f64, f64, [f64; 2])>,
    /// The law's material-independent parts of the move (the same-characteristic rule).
    mv: Option<bristle::Move>,
    /// The higher-order rules' start material is set: the heat weighs the end stress by
    /// 1/2 + [`QLIN`].
    ho: bool,
    /// The stress the damped release is measured from; the first evaluation sets it.
    release_ref: Cell<Option<[f64; 2]>>,
}

impl TrialMove<'_> {
    /// The flexibilities L + L_e and the elastic increment (Eq. 4.21) for the layer's L_e.
    #[inline]
    fn flex(&self, le: f64) -> (f64, f64, [f64; 2]) {
        self.k.flex(le, self.xy)
    }

    /// The end state of the move at trial temperature `t` (degC) and its heat density q
    /// (W/m^2, 0 without heat flow).
    #[inline]
    fn trial(&self, t: f64) -> (BristleState, f64) {
        let m = match self.m_hist {
            Some(m) if t == self.t_hist => m,
            _ => self.c.law.material(self.np, t, self.u_abs, self.slip),
        };
        let (lxe, lye, dtau) = match self.fixed {
            Some(f) => f,
            None => self.flex(m.le),
        };
        let mut ns = self.old;
        match &self.mv {
            Some(mv) => bristle::update_move(&mut ns, mv, dtau, &m, [lxe, lye]),
            None => bristle::update(&mut ns, self.du, dtau, &m, [lxe, lye], self.c.law.r.on.rule),
        }
        let q = if self.k.heat {
            self.heat(&mut ns, [lxe, lye])
        } else {
            0.0
        };
        (ns, q)
    }

    /// The heat density (W/m^2) of the move to end state `ns` with flexibilities
    /// (L_x + L_e, L_y + L_e), m/Pa: the trapezoid stress over the plastic slip, with the elastic release
    /// weighed by theta from the release reference (Eq. 4.29); under the higher-order rules
    /// the end-weighted heat, with the mean kept in `ns.q`.
    #[inline]
    fn heat(&self, ns: &mut BristleState, [lxe, lye]: [f64; 2]) -> f64 {
        let (old, du, k) = (&self.old, self.du, self.k);
        let theta = self.theta;
        let tr = match self.release_ref.get() {
            Some(r) => [
                r[0] + theta * (ns.tau[0] - r[0]),
                r[1] + theta * (ns.tau[1] - r[1]),
            ],
            None => {
                self.release_ref.set(Some(ns.tau));
                ns.tau
            }
        };
        let dux = du[0] - lxe * (tr[0] - old.tau[0]);
        let duy = du[1] - lye * (tr[1] - old.tau[1]);
        let tw = trapezoid_stress(ns.tau, old.tau);
        let kq = self.c.law.r.kq;
        let qbar = (kq * (tw[0] * dux + tw[1] * duy) / k.h).max(0.0);
        if self.ho {
            // the heat rate linear over the move from the start stress's to the end
            // stress's: the newest interval of Eq. 4.35 weighs its end by 2/3,
            // 2 sqrt(h) (qbar + (q1 - q0)/6); ns.q keeps the mean qbar (the
            // accumulators' piecewise-constant heat)
            let q1 = kq * (ns.tau[0] * dux + ns.tau[1] * duy) / k.h;
            let q0 = kq * (old.tau[0] * dux + old.tau[1] * duy) / k.h;
            ns.q = qbar;
            end_weighted_heat(qbar, q1, q0)
        } else {
            qbar
        }
    }

    /// A bristle elastic at the start of the move makes no heat until it crosses tau_c1: it
    /// crosses at the yield stress of its temperature while elastic, t_hist, and its heat
    /// flows only over the plastic remainder (1 - lambda) h of the move, so that its
    /// self-heating is 2 alpha C q sqrt(h) / sqrt(1 - lambda) for the move's mean heat
    /// density q (docs/model.md section 4). Sets the move's cold yield, `self_c` and the
    /// material at t_hist of such a bristle under the same-characteristic rule with heat.
    #[inline]
    fn set_cold_crossing(&mut self) {
        let (c, k, np, old) = (self.c, self.k, self.np, self.old);
        if !(self.mv.is_some()
            && c.law.r.on.temperature
            && k.heat
            && old.regime == bristle::Regime::Elastic)
        {
            return;
        }
        let (t_hist, u_abs, slip) = (self.t_hist, self.u_abs, self.slip);
        let m = c.law.material(np, t_hist, u_abs, slip);
        let dtau = match self.fixed {
            Some(f) => f.2,
            None => self.flex(m.le).2,
        };
        let tc1_of = |p: &NodeP| c.law.material(p, t_hist, u_abs, slip).tc1;
        let tc1 = c.crossing_yield(k, np, self.xy, [old.tau, dtau], m.tc1, tc1_of);
        if let Some(mv) = self.mv.as_mut() {
            let lam = mv.set_cold_yield(&old, dtau, tc1);
            if lam > 0.0 && lam < 1.0 {
                self.self_c /= (1.0 - lam).sqrt();
            }
        }
        self.m_hist = Some(m);
    }

    /// The higher-order rules (docs/model.md section 3.3): the start material is the
    /// start node `np0`'s at the bristle's temperature at the start of the move, the same for
    /// every trial temperature; the temperature profile's sqrt(s) part is the self-heating of
    /// the jump of the heat rate at the start of the move, from the old stress over the rigid
    /// slip against the previous move's mean heat. Sets the move's [`bristle::Along`].
    #[inline]
    fn set_start_material(&mut self, np0: &NodeP) {
        let Some(mv) = &self.mv else {
            return;
        };
        let c = self.c;
        let m0 = c.law.material(np0, self.old.temp, self.u_abs, self.slip);
        let lp_sqrt = if c.law.r.on.temperature && self.k.heat {
            c.lp_sqrt(self.k, self.self_c, &self.old, self.du)
        } else {
            f64::NAN
        };
        mv.set_along(bristle::Along {
            tc2_start: m0.tc2,
            lp_start: m0.lp,
            lp_sqrt,
        });
        self.ho = true;
    }

    /// The reference of the damped release (theta < 1) of a bristle that heated in its
    /// previous move: its stress at the predictor t_hist + self_c q_prev, the estimate of its
    /// end temperature for a heat that goes on. At t_hist instead, colder by the previous
    /// move's own heat (O(sqrt h)), the damped release took the stress change of that
    /// cooling, which outweighs the move's heat (O(h)): on fine grids a bristle riding on
    /// tau_c1 jumped off it and the sliding zone lost heat (docs/model.md section 6).
    /// Under the higher-order rules (`higher_order`) the temperature of the previous
    /// move is the end-weighted heat's and its history the mean heat's, so on short moves the
    /// predictor misses the bristle's temperature by their difference: there only a riding
    /// bristle takes it. (Measured for the default rule, the same characteristic; elastic
    /// unloading keeps t_hist.) Elsewhere the first evaluation of the solve sets it. `eval`:
    /// [`TrialMove::trial`], the closure the solve takes too.
    #[inline]
    fn seed_release_reference(
        &self,
        higher_order: bool,
        eval: impl Fn(f64) -> (BristleState, f64),
    ) {
        let old = &self.old;
        if self.theta < 1.0
            && self.self_c > 0.0
            && old.q > 0.0
            && self.c.law.r.on.rule == bristle::Rule::SameCharacteristic
            && (self.riding || !higher_order)
        {
            let (at_predictor, _) = eval(self.t_hist + self.self_c * old.q);
            if !(at_predictor.tau[0].is_finite() && at_predictor.tau[1].is_finite()) {
                // no finite stress at the predictor (a runaway heat history, e.g. a layer
                // whose compliance grows with T without bound): the reference stays at t_hist
                self.release_ref.set(None);
            }
        }
    }

    /// The end state and heat density of the move at the root of T = t_hist + self_c q(T)
    /// (Eq. 4.35). A sliding bristle that heated in its previous move starts the solve at the
    /// predictor; this is valid where the root is unique (a bristle sliding at tau_c2(T),
    /// whose heat falls with T) and the release is not damped; otherwise (or when a trial
    /// state is not sliding) the full solve from t_hist. Plastic bristles are left to the
    /// full solve: an elastic state at t_hist can be the smallest root there. `eval`:
    /// [`TrialMove::trial`].
    #[inline]
    fn solve(&self, eval: impl Fn(f64) -> (BristleState, f64) + Copy) -> (BristleState, f64) {
        let (t_hist, self_c, old) = (self.t_hist, self.self_c, &self.old);
        let temperature = self.c.law.r.on.temperature;
        let t_tol = self.c.law.t_tol;
        let sliding = |s: &BristleState| s.regime == bristle::Regime::Sliding;
        let from_predictor = temperature && self_c > 0.0 && old.q > 0.0 && self.theta == 1.0;
        if from_predictor
            && self.c.law.t_solve == thermal::TemperatureSolve::PredictorCorrector
            && old.regime != bristle::Regime::Elastic
        {
            // the cheaper solve where it applies (thermal::solve_predictor_corrector): a
            // bristle that heated in its previous move and yields at both trials (an
            // adhering state may be a smaller root: the exact solve searches from t_hist)
            let on_branch = |s: &BristleState| s.regime != bristle::Regime::Elastic;
            let q_pred = self.c.predicted_heat(self.k, old, self.du);
            if let Some(r) = thermal::solve_predictor_corrector(
                t_hist,
                self_c,
                q_pred,
                self.c.law.pc_miss,
                eval,
                lerp,
                on_branch,
            ) {
                return r;
            }
        }
        let predicted = if from_predictor && sliding(old) {
            thermal::solve_from_predictor(t_hist, self_c, old.q, t_tol, eval, lerp, sliding)
        } else {
            None
        };
        let (mut ns, mut q) = match predicted {
            Some(r) => r,
            None => eval(t_hist),
        };
        if predicted.is_none() && temperature && q > 0.0 && self_c > 0.0 {
            (ns, q) = thermal::solve_self_heating(t_hist, self_c, q, ns, old.q, t_tol, eval, lerp);
        }
        (ns, q)
    }
}

impl Mover<'_> {
    /// Advances one bristle by one sub-step; returns its heat density q (W/m^2, both bodies).
    /// `np0`: the pressure parts at the start of the move under the higher-order rules
    /// ([`super::Scheme::CellsHigher`]), None otherwise.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn update_bristle(
        &self,
        k: &Kin,
        np: &NodeP,
        np0: Option<&NodeP>,
        [x, y]: [f64; 2],
        s: &mut BristleState,
        acc: &mut [f64; N_KERNEL],
        fac: &StepFactors,
    ) -> f64 {
        let du = k.rigid_slip([x, y]);
        // acc[0] integrates all heat ever received (rate 0): zero means a cold history
        let warm = acc[0] != 0.0;
        let t_hist = self.t_hist(k, acc, fac);
        // a layer that only softens as it heats: the scalar solve (module `softening`)
        if self.law.fast.softening && k.heat {
            if let Some(q) = self.update_softening(k, np, np0, [x, y], du, t_hist, s, acc, fac) {
                return q;
            }
        }
        let mut tm = self.trial_move(k, np, [x, y], du, t_hist, *s);
        tm.set_cold_crossing();
        if let Some(np0) = np0 {
            tm.set_start_material(np0);
        }
        let eval = |t: f64| tm.trial(t);
        tm.seed_release_reference(np0.is_some(), eval);
        let (mut ns, q) = tm.solve(eval);
        ns.temp = if self.law.r.on.temperature {
            t_hist + tm.self_c * q
        } else {
            k.t_bulk
        };
        // the higher-order rules: the temperature from the end-weighted heat, the
        // accumulators (and the friction power) from the move's mean heat
        let q = if tm.ho && k.heat && q > 0.0 { ns.q } else { q };
        ns.q = q;
        *s = ns;
        if self.law.r.on.temperature && k.heat && (warm || q > 0.0) {
            fac.accumulate(acc, q); // alpha is folded into alpha_c
        }
        q
    }

    /// The general move of bristle `old` by the rigid slip `du` (m) at midpoint `xy` to the
    /// end node `np`, for its temperature solve from the heat history's `t_hist`: the release
    /// weight, the flexibilities where they do not depend on T and the law's
    /// material-independent parts.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn trial_move<'a>(
        &'a self,
        k: &'a Kin,
        np: &'a NodeP,
        xy: [f64; 2],
        du: [f64; 2],
        t_hist: f64,
        old: BristleState,
    ) -> TrialMove<'a> {
        // displacements and stresses are far from overflow: sqrt instead of hypot
        let u_abs = (old.u[0] * old.u[0] + old.u[1] * old.u[1]).sqrt();
        let slip = if k.h > 0.0 {
            (du[0] * du[0] + du[1] * du[1]).sqrt() / k.h
        } else {
            0.0
        };
        // A plastic bristle below the yield stress tau_c1 of its heat history's temperature
        // may ride on tau_c1 in this move (the floor of the law, `bristle::update`), where its
        // heat follows tau_c1(T): the release weight then bounds tau_c1's temperature
        // coefficient too (docs/model.md section 6). The material at t_hist is the
        // solve's first evaluation, kept for it.
        let m_plastic = (self.law.r.on.temperature
            && k.heat
            && old.regime == bristle::Regime::Plastic
            && self.law.r.on.rule == bristle::Rule::SameCharacteristic)
            .then(|| self.law.material(np, t_hist, u_abs, slip));
        let riding = m_plastic.is_some_and(|m| bristle::norm(old.tau) < m.tc1);
        let theta = self.release_weight(k, np, old.tau, riding);
        // Without a temperature coefficient of L_e (every preset) and without formula
        // effects, material_base gives L_e = the node's (divided by exactly 1): the same for
        // every trial temperature, so this is computed once per move, not per evaluation.
        let fixed = self.law.fast.fixed_le.then(|| k.flex(np.le, xy));
        // the law's material-independent parts of this move, shared by all evaluations
        let mv = (self.law.r.on.rule == bristle::Rule::SameCharacteristic)
            .then(|| bristle::Move::new(&old, du));
        TrialMove {
            c: self,
            k,
            np,
            xy,
            old,
            du,
            u_abs,
            slip,
            t_hist,
            m_hist: m_plastic,
            self_c: k.self_c,
            riding,
            theta,
            fixed,
            mv,
            ho: false,
            release_ref: Cell::new(None),
        }
    }

    /// [`bristle::Along::lp_sqrt`] of the move of bristle `old` by the rigid slip `du` (m)
    /// under the higher-order rules: X_T,Lp A, A = `self_c` times the jump of the heat rate at
    /// the start of the move (the old stress over the rigid slip against the previous move's
    /// mean heat).
    #[inline]
    pub(super) fn lp_sqrt(&self, k: &Kin, self_c: f64, old: &BristleState, du: [f64; 2]) -> f64 {
        self.law.r.lp_t * self_c * (self.start_heat(k, old, du) - old.q)
    }

    /// The heat rate (W/m^2) of bristle `old`'s stress over the rigid slip `du` (m) of its
    /// move: its heat at the start of the move, at least 0.
    #[inline]
    fn start_heat(&self, k: &Kin, old: &BristleState, du: [f64; 2]) -> f64 {
        (self.law.r.kq * (old.tau[0] * du[0] + old.tau[1] * du[1]) / k.h).max(0.0)
    }

    /// The predictor of the predictor-corrector's heat density (W/m^2) for the move of bristle
    /// `old` by the rigid slip `du` (m): its heat at the start of the move
    /// ([`Mover::start_heat`]), which follows the move's own slip and misses the move's heat
    /// by 3-10 times less than the previous move's heat `old.q` (which stands in where the
    /// start's is 0).
    #[inline]
    pub(super) fn predicted_heat(&self, k: &Kin, old: &BristleState, du: [f64; 2]) -> f64 {
        let q = self.start_heat(k, old, du);
        if q > 0.0 {
            q
        } else {
            old.q
        }
    }

    /// The temperature of a bristle from its heat history (all but the newest interval,
    /// Eq. 4.35), degC; the bulk temperature for a cold history or without heat.
    #[inline]
    fn t_hist(&self, k: &Kin, acc: &[f64; N_KERNEL], fac: &StepFactors) -> f64 {
        if self.law.r.on.temperature && k.heat && acc[0] != 0.0 {
            k.t_bulk + k.alpha_c * fac.history(acc)
        } else {
            k.t_bulk
        }
    }

    /// The weight theta (0 < theta <= 1) of the move's own elastic-release heat. That heat
    /// (the -L dtau part of Eq. 4.29), caused by the sub-step's own self-heating, feeds back
    /// on the temperature with a gain of about self_c |tau|^2 (L_x + L_e) X_T / h, which grows
    /// like 1/sqrt(h): below ~1 us the implicit solve would run away (the half-space kernel
    /// has no heat capacity of the layer to stop it). theta = min(1, 0.8/gain): fully
    /// implicit while the sub-step's temperature equation is a contraction with margin
    /// (gain < 0.8), damped only for tiny sub-steps (docs/model.md, section 6). `riding`: the
    /// bristle may ride on tau_c1 in this move, whose coefficient then counts in X_T
    /// ([`crate::material::Resolved::release_t_riding`]).
    #[inline]
    pub(super) fn release_weight(&self, k: &Kin, np: &NodeP, tau: [f64; 2], riding: bool) -> f64 {
        if !(k.heat && self.law.r.on.temperature) {
            return 1.0;
        }
        let cmax = if riding {
            self.law.r.release_t_riding()
        } else {
            self.law.r.release_t()
        };
        let t0 = (tau[0] * tau[0] + tau[1] * tau[1]).sqrt().max(1.0);
        let gain = k.self_c * t0 * t0 * (k.lx.max(k.ly) + np.le) * cmax / k.h;
        if gain > 0.8 {
            0.8 / gain
        } else {
            1.0
        }
    }

    /// The yield stress tau_c1 (Pa) at which a bristle that is elastic at the start of a move
    /// (stress `tau` at its start, elastic increment `dtau`; `tc1_end` the yield stress at the move's end
    /// node `np`, `tc1_of` that at any point, both at the temperature the bristle has while
    /// elastic) leaves the elastic branch. Where the
    /// pressure, and with it tau_c1, rises along the move (towards the middle of the
    /// contact), the crossing is found at its own position: near the leading edge the
    /// pressure grows like the square root of the distance from the edge, so the end node's
    /// tau_c1 overstates the yield stress at the crossing by O(sqrt(dx)), an error of order
    /// 1/2 that the hardening and the heat of the bristle carry downstream (docs/model.md,
    /// section 4). Elsewhere, or when the trial stays elastic, the end node's tau_c1.
    fn crossing_yield(
        &self,
        k: &Kin,
        np: &NodeP,
        [x, y]: [f64; 2],
        [tau, dtau]: [[f64; 2]; 2],
        tc1_end: f64,
        tc1_of: impl Fn(&NodeP) -> f64,
    ) -> f64 {
        let norm = |l: f64| {
            let t = [tau[0] + l * dtau[0], tau[1] + l * dtau[1]];
            (t[0] * t[0] + t[1] * t[1]).sqrt()
        };
        let t0 = norm(0.0);
        if !(t0 < tc1_end && norm(1.0) > tc1_end) {
            return tc1_end;
        }
        let (a, b) = (self.patch.a, self.patch.b);
        let eta = if self.patch.line { 0.0 } else { y / b };
        // the move runs from xi(0) to xi(1) = the end node; x is its midpoint
        let xi = |l: f64| (x + k.dist * (0.5 - l)) / a;
        let np0 = self.law.r.node_p(self.patch, xi(0.0), eta);
        if np0.p >= np.p {
            return tc1_end;
        }
        let tc1_at = |l: f64| tc1_of(&self.law.r.node_p(self.patch, xi(l), eta));
        // g(l) = |tau(l)| - tc1(l): g(1) > 0; g(0) <= 0 for a bristle below its yield stress.
        // Solved in r = sqrt(l): near the leading edge tc1 rises like sqrt(l), which is
        // singular in l but linear in r, so the regula falsi converges at its usual rate.
        let g = |r: f64| norm(r * r) - tc1_at(r * r);
        let (mut ra, mut ga) = (0.0, t0 - tc1_at(0.0));
        let (mut rb, mut gb) = (1.0, norm(1.0) - tc1_end);
        if ga > 0.0 {
            // already at or above the yield stress of its start position: it yields at once,
            // at its own stress (the limit of a crossing at lambda -> 0, so the outputs stay
            // continuous in the inputs)
            return t0;
        }
        // Illinois regula falsi to a crossing within 1e-13 in r, with bisection steps when
        // it stalls: the outputs must be smooth in the inputs to rounding (docs/model.md section 6)
        // (a bristle entering at the leading edge starts with g(0) = 0, no stress and no
        // strength, and is below its yield stress just after: bisect until g(ra) < 0)
        let mut side = 0;
        for it in 0..100 {
            let r = if it % 8 == 7 || ga == 0.0 {
                0.5 * (ra + rb)
            } else {
                (ra * gb - rb * ga) / (gb - ga)
            };
            let gr = g(r);
            if gr > 0.0 {
                (rb, gb) = (r, gr);
                if side == 1 {
                    ga *= 0.5;
                }
                side = 1;
            } else {
                (ra, ga) = (r, gr);
                if side == -1 {
                    gb *= 0.5;
                }
                side = -1;
            }
            if rb - ra < 1e-13 {
                break;
            }
        }
        // the yield stress the stress path meets at the crossing
        let r = 0.5 * (ra + rb);
        norm(r * r)
    }
}
