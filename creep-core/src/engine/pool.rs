//! The contact's threads: a pool whose idle workers spin a while before they sleep, so that handing a step's work to them costs far less than waking a sleeping thread.

use micropool::iter::{ExactParallelSourceExt, IntoExactParallelRefMutSource, ParallelIteratorExt};
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::Mutex;

/// Spin iterations (`std::hint::spin_loop`) an idle worker waits for more work before it
/// sleeps: longer than the caller's work between two steps of a coarse grid (integration
/// of the forces, the importer's own work), so that the next step finds the worker awake.
/// The crate's default; 300 made two threads on 20 x 3 slower than one (`thread_ratio`).
const IDLE_SPIN: usize = 3000;

/// Threads that advance one contact's bristles: the calling thread and `threads - 1`
/// workers.
pub(crate) struct Pool {
    pool: micropool::ThreadPool,
    threads: usize,
}

impl Pool {
    /// A pool of `threads` threads in all (the caller is one of them), `threads` >= 2.
    pub fn new(threads: usize) -> Self {
        Pool {
            pool: micropool::ThreadPoolBuilder::default()
                .num_threads(threads.saturating_sub(1).max(1))
                .idle_spin_cycles(IDLE_SPIN)
                .build(),
            threads,
        }
    }

    /// Threads in all, the caller's included.
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// Runs `f` on every item, the items spread over the threads (the caller takes part).
    /// A panic in `f` is raised again on the caller once every item is done, as on one
    /// thread (the pool itself would abort the process).
    pub fn run<T: Send>(&self, items: &mut [T], f: impl Fn(&mut T) + Sync) {
        let panicked = Mutex::new(None);
        items
            .par_iter_mut()
            .with_thread_pool(self.pool.split_per_item())
            .for_each(|x| {
                if let Err(p) = catch_unwind(AssertUnwindSafe(|| f(x))) {
                    if let Ok(mut first) = panicked.lock() {
                        first.get_or_insert(p);
                    }
                }
            });
        if let Some(p) = panicked.into_inner().ok().flatten() {
            resume_unwind(p);
        }
    }
}

impl std::fmt::Debug for Pool {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Pool {{ threads: {} }}", self.threads)
    }
}

#[cfg(test)]
mod tests {
    use super::Pool;

    #[test]
    fn every_item_runs_once_and_a_panic_reaches_the_caller() {
        let pool = Pool::new(2);
        let mut items: Vec<u32> = (0..7).collect();
        pool.run(&mut items, |x| *x += 100);
        assert_eq!(items, (100..107).collect::<Vec<_>>());
        let caught = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            pool.run(&mut items, |x| {
                if *x == 103 {
                    panic!("item {x}");
                }
                *x += 1000;
            })
        }));
        let msg = caught
            .err()
            .and_then(|p| p.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        assert_eq!(msg, "item 103");
        // the other items ran, and the pool still works
        assert_eq!(items.iter().filter(|x| **x >= 1100).count(), 6);
        assert_eq!(items[3], 103);
        pool.run(&mut items, |x| *x = 0);
        assert!(items.iter().all(|x| *x == 0));
    }
}
