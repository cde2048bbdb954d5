//! The full model on the search's best forms: the shortlist with the form's parameters and the target's level refitted on each fold, then the finalists with every free parameter, as a catalogue effect is scored.

use super::shapes::{Shape, Var};
use super::{cv_of, level_params, mask, Fold, Screened, Searcher, SHORTLIST};
use crate::evaluate::predict_with;
use crate::fit::{fit_params_with, FitOptions, FitResult, FreeParam};
use crate::heldout::{side_by_side, subset};
use crate::stats::mean_sd;
use creep_core::config::Config;
use creep_core::error::Result;
use creep_core::formula::{FormulaEffect, FormulaParam, Target};
use creep_core::Modifier;

/// Convergence tolerance of the search's fits ([`FitOptions::tolerance`]): the ranking reads
/// held-out errors to a hundredth of a percent.
pub const FIT_TOLERANCE: f64 = 1e-5;

/// How many of the shortlist's best forms are fitted with every free parameter.
pub const FINALISTS: usize = 2;

/// The name of a form's formula effect in `cfg`: `form_<target>`, or `form_<target>_2`, `_3`,
/// ... when `cfg` already has a modifier of that name (a second round of the diagnosis on a
/// configuration the first one proposed; a configuration file refuses a name twice).
fn effect_name(cfg: &Config, t: Target) -> String {
    let base = format!("form_{}", t.name());
    let taken = |n: &str| cfg.modifiers.iter().any(|m| m.name() == n);
    if !taken(&base) {
        return base;
    }
    (2..)
        .map(|k| format!("{base}_{k}"))
        .find(|n| !taken(n))
        .unwrap_or(base)
}

/// `cfg` plus the form with parameters `p` (the target's level parameters scaled by
/// exp(`level`), the screening's level), and the free parameters `base_free` plus the form's.
pub(super) fn with_form(
    cfg: &Config,
    base_free: &[FreeParam],
    t: Target,
    shape: Shape,
    v: &Var,
    p: &[f64],
    level: f64,
) -> Result<(Config, Vec<FreeParam>)> {
    let params: Vec<FormulaParam> = shape
        .params()
        .iter()
        .zip(p)
        .map(|(q, val)| FormulaParam {
            name: q.0.into(),
            value: val.clamp(q.1, q.2),
            min: q.1,
            max: q.2,
        })
        .collect();
    let fe = FormulaEffect::new(&effect_name(cfg, t), t, &shape.factor(v), params)?;
    let mut c = cfg.clone();
    if level.is_finite() && level != 0.0 {
        for &q in level_params(t) {
            let (lo, hi) = c.params.bounds(q);
            let x = (c.params.get(q) * level.clamp(-0.7, 0.7).exp()).clamp(lo, hi);
            c.params.set(q, x)?;
        }
    }
    c.modifiers.push(creep_core::AnyModifier::Formula(fe));
    let mut free = base_free.to_vec();
    for k in 0..shape.params().len() {
        free.push(FreeParam::Modifier {
            effect: c.modifiers.len() - 1,
            param: k,
        });
    }
    Ok((c, free))
}

/// A shortlisted form fitted on the folds with its own parameters and the target's level:
/// its held-out CV(RMSE) and each fold's fit.
pub(super) struct Shortlisted {
    /// Index into the screened forms.
    pub screened: usize,
    pub cv: f64,
    configs: Vec<Config>,
}

/// A finalist fitted on the folds and on all rows with every free parameter.
pub(super) struct Final {
    /// Index into the shortlisted forms.
    pub short: usize,
    pub resid: Vec<f64>,
    pub cv: f64,
    pub fit: FitResult,
}

/// The free parameters of `cfg` with a form as its last modifier: the diagnosis' and the
/// form's (`all`), or the form's and the target's level only.
fn form_free(cfg: &Config, base_free: &[FreeParam], t: Target, all: bool) -> Vec<FreeParam> {
    let e = cfg.modifiers.len() - 1;
    let mut free: Vec<FreeParam> = base_free
        .iter()
        .filter(|q| all || matches!(q, FreeParam::Builtin(b) if level_params(t).contains(b)))
        .copied()
        .collect();
    free.extend(
        (0..cfg.modifiers[e].n_params()).map(|k| FreeParam::Modifier {
            effect: e,
            param: k,
        }),
    );
    free
}

/// The screened forms (indices, best first) to fit with the full model: the best
/// [`SHORTLIST`], taking at most two shapes of one target and variable and three forms of
/// one variable, so that variables the screening cannot tell apart (the load and the Hertz
/// pressure, a local variable and its value over the row) all reach the full model.
pub(super) fn shortlist(screened: &[Screened]) -> Vec<usize> {
    let mut out: Vec<usize> = Vec::new();
    for (j, sc) in screened.iter().enumerate() {
        if out.len() == SHORTLIST {
            break;
        }
        let p = sc.plan;
        if out.iter().any(|&k| screened[k].plan.same_form(&p)) {
            continue;
        }
        let same_pair = out
            .iter()
            .filter(|&&k| screened[k].plan.var == p.var && screened[k].plan.group == p.group)
            .count();
        let same_var = out
            .iter()
            .filter(|&&k| screened[k].plan.var == p.var)
            .count();
        if same_pair < 2 && same_var < 3 && sc.cv.is_finite() {
            out.push(j);
        }
    }
    out
}

