//! Runs a configuration over a measurement file and compares: per-row predictions, CV(RMSE) overall, per group and per creepage regime.

use crate::config::{Config, Geometry};
use crate::error::Result;
use crate::measure::{cv_rmse_pct, Dataset, Row};
use crate::model::Model;
use std::collections::BTreeMap;

/// Model result at one measured point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Prediction {
    /// Model traction coefficient, -.
    pub f: f64,
    /// Maximum model temperature, degC.
    pub t_max: f64,
    /// Model frictional power, W.
    pub p_fric: f64,
    /// Maximum Hertz pressure, Pa.
    pub p0: f64,
    /// Slip velocity |c| v, m/s.
    pub slip_velocity: f64,
    /// Time derivative of the creepage (time series), 1/s; 0 for steady rows.
    pub dcx_dt: f64,
}

fn config_for(cfg: &Config, r: &Row) -> Config {
    let mut c = cfg.clone();
    if let Some((a, b)) = r.ab {
        c.geometry = Geometry::SemiAxes {
            a,
            b,
            fn_ref: r.fn_n,
        };
    }
    c
}

fn extras(data: &Dataset, r: &Row) -> Vec<(String, f64)> {
    data.extra_names
        .iter()
        .cloned()
        .zip(r.extra.iter().copied())
        .collect()
}

fn geometry_key(r: &Row) -> Option<(u64, u64, u64)> {
    r.ab.map(|(a, b)| (a.to_bits(), b.to_bits(), r.fn_n.to_bits()))
}

/// Work items: a steady row, or a whole time series (row indices in time order).
enum Job {
    Steady(usize),
    Series(Vec<usize>),
}

fn run_job(
    cfg: &Config,
    data: &Dataset,
    job: &Job,
    cache: &mut BTreeMap<Option<(u64, u64, u64)>, Model>,
    out: &mut Vec<(usize, Prediction)>,
) -> Result<()> {
    match job {
        Job::Steady(i) => {
            let r = &data.rows[*i];
            let key = geometry_key(r);
            let m = match cache.entry(key) {
                std::collections::btree_map::Entry::Occupied(e) => e.into_mut(),
                std::collections::btree_map::Entry::Vacant(e) => {
                    e.insert(Model::new(&config_for(cfg, r))?)
                }
            };
            if !cfg.formulas.is_empty() || !cfg.custom.is_empty() {
                m.set_extra(&extras(data, r))?;
            }
            let o = m.steady(&r.inputs())?;
            out.push((
                *i,
                Prediction {
                    f: o.f,
                    t_max: o.t_max,
                    p_fric: o.p_fric,
                    p0: o.p0,
                    slip_velocity: (r.cx.hypot(r.cy)) * r.v,
                    dcx_dt: 0.0,
                },
            ));
        }
        Job::Series(idx) => {
            let first = &data.rows[idx[0]];
            let mut m = Model::new(&config_for(cfg, first))?;
            let mut prev: Option<&Row> = None;
            for &i in idx {
                let r = &data.rows[i];
                if !cfg.formulas.is_empty() || !cfg.custom.is_empty() {
                    m.set_extra(&extras(data, r))?;
                }
                let o = match prev {
                    None => m.steady(&r.inputs())?,
                    Some(p) => m.step(r.t.unwrap_or(0.0) - p.t.unwrap_or(0.0), &r.inputs())?,
                };
                let dcx = match prev {
                    Some(p) => (r.cx - p.cx) / (r.t.unwrap_or(0.0) - p.t.unwrap_or(0.0)),
                    None => 0.0,
                };
                out.push((
                    i,
                    Prediction {
                        f: o.f,
                        t_max: o.t_max,
                        p_fric: o.p_fric,
                        p0: o.p0,
                        slip_velocity: (r.cx.hypot(r.cy)) * r.v,
                        dcx_dt: dcx,
                    },
                ));
                prev = Some(r);
            }
        }
    }
    Ok(())
}

/// Predictions for every row (in row order), computed on `threads` threads.
pub fn predict(cfg: &Config, data: &Dataset, threads: usize) -> Result<Vec<Prediction>> {
    let mut jobs = Vec::new();
    let mut series: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
    for (i, r) in data.rows.iter().enumerate() {
        if r.t.is_some() {
            series.entry(r.series.as_str()).or_default().push(i);
        } else {
            jobs.push(Job::Steady(i));
        }
    }
    for (_, mut idx) in series {
        idx.sort_by(|a, b| {
            data.rows[*a]
                .t
                .unwrap_or(0.0)
                .total_cmp(&data.rows[*b].t.unwrap_or(0.0))
        });
        jobs.push(Job::Series(idx));
    }
    let threads = threads.clamp(1, 64).min(jobs.len().max(1));
    let mut results: Vec<Result<Vec<(usize, Prediction)>>> = Vec::new();
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                let jobs = &jobs;
                s.spawn(move || {
                    let mut cache = BTreeMap::new();
                    let mut out = Vec::new();
                    for job in jobs.iter().skip(t).step_by(threads) {
                        run_job(cfg, data, job, &mut cache, &mut out)?;
                    }
                    Ok(out)
                })
            })
            .collect();
        for h in handles {
            results.push(h.join().unwrap_or_else(|_| {
                Err(crate::error::CreepError::State(
                    "a worker thread panicked".into(),
                ))
            }));
        }
    });
    let mut pred = vec![Prediction::default(); data.rows.len()];
    for r in results {
        for (i, p) in r? {
            pred[i] = p;
        }
    }
    Ok(pred)
}

