//! One strip of the bristle grid as a unit of work: its bristles, ring buffer and caches borrowed out of the contact, so that strips advance independently (on several threads with `threads`).

use super::{Contact, Scheme};
use crate::bristle::BristleState;
use crate::material::NodeP;
use crate::thermal::{StepFactors, N_KERNEL};
use rayon::prelude::*;

/// The mutable state of strip `j` during a step (the rest of the contact is read only).
pub(super) struct Strip<'a> {
    /// Strip index.
    pub j: usize,
    /// Its `nx + 1` bristles (ring buffer, see `slot`).
    pub st: &'a mut [BristleState],
    /// Their heat-kernel accumulators.
    pub acc: &'a mut [[f64; N_KERNEL]],
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
}

impl Contact {
    /// Runs `f` on every strip, on the contact's threads when it has them (results do not
    /// depend on the number of threads: strips share no mutable state). While `f` runs, the
    /// contact's per-strip vectors (`st`, `acc`, `head`, `phase`, caches) are moved into the
    /// strips: `f` reaches them through its [`Strip`] only, never through the contact.
    pub(super) fn each_strip(&mut self, f: impl Fn(&Contact, &mut Strip) + Sync) {
        let nx1 = self.nx + 1;
        let mut st = std::mem::take(&mut self.st);
        let mut acc = std::mem::take(&mut self.acc);
        let mut head = std::mem::take(&mut self.head);
        let mut phase = std::mem::take(&mut self.phase);
        let mut nodes = std::mem::take(&mut self.np_cache);
        let mut nodes_p0 = std::mem::take(&mut self.np_cache_p0);
        let mut fac = std::mem::take(&mut self.fac_cache);
        {
            let this = &*self;
            let mut strips: Vec<Strip> = st
                .chunks_mut(nx1)
                .zip(acc.chunks_mut(nx1))
                .zip(head.iter_mut().zip(phase.iter_mut()))
                .zip(nodes.iter_mut().zip(nodes_p0.iter_mut()))
                .zip(fac.iter_mut())
                .enumerate()
                .map(
                    |(j, ((((st, acc), (head, phase)), (nodes, nodes_p0)), fac))| Strip {
                        j,
                        st,
                        acc,
                        head,
                        phase,
                        nodes,
                        nodes_p0,
                        fac,
                    },
                )
                .collect();
            match &self.pool {
                Some(pool) if strips.len() > 1 => pool.install(|| {
                    strips
                        .par_iter_mut()
                        .with_max_len(1)
                        .for_each(|sp| f(this, sp))
                }),
                _ => strips.iter_mut().for_each(|sp| f(this, sp)),
            }
        }
        self.st = st;
        self.acc = acc;
        self.head = head;
        self.phase = phase;
        self.np_cache = nodes;
        self.np_cache_p0 = nodes_p0;
        self.fac_cache = fac;
    }

    /// Advances the strips on `threads` threads (1: the calling thread alone, the default).
    /// The results do not depend on it.
    pub fn set_threads(&mut self, threads: usize) -> crate::Result<()> {
        self.pool = if threads <= 1 {
            None
        } else {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map_err(|e| crate::CreepError::Config {
                    source_name: "threads".into(),
                    message: format!("cannot start {threads} threads: {e}"),
                })?;
            Some(std::sync::Arc::new(pool))
        };
        Ok(())
    }

    /// Threads that advance the strips.
    pub fn threads(&self) -> usize {
        self.pool.as_ref().map_or(1, |p| p.current_num_threads())
    }

    /// The reference scheme for strip `sp`: every bristle gets one sub-step per cell crossing,
    /// cut at the instants a new bristle enters (the steady march's sub-steps exactly). Costs
    /// about (cells travelled) x (bristles) moves per step.
    pub(super) fn advance_cells(&self, sp: &mut Strip, dt: f64) {
        let j = sp.j;
        let v = self.inputs.v;
        let a = self.patch.a;
        let march = self.scheme == Scheme::CellsMarch;
        let dx = 2.0 * self.ell[j] * a / self.nx as f64;
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
        let wraps = {
            let (mut rem, mut ph, mut w) = (remaining, *sp.phase, 0usize);
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
        };
        while remaining > tol {
            let to_next = (1.0 - *sp.phase) * dx;
            if remaining >= to_next - tol {
                // end positions are one node further (phase 1), then the slots shift
                if !march {
                    self.substep_strip(sp, to_next / v, to_next, 1.0, 0, self.nx + 1);
                } else if n_new + (wraps - n_new) <= self.nx {
                    self.substep_strip(
                        sp,
                        to_next / v,
                        to_next,
                        1.0,
                        n_new,
                        self.nx + 1 - (wraps - n_new),
                    );
                }
                // all bristles moved one node: the slot numbering shifts by recycling the oldest
                self.enter_bristle(sp);
                n_new += 1;
                remaining -= to_next;
            } else {
                let ph = *sp.phase + remaining / dx;
                if !march {
                    self.substep_strip(sp, remaining / v, remaining, ph, 0, self.nx + 1);
                } else if n_new <= self.nx {
                    self.substep_strip(sp, remaining / v, remaining, ph, n_new, self.nx + 1);
                }
                *sp.phase = ph;
                d_end = remaining;
                remaining = 0.0;
            }
        }
        if n_new > 0 && march {
            self.march_new(sp, n_new.min(self.nx + 1), d_end);
        }
    }
}
