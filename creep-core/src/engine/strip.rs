//! One strip of the bristle grid as a unit of work: its bristles, ring buffer and caches borrowed out of the contact, so that strips advance independently (on several threads with `threads`).

use super::law::Mover;
use super::Contact;
use crate::bristle::BristleState;
use crate::material::NodeP;
use crate::thermal::{StepFactors, N_KERNEL};

/// The caches of one strip's moves, kept from step to step (one per strip and thread, so
/// strips and threads share no mutable state).
#[derive(Clone, Debug, Default)]
pub(super) struct StripScratch {
    /// Pressure parts of the lattice nodes, for the peak pressure `nodes_p0`.
    pub nodes: Vec<NodeP>,
    /// Peak pressure the cached `nodes` belong to, Pa (NaN: none yet).
    pub nodes_p0: f64,
    /// Kernel factors of recent sub-step lengths (h, factors).
    pub fac: Vec<(f64, StepFactors)>,
    /// A thread's own copies of the strip's bristles where they are shared among threads.
    pub own: super::share::Private,
}

impl StripScratch {
    /// Empty caches.
    pub fn new() -> Self {
        StripScratch {
            nodes: Vec::new(),
            nodes_p0: f64::NAN,
            fac: Vec::new(),
            own: super::share::Private::default(),
        }
    }
}

/// Which strips a step computes: strips that are mirror images of each other about y = 0
/// once, while that holds ([`Contact::each_strip`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct Symmetry {
    /// Every strip's state equals its mirror image's about y = 0 (strip ny - 1 - j), bit for
    /// bit: then, while the inputs are symmetric too, one of each pair is computed and copied.
    pub mirrored: bool,
    /// `mirrored` is still to be found from the state FASTSIM's steady march left
    /// ([`Contact::settle_mirrored`]): a run of steady states alone never needs it, so the
    /// comparison of every strip with its mirror image waits for the next step.
    pub unknown: bool,
    /// Symmetric strips are computed once ([`Contact::set_mirror_strips`]; off for tests and
    /// benchmarks that compare both).
    pub on: bool,
}

impl Symmetry {
    /// A new contact's: mirror images, computed once.
    pub fn new() -> Self {
        Symmetry {
            mirrored: true,
            unknown: false,
            on: true,
        }
    }
}

/// The mutable state of strip `j` during a step: its part of the grid state and its scratch
/// (the law, lattice and kinematics reach its moves through a [`Mover`], read only).
pub(super) struct Strip<'a> {
    /// Strip index.
    pub j: usize,
    /// Where the strip's bristles are shared among threads: which thread moves each
    /// (storage index), and which thread this is. The arrays are then this thread's copies,
    /// current for its own bristles only ([`Strip::owns`]).
    pub owner: Option<(&'a [u8], u8)>,
    /// Its `nx + 1` bristles (ring buffer, see `slot`).
    pub st: &'a mut [BristleState],
    /// Their heat-kernel accumulators.
    pub acc: &'a mut [[f64; N_KERNEL]],
    /// Their states at their last lattice node (whole-cell commit).
    pub node_st: &'a mut [BristleState],
    /// Their heat-kernel accumulators at that node.
    pub node_acc: &'a mut [[f64; N_KERNEL]],
    /// The part of the current cell travelled since that node.
    pub part: &'a mut super::Partial,
    /// Ring-buffer head.
    pub head: &'a mut usize,
    /// Phase in [0, 1) (Eq. 4.17).
    pub phase: &'a mut f64,
    /// Pressure parts of the lattice nodes, for the peak pressure `nodes_p0`.
    pub nodes: &'a mut Vec<NodeP>,
    /// Peak pressure the cached `nodes` belong to, Pa.
    pub nodes_p0: &'a mut f64,
    /// Kernel factors of recent sub-step lengths.
    pub fac: &'a mut Vec<(f64, StepFactors)>,
}

impl Strip<'_> {
    /// Storage index of ring slot `slot` (0: the bristle nearest the leading edge).
    #[inline]
    pub fn slot(&self, slot: usize) -> usize {
        (*self.head + slot) % self.st.len()
    }

    /// True if this thread moves bristle `id` (storage index): every bristle unless the
    /// strip's bristles are shared among threads.
    #[inline]
    pub fn owns(&self, id: usize) -> bool {
        self.owner.is_none_or(|(o, me)| o[id] == me)
    }
}

