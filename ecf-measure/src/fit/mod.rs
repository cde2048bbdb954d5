//! Bounded nonlinear least squares of model parameters against measurements (seed Eq. 5.1) with Levenberg-Marquardt on nalgebra.
//!
//! Minimizes sum((f_model - f_measured)^2), i.e. the RMSE of Eq. 5.1, over the free
//! parameters. Bounds are kept by a change of variables: p = lo + exp(z) for a parameter
//! bounded below only (or with an upper bound far above its value), and a logistic map for a
//! finite interval. The Jacobian is a forward difference in z. Standard errors come from the
//! covariance s^2 (J^T J)^-1 in parameter units at the optimum, s^2 = RSS/(n - k).
//!
//! A fit never ends worse than it started: a start on (or within a thousandth of
//! the interval of) a bound, where the change of variables has no slope, begins a little
//! inside; a result stuck at a bound is fitted again with that parameter on the bound and
//! kept there when the data push it outward (moving it inside makes the fit worse); a
//! result stuck at a bound that does not hold it, or worse than the start, is tried again
//! from several starts spread over the bounds ([`STARTS`]) and the best is kept; a parameter ending next
//! to its bound is set on the bound when that is no worse (status `at_lower_bound` /
//! `at_upper_bound`); a best result still worse than the start is a failed fit.

mod free;
mod map;
mod problem;
mod uncertainty;

pub use free::FreeParam;
pub use map::STARTS;

use crate::evaluate::{predict_with, Memo};
use crate::measure::Dataset;
use crate::stats::cv_rmse_pct;
use creep_core::config::{Config, ModelKind};
use creep_core::effects::Effect;
use creep_core::error::{CreepError, Result};
use creep_core::params::P;
use levenberg_marquardt::LevenbergMarquardt;
use map::{Bound, Map, NEAR};
use nalgebra::DVector;
use problem::Problem;
use uncertainty::uncertainties;

/// Relative difference of two CV(RMSE) values that counts as rounding: setting a parameter
/// that is next to its bound onto the bound is kept when its CV(RMSE) is no worse by more.
const ROUNDING: f64 = 1e-12;

/// Relative rise of the CV(RMSE) that a step off a bound must exceed for the bound to count as
/// the optimum ([`Solver::bounds_hold`]): smaller rises are a plateau, not a push outward.
const PLATEAU: f64 = 1e-6;

/// What the data say about a fitted parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ParamStatus {
    /// Determined by the data: finite standard error.
    Determined,
    /// At its lower bound: the data push it further; no standard error.
    AtLowerBound,
    /// At its upper bound.
    AtUpperBound,
    /// The data do not determine it (the model does not depend on it, or only through a
    /// combination with other free parameters): infinite standard error.
    NotIdentifiable,
}

impl ParamStatus {
    /// Words for reports.
    pub fn note(&self) -> &'static str {
        match self {
            ParamStatus::Determined => "",
            ParamStatus::AtLowerBound => "at its lower bound",
            ParamStatus::AtUpperBound => "at its upper bound",
            ParamStatus::NotIdentifiable => "not identifiable from these data",
        }
    }
}

/// One fitted parameter.
#[derive(Clone, Debug)]
pub struct FittedParam {
    /// Name as `--free` takes it (registry name or `EFFECT.PARAM`).
    pub name: String,
    /// Value before the fit, display unit.
    pub start: f64,
    /// Fitted value, display unit.
    pub value: f64,
    /// Standard error, display unit (NaN when skipped, inf when not identifiable).
    pub stderr: f64,
}

/// The result of a fit.
#[derive(Clone, Debug)]
pub struct FitResult {
    /// Status of each free parameter (order of `params`); empty when the fit skipped the
    /// uncertainties ([`FitOptions::skip_uncertainties`]).
    pub status: Vec<ParamStatus>,
    /// Warnings: fitted values outside their plausible physical range, solver stops that are
    /// not convergence.
    pub warnings: Vec<String>,
    /// The fitted configuration.
    pub config: Config,
    /// CV(RMSE) before the fit, %.
    pub cv_rmse_pct_before: f64,
    /// CV(RMSE) after the fit, %.
    pub cv_rmse_pct_after: f64,
    /// Free parameters with their start and fitted values, display units.
    pub params: Vec<FittedParam>,
    /// Correlation matrix of the free parameters (empty when the uncertainties were skipped).
    pub correlation: Vec<Vec<f64>>,
    /// Residual evaluations used.
    pub evaluations: usize,
    /// Why the solver stopped (in the run kept).
    pub termination: String,
    /// Solver runs: 1; 2 when the first ended stuck at a bound that holds the optimum (the
    /// run with the parameter on the bound); more when the fit was tried again from spread
    /// starts ([`STARTS`]).
    pub starts: usize,
}

