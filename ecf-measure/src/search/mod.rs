//! Search of formula-effect forms when no catalogue effect brings the held-out error to the noise: the factor each row needs, regressed on every variable and shape, then the best forms fitted with the full model on the diagnosis' folds.
//!
//! A form scales a target group (one layer strength, both strengths by one factor, L_p, L_e
//! where the layer's elasticity is on; mu for a Coulomb model) by a factor of one variable
//! ([`shapes::Shape`]: linear, reciprocal, exponential, power; saturating and a logistic step
//! with two parameters). The variables are the operating point (`v_mps`, `fn_kN`,
//! `abs(cx)`), the local state the formula sees (`slip_mps`, `p_GPa`, `T_C`; their data
//! values are the model's slip speed, maximum pressure and maximum temperature of the row)
//! and every extra column; a variable constant over the data is passed over.
//!
//! Four stages, each on the diagnosis' folds (no fold's rows shape its own prediction):
//! 1. **The factor each row needs** ([`inverse`]): for every target group, the log-factor
//!    that brings the model onto each row and the traction coefficient's slope in it, from
//!    two starting points: every fold's configuration with its free parameters fitted on the
//!    other folds, and the configuration as given (which shows an effect undisguised where
//!    the fits bend a free parameter to stand in for it).
//! 2. **Screening by regression** ([`shapes::fit`]): every form (group x variable x shape) is
//!    fitted to the other folds' log-factors, weighted by the slopes, with a free level, and
//!    scores the fold's rows through the slopes, from each starting point. No model runs:
//!    every form is screened.
//! 3. **The shortlist**: the best [`SHORTLIST`] screened forms (at most two shapes of one
//!    target and variable, three forms of one variable) fitted with the full model on each
//!    fold's training rows, the form's parameters and the target's level free (the other
//!    free parameters stay at the starting point's values), started where the screening
//!    ended.
//! 4. **The finalists**: the shortlist's best [`FINALISTS`] (and its best form with fewer
//!    parameters) fitted on the folds and on all rows with every free parameter of the
//!    diagnosis plus their own, as a catalogue effect is scored, and ranked by that held-out
//!    CV(RMSE). A form with two parameters ranks above one with one only when it earns them:
//!    when its per-row held-out absolute errors are lower by more than one standard error of
//!    the paired difference.
//!
//! A form is proposed when it beats the best model so far, lowers the configuration's own
//! held-out CV(RMSE) by [`gain_of_noise`] of the noise level (by
//! [`crate::heldout::CLAIM_FRACTION`] of its own when the noise cannot be estimated), and its
//! per-row held-out absolute errors are lower than the configuration's by at least
//! [`EVIDENCE`] standard errors of the paired difference.

mod fits;
pub(crate) mod inverse;
pub(crate) mod shapes;

use crate::evaluate::Prediction;
use crate::fit::{FitOptions, FreeParam};
use crate::heldout::{fold_count, side_by_side, subset, CLAIM_FRACTION};
use crate::measure::Dataset;
use crate::stats::mean_sd;
use creep_core::config::Config;
use creep_core::effects::Effect;
use creep_core::error::Result;
use creep_core::formula::Target;
use creep_core::params::P;
use inverse::Inverse;
use shapes::{sig4, Shape, Var};

/// Time bound of the diagnosis, s from its start: every form is screened; the shortlist's
/// fits start a new form only while the time left holds it and the finalists' expected cost
/// ([`FINALIST_COST`]), and a further finalist only while the time left holds the last
/// one's (the best screened form and the best finalist are always fitted).
pub const SEARCH_SECONDS: f64 = 50.0;

/// A finalist's fits cost about this many shortlisted forms' (their model evaluations were
/// 1.8-4.3 times one shortlisted form's in the sweeps of `scripts/loop-sweep.sh`).
pub const FINALIST_COST: f64 = 3.0;

/// How many of the best screened forms are fitted with the full model on the folds (with
/// their own parameters and the target's level).
pub const SHORTLIST: usize = 6;

pub use fits::{FINALISTS, FIT_TOLERANCE};

/// Standard errors of the paired per-row difference of held-out absolute errors by which a
/// proposed form must beat the configuration as given.
pub const EVIDENCE: f64 = 2.0;

