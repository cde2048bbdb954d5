//! Diagnosis: which physical effect is missing? Residual correlations, then each catalogue effect added, refitted and judged on held-out groups.
//!
//! 1. Residuals of the configuration (as given) against every variable: creepage, slip
//!    velocity, frictional power, model temperature, speed, load, p0, dc_x/dt (time series)
//!    and every extra column; ranked by |Pearson r|.
//! 2. Held-out error: the rows are split into folds by curves of speed x load where the
//!    file crosses them (each fold's training rows then have every speed and every load),
//!    else by speed (or load, or series, whichever has at least two values);
//!    for each fold the free parameters are fitted on the other folds and the fold is
//!    predicted. The baseline is the configuration with its default
//!    free parameters ([`crate::fit::default_free`]); each candidate is the configuration
//!    plus one catalogue effect it lacks, with that effect's parameters freed as well.
//! 3. Candidates are ranked by held-out CV(RMSE). A missing effect is claimed only when the
//!    best candidate lowers the held-out error by at least `CLAIM_FRACTION` of the baseline.
//! 4. The best model is compared with the noise of the data ([`crate::noise`]), and the
//!    search of formula forms ([`crate::search`]) looks for a factor of one variable on a
//!    material function that no catalogue effect has; it proposes one only when it lowers
//!    the held-out error by a fraction of the noise level, with per-row evidence.
//!
//! Without an explicit grid the model runs on a cheaper grid where the noise allows it
//! ([`loop_config`]).

use crate::evaluate::{predict_warned, Memo, ModelWarning};
use crate::fit::{default_free, FitOptions, FitResult, FreeParam};
pub use crate::heldout::CLAIM_FRACTION;
use crate::heldout::{fold_count, folds, heldout, heldout_and_fit_all};
use crate::measure::Dataset;
pub use crate::residuals::{correlations, Correlation};
use crate::stats::cv_rmse_pct;
use creep_core::config::{Config, ModelKind};
use creep_core::effects::{self, Effect, EffectInfo};
use creep_core::error::Result;
use creep_core::params::P;
use creep_core::Modifier;

/// A held-out CV(RMSE) up to this many times the noise level counts as at the noise: a model
/// with nothing missing scores the noise plus what fitting on the other folds adds.
pub const AT_NOISE: f64 = 1.5;

/// A proposed form whose factor spans more than this over the file's rows (largest over
/// smallest) is said to be more likely a stand-in than a property of the layer: the hidden
/// effects of the tests span 1.3-2-fold, while a creepage offset of 0.05 % that the search
/// took up as L_e spanned 280-fold.
pub const FACTOR_SPAN: f64 = 10.0;

/// |r| from which an extra column counts as showing strong residual structure.
pub const STRONG: f64 = 0.3;

/// One tried effect.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Candidate {
    /// Effect name (catalogue name).
    pub effect: String,
    /// Held-out CV(RMSE), %.
    pub heldout_cv_rmse_pct: f64,
    /// In-sample CV(RMSE) after fitting on all rows, %.
    pub fitted_cv_rmse_pct: f64,
    /// Parameters freed.
    pub free: Vec<String>,
    /// Physical description and the evidence.
    pub explanation: String,
}

/// The diagnosis.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Diagnosis {
    /// CV(RMSE) of the configuration as given, %.
    pub baseline_cv_rmse_pct: f64,
    /// Held-out CV(RMSE) of the configuration with its own parameters refitted, %.
    pub baseline_heldout_cv_rmse_pct: f64,
    /// Grouping used for the folds.
    pub folds_by: String,
    /// Number of folds.
    pub folds: usize,
    /// Candidates, best (lowest held-out error) first.
    pub candidates: Vec<Candidate>,
    /// Residual correlations, strongest first.
    pub correlations: Vec<Correlation>,
    /// The effect claimed missing, if any.
    pub missing_effect: Option<String>,
    /// One-paragraph verdict in words.
    pub verdict: String,
    /// True when every catalogue effect that applies to the data (Coulomb aside; the
    /// wheel-slide effect only for rows with |1 + c_x| < 0.5; the transient and
    /// elastic-unloading effects only for time series) is already in the configuration.
    pub catalogue_all_on: bool,
    /// Noise level of the measured traction coefficient, estimated from the data alone
    /// ([`crate::noise::estimate`]); `None` when the file has neither repeats nor curves of
    /// five points.
    pub noise: Option<crate::noise::Noise>,
    /// The best model's held-out CV(RMSE), %: the best candidate's, or the configuration's as
    /// given when no candidate does better.
    pub best_heldout_cv_rmse_pct: f64,
    /// The best model: a candidate's name, or "the configuration as given".
    pub best_model: String,
    /// The best held-out CV(RMSE) over the noise level's CV(RMSE) (`None` without an estimate).
    pub times_noise: Option<f64>,
    /// Whether the best model is at the noise level (`times_noise` <= [`AT_NOISE`]): `false`
    /// means something is still missing.
    pub at_noise: Option<bool>,
    /// The search of formula-effect forms, run when the best model is not at the noise level
    /// ([`crate::search`]); `None` when it did not run.
    pub search: Option<crate::search::Search>,
    /// Warnings the model raised for the rows under the configuration as given (wheel slide,
    /// Péclet condition, ...), counted per series.
    pub warnings: Vec<ModelWarning>,
    /// Where the diagnosis ran the model on another grid than the configuration's, which and
    /// why ([`loop_config`]); `None`: on the configuration's.
    pub model_grid: Option<String>,
}

