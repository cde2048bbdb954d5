//! FASTSIM's steady state in one pass: the march of every strip at phase 0, [`LANES`] strips side by side, with the force integrals summed on the way.

use super::{Contact, V_STANDSTILL};
use crate::bristle::{self, BristleState};

/// Strips marched side by side in [`Contact::steady_coulomb`] (independent dependency
/// chains the processor overlaps).
pub(super) const LANES: usize = 4;

/// The caches of FASTSIM's steady march, kept from call to call.
#[derive(Clone, Debug)]
pub(super) struct CoulombScratch {
    /// Coulomb bounds of the lattice nodes, strips side by side, for the peak pressure `p0`.
    pub bounds: Vec<[f64; LANES]>,
    /// Peak pressure `bounds` belong to, Pa (NaN: none yet).
    pub p0: f64,
    /// Every node accumulator of the grid state is 0 (bit for bit): the march then need not
    /// clear them again. Whatever may write them (a step, a restored state, a reset of the
    /// nodes) sets this false.
    pub node_acc_zero: bool,
}

impl CoulombScratch {
    /// Empty caches, node accumulators zero.
    pub fn new() -> Self {
        CoulombScratch {
            bounds: Vec::new(),
            p0: f64::NAN,
            node_acc_zero: true,
        }
    }
}

/// What every strip's march shares: the grid, the creepages and the flexibilities of the
/// step's inputs.
#[derive(Clone, Copy)]
struct CoulombMarch {
    nx: usize,
    /// Semi-axes a, b, m.
    a: f64,
    b: f64,
    /// Line contact: every strip is the whole width 2b at y = 0.
    line: bool,
    /// Rolling speed, m/s.
    v: f64,
    /// True if the bristles carry heat (v above standstill).
    heat: bool,
    t_bulk: f64,
    /// Flexibilities L_x, L_y (m/Pa) and the reciprocals of L_x, L_y, L_s.
    lx: f64,
    ly: f64,
    ilx: f64,
    ily: f64,
    ils: f64,
    /// Creepages c_x, c_y and spin c_s (1/m).
    cx: f64,
    cy: f64,
    cs: f64,
}

/// The per-strip constants of one group of [`LANES`] strips (padding lanes repeat the last
/// strip).
#[derive(Clone, Copy)]
struct LaneGroup {
    /// Real strips in the group (the rest are padding).
    lanes: usize,
    /// Cell length, m.
    d: [f64; LANES],
    /// Cell length, normalized.
    dxi: [f64; LANES],
    /// Half-length of the strip, normalized.
    ell: [f64; LANES],
    /// Lateral position and width of the strip, m.
    y: [f64; LANES],
    dy: [f64; LANES],
    /// kq / h of a one-cell move (0 without heat).
    inv_h: [f64; LANES],
    /// Half the move in normalized length: the spin lever arm at the move's midpoint.
    hd: [f64; LANES],
    /// The longitudinal rigid slip and elastic stress increment of a move (independent of
    /// the position along the strip).
    du0: [f64; LANES],
    dt0: [f64; LANES],
}

/// The trapezoid sums of one group's strips over their nodes (node k at x_k = a xi_k, phase
/// 0): tau_x, tau_y, x tau_y, q and the elastic length, per lane.
struct LaneSums {
    sx: [f64; LANES],
    sy: [f64; LANES],
    sxy: [f64; LANES],
    sq: [f64; LANES],
    sel: [f64; LANES],
}

/// The contact's integrals summed over the groups.
#[derive(Default)]
struct Totals {
    fx: f64,
    fy: f64,
    mz: f64,
    pf: f64,
    area: f64,
    el: f64,
}

impl Contact {
    /// The Coulomb bounds mu p of the lattice nodes k = 0..=nx, [`LANES`] strips side by side
    /// (group g, node k at `g * (nx + 1) + k`), cached per peak pressure.
    fn bound_lanes(&mut self) -> Vec<[f64; LANES]> {
        let nx = self.lat.nx;
        let groups = self.lat.ny.div_ceil(LANES);
        let mut b = std::mem::take(&mut self.coulomb.bounds);
        if self.coulomb.p0 != self.load.patch.p0 || b.len() != groups * (nx + 1) {
            b.clear();
            b.resize(groups * (nx + 1), [0.0; LANES]);
            for j in 0..self.lat.ny {
                let mut nodes = std::mem::take(&mut self.scratch[j].nodes);
                let mut p0 = self.scratch[j].nodes_p0;
                self.mover().lattice_nodes(j, &mut nodes, &mut p0);
                self.scratch[j].nodes_p0 = p0;
                let (g, l) = (j / LANES, j % LANES);
                for (k, n) in nodes.iter().enumerate().skip(1) {
                    b[g * (nx + 1) + k][l] = n.bound;
                }
                self.scratch[j].nodes = nodes;
            }
            self.coulomb.p0 = self.load.patch.p0;
        }
        b
    }

