//! Held-out scoring shared by the diagnosis and the search of forms: fold labels, a subset of the rows, the held-out CV(RMSE) and the fraction by which a candidate must lower it.

use crate::evaluate::predict_with;
use crate::fit::{fit_params_with, FitOptions, FitResult, FreeParam};
use crate::measure::Dataset;
use crate::stats::cv_rmse_pct;
use creep_core::config::Config;
use creep_core::error::{CreepError, Result};

/// A candidate must lower the held-out CV(RMSE) by this fraction of the baseline's to be claimed.
pub const CLAIM_FRACTION: f64 = 0.25;

/// Fold labels: crossed curves of speed and load ([`crossed`]) where the file has them, else
/// by speed, else load, else series, else 3 interleaved folds.
pub(crate) fn folds(data: &Dataset) -> (String, Vec<usize>) {
    if let Some(labels) = crossed(data) {
        return ("curves of v_mps x fn_kN".into(), labels);
    }
    type KeyFn = fn(&crate::measure::Row) -> String;
    let by: [(&str, KeyFn); 3] = [
        ("v_mps", |r| format!("{}", r.v)),
        ("fn_kN", |r| format!("{}", r.fn_n)),
        ("series", |r| r.series.clone()),
    ];
    for (name, key) in by.iter() {
        let mut values: Vec<String> = Vec::new();
        let labels: Vec<usize> = data
            .rows
            .iter()
            .map(|r| {
                let k = key(r);
                match values.iter().position(|v| *v == k) {
                    Some(i) => i,
                    None => {
                        values.push(k);
                        values.len() - 1
                    }
                }
            })
            .collect();
        if values.len() >= 2 {
            return (name.to_string(), labels);
        }
    }
    (
        "rows (3 interleaved folds)".into(),
        (0..data.rows.len()).map(|i| i % 3).collect(),
    )
}

/// Fold labels for steady curves on crossed speeds and loads: when every speed is measured at
/// two loads or more and every load at two speeds or more, the curve of the `i`-th speed
/// (by value) and `j`-th load falls in fold (i + j) mod max(speeds, loads). A fold then holds
/// at most one curve of each speed and of each load, and its training rows have every speed
/// and every load: a factor that changes between two measured speeds (a threshold) is placed
/// by the other load's curves, where folds by speed would never see the held-out speed. As
/// many folds as folds by speed (or load) would give, of the same size. `None` for time
/// series and for files whose speeds and loads are not crossed.
fn crossed(data: &Dataset) -> Option<Vec<usize>> {
    if data.rows.iter().any(|r| r.t.is_some()) {
        return None;
    }
    let distinct = |x: &mut Vec<f64>| {
        x.sort_by(|a, b| a.total_cmp(b));
        x.dedup();
    };
    let mut speeds: Vec<f64> = data.rows.iter().map(|r| r.v).collect();
    let mut loads: Vec<f64> = data.rows.iter().map(|r| r.fn_n).collect();
    distinct(&mut speeds);
    distinct(&mut loads);
    let rank = |x: &[f64], v: f64| x.iter().position(|u| *u == v).unwrap_or(0);
    let cells: Vec<(usize, usize)> = data
        .rows
        .iter()
        .map(|r| (rank(&speeds, r.v), rank(&loads, r.fn_n)))
        .collect();
    let mut seen = vec![vec![false; loads.len()]; speeds.len()];
    for &(i, j) in &cells {
        seen[i][j] = true;
    }
    let per_speed = seen.iter().all(|l| l.iter().filter(|s| **s).count() >= 2);
    let per_load = (0..loads.len()).all(|j| seen.iter().filter(|l| l[j]).count() >= 2);
    if !(per_speed && per_load) {
        return None;
    }
    let k = speeds.len().max(loads.len());
    // the folds that hold a curve, numbered 0, 1, ... in order
    let raw: Vec<usize> = cells.iter().map(|(i, j)| (i + j) % k).collect();
    let mut used: Vec<usize> = raw.clone();
    used.sort_unstable();
    used.dedup();
    Some(
        raw.iter()
            .map(|f| used.iter().position(|u| u == f).unwrap_or(0))
            .collect(),
    )
}

