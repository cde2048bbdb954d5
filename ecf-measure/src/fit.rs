//! Bounded nonlinear least squares of model parameters against measurements (seed Eq. 5.1) with Levenberg-Marquardt on nalgebra.
//!
//! Minimizes sum((f_model - f_measured)^2), i.e. the RMSE of Eq. 5.1, over the free
//! parameters. Bounds are kept by a change of variables: p = lo + exp(z) for a parameter
//! bounded below only (or with an upper bound far above its value), and a logistic map for a
//! finite interval. The Jacobian is a forward difference in z. Standard errors come from the
//! covariance s^2 (J^T J)^-1 in parameter units at the optimum, s^2 = RSS/(n - k).
//!
//! A fit never ends worse than it started (issue 26): a start on (or within a thousandth of
//! the interval of) a bound, where the change of variables has no slope, begins a little
//! inside; a result stuck at a bound, or worse than the start, is tried again from several
//! starts spread over the bounds ([`STARTS`]) and the best is kept; a parameter ending next
//! to its bound is set on the bound when that is no worse (status `at_lower_bound` /
//! `at_upper_bound`); a best result still worse than the start is a failed fit.

use crate::evaluate::{predict_with, Memo};
use crate::measure::Dataset;
use crate::stats::cv_rmse_pct;
use creep_core::config::{Config, ModelKind};
use creep_core::effects::Effect;
use creep_core::error::{CreepError, Result};
use creep_core::params::{spec, P};
use creep_core::Modifier;

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{storage::Owned, DMatrix, DVector, Dyn};

/// A parameter that can be fitted: one of the registry's, or a modifier's own (a formula
/// or Rust effect, module [`creep_core::modifier`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FreeParam {
    /// A registry parameter.
    Builtin(P),
    /// Parameter `param` of modifier `effect` (indices into `Config::modifiers`).
    Modifier {
        /// Index of the modifier.
        effect: usize,
        /// Index of its parameter.
        param: usize,
    },
}

impl From<P> for FreeParam {
    fn from(p: P) -> Self {
        FreeParam::Builtin(p)
    }
}

