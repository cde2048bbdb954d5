//! Held-out scoring shared by the diagnosis and the search of forms: fold labels, a subset of the rows, the held-out CV(RMSE) and the fraction by which a candidate must lower it.

use crate::evaluate::predict_with;
use crate::fit::{FitOptions, FreeParam};
use crate::measure::Dataset;
use crate::stats::cv_rmse_pct;
use creep_core::config::Config;
use creep_core::error::Result;

/// A candidate must lower the held-out CV(RMSE) by this fraction of the baseline's to be claimed.
pub const CLAIM_FRACTION: f64 = 0.25;

/// Fold labels: by speed, else load, else series, else 3 interleaved folds.
pub(crate) fn folds(data: &Dataset) -> (String, Vec<usize>) {
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

/// Held-out CV(RMSE): fit `free` on all folds but one, predict that one.
pub(crate) fn heldout(
    cfg: &Config,
    data: &Dataset,
    labels: &[usize],
    free: &[FreeParam],
    threads: usize,
    opts: &FitOptions,
) -> Result<f64> {
    let nf = labels.iter().max().map(|m| m + 1).unwrap_or(1);
    let mut meas = Vec::new();
    let mut model = Vec::new();
    for f in 0..nf {
        let train = subset(data, &labels.iter().map(|l| *l != f).collect::<Vec<_>>());
        let test = subset(data, &labels.iter().map(|l| *l == f).collect::<Vec<_>>());
        if test.rows.is_empty() {
            continue;
        }
        let fitted = if free.is_empty() || train.rows.len() <= free.len() {
            cfg.clone()
        } else {
            crate::fit::fitted_or_kept(cfg, &train, free, threads, opts)?
        };
        let p = predict_with(&fitted, &test, threads, opts.memo)?;
        meas.extend(test.rows.iter().map(|r| r.f));
        model.extend(p.iter().map(|p| p.f));
    }
    Ok(cv_rmse_pct(&meas, &model))
}
