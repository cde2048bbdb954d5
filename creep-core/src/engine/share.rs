//! One strip's bristles shared among threads: on coarse grids a step has too few strips to keep the threads busy with whole ones, so the bristles of the costliest strip are split among the threads, in proportions adapted to their times.

use super::law::Mover;
use super::strip::{entries, Arrays, Ring, Strip, StripScratch, Taken};
use super::Contact;
use crate::bristle::BristleState;
use crate::thermal::N_KERNEL;

/// A thread's copies of a strip's per-bristle arrays where a step's bristles are shared
/// among threads ([`Contact::each_strip_shared`]): the thread copies in the bristles it
/// moves, moves them here and copies them back, so that no two threads write to the same
/// cache line during a step. Only those bristles are current.
#[derive(Clone, Debug, Default)]
pub(super) struct Private {
    st: Vec<BristleState>,
    acc: Vec<[f64; N_KERNEL]>,
    node_st: Vec<BristleState>,
    node_acc: Vec<[f64; N_KERNEL]>,
}

/// How a step's bristles are shared among the threads ([`Contact::each_strip_shared`]): a
/// weight per thread, adapted from step to step so that the threads finish together.
#[derive(Clone, Debug, Default)]
pub(super) struct Balance {
    /// Fraction of each strip's bristles per thread (sums to 1).
    weights: Vec<f64>,
    /// Smoothed time each thread took for its share of a step, s.
    busy: Vec<f64>,
    /// The weights are held fixed (tests of the sharing's independence of them).
    fixed: bool,
    /// The last step's owners, strip after strip (kept for its allocation).
    owners: Vec<u8>,
    /// Smoothed time each strip took to advance (all threads' shares summed), s, per strip
    /// index (0: not measured yet).
    cost: Vec<f64>,
    /// Smoothed work of a step's strips (the threads' times summed), s (0: not measured).
    work: f64,
    /// The steps run on one thread: too little work to hand out ([`SERIAL_BELOW`]).
    serial: bool,
}

/// A step whose strips take less than this (s, smoothed) runs on the calling thread alone:
/// handing out the work, the shared strip's copies and its bookkeeping done twice cost
/// about 2-4 us, which made two threads slower than one on 6 x 3 at 5 m/s with 0.1 ms steps
/// (about 7 us of work: 1.11x) and faster from about 10 us (10 x 3 at 20 m/s, 0.05 ms steps,
/// 14 us: 0.90x; 10 x 3 at 5 m/s, 1 ms, 23 us: 0.71x).
const SERIAL_BELOW: f64 = 10e-6;
/// ... and on the threads again above this (s; apart from [`SERIAL_BELOW`] so that work near
/// the bound does not switch back and forth).
const PARALLEL_ABOVE: f64 = 13e-6;

/// Smoothing factor of the threads' times (the weight of the newest step).
const BALANCE_EMA: f64 = 0.2;
/// Exponent of the weights' correction: w *= (mean time / own time)^BALANCE_GAIN.
const BALANCE_GAIN: f64 = 0.5;

impl Balance {
    /// Equal weights for `threads` threads (kept where the count is unchanged).
    fn fit(&mut self, threads: usize) {
        if self.weights.len() != threads {
            self.weights = vec![1.0 / threads as f64; threads];
            self.busy.clear();
        }
    }

    /// Whether the next step's strips go to the threads (else to the calling thread alone).
    pub(super) fn parallel(&self) -> bool {
        self.fixed || !self.serial
    }

    /// Adds the last step's work (s, the threads' times summed) to its smoothed value and
    /// decides whether the next steps use the threads.
    pub(super) fn learn_work(&mut self, work: f64) {
        if work.is_nan() || work <= 0.0 {
            return;
        }
        self.work = if self.work > 0.0 {
            self.work + BALANCE_EMA * (work - self.work)
        } else {
            work
        };
        if self.serial && self.work > PARALLEL_ABOVE {
            self.serial = false;
        } else if !self.serial && self.work < SERIAL_BELOW {
            self.serial = true;
        }
    }

    /// Adds the strips' times of the last step, `(strip, s)`, to their smoothed costs.
    fn learn_costs(&mut self, ny: usize, times: impl Iterator<Item = (usize, f64)>) {
        if self.cost.len() != ny {
            self.cost = vec![0.0; ny];
        }
        let mut now = [0.0; MAX_COST];
        for (j, t) in times {
            if let Some(x) = now.get_mut(j) {
                *x += t;
            }
        }
        for (c, t) in self.cost.iter_mut().zip(now) {
            if t > 0.0 {
                *c = if *c > 0.0 {
                    *c + BALANCE_EMA * (t - *c)
                } else {
                    t
                };
            }
        }
    }