/// CV(RMSE) of one group of rows.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct GroupStat {
    /// Grouping variable ("series", "condition", "v_mps", "fn_kN", "regime", "cx>=1%").
    pub by: String,
    /// Group value.
    pub value: String,
    /// Number of rows.
    pub n: usize,
    /// CV(RMSE), %.
    pub cv_rmse_pct: f64,
    /// Mean residual model - measured, -.
    pub mean_residual: f64,
}

/// Creepage regime of a row: R1 below 0.5 %, R3 beyond the creepage of the series' measured
/// maximum of f, R2 between (seed Sec. 3.1: steep rise, moderate rise, falling branch).
pub fn regimes(data: &Dataset) -> Vec<&'static str> {
    let mut cmax: BTreeMap<&str, (f64, f64)> = BTreeMap::new();
    for r in &data.rows {
        let e = cmax.entry(r.series.as_str()).or_insert((f64::MIN, 0.0));
        if r.f.abs() > e.0 {
            *e = (r.f.abs(), r.cx.abs());
        }
    }
    data.rows
        .iter()
        .map(|r| {
            let c = r.cx.abs();
            let cm = cmax
                .get(r.series.as_str())
                .map(|e| e.1)
                .unwrap_or(f64::INFINITY);
            if c < 0.005 {
                "R1"
            } else if c <= cm {
                "R2"
            } else {
                "R3"
            }
        })
        .collect()
}

/// The full comparison of a configuration with a measurement file.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Comparison {
    /// CV(RMSE) over all rows, % (Eq. 2.9).
    pub cv_rmse_pct: f64,
    /// CV(RMSE) over rows with |c_x| >= 1 %, % (seed Tab. 6.3).
    pub cv_rmse_pct_cx_ge_1pct: f64,
    /// Number of rows.
    pub n: usize,
    /// Per group (series, condition, speed, load) and per regime.
    pub groups: Vec<GroupStat>,
}

/// Compares predictions with the measurements.
pub fn compare(data: &Dataset, pred: &[Prediction]) -> Comparison {
    let meas: Vec<f64> = data.rows.iter().map(|r| r.f).collect();
    let model: Vec<f64> = pred.iter().map(|p| p.f).collect();
    let subset = |keep: &dyn Fn(usize) -> bool| -> (Vec<f64>, Vec<f64>) {
        let idx: Vec<usize> = (0..meas.len()).filter(|&i| keep(i)).collect();
        (
            idx.iter().map(|&i| meas[i]).collect(),
            idx.iter().map(|&i| model[i]).collect(),
        )
    };
    let stat = |by: &str, value: String, keep: &dyn Fn(usize) -> bool| {
        let (a, b) = subset(keep);
        let mean_residual = if a.is_empty() {
            f64::NAN
        } else {
            a.iter().zip(&b).map(|(x, y)| y - x).sum::<f64>() / a.len() as f64
        };
        GroupStat {
            by: by.into(),
            value,
            n: a.len(),
            cv_rmse_pct: cv_rmse_pct(&a, &b),
            mean_residual,
        }
    };
    let mut groups = Vec::new();
    let reg = regimes(data);
    type Key = fn(&Row) -> String;
    let keys: [(&str, Key); 4] = [
        ("series", |r| r.series.clone()),
        ("condition", |r| r.condition.clone()),
        ("v_mps", |r| format!("{}", r.v)),
        ("fn_kN", |r| format!("{}", r.fn_n / 1e3)),
    ];
    for (by, key) in keys {
        let mut values: Vec<String> = Vec::new();
        for r in &data.rows {
            let k = key(r);
            if !values.contains(&k) {
                values.push(k);
            }
        }
        for v in values {
            groups.push(stat(by, v.clone(), &|i| key(&data.rows[i]) == v));
        }
    }
    for rg in ["R1", "R2", "R3"] {
        let g = stat("regime", rg.into(), &|i| reg[i] == rg);
        if g.n > 0 {
            groups.push(g);
        }
    }
    let ge1 = stat("cx>=1%", "yes".into(), &|i| data.rows[i].cx.abs() >= 0.01);
    Comparison {
        cv_rmse_pct: cv_rmse_pct(&meas, &model),
        cv_rmse_pct_cx_ge_1pct: ge1.cv_rmse_pct,
        n: meas.len(),
        groups,
    }
}