pub(crate) fn subset(data: &Dataset, keep: &[bool]) -> Dataset {
    Dataset {
        source: data.source.clone(),
        extra_names: data.extra_names.clone(),
        columns: data.columns.clone(),
        delimiter: data.delimiter,
        rows: data
            .rows
            .iter()
            .zip(keep)
            .filter(|(_, k)| **k)
            .map(|(r, _)| r.clone())
            .collect(),
    }
}

/// Held-out CV(RMSE): fit `free` on all folds but one, predict that one. The folds' fits
/// run side by side on `threads` workers ([`side_by_side`]); the result does not depend on
/// `threads`.
pub(crate) fn heldout(
    cfg: &Config,
    data: &Dataset,
    labels: &[usize],
    free: &[FreeParam],
    threads: usize,
    opts: &FitOptions,
) -> Result<f64> {
    pooled_cv(side_by_side(fold_count(labels), threads, &|f, inner| {
        fold(cfg, data, labels, free, f, inner, opts)
    }))
}

/// The number of folds of `labels` (labels are 0, 1, ...).
pub(crate) fn fold_count(labels: &[usize]) -> usize {
    labels.iter().max().map(|m| m + 1).unwrap_or(1)
}

/// The held-out CV(RMSE) over the folds' measured and model values, in fold order; the first
/// fold's error, if any.
fn pooled_cv(folds: impl IntoIterator<Item = Result<(Vec<f64>, Vec<f64>)>>) -> Result<f64> {
    let (mut meas, mut model) = (Vec::new(), Vec::new());
    for r in folds {
        let (m, p) = r?;
        meas.extend(m);
        model.extend(p);
    }
    Ok(cv_rmse_pct(&meas, &model))
}

/// [`heldout`] and the fit on all rows ([`crate::fit::fit_params_with`]) of several
/// candidates (configuration, free parameters), all their
/// fits side by side in one pool of `threads` workers ([`side_by_side`]: no core waits for a
/// candidate's last fit while another candidate has fits to run); results in the order of
/// `items`, each as the candidate's fits one after the other would give it. `started(i)` is called when the
/// first fit of candidate `i` starts.
pub(crate) fn heldout_and_fit_all(
    items: &[(&Config, &[FreeParam])],
    data: &Dataset,
    labels: &[usize],
    threads: usize,
    opts: &FitOptions,
    started: &(dyn Fn(usize) + Sync),
) -> Vec<Result<(f64, FitResult)>> {
    // per candidate the fit on all rows first (it has the most rows), then the folds
    let per = 1 + fold_count(labels);
    let done = side_by_side(items.len() * per, threads, &|j, inner| {
        let (i, k) = (j / per, j % per);
        let (cfg, free) = items[i];
        if k == 0 {
            started(i);
            return Job::Full(Box::new(fit_params_with(
                cfg,
                data,
                free,
                inner,
                opts,
                &|_| {},
            )));
        }
        Job::Fold(fold(cfg, data, labels, free, k - 1, inner, opts))
    });
    let mut out = Vec::with_capacity(items.len());
    let mut jobs = done.into_iter();
    for _ in items {
        // each candidate's jobs taken whole, also where its result stops at an error
        let own: Vec<Job> = jobs.by_ref().take(per).collect();
        out.push(collect(own));
    }
    out
}

/// One job of [`heldout_and_fit_all`]: a fold's measured and held-out model values, or the
/// fit on all rows.
enum Job {
    Fold(Result<(Vec<f64>, Vec<f64>)>),
    Full(Box<Result<FitResult>>),
}

/// The held-out CV(RMSE) of one candidate's fold jobs (in fold order) and its fit on all rows;
/// the first error in the order of the sequential code: the folds', then the full fit's.
fn collect(jobs: Vec<Job>) -> Result<(f64, FitResult)> {
    let mut fitted = None;
    let h = pooled_cv(jobs.into_iter().filter_map(|d| match d {
        Job::Fold(r) => Some(r),
        Job::Full(r) => {
            fitted = Some(*r);
            None
        }
    }))?;
    match fitted {
        Some(f) => Ok((h, f?)),
        None => Err(CreepError::State("the fit on all rows did not run".into())),
    }
}