    /// The steady state of FASTSIM (see [`Law::coulomb_path`](super::law::Law::coulomb_path)): the march of
    /// [`Mover::march_coulomb`](super::law::Mover::march_coulomb) for every strip at phase 0, [`LANES`] strips side by side, with
    /// the integrals of [`Self::integrate`] (trapezoid over the nodes) summed in the same
    /// pass. Every strip has nx cells, so the strips of a group advance in lockstep and
    /// the latency of each strip's sqrt/division chain is hidden behind the others'.
    /// The states stored are those of the general march (to rounding).
    pub(super) fn steady_coulomb(&mut self) -> super::Outputs {
        if self.state.run.inputs.cy == 0.0 && self.state.run.inputs.spin == 0.0 {
            self.steady_coulomb_lanes::<false>()
        } else {
            self.steady_coulomb_lanes::<true>()
        }
    }

    /// [`Self::steady_coulomb`]; `LAT = false` for pure longitudinal creepage, where the
    /// lateral stress stays 0 and the norms are absolute values (no square roots; the
    /// same numbers, since sqrt(x^2) = |x| exactly).
    #[inline(never)]
    fn steady_coulomb_lanes<const LAT: bool>(&mut self) -> super::Outputs {
        let nx = self.lat.nx;
        for j in 0..self.lat.ny {
            self.state.head[j] = 0;
            self.state.phase[j] = 0.0;
        }
        let bounds = self.bound_lanes();
        let mut tot = Totals::default();
        let m = self.coulomb_march();
        let init = BristleState {
            temp: m.t_bulk,
            ..BristleState::default()
        };
        let mut scratch = vec![init; (LANES - 1) * (nx + 1)];
        let mut st = std::mem::take(&mut self.state.st);
        let mut node_st = std::mem::take(&mut self.state.node_st);
        for (g, ((strips, nodes), bnd)) in st
            .chunks_mut(LANES * (nx + 1))
            .zip(node_st.chunks_mut(LANES * (nx + 1)))
            .zip(bounds.chunks_exact(nx + 1))
            .enumerate()
        {
            let grp = self.lane_group(&m, g);
            let lanes = grp.lanes;
            let (real, pad) = strips.split_at_mut(lanes * (nx + 1));
            let mut out: Vec<&mut [BristleState]> = real
                .chunks_exact_mut(nx + 1)
                .chain(scratch.chunks_exact_mut(nx + 1))
                .take(LANES)
                .collect();
            debug_assert!(pad.is_empty() || g * LANES + lanes == self.lat.ny);
            for o in out.iter_mut() {
                o[0] = init;
            }
            let sums = march_group::<LAT>(&m, &grp, bnd, &mut out);
            tot.add(&grp, &sums, m.a);
            // as the general march: every bristle at its node, its node state its state
            // (copied strip by strip while the group's states are in the cache)
            for (n, o) in nodes
                .chunks_exact_mut(nx + 1)
                .zip(real.chunks_exact(nx + 1))
            {
                n.copy_from_slice(o);
            }
        }
        self.state.st = st;
        self.state.node_st = node_st;
        // ... with no heat history and no part of a cell travelled: a step after a steady
        // state in mid-run must not start from the parts and node states of the run before
        // it (the node accumulators are cleared only where a step, a reset of the nodes or a
        // restored state may have written them since they were last cleared)
        if !self.coulomb.node_acc_zero {
            self.state.node_acc.fill([0.0; crate::thermal::N_KERNEL]);
            self.coulomb.node_acc_zero = true;
        }
        self.state.part.fill(super::Partial::default());
        self.coulomb.bounds = bounds;
        self.coulomb_outputs(&tot)
    }

