//! Runs a configuration over a measurement file and compares: per-row predictions, CV(RMSE) overall, per group and per creepage regime.

use crate::measure::{Dataset, Row};
use crate::stats::Residuals;
use creep_core::config::{Config, Geometry};
use creep_core::error::{CreepError, Result};
use creep_core::model::Model;
use creep_core::Modifier;
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

/// The data-column values of row `r` as (name, value) pairs, for [`creep_core::Model::set_extra`].
pub fn extras(data: &Dataset, r: &Row) -> Vec<(String, f64)> {
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
    warns: &mut Vec<(usize, Vec<String>)>,
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
            if !cfg.modifiers.is_empty() {
                m.set_extra(&extras(data, r))?;
            }
            let o = m.steady(&r.inputs())?;
            let w = m.take_warnings();
            if !w.is_empty() {
                warns.push((*i, w));
            }
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
                if !cfg.modifiers.is_empty() {
                    m.set_extra(&extras(data, r))?;
                }
                let o = match prev {
                    None => m.steady(&r.inputs())?,
                    Some(p) => m.step(r.t.unwrap_or(0.0) - p.t.unwrap_or(0.0), &r.inputs())?,
                };
                let w = m.take_warnings();
                if !w.is_empty() {
                    warns.push((i, w));
                }
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

/// Checks that every data column a formula or Rust effect uses is in the data file.
pub fn check_columns(cfg: &Config, data: &Dataset) -> Result<()> {
    let have = || {
        if data.extra_names.is_empty() {
            "none".to_string()
        } else {
            data.extra_names.join(", ")
        }
    };
    for m in &cfg.modifiers {
        for c in m.columns() {
            if !data.extra_names.iter().any(|n| n == c) {
                let verb = match m {
                    creep_core::AnyModifier::Formula(_) => "uses",
                    creep_core::AnyModifier::Rust(_) => "needs",
                };
                return Err(CreepError::Data {
                    source_name: data.source.clone(),
                    message: format!(
                        "{} {verb} the column '{c}', which this data file does not have (extra columns: {})",
                        m.describe(),
                        have()
                    ),
                });
            }
        }
    }
    Ok(())
}

/// Factors of the formula and Rust effects at a row's operating point (local ones with the
/// bristle at rest at p = 0 and 1 GPa, bulk temperature, u = 0): (effect, value) of the first
/// factor that is not finite or negative. Factors scale strengths (tau_c1, tau_c2, mu) and
/// compliances (L_e, L_p), so they must be finite and >= 0.
fn bad_factor(cfg: &Config, data: &Dataset, r: &Row) -> Option<(String, f64)> {
    let slip = r.cx.hypot(r.cy) * r.v;
    let named: Vec<(String, f64)> = data
        .extra_names
        .iter()
        .cloned()
        .zip(r.extra.iter().copied())
        .collect();
    let op = creep_core::custom::OperatingPoint {
        v_mps: r.v,
        fn_kn: r.fn_n / 1e3,
        cx: r.cx,
        cy: r.cy,
        spin_per_m: r.spin,
        t_bulk_c: r.t_bulk,
        columns: &named,
    };
    for m in &cfg.modifiers {
        let mut cols = Vec::new();
        for c in m.columns() {
            let k = data.extra_names.iter().position(|n| n == c)?;
            cols.push(r.extra[k]);
        }
        let probes: &[f64] = if m.uses_local_state() {
            &[0.0, 1.0]
        } else {
            &[0.0]
        };
        for &p in probes {
            let local = creep_core::custom::LocalState {
                p_gpa: p,
                t_c: r.t_bulk,
                u_mm: 0.0,
                slip_mps: slip,
            };
            let x = m.factor(&local, &op, &cols);
            if !(x.is_finite() && x >= 0.0) {
                return Some((m.describe(), x));
            }
        }
    }
    None
}

fn lines_text(lines: &[usize]) -> String {
    let shown: Vec<String> = lines.iter().take(8).map(|l| l.to_string()).collect();
    if lines.len() > 8 {
        format!("{} and {} more", shown.join(", "), lines.len() - 8)
    } else {
        shown.join(", ")
    }
}

/// Key of a steady row's operating point: rows with equal keys have equal predictions.
fn point_key(cfg: &Config, cols: &[usize], r: &Row) -> Vec<u64> {
    let (a, b) = r.ab.unwrap_or((f64::NAN, f64::NAN));
    let mut k = vec![
        r.cx.to_bits(),
        r.cy.to_bits(),
        r.spin.to_bits(),
        r.v.to_bits(),
        r.fn_n.to_bits(),
        r.t_bulk.to_bits(),
        a.to_bits(),
        b.to_bits(),
    ];
    if !cfg.modifiers.is_empty() {
        k.extend(cols.iter().map(|&c| r.extra[c].to_bits()));
    }
    k
}

/// Steady predictions already computed, by configuration and operating point: a fit, the
/// folds of a cross-validation and the Jacobians of their solvers evaluate many
/// configurations more than once (the start, the best point, ...) on overlapping rows;
/// [`predict_with`] looks those up instead of running the model again.
///
/// A configuration is identified by the full text of its `Debug` form (every field, floating
/// point numbers written so that they read back bit for bit) plus the names of its Rust
/// effects, an operating point by the exact bits of the row's inputs that the model sees (as
/// [`predict`] merges rows). A steady prediction depends on nothing else, so a looked-up
/// value is bit-identical to a recomputed one. Time series rows (stateful) are never
/// memoised.
#[derive(Debug, Default)]
pub struct Memo {
    inner: std::sync::Mutex<MemoInner>,
}

#[derive(Debug, Default)]
struct MemoInner {
    configs: std::collections::HashMap<String, usize>,
    points: std::collections::HashMap<(usize, Vec<u64>), Prediction>,
    hits: usize,
    misses: usize,
}

impl Memo {
    /// An empty memo.
    pub fn new() -> Self {
        Self::default()
    }
    /// (operating points looked up, operating points evaluated) so far.
    pub fn counts(&self) -> (usize, usize) {
        let m = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        (m.hits, m.misses)
    }
    fn lock(&self) -> std::sync::MutexGuard<'_, MemoInner> {
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }
    fn config_id(&self, cfg: &Config) -> usize {
        let mut key = format!("{cfg:?}");
        for u in cfg.rust_effects() {
            key.push('|');
            key.push_str(u.effect.name());
        }
        let mut m = self.lock();
        let n = m.configs.len();
        *m.configs.entry(key).or_insert(n)
    }
}