    /// Adapts the weights to the threads' times `busy` (s) of the last step.
    fn learn(&mut self, busy: &[f64]) {
        if self.fixed || busy.len() != self.weights.len() || busy.iter().any(|b| *b <= 0.0) {
            return;
        }
        if self.busy.len() != busy.len() {
            self.busy = busy.to_vec();
        } else {
            for (s, b) in self.busy.iter_mut().zip(busy) {
                *s += BALANCE_EMA * (b - *s);
            }
        }
        let mean = self.busy.iter().sum::<f64>() / self.busy.len() as f64;
        for (w, b) in self.weights.iter_mut().zip(&self.busy) {
            *w *= (mean / b).powf(BALANCE_GAIN);
        }
        // no thread's share below a floor, so that its time keeps being measured
        let floor = 0.02 / self.weights.len() as f64;
        let total: f64 = self.weights.iter().sum();
        for w in self.weights.iter_mut() {
            *w = (*w / total).max(floor);
        }
        let total: f64 = self.weights.iter().sum();
        for w in self.weights.iter_mut() {
            *w /= total;
        }
    }

    /// Appends to `out` which thread moves each bristle (storage index) of a strip of `n`
    /// bristles with ring head `head` in a step in which `leaving` bristles leave: the
    /// bristles of the ring's last `leaving` slots, whose storage the bristles entering
    /// during the step take (one march, in sequence), to thread `chain`; the others by
    /// smooth weighted round robin over their storage index, so that a bristle stays on its
    /// thread from step to step.
    fn owners(&self, out: &mut Vec<u8>, n: usize, head: usize, leaving: usize, chain: usize) {
        let t = self.weights.len().min(MAX_SHARED);
        let start = out.len();
        let mut credit = [0.0; MAX_SHARED];
        for _ in 0..n {
            for (c, w) in credit.iter_mut().zip(&self.weights) {
                *c += w;
            }
            let mut best = 0;
            for r in 1..t {
                if credit[r] > credit[best] {
                    best = r;
                }
            }
            credit[best] -= 1.0;
            out.push(best as u8);
        }
        for k in 0..leaving.min(n) {
            out[start + (head + n - 1 - k) % n] = chain as u8;
        }
    }
}