impl Contact {
    /// Runs `f` on every strip, on the contact's threads when it has them (results do not
    /// depend on the number of threads: strips share no mutable state). While `f` runs, the
    /// grid state's per-strip vectors (`st`, `acc`, `head`, `phase`, ...) and the strips'
    /// scratch are moved into the strips: `f` reaches them through its [`Strip`] only, and
    /// the rest through the [`Mover`] (law, lattice, kinematics), read only.
    ///
    /// Symmetric strips are computed once: the strips lie symmetric about y = 0 (bit for bit,
    /// [`super::grid::strip_rule`]) and, without spin, nothing a move computes depends on the
    /// sign of y (the rigid slip and the elastic increments are uniform over the contact, y
    /// enters only through c_s y and c_s x; the pressure through eta^2; IEEE rounding is
    /// symmetric in sign), with or without lateral creepage. So a strip whose state equals
    /// that of the strip at -eta stays equal to it: while that holds for every strip
    /// (`Symmetry::mirrored`) and the spin is 0, `f` runs on the strips j <= ny - 1 - j only
    /// and each is copied onto strip ny - 1 - j, with bit-identical results (test
    /// `mirrored_strips_are_bit_identical`).
    pub(super) fn each_strip(&mut self, f: impl Fn(&Mover, &mut Strip) + Sync) {
        let (mirror, computed) = self.begin_strips();
        let nx1 = self.lat.nx + 1;
        let mut t = Taken::from(self);
        {
            let this = self.mover();
            let (strips, scratch) = t.strips(nx1);
            let mut strips: Vec<Strip> = strips
                .zip(scratch.iter_mut())
                .enumerate()
                .map(|(j, ((arrays, ring), sc))| Strip::whole(j, arrays, ring, sc))
                .take(computed)
                .collect();
            let t0 = std::time::Instant::now();
            let parallel = self.balance.parallel();
            let work = match &self.pool {
                Some(pool) if strips.len() > 1 && parallel => {
                    let mut timed: Vec<(Strip, f64)> =
                        strips.into_iter().map(|s| (s, 0.0)).collect();
                    pool.run(&mut timed, |(sp, busy)| {
                        let ts = std::time::Instant::now();
                        f(&this, sp);
                        *busy = ts.elapsed().as_secs_f64();
                    });
                    timed.iter().map(|(_, b)| b).sum()
                }
                _ => {
                    strips.iter_mut().for_each(|sp| f(&this, sp));
                    t0.elapsed().as_secs_f64()
                }
            };
            self.balance.learn_work(work);
        }
        t.put_back(self);
        if mirror {
            self.copy_to_mirror_strips();
        }
    }

    /// Copies the state of each strip j < ny / 2 onto its mirror image ny - 1 - j (bristles,
    /// accumulators, node states, part of the cell, ring-buffer head and phase; the caches
    /// refill themselves).
    pub(super) fn copy_to_mirror_strips(&mut self) {
        let (ny, nx1) = (self.lat.ny, self.lat.nx + 1);
        for j in 0..ny / 2 {
            let m = ny - 1 - j;
            let (src, dst) = (j * nx1, m * nx1);
            self.state.st.copy_within(src..src + nx1, dst);
            self.state.acc.copy_within(src..src + nx1, dst);
            self.state.node_st.copy_within(src..src + nx1, dst);
            self.state.node_acc.copy_within(src..src + nx1, dst);
            self.state.part[m] = self.state.part[j];
            self.state.head[m] = self.state.head[j];
            self.state.phase[m] = self.state.phase[j];
        }
    }

    /// Prepares a step of the strips ([`Self::each_strip`], `each_strip_shared`): whether
    /// it computes one of each pair of mirror-image strips, and how many strips it computes.
    pub(super) fn begin_strips(&mut self) -> (bool, usize) {
        self.settle_mirrored();
        // the step may write the node accumulators
        self.coulomb.node_acc_zero = false;
        let mirror = self.mirror_now();
        let ny = self.lat.ny;
        (mirror, if mirror { ny.div_ceil(2) } else { ny })
    }

    /// Whether this step computes one of each pair of mirror-image strips (they are mirror
    /// images and the inputs symmetric; see [`Self::each_strip`]).
    pub(super) fn mirror_now(&mut self) -> bool {
        let sym = self.sym.mirrored
            && self.lat.ny > 1
            && !self.load.patch.line
            && self.state.run.inputs.spin == 0.0;
        self.sym.mirrored = sym;
        sym && self.sym.on
    }