/// One solver run's end.
struct Run {
    config: Config,
    values: Vec<f64>,
    cv: f64,
    /// Why the solver stopped, in words.
    termination: String,
    /// The solver stopped without meeting its convergence tolerances.
    unconverged: bool,
}

/// Parameters fitted when the user names none: the layer strengths and hardening scale
/// (plus their temperature coefficients when `temperature` is on) for ECF, mu for FASTSIM,
/// the five Polach coefficients for Polach.
pub fn default_free(cfg: &Config) -> Vec<P> {
    match cfg.model {
        ModelKind::Polach => vec![P::PolMu0, P::PolA, P::PolB, P::PolKA, P::PolKS],
        _ if cfg.has(Effect::Coulomb) => vec![P::Mu],
        _ => {
            let mut v = vec![P::Tc10, P::Tc20, P::Lp0];
            if cfg.has(Effect::Temperature) {
                v.extend([P::Tc1T, P::Tc2T]);
            }
            v
        }
    }
}

/// Model values for the measured points under a configuration.
pub type ModelFn<'a> = &'a (dyn Fn(&Config) -> Result<Vec<f64>> + Sync);

/// Fits the parameters `free` of `cfg` to `data`. `progress` is called with the number of
/// model evaluations so far.
pub fn fit(
    cfg: &Config,
    data: &Dataset,
    free: &[P],
    threads: usize,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<FitResult> {
    let refs: Vec<FreeParam> = free.iter().map(|p| FreeParam::Builtin(*p)).collect();
    fit_params(cfg, data, &refs, threads, progress)
}

/// Like [`fit`], for registry and formula parameters.
pub fn fit_params(
    cfg: &Config,
    data: &Dataset,
    free: &[FreeParam],
    threads: usize,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<FitResult> {
    fit_params_with(cfg, data, free, threads, &FitOptions::default(), progress)
}

/// How a fit runs beyond its free parameters (the default: as [`fit_params`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct FitOptions<'a> {
    /// Skip the standard errors and correlations (two model evaluations per free parameter
    /// at the optimum): `status` and `correlation` of the result are then empty and the
    /// standard errors NaN. The fitted values are the same.
    pub skip_uncertainties: bool,
    /// Look model values up in this memo and add the computed ones
    /// ([`crate::evaluate::predict_with`]); the result is bit-identical.
    pub memo: Option<&'a Memo>,
    /// Relative tolerances of the solver's convergence tests (`ftol`: reduction of the sum of
    /// squares, `xtol`: step relative to the scaled parameters); `None`: the solver's
    /// default, 30 machine epsilons. A looser tolerance stops the same iterations earlier.
    pub tolerance: Option<f64>,
}

/// The configuration fitted to a training fold, or `cfg` itself where the fit fails (no
/// start improves on the given values, or the fold's CV(RMSE) is not finite): a held-out
/// score then scores the values as given on that fold instead of ending the whole run.
pub fn fitted_or_kept(
    cfg: &Config,
    data: &Dataset,
    free: &[FreeParam],
    threads: usize,
    opts: &FitOptions,
) -> Result<Config> {
    match fit_params_with(cfg, data, free, threads, opts, &|_| {}) {
        Ok(r) => Ok(r.config),
        Err(CreepError::Fit(_)) => Ok(cfg.clone()),
        Err(e) => Err(e),
    }
}

/// [`fit_params`] with options.
pub fn fit_params_with(
    cfg: &Config,
    data: &Dataset,
    free: &[FreeParam],
    threads: usize,
    opts: &FitOptions,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<FitResult> {
    let meas: Vec<f64> = data.rows.iter().map(|r| r.f).collect();
    let memo = opts.memo;
    let model = |c: &Config| -> Result<Vec<f64>> {
        Ok(predict_with(c, data, threads, memo)?
            .iter()
            .map(|p| p.f)
            .collect())
    };
    fit_generic_with(cfg, &data.source, &meas, &model, free, opts, progress)
}

/// Bounded least squares of `model(cfg)` against `meas` over the free parameters.
pub fn fit_generic(
    cfg: &Config,
    source: &str,
    meas: &[f64],
    model: ModelFn,
    free: &[FreeParam],
    progress: &(dyn Fn(usize) + Sync),
) -> Result<FitResult> {
    fit_generic_with(
        cfg,
        source,
        meas,
        model,
        free,
        &FitOptions::default(),
        progress,
    )
}

/// [`fit_generic`] with options (`opts.memo` is not used here: `model` is the caller's).
pub fn fit_generic_with(
    cfg: &Config,
    source: &str,
    meas: &[f64],
    model: ModelFn,
    free: &[FreeParam],
    opts: &FitOptions,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<FitResult> {
    if free.is_empty() {
        return Err(CreepError::Config {
            source_name: "--free".into(),
            message: "no parameter to fit".into(),
        });
    }
    if meas.len() <= free.len() {
        return Err(CreepError::Data {
            source_name: source.into(),
            message: format!(
                "{} rows cannot determine {} parameters",
                meas.len(),
                free.len()
            ),
        });
    }
    let start: Vec<f64> = free.iter().map(|id| id.get(cfg)).collect();
    let (maps, s0): (Vec<Map>, Vec<f64>) = free
        .iter()
        .zip(&start)
        .map(|(id, s)| Map::new(id.bounds(cfg), *s))
        .unzip();
    let before = model(cfg)?;
    let cv_before = cv_rmse_pct(meas, &before);
    if !cv_before.is_finite() {
        let mean = crate::stats::mean(meas);
        return Err(CreepError::Fit(format!(
            "CV(RMSE) of {source} is not finite before the fit ({cv_before}): the mean measured traction coefficient is {mean}; CV(RMSE) divides by it"
        )));
    }
    let mut lm = LevenbergMarquardt::new().with_patience(30);
    if let Some(t) = opts.tolerance {
        lm = lm.with_ftol(t).with_xtol(t);
    }
    let solver = Solver {
        cfg,
        meas,
        model,
        free,
        maps,
        s0,
        progress,
        evals: std::cell::Cell::new(0),
        lm,
    };
    // worse than the start beyond the last digits of the sum of squares
    let worse = |cv: f64| cv.is_nan() || cv > cv_before * (1.0 + 1e-9);
    let (best, starts) = solver.best_of_starts(worse)?;
    let best = solver.onto_bounds(best)?;
    if worse(best.cv) {
        return Err(CreepError::Fit(format!(
            "it ended worse than it started: CV(RMSE) {:.4} % at the best of {starts} start(s) against {:.4} % at the start values ({}); the configuration is left as it was",
            best.cv,
            cv_before,
            free.iter()
                .zip(&start)
                .map(|(id, s)| format!("{} = {s}", id.name(cfg)))
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    solver.result(best, cv_before, &start, starts, opts)
}

/// One fit's data, free parameters, maps and solver, and its count of model evaluations.
struct Solver<'a> {
    cfg: &'a Config,
    meas: &'a [f64],
    model: ModelFn<'a>,
    free: &'a [FreeParam],
    maps: Vec<Map>,
    /// Where the solver starts (the start values, moved inside where they lie on a bound).
    s0: Vec<f64>,
    progress: &'a (dyn Fn(usize) + Sync),
    evals: std::cell::Cell<usize>,
    lm: LevenbergMarquardt<f64>,
}

impl Solver<'_> {
    /// One solver run from the values `x0` (parameter units).
    fn run(&self, x0: &[f64]) -> Result<Run> {
        let free = self.free;
        let z0 = DVector::from_iterator(
            free.len(),
            self.maps.iter().zip(x0).map(|(m, s)| m.to_z(*s)),
        );
        let problem = Problem {
            base: self.cfg.clone(),
            meas: self.meas.to_vec(),
            model: self.model,
            free: free.to_vec(),
            maps: self.maps.clone(),
            z: z0,
            progress: self.progress,
            evals: &self.evals,
            error: std::cell::RefCell::new(None),
            last: std::cell::RefCell::new(None),
        };
        let (problem, report) = self.lm.minimize(problem);
        if let Some(e) = problem.error.borrow_mut().take() {
            return Err(match e {
                CreepError::Fit(m) => CreepError::Fit(m),
                other => CreepError::Fit(other.to_string()),
            });
        }
        use levenberg_marquardt::TerminationReason as T;
        match &report.termination {
            T::User(m) | T::Numerical(m) => {
                return Err(CreepError::Fit(format!("the solver stopped: {m}")))
            }
            T::NoParameters | T::NoResiduals | T::WrongDimensions(_) => {
                return Err(CreepError::Fit(format!(
                    "the solver stopped: {:?}",
                    report.termination
                )))
            }
            _ => {}
        }
        let config = problem.config_at(&problem.z)?;
        let values: Vec<f64> = (self.model)(&config).map_err(|e| CreepError::Fit(e.to_string()))?;
        let cv = cv_rmse_pct(self.meas, &values);
        Ok(Run {
            config,
            values,
            cv,
            termination: format!("{:?}", report.termination),
            unconverged: matches!(
                report.termination,
                T::LostPatience | T::NoImprovementPossible(_)
            ),
        })
    }

    /// The bound each parameter of `c` is stuck at, if any.
    fn stuck_at(&self, c: &Config) -> Vec<Option<Bound>> {
        self.free
            .iter()
            .enumerate()
            .map(|(k, id)| self.maps[k].stuck(id.get(c), id.bounds(self.cfg), self.s0[k]))
            .collect()
    }

    /// The first run; when it ends stuck at a bound, the run on the bound
    /// ([`Self::polish_at_bounds`]), kept if the bound holds ([`Self::bounds_hold`]);
    /// otherwise, or when `worse` than the start, the best of these and the runs from
    /// [`STARTS`]; with the number of runs.
    fn best_of_starts(&self, worse: impl Fn(f64) -> bool) -> Result<(Run, usize)> {
        let free = self.free;
        let mut best = self.run(&self.s0)?;
        let mut starts = 1;
        let stuck = self.stuck_at(&best.config);
        let any_stuck = stuck.iter().any(Option::is_some);
        if any_stuck && !worse(best.cv) {
            // a bound that holds the optimum needs no search elsewhere: the stuck parameters
            // on their bounds, the others fitted again there, and every stuck one pushed
            // outward by the data (the bound's optimality condition)
            // the run on the bound counts as a start, also where the model fails in it
            starts += 1;
            if let Some(p) = self.polish_at_bounds(&best, &stuck)? {
                // no worse than the first end beyond rounding (a first end within 1e-15 of the
                // bound can be better in its last bits, as in `onto_bounds`)
                let holds = p.cv <= best.cv * (1.0 + ROUNDING) && self.bounds_hold(&p, &stuck);
                if p.cv < best.cv {
                    best = p;
                }
                if holds {
                    return Ok((best, starts));
                }
            }
        }
        if any_stuck || worse(best.cv) {
            // again from starts spread over the bounds: the stuck parameters alone (the others
            // from where the first run left them), or all of them when the result is worse
            let grids: Vec<Vec<f64>> = self
                .maps
                .iter()
                .zip(&self.s0)
                .map(|(m, s)| m.starts(*s))
                .collect();
            let from: Vec<f64> = free.iter().map(|id| id.get(&best.config)).collect();
            let xs: Vec<Vec<f64>> = (0..STARTS.len())
                .map(|j| {
                    (0..free.len())
                        .map(|k| {
                            if !any_stuck || stuck[k].is_some() {
                                grids[k][j]
                            } else {
                                from[k]
                            }
                        })
                        .collect()
                })
                .collect();
            for x in xs {
                starts += 1;
                // a start from which the model fails is passed over: the first run stands
                if let Ok(r) = self.run(&x) {
                    if r.cv < best.cv {
                        best = r;
                    }
                }
            }
        }
        Ok((best, starts))
    }

    /// The fit with each stuck parameter (`stuck`) set onto its bound and the others run again
    /// from where `first` left them (the stuck ones alone: no run, the model at the bounds);
    /// None where the model fails there.
    fn polish_at_bounds(&self, first: &Run, stuck: &[Option<Bound>]) -> Result<Option<Run>> {
        let mut cfg = first.config.clone();
        let (mut free, mut maps, mut s0) = (Vec::new(), Vec::new(), Vec::new());
        for (k, id) in self.free.iter().enumerate() {
            match stuck[k] {
                Some(b) => {
                    let v = b.of(id.bounds(self.cfg));
                    if !v.is_finite() {
                        return Ok(None);
                    }
                    id.set(&mut cfg, v)?;
                }
                None => {
                    free.push(*id);
                    maps.push(self.maps[k]);
                    s0.push(self.s0[k]);
                }
            }
        }
        if free.is_empty() {
            return Ok(self.evaluated(cfg, first));
        }
        let x0: Vec<f64> = free.iter().map(|id| id.get(&cfg)).collect();
        let reduced = Solver {
            cfg: &cfg,
            meas: self.meas,
            model: self.model,
            free: &free,
            maps,
            s0,
            progress: self.progress,
            evals: std::cell::Cell::new(self.evals.get()),
            lm: self.lm,
        };
        let run = reduced.run(&x0);
        self.evals.set(reduced.evals.get());
        Ok(run.ok())
    }

    /// True if, at `at` (stuck parameters on their bounds), moving any stuck parameter off its
    /// bound by the stuck distance (a thousandth of its interval, or of the start's distance
    /// from a lower bound) makes the fit worse: the data push it outward.
    fn bounds_hold(&self, at: &Run, stuck: &[Option<Bound>]) -> bool {
        self.free.iter().enumerate().all(|(k, id)| {
            let Some(b) = stuck[k] else { return true };
            let (lo, hi) = id.bounds(self.cfg);
            let step = match self.maps[k] {
                Map::Logistic { lo, hi } => NEAR * (hi - lo),
                Map::Exp { lo } => NEAR * (self.s0[k] - lo),
                Map::Identity => return false,
            };
            let v = if b == Bound::Lower {
                lo + step
            } else {
                hi - step
            };
            let mut c = at.config.clone();
            if id.set(&mut c, v).is_err() {
                return false;
            }
            // worse beyond the last digits: on a plateau (a bound far out, where the model no
            // longer depends on the parameter) the bound is no optimum of the data
            self.evaluated(c, at)
                .is_some_and(|r| r.cv > at.cv * (1.0 + PLATEAU))
        })
    }

    /// The model at `config`, counted as one evaluation, as a run that stopped as `like` did;
    /// None where the model fails there.
    fn evaluated(&self, config: Config, like: &Run) -> Option<Run> {
        self.evals.set(self.evals.get() + 1);
        let values = (self.model)(&config).ok()?;
        let cv = cv_rmse_pct(self.meas, &values);
        Some(Run {
            config,
            values,
            cv,
            termination: like.termination.clone(),
            unconverged: like.unconverged,
        })
    }

    /// `best` with each parameter next to its bound set onto it where that is no worse (within
    /// [`ROUNDING`] relative of the best CV(RMSE)).
    fn onto_bounds(&self, mut best: Run) -> Result<Run> {
        let free = self.free;
        for (k, b) in self.stuck_at(&best.config).into_iter().enumerate() {
            let Some(b) = b else { continue };
            let v = b.of(free[k].bounds(self.cfg));
            if !v.is_finite() || free[k].get(&best.config) == v {
                continue;
            }
            let mut c = best.config.clone();
            free[k].set(&mut c, v)?;
            if let Some(r) = self.evaluated(c, &best) {
                // no worse beyond rounding: a parameter within 1e-15 of its bound can move the
                // model's values in their last bits either way (measured: 6e-15 relative)
                if r.cv <= best.cv * (1.0 + ROUNDING) {
                    best = r;
                }
            }
        }
        Ok(best)
    }

    /// The result of the run kept: its uncertainties (unless skipped) and warnings.
    fn result(
        &self,
        best: Run,
        cv_before: f64,
        start: &[f64],
        starts: usize,
        opts: &FitOptions,
    ) -> Result<FitResult> {
        let (cfg, free) = (self.cfg, self.free);
        let mut warnings = Vec::new();
        if best.unconverged {
            warnings.push(format!(
                "the solver stopped without meeting its convergence tolerances ({}); the result is the best point found",
                best.termination
            ));
        }
        let Run {
            config: fitted,
            values: model_values,
            cv: cv_after,
            termination,
            ..
        } = best;
        if !cv_after.is_finite() {
            return Err(CreepError::Fit(format!(
                "CV(RMSE) after the fit is not finite ({cv_after})"
            )));
        }
        let values: Vec<f64> = free.iter().map(|id| id.get(&fitted)).collect();
        let (status, stderr, corr, n_unc) = if opts.skip_uncertainties {
            (Vec::new(), vec![f64::NAN; free.len()], Vec::new(), 0)
        } else {
            uncertainties(&fitted, self.meas, &model_values, self.model, free, start)?
        };
        for (k, id) in free.iter().enumerate() {
            if let Some((lo, hi)) = id.plausible() {
                if values[k] < lo || values[k] > hi {
                    warnings.push(format!(
                        "{} = {} {} is outside its plausible physical range [{lo}, {hi}]: check the data, or narrow its bounds (--bound {}=MIN:MAX)",
                        id.name(cfg),
                        values[k],
                        id.unit(),
                        id.name(cfg)
                    ));
                }
            }
        }
        let params = free
            .iter()
            .enumerate()
            .map(|(k, id)| FittedParam {
                name: id.name(cfg),
                start: start[k],
                value: values[k],
                stderr: stderr[k],
            })
            .collect();
        Ok(FitResult {
            status,
            warnings,
            config: fitted,
            cv_rmse_pct_before: cv_before,
            cv_rmse_pct_after: cv_after,
            params,
            correlation: corr,
            evaluations: self.evals.get() + n_unc,
            termination,
            starts,
        })
    }
}