impl Contact {
    /// [`Self::each_strip`] for the cell-by-cell step of `dt` (s) ([`Mover::advance_cells`]):
    /// with several threads, the strips computed are handed out whole but for the costliest
    /// ([`whole_strips`]; all of them where there are fewer strips than threads), whose
    /// bristles are shared among the threads in the proportions [`Balance`] adapts from step
    /// to step, so that the threads finish together however few strips the grid computes.
    /// On a shared strip each thread moves its bristles ([`Balance::owners`]) in its own
    /// copies ([`Private`]), with its own copy of the ring buffer's head, phase and part of
    /// the cell (the same arithmetic on the same inputs, so the copies stay equal) and its
    /// own caches; a bristle's moves within a step read and write its own state only, so the
    /// results are bit for bit those of one thread, whoever moves which bristle (test
    /// `shared_strips_do_not_depend_on_the_share`).
    pub(super) fn each_strip_shared(&mut self, dt: f64, f: impl Fn(&Mover, &mut Strip) + Sync) {
        let threads = self.threads().min(MAX_SHARED);
        let Some(pool) = self
            .pool
            .clone()
            .filter(|_| threads > 1 && self.balance.parallel())
        else {
            return self.each_strip(f);
        };
        let (mirror, computed) = self.begin_strips();
        let ny = self.lat.ny;
        let n = self.lat.nx + 1;
        if self.scratch.len() < ny * threads {
            self.scratch.resize(ny * threads, StripScratch::new());
        }
        let (assign, owners) = self.share_plan(dt, computed, threads);
        let shared: Vec<usize> = (0..computed).filter(|&j| assign[j].is_none()).collect();
        let mut t = Taken::from(self);
        // on a shared strip, threads 1.. work on copies of the ring bookkeeping
        let mut rings: Vec<(usize, f64, super::Partial)> = shared
            .iter()
            .flat_map(|&j| (1..threads).map(move |_| j))
            .map(|j| (t.head[j], t.phase[j], t.part[j]))
            .collect();
        let mut busy = [0.0; MAX_SHARED];
        {
            let this = self.mover();
            let mut work: Vec<Work> = (0..threads)
                .map(|_| Work {
                    strips: Vec::with_capacity(computed),
                    times: Vec::with_capacity(computed),
                    bristles: Vec::with_capacity(shared.len() * n),
                    busy: 0.0,
                })
                .collect();
            let mut copies = rings.iter_mut();
            let (strips, scratch) = t.strips(n);
            let mut caches: Vec<_> = scratch.chunks_mut(ny).map(|c| c.iter_mut()).collect();
            for (j, (arrays, ring)) in strips.take(computed).enumerate() {
                // the strip's caches, one per thread (a whole strip uses thread 0's)
                let mut sc: Vec<&mut StripScratch> =
                    caches.iter_mut().filter_map(|c| c.next()).collect();
                if let Some(r) = assign[j] {
                    let sc = sc.drain(..).next().expect("a cache per strip and thread");
                    let strip = Strip::whole(j, arrays, ring, sc);
                    work[r].strips.push(strip);
                } else {
                    let s = shared
                        .iter()
                        .position(|&k| k == j)
                        .expect("a strip not given whole is shared");
                    let owner = &owners[s * n..(s + 1) * n];
                    share_strip(&mut work, j, owner, arrays, ring, &mut copies, sc);
                }
            }
            pool.run(&mut work, |w| {
                let t0 = std::time::Instant::now();
                w.copy_in();
                for sp in w.strips.iter_mut() {
                    let ts = std::time::Instant::now();
                    f(&this, sp);
                    w.times.push(ts.elapsed().as_secs_f64());
                }
                w.copy_out();
                w.busy = t0.elapsed().as_secs_f64();
            });
            for (b, w) in busy.iter_mut().zip(&work) {
                *b = w.busy;
            }
            let times = work
                .iter()
                .flat_map(|w| w.strips.iter().map(|sp| sp.j).zip(w.times.iter().copied()));
            self.balance.learn_costs(ny, times);
        }
        debug_assert!(
            rings.chunks(threads - 1).zip(&shared).all(|(c, &j)| {
                c.iter().all(|r| {
                    r.0 == t.head[j]
                        && r.1.to_bits() == t.phase[j].to_bits()
                        && r.2.d.to_bits() == t.part[j].d.to_bits()
                        && r.2.h.to_bits() == t.part[j].h.to_bits()
                })
            }),
            "the threads' copies of the ring bookkeeping went apart"
        );
        self.balance.owners = owners;
        self.balance.learn(&busy[..threads]);
        self.balance.learn_work(busy[..threads].iter().sum());
        t.put_back(self);
        if mirror {
            self.copy_to_mirror_strips();
        }
    }

    /// Which thread advances each of the first `computed` strips whole (None: shared, see
    /// [`whole_strips`]) and which thread moves each bristle of the shared strips, strip
    /// after strip (`n` each). The bristles that enter a shared strip during the step are
    /// marched in one sequence: that march goes to the thread with the fewest whole strips,
    /// the next shared strip's to the next thread.
    fn share_plan(
        &mut self,
        dt: f64,
        computed: usize,
        threads: usize,
    ) -> (Vec<Option<usize>>, Vec<u8>) {
        // the strips' measured costs where each is known, else their moves (1 / ell)
        let measured = self.balance.cost.len() >= computed
            && self.balance.cost[..computed].iter().all(|c| *c > 0.0);
        let cost: Vec<f64> = (0..computed)
            .map(|j| {
                if measured {
                    self.balance.cost[j]
                } else {
                    1.0 / self.lat.ell[j].max(1e-9)
                }
            })
            .collect();
        let assign = whole_strips(&cost, threads);
        let n = self.lat.nx + 1;
        self.balance.fit(threads);
        let mut whole = vec![0usize; threads];
        for r in assign.iter().flatten() {
            whole[*r] += 1;
        }
        let least = (0..threads).min_by_key(|&r| (whole[r], r)).unwrap_or(0);
        let mut owners = std::mem::take(&mut self.balance.owners);
        owners.clear();
        for (k, j) in (0..computed).filter(|&j| assign[j].is_none()).enumerate() {
            let dx = 2.0 * self.lat.ell[j] * self.load.patch.a / self.lat.nx as f64;
            let leaving = entries(self.state.run.inputs.v * dt, self.state.phase[j], dx);
            let chain = (least + k) % threads;
            self.balance
                .owners(&mut owners, n, self.state.head[j], leaving, chain);
        }
        (assign, owners)
    }