    /// Sets whether the strips are mirror images of each other (known now).
    pub(super) fn set_mirrored(&mut self, mirrored: bool) {
        self.sym.mirrored = mirrored;
        self.sym.unknown = false;
    }

    /// Finds whether the strips are mirror images where FASTSIM's steady march left that
    /// open ([`Self::strips_equal`] on its state, unchanged since).
    pub(super) fn settle_mirrored(&mut self) {
        if self.sym.unknown {
            self.set_mirrored(self.strips_equal());
        }
    }

    /// True if every strip's state equals its mirror image's about y = 0, bit for bit (see
    /// [`Self::each_strip`]; 0 and -0 differ, so a state that holds both is computed strip by
    /// strip).
    pub(super) fn strips_equal(&self) -> bool {
        let (ny, nx1) = (self.lat.ny, self.lat.nx + 1);
        let same = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
        let bristle = |s: &BristleState| [s.u[0], s.u[1], s.tau[0], s.tau[1], s.sh, s.temp, s.q];
        let bristles = |a: &[BristleState], b: &[BristleState]| {
            a.iter()
                .zip(b)
                .all(|(x, y)| x.regime == y.regime && same(&bristle(x), &bristle(y)))
        };
        let accs =
            |a: &[[f64; N_KERNEL]], b: &[[f64; N_KERNEL]]| a.iter().zip(b).all(|(x, y)| same(x, y));
        let part = |p: &super::Partial| [p.d, p.h, p.dcx, p.dcy, p.dcs];
        (0..ny / 2).all(|j| {
            let m = ny - 1 - j;
            let (a, b) = (j * nx1..(j + 1) * nx1, m * nx1..(m + 1) * nx1);
            self.state.head[j] == self.state.head[m]
                && same(&[self.state.phase[j]], &[self.state.phase[m]])
                && same(&part(&self.state.part[j]), &part(&self.state.part[m]))
                && bristles(&self.state.st[a.clone()], &self.state.st[b.clone()])
                && bristles(
                    &self.state.node_st[a.clone()],
                    &self.state.node_st[b.clone()],
                )
                && accs(&self.state.acc[a.clone()], &self.state.acc[b.clone()])
                && accs(&self.state.node_acc[a], &self.state.node_acc[b])
        })
    }

    /// Computes strips that are mirror images of each other once (on, the default) or each
    /// of them (off: for tests and benchmarks that compare both; results are bit-identical).
    #[doc(hidden)]
    pub fn set_mirror_strips(&mut self, on: bool) {
        self.sym.on = on;
    }

    /// True while the strips at eta and -eta hold equal states, so that the next step without
    /// spin computes one of each pair (for tests).
    #[doc(hidden)]
    pub fn strips_mirrored(&self) -> bool {
        if self.sym.unknown {
            self.strips_equal()
        } else {
            self.sym.mirrored
        }
    }

    /// Advances the strips on `threads` threads (1: the calling thread alone, the default).
    /// The results do not depend on it.
    pub fn set_threads(&mut self, threads: usize) -> crate::Result<()> {
        self.pool = if threads <= 1 {
            None
        } else {
            // the pool panics where the system refuses a thread
            let pool =
                std::panic::catch_unwind(|| super::pool::Pool::new(threads)).map_err(|_| {
                    crate::CreepError::Config {
                        source_name: "threads".into(),
                        message: format!("cannot start {threads} threads"),
                    }
                })?;
            Some(std::sync::Arc::new(pool))
        };
        Ok(())
    }

    /// Threads that advance the strips.
    pub fn threads(&self) -> usize {
        self.pool.as_ref().map_or(1, |p| p.threads())
    }
}

/// The grid state's per-strip vectors and the strips' caches, moved out of the contact for
/// a step (the rest of it stays readable through a [`Mover`]).
pub(super) struct Taken {
    pub st: Vec<BristleState>,
    pub acc: Vec<[f64; N_KERNEL]>,
    pub node_st: Vec<BristleState>,
    pub node_acc: Vec<[f64; N_KERNEL]>,
    pub part: Vec<super::Partial>,
    pub head: Vec<usize>,
    pub phase: Vec<f64>,
    pub scratch: Vec<StripScratch>,
}

