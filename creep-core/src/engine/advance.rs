//! Advancing the bristles: one bristle move with its local temperature (Eq. 4.16, 4.21, 4.35), sub-steps of a strip, the march of new bristles.

use super::kin::{trapezoid_stress, Kin};
use super::law::Mover;
use super::strip::Strip;
use crate::bristle::{self, BristleState};
use crate::material::NodeP;
use crate::thermal::{StepFactors, N_KERNEL};

/// The edge of the contact a graded move ends at ([`Mover::graded_moves`]).
#[derive(Clone, Copy)]
enum Edge {
    Leading,
    Trailing,
}

/// Entries of the kernel-factor cache (distinct sub-step lengths kept).
const FAC_CACHE: usize = 8;

/// Sub-moves of the move that starts at the leading edge under the higher-order rules
/// ([`super::Scheme::CellsHigher`]), graded at (i/EDGE_SUB)^2 of the move.
pub const EDGE_SUB: usize = 4;

impl Mover<'_> {
    /// One sub-step of strip `sp`: bristles move by `dist` (m) in time `h` (s); the phase is
    /// advanced by the caller. Nodes are evaluated at their end-of-sub-step positions.
    pub(super) fn substep_strip(
        &self,
        sp: &mut Strip,
        h: f64,
        dist: f64,
        phase_end: f64,
        skip: usize,
        end: usize,
    ) {
        let kin = self.kin(h, dist);
        self.substep_strip_kin(sp, &kin, phase_end, skip, end);
    }

    /// [`Self::substep_strip`] with the sub-step's kinematics given.
    pub(super) fn substep_strip_kin(
        &self,
        sp: &mut Strip,
        kin: &Kin,
        phase_end: f64,
        skip: usize,
        end: usize,
    ) {
        let (nx, j) = (self.lat.nx, sp.j);
        let dxi = 2.0 * self.lat.ell[j] / nx as f64;
        let fac = self.factors(sp.fac, kin.h, kin.heat);
        let inside = if phase_end > 0.0 { nx } else { nx + 1 };
        // the moves start on the lattice nodes where the bristles are at their node states
        // (whole-cell commit): the move covers phase_end of a cell. Not so after the node
        // states were reset where the bristles stand (a reversal, a lift-off, an old state)
        let from_nodes =
            self.law.start_cache && (kin.dist / self.patch.a - phase_end * dxi).abs() <= 1e-9 * dxi;
        if phase_end == 1.0 {
            // full-cell moves end on the lattice nodes: their pressure parts are cached
            self.lattice_nodes(j, sp.nodes, sp.nodes_p0);
            for slot in skip..inside.min(end) {
                let xi = self.lat.ell[j] - (slot as f64 + phase_end) * dxi;
                let id = sp.slot(slot);
                if !sp.owns(id) {
                    continue;
                }
                let (s, ac) = (&mut sp.st[id], &mut sp.acc[id]);
                // the move's start node (higher-order rules): lattice node `slot`, cached
                // except at the leading edge
                let np0 = (from_nodes && slot > 0).then(|| &sp.nodes[slot]);
                self.move_bristle_with(j, xi, &sp.nodes[slot + 1], np0, kin, &fac, s, ac);
            }
        } else {
            // partial moves from the lattice nodes: the start node's pressure parts
            // (higher-order rules) are cached
            let from_nodes = self.law.ho && from_nodes;
            if from_nodes {
                self.lattice_nodes(j, sp.nodes, sp.nodes_p0);
            }
            for slot in skip..inside.min(end) {
                let xi = self.lat.ell[j] - (slot as f64 + phase_end) * dxi;
                let id = sp.slot(slot);
                if !sp.owns(id) {
                    continue;
                }
                let (s, ac) = (&mut sp.st[id], &mut sp.acc[id]);
                let np0 = (from_nodes && slot > 0).then(|| &sp.nodes[slot]);
                self.move_bristle(j, xi, np0, kin, &fac, s, ac);
            }
        }
    }

    /// Kernel factors of a sub-step of length `h` (identity when no heat flows), from a small
    /// cache keyed by h: a march and the full-cell sub-steps of a step repeat the same h.
    pub(super) fn factors(
        &self,
        cache: &mut Vec<(f64, StepFactors)>,
        h: f64,
        heat: bool,
    ) -> StepFactors {
        if !(self.law.r.on.temperature && heat) {
            return StepFactors::identity(h);
        }
        if let Some((_, f)) = cache.iter().find(|(hh, _)| *hh == h) {
            return *f;
        }
        let f = self.law.kernel.factors(h);
        if cache.len() >= FAC_CACHE {
            cache.remove(0);
        }
        cache.push((h, f));
        f
    }

    /// Moves one bristle of strip `j` over `kin.dist` to its end position `xi_end`
    /// (normalized). The material is taken at the end of the sub-step (Eq. 4.5), but never
    /// closer to the trailing edge than [`super::grid::TRAILING_NODE`] of a cell: the last node
    /// stands for the last cell (docs/model.md section 3); the spin lever arm is the path's
    /// midpoint. `np0`: the start node's pressure parts where cached (see
    /// [`Self::move_bristle_with`]).
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn move_bristle(
        &self,
        j: usize,
        xi_end: f64,
        np0: Option<&NodeP>,
        kin: &Kin,
        fac: &StepFactors,
        s: &mut BristleState,
        acc: &mut [f64; N_KERNEL],
    ) {
        let dxi = 2.0 * self.lat.ell[j] / self.lat.nx as f64;
        let np = self.law.r.node_p(
            self.patch,
            xi_end.max(-self.lat.ell[j] + super::grid::TRAILING_NODE * dxi),
            self.lat.eta[j],
        );
        self.move_bristle_with(j, xi_end, &np, np0, kin, fac, s, acc);
    }

    /// [`Self::move_bristle`] with the pressure parts `np` of the end node given (the march
    /// takes them from the per-load cache of the lattice nodes), and, where cached, those of
    /// the start node `np0_cached` (a full-cell move from lattice node k >= 1; read by the
    /// higher-order rules only). Under the higher-order rules the move that starts at the
    /// leading edge is made of [`EDGE_SUB`] sub-moves ending at (i/EDGE_SUB)^2 of it: the
    /// pressure rises like sqrt(s) there and the layer yields and heats within the first
    /// cell (docs/model.md section 3.3).
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn move_bristle_with(
        &self,
        j: usize,
        xi_end: f64,
        np: &NodeP,
        np0_cached: Option<&NodeP>,
        kin: &Kin,
        fac: &StepFactors,
        s: &mut BristleState,
        acc: &mut [f64; N_KERNEL],
    ) {
        let a = self.patch.a;
        let xi0 = xi_end + kin.dist / a;
        if self.law.ho && xi0 >= self.lat.ell[j] - 1e-12 && kin.h > 0.0 {
            self.graded_moves(j, xi0, xi_end, Some(np), kin, Edge::Leading, s, acc);
            return;
        }
        // the move that ends at the trailing edge under the higher-order rules, with heat: the
        // temperatures along it from sub-moves graded toward the edge (below)
        let dxi = 2.0 * self.lat.ell[j] / self.lat.nx as f64;
        let trailing = self.law.ho
            && self.law.r.on.temperature
            && kin.heat
            && kin.h > 0.0
            && xi_end <= -self.lat.ell[j] + 1e-9 * dxi;
        let start = if trailing { Some((*s, *acc)) } else { None };
        self.move_bristle_one(j, xi_end, np, np0_cached, kin, fac, s, acc);
        // the trailing node's temperature: the highest the bristle reaches over its last cell
        if let Some((mut s0, mut acc0)) = start {
            s.temp = self.graded_moves(
                j,
                xi0,
                xi_end,
                None,
                kin,
                Edge::Trailing,
                &mut s0,
                &mut acc0,
            );
        }
    }

    /// The move of strip `j` from `xi0` over `kin.dist` to `xi_end`, at an edge of the contact, as
    /// [`EDGE_SUB`] sub-moves graded toward that edge, where the pressure goes like the square
    /// root of the distance from it. *Leading*: the sub-moves end at (i/EDGE_SUB)^2 of the
    /// move, the last one on the end node `np_end`; the layer yields and heats within the
    /// first cell (docs/model.md section 3.3). *Trailing*: they end at
    /// 1 - (1 - i/EDGE_SUB)^2 of it, the last one's material [`super::grid::TRAILING_NODE`] of
    /// its own length inside the edge; the falling pressure lets the layer release its stress
    /// within the last cell, and that release heats the bristle to the contact's highest
    /// temperature (the caller keeps only the temperature: docs/model.md section 3.3).
    /// Returns the highest temperature at the sub-moves' ends, degC. The sub-moves'
    /// kernel factors come from one exp and expm1 per term (the two gradings have the same
    /// sub-move lengths, in reverse).
    #[allow(clippy::too_many_arguments)]
    fn graded_moves(
        &self,
        j: usize,
        xi0: f64,
        xi_end: f64,
        np_end: Option<&NodeP>,
        kin: &Kin,
        edge: Edge,
        s: &mut BristleState,
        acc: &mut [f64; N_KERNEL],
    ) -> f64 {
        let (a, n) = (self.patch.a, EDGE_SUB);
        let dxi = 2.0 * self.lat.ell[j] / self.lat.nx as f64;
        let frac = |i: usize| match edge {
            Edge::Leading => {
                let f = i as f64 / n as f64;
                f * f
            }
            Edge::Trailing => {
                let f = 1.0 - i as f64 / n as f64;
                1.0 - f * f
            }
        };
        let heat = self.law.r.on.temperature && kin.heat;
        let graded = heat.then(|| self.law.kernel.graded_factors::<EDGE_SUB>(kin.h));
        // sub-move i starts where i - 1 ended: its start node is that one's end node
        let mut np_prev: Option<NodeP> = None;
        let mut peak = f64::NEG_INFINITY;
        for i in 1..=n {
            let df = frac(i) - frac(i - 1);
            let (h, d) = (kin.h * df, kin.dist * df);
            let ki = Kin {
                h,
                dist: d,
                self_c: if kin.heat {
                    kin.alpha_c * 2.0 * h.sqrt()
                } else {
                    0.0
                },
                ..*kin
            };
            // sub-move lengths (2k - 1)/n^2 of the move: the k-th of the leading grading
            let fi = match (&graded, edge) {
                (Some(g), Edge::Leading) => g[i - 1],
                (Some(g), Edge::Trailing) => g[n - i],
                (None, _) => StepFactors::identity(h),
            };
            let xe = if i == n {
                xi_end
            } else {
                xi0 - frac(i) * kin.dist / a
            };
            let npi = match (np_end, i == n) {
                (Some(np), true) => *np,
                _ => {
                    let inside = match edge {
                        Edge::Leading => super::grid::TRAILING_NODE * dxi,
                        Edge::Trailing => super::grid::TRAILING_NODE * d / a,
                    };
                    self.law.r.node_p(
                        self.patch,
                        xe.max(-self.lat.ell[j] + inside),
                        self.lat.eta[j],
                    )
                }
            };
            self.move_bristle_one(j, xe, &npi, np_prev.as_ref(), &ki, &fi, s, acc);
            peak = peak.max(s.temp);
            np_prev = self.law.start_cache.then_some(npi);
        }
        peak
    }

    /// One move of [`Self::move_bristle_with`] (no sub-moves).
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn move_bristle_one(
        &self,
        j: usize,
        xi_end: f64,
        np: &NodeP,
        np0_cached: Option<&NodeP>,
        kin: &Kin,
        fac: &StepFactors,
        s: &mut BristleState,
        acc: &mut [f64; N_KERNEL],
    ) {
        let a = self.patch.a;
        let y = if self.patch.line {
            0.0
        } else {
            self.lat.eta[j] * self.patch.b
        };
        let x_mid = a * (xi_end + 0.5 * kin.dist / a);
        // the higher-order rules' start node: pressure parts at the start of the move, clamped
        // as the end node is
        let np0 = self.law.ho.then(|| match np0_cached {
            Some(n0) => *n0,
            None => {
                let dxi = 2.0 * self.lat.ell[j] / self.lat.nx as f64;
                let xi0 = (xi_end + kin.dist / a)
                    .max(-self.lat.ell[j] + super::grid::TRAILING_NODE * dxi);
                self.law.r.node_p(self.patch, xi0, self.lat.eta[j])
            }
        });
        if self.law.fast.cold {
            self.update_bristle_cold(kin, np, np0.as_ref(), [x_mid, y], s);
        } else {
            self.update_bristle(kin, np, np0.as_ref(), [x_mid, y], s, acc, fac);
        }
    }

    /// [`Self::update_bristle`] on the fast path [`super::FastPath::Cold`] (what it supports:
    /// engine/fastpath.rs `COLD`; FASTSIM, isothermal ECF): the same operations without the
    /// temperature solve and the heat kernel.
    #[inline]
    fn update_bristle_cold(
        &self,
        k: &Kin,
        np: &NodeP,
        np0: Option<&NodeP>,
        [x, y]: [f64; 2],
        s: &mut BristleState,
    ) {
        let du = k.rigid_slip([x, y]);
        let m = self.law.r.material_base(np, k.t_bulk);
        let (lxe, lye, dtau) = k.flex(m.le, [x, y]);
        let old = s.tau;
        match np0 {
            // the higher-order rules: tau_c2 and L_p from the start node's to the end node's
            Some(np0) if self.law.r.on.rule == bristle::Rule::SameCharacteristic => {
                let mv = bristle::Move::new(s, du);
                let m0 = self.law.r.material_base(np0, k.t_bulk);
                mv.set_along(bristle::Along {
                    tc2_start: m0.tc2,
                    lp_start: m0.lp,
                    lp_sqrt: f64::NAN,
                });
                bristle::update_move(s, &mv, dtau, &m, [lxe, lye]);
            }
            _ => bristle::update(s, du, dtau, &m, [lxe, lye], self.law.r.on.rule),
        }
        s.q = if k.heat {
            let dux = du[0] - lxe * (s.tau[0] - old[0]);
            let duy = du[1] - lye * (s.tau[1] - old[1]);
            let tw = trapezoid_stress(s.tau, old);
            (self.law.r.kq * (tw[0] * dux + tw[1] * duy) / k.h).max(0.0)
        } else {
            0.0
        };
        s.temp = k.t_bulk;
    }

    /// Pressure parts of the lattice nodes k = 1..=nx of strip `j` at the current load in
    /// `nodes`, cached: recomputed when the peak pressure `p0` they belong to changes.
    pub(super) fn lattice_nodes(&self, j: usize, nodes: &mut Vec<NodeP>, p0: &mut f64) {
        let nx = self.lat.nx;
        if *p0 != self.patch.p0 || nodes.len() != nx + 1 {
            let dxi = 2.0 * self.lat.ell[j] / nx as f64;
            nodes.clear();
            nodes.push(NodeP::default());
            for k in 1..=nx {
                let xi = (self.lat.ell[j] - k as f64 * dxi)
                    .max(-self.lat.ell[j] + super::grid::TRAILING_NODE * dxi);
                nodes.push(self.law.r.node_p(self.patch, xi, self.lat.eta[j]));
            }
            *p0 = self.patch.p0;
        }
    }

    /// States of the `count` bristles that entered strip `j` during the current step: the one
    /// in slot k made k full cell moves, then the final partial move `d_end` (m) that ends at
    /// the strip's phase. Same updates, positions and sub-step lengths as the sub-step loop.
    pub(super) fn march_new(&self, sp: &mut Strip, count: usize, d_end: f64) {
        let j = sp.j;
        let dx = 2.0 * self.lat.ell[j] * self.patch.a / self.lat.nx as f64;
        let dxi = 2.0 * self.lat.ell[j] / self.lat.nx as f64;
        let phase_end = *sp.phase;
        // With v = 0 (the steady march at standstill) the march is over distance only and
        // carries no heat: the v -> 0 limit.
        let time = |d: f64| self.time_of(d);
        let kin_full = self.kin(time(dx), dx);
        let fac_full = self.factors(sp.fac, time(dx), kin_full.heat);
        let kin_part = self.kin(time(d_end), d_end);
        let fac_part = self.factors(sp.fac, time(d_end), kin_part.heat);
        let mut s = BristleState {
            temp: self.inputs.t_bulk,
            ..BristleState::default()
        };
        let mut acc = [0.0; N_KERNEL];
        if d_end == 0.0 && self.law.coulomb_path() {
            self.march_coulomb(sp, count, &kin_full);
            return;
        }
        // without temperature the accumulators stay zero: no copies
        let hot = self.law.r.on.temperature;
        self.lattice_nodes(j, sp.nodes, sp.nodes_p0);
        let nodes = &*sp.nodes;
        // where the strip's bristles are shared among threads, the march goes as far as this
        // thread's last bristle
        let count = (0..count)
            .rev()
            .find(|&k| sp.owns(sp.slot(k)))
            .map_or(0, |k| k + 1);
        for k in 0..count {
            let id = sp.slot(k);
            // a bristle of another thread's share: only the march's own state goes on
            if sp.owns(id) {
                // the state at its last node (whole-cell commit)
                sp.node_st[id] = s;
                sp.node_acc[id] = acc;
                // slot nx is past the trailing edge once the phase is > 0: not moved (as in
                // the loop)
                if d_end > 0.0 && k < self.lat.nx {
                    let (mut ps, mut pacc) = (s, acc);
                    self.move_bristle(
                        j,
                        self.lat.ell[j] - (k as f64 + phase_end) * dxi,
                        (self.law.start_cache && k > 0).then(|| &nodes[k]),
                        &kin_part,
                        &fac_part,
                        &mut ps,
                        &mut pacc,
                    );
                    sp.st[id] = ps;
                    if hot {
                        sp.acc[id] = pacc;
                    }
                } else {
                    sp.st[id] = s;
                    if hot {
                        sp.acc[id] = acc;
                    }
                }
            }
            if k + 1 < count {
                self.move_bristle_with(
                    j,
                    self.lat.ell[j] - (k as f64 + 1.0) * dxi,
                    &nodes[k + 1],
                    (self.law.start_cache && k > 0).then(|| &nodes[k]),
                    &kin_full,
                    &fac_full,
                    &mut s,
                    &mut acc,
                );
            }
        }
    }

    /// The march of [`Self::march_new`] at phase 0 for FASTSIM (see [`Law::coulomb_path`](super::law::Law::coulomb_path)):
    /// Kalker's brush with the radial return onto the Coulomb bound mu p, in one tight loop
    /// with the same operations as [`bristle::update`] for tc1 = tc2 = mu p and L_e = 0
    /// (results equal the general path to rounding: reciprocals are multiplied, not divided).
    fn march_coulomb(&self, sp: &mut Strip, count: usize, kin: &Kin) {
        let (nx, j) = (self.lat.nx, sp.j);
        self.lattice_nodes(j, sp.nodes, sp.nodes_p0);
        let nodes = &*sp.nodes;
        let a = self.patch.a;
        let dxi = 2.0 * self.lat.ell[j] / nx as f64;
        let y = if self.patch.line {
            0.0
        } else {
            self.lat.eta[j] * self.patch.b
        };
        let d = kin.dist;
        let (ilx, ily, ils) = (1.0 / kin.lx, 1.0 / kin.ly, 1.0 / kin.ls);
        let (lx, ly) = (kin.lx, kin.ly);
        let inv_h = if kin.heat { self.law.r.kq / kin.h } else { 0.0 };
        // increments that do not depend on the position along the strip
        let du0 = d * (kin.cx - kin.cs * y);
        let dt0 = d * (kin.cx * ilx - kin.cs * y * ils);
        let mut s = BristleState {
            temp: self.inputs.t_bulk,
            ..BristleState::default()
        };
        for k in 0..count {
            let id = sp.slot(k);
            if sp.owns(id) {
                sp.st[id] = s;
            }
            if k + 1 >= count {
                break;
            }
            let xi_end = self.lat.ell[j] - (k as f64 + 1.0) * dxi;
            let x = a * (xi_end + 0.5 * d / a);
            let du = [du0, d * (kin.cy + kin.cs * x)];
            let dtau = [dt0, d * (kin.cy * ily + kin.cs * x * ils)];
            let g = nodes[k + 1].bound;
            let old = s.tau;
            s.u = [s.u[0] + du[0], s.u[1] + du[1]];
            let tr = [old[0] + dtau[0], old[1] + dtau[1]];
            let n2 = tr[0] * tr[0] + tr[1] * tr[1];
            if g.is_nan() || g <= 0.0 {
                s.tau = [0.0, 0.0];
                s.regime = bristle::Regime::Sliding;
            } else if n2 <= g * g {
                s.tau = tr;
                s.regime = bristle::Regime::Elastic;
            } else {
                let ntr = n2.sqrt();
                let dir = [tr[0] / ntr, tr[1] / ntr];
                let kk = ((dir[0] * ilx).powi(2) + (dir[1] * ily).powi(2)).sqrt();
                s.sh = bristle::add_slip(s.sh, (ntr - g) / kk);
                s.tau = [g * dir[0], g * dir[1]];
                s.regime = bristle::Regime::Sliding;
            }
            s.q = if kin.heat {
                let dux = du[0] - lx * (s.tau[0] - old[0]);
                let duy = du[1] - ly * (s.tau[1] - old[1]);
                let tw = trapezoid_stress(s.tau, old);
                ((tw[0] * dux + tw[1] * duy) * inv_h).max(0.0)
            } else {
                0.0
            };
        }
    }

    /// A new bristle enters the strip: the oldest slot is recycled at the leading edge.
    pub(super) fn enter_bristle(&self, sp: &mut Strip) {
        let nx1 = self.lat.nx + 1;
        *sp.head = (*sp.head + self.lat.nx) % nx1;
        let id = sp.slot(0);
        if sp.owns(id) {
            sp.st[id] = BristleState {
                temp: self.inputs.t_bulk,
                ..BristleState::default()
            };
            sp.acc[id] = [0.0; N_KERNEL];
        }
        *sp.phase = 0.0;
        *sp.part = super::Partial::default();
    }
}