/// Fraction of the noise level's CV(RMSE) by which a proposed form must lower the
/// configuration's own held-out CV(RMSE) on a file of [`GAIN_ROWS`] rows or more: a gain
/// that matters against the scatter of the data, whatever the starting error. On files with
/// nothing missing the configuration is already near the noise, where no form can gain this
/// much without luck.
pub const GAIN_OF_NOISE: f64 = 0.12;

/// Rows from which the required gain is [`GAIN_OF_NOISE`]; on fewer rows it grows as
/// sqrt(GAIN_ROWS / rows), as the scatter of a held-out difference of two fits does.
pub const GAIN_ROWS: usize = 150;

/// The fraction of the noise level a proposed form must gain on a file of `rows` rows:
/// [`GAIN_OF_NOISE`], times sqrt([`GAIN_ROWS`] / rows) on fewer rows (0.185 on 63).
pub fn gain_of_noise(rows: usize) -> f64 {
    GAIN_OF_NOISE * (GAIN_ROWS as f64 / rows.max(1) as f64).sqrt().max(1.0)
}

/// The held-out CV(RMSE) (%) a proposed form must reach at most on a file of `rows` rows:
/// [`gain_of_noise`] of the noise level `noise_cv` (%) below `base_heldout`, or
/// [`CLAIM_FRACTION`] below it when the noise is unknown.
pub fn proposal_bound(base_heldout: f64, noise_cv: Option<f64>, rows: usize) -> f64 {
    match noise_cv.filter(|n| *n > 0.0) {
        Some(n) => base_heldout - gain_of_noise(rows) * n,
        None => (1.0 - CLAIM_FRACTION) * base_heldout,
    }
}

/// A fitted parameter of a form.
#[derive(Clone, Debug, serde::Serialize)]
pub struct FormParam {
    /// Name in the formula (`k`; `a`, `b` or `c` for two-parameter shapes).
    pub name: String,
    /// Fitted value on all rows (NaN when the form was not fitted with the full model), -.
    pub value: f64,
    /// Its standard error, - (NaN when not fitted or at a bound).
    pub stderr: f64,
}

/// One formula form tried.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Form {
    /// Target scaled by the factor (`strengths` scales tau_c1 and tau_c2 together).
    pub target: String,
    /// Variable of the factor (a formula variable or a data column).
    pub variable: String,
    /// Shape: `linear`, `reciprocal`, `exp`, `power`, `saturating` or `step`.
    pub shape: String,
    /// The factor as written into the configuration.
    pub factor: String,
    /// The screening's held-out CV(RMSE) (regression on the needed factors), %.
    pub screen_cv_rmse_pct: f64,
    /// Held-out CV(RMSE) with the form's parameters and the target's level fitted on the
    /// folds, % (NaN for the forms not on the shortlist).
    pub shortlist_cv_rmse_pct: f64,
    /// Held-out CV(RMSE) with every free parameter fitted on the folds, as a catalogue
    /// effect's, % (NaN for the forms not among the finalists).
    pub heldout_cv_rmse_pct: f64,
    /// Per-row evidence against the configuration as given: the mean paired difference of
    /// held-out absolute errors over its standard error (NaN for the forms not among the
    /// finalists).
    pub evidence_z: f64,
    /// The form's parameters, fitted on all rows.
    pub params: Vec<FormParam>,
    /// In-sample CV(RMSE) on all rows, % (NaN when not fitted).
    pub fitted_cv_rmse_pct: f64,
    /// The smallest and the largest factor over the file's rows with the parameters fitted
    /// on all rows, - (NaN when not fitted).
    pub factor_range: [f64; 2],
}