impl FreeParam {
    /// Name: the registry name, or `EFFECT.PARAM` for a modifier's parameter.
    pub fn name(&self, cfg: &Config) -> String {
        match *self {
            FreeParam::Builtin(p) => spec(p).name.to_string(),
            FreeParam::Modifier { effect, param } => {
                let m = &cfg.modifiers[effect];
                format!("{}.{}", m.name(), m.param(param).name)
            }
        }
    }
    /// Current value (display unit).
    pub fn get(&self, cfg: &Config) -> f64 {
        match *self {
            FreeParam::Builtin(p) => cfg.params.get(p),
            FreeParam::Modifier { effect, param } => cfg.modifiers[effect].param(param).value,
        }
    }
    /// Bounds (display unit): the registry's or the effect's, narrowed by the user.
    pub fn bounds(&self, cfg: &Config) -> (f64, f64) {
        match *self {
            FreeParam::Builtin(p) => cfg.params.bounds(p),
            FreeParam::Modifier { effect, param } => {
                let q = cfg.modifiers[effect].param(param);
                (q.min, q.max)
            }
        }
    }
    /// Narrows the bounds for a fit (`--bound NAME=MIN:MAX`): within the parameter's own
    /// bounds, with the current value inside.
    pub fn set_bounds(&self, cfg: &mut Config, lo: f64, hi: f64) -> Result<()> {
        let name = self.name(cfg);
        let (olo, ohi) = match *self {
            FreeParam::Builtin(p) => (spec(p).min, spec(p).max),
            FreeParam::Modifier { effect, param } => cfg.modifiers[effect].param(param).limits,
        };
        let v = self.get(cfg);
        if lo.is_nan() || hi.is_nan() || lo >= hi || lo < olo || hi > ohi || v < lo || v > hi {
            return Err(CreepError::OutOfRange {
                field: format!("--bound {name}"),
                value: v,
                expected: format!(
                    "need min < max within [{olo}, {ohi}] and the current value inside [{lo}, {hi}]"
                ),
            });
        }
        match *self {
            FreeParam::Builtin(p) => cfg.params.set_bounds(p, lo, hi)?,
            FreeParam::Modifier { effect, param } => {
                cfg.modifiers[effect].set_bounds(param, lo, hi)
            }
        }
        Ok(())
    }
    /// Plausible physical range (registry parameters; see [`creep_core::params::plausible`]).
    pub fn plausible(&self) -> Option<(f64, f64)> {
        match *self {
            FreeParam::Builtin(p) => Some(creep_core::params::plausible(p)),
            _ => None,
        }
    }
    /// Unit (display).
    pub fn unit(&self) -> &'static str {
        match *self {
            FreeParam::Builtin(p) => spec(p).unit,
            FreeParam::Modifier { .. } => "-",
        }
    }
    fn set(&self, cfg: &mut Config, v: f64) -> Result<()> {
        match *self {
            FreeParam::Builtin(p) => cfg.params.set(p, v),
            FreeParam::Modifier { effect, param } => {
                cfg.modifiers[effect].set_param(param, v);
                Ok(())
            }
        }
    }
    /// The parameters of a comma-separated list of names ([`FreeParam::resolve`], as `--free`
    /// takes them), or `default` when no list is given.
    pub fn list(cfg: &Config, names: Option<&str>, default: Vec<P>) -> Result<Vec<FreeParam>> {
        match names {
            Some(list) => list
                .split(',')
                .map(|n| FreeParam::resolve(cfg, n.trim()))
                .collect(),
            None => Ok(default.into_iter().map(FreeParam::Builtin).collect()),
        }
    }
    /// Resolves a name: a registry parameter, `EFFECT.PARAM`, or a formula effect's parameter
    /// name alone where it is unique among the formula effects.
    pub fn resolve(cfg: &Config, name: &str) -> Result<FreeParam> {
        if let Some(p) = creep_core::params::by_name(name) {
            return Ok(FreeParam::Builtin(p));
        }
        let mut found = Vec::new();
        for (e, m) in cfg.modifiers.iter().enumerate() {
            // a formula parameter may be named alone (formulas name their own parameters;
            // a Rust effect's are named by its author, so they need the effect's name)
            let bare = matches!(m, creep_core::AnyModifier::Formula(_));
            for k in 0..m.n_params() {
                let q = m.param(k).name;
                if name == format!("{}.{q}", m.name()) || (bare && name == q) {
                    found.push(FreeParam::Modifier {
                        effect: e,
                        param: k,
                    });
                }
            }
        }
        match found.len() {
            1 => Ok(found[0]),
            0 => Err(CreepError::Unknown {
                kind: "parameter".into(),
                name: name.into(),
                accepted: creep_core::params::SPECS
                    .iter()
                    .map(|s| s.name.to_string())
                    .chain(cfg.modifiers.iter().flat_map(|m| {
                        (0..m.n_params()).map(move |k| format!("{}.{}", m.name(), m.param(k).name))
                    }))
                    .collect::<Vec<_>>()
                    .join(", "),
            }),
            _ => Err(CreepError::Config {
                source_name: "--free".into(),
                message: format!("'{name}' is ambiguous; write EFFECT.PARAM"),
            }),
        }
    }
}

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
    /// Solver runs: 1, or more when the first ended stuck at a bound or worse than its start
    /// and the fit was tried again from spread starts ([`STARTS`]).
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

/// Fractions of the interval (logistic map) from which a fit stuck at a bound, or worse than
/// its start, is tried again; for a parameter bounded below only, the distances from the
/// bound are the start's times 10^(-1), 10 and 100.
pub const STARTS: [f64; 3] = [0.1, 0.5, 0.9];

/// A fitted value this close to a bound (fraction of the interval, or of the start's distance
/// from a lower bound) counts as stuck there.
const NEAR: f64 = 1e-3;

#[derive(Clone, Copy, Debug)]
enum Map {
    Identity,
    Exp { lo: f64 },
    Logistic { lo: f64, hi: f64 },
}