impl Taken {
    /// Moves them out of `c`.
    pub(super) fn from(c: &mut Contact) -> Self {
        Taken {
            st: std::mem::take(&mut c.state.st),
            acc: std::mem::take(&mut c.state.acc),
            node_st: std::mem::take(&mut c.state.node_st),
            node_acc: std::mem::take(&mut c.state.node_acc),
            part: std::mem::take(&mut c.state.part),
            head: std::mem::take(&mut c.state.head),
            phase: std::mem::take(&mut c.state.phase),
            scratch: std::mem::take(&mut c.scratch),
        }
    }

    /// Strip by strip (`n` bristles each), its per-bristle arrays and ring bookkeeping, and
    /// beside them the strips' caches.
    pub(super) fn strips(
        &mut self,
        n: usize,
    ) -> (
        impl Iterator<Item = (Arrays<'_>, Ring<'_>)>,
        &mut [StripScratch],
    ) {
        let arrays = self
            .st
            .chunks_mut(n)
            .zip(self.acc.chunks_mut(n))
            .zip(self.node_st.chunks_mut(n).zip(self.node_acc.chunks_mut(n)))
            .map(|((st, acc), (node_st, node_acc))| (st, acc, node_st, node_acc));
        let rings = self
            .head
            .iter_mut()
            .zip(self.phase.iter_mut())
            .zip(self.part.iter_mut())
            .map(|((head, phase), part)| (head, phase, part));
        (arrays.zip(rings), &mut self.scratch)
    }

    /// Moves them back into `c`.
    pub(super) fn put_back(self, c: &mut Contact) {
        c.state.st = self.st;
        c.state.acc = self.acc;
        c.state.node_st = self.node_st;
        c.state.node_acc = self.node_acc;
        c.state.part = self.part;
        c.state.head = self.head;
        c.state.phase = self.phase;
        c.scratch = self.scratch;
    }
}

/// A strip's per-bristle arrays: states, accumulators, node states, node accumulators.
pub(super) type Arrays<'a> = (
    &'a mut [BristleState],
    &'a mut [[f64; N_KERNEL]],
    &'a mut [BristleState],
    &'a mut [[f64; N_KERNEL]],
);

/// A strip's ring bookkeeping: head, phase, part of the cell.
pub(super) type Ring<'a> = (&'a mut usize, &'a mut f64, &'a mut super::Partial);

impl<'a> Strip<'a> {
    /// Strip `j` advanced whole by one thread.
    pub(super) fn whole(
        j: usize,
        arrays: Arrays<'a>,
        ring: Ring<'a>,
        sc: &'a mut StripScratch,
    ) -> Self {
        let (st, acc, node_st, node_acc) = arrays;
        let (head, phase, part) = ring;
        Strip {
            j,
            owner: None,
            st,
            acc,
            node_st,
            node_acc,
            part,
            head,
            phase,
            nodes: &mut sc.nodes,
            nodes_p0: &mut sc.nodes_p0,
            fac: &mut sc.fac,
        }
    }
}

/// Bristles that enter a strip while it rolls `dist` (m) from `phase` on cells of `dx` (m):
/// the count [`Mover::advance_cells`] makes (for `dist` < 2a, about nx / l_j loops).
pub(super) fn entries(dist: f64, phase: f64, dx: f64) -> usize {
    let tol = 1e-9 * dx;
    let (mut rem, mut ph, mut w) = (dist, phase, 0usize);
    while rem > tol {
        let to_next = (1.0 - ph) * dx;
        if rem >= to_next - tol {
            w += 1;
            rem -= to_next;
            ph = 0.0;
        } else {
            rem = 0.0;
        }
    }
    w
}

impl Strip<'_> {
    /// The bristles of `slots` are at their lattice nodes: their states become the node states.
    fn keep_at_nodes(&mut self, slots: std::ops::Range<usize>) {
        for slot in slots {
            let id = self.slot(slot);
            self.node_st[id] = self.st[id];
            self.node_acc[id] = self.acc[id];
        }
    }

    /// The bristles of `slots` go back to their node states (the provisional part of the
    /// current cell is dropped, to be moved again from the node).
    fn back_to_nodes(&mut self, slots: std::ops::Range<usize>) {
        for slot in slots {
            let id = self.slot(slot);
            self.st[id] = self.node_st[id];
            self.acc[id] = self.node_acc[id];
        }
    }
}