impl Form {
    /// The fitted parameters in words: `k = +0.3493 ± 0.0085`.
    pub fn params_text(&self) -> String {
        self.params
            .iter()
            .map(|p| {
                if p.value.is_nan() {
                    format!("{} not fitted", p.name)
                } else if p.stderr.is_finite() {
                    format!("{} = {:+.4} ± {:.4}", p.name, p.value, p.stderr)
                } else {
                    format!("{} = {:+.4}", p.name, p.value)
                }
            })
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// Where the search's time went: wall seconds and steady model evaluations (one row at one
/// configuration) per stage.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct SearchCost {
    /// Seconds in the fits of the configuration on each fold's training rows.
    pub fold_fits_s: f64,
    /// Model evaluations in them (those the diagnosis' own held-out fits had made are looked
    /// up, not counted).
    pub fold_fit_evaluations: usize,
    /// Seconds in the solves for each row's needed factor.
    pub inverse_s: f64,
    /// Model evaluations in them.
    pub inverse_evaluations: usize,
    /// Seconds in the screening regressions (no model runs).
    pub screen_s: f64,
    /// Seconds in the shortlist's fits on the folds (the form and the target's level).
    pub shortlist_s: f64,
    /// Model evaluations in them.
    pub shortlist_evaluations: usize,
    /// Forms of the shortlist fitted within the time bound.
    pub shortlisted: usize,
    /// Seconds in the finalists' fits with every free parameter.
    pub final_s: f64,
    /// Model evaluations in them.
    pub final_evaluations: usize,
    /// Finalists fitted.
    pub finalists: usize,
    /// Finalists not fitted for the time bound.
    pub finalists_cut: usize,
    /// Worker threads.
    pub threads: usize,
}

impl SearchCost {
    /// Milliseconds of one thread per model evaluation, over the stages that run the model.
    pub fn ms_per_evaluation(&self) -> f64 {
        let n = self.fold_fit_evaluations
            + self.inverse_evaluations
            + self.shortlist_evaluations
            + self.final_evaluations;
        1e3 * (self.fold_fits_s + self.inverse_s + self.shortlist_s + self.final_s)
            * self.threads as f64
            / n.max(1) as f64
    }
}

/// The result of the search.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Search {
    /// The forms tried: those fitted with the full model first (best held-out error first),
    /// then the others by their screening error.
    pub forms: Vec<Form>,
    /// Forms screened.
    pub tried: usize,
    /// Forms there are.
    pub total: usize,
    /// Time spent, s.
    pub seconds: f64,
    /// Seconds by which the search ended past its time bound (0 within it): the best
    /// screened form and the best finalist are fitted however long they take.
    pub past_bound_s: f64,
    /// Where the time went.
    pub cost: SearchCost,
    /// The best form, when it earns a proposal (module doc).
    pub proposed: Option<Form>,
    /// The configuration with the proposed form, fitted on all rows: ready for `ecf fit` and
    /// the FMU.
    pub proposed_config: Option<serde_json::Value>,
    /// The warnings of that fit on all rows, as `ecf fit` prints them: fitted values outside
    /// their plausible physical range, solver stops that are not convergence.
    pub proposed_warnings: Vec<String>,
}

fn variables(data: &Dataset, pred: &[Prediction]) -> Vec<Var> {
    let mut v: Vec<(String, Vec<f64>)> = vec![
        ("v_mps".into(), data.rows.iter().map(|r| r.v).collect()),
        (
            "fn_kN".into(),
            data.rows.iter().map(|r| r.fn_n / 1e3).collect(),
        ),
        (
            "abs(cx)".into(),
            data.rows.iter().map(|r| r.cx.abs()).collect(),
        ),
        (
            "slip_mps".into(),
            pred.iter().map(|p| p.slip_velocity).collect(),
        ),
        ("p_GPa".into(), pred.iter().map(|p| p.p0 / 1e9).collect()),
        ("T_C".into(), pred.iter().map(|p| p.t_max).collect()),
        // the bulk temperature, where the file gives it per row (a constant is passed over)
        (
            "t_bulk_C".into(),
            data.rows.iter().map(|r| r.t_bulk).collect(),
        ),
    ];
    for (k, n) in data.extra_names.iter().enumerate() {
        v.push((n.clone(), data.rows.iter().map(|r| r.extra[k]).collect()));
    }
    v.into_iter()
        .filter_map(|(expr, x)| {
            let (r, s) = mean_sd(&x);
            let (r, s) = (sig4(r), sig4(s));
            let min = x.iter().copied().fold(f64::INFINITY, f64::min);
            let ok = x.iter().all(|v| v.is_finite()) && s > 1e-9 * r.abs().max(1e-12);
            ok.then(|| Var {
                expr,
                r,
                s,
                min: sig4(min),
                positive: x.iter().all(|v| *v > 0.0),
                x,
            })
        })
        .collect()
}

