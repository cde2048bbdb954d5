//! Search of formula-effect forms when no catalogue effect brings the held-out error to the noise: targets x variables x one-parameter shapes, each fitted on the diagnosis' folds and ranked by held-out error.
//!
//! Each form scales one target (tau_c1, tau_c2, L_p, L_e where the layer's elasticity is on;
//! mu for a Coulomb model) by a one-parameter factor of one variable X about its mean r over
//! the data, in units of its standard deviation s: `1 + k (X - r)/s` (floored at 0.01),
//! `1/(1 + k (X - r)/s)` (the same floor), `exp(-k (X - r)/s)`, and `(X/r)^k` for a positive
//! variable. The variables are the operating point (`v_mps`, `fn_kN`, `abs(cx)`), the local
//! state the formula sees (`slip_mps`, `p_GPa`, `T_C`; their data values are the model's
//! slip speed, maximum pressure and maximum temperature of the row) and every extra column;
//! a variable constant over the data is passed over. Forms are tried in the order of the
//! residual correlation of their variable, strongest first, until the time bound. Two stages:
//! every form is screened on the diagnosis' folds with k alone free (k in [-3, 3]; the other
//! parameters at the baseline's values fitted on the same training folds); the best
//! [`REFIT_HELDOUT`] are then fitted on the same folds with the diagnosis' free parameters plus
//! k, as the catalogue candidates are, and ranked by that held-out error.

use crate::evaluate::{predict_with, Prediction};
use crate::fit::{fit_params_with, FitOptions, FreeParam};
use crate::heldout::{fold_count, heldout, subset, CLAIM_FRACTION};
use crate::measure::Dataset;
use crate::stats::{cv_rmse_pct, mean_sd};
use creep_core::config::Config;
use creep_core::effects::Effect;
use creep_core::error::Result;
use creep_core::formula::{FormulaEffect, FormulaParam, Target};

/// Time bound of the search, s: the screening stops at 60 % of it (the forms not reached are
/// counted as not tried), the fits with every free parameter at the bound (the best screened
/// form is always fitted, so that a search that ran can propose).
pub const SEARCH_SECONDS: f64 = 50.0;

/// How many of the best screened forms are fitted on the folds with all free parameters.
pub const REFIT_HELDOUT: usize = 5;

/// Convergence tolerance of the screening fits (k alone).
const SCREEN_TOLERANCE: f64 = 1e-4;

/// How many of the best forms are refitted on all rows with their standard error.
pub const REFIT_BEST: usize = 3;

/// One formula form tried.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Form {
    /// Target scaled by the factor.
    pub target: String,
    /// Variable of the factor (a formula variable or a data column).
    pub variable: String,
    /// Shape: `linear`, `reciprocal`, `exp` or `power`.
    pub shape: String,
    /// The factor as written into the configuration.
    pub factor: String,
    /// Held-out CV(RMSE) with k alone fitted on the folds (screening), %.
    pub screen_cv_rmse_pct: f64,
    /// Held-out CV(RMSE) with all free parameters fitted on the folds, % (NaN for the forms
    /// not among the best screened, [`REFIT_HELDOUT`]).
    pub heldout_cv_rmse_pct: f64,
    /// Fitted k on all rows (NaN for the forms not refitted, [`REFIT_BEST`]), -.
    pub k: f64,
    /// Its standard error, - (NaN when not refitted or at a bound).
    pub k_stderr: f64,
    /// In-sample CV(RMSE) on all rows, % (NaN when not refitted).
    pub fitted_cv_rmse_pct: f64,
}

/// The result of the search.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Search {
    /// The forms tried: those fitted with all free parameters first (best held-out error
    /// first), then the others by their screening error.
    pub forms: Vec<Form>,
    /// Forms tried (fitted on the folds) within the time bound.
    pub tried: usize,
    /// Forms that would have been tried without the time bound.
    pub total: usize,
    /// Time spent, s.
    pub seconds: f64,
    /// The best form, when it beats the best model so far by more than the noise on the
    /// held-out folds (without a noise estimate: by [`crate::heldout::CLAIM_FRACTION`]).
    pub proposed: Option<Form>,
    /// The configuration with the proposed form, fitted on all rows: ready for `ecf fit` and
    /// the FMU.
    pub proposed_config: Option<serde_json::Value>,
}

struct Var {
    /// Name in the formula.
    expr: String,
    /// Name in the residual correlations.
    corr: String,
    /// Mean and standard deviation over the data.
    r: f64,
    s: f64,
    /// Every value > 0.
    positive: bool,
}