/// Fold `f`'s measured values and the model fitted on the other folds there (empty when the
/// fold has no rows).
fn fold(
    cfg: &Config,
    data: &Dataset,
    labels: &[usize],
    free: &[FreeParam],
    f: usize,
    threads: usize,
    opts: &FitOptions,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let train = subset(data, &labels.iter().map(|l| *l != f).collect::<Vec<_>>());
    let test = subset(data, &labels.iter().map(|l| *l == f).collect::<Vec<_>>());
    if test.rows.is_empty() {
        return Ok((Vec::new(), Vec::new()));
    }
    let fitted = if free.is_empty() || train.rows.len() <= free.len() {
        cfg.clone()
    } else {
        crate::fit::fitted_or_kept(cfg, &train, free, threads, opts)?
    };
    let p = predict_with(&fitted, &test, threads, opts.memo)?;
    Ok((
        test.rows.iter().map(|r| r.f).collect(),
        p.iter().map(|p| p.f).collect(),
    ))
}

/// Runs jobs `0..n` on up to `threads` workers, each taking the next job as it finishes one
/// (the longest first, if the caller orders them so), and returns their results in job
/// order. `job(j, inner)` runs job `j` with `inner` threads of its own (`threads` shared
/// among the workers). A worker's panic is passed on.
pub(crate) fn side_by_side<T: Send>(
    n: usize,
    threads: usize,
    job: &(dyn Fn(usize, usize) -> T + Sync),
) -> Vec<T> {
    let workers = threads.clamp(1, n.max(1));
    let inner = (threads / workers).max(1);
    if workers == 1 {
        return (0..n).map(|j| job(j, inner)).collect();
    }
    let next = std::sync::atomic::AtomicUsize::new(0);
    let mut done: Vec<(usize, T)> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                s.spawn(|| {
                    let mut out = Vec::new();
                    loop {
                        let j = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        if j >= n {
                            return out;
                        }
                        out.push((j, job(j, inner)));
                    }
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    });
    done.sort_by_key(|(j, _)| *j);
    done.into_iter().map(|(_, t)| t).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::Defaults;

    /// A file with one row per (speed, load) point.
    fn file(points: &[(f64, f64)]) -> Dataset {
        let mut csv = String::from("cx,f,v_mps,fn_kN\n");
        for (v, fkn) in points {
            csv += &format!("0.01,0.3,{v},{fkn}\n");
        }
        Dataset::from_csv_str(&csv, "t.csv", &Defaults::default()).unwrap()
    }

    #[test]
    fn crossed_curves_keep_every_speed_and_load_in_training() {
        let speeds = [6.0, 12.0, 18.0, 28.0];
        let pts: Vec<(f64, f64)> = speeds
            .iter()
            .flat_map(|&v| [(v, 80.0), (v, 120.0)])
            .collect();
        let d = file(&pts);
        let (by, labels) = folds(&d);
        assert_eq!(by, "curves of v_mps x fn_kN");
        assert_eq!(fold_count(&labels), 4);
        for f in 0..4 {
            let train: Vec<&(f64, f64)> = pts
                .iter()
                .zip(&labels)
                .filter(|(_, l)| **l != f)
                .map(|(p, _)| p)
                .collect();
            for v in speeds {
                assert!(train.iter().any(|p| p.0 == v), "fold {f} lacks speed {v}");
            }
            for l in [80.0, 120.0] {
                assert!(train.iter().any(|p| p.1 == l), "fold {f} lacks load {l}");
            }
        }
    }

    #[test]
    fn speeds_at_one_load_each_fall_back_to_folds_by_speed() {
        // the second load only at one speed: not crossed
        let d = file(&[(5.0, 80.0), (10.0, 80.0), (15.0, 80.0), (15.0, 120.0)]);
        let (by, labels) = folds(&d);
        assert_eq!(by, "v_mps");
        assert_eq!(labels, vec![0, 1, 2, 2]);
    }
}