impl Mover<'_> {
    /// Time to roll `d` (m) at the current speed, s (0 at standstill, the v -> 0 limit).
    pub(super) fn time_of(&self, d: f64) -> f64 {
        let v = self.inputs.v;
        if v > super::V_STANDSTILL {
            d / v
        } else {
            0.0
        }
    }

    /// Adds `d` (m) rolled at the current inputs to the strip's part `p` of its current cell.
    pub(super) fn add_part(&self, p: &mut super::Partial, d: f64) {
        let i = &self.inputs;
        p.d += d;
        p.h += self.time_of(d);
        p.dcx += d * i.cx;
        p.dcy += d * i.cy;
        p.dcs += d * i.spin;
    }

    /// Kinematics of a move over the strip's part `p` of the current cell plus `d` (m) more
    /// at the current inputs: the creepages weighted by distance (the rigid slip and the
    /// elastic increment of Eq. 4.21 are linear in them), the time summed.
    pub(super) fn part_kin(&self, p: &super::Partial, d: f64) -> super::kin::Kin {
        if p.d == 0.0 {
            // nothing of the cell travelled before: the current inputs as they are
            return self.kin(self.time_of(d), d);
        }
        let mut q = *p;
        self.add_part(&mut q, d);
        let mut k = self.kin(q.h, q.d);
        if q.d > 0.0 {
            k.cx = q.dcx / q.d;
            k.cy = q.dcy / q.d;
            k.cs = q.dcs / q.d;
        }
        k
    }

    /// The reference scheme for strip `sp`: every bristle gets one sub-step per cell crossing,
    /// cut at the instants a new bristle enters (the steady march's sub-steps exactly). Costs
    /// about (cells travelled) x (bristles) moves per step.
    pub(super) fn advance_cells(&self, sp: &mut Strip, dt: f64) {
        let j = sp.j;
        let v = self.inputs.v;
        let a = self.patch.a;
        let march = self.law.march_new;
        let dx = 2.0 * self.lat.ell[j] * a / self.lat.nx as f64;
        let mut remaining = v * dt;
        let tol = 1e-9 * dx;
        // Bristles that enter during this step see only this step's (constant) inputs:
        // full cells, then the final partial move. They are computed afterwards by a march
        // (`march_new`), which performs exactly the updates the sub-step loop would, so the
        // loop only advances the bristles that were in the contact before the step
        // (slots >= n_new). With v dt >= 2a the whole step costs one steady march.
        let mut n_new = 0usize;
        let mut d_end = 0.0;
        // Bristles that will leave before the end of the step need no update at all: count
        // this step's entries first (same arithmetic as the loop below).
        let wraps = entries(remaining, *sp.phase, dx);
        while remaining > tol {
            let to_next = (1.0 - *sp.phase) * dx;
            if remaining >= to_next - tol {
                // end positions are one node further (phase 1), then the slots shift. A cell
                // begun in an earlier step is moved whole from the bristles' node states with
                // the distance-weighted inputs of its parts (whole-cell commit: no cell is cut)
                if !march || n_new + (wraps - n_new) <= self.lat.nx {
                    // (within this guard: with more entries than cells, end would underflow)
                    let (skip, end) = if !march {
                        (0, self.lat.nx + 1)
                    } else {
                        (n_new, self.lat.nx + 1 - (wraps - n_new))
                    };
                    let kin = if *sp.phase > 0.0 {
                        sp.back_to_nodes(skip..self.lat.nx.min(end));
                        self.part_kin(sp.part, to_next)
                    } else {
                        self.kin(to_next / v, to_next)
                    };
                    self.substep_strip_kin(sp, &kin, 1.0, skip, end);
                }
                // all bristles moved one node: the slot numbering shifts by recycling the oldest
                self.enter_bristle(sp);
                n_new += 1;
                remaining -= to_next;
            } else {
                let ph = *sp.phase + remaining / dx;
                let skip = if !march { 0 } else { n_new };
                if !march || n_new <= self.lat.nx {
                    // the bristles at the step's phase, from their node states over the whole
                    // part of the cell travelled since (for the outputs; not committed)
                    if *sp.phase == 0.0 {
                        sp.keep_at_nodes(skip..self.lat.nx);
                    } else {
                        sp.back_to_nodes(skip..self.lat.nx);
                    }
                    let kin = self.part_kin(sp.part, remaining);
                    self.substep_strip_kin(sp, &kin, ph, skip, self.lat.nx + 1);
                }
                self.add_part(sp.part, remaining);
                *sp.phase = ph;
                d_end = remaining;
                remaining = 0.0;
            }
        }
        if n_new > 0 && march {
            self.march_new(sp, n_new.min(self.lat.nx + 1), d_end);
        }
    }
}