    /// The march's shared constants from the step's inputs and the flexibilities.
    fn coulomb_march(&self) -> CoulombMarch {
        let kin0 = self.mover().kin(0.0, 0.0);
        let v = self.state.run.inputs.v;
        CoulombMarch {
            nx: self.lat.nx,
            a: self.load.patch.a,
            b: self.load.patch.b,
            line: self.load.patch.line,
            v,
            heat: v > V_STANDSTILL,
            t_bulk: self.state.run.inputs.t_bulk,
            lx: kin0.lx,
            ly: kin0.ly,
            ilx: 1.0 / kin0.lx,
            ily: 1.0 / kin0.ly,
            ils: 1.0 / kin0.ls,
            cx: kin0.cx,
            cy: kin0.cy,
            cs: kin0.cs,
        }
    }

    /// The cell lengths, positions and move increments of the strips of group `g`.
    fn lane_group(&self, m: &CoulombMarch, g: usize) -> LaneGroup {
        let (nx, a, b, line) = (m.nx, m.a, m.b, m.line);
        let g0 = g * LANES;
        let lanes = (self.lat.ny - g0).min(LANES);
        // per-lane constants (padding lanes repeat the last strip into scratch)
        let jl = |l: usize| g0 + l.min(lanes - 1);
        let d: [f64; LANES] = std::array::from_fn(|l| 2.0 * self.lat.ell[jl(l)] * a / nx as f64);
        let y: [f64; LANES] =
            std::array::from_fn(|l| if line { 0.0 } else { self.lat.eta[jl(l)] * b });
        LaneGroup {
            lanes,
            d,
            dxi: std::array::from_fn(|l| 2.0 * self.lat.ell[jl(l)] / nx as f64),
            ell: std::array::from_fn(|l| self.lat.ell[jl(l)]),
            y,
            dy: std::array::from_fn(|l| {
                if line {
                    2.0 * b
                } else {
                    self.lat.deta[jl(l)] * b
                }
            }),
            inv_h: std::array::from_fn(|l| {
                if m.heat {
                    self.law.r.kq / (d[l] / m.v)
                } else {
                    0.0
                }
            }),
            hd: std::array::from_fn(|l| 0.5 * d[l] / a),
            du0: std::array::from_fn(|l| d[l] * (m.cx - m.cs * y[l])),
            dt0: std::array::from_fn(|l| d[l] * (m.cx * m.ilx - m.cs * y[l] * m.ils)),
        }
    }

    /// The outputs of FASTSIM's steady state from the contact's integrals (no temperature
    /// rise, no plastic regime).
    fn coulomb_outputs(&self, t: &Totals) -> super::Outputs {
        let (a, b) = (self.load.patch.a, self.load.patch.b);
        let t_bulk = self.state.run.inputs.t_bulk;
        let fn_n = self.state.run.inputs.fn_n;
        let area = t.area.max(f64::MIN_POSITIVE);
        super::Outputs {
            fx: t.fx,
            fy: t.fy,
            mz: t.mz,
            f: if fn_n > 0.0 { t.fx / fn_n } else { 0.0 },
            t_max: t_bulk,
            t_mean: t_bulk,
            p_fric: t.pf,
            frac_elastic: t.el / area,
            frac_plastic: 0.0,
            frac_sliding: (area - t.el).max(0.0) / area,
            a,
            b,
            p0: self.load.patch.p0,
        }
    }
}