    /// Fixes how [`Self::each_strip_shared`] shares the bristles among threads (weights per
    /// thread, normalized) and keeps every step on the threads however little its work, or
    /// lets both adapt again (None). For tests.
    #[doc(hidden)]
    pub fn set_share_weights(&mut self, weights: Option<Vec<f64>>) {
        match weights {
            Some(w) => {
                let total: f64 = w.iter().sum();
                self.balance.weights = w.iter().map(|x| x / total).collect();
                self.balance.fixed = true;
            }
            None => self.balance.fixed = false,
        }
    }
}

/// One thread's work in a shared step: its view of each strip computed, the grid state's
/// entries of the bristles it moves, and the time it took, s.
struct Work<'a> {
    strips: Vec<Strip<'a>>,
    /// The time each of `strips` took, s.
    times: Vec<f64>,
    bristles: Vec<Bristle<'a>>,
    busy: f64,
}

/// The grid state's entries of bristle `id` of a shared strip (`strip`: its index in the
/// [`Work`]'s strips).
struct Bristle<'a> {
    strip: usize,
    id: usize,
    st: &'a mut BristleState,
    acc: &'a mut [f64; N_KERNEL],
    node_st: &'a mut BristleState,
    node_acc: &'a mut [f64; N_KERNEL],
}

impl Work<'_> {
    /// The thread's bristles from the grid state into its copies.
    fn copy_in(&mut self) {
        for b in self.bristles.iter() {
            let sp = &mut self.strips[b.strip];
            sp.st[b.id] = *b.st;
            sp.acc[b.id] = *b.acc;
            sp.node_st[b.id] = *b.node_st;
            sp.node_acc[b.id] = *b.node_acc;
        }
    }

    /// The thread's bristles back into the grid state.
    fn copy_out(&mut self) {
        for b in self.bristles.iter_mut() {
            let sp = &self.strips[b.strip];
            *b.st = sp.st[b.id];
            *b.acc = sp.acc[b.id];
            *b.node_st = sp.node_st[b.id];
            *b.node_acc = sp.node_acc[b.id];
        }
    }
}

/// Adds shared strip `j` to every thread's work: each bristle's grid-state entries to the
/// thread `owner` gives it, and to each thread a view of the strip on its own copies, with
/// the strip's ring bookkeeping (thread 0) or a copy of it (`copies`, threads 1..) and its
/// caches `sc` (one per thread).
fn share_strip<'a>(
    work: &mut [Work<'a>],
    j: usize,
    owner: &'a [u8],
    (st, acc, node_st, node_acc): Arrays<'a>,
    ring: Ring<'a>,
    copies: &mut impl Iterator<Item = &'a mut (usize, f64, super::Partial)>,
    sc: Vec<&'a mut StripScratch>,
) {
    let n = st.len();
    let bristles = st
        .iter_mut()
        .zip(acc.iter_mut())
        .zip(node_st.iter_mut().zip(node_acc.iter_mut()));
    for (id, ((st, acc), (node_st, node_acc))) in bristles.enumerate() {
        let w = &mut work[owner[id] as usize];
        w.bristles.push(Bristle {
            strip: w.strips.len(),
            id,
            st,
            acc,
            node_st,
            node_acc,
        });
    }
    let mut ring = Some(ring);
    for ((r, w), sc) in work.iter_mut().enumerate().zip(sc) {
        let (head, phase, part) = match ring.take() {
            Some(own) => own,
            None => {
                let (h, p, q) = copies
                    .next()
                    .expect("a copy of the ring per shared strip and thread");
                (h, p, q)
            }
        };
        let StripScratch {
            nodes,
            nodes_p0,
            fac,
            own,
        } = sc;
        own.fit(n);
        w.strips.push(Strip {
            j,
            owner: Some((owner, r as u8)),
            st: &mut own.st,
            acc: &mut own.acc,
            node_st: &mut own.node_st,
            node_acc: &mut own.node_acc,
            part,
            head,
            phase,
            nodes,
            nodes_p0,
            fac,
        });
    }
}

/// Threads a shared step keeps times for (more threads share equally).
const MAX_SHARED: usize = 64;
/// Strips whose costs are kept (more: the fallback, their moves).
const MAX_COST: usize = 256;