/// The first sentence of a description (a ". " after "Eq", "Sec" or "Fig" does not end it).
fn first_sentence(text: &str) -> &str {
    let mut from = 0;
    while let Some(i) = text[from..].find(". ") {
        let end = from + i;
        let before = &text[..end];
        if !(before.ends_with("Eq")
            || before.ends_with("Sec")
            || before.ends_with("Fig")
            || before.ends_with("Tab"))
        {
            return &text[..end];
        }
        from = end + 2;
    }
    text.trim_end_matches('.')
}

/// Convergence tolerance of the diagnosis' fits ([`FitOptions::tolerance`]).
///
/// The solver's default (30 machine epsilons) spends about half of the diagnosis' model
/// evaluations on the last digits of parameters that the report shows to two decimals of a
/// percent at most. At 1e-7 every held-out and fitted CV(RMSE) of the worked example
/// (examples/measurements/humid.csv with dry.json) stays within 1e-3 percentage points of
/// the default's (test `the_looser_fit_tolerance_changes_no_printed_figure`); 1e-6 moved one
/// candidate's by 2.5e-3 on a 10 x 5 grid (docs/history.md).
pub const FIT_TOLERANCE: f64 = 1e-7;

/// How a diagnosis runs.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Worker threads (the result does not depend on them).
    pub threads: usize,
    /// Convergence tolerance of the fits (`None`: the solver's default, as
    /// [`crate::fit::fit`]); [`FIT_TOLERANCE`] by default.
    pub fit_tolerance: Option<f64>,
    /// Time bound of the diagnosis, s from its start, which the search of formula forms
    /// keeps ([`crate::search::SEARCH_SECONDS`]; 0: no search).
    pub search_seconds: f64,
    /// Run the model on a cheaper grid than the configuration's where the noise of the data
    /// allows it ([`loop_config`]); `false` keeps the configuration's grid and scheme.
    pub loop_grid: bool,
}

impl Options {
    /// The defaults on `threads` threads.
    pub fn new(threads: usize) -> Self {
        Options {
            threads,
            fit_tolerance: Some(FIT_TOLERANCE),
            search_seconds: crate::search::SEARCH_SECONDS,
            loop_grid: true,
        }
    }
}