impl Map {
    /// Exponential map for a lower bound only (or an upper bound three orders of magnitude
    /// above the start), logistic for a finite interval, identity when unbounded. Returns the
    /// map and the value the solver starts from: the start itself, or, where the start lies on
    /// a bound or within [`NEAR`] of it (the map has no slope there, so the solver could not
    /// move), a point a hundredth of the interval inside (for a lower bound with no finite
    /// upper bound near: a hundredth of max(|lower bound|, 1) above it).
    fn new((lo, hi): (f64, f64), start: f64) -> (Self, f64) {
        let far = |h: f64| h.is_infinite() || h >= 1e3 * start.abs().max(lo.abs()).max(1e-12);
        if lo.is_finite() && start > lo && far(hi) {
            (Map::Exp { lo }, start)
        } else if lo.is_finite() && hi.is_finite() && hi > lo {
            let w = hi - lo;
            if start <= lo && w > 1e3 * lo.abs().max(1.0) {
                // on the lower bound of a very wide interval: a hundredth of the interval
                // would be far off any value of interest
                return (Map::Exp { lo }, lo + 1e-2 * lo.abs().max(1.0));
            }
            let r = ((start - lo) / w).clamp(0.0, 1.0);
            let s = if r < NEAR {
                lo + 1e-2 * w
            } else if r > 1.0 - NEAR {
                hi - 1e-2 * w
            } else {
                start
            };
            (Map::Logistic { lo, hi }, s)
        } else if lo.is_finite() && start <= lo {
            (Map::Exp { lo }, lo + 1e-2 * lo.abs().max(1.0))
        } else {
            (Map::Identity, start)
        }
    }
    fn to_p(self, z: f64) -> f64 {
        match self {
            Map::Identity => z,
            Map::Exp { lo } => lo + z.exp(),
            Map::Logistic { lo, hi } => lo + (hi - lo) / (1.0 + (-z).exp()),
        }
    }
    fn to_z(self, p: f64) -> f64 {
        match self {
            Map::Identity => p,
            Map::Exp { lo } => (p - lo).max(1e-12).ln(),
            Map::Logistic { lo, hi } => {
                let r = ((p - lo) / (hi - lo)).clamp(1e-9, 1.0 - 1e-9);
                (r / (1.0 - r)).ln()
            }
        }
    }
    /// The bound `p` is stuck at, if any: on or beyond it, or within [`NEAR`] of the interval
    /// (logistic) or of the solver's start's distance `s0 - lo` (exponential).
    fn stuck(self, p: f64, (lo, hi): (f64, f64), s0: f64) -> Option<Bound> {
        if p <= lo {
            return Some(Bound::Lower);
        }
        if p >= hi {
            return Some(Bound::Upper);
        }
        match self {
            Map::Logistic { lo, hi } => {
                let r = (p - lo) / (hi - lo);
                if r < NEAR {
                    Some(Bound::Lower)
                } else if r > 1.0 - NEAR {
                    Some(Bound::Upper)
                } else {
                    None
                }
            }
            Map::Exp { lo } => (p - lo < NEAR * (s0 - lo)).then_some(Bound::Lower),
            Map::Identity => None,
        }
    }
    /// The solver's other starts ([`STARTS`]), from the first start `s0`.
    fn starts(self, s0: f64) -> Vec<f64> {
        match self {
            Map::Logistic { lo, hi } => STARTS.iter().map(|f| lo + f * (hi - lo)).collect(),
            Map::Exp { lo } => [0.1, 10.0, 100.0]
                .iter()
                .map(|f| lo + f * (s0 - lo))
                .collect(),
            Map::Identity => {
                let d = s0.abs().max(1.0);
                vec![s0 - d, s0 + d, s0 + 10.0 * d]
            }
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Bound {
    Lower,
    Upper,
}

/// Model values for the measured points under a configuration.
pub type ModelFn<'a> = &'a (dyn Fn(&Config) -> Result<Vec<f64>> + Sync);

struct Problem<'a> {
    base: Config,
    meas: Vec<f64>,
    model: ModelFn<'a>,
    free: Vec<FreeParam>,
    maps: Vec<Map>,
    z: DVector<f64>,
    progress: &'a (dyn Fn(usize) + Sync),
    evals: &'a std::cell::Cell<usize>,
    error: std::cell::RefCell<Option<CreepError>>,
    /// The last point evaluated and its residuals: the Jacobian at the current point reuses
    /// them (the solver asks for the residuals at a point before the Jacobian there).
    last: std::cell::RefCell<Option<(DVector<f64>, DVector<f64>)>>,
}

impl Problem<'_> {
    fn config_at(&self, z: &DVector<f64>) -> Result<Config> {
        let mut c = self.base.clone();
        for (k, id) in self.free.iter().enumerate() {
            let (lo, hi) = id.bounds(&self.base);
            let v = self.maps[k].to_p(z[k]).clamp(lo, hi);
            id.set(&mut c, v)?;
        }
        Ok(c)
    }
    fn residuals_at(&self, z: &DVector<f64>) -> Option<DVector<f64>> {
        let n = self.evals.get() + 1;
        self.evals.set(n);
        (self.progress)(n);
        let r = self.config_at(z).and_then(|c| (self.model)(&c));
        match r {
            Ok(p) => {
                if let Some(k) = p.iter().position(|x| !x.is_finite()) {
                    *self.error.borrow_mut() = Some(CreepError::Fit(format!(
                        "the model value of point {} is {} at {}",
                        k + 1,
                        p[k],
                        self.describe(z)
                    )));
                    return None;
                }
                let r =
                    DVector::from_iterator(p.len(), p.iter().zip(&self.meas).map(|(m, y)| m - y));
                *self.last.borrow_mut() = Some((z.clone(), r.clone()));
                Some(r)
            }
            Err(e) => {
                *self.error.borrow_mut() = Some(e);
                None
            }
        }
    }
}

impl Problem<'_> {
    fn describe(&self, z: &DVector<f64>) -> String {
        self.free
            .iter()
            .enumerate()
            .map(|(k, id)| format!("{} = {}", id.name(&self.base), self.maps[k].to_p(z[k])))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;
    fn set_params(&mut self, x: &DVector<f64>) {
        self.z.copy_from(x);
    }
    fn params(&self) -> DVector<f64> {
        self.z.clone()
    }
    fn residuals(&self) -> Option<DVector<f64>> {
        self.residuals_at(&self.z)
    }
    fn jacobian(&self) -> Option<DMatrix<f64>> {
        // the residuals at the current point: those of the last evaluation when it was at
        // exactly this point (bit for bit), as the model is a function of the point alone
        let cached = self.last.borrow().as_ref().and_then(|(z, r)| {
            let same = z.len() == self.z.len()
                && z.iter()
                    .zip(self.z.iter())
                    .all(|(a, b)| a.to_bits() == b.to_bits());
            same.then(|| r.clone())
        });
        let r0 = match cached {
            Some(r) => r,
            None => self.residuals_at(&self.z)?,
        };
        let mut j = DMatrix::zeros(r0.len(), self.z.len());
        for k in 0..self.z.len() {
            let h = 1e-3 * self.z[k].abs().max(1.0);
            let mut z = self.z.clone();
            z[k] += h;
            let r = self.residuals_at(&z)?;
            j.set_column(k, &((r - &r0) / h));
        }
        Some(j)
    }
}

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
    let evals = std::cell::Cell::new(0);
    let mut lm = LevenbergMarquardt::new().with_patience(30);
    if let Some(t) = opts.tolerance {
        lm = lm.with_ftol(t).with_xtol(t);
    }
    // one solver run from the values x0 (parameter units)
    let run = |x0: &[f64]| -> Result<Run> {
        let z0 = DVector::from_iterator(free.len(), maps.iter().zip(x0).map(|(m, s)| m.to_z(*s)));
        let problem = Problem {
            base: cfg.clone(),
            meas: meas.to_vec(),
            model,
            free: free.to_vec(),
            maps: maps.clone(),
            z: z0,
            progress,
            evals: &evals,
            error: std::cell::RefCell::new(None),
            last: std::cell::RefCell::new(None),
        };
        let (problem, report) = lm.minimize(problem);
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
        let values: Vec<f64> = model(&config).map_err(|e| CreepError::Fit(e.to_string()))?;
        let cv = cv_rmse_pct(meas, &values);
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
    };
    let stuck_at = |c: &Config| -> Vec<Option<Bound>> {
        free.iter()
            .enumerate()
            .map(|(k, id)| maps[k].stuck(id.get(c), id.bounds(cfg), s0[k]))
            .collect()
    };
    // worse than the start beyond the last digits of the sum of squares
    let worse = |cv: f64| cv.is_nan() || cv > cv_before * (1.0 + 1e-9);
    let mut best = run(&s0)?;
    let mut starts = 1;
    let stuck = stuck_at(&best.config);
    let any_stuck = stuck.iter().any(Option::is_some);
    if any_stuck || worse(best.cv) {
        // again from starts spread over the bounds: the stuck parameters alone (the others
        // from where the first run left them), or all of them when the result is worse
        let grids: Vec<Vec<f64>> = maps.iter().zip(&s0).map(|(m, s)| m.starts(*s)).collect();
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
            if let Ok(r) = run(&x) {
                if r.cv < best.cv {
                    best = r;
                }
            }
        }
    }
    // a parameter next to its bound goes onto it when that is no worse
    for (k, b) in stuck_at(&best.config).into_iter().enumerate() {
        let Some(b) = b else { continue };
        let (lo, hi) = free[k].bounds(cfg);
        let v = if b == Bound::Lower { lo } else { hi };
        if !v.is_finite() || free[k].get(&best.config) == v {
            continue;
        }
        let mut c = best.config.clone();
        free[k].set(&mut c, v)?;
        evals.set(evals.get() + 1);
        if let Ok(values) = model(&c) {
            let cv = cv_rmse_pct(meas, &values);
            if cv <= best.cv {
                best = Run {
                    config: c,
                    values,
                    cv,
                    termination: best.termination.clone(),
                    unconverged: best.unconverged,
                };
            }
        }
    }
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
        uncertainties(&fitted, meas, &model_values, model, free, &start)?
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
        evaluations: evals.get() + n_unc,
        termination,
        starts,
    })
}