/// Predictions for every row (in row order), computed on `threads` threads. Steady rows that
/// share an operating point (creepages, speed, load, temperature, semi-axes and the data
/// columns the configuration's formula/Rust effects use) are evaluated once. Fails, naming
/// the rows, when a formula or Rust effect's factor is not finite or negative, or when the
/// model's traction coefficient is not finite.
pub fn predict(cfg: &Config, data: &Dataset, threads: usize) -> Result<Vec<Prediction>> {
    predict_with(cfg, data, threads, None)
}

/// [`predict`], looking steady operating points up in `memo` (and adding the ones computed).
/// The result is bit-identical to [`predict`]'s.
pub fn predict_with(
    cfg: &Config,
    data: &Dataset,
    threads: usize,
    memo: Option<&Memo>,
) -> Result<Vec<Prediction>> {
    Ok(predict_inner(cfg, data, threads, memo)?.0)
}

/// [`predict`], with the warnings the model raised for the rows (wheel slide, Péclet
/// condition, ...), grouped by kind and counted per series ([`ModelWarning`]).
pub fn predict_warned(
    cfg: &Config,
    data: &Dataset,
    threads: usize,
) -> Result<(Vec<Prediction>, Vec<ModelWarning>)> {
    let (pred, per_row) = predict_inner(cfg, data, threads, None)?;
    Ok((pred, group_warnings(data, &per_row)))
}

/// One kind of warning the model raised, with the rows it was raised for.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ModelWarning {
    /// The model's message for the first row it was raised for (its numbers are that row's).
    pub message: String,
    /// Number of rows it was raised for.
    pub rows: usize,
    /// Rows per series, in the file's order of series.
    pub per_series: Vec<SeriesWarningCount>,
}

/// How many rows of one series a warning was raised for.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SeriesWarningCount {
    /// Series name.
    pub series: String,
    /// Rows of the series.
    pub rows: usize,
    /// Their lines in the file.
    pub lines: Vec<usize>,
}