fn variables(data: &Dataset, pred: &[Prediction]) -> Vec<Var> {
    let mut v: Vec<(String, String, Vec<f64>)> = vec![
        (
            "v_mps".into(),
            "v_mps".into(),
            data.rows.iter().map(|r| r.v).collect(),
        ),
        (
            "fn_kN".into(),
            "fn_kN".into(),
            data.rows.iter().map(|r| r.fn_n / 1e3).collect(),
        ),
        (
            "abs(cx)".into(),
            "cx".into(),
            data.rows.iter().map(|r| r.cx.abs()).collect(),
        ),
        (
            "slip_mps".into(),
            "slip_velocity_mps".into(),
            pred.iter().map(|p| p.slip_velocity).collect(),
        ),
        (
            "p_GPa".into(),
            "p0_MPa".into(),
            pred.iter().map(|p| p.p0 / 1e9).collect(),
        ),
        (
            "T_C".into(),
            "model_T_max_C".into(),
            pred.iter().map(|p| p.t_max).collect(),
        ),
    ];
    for (k, n) in data.extra_names.iter().enumerate() {
        v.push((
            n.clone(),
            n.clone(),
            data.rows.iter().map(|r| r.extra[k]).collect(),
        ));
    }
    v.into_iter()
        .filter_map(|(expr, corr, x)| {
            let (r, s) = mean_sd(&x);
            // four significant digits: the factor is written into the configuration
            let sig = |v: f64| {
                if v == 0.0 || !v.is_finite() {
                    v
                } else {
                    let e = 10f64.powi(3 - v.abs().log10().floor() as i32);
                    (v * e).round() / e
                }
            };
            let (r, s) = (sig(r), sig(s));
            let ok = x.iter().all(|v| v.is_finite()) && s > 1e-9 * r.abs().max(1e-12);
            ok.then(|| Var {
                expr,
                corr,
                r,
                s,
                positive: x.iter().all(|v| *v > 0.0),
            })
        })
        .collect()
}

/// The shapes of a variable: (name, factor).
fn shapes(v: &Var) -> Vec<(&'static str, String)> {
    let (x, r, s) = (&v.expr, v.r, v.s);
    let z = format!("({x} - {r}) / {s}");
    let mut out = vec![
        ("linear", format!("max(1 + k * {z}, 0.01)")),
        ("reciprocal", format!("1 / max(1 + k * {z}, 0.01)")),
        ("exp", format!("exp(-k * {z})")),
    ];
    if v.positive && r > 0.0 {
        out.push(("power", format!("(max({x}, {}) / {r}) ^ k", r / 100.0)));
    }
    out
}

/// `cfg` plus the form (k = 0 in [-3, 3]) and the free parameters `base_free` plus k.
fn with_form_on(
    cfg: &Config,
    base_free: &[FreeParam],
    t: Target,
    factor: &str,
) -> Result<(Config, Vec<FreeParam>)> {
    let k = FormulaParam {
        name: "k".into(),
        value: 0.0,
        min: -3.0,
        max: 3.0,
    };
    let fe = FormulaEffect::new(&format!("form_{}", t.name()), t, factor, vec![k])?;
    let mut c = cfg.clone();
    c.modifiers.push(creep_core::AnyModifier::Formula(fe));
    let mut free = base_free.to_vec();
    free.push(FreeParam::Modifier {
        effect: c.modifiers.len() - 1,
        param: 0,
    });
    Ok((c, free))
}