type Uncertainty = (Vec<ParamStatus>, Vec<f64>, Vec<Vec<f64>>, usize);

/// Standard errors and correlations, computed the same way for every kind of parameter: the
/// Jacobian of the model values in parameter units (central differences, one-sided next to a
/// bound) at the optimum, s^2 = RSS/(n - k), covariance s^2 (J^T J)^-1 over the parameters
/// that are neither at a bound nor unidentifiable. At a bound: status AtLower/UpperBound,
/// standard error NaN. Unidentifiable (a zero Jacobian column, or a near-null direction of the
/// column-scaled J^T J, eigenvalue < 1e-10 of the largest): status NotIdentifiable, standard
/// error infinite. Correlations of excluded parameters are NaN.
fn uncertainties(
    fitted: &Config,
    meas: &[f64],
    values: &[f64],
    model: ModelFn,
    free: &[FreeParam],
    start: &[f64],
) -> Result<Uncertainty> {
    let m = free.len();
    let mut status = vec![ParamStatus::Determined; m];
    let mut evals = 0;
    let mut cols: Vec<Option<Vec<f64>>> = vec![None; m];
    for (k, id) in free.iter().enumerate() {
        let (lo, hi) = id.bounds(fitted);
        let p = id.get(fitted);
        // the width of a finite interval, unless it is far wider than the values (then the
        // values' magnitude, as for a parameter bounded below only)
        let mag = p.abs().max(start[k].abs()).max(1e-9);
        let scale = if lo.is_finite() && hi.is_finite() && hi - lo < 1e3 * mag {
            hi - lo
        } else {
            mag
        };
        let tol = 1e-4 * scale;
        if p - lo <= tol {
            status[k] = ParamStatus::AtLowerBound;
            continue;
        }
        if hi - p <= tol {
            status[k] = ParamStatus::AtUpperBound;
            continue;
        }
        let h = (1e-3 * p.abs())
            .max(1e-6 * scale)
            .min(0.5 * (p - lo))
            .min(0.5 * (hi - p));
        let eval = |x: f64| -> Result<Vec<f64>> {
            let mut c = fitted.clone();
            id.set(&mut c, x)?;
            model(&c)
                .map_err(|e| CreepError::Fit(format!("uncertainty of {}: {e}", id.name(fitted))))
        };
        let (a, b) = (eval(p - h)?, eval(p + h)?);
        evals += 2;
        cols[k] = Some(a.iter().zip(&b).map(|(a, b)| (b - a) / (2.0 * h)).collect());
    }
    let n = meas.len();
    let rss: f64 = meas
        .iter()
        .zip(values)
        .map(|(a, b)| (a - b) * (a - b))
        .sum();
    let s2 = rss / (n - m) as f64;
    // column norms; zero columns are unidentifiable
    let norm: Vec<f64> = cols
        .iter()
        .map(|c| {
            c.as_ref()
                .map(|c| c.iter().map(|x| x * x).sum::<f64>().sqrt())
                .unwrap_or(0.0)
        })
        .collect();
    let big = norm.iter().cloned().fold(0.0, f64::max);
    for k in 0..m {
        if status[k] == ParamStatus::Determined && norm[k] <= 1e-12 * big.max(1e-300) {
            status[k] = ParamStatus::NotIdentifiable;
        }
    }
    // near-null directions of the scaled normal matrix
    loop {
        let act: Vec<usize> = (0..m)
            .filter(|&k| status[k] == ParamStatus::Determined)
            .collect();
        if act.is_empty() {
            break;
        }
        let jn = DMatrix::from_fn(n, act.len(), |i, j| {
            cols[act[j]].as_ref().map(|c| c[i]).unwrap_or(0.0) / norm[act[j]]
        });
        let a = jn.transpose() * &jn;
        let eig = a.clone().symmetric_eigen();
        let lmax = eig.eigenvalues.iter().cloned().fold(0.0, f64::max);
        let (imin, lmin) =
            eig.eigenvalues
                .iter()
                .cloned()
                .enumerate()
                .fold(
                    (0, f64::INFINITY),
                    |b, (i, l)| if l < b.1 { (i, l) } else { b },
                );
        if lmin > 1e-10 * lmax {
            break;
        }
        // the parameter with the largest share in the null direction cannot be determined
        let v = eig.eigenvectors.column(imin);
        let (jmax, _) =
            v.iter().enumerate().fold(
                (0, -1.0),
                |b, (j, x)| if x.abs() > b.1 { (j, x.abs()) } else { b },
            );
        status[act[jmax]] = ParamStatus::NotIdentifiable;
    }
    let mut se = vec![f64::NAN; m];
    let mut corr = vec![vec![f64::NAN; m]; m];
    for k in 0..m {
        if status[k] == ParamStatus::NotIdentifiable {
            se[k] = f64::INFINITY;
        }
    }
    let act: Vec<usize> = (0..m)
        .filter(|&k| status[k] == ParamStatus::Determined)
        .collect();
    if !act.is_empty() {
        let jn = DMatrix::from_fn(n, act.len(), |i, j| {
            cols[act[j]].as_ref().map(|c| c[i]).unwrap_or(0.0) / norm[act[j]]
        });
        let a = jn.transpose() * &jn;
        let inv = a.try_inverse().ok_or_else(|| {
            CreepError::Fit("the normal matrix of the determined parameters is singular".into())
        })?;
        for (i, &ki) in act.iter().enumerate() {
            se[ki] = (s2 * inv[(i, i)]).max(0.0).sqrt() / norm[ki];
            for (j, &kj) in act.iter().enumerate() {
                corr[ki][kj] = inv[(i, j)] / (inv[(i, i)] * inv[(j, j)]).sqrt();
            }
        }
    }
    Ok((status, se, corr, evals))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn maps_round_trip_and_respect_bounds() {
        for (id, p) in [
            (P::Tc10, 0.3),
            (P::Kq, 0.7),
            (P::Mu, 0.25),
            (P::PolKA, 0.68),
        ] {
            let (m, s0) = Map::new((spec(id).min, spec(id).max), p);
            assert_eq!(s0, p, "{id:?}: a start inside its bounds is kept");
            assert!((m.to_p(m.to_z(p)) - p).abs() < 1e-9 * p.max(1.0), "{id:?}");
            let s = spec(id);
            for z in [-50.0, 0.0, 50.0] {
                let v = m.to_p(z);
                assert!(
                    v >= s.min
                        && (v <= s.max || s.max.is_infinite() || matches!(m, Map::Exp { .. }))
                );
            }
        }
    }

    #[test]
    fn starts_on_a_bound_begin_inside_where_the_map_has_a_slope() {
        // on the lower bound of a finite interval: a hundredth of the interval inside
        let (m, s0) = Map::new((0.0, 20.0), 0.0);
        assert!(matches!(m, Map::Logistic { .. }) && (s0 - 0.2).abs() < 1e-12);
        // on the upper bound
        let (_, s0) = Map::new((-1.0, 3.0), 3.0);
        assert!((s0 - 2.96).abs() < 1e-12, "{s0}");
        // on the lower bound of a very wide interval: near the bound, not at 1e7
        let (m, s0) = Map::new((0.0, 1e9), 0.0);
        assert!(matches!(m, Map::Exp { .. }) && (s0 - 0.01).abs() < 1e-12);
        // the slope of the map at the solver's start is not zero
        for (b, s) in [((0.0, 20.0), 0.0), ((-0.01, 20.0), 0.0), ((0.0, 1e9), 0.0)] {
            let (m, s0) = Map::new(b, s);
            let z = m.to_z(s0);
            let slope = (m.to_p(z + 1e-3) - m.to_p(z)) / 1e-3;
            assert!(slope > 1e-3, "{b:?}: slope {slope}");
        }
    }
}