impl Private {
    /// Sized for `n` bristles.
    fn fit(&mut self, n: usize) {
        self.st.resize(n, BristleState::default());
        self.acc.resize(n, [0.0; N_KERNEL]);
        self.node_st.resize(n, BristleState::default());
        self.node_acc.resize(n, [0.0; N_KERNEL]);
    }
}

/// Which thread advances each strip whole (None: its bristles are shared among the
/// threads), from the strips' costs: with fewer strips than threads every strip is shared;
/// else the costliest is shared and the others go whole to the thread with the least cost
/// so far, the costliest first, so that the shared strip's split can even out what remains.
fn whole_strips(cost: &[f64], threads: usize) -> Vec<Option<usize>> {
    let c = cost.len();
    if c < threads {
        return vec![None; c];
    }
    let mut order: Vec<usize> = (0..c).collect();
    order.sort_by(|&a, &b| cost[b].total_cmp(&cost[a]).then(a.cmp(&b)));
    let mut assign = vec![None; c];
    let mut load = vec![0.0; threads];
    for &j in order.iter().skip(1) {
        let mut r = 0;
        for k in 1..threads {
            if load[k] < load[r] {
                r = k;
            }
        }
        load[r] += cost[j];
        assign[j] = Some(r);
    }
    assign
}

#[cfg(test)]
mod tests {
    use super::{whole_strips, Balance};

    #[test]
    fn the_costliest_strip_is_shared_and_the_others_go_to_the_least_loaded_thread() {
        // 20 x 5 without spin: strips at eta = -0.8, -0.4, 0, costs as moves (1 / ell)
        let cost = [1.0 / 0.6, 1.0 / 0.9165, 1.0];
        assert_eq!(whole_strips(&cost, 2), vec![None, Some(0), Some(1)]);
        // fewer strips than threads: all shared
        assert_eq!(whole_strips(&cost, 4), vec![None; 3]);
        // five strips: the costliest is shared, the others balanced (3 + 1 against 2 + 2)
        let cost5 = [3.0, 2.0, 1.0, 2.0, 4.0];
        let a = whole_strips(&cost5, 2);
        assert_eq!(a, vec![Some(0), Some(1), Some(0), Some(1), None]);
    }

    #[test]
    fn the_weights_move_work_to_the_thread_that_finished_first() {
        let mut b = Balance::default();
        b.fit(2);
        for _ in 0..30 {
            b.learn(&[2e-5, 1e-5]);
        }
        assert!(b.weights[0] < 0.4 && b.weights[1] > 0.6, "{:?}", b.weights);
        assert!((b.weights.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        // held fixed: unchanged
        b.fixed = true;
        let w = b.weights.clone();
        b.learn(&[1e-5, 5e-5]);
        assert_eq!(w, b.weights);
    }

    #[test]
    fn little_work_runs_on_one_thread_with_a_margin_against_switching() {
        let mut b = Balance::default();
        assert!(b.parallel());
        for _ in 0..20 {
            b.learn_work(7e-6);
        }
        assert!(!b.parallel());
        // between the bounds: stays as it is
        for _ in 0..20 {
            b.learn_work(11.5e-6);
        }
        assert!(!b.parallel());
        for _ in 0..20 {
            b.learn_work(20e-6);
        }
        assert!(b.parallel());
        for _ in 0..20 {
            b.learn_work(11.5e-6);
        }
        assert!(b.parallel());
    }

    #[test]
    fn owners_follow_the_weights_and_the_leaving_bristles_go_to_the_march() {
        let mut b = Balance::default();
        b.fit(2);
        b.weights = vec![0.75, 0.25];
        let mut o = Vec::new();
        // 21 bristles, ring head 5, 3 leave: the ring's last three slots are storage
        // indices 4, 3, 2
        b.owners(&mut o, 21, 5, 3, 0);
        assert_eq!(o.len(), 21);
        assert!([2, 3, 4].iter().all(|&id| o[id] == 0));
        let others: Vec<u8> = (0..21)
            .filter(|id| ![2, 3, 4].contains(id))
            .map(|id| o[id])
            .collect();
        let to_1 = others.iter().filter(|&&r| r == 1).count();
        assert!((4..=6).contains(&to_1), "{o:?}");
        // appended after what is there
        b.owners(&mut o, 21, 0, 0, 1);
        assert_eq!(o.len(), 42);
    }
}