/// The kind of a warning: its text before the first digit (the numbers are the row's).
fn warning_kind(m: &str) -> &str {
    m.find(|c: char| c.is_ascii_digit())
        .map(|i| &m[..i])
        .unwrap_or(m)
}

fn group_warnings(data: &Dataset, per_row: &[Vec<String>]) -> Vec<ModelWarning> {
    let mut out: Vec<ModelWarning> = Vec::new();
    for (r, ws) in data.rows.iter().zip(per_row) {
        for w in ws {
            let k = warning_kind(w);
            let i = match out.iter().position(|x| warning_kind(&x.message) == k) {
                Some(i) => i,
                None => {
                    out.push(ModelWarning {
                        message: w.clone(),
                        rows: 0,
                        per_series: Vec::new(),
                    });
                    out.len() - 1
                }
            };
            let mw = &mut out[i];
            mw.rows += 1;
            match mw.per_series.iter_mut().find(|s| s.series == r.series) {
                Some(s) => {
                    s.rows += 1;
                    s.lines.push(r.line);
                }
                None => mw.per_series.push(SeriesWarningCount {
                    series: r.series.clone(),
                    rows: 1,
                    lines: vec![r.line],
                }),
            }
        }
    }
    out
}

/// The warnings in words for a report: each message once, then its rows counted per series.
pub fn warnings_text(ws: &[ModelWarning]) -> String {
    let mut s = String::new();
    for w in ws {
        s += &format!("warning ({} row(s)): {}\n", w.rows, w.message);
        let per: Vec<String> = w
            .per_series
            .iter()
            .map(|c| {
                format!(
                    "series {}: {} row(s) (line(s) {})",
                    c.series,
                    c.rows,
                    lines_text(&c.lines)
                )
            })
            .collect();
        s += &format!("  {}\n", per.join("; "));
    }
    s
}

/// The work of one prediction: a job per unique steady operating point not in the memo and
/// per time series, and where each row's prediction comes from.
struct Plan {
    jobs: Vec<Job>,
    /// The unique operating point of each steady row (`usize::MAX` for time-series rows).
    of_row: Vec<usize>,
    /// Each unique point's key (with a memo only).
    keys: Vec<Vec<u64>>,
    /// Each unique point's prediction, where the memo has it.
    by_point: Vec<Option<Prediction>>,
}

/// Plans the prediction of `data`: unique steady points (looked up in `memo` under `cfg_id`)
/// and the time series sorted by time; an error where a formula or Rust factor is not finite
/// and >= 0 at a row's operating point.
fn plan(cfg: &Config, data: &Dataset, memo: Option<&Memo>, cfg_id: Option<usize>) -> Result<Plan> {
    // extra columns that change the model: those the effects use
    let used: Vec<usize> = (0..data.extra_names.len())
        .filter(|&k| {
            let n = &data.extra_names[k];
            cfg.modifiers.iter().any(|m| match m {
                creep_core::AnyModifier::Formula(f) => f.columns.contains(n),
                // a Rust effect may read any column by name
                creep_core::AnyModifier::Rust(_) => true,
            })
        })
        .collect();
    let mut jobs = Vec::new();
    let mut series: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
    let mut unique: std::collections::HashMap<Vec<u64>, usize> = std::collections::HashMap::new();
    let mut of_row = vec![usize::MAX; data.rows.len()];
    // per unique operating point: its key (memo only) and its prediction when looked up
    let mut keys: Vec<Vec<u64>> = Vec::new();
    let mut by_point: Vec<Option<Prediction>> = Vec::new();
    let mut bad: BTreeMap<String, (Vec<usize>, f64)> = BTreeMap::new();
    for (i, r) in data.rows.iter().enumerate() {
        if r.t.is_some() {
            series.entry(r.series.as_str()).or_default().push(i);
            if !cfg.modifiers.is_empty() {
                if let Some((e, x)) = bad_factor(cfg, data, r) {
                    bad.entry(e).or_insert((Vec::new(), x)).0.push(r.line);
                }
            }
            continue;
        }
        let key = point_key(cfg, &used, r);
        let n = unique.len();
        let known = match (memo, cfg_id) {
            (Some(m), Some(id)) if !unique.contains_key(&key) => {
                keys.push(key.clone());
                m.lock().points.get(&(id, key.clone())).copied()
            }
            _ => None,
        };
        let u = *unique.entry(key).or_insert(n);
        if u == n {
            by_point.push(known);
            if known.is_none() {
                jobs.push(Job::Steady(i));
            }
            if !cfg.modifiers.is_empty() {
                if let Some((e, x)) = bad_factor(cfg, data, r) {
                    bad.entry(e).or_insert((Vec::new(), x)).0.push(r.line);
                }
            }
        }
        of_row[i] = u;
    }
    if let Some((e, (lines, x))) = bad.into_iter().next() {
        return Err(CreepError::Data {
            source_name: data.source.clone(),
            message: format!(
                "{e} is {x} at line(s) {}: a factor scaling a strength or compliance must be finite and >= 0",
                lines_text(&lines)
            ),
        });
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
    Ok(Plan {
        jobs,
        of_row,
        keys,
        by_point,
    })
}

/// The predictions and warnings of each worker (jobs dealt round-robin to `threads` threads).
type Done = (Vec<(usize, Prediction)>, Vec<(usize, Vec<String>)>);

/// Runs the jobs on up to `threads` scoped threads.
fn run_jobs(cfg: &Config, data: &Dataset, jobs: &[Job], threads: usize) -> Vec<Result<Done>> {
    let threads = threads.clamp(1, 64).min(jobs.len().max(1));
    let mut results: Vec<Result<Done>> = Vec::new();
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                s.spawn(move || {
                    let mut cache = BTreeMap::new();
                    let mut out = Vec::new();
                    let mut warns = Vec::new();
                    for job in jobs.iter().skip(t).step_by(threads) {
                        run_job(cfg, data, job, &mut cache, &mut out, &mut warns)?;
                    }
                    Ok((out, warns))
                })
            })
            .collect();
        for h in handles {
            results.push(
                h.join()
                    .unwrap_or_else(|_| Err(CreepError::State("a worker thread panicked".into()))),
            );
        }
    });
    results
}