/// Searches the forms; `best_heldout` is the best held-out CV(RMSE) so far (%), `noise_cv` the
/// noise level as a CV(RMSE) (%), `baseline` the configuration's own held-out CV(RMSE).
#[allow(clippy::too_many_arguments)]
pub(crate) fn search(
    cfg: &Config,
    data: &Dataset,
    pred: &[Prediction],
    corr: &[crate::residuals::Correlation],
    labels: &[usize],
    base_free: &[FreeParam],
    threads: usize,
    opts: &FitOptions,
    best_heldout: f64,
    noise_cv: Option<f64>,
    budget_s: f64,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Search> {
    let t0 = std::time::Instant::now();
    let vars = ranked_variables(data, pred, corr);
    let plan = plan(&vars, &targets(cfg));
    let total = plan.len();
    let s = Searcher {
        cfg,
        data,
        labels,
        base_free,
        threads,
        opts,
        t0,
        budget_s,
        progress,
    };
    let (mut forms, tried) = s.screen(&plan)?;
    s.heldout_best(&mut forms)?;
    let mut proposed_config = s.refit_best(&mut forms)?;
    let margin_ok = |h: f64| match noise_cv {
        Some(n) => h < best_heldout - n,
        None => h < (1.0 - CLAIM_FRACTION) * best_heldout,
    };
    let proposed = forms
        .first()
        .filter(|f| {
            f.heldout_cv_rmse_pct.is_finite() && margin_ok(f.heldout_cv_rmse_pct) && f.k.is_finite()
        })
        .cloned();
    if proposed.is_none() {
        proposed_config = None;
    }
    Ok(Search {
        forms,
        tried,
        total,
        seconds: t0.elapsed().as_secs_f64(),
        proposed,
        proposed_config,
    })
}

/// The material functions a form may scale: mu for Coulomb, else the layer's strengths and
/// hardening scale (and L_e with elasticity on).
fn targets(cfg: &Config) -> Vec<Target> {
    if cfg.has(Effect::Coulomb) {
        vec![Target::Mu]
    } else {
        let mut t = vec![Target::TauC1, Target::TauC2, Target::Lp];
        if cfg.has(Effect::LayerElasticity) {
            t.push(Target::Le);
        }
        t
    }
}

/// The variables, strongest residual correlation first.
fn ranked_variables(
    data: &Dataset,
    pred: &[Prediction],
    corr: &[crate::residuals::Correlation],
) -> Vec<Var> {
    let mut vars = variables(data, pred);
    let strength = |v: &Var| {
        corr.iter()
            .find(|c| c.variable == v.corr)
            .map(|c| c.r.abs())
            .unwrap_or(0.0)
    };
    vars.sort_by(|a, b| strength(b).total_cmp(&strength(a)));
    vars
}

/// One form to try: target, variable, shape and factor.
type Planned<'v> = (Target, &'v Var, &'static str, String);

/// Every form, variable by variable (in the order given), target by target, shape by shape.
fn plan<'v>(vars: &'v [Var], targets: &[Target]) -> Vec<Planned<'v>> {
    let mut plan = Vec::new();
    for v in vars {
        for &t in targets {
            for (shape, factor) in shapes(v) {
                plan.push((t, v, shape, factor));
            }
        }
    }
    plan
}

/// What every stage of one search shares: the data and folds, the baseline's free
/// parameters, the options and the time bound.
struct Searcher<'a> {
    cfg: &'a Config,
    data: &'a Dataset,
    labels: &'a [usize],
    base_free: &'a [FreeParam],
    threads: usize,
    opts: &'a FitOptions<'a>,
    t0: std::time::Instant,
    budget_s: f64,
    progress: &'a (dyn Fn(&str) + Sync),
}

