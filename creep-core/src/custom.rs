//! Effects written in Rust: implement [`CustomEffect`] in your own crate and register it with [`crate::register_effect!`]; it joins the [`catalogue`] at link time.
//!
//! No fork of the project is needed: a crate that depends on creep-core registers its effects,
//! and `scripts/build-fmu.sh --effects PATH/TO/CRATE` builds an `ecf` binary and an FMU that
//! link it (worked example: `examples/user-effect/`, docs/measurements.md "Effects in Rust").
//!
//! A custom effect scales one material function (like a formula effect, module
//! [`crate::formula`]) by a factor computed in Rust from its parameters, the bristle's local
//! state and the operating point (including data columns). A configuration switches it on with
//! `"custom_effects": [{"name": "humidity_softening", "params": {"k": 0.3}}]`; its parameters
//! are fitted like any other (`--free humidity_softening.k`). Worked example:
//! [`HumiditySoftening`] and docs/measurements.md.

use crate::error::{CreepError, Result};
pub use crate::modifier::{LocalState, OperatingPoint};
use crate::modifier::{Modifier, ModifierParam, Target};

/// An effect written in Rust.
pub trait CustomEffect: Send + Sync + std::fmt::Debug {
    /// Name in configuration files.
    fn name(&self) -> &'static str;
    /// One-paragraph physical description.
    fn description(&self) -> &'static str;
    /// Material function it scales.
    fn target(&self) -> Target;
    /// Parameters: (name with unit, default, min, max, one-line meaning).
    fn params(&self) -> &'static [(&'static str, f64, f64, f64, &'static str)];
    /// Data columns it needs (checked before a run).
    fn columns(&self) -> &'static [&'static str] {
        &[]
    }
    /// True if the factor depends on the bristle's local state (evaluated per bristle).
    fn uses_local_state(&self) -> bool {
        false
    }
    /// The factor (>= 0) multiplying the target.
    fn factor(&self, params: &[f64], local: &LocalState, op: &OperatingPoint) -> f64;
}

/// Worked example: the layer's shear strength falls linearly with air humidity,
/// tau_c2 <- tau_c2 (1 - k (humidity - h0)/h0), from the data column `humidity` (%).
#[derive(Debug)]
pub struct HumiditySoftening;

impl CustomEffect for HumiditySoftening {
    fn name(&self) -> &'static str {
        "humidity_softening"
    }
    fn description(&self) -> &'static str {
        "Water adsorbed from humid air weakens the oxide third body layer: its shear strength tau_c2 falls linearly with the relative air humidity around a reference humidity (an example of an effect written in Rust; uses the data column 'humidity', %)."
    }
    fn target(&self) -> Target {
        Target::TauC2
    }
    fn params(&self) -> &'static [(&'static str, f64, f64, f64, &'static str)] {
        &[
            (
                "k",
                0.0,
                -1.0,
                1.0,
                "relative strength change per reference humidity, -",
            ),
            ("h0_pct", 50.0, 1.0, 100.0, "reference humidity, %"),
        ]
    }
    fn columns(&self) -> &'static [&'static str] {
        &["humidity"]
    }
    fn factor(&self, p: &[f64], _local: &LocalState, op: &OperatingPoint) -> f64 {
        let h = op.column("humidity").unwrap_or(p[1]);
        (1.0 - p[0] * (h - p[1]) / p[1]).max(0.0)
    }
}

static HUMIDITY_SOFTENING: HumiditySoftening = HumiditySoftening;
crate::register_effect!(HUMIDITY_SOFTENING);

/// One registered Rust effect (made by [`crate::register_effect!`]; collected at link time).
pub struct Registration(pub &'static dyn CustomEffect);

inventory::collect!(Registration);

/// Registers a Rust effect with creep-core's catalogue at link time:
/// `static MINE: Mine = Mine; creep_core::register_effect!(MINE);` in any crate linked into
/// the program (the `ecf` binary or the FMU built by `scripts/build-fmu.sh --effects`).
#[macro_export]
macro_rules! register_effect {
    ($effect:path) => {
        $crate::inventory::submit! { $crate::custom::Registration(&$effect) }
    };
}

/// The registered Rust effects, sorted by name: the built-in example and every effect of
/// the crates linked into this program.
pub fn catalogue() -> Vec<&'static dyn CustomEffect> {
    let mut v: Vec<&'static dyn CustomEffect> = inventory::iter::<Registration>
        .into_iter()
        .map(|r| r.0)
        .collect();
    v.sort_by_key(|e| e.name());
    v
}