/// Runs the diagnosis with the default [`Options`]. `progress` receives a short text per stage.
pub fn diagnose(
    cfg: &Config,
    data: &Dataset,
    threads: usize,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Diagnosis> {
    diagnose_opts(cfg, data, &Options::new(threads), progress)
}

/// [`diagnose`] with the fits' convergence tolerance (`None`: the solver's default, as
/// [`crate::fit::fit`]).
pub fn diagnose_with(
    cfg: &Config,
    data: &Dataset,
    threads: usize,
    fit_tolerance: Option<f64>,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Diagnosis> {
    let o = Options {
        fit_tolerance,
        ..Options::new(threads)
    };
    diagnose_opts(cfg, data, &o, progress)
}

/// The grids the diagnosis may run instead of a costlier configuration grid, cheapest first:
/// (cells per strip, strips, largest steady error of f against 640 x 168 cells over
/// c_x = 0.2-30 % for dry, table4.1 and wet at 5-30 m/s, %), all with the higher-order rules
/// (`bash scripts/bench.sh --only steady-grid`, second table). With [`LOOP_ERROR_OF_NOISE`]
/// as the bound, a file's grid follows its noise without a jump in cost: 20 x 5 from a noise
/// level of 3.7 %, 40 x 5 from 1.8 %, 40 x 9 from 1.1 %, 80 x 7 from 0.73 %.
pub const LOOP_GRIDS: [(usize, usize, f64); 4] = [
    (20, 5, LOOP_ERR_20X5),
    (40, 5, LOOP_ERR_40X5),
    (40, 9, LOOP_ERR_40X9),
    (80, 7, LOOP_ERR_80X7),
];
const LOOP_ERR_20X5: f64 = 1.12;
const LOOP_ERR_40X5: f64 = 0.54;
const LOOP_ERR_40X9: f64 = 0.33;
const LOOP_ERR_80X7: f64 = 0.22;

/// A loop grid is used when its error is at most this fraction of the noise level: it then
/// adds at most 4.4 % to the noise in quadrature, and a form that absorbed the whole grid
/// error would gain at most 0.044 noise levels, a third of the least gain a proposal needs
/// ([`crate::search::GAIN_OF_NOISE`]).
pub const LOOP_ERROR_OF_NOISE: f64 = 0.3;

/// Relative cost of a grid: its cells, twice for the higher-order rules.
fn grid_cost(cfg: &Config) -> usize {
    let k = if cfg.scheme == creep_core::engine::Scheme::CellsHigher {
        2
    } else {
        1
    };
    cfg.grid.nx * cfg.grid.ny * k
}

/// The configuration on the cheapest loop grid ([`LOOP_GRIDS`]) whose error is at most
/// [`LOOP_ERROR_OF_NOISE`] of the noise level `noise_cv` (%), when that grid costs less than
/// the configuration's own; `None` otherwise (and for FASTSIM and Polach, whose steady runs
/// are cheap). With the reason, in words.
pub fn loop_config(cfg: &Config, noise_cv: Option<f64>) -> Option<(Config, String)> {
    if cfg.model == ModelKind::Polach || cfg.has(Effect::Coulomb) {
        return None;
    }
    let noise = noise_cv?;
    let own = grid_cost(cfg);
    LOOP_GRIDS.iter().find_map(|&(nx, ny, err)| {
        let mut c = cfg.clone();
        c.grid = creep_core::config::Grid { nx, ny };
        c.scheme = creep_core::engine::Scheme::CellsHigher;
        (err <= LOOP_ERROR_OF_NOISE * noise && grid_cost(&c) < own).then(|| {
            let why = format!(
                "the model runs on {nx}x{ny} cells-ho instead of the configuration's {}x{} {}: {:.1} times cheaper, within {err} % of the converged steady curves, {LOOP_ERROR_OF_NOISE} times the noise level ({noise:.2} %) or less; --grid keeps a grid of your choice",
                cfg.grid.nx,
                cfg.grid.ny,
                cfg.scheme.name(),
                own as f64 / grid_cost(&c) as f64
            );
            (c, why)
        })
    })
}

/// Runs the diagnosis with options `o`.
pub fn diagnose_opts(
    cfg: &Config,
    data: &Dataset,
    o: &Options,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Diagnosis> {
    let started = std::time::Instant::now();
    let noise = crate::noise::estimate(data);
    let looped = if o.loop_grid {
        loop_config(cfg, noise.as_ref().map(|n| n.cv_rmse_pct))
    } else {
        None
    };
    let (run_cfg, model_grid) = match &looped {
        Some((c, why)) => (c, Some(why.clone())),
        None => (cfg, None),
    };
    let mut d = run(run_cfg, data, noise, o, started, progress)?;
    d.model_grid = model_grid;
    if looped.is_some() {
        // the proposal keeps the user's grid and scheme
        if let Some(j) = d.search.as_mut().and_then(|s| s.proposed_config.as_mut()) {
            j["grid"] = serde_json::json!(cfg.grid);
            j["scheme"] = serde_json::json!(cfg.scheme.name());
        }
    }
    Ok(d)
}

/// What every candidate of one diagnosis is judged against: the data, the folds, the
/// configuration as given with its default free parameters and their held-out error.
struct Baseline<'a> {
    cfg: &'a Config,
    data: &'a Dataset,
    threads: usize,
    opts: &'a FitOptions<'a>,
    corr: &'a [Correlation],
    labels: &'a [usize],
    folds_by: &'a str,
    free: &'a [FreeParam],
    heldout: f64,
}

/// A candidate's report entry from its held-out CV(RMSE) (%) and its fit on all rows.
type Entry = Box<dyn FnOnce(f64, &FitResult) -> Candidate>;

/// A candidate before its fits: its configuration and free parameters, the stage shown while
/// it runs, and its report entry.
struct Pending {
    cfg: Config,
    free: Vec<FreeParam>,
    stage: String,
    entry: Entry,
}

impl Baseline<'_> {
    /// The candidates scored: every fit of every candidate side by side
    /// ([`heldout_and_fit_all`]), the same results as one candidate after the other; the
    /// first error in the candidates' order.
    fn score_all(
        &self,
        pending: Vec<Pending>,
        progress: &(dyn Fn(&str) + Sync),
    ) -> Result<Vec<Candidate>> {
        let items: Vec<(&Config, &[FreeParam])> = pending
            .iter()
            .map(|p| (&p.cfg, p.free.as_slice()))
            .collect();
        let stages: Vec<&str> = pending.iter().map(|p| p.stage.as_str()).collect();
        let results = heldout_and_fit_all(
            &items,
            self.data,
            self.labels,
            self.threads,
            self.opts,
            &|i| progress(&format!("refitting with {}", stages[i])),
        );
        drop(items);
        pending
            .into_iter()
            .zip(results)
            .map(|(p, r)| {
                let (h, fitted) = r?;
                Ok((p.entry)(h, &fitted))
            })
            .collect()
    }

    /// The baseline's free parameters with `more` added (each once).
    fn free_with(&self, more: impl IntoIterator<Item = P>) -> Vec<FreeParam> {
        let mut free = self.free.to_vec();
        for p in more {
            if !free.contains(&FreeParam::Builtin(p)) {
                free.push(FreeParam::Builtin(p));
            }
        }
        free
    }

    /// Each catalogue effect the configuration lacks and the data can show, added and
    /// refitted; and whether every effect that can act on these data is already on.
    fn catalogue(&self) -> Result<(Vec<Pending>, bool)> {
        let (cfg, data) = (self.cfg, self.data);
        let mut candidates = Vec::new();
        if cfg.model == ModelKind::Polach || cfg.has(Effect::Coulomb) {
            return Ok((candidates, false));
        }
        let has_series = data.rows.iter().any(|r| r.t.is_some());
        let sliding = data.rows.iter().any(|r| (1.0 + r.cx).abs() < 0.5);
        // where an effect applies is its catalogue row's (`applies`); one that cannot act on
        // these data is neither tried nor counted as off
        let applies = |i: &EffectInfo| i.applies.holds(cfg.effects, has_series, sliding);
        let all_on = effects::CATALOGUE
            .iter()
            .all(|i| cfg.has(i.effect) || !applies(i));
        for info in effects::CATALOGUE {
            let e = info.effect;
            if cfg.has(e) || !applies(info) {
                continue;
            }
            let mut c = cfg.clone();
            c.effects.insert(e);
            let free = self.free_with(info.fit.iter().copied());
            let evidence = self
                .corr
                .iter()
                .filter(|k| info.signature.contains(&k.variable.as_str()))
                .max_by(|a, b| a.r.abs().total_cmp(&b.r.abs()))
                .map(|k| format!("residual correlation with {} r = {:+.2}", k.variable, k.r))
                .unwrap_or_else(|| "no signature variable in the data".into());
            let first_sentence = first_sentence(info.description);
            let (folds_by, base_heldout) = (self.folds_by.to_string(), self.heldout);
            let names: Vec<String> = free.iter().map(|p| p.name(&c)).collect();
            candidates.push(Pending {
                cfg: c,
                free,
                stage: info.name.to_string(),
                entry: Box::new(move |h, fitted| Candidate {
                    effect: info.name.to_string(),
                    heldout_cv_rmse_pct: h,
                    fitted_cv_rmse_pct: fitted.cv_rmse_pct_after,
                    free: names,
                    explanation: format!(
                        "{first_sentence}. Evidence: {evidence}; adding it and refitting takes the held-out error (folds by {folds_by}) from {base_heldout:.2} % to {h:.2} %."
                    ),
                }),
            });
        }
        Ok((candidates, all_on))
    }

    /// Registered Rust effects the configuration lacks, whose data columns the file has, added
    /// and refitted; and those not tried for a missing column, in words.
    fn rust_effects(&self) -> Result<(Vec<Pending>, Vec<String>)> {
        let (cfg, data) = (self.cfg, self.data);
        let (mut candidates, mut untried) = (Vec::new(), Vec::new());
        if cfg.model == ModelKind::Polach {
            return Ok((candidates, untried));
        }
        for eff in creep_core::custom::catalogue() {
            if cfg.modifiers.iter().any(|u| u.name() == eff.name()) {
                continue;
            }
            if let Some(c) = eff
                .columns()
                .iter()
                .find(|c| !data.extra_names.iter().any(|n| n == *c))
            {
                untried.push(format!("{} (needs the column '{c}')", eff.name()));
                continue;
            }
            let mut c = cfg.clone();
            c.modifiers.push(creep_core::AnyModifier::Rust(
                creep_core::custom::CustomUse::by_name(eff.name())?,
            ));
            let mut free = self.free.to_vec();
            let e = c.modifiers.len() - 1;
            for (k, p) in eff.params().iter().enumerate() {
                // parameters whose bounds are a reference value (lower bound > 0) stay fixed
                if p.2 <= 0.0 {
                    free.push(FreeParam::Modifier {
                        effect: e,
                        param: k,
                    });
                }
            }
            let (folds_by, base_heldout) = (self.folds_by.to_string(), self.heldout);
            let names: Vec<String> = free.iter().map(|p| p.name(&c)).collect();
            candidates.push(Pending {
                cfg: c,
                free,
                stage: eff.name().to_string(),
                entry: Box::new(move |h, fitted| Candidate {
                    effect: format!("Rust effect {}", eff.name()),
                    heldout_cv_rmse_pct: h,
                    fitted_cv_rmse_pct: fitted.cv_rmse_pct_after,
                    free: names,
                    explanation: format!(
                        "{}. Adding this registered Rust effect and refitting takes the held-out error (folds by {folds_by}) from {base_heldout:.2} % to {h:.2} %.",
                        first_sentence(eff.description())
                    ),
                }),
            });
        }
        Ok((candidates, untried))
    }
}

/// The diagnosis of `cfg` (the grid already chosen) with the data's noise estimate `noise`.
fn run(
    cfg: &Config,
    data: &Dataset,
    noise: Option<crate::noise::Noise>,
    o: &Options,
    started: std::time::Instant,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Diagnosis> {
    let (threads, search_seconds) = (o.threads, o.search_seconds);
    progress("fitting the configuration as given on the folds");
    // every fit below is judged by its fitted values alone (no standard errors), and repeated
    // model evaluations (start points, best points, rows shared by folds) are looked up
    let memo = Memo::new();
    let opts = FitOptions {
        skip_uncertainties: true,
        memo: Some(&memo),
        tolerance: o.fit_tolerance,
    };
    let (pred, warnings) = predict_warned(cfg, data, threads)?;
    let meas: Vec<f64> = data.rows.iter().map(|r| r.f).collect();
    let baseline_cv = cv_rmse_pct(&meas, &pred.iter().map(|p| p.f).collect::<Vec<_>>());
    let corr = correlations(data, &pred);
    let (folds_by, labels) = folds(data);
    let nfolds = fold_count(&labels);
    let base_free: Vec<FreeParam> = default_free(cfg)
        .into_iter()
        .map(FreeParam::Builtin)
        .collect();
    let base_heldout = heldout(cfg, data, &labels, &base_free, threads, &opts)?;
    let base = Baseline {
        cfg,
        data,
        threads,
        opts: &opts,
        corr: &corr,
        labels: &labels,
        folds_by: &folds_by,
        free: &base_free,
        heldout: base_heldout,
    };
    // every candidate's fits side by side (the same results as one after the other)
    let (mut pending, catalogue_all_on) = base.catalogue()?;
    let (rust, untried) = base.rust_effects()?;
    pending.extend(rust);
    let mut candidates = base.score_all(pending, progress)?;
    candidates.sort_by(|a, b| a.heldout_cv_rmse_pct.total_cmp(&b.heldout_cv_rmse_pct));
    let missing = candidates
        .first()
        .filter(|c| c.heldout_cv_rmse_pct < (1.0 - CLAIM_FRACTION) * base_heldout)
        .map(|c| c.effect.clone());
    let verdict = claim_words(
        data,
        &candidates,
        &corr,
        missing.as_deref(),
        catalogue_all_on,
        &untried,
        base_heldout,
    );
    // the best model against the noise of the data
    let (best_model, best_heldout) = match candidates.first() {
        Some(c) if c.heldout_cv_rmse_pct < base_heldout => {
            (c.effect.clone(), c.heldout_cv_rmse_pct)
        }
        _ => ("the configuration as given".to_string(), base_heldout),
    };
    let times_noise = noise
        .as_ref()
        .filter(|n| n.cv_rmse_pct > 0.0)
        .map(|n| best_heldout / n.cv_rmse_pct);
    let at_noise = times_noise.map(|t| t <= AT_NOISE);
    let mut verdict = verdict
        + &noise_words(
            noise.as_ref(),
            times_noise,
            &best_model,
            best_heldout,
            data.rows.len(),
        );
    // the search of formula forms runs at the noise too: the estimate of a 150-row file is off the true noise
    // by up to 20-30 % either way, and a curve bent by the missing effect itself reads as
    // noise; its proposal rule, a held-out gain against the noise, decides
    let search = if cfg.model != ModelKind::Polach && search_seconds > 0.0 {
        let s = crate::search::search(
            cfg,
            data,
            &pred,
            &labels,
            &base_free,
            threads,
            &opts,
            best_heldout,
            base_heldout,
            noise.as_ref().map(|n| n.cv_rmse_pct),
            started + std::time::Duration::from_secs_f64(search_seconds.min(1e9)),
            progress,
        )?;
        verdict += &search_words(
            &s,
            noise.as_ref(),
            best_heldout,
            base_heldout,
            search_seconds,
            data.rows.len(),
        );
        Some(s)
    } else {
        None
    };
    Ok(Diagnosis {
        baseline_cv_rmse_pct: baseline_cv,
        baseline_heldout_cv_rmse_pct: base_heldout,
        folds_by,
        folds: nfolds,
        candidates,
        correlations: corr,
        missing_effect: missing,
        verdict,
        catalogue_all_on,
        noise,
        best_heldout_cv_rmse_pct: best_heldout,
        best_model,
        times_noise,
        at_noise,
        search,
        warnings,
        model_grid: None,
    })
}

/// The verdict's first part: what was not tried, and the missing effect claimed or why none is.
fn claim_words(
    data: &Dataset,
    candidates: &[Candidate],
    corr: &[Correlation],
    missing: Option<&str>,
    catalogue_all_on: bool,
    untried: &[String],
    base_heldout: f64,
) -> String {
    // the strongest correlation with something the user can act on: a data column or an
    // operating variable, not a model output
    let strongest_extra = corr.iter().find(|c| data.extra_names.contains(&c.variable));
    let mut preface = String::new();
    if catalogue_all_on {
        preface += "Every catalogue effect is already in the configuration; ";
        preface += if candidates.is_empty() {
            "there is nothing to try, so the residual correlations are the evidence. "
        } else {
            "only the candidates below were tried. "
        };
    }
    if !untried.is_empty() {
        preface += &format!("Not tried: {}. ", untried.join(", "));
    }
    let hint = match strongest_extra {
        Some(c) if c.r.abs() >= STRONG => format!(
            " The data column '{}' follows the residuals (r = {:+.2}): try a formula effect on it.",
            c.variable, c.r
        ),
        _ => String::new(),
    };
    let verdict = match missing {
        Some(m) => format!(
            "Missing effect: {m}. With it the held-out CV(RMSE) falls from {base_heldout:.2} % to {:.2} %; the strongest residual correlation of the configuration as given is with {} (r = {:+.2}).",
            candidates[0].heldout_cv_rmse_pct, corr[0].variable, corr[0].r
        ),
        None if candidates.is_empty() => format!(
            "No candidate to try. Strongest residual correlation: {} (r = {:+.2}).{hint}",
            corr.first().map(|c| c.variable.as_str()).unwrap_or("-"),
            corr.first().map(|c| c.r).unwrap_or(0.0)
        ),
        None => format!(
            "No missing effect claimed: no candidate lowers the held-out CV(RMSE) ({base_heldout:.2} %) by {:.0} % or more. Strongest residual correlation: {} (r = {:+.2}).{hint}",
            CLAIM_FRACTION * 100.0,
            corr.first().map(|c| c.variable.as_str()).unwrap_or("-"),
            corr.first().map(|c| c.r).unwrap_or(0.0)
        ),
    };
    format!("{preface}{verdict}")
}

/// The verdict's part on the best model against the noise level of the data.
fn noise_words(
    noise: Option<&crate::noise::Noise>,
    times_noise: Option<f64>,
    best_model: &str,
    best_heldout: f64,
    rows: usize,
) -> String {
    match (noise, times_noise) {
        (Some(n), Some(t)) if t <= AT_NOISE => format!(
            " The best model ({best_model}, held-out {best_heldout:.2} %) is at the noise level of the data within what fitting on the other folds adds ({t:.1} times it: about {:.2} %, sd {:.4} of F_x/F_N, from {}). The estimate can be off by a fifth or more, and a weak effect may hide there: the search of formula forms looks all the same, and proposes only a form that lowers the held-out error by {:.2} times the noise level.",
            n.cv_rmse_pct, n.sd_f, n.method, crate::search::gain_of_noise(rows)
        ),
        (Some(n), Some(t)) => format!(
            " The best model ({best_model}, held-out {best_heldout:.2} %) is still {t:.1} times the noise level of the data (about {:.2} %, sd {:.4} of F_x/F_N, from {}): something is still missing. Besides data columns, a formula effect can use the operating point (v_mps, fn_kN, cx, cy, spin_per_m, t_bulk_C) and the local state (p_GPa, T_C, u_mm, slip_mps) to scale tau_c1, tau_c2, both strengths together, L_e, L_p or mu (docs/measurements.md).",
            n.cv_rmse_pct, n.sd_f, n.method
        ),
        _ => " The noise level of the data could not be estimated (no repeated operating points, no curve of five points or more): whether something is still missing cannot be said.".to_string(),
    }
}

/// The verdict's part on the search of formula forms: how far it got, what it proposes, how
/// far above the noise that leaves the model and what to try next.
fn search_words(
    s: &crate::search::Search,
    noise: Option<&crate::noise::Noise>,
    best_heldout: f64,
    base_heldout: f64,
    search_seconds: f64,
    rows: usize,
) -> String {
    let c = &s.cost;
    let mut bound = String::new();
    if c.shortlisted < crate::search::SHORTLIST.min(s.total) {
        bound += &format!(
            "; {} of the {} shortlisted fitted before the time bound of {search_seconds:.0} s",
            c.shortlisted,
            crate::search::SHORTLIST
        );
    }
    if c.finalists_cut > 0 {
        bound += &format!(
            "; {} finalist(s) left out for the time bound of {search_seconds:.0} s (a finer look: --threads on more cores, or a coarser --grid)",
            c.finalists_cut
        );
    }
    // the best screened form and the best finalist are fitted however long they take
    if s.past_bound_s >= 1.0 {
        bound += &format!(
            "; it ended {:.0} s past the time bound of {search_seconds:.0} s, fitting the forms it always fits (a busy machine, or a fine grid)",
            s.past_bound_s
        );
    }
    let head = format!(
        " Search of formula forms: {} of {} screened on the factor each row needs, the best {} refitted on the folds with their own parameters and the target's level, the best {} of those with every free parameter, in {:.0} s{bound}.",
        s.tried, s.total, c.shortlisted, c.finalists, s.seconds
    );
    let times = |h: f64| {
        noise
            .filter(|n| n.cv_rmse_pct > 0.0)
            .map(|n| h / n.cv_rmse_pct)
    };
    head + &match (&s.proposed, s.forms.first()) {
        (Some(f), _) => {
            let next = match times(f.heldout_cv_rmse_pct) {
                Some(t) if t <= AT_NOISE => format!(
                    " That is {t:.1} times the noise level: at the noise, nothing more is missing that these data can show."
                ),
                Some(t) => {
                    let others: Vec<String> = s
                        .forms
                        .iter()
                        .filter(|g| g.variable != f.variable)
                        .take(2)
                        .map(|g| format!("{} x {} in {}", g.target, g.shape, g.variable))
                        .collect();
                    format!(
                        " That is still {t:.1} times the noise level: something more is missing. Next: run ecf diagnose again on the proposed configuration (--config with the file --out writes), which searches for a second form on top of this one{}; or look at the residuals over each variable (ecf compare --plots).",
                        if others.is_empty() {
                            String::new()
                        } else {
                            format!(" (the next variables in the ranking: {})", others.join(", "))
                        }
                    )
                }
                None => " The noise level could not be estimated: whether more is missing cannot be said.".into(),
            };
            // what ecf fit would say of the proposal's fit on all rows: a parameter far outside
            // its plausible range stands in for something else
            let mut warned = if s.proposed_warnings.is_empty() {
                String::new()
            } else {
                format!(
                    " Its fit on all rows warns: {}",
                    s.proposed_warnings.join("; ")
                )
            };
            let [lo, hi] = f.factor_range;
            if lo > 0.0 && hi / lo > FACTOR_SPAN {
                warned += &format!(
                    " Its factor spans {lo:.3} to {hi:.3} over the file's rows ({:.0}-fold): a change that large in {} is more likely a stand-in for something else, such as an offset or a gain of the measured creepage or force, than a property of the layer.",
                    hi / lo,
                    f.target
                );
            }
            format!(
                " Proposed: {} x {} in {} (factor {}), {}: the held-out CV(RMSE) falls from {best_heldout:.2} % to {:.2} % ({:.0} % lower).{next} The configuration with it, fitted on all rows, is in proposed_config (ecf diagnose --out FILE writes it; ecf fit and the FMU take it as is).{warned}",
                f.target,
                f.shape,
                f.variable,
                f.factor,
                f.params_text(),
                f.heldout_cv_rmse_pct,
                100.0 * (1.0 - f.heldout_cv_rmse_pct / best_heldout)
            )
        }
        (None, Some(f)) => format!(
            " No form is proposed: the best ({} x {} in {}, held-out {:.2} % against {best_heldout:.2} %) does not lower the configuration's held-out error ({base_heldout:.2} %) to {:.2} % or below ({}) with per-row evidence of {} standard errors (it has {:.1}). {}",
            f.target,
            f.shape,
            f.variable,
            f.heldout_cv_rmse_pct,
            crate::search::proposal_bound(base_heldout, noise.map(|n| n.cv_rmse_pct), rows),
            match noise {
                Some(_) => format!(
                    "{:.0} % of the noise level below it",
                    crate::search::gain_of_noise(rows) * 100.0
                ),
                None => format!("{:.0} % below it", CLAIM_FRACTION * 100.0),
            },
            crate::search::EVIDENCE,
            f.evidence_z,
            match times(best_heldout) {
                Some(t) if t > AT_NOISE => "What is missing is then not a factor of one variable on one material function: try two variables together (a formula effect of your own), or an effect on another quantity.",
                _ => "",
            }
        ),
        (None, None) => " No form could be evaluated: no form is proposed.".to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_verdict_carries_the_warnings_of_the_proposals_fit() {
        let form = crate::search::Form {
            target: "tau_c2".into(),
            variable: "fn_kN".into(),
            shape: "power".into(),
            factor: "(fn_kN / 100)^k".into(),
            screen_cv_rmse_pct: 8.5,
            shortlist_cv_rmse_pct: 8.2,
            heldout_cv_rmse_pct: 8.09,
            evidence_z: 6.0,
            params: vec![crate::search::FormParam {
                name: "k".into(),
                value: -0.3,
                stderr: 0.01,
            }],
            fitted_cv_rmse_pct: 7.9,
            factor_range: [0.8, 1.2],
        };
        let warning = "tau_c2_0 = 1.29e11 Pa is outside its plausible physical range";
        let mut s = crate::search::Search {
            forms: vec![form.clone()],
            tried: 1,
            total: 1,
            seconds: 1.0,
            past_bound_s: 0.0,
            cost: crate::search::SearchCost {
                shortlisted: 1,
                finalists: 1,
                ..Default::default()
            },
            proposed: Some(form),
            proposed_config: None,
            proposed_warnings: vec![warning.into()],
        };
        let noise = crate::noise::Noise {
            sd_f: 0.006,
            cv_rmse_pct: 2.0,
            method: "test".into(),
            dof: 100,
        };
        let words = |s: &crate::search::Search| search_words(s, Some(&noise), 9.7, 9.7, 50.0, 120);
        assert!(words(&s).contains(&format!("Its fit on all rows warns: {warning}")));
        s.proposed_warnings.clear();
        assert!(!words(&s).contains("warns"));
        assert!(!words(&s).contains("stand-in"));
        // a factor from 0.22 to 62 over the file (an offset of c_x taken up as L_e)
        if let Some(f) = s.proposed.as_mut() {
            f.factor_range = [0.22, 62.0];
        }
        assert!(words(&s).contains("(282-fold)"), "{}", words(&s));
        // a search that ended past its time bound says so
        assert!(!words(&s).contains("past the time bound"));
        s.past_bound_s = 41.0;
        assert!(words(&s).contains("it ended 41 s past the time bound of 50 s"));
    }

    /// The grid chosen for a preset at a noise level (%): `None` keeps the preset's 80 x 21.
    fn chosen(noise: f64) -> Option<(usize, usize)> {
        let cfg = Config::preset("dry").unwrap();
        loop_config(&cfg, Some(noise)).map(|(c, _)| (c.grid.nx, c.grid.ny))
    }

    #[test]
    fn the_loop_grid_follows_the_noise_level_step_by_step() {
        assert_eq!(chosen(5.0), Some((20, 5)));
        assert_eq!(chosen(3.0), Some((40, 5)));
        // a noise level between 40 x 5's and 80 x 21's bounds takes an intermediate grid,
        // not the preset's grid at 8 times 40 x 5's cost
        assert_eq!(chosen(1.5), Some((40, 9)));
        assert_eq!(chosen(0.8), Some((80, 7)));
        assert_eq!(chosen(0.5), None);
        // every grid's error is within the bound's fraction of the noise where it is chosen
        for noise in [0.75, 1.1, 1.8, 3.7, 10.0] {
            let (nx, ny) = chosen(noise).unwrap();
            let err = LOOP_GRIDS
                .iter()
                .find(|g| (g.0, g.1) == (nx, ny))
                .unwrap()
                .2;
            assert!(err <= LOOP_ERROR_OF_NOISE * noise, "{nx}x{ny} at {noise} %");
        }
        // cheapest first, and each grid more accurate than the one before
        for w in LOOP_GRIDS.windows(2) {
            assert!(w[0].0 * w[0].1 < w[1].0 * w[1].1 && w[0].2 > w[1].2);
        }
    }
}