/// The shortlist's forms to fit with every free parameter: the [`FINALISTS`] best, and the
/// best with fewer parameters than the best where it is not among them (it may be chosen for
/// its parsimony).
pub(super) fn finalists(short: &[Shortlisted], screened: &[Screened]) -> Vec<usize> {
    let np = |j: usize| screened[short[j].screened].plan.shape.params().len();
    let mut order: Vec<usize> = (0..short.len())
        .filter(|&j| short[j].cv.is_finite())
        .collect();
    order.sort_by(|&a, &b| short[a].cv.total_cmp(&short[b].cv));
    let mut out: Vec<usize> = order.iter().take(FINALISTS).copied().collect();
    if let Some(&best) = order.first() {
        if let Some(&j) = order.iter().find(|&&j| np(j) < np(best)) {
            if !out.contains(&j) {
                out.push(j);
            }
        }
    }
    out
}

/// The finalist to propose: the lowest held-out error, unless one with fewer parameters is
/// within one standard error of it (paired per-row absolute errors).
pub(super) fn choose(
    finals: &[Final],
    short: &[Shortlisted],
    screened: &[Screened],
) -> Option<usize> {
    let np = |j: usize| {
        screened[short[finals[j].short].screened]
            .plan
            .shape
            .params()
            .len()
    };
    let best = (0..finals.len())
        .filter(|&j| finals[j].cv.is_finite())
        .min_by(|&a, &b| finals[a].cv.total_cmp(&finals[b].cv))?;
    let simpler = (0..finals.len())
        .filter(|&j| finals[j].cv.is_finite() && np(j) < np(best))
        .min_by(|&a, &b| finals[a].cv.total_cmp(&finals[b].cv));
    match simpler {
        Some(j) if paired_z(&finals[j].resid, &finals[best].resid) < 1.0 => Some(j),
        _ => Some(best),
    }
}

/// The mean of |e_a| - |e_b| over the rows in standard errors of that mean: how much better
/// `b` predicts the rows than `a` (absolute errors: squared ones let the few rows of the
/// largest errors decide the standard error).
pub(super) fn paired_z(a: &[f64], b: &[f64]) -> f64 {
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x.abs() - y.abs()).collect();
    if d.len() < 3 {
        return 0.0;
    }
    let (m, sd) = mean_sd(&d);
    let se = sd / (d.len() as f64).sqrt();
    if se > 0.0 {
        m / se
    } else if m > 0.0 {
        f64::INFINITY
    } else {
        0.0
    }
}

/// One fit job of a finalist: a fold's held-out residuals, or the fit on all rows.
enum Job {
    Fold(Result<Vec<f64>>),
    All(Box<Result<FitResult>>),
}