impl Searcher<'_> {
    fn elapsed(&self) -> f64 {
        self.t0.elapsed().as_secs_f64()
    }

    /// The baseline fitted on each training fold, once: (train, test, fitted configuration).
    fn folds(&self) -> Result<Vec<(Dataset, Dataset, Config)>> {
        let (cfg, data, labels, base_free) = (self.cfg, self.data, self.labels, self.base_free);
        let nf = fold_count(labels);
        let mut folds = Vec::new();
        for f in 0..nf {
            let train = subset(data, &labels.iter().map(|l| *l != f).collect::<Vec<_>>());
            let test = subset(data, &labels.iter().map(|l| *l == f).collect::<Vec<_>>());
            if test.rows.is_empty() {
                continue;
            }
            let c = if base_free.is_empty() || train.rows.len() <= base_free.len() + 1 {
                cfg.clone()
            } else {
                crate::fit::fitted_or_kept(cfg, &train, base_free, self.threads, self.opts)?
            };
            folds.push((train, test, c));
        }
        Ok(folds)
    }

    /// Screens the planned forms (k alone on the baseline's fold fits) until 60 % of the time
    /// bound; the forms that could be evaluated, best first, and how many were tried.
    fn screen(&self, plan: &[Planned]) -> Result<(Vec<Form>, usize)> {
        let (base_free, threads) = (self.base_free, self.threads);
        let folds = self.folds()?;
        // no memo for the screening: every form's configurations are new, so its points would
        // only be stored, never looked up again (the memory would grow with the forms)
        let screen_opts = FitOptions {
            tolerance: Some(SCREEN_TOLERANCE),
            memo: None,
            ..*self.opts
        };
        let screen = |t: Target, factor: &str| -> Result<f64> {
            let mut meas = Vec::new();
            let mut model = Vec::new();
            for (train, test, c) in &folds {
                let (c, _) = with_form_on(c, base_free, t, factor)?;
                let k = [FreeParam::Modifier {
                    effect: c.modifiers.len() - 1,
                    param: 0,
                }];
                let fitted = crate::fit::fitted_or_kept(&c, train, &k, threads, &screen_opts)?;
                let p = predict_with(&fitted, test, threads, None)?;
                meas.extend(test.rows.iter().map(|r| r.f));
                model.extend(p.iter().map(|p| p.f));
            }
            Ok(cv_rmse_pct(&meas, &model))
        };
        let total = plan.len();
        let mut forms: Vec<Form> = Vec::new();
        let mut tried = 0;
        for (i, (t, v, shape, factor)) in plan.iter().enumerate() {
            if self.elapsed() > 0.6 * self.budget_s {
                break;
            }
            tried += 1;
            (self.progress)(&format!(
                "form {}/{total}: {} x {shape}({})",
                i + 1,
                t.name(),
                v.expr
            ));
            // a form the model cannot evaluate (a factor out of range at some row) is passed over
            let Ok(h) = screen(*t, factor) else {
                continue;
            };
            if !h.is_finite() {
                continue;
            }
            forms.push(Form {
                target: t.name().to_string(),
                variable: v.expr.clone(),
                shape: shape.to_string(),
                factor: factor.clone(),
                screen_cv_rmse_pct: h,
                heldout_cv_rmse_pct: f64::NAN,
                k: f64::NAN,
                k_stderr: f64::NAN,
                fitted_cv_rmse_pct: f64::NAN,
            });
        }
        forms.sort_by(|a, b| a.screen_cv_rmse_pct.total_cmp(&b.screen_cv_rmse_pct));
        Ok((forms, tried))
    }

    /// The best screened forms on the same folds with every free parameter, as the
    /// catalogue's; then every form ranked: held-out errors first, then screened ones.
    fn heldout_best(&self, forms: &mut [Form]) -> Result<()> {
        for (j, f) in forms.iter_mut().take(REFIT_HELDOUT).enumerate() {
            if j > 0 && self.elapsed() > self.budget_s {
                break;
            }
            (self.progress)(&format!(
                "the best forms on the folds with every free parameter ({}/{REFIT_HELDOUT})",
                j + 1
            ));
            let t = Target::parse(&f.target)?;
            let (c, free) = with_form_on(self.cfg, self.base_free, t, &f.factor)?;
            if let Ok(h) = heldout(&c, self.data, self.labels, &free, self.threads, self.opts) {
                f.heldout_cv_rmse_pct = h;
            }
        }
        let key = |f: &Form| {
            if f.heldout_cv_rmse_pct.is_finite() {
                (0, f.heldout_cv_rmse_pct)
            } else {
                (1, f.screen_cv_rmse_pct)
            }
        };
        forms.sort_by(|a, b| {
            let (ka, kb) = (key(a), key(b));
            ka.0.cmp(&kb.0).then(ka.1.total_cmp(&kb.1))
        });
        Ok(())
    }

    /// The best few forms refitted on all rows with the standard error of k; the
    /// configuration of the best one, as JSON.
    fn refit_best(&self, forms: &mut [Form]) -> Result<Option<serde_json::Value>> {
        let mut proposed_config = None;
        let full = FitOptions {
            skip_uncertainties: false,
            ..*self.opts
        };
        for (j, f) in forms.iter_mut().take(REFIT_BEST).enumerate() {
            if j > 0 && self.elapsed() > self.budget_s {
                break;
            }
            (self.progress)(&format!(
                "refitting the best forms on all rows ({}/{REFIT_BEST})",
                j + 1
            ));
            let t = Target::parse(&f.target)?;
            let (c, free) = with_form_on(self.cfg, self.base_free, t, &f.factor)?;
            if let Ok(r) = fit_params_with(&c, self.data, &free, self.threads, &full, &|_| {}) {
                if let Some(p) = r.params.last() {
                    f.k = p.value;
                    f.k_stderr = p.stderr;
                }
                f.fitted_cv_rmse_pct = r.cv_rmse_pct_after;
                if j == 0 {
                    proposed_config = Some(r.config.to_json());
                }
            }
        }
        Ok(proposed_config)
    }
}
