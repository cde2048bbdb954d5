//! The parameters a fit can free: the registry's and any modifier's own, by name, with their bounds and plausible ranges.

use creep_core::config::Config;
use creep_core::error::{CreepError, Result};
use creep_core::params::{spec, P};
use creep_core::Modifier;

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
    /// Sets the value (display unit; no bounds check).
    pub(crate) fn set(&self, cfg: &mut Config, v: f64) -> Result<()> {
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