impl Searcher<'_> {
    /// Fold `f`'s fit of `start` with `free` on its training rows, its held-out residuals.
    fn fold_fit(
        &self,
        f: &Fold,
        start: &Config,
        free: &[FreeParam],
        threads: usize,
        opts: &FitOptions,
    ) -> Result<(Vec<f64>, Config)> {
        let n = self.data.rows.len();
        let train = subset(self.data, &mask(n, &f.train));
        let fitted = crate::fit::fitted_or_kept(start, &train, free, threads, opts)?;
        let test = subset(self.data, &mask(n, &f.test));
        let p = predict_with(&fitted, &test, threads, self.opts.memo)?;
        Ok((
            p.iter().zip(&test.rows).map(|(p, r)| p.f - r.f).collect(),
            fitted,
        ))
    }

    fn fit_opts(&self) -> FitOptions<'_> {
        FitOptions {
            tolerance: Some(FIT_TOLERANCE),
            ..*self.opts
        }
    }

    /// The shortlist fitted on the folds with each form's parameters and its target's level
    /// (the other free parameters at the fold's fit), side by side, form after form until
    /// the time bound (the first always).
    pub(super) fn shortlist_fits(
        &self,
        screened: &[Screened],
        list: &[usize],
        vars: &[Var],
        groups: &[Target],
        folds: &[Fold],
    ) -> Vec<Shortlisted> {
        let mean = self.test_mean(folds);
        let opts = self.fit_opts();
        let mut out = Vec::new();
        let started = self.elapsed();
        for (done, &j) in list.iter().enumerate() {
            // a further form only while the time left holds it and the finalists after it
            if done > 0 {
                let per_form = (self.elapsed() - started) / done as f64;
                if self.left() < per_form * (1.0 + super::FINALIST_COST * FINALISTS as f64) {
                    break;
                }
            }
            let sc = &screened[j];
            let (p, v, t) = (sc.plan, &vars[sc.plan.var], groups[sc.plan.group]);
            self.tick(
                &format!(
                    "search: the shortlist on the folds, {} x {} in {}",
                    t.name(),
                    p.shape.name(),
                    v.expr
                ),
                done,
                list.len(),
            );
            let jobs = side_by_side(folds.len(), self.threads, &|k, inner| {
                let fit = &sc.fits[k];
                // the screening's starting point: the fold's fit or the configuration as given
                let anchor = if p.given { self.cfg } else { &folds[k].cfg };
                let (c, _) = with_form(anchor, self.base_free, t, p.shape, v, &fit.p, fit.level)?;
                let free = form_free(&c, self.base_free, t, false);
                self.fold_fit(&folds[k], &c, &free, inner, &opts)
            });
            // a form the model cannot evaluate (a factor out of range at some row) is passed over
            let Ok(jobs) = jobs.into_iter().collect::<Result<Vec<_>>>() else {
                continue;
            };
            let (resid, configs): (Vec<Vec<f64>>, Vec<Config>) = jobs.into_iter().unzip();
            let resid: Vec<f64> = resid.concat();
            out.push(Shortlisted {
                screened: j,
                cv: cv_of(&resid, mean),
                configs,
            });
        }
        out
    }

    /// The finalists fitted on the folds and on all rows with every free parameter (started
    /// from the shortlist's fits), side by side; the fit on all rows with standard errors.
    /// A further finalist only while the time left holds the last one's time; with the
    /// number of finalists left out for the time bound.
    pub(super) fn final_fits(
        &self,
        short: &[Shortlisted],
        list: &[usize],
        screened: &[Screened],
        groups: &[Target],
        folds: &[Fold],
    ) -> (Vec<Final>, usize) {
        let mean = self.test_mean(folds);
        let opts = self.fit_opts();
        let all_opts = FitOptions {
            skip_uncertainties: false,
            ..opts
        };
        let nf = folds.len();
        let mut out = Vec::new();
        let mut last = 0.0;
        for (done, &j) in list.iter().enumerate() {
            if done > 0 && self.left() < last {
                return (out, list.len() - done);
            }
            let began = self.elapsed();
            let sh = &short[j];
            let t = groups[screened[sh.screened].plan.group];
            self.tick(
                "search: the finalists with every free parameter",
                done,
                list.len(),
            );
            let jobs = side_by_side(nf + 1, self.threads, &|k, inner| {
                // the fit on all rows starts from fold 0's
                let start = &sh.configs[k.min(nf - 1)];
                let free = form_free(start, self.base_free, t, true);
                if k == nf {
                    return Job::All(Box::new(fit_params_with(
                        start,
                        self.data,
                        &free,
                        inner,
                        &all_opts,
                        &|_| {},
                    )));
                }
                Job::Fold(
                    self.fold_fit(&folds[k], start, &free, inner, &opts)
                        .map(|(r, _)| r),
                )
            });
            let (mut resid, mut fit, mut failed) = (Vec::new(), None, false);
            for job in jobs {
                match job {
                    Job::Fold(Ok(r)) => resid.extend(r),
                    Job::Fold(Err(_)) => failed = true,
                    Job::All(r) => fit = (*r).ok(),
                }
            }
            if let (false, Some(fit)) = (failed, fit) {
                out.push(Final {
                    short: j,
                    cv: cv_of(&resid, mean),
                    resid,
                    fit,
                });
            }
            last = self.elapsed() - began;
        }
        (out, 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_form_on_a_target_gets_a_name_of_its_own_and_the_file_reads_back() {
        let cfg = Config::preset("dry").expect("preset");
        let v = Var {
            expr: "v_mps".into(),
            r: 15.0,
            s: 8.165,
            min: 5.0,
            positive: true,
            x: vec![5.0, 15.0, 25.0],
        };
        let (one, _) = with_form(&cfg, &[], Target::Strengths, Shape::Linear, &v, &[0.1], 0.0)
            .expect("first form");
        let (two, free) = with_form(&one, &[], Target::Strengths, Shape::Exp, &v, &[0.2], 0.0)
            .expect("second form");
        let names: Vec<&str> = two.modifiers.iter().map(|m| m.name()).collect();
        assert_eq!(names, ["form_strengths", "form_strengths_2"]);
        assert_eq!(free.len(), 1);
        // the configuration `--out` writes is one a second run reads
        let text = two.to_json().to_string();
        let back = Config::from_json_str(&text, "proposed.json").expect("reads back");
        let back_names: Vec<&str> = back.modifiers.iter().map(|m| m.name()).collect();
        assert_eq!(back_names, names);
    }
}