/// Predictions and, per row, the warnings the model raised for it (none for points looked up
/// in the memo).
fn predict_inner(
    cfg: &Config,
    data: &Dataset,
    threads: usize,
    memo: Option<&Memo>,
) -> Result<(Vec<Prediction>, Vec<Vec<String>>)> {
    check_columns(cfg, data)?;
    let cfg_id = memo.map(|m| m.config_id(cfg));
    let Plan {
        jobs,
        of_row,
        keys,
        mut by_point,
        ..
    } = plan(cfg, data, memo, cfg_id)?;
    let results = run_jobs(cfg, data, &jobs, threads);
    let mut pred = vec![Prediction::default(); data.rows.len()];
    let looked_up = by_point.iter().filter(|p| p.is_some()).count();
    let mut computed = Vec::new();
    let mut warned: Vec<(usize, Vec<String>)> = Vec::new();
    for r in results {
        let (r, w) = r?;
        warned.extend(w);
        for (i, p) in r {
            if data.rows[i].t.is_some() {
                pred[i] = p;
            } else {
                by_point[of_row[i]] = Some(p);
                computed.push(of_row[i]);
            }
        }
    }
    if let (Some(m), Some(id)) = (memo, cfg_id) {
        let mut m = m.lock();
        m.hits += looked_up;
        m.misses += computed.len();
        for u in computed {
            if let Some(p) = by_point[u] {
                m.points.insert((id, keys[u].clone()), p);
            }
        }
    }
    for (i, r) in data.rows.iter().enumerate() {
        if r.t.is_none() {
            pred[i] = by_point[of_row[i]].unwrap_or_default();
        }
    }
    check_finite(cfg, data, &pred)?;
    Ok((pred, warnings_per_row(data, &of_row, warned)))
}

/// An error naming the lines where the model's traction coefficient is not finite.
fn check_finite(cfg: &Config, data: &Dataset, pred: &[Prediction]) -> Result<()> {
    let nonfinite: Vec<usize> = data
        .rows
        .iter()
        .zip(pred)
        .filter(|(_, p)| !p.f.is_finite())
        .map(|(r, _)| r.line)
        .collect();
    if nonfinite.is_empty() {
        return Ok(());
    }
    let mut who = format!(
        "model {} with effects {:?}",
        cfg.model.name(),
        cfg.effects
            .to_vec()
            .iter()
            .map(|e| creep_core::effects::info(*e).name)
            .collect::<Vec<_>>()
    );
    for m in &cfg.modifiers {
        who += &format!(", {}", m.describe());
    }
    Err(CreepError::Data {
        source_name: data.source.clone(),
        message: format!(
            "the {who} gives a non-finite traction coefficient at line(s) {}",
            lines_text(&nonfinite)
        ),
    })
}