/// Marches the bristles of group `grp` over nodes 1..=nx against the Coulomb bounds `bnd`,
/// storing each lane's state at each node in `out`, and returns the group's sums.
fn march_group<const LAT: bool>(
    m: &CoulombMarch,
    grp: &LaneGroup,
    bnd: &[[f64; LANES]],
    out: &mut [&mut [BristleState]],
) -> LaneSums {
    // local copies: the compiler keeps them in registers (read through `grp`, every store
    // of a bristle state could alias them)
    let (nx, a, t_bulk) = (m.nx, m.a, m.t_bulk);
    let (ilx, ily, ils) = (m.ilx, m.ily, m.ils);
    let (lx, ly) = (m.lx, m.ly);
    let (cy, cs) = (m.cy, m.cs);
    let (d, dxi, ell, inv_h, hd, du0, dt0) =
        (grp.d, grp.dxi, grp.ell, grp.inv_h, grp.hd, grp.du0, grp.dt0);
    let (mut t0, mut t1, mut u0, mut u1, mut sh) = (
        [0.0; LANES],
        [0.0; LANES],
        [0.0; LANES],
        [0.0; LANES],
        [0.0; LANES],
    );
    let (mut sx, mut sy, mut sxy, mut sq, mut sel) = (
        [0.0; LANES],
        [0.0; LANES],
        [0.0; LANES],
        [0.0; LANES],
        [0.0; LANES],
    );
    // node 0: zero stress, elastic, half weight
    for (l, e) in sel.iter_mut().enumerate() {
        *e = 0.5 * dxi[l];
    }
    for k in 1..=nx {
        let w = if k < nx { 1.0 } else { 0.5 };
        let gk = bnd[k];
        // branch-free over the lanes (the compiler keeps them in SIMD registers):
        // elastic trial, radial return onto mu p where it is exceeded, zero where
        // the node carries no pressure (two square roots and one division per lane,
        // where the C march has one of each, but two lanes per instruction)
        let mut xk = [0.0; LANES];
        let mut du1 = [0.0; LANES];
        let mut o = [[0.0; LANES]; 2];
        let mut slide = [false; LANES];
        let mut q = [0.0; LANES];
        for l in 0..LANES {
            let xi_end = ell[l] - k as f64 * dxi[l];
            xk[l] = a * xi_end;
            let x = a * (xi_end + hd[l]);
            du1[l] = d[l] * (cy + cs * x);
            let dt1 = d[l] * (cy * ily + cs * x * ils);
            o[0][l] = t0[l];
            o[1][l] = t1[l];
            u0[l] += du0[l];
            u1[l] += du1[l];
            let tr = [t0[l] + dt0[l], if LAT { t1[l] + dt1 } else { 0.0 }];
            let n2 = if LAT {
                tr[0] * tr[0] + tr[1] * tr[1]
            } else {
                tr[0] * tr[0]
            };
            let g = gk[l];
            let live = g > 0.0; // false for NaN
            slide[l] = n2 > g * g;
            // |trial| and the stiffness along it k = m / |trial|,
            // m = |(tr_x / L_x, tr_y / L_y)|, with one division:
            // 1/|trial| = m inv, 1/m = |trial| inv
            let (ntr, m) = if LAT {
                (
                    n2.sqrt(),
                    ((tr[0] * ilx).powi(2) + (tr[1] * ily).powi(2)).sqrt(),
                )
            } else {
                (tr[0].abs(), (tr[0] * ilx).abs())
            };
            let inv = 1.0 / (ntr * m);
            let scale = if !live {
                0.0
            } else if slide[l] {
                g * m * inv
            } else {
                1.0
            };
            // plastic slip (|trial| - mu p) / k
            if live && slide[l] {
                sh[l] = bristle::add_slip(sh[l], (n2 - g * ntr) * ntr * inv);
            }
            slide[l] |= !live;
            t0[l] = tr[0] * scale;
            t1[l] = tr[1] * scale;
            let dux = du0[l] - lx * (t0[l] - o[0][l]);
            let duy = du1[l] - ly * (t1[l] - o[1][l]);
            let tw = super::kin::trapezoid_stress([t0[l], t1[l]], [o[0][l], o[1][l]]);
            q[l] = ((tw[0] * dux + tw[1] * duy) * inv_h[l]).max(0.0);
            // trapezoid: node k at x_k = a xi_k (phase 0)
            let wk = w * dxi[l];
            sx[l] += wk * t0[l];
            sy[l] += wk * t1[l];
            sxy[l] += wk * xk[l] * t1[l];
            sq[l] += wk * q[l];
            sel[l] += if slide[l] { 0.0 } else { wk };
        }
        for l in 0..LANES {
            out[l][k] = BristleState {
                u: [u0[l], u1[l]],
                tau: [t0[l], t1[l]],
                sh: sh[l],
                temp: t_bulk,
                q: q[l],
                regime: if slide[l] {
                    bristle::Regime::Sliding
                } else {
                    bristle::Regime::Elastic
                },
            };
        }
    }
    LaneSums {
        sx,
        sy,
        sxy,
        sq,
        sel,
    }
}

impl Totals {
    /// Adds the integrals of a group's real strips (strip area a dy; M_z about the contact
    /// centre).
    fn add(&mut self, grp: &LaneGroup, s: &LaneSums, a: f64) {
        for l in 0..grp.lanes {
            let da = a * grp.dy[l];
            self.fx += s.sx[l] * da;
            self.fy += s.sy[l] * da;
            self.mz += (s.sxy[l] - grp.y[l] * s.sx[l]) * da;
            self.pf += s.sq[l] * da;
            self.el += s.sel[l] * da;
            self.area += 2.0 * grp.ell[l] * da;
        }
    }
}