/// The target groups a form may scale: mu for Coulomb, else both strengths together, each
/// alone, the hardening scale (and L_e with elasticity on).
fn targets(cfg: &Config) -> Vec<Target> {
    if cfg.has(Effect::Coulomb) {
        vec![Target::Mu]
    } else {
        let mut t = vec![Target::Strengths, Target::TauC1, Target::TauC2, Target::Lp];
        if cfg.has(Effect::LayerElasticity) {
            t.push(Target::Le);
        }
        t
    }
}

/// The registry parameters that set the level of a target group (scaled by the screening's
/// level when a full fit starts from it).
fn level_params(t: Target) -> &'static [P] {
    match t {
        Target::Strengths => &[P::Tc10, P::Tc20],
        Target::TauC1 => &[P::Tc10],
        Target::TauC2 => &[P::Tc20],
        Target::Lp => &[P::Lp0],
        Target::Le => &[P::Le0],
        Target::Mu => &[P::Mu],
    }
}

/// One form: target group, variable (index into the variables) and shape.
#[derive(Clone, Copy, Debug)]
struct Planned {
    group: usize,
    var: usize,
    shape: Shape,
    /// Screened on the factors the configuration as given needs, not each fold's fit: where
    /// the fold fits bend their free parameters (temperature coefficients, say) to stand in
    /// for the missing effect, the configuration as given shows it undisguised.
    given: bool,
}

impl Planned {
    /// The same form (target, variable and shape), whichever factors screened it.
    fn same_form(&self, o: &Planned) -> bool {
        (self.group, self.var, self.shape) == (o.group, o.var, o.shape)
    }
}

/// A fold: its training and test rows and the configuration fitted on the training rows.
struct Fold {
    train: Vec<usize>,
    test: Vec<usize>,
    cfg: Config,
}

/// What every stage of one search shares.
struct Searcher<'a> {
    cfg: &'a Config,
    data: &'a Dataset,
    labels: &'a [usize],
    base_free: &'a [FreeParam],
    threads: usize,
    opts: &'a FitOptions<'a>,
    t0: std::time::Instant,
    /// When the time bound ends: [`SEARCH_SECONDS`] (or the caller's bound) after the
    /// diagnosis began.
    deadline: std::time::Instant,
    progress: &'a (dyn Fn(&str) + Sync),
}

/// A screened form: the regression's fit per fold and its held-out CV.
struct Screened {
    plan: Planned,
    fits: Vec<shapes::Fitted>,
    cv: f64,
}