/// The model's warnings per row: a steady point's warnings hold for every row of that point.
fn warnings_per_row(
    data: &Dataset,
    of_row: &[usize],
    warned: Vec<(usize, Vec<String>)>,
) -> Vec<Vec<String>> {
    let mut per_row: Vec<Vec<String>> = vec![Vec::new(); data.rows.len()];
    let mut per_point: std::collections::HashMap<usize, Vec<String>> = Default::default();
    for (i, w) in warned {
        if data.rows[i].t.is_some() {
            per_row[i] = w;
        } else {
            per_point.insert(of_row[i], w);
        }
    }
    for (i, r) in data.rows.iter().enumerate() {
        if r.t.is_none() {
            if let Some(w) = per_point.get(&of_row[i]) {
                per_row[i] = w.clone();
            }
        }
    }
    per_row
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

/// One group's statistics, named.
fn group_stat(acc: &Residuals, by: &str, value: String) -> GroupStat {
    GroupStat {
        by: by.into(),
        value,
        n: acc.n,
        cv_rmse_pct: acc.cv_rmse_pct(),
        mean_residual: acc.mean_residual(),
    }
}

/// Compares predictions with the measurements (one pass over the rows).
pub fn compare(data: &Dataset, pred: &[Prediction]) -> Comparison {
    use std::collections::HashMap;
    let mut groups = Vec::new();
    let reg = regimes(data);
    // per key: first-appearance order of the values and their accumulators
    type TextKey<'a> = (Vec<String>, HashMap<&'a str, usize>, Vec<Residuals>);
    type NumKey = (Vec<f64>, HashMap<u64, usize>, Vec<Residuals>);
    let mut text_keys: [TextKey; 2] = Default::default();
    let mut num_keys: [NumKey; 2] = Default::default();
    let mut regime = [Residuals::default(); 3];
    let (mut all, mut ge1) = (Residuals::default(), Residuals::default());
    for (i, r) in data.rows.iter().enumerate() {
        let (m, y) = (r.f, pred[i].f);
        all.add(m, y);
        if r.cx.abs() >= 0.01 {
            ge1.add(m, y);
        }
        regime[match reg[i] {
            "R1" => 0,
            "R2" => 1,
            _ => 2,
        }]
        .add(m, y);
        for (k, v) in [r.series.as_str(), r.condition.as_str()]
            .into_iter()
            .enumerate()
        {
            let (names, idx, acc) = &mut text_keys[k];
            let j = *idx.entry(v).or_insert_with(|| {
                names.push(v.to_string());
                acc.push(Residuals::default());
                names.len() - 1
            });
            acc[j].add(m, y);
        }
        for (k, v) in [r.v, r.fn_n / 1e3].into_iter().enumerate() {
            let (vals, idx, acc) = &mut num_keys[k];
            let j = *idx.entry(v.to_bits()).or_insert_with(|| {
                vals.push(v);
                acc.push(Residuals::default());
                vals.len() - 1
            });
            acc[j].add(m, y);
        }
    }
    for (k, by) in ["series", "condition"].into_iter().enumerate() {
        let (names, _, acc) = &text_keys[k];
        for (n, a) in names.iter().zip(acc) {
            groups.push(group_stat(a, by, n.clone()));
        }
    }
    for (k, by) in ["v_mps", "fn_kN"].into_iter().enumerate() {
        let (vals, _, acc) = &num_keys[k];
        for (v, a) in vals.iter().zip(acc) {
            groups.push(group_stat(a, by, format!("{v}")));
        }
    }
    for (k, rg) in ["R1", "R2", "R3"].into_iter().enumerate() {
        if regime[k].n > 0 {
            groups.push(group_stat(&regime[k], "regime", rg.into()));
        }
    }
    Comparison {
        cv_rmse_pct: all.cv_rmse_pct(),
        cv_rmse_pct_cx_ge_1pct: ge1.cv_rmse_pct(),
        n: data.rows.len(),
        groups,
    }
}