impl Mover<'_> {
    /// A step of `dt` that rolls past the whole contact (v dt >= 2a): every bristle enters
    /// during it, so the strip is the steady march of the step's inputs, ending at the
    /// strip's new phase (the entries are counted in closed form: bounded work however long
    /// the step or small the contact).
    pub(super) fn march_all(&self, sp: &mut Strip, dt: f64) {
        let dist = self.inputs.v * dt;
        let dx = 2.0 * self.lat.ell[sp.j] * self.patch.a / self.lat.nx as f64;
        let cells = *sp.phase + dist / dx;
        let ph = (cells - (cells + 1e-9).floor()).max(0.0);
        let ph = if ph < 1e-9 { 0.0 } else { ph };
        *sp.head = 0;
        *sp.phase = ph;
        *sp.part = super::Partial::default();
        self.add_part(sp.part, ph * dx);
        self.march_new(sp, self.lat.nx + 1, ph * dx);
    }

    /// [`super::Scheme::Continuous`]: advances the strip by `dt` (0 < v dt < 2a). The bristles
    /// that stay in the contact move by v dt in `n_sub` equal sub-steps of at most
    /// [`super::MAX_SUBSTEP_CELLS`] cells (material at each sub-step's end, Eq. 4.5), cut
    /// into pieces of at most a cell near the trailing edge and at the end of the step
    /// (see the comments below); those
    /// that enter during the step are marched cell by cell from the leading edge (their
    /// whole history is this step's constant inputs, as in the steady march); those that
    /// leave are not moved. The number of entries is computed in closed form, so the work
    /// of a step is bounded by about one sweep times `n_sub`, however far it rolls: a step
    /// that rolls past the whole contact (v dt >= 2a) is the steady state of its inputs.
    pub(super) fn advance_continuous(&self, sp: &mut Strip, dt: f64) {
        let v = self.inputs.v;
        let a = self.patch.a;
        let nx = self.lat.nx;
        let j = sp.j;
        let dist = v * dt;
        let d_max = super::MAX_SUBSTEP_CELLS * 2.0 * a / nx as f64;
        // equal parts of `len`, each at most `max` (a part a rounding error longer is
        // not split off)
        let parts = |len: f64, max: f64| ((len / max) * (1.0 - 1e-12)).ceil().max(1.0);
        let n_sub_eff = parts(dist, d_max);
        let (h, d) = (dt / n_sub_eff, dist / n_sub_eff);
        let dx = 2.0 * self.lat.ell[j] * a / nx as f64;
        let dxi = 2.0 * self.lat.ell[j] / nx as f64;
        // a sub-step of n > 1 cells dissipates at the trapezoid of its start and end
        // stresses, as every move does (kin::trapezoid_stress): n one-cell moves sum to that,
        // to second order
        let kin = self.kin(h, d);
        let fac = self.factors(sp.fac, h, kin.heat);
        // A sub-step longer than a cell is cut into m pieces of at most one cell where it
        // ends within EDGE_CELLS cells of the trailing edge (the pressure falls to 0 there and
        // the bristles heat fastest), and the last sub-step of the step ends with one such
        // piece, so that the stresses and heat densities the step reports are those of a
        // move of at most one cell, as in the other schemes.
        let m = parts(d, dx);
        let pieces = (m > 1.0).then(|| {
            let (hf, df) = (h / m, d / m);
            let fine = self.kin(hf, df);
            let fine_fac = self.factors(sp.fac, hf, fine.heat);
            let (hr, dr) = (h - hf, d - df);
            let rest = self.kin(hr, dr);
            let rest_fac = self.factors(sp.fac, hr, rest.heat);
            (fine, fine_fac, rest, rest_fac)
        });
        let edge = -self.lat.ell[j] + super::EDGE_CELLS * dxi;
        let n_sub = n_sub_eff as usize;
        let ph0 = *sp.phase;
        let cells = ph0 + dist / dx;
        let wraps_f = (cells + 1e-9).floor();
        let wraps = if wraps_f > nx as f64 {
            nx + 1
        } else {
            wraps_f as usize
        };
        let phase_end = if wraps > nx {
            (cells - wraps_f).max(0.0)
        } else {
            (cells - wraps_f).clamp(0.0, 1.0 - f64::EPSILON)
        };
        let phase_end = if phase_end < 1e-9 { 0.0 } else { phase_end };
        if wraps <= nx {
            // old slot s ends in slot s + wraps at phase_end; it is moved if it is still
            // inside then (the last slot only at phase 0)
            for slot in 0..=nx - wraps {
                if slot + wraps == nx && phase_end > 0.0 {
                    continue;
                }
                let xi0 = self.lat.ell[j] - (slot as f64 + ph0) * dxi;
                let id = sp.slot(slot);
                if !sp.owns(id) {
                    continue;
                }
                let (s, ac) = (&mut sp.st[id], &mut sp.acc[id]);
                for i in 1..=n_sub {
                    let xi_end = xi0 - i as f64 * d / a;
                    let xi_start = xi0 - (i - 1) as f64 * d / a;
                    match &pieces {
                        Some((fine, fine_fac, _, _)) if xi_end < edge => {
                            for p in 1..=m as usize {
                                let xe = if p == m as usize {
                                    xi_end
                                } else {
                                    xi_start - p as f64 * fine.dist / a
                                };
                                self.move_bristle(j, xe, None, fine, fine_fac, s, ac);
                            }
                        }
                        Some((fine, fine_fac, rest, rest_fac)) if i == n_sub => {
                            let xe = xi_start - rest.dist / a;
                            self.move_bristle(j, xe, None, rest, rest_fac, s, ac);
                            self.move_bristle(j, xi_end, None, fine, fine_fac, s, ac);
                        }
                        _ => self.move_bristle(j, xi_end, None, &kin, &fac, s, ac),
                    }
                }
            }
        }
        for _ in 0..wraps.min(nx + 1) {
            self.enter_bristle(sp);
        }
        *sp.phase = phase_end;
        if wraps > 0 {
            self.march_new(sp, wraps.min(nx + 1), phase_end * dx);
        }
    }
}