/// Searches the forms; `best_heldout` is the best held-out CV(RMSE) so far (%),
/// `base_heldout` the configuration's own, `noise_cv` the data's noise level (%, when
/// known), `deadline` the end of the time bound.
#[allow(clippy::too_many_arguments)]
pub(crate) fn search(
    cfg: &Config,
    data: &Dataset,
    pred: &[Prediction],
    labels: &[usize],
    base_free: &[FreeParam],
    threads: usize,
    opts: &FitOptions,
    best_heldout: f64,
    base_heldout: f64,
    noise_cv: Option<f64>,
    deadline: std::time::Instant,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Search> {
    let s = Searcher {
        cfg,
        data,
        labels,
        base_free,
        threads,
        opts,
        t0: std::time::Instant::now(),
        deadline,
        progress,
    };
    let vars = variables(data, pred);
    let groups = targets(cfg);
    let mut cost = SearchCost {
        threads,
        ..SearchCost::default()
    };
    let evaluated = || opts.memo.map(|m| m.counts().1).unwrap_or(0);
    let e0 = evaluated();
    let folds = s.folds()?;
    cost.fold_fits_s = s.elapsed();
    cost.fold_fit_evaluations = evaluated() - e0;
    let inv = s.inverses(&folds, &groups, &mut cost)?;
    let t = s.elapsed();
    let plan = plan(&vars, groups.len());
    let total = plan.len() / 2;
    s.tick(&format!("search: screening {total} forms"), 0, 1);
    let mut screened = s.screen(&plan, &vars, &folds, &inv);
    screened.sort_by(|a, b| a.cv.total_cmp(&b.cv));
    cost.screen_s = s.elapsed() - t;
    let (t, e0) = (s.elapsed(), evaluated());
    let list = fits::shortlist(&screened);
    let short = s.shortlist_fits(&screened, &list, &vars, &groups, &folds);
    cost.shortlist_s = s.elapsed() - t;
    cost.shortlist_evaluations = evaluated() - e0;
    cost.shortlisted = short.len();
    let (t, e0) = (s.elapsed(), evaluated());
    let fin = fits::finalists(&short, &screened);
    let (finals, cut) = s.final_fits(&short, &fin, &screened, &groups, &folds);
    cost.final_s = s.elapsed() - t;
    cost.final_evaluations = evaluated() - e0;
    cost.finalists = finals.len();
    cost.finalists_cut = cut;
    let base_resid = s.base_residuals(&folds, &inv[0]);
    let chosen = fits::choose(&finals, &short, &screened);
    let z: Vec<f64> = finals
        .iter()
        .map(|f| fits::paired_z(&base_resid, &f.resid))
        .collect();
    let bound = proposal_bound(base_heldout, noise_cv, data.rows.len());
    let proposed_at = chosen
        .filter(|&j| finals[j].cv < best_heldout && finals[j].cv <= bound && z[j] >= EVIDENCE);
    // the report: the finalists (the chosen one first), the rest of the shortlist, the
    // screened rest
    let mut order: Vec<usize> = (0..finals.len()).collect();
    order.sort_by(|&a, &b| finals[a].cv.total_cmp(&finals[b].cv));
    if let Some(c) = chosen {
        order.retain(|&j| j != c);
        order.insert(0, c);
    }
    let report = |sh: usize| -> Form {
        let mut f = s.form(&screened[short[sh].screened], &vars, &groups);
        f.shortlist_cv_rmse_pct = short[sh].cv;
        f
    };
    let finalist = |j: usize| -> Form {
        let (fi, mut f) = (&finals[j], report(finals[j].short));
        f.heldout_cv_rmse_pct = fi.cv;
        f.evidence_z = z[j];
        let np = f.params.len();
        for (q, fp) in f
            .params
            .iter_mut()
            .zip(&fi.fit.params[fi.fit.params.len() - np..])
        {
            q.value = fp.value;
            q.stderr = fp.stderr;
        }
        f.fitted_cv_rmse_pct = fi.fit.cv_rmse_pct_after;
        let plan = screened[short[fi.short].screened].plan;
        let p: Vec<f64> = f.params.iter().map(|q| q.value).collect();
        f.factor_range = plan.shape.factor_range(&vars[plan.var], &p);
        f
    };
    let mut forms: Vec<Form> = order.iter().map(|&j| finalist(j)).collect();
    let mut rest: Vec<usize> = (0..short.len()).filter(|j| !fin.contains(j)).collect();
    rest.sort_by(|&a, &b| short[a].cv.total_cmp(&short[b].cv));
    forms.extend(rest.iter().map(|&j| report(j)));
    // each form once, with the better of its two screenings (the list is sorted)
    let mut listed: Vec<Planned> = short.iter().map(|x| screened[x.screened].plan).collect();
    for sc in &screened {
        if !listed.iter().any(|p| p.same_form(&sc.plan)) {
            listed.push(sc.plan);
            forms.push(s.form(sc, &vars, &groups));
        }
    }
    Ok(Search {
        forms,
        tried: total,
        total,
        seconds: s.elapsed(),
        past_bound_s: std::time::Instant::now()
            .saturating_duration_since(deadline)
            .as_secs_f64(),
        cost,
        proposed: proposed_at.map(finalist),
        proposed_config: proposed_at.map(|j| finals[j].fit.config.to_json()),
        proposed_warnings: proposed_at.map_or_else(Vec::new, |j| finals[j].fit.warnings.clone()),
    })
}

/// Every form: each target group, variable and shape that applies, screened on the folds'
/// factors and on the configuration's as given.
fn plan(vars: &[Var], groups: usize) -> Vec<Planned> {
    (0..groups)
        .flat_map(|g| {
            vars.iter().enumerate().flat_map(move |(vi, v)| {
                Shape::ALL
                    .into_iter()
                    .filter(move |sh| sh.applies(v))
                    .flat_map(move |shape| {
                        [false, true].map(|given| Planned {
                            group: g,
                            var: vi,
                            shape,
                            given,
                        })
                    })
            })
        })
        .collect()
}

/// A mask of `n` rows with the rows `idx` set.
fn mask(n: usize, idx: &[usize]) -> Vec<bool> {
    let mut m = vec![false; n];
    for &i in idx {
        m[i] = true;
    }
    m
}

/// CV(RMSE) of residuals against the mean measurement, %.
fn cv_of(resid: &[f64], meas_mean: f64) -> f64 {
    let ss: f64 = resid.iter().map(|r| r * r).sum();
    100.0 * (ss / resid.len().max(1) as f64).sqrt() / meas_mean
}

/// Counts a finished job when dropped (also when the job returns early) and reports the
/// count.
struct Ticker<'a, F: Fn(usize)> {
    count: &'a std::sync::atomic::AtomicUsize,
    report: F,
}