/// A custom effect switched on in a configuration, with its parameter values.
#[derive(Clone, Debug)]
pub struct CustomUse {
    /// The effect.
    pub effect: &'static dyn CustomEffect,
    /// Parameter values, in the order of [`CustomEffect::params`].
    pub params: Vec<f64>,
    /// Bounds a fit keeps them in (the effect's, or narrower ones the user gave).
    pub bounds: Vec<(f64, f64)>,
}

impl PartialEq for CustomUse {
    fn eq(&self, other: &Self) -> bool {
        self.effect.name() == other.effect.name() && self.params == other.params
    }
}

impl CustomUse {
    /// Looks an effect up by name, with default parameters.
    pub fn by_name(name: &str) -> Result<Self> {
        let all = catalogue();
        let mut found = all.iter().filter(|e| e.name() == name);
        let e = found.next().ok_or_else(|| CreepError::Unknown {
            kind: "custom effect".into(),
            name: name.into(),
            accepted: format!(
                "{} (effects of your own crate are linked with scripts/build-fmu.sh --effects PATH)",
                all.iter().map(|e| e.name()).collect::<Vec<_>>().join(", ")
            ),
        })?;
        if found.next().is_some() {
            return Err(CreepError::Config {
                source_name: "custom_effects".into(),
                message: format!(
                    "two linked crates register a Rust effect named '{name}'; rename one"
                ),
            });
        }
        Ok(CustomUse {
            effect: *e,
            params: e.params().iter().map(|p| p.1).collect(),
            bounds: e.params().iter().map(|p| (p.2, p.3)).collect(),
        })
    }

    /// Sets a parameter by name, checking its bounds.
    pub fn set(&mut self, name: &str, v: f64) -> Result<()> {
        let k = self
            .effect
            .params()
            .iter()
            .position(|p| p.0 == name)
            .ok_or_else(|| CreepError::Unknown {
                kind: format!("parameter of {}", self.effect.name()),
                name: name.into(),
                accepted: self
                    .effect
                    .params()
                    .iter()
                    .map(|p| p.0)
                    .collect::<Vec<_>>()
                    .join(", "),
            })?;
        let (_, _, lo, hi, _) = self.effect.params()[k];
        if !(v.is_finite() && lo <= v && v <= hi) {
            return Err(CreepError::OutOfRange {
                field: format!("{}.{name}", self.effect.name()),
                value: v,
                expected: format!("must be within [{lo}, {hi}]"),
            });
        }
        self.params[k] = v;
        Ok(())
    }
}

impl Modifier for CustomUse {
    fn name(&self) -> &str {
        self.effect.name()
    }
    fn describe(&self) -> String {
        format!("Rust effect '{}'", self.effect.name())
    }
    fn target(&self) -> Target {
        self.effect.target()
    }
    fn uses_local_state(&self) -> bool {
        self.effect.uses_local_state()
    }
    fn columns(&self) -> Vec<&str> {
        self.effect.columns().to_vec()
    }
    fn n_params(&self) -> usize {
        self.params.len()
    }
    fn param(&self, k: usize) -> ModifierParam {
        let spec = self.effect.params()[k];
        ModifierParam {
            name: spec.0.to_string(),
            value: self.params[k],
            min: self.bounds[k].0,
            max: self.bounds[k].1,
            limits: (spec.2, spec.3),
        }
    }
    fn set_param(&mut self, k: usize, v: f64) {
        self.params[k] = v;
    }
    fn set_bounds(&mut self, k: usize, lo: f64, hi: f64) {
        self.bounds[k] = (lo, hi);
    }
    /// The effect's own factor; it reads its columns from `op` by name (the
    /// [`CustomEffect`] interface), so `cols` is not used.
    #[inline]
    fn factor(&self, local: &LocalState, op: &OperatingPoint, _cols: &[f64]) -> f64 {
        self.effect.factor(&self.params, local, op)
    }
}