impl<'a, F: Fn(usize)> Ticker<'a, F> {
    fn new(count: &'a std::sync::atomic::AtomicUsize, report: F) -> Self {
        Ticker { count, report }
    }
}

impl<F: Fn(usize)> Drop for Ticker<'_, F> {
    fn drop(&mut self) {
        let k = self
            .count
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed)
            + 1;
        (self.report)(k);
    }
}

impl Searcher<'_> {
    fn elapsed(&self) -> f64 {
        self.t0.elapsed().as_secs_f64()
    }

    /// Seconds left until the time bound ends (0 past it).
    fn left(&self) -> f64 {
        self.deadline
            .saturating_duration_since(std::time::Instant::now())
            .as_secs_f64()
    }

    /// Reports a stage's progress as `STAGE [done/total]` (the command's progress bar reads
    /// the counts).
    fn tick(&self, stage: &str, done: usize, total: usize) {
        (self.progress)(&format!("{stage} [{done}/{total}]"));
    }

    /// The mean measurement over the folds' test rows.
    fn test_mean(&self, folds: &[Fold]) -> f64 {
        let (mut s, mut n) = (0.0, 0);
        for f in folds {
            for &i in &f.test {
                s += self.data.rows[i].f;
                n += 1;
            }
        }
        s / n.max(1) as f64
    }

    /// The configuration fitted on each fold's training rows, side by side (the diagnosis'
    /// held-out score made the same fits: their model values are looked up).
    fn folds(&self) -> Result<Vec<Fold>> {
        let nf = fold_count(self.labels);
        let n = self.data.rows.len();
        let parts: Vec<(Vec<usize>, Vec<usize>)> = (0..nf)
            .map(|f| {
                let test: Vec<usize> = (0..n).filter(|&i| self.labels[i] == f).collect();
                let train: Vec<usize> = (0..n).filter(|&i| self.labels[i] != f).collect();
                (train, test)
            })
            .filter(|(_, test)| !test.is_empty())
            .collect();
        let count = std::sync::atomic::AtomicUsize::new(0);
        let total = parts.len();
        self.tick("search: the configuration on each fold", 0, total);
        let fitted = side_by_side(parts.len(), self.threads, &|j, inner| {
            let _done = Ticker::new(&count, |k| {
                self.tick("search: the configuration on each fold", k, total)
            });
            let train = subset(self.data, &mask(n, &parts[j].0));
            if self.base_free.is_empty() || train.rows.len() <= self.base_free.len() + 1 {
                Ok(self.cfg.clone())
            } else {
                crate::fit::fitted_or_kept(self.cfg, &train, self.base_free, inner, self.opts)
            }
        });
        parts
            .into_iter()
            .zip(fitted)
            .map(|((train, test), c)| {
                Ok(Fold {
                    train,
                    test,
                    cfg: c?,
                })
            })
            .collect()
    }

    /// The needed factors per target group: each fold's fit's, then the configuration's as
    /// given, `[group][fold or folds.len()]`.
    fn inverses(
        &self,
        folds: &[Fold],
        groups: &[Target],
        cost: &mut SearchCost,
    ) -> Result<Vec<Vec<Inverse>>> {
        let t = self.elapsed();
        // per group: each fold's fit, then the configuration as given
        let per = folds.len() + 1;
        let jobs = groups.len() * per;
        let count = std::sync::atomic::AtomicUsize::new(0);
        let stage = "search: the factor each row needs, per fold and target";
        self.tick(stage, 0, jobs);
        let rows = self.data.rows.len();
        let done = side_by_side(jobs, self.threads, &|j, inner| {
            let _done = Ticker::new(&count, |k| self.tick(stage, k, jobs));
            let cfg = folds.get(j % per).map(|f| &f.cfg).unwrap_or(self.cfg);
            inverse::solve(cfg, self.data, groups[j / per], inner)
        });
        let mut out: Vec<Vec<Inverse>> = (0..groups.len()).map(|_| Vec::new()).collect();
        for (j, r) in done.into_iter().enumerate() {
            let r = r?;
            cost.inverse_evaluations += r.predictions * rows;
            out[j / per].push(r);
        }
        cost.inverse_s = self.elapsed() - t;
        Ok(out)
    }

    /// The configuration's own held-out residuals, in the folds' test-row order.
    fn base_residuals(&self, folds: &[Fold], inv: &[Inverse]) -> Vec<f64> {
        folds
            .iter()
            .zip(inv)
            .flat_map(|(f, v)| f.test.iter().map(|&i| v.base_miss[i]))
            .collect()
    }

    /// Every planned form screened: regression on each fold's training rows, scored on its
    /// test rows (module doc, stage 2).
    fn screen(
        &self,
        plan: &[Planned],
        vars: &[Var],
        folds: &[Fold],
        inv: &[Vec<Inverse>],
    ) -> Vec<Screened> {
        let mean = self.test_mean(folds);
        let nf = folds.len();
        // group g's factors for fold k: the fold fit's, or the configuration's as given
        let rows = |g: usize, given: bool, k: usize| {
            let iv = &inv[g][if given { nf } else { k }];
            shapes::Rows {
                lam: &iv.lam,
                sens: &iv.sens,
                miss: &iv.miss,
            }
        };
        side_by_side(plan.len(), self.threads, &|j, _| {
            let p = plan[j];
            let v = &vars[p.var];
            let mut resid = Vec::new();
            let fits: Vec<shapes::Fitted> = folds
                .iter()
                .enumerate()
                .map(|(k, f)| {
                    let r = rows(p.group, p.given, k);
                    let fit = shapes::fit(p.shape, v, &r, &f.train);
                    resid.extend(shapes::residuals(p.shape, v, &r, &f.test, &fit));
                    fit
                })
                .collect();
            Screened {
                plan: p,
                fits,
                cv: cv_of(&resid, mean),
            }
        })
    }

    /// A form's report entry before its full fit.
    fn form(&self, sc: &Screened, vars: &[Var], groups: &[Target]) -> Form {
        let v = &vars[sc.plan.var];
        Form {
            target: groups[sc.plan.group].name().to_string(),
            variable: v.expr.clone(),
            shape: sc.plan.shape.name().to_string(),
            factor: sc.plan.shape.factor(v),
            screen_cv_rmse_pct: sc.cv,
            shortlist_cv_rmse_pct: f64::NAN,
            heldout_cv_rmse_pct: f64::NAN,
            evidence_z: f64::NAN,
            params: sc
                .plan
                .shape
                .params()
                .iter()
                .map(|q| FormParam {
                    name: q.0.into(),
                    value: f64::NAN,
                    stderr: f64::NAN,
                })
                .collect(),
            fitted_cv_rmse_pct: f64::NAN,
            factor_range: [f64::NAN; 2],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_required_gain_grows_on_small_files_only() {
        assert_eq!(gain_of_noise(GAIN_ROWS), GAIN_OF_NOISE);
        assert_eq!(gain_of_noise(600), GAIN_OF_NOISE);
        assert!((gain_of_noise(63) - 0.12 * (150.0f64 / 63.0).sqrt()).abs() < 1e-12);
        assert!(gain_of_noise(30) > gain_of_noise(63) && gain_of_noise(63) > gain_of_noise(128));
        assert_eq!(
            proposal_bound(3.0, Some(2.0), 600),
            3.0 - 2.0 * GAIN_OF_NOISE
        );
        assert!(proposal_bound(3.0, Some(2.0), 63) < proposal_bound(3.0, Some(2.0), 600));
    }
}
