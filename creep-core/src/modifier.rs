//! One way to extend the material law: a [`Modifier`] scales one material function by a factor of the operating point and, where it says so, of the bristle's local state.
//!
//! Formula effects ([`crate::formula::FormulaEffect`], written in the configuration) and
//! Rust effects ([`crate::custom::CustomUse`], a [`crate::custom::CustomEffect`] linked into
//! the program) are its two kinds. A configuration holds them in one list,
//! [`crate::Config::modifiers`] ([`AnyModifier`]); the engine evaluates them through
//! [`Modifier::factor`] (module `engine::modifiers`), the fit reaches their parameters
//! through [`Modifier::param`] and [`Modifier::set_param`]. Nothing else in the engine or the
//! fit knows which kind a modifier is.
//!
//! The factors of all modifiers of one target multiply (in list order) the material function
//! wherever the engine evaluates it: tau_c1, tau_c2, L_p, L_e (Eq. 4.3, 4.4, 4.21) or mu of the
//! Coulomb bound.

use crate::custom::{CustomUse, LocalState, OperatingPoint};
use crate::formula::{FormulaEffect, Target};

/// One parameter of a modifier, as a fit sees it.
#[derive(Clone, Debug, PartialEq)]
pub struct ModifierParam {
    /// Name (without the modifier's name).
    pub name: String,
    /// Current value (the modifier's own unit; fits show "-").
    pub value: f64,
    /// Lower bound a fit keeps (narrowed by the user where given).
    pub min: f64,
    /// Upper bound a fit keeps.
    pub max: f64,
    /// The widest bounds a user may narrow to (`--bound` checks against them).
    pub limits: (f64, f64),
}

/// A modifier of the material functions at an operating point (see the module).
pub trait Modifier {
    /// Name in configuration files and in parameter names (`NAME.PARAM`).
    fn name(&self) -> &str;
    /// How reports name it, e.g. "formula effect 'x' (factor '...')".
    fn describe(&self) -> String;
    /// The material function it scales.
    fn target(&self) -> Target;
    /// True if the factor depends on the bristle's local state (p, T, |u|, slip): evaluated
    /// per bristle; otherwise once per operating point.
    fn uses_local_state(&self) -> bool;
    /// Data columns it reads, in the order [`Modifier::factor`] receives their values.
    fn columns(&self) -> Vec<&str>;
    /// Number of parameters.
    fn n_params(&self) -> usize;
    /// Parameter `k` (0 <= k < [`Modifier::n_params`]).
    fn param(&self, k: usize) -> ModifierParam;
    /// Sets parameter `k` (a fit keeps it within its bounds; no check here).
    fn set_param(&mut self, k: usize, v: f64);
    /// Narrows the bounds of parameter `k` (the caller checks them against its limits).
    fn set_bounds(&mut self, k: usize, lo: f64, hi: f64);
    /// The factor (finite and >= 0 where the modifier is sensible; the engine clamps
    /// negative values to 0) at the bristle's `local` state and the operating point `op`;
    /// `cols` holds the values of [`Modifier::columns`] in their order, resolved once per
    /// operating point.
    fn factor(&self, local: &LocalState, op: &OperatingPoint, cols: &[f64]) -> f64;
}

/// A modifier of either kind, as a configuration holds it.
#[derive(Clone, Debug, PartialEq)]
pub enum AnyModifier {
    /// A formula effect (configuration key `formula_effects`).
    Formula(FormulaEffect),
    /// A Rust effect (configuration key `custom_effects`).
    Rust(CustomUse),
}

impl AnyModifier {
    fn inner(&self) -> &dyn Modifier {
        match self {
            AnyModifier::Formula(f) => f,
            AnyModifier::Rust(c) => c,
        }
    }
    fn inner_mut(&mut self) -> &mut dyn Modifier {
        match self {
            AnyModifier::Formula(f) => f,
            AnyModifier::Rust(c) => c,
        }
    }
}

impl Modifier for AnyModifier {
    fn name(&self) -> &str {
        self.inner().name()
    }
    fn describe(&self) -> String {
        self.inner().describe()
    }
    fn target(&self) -> Target {
        self.inner().target()
    }
    fn uses_local_state(&self) -> bool {
        self.inner().uses_local_state()
    }
    fn columns(&self) -> Vec<&str> {
        self.inner().columns()
    }
    fn n_params(&self) -> usize {
        self.inner().n_params()
    }
    fn param(&self, k: usize) -> ModifierParam {
        self.inner().param(k)
    }
    fn set_param(&mut self, k: usize, v: f64) {
        self.inner_mut().set_param(k, v)
    }
    fn set_bounds(&mut self, k: usize, lo: f64, hi: f64) {
        self.inner_mut().set_bounds(k, lo, hi)
    }
    #[inline]
    fn factor(&self, local: &LocalState, op: &OperatingPoint, cols: &[f64]) -> f64 {
        match self {
            AnyModifier::Formula(f) => f.factor(local, op, cols),
            AnyModifier::Rust(c) => c.factor(local, op, cols),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Config;

    #[test]
    fn formula_and_rust_effects_share_one_name_space() {
        let json = r#"{"preset": "dry",
            "formula_effects": [{"name": "humidity_softening", "target": "tau_c2", "factor": "1"}],
            "custom_effects": [{"name": "humidity_softening", "params": {"k": 0.3}}]}"#;
        let e = Config::from_json_str(json, "x").unwrap_err().to_string();
        assert!(e.contains("share one name space"), "{e}");
        let ok = json.replacen("\"humidity_softening\", \"target\"", "\"h\", \"target\"", 1);
        let c = Config::from_json_str(&ok, "x").unwrap();
        // one list, formula effects first, reached through the trait
        let names: Vec<&str> = c.modifiers.iter().map(|m| m.name()).collect();
        assert_eq!(names, ["h", "humidity_softening"]);
        assert!(c.modifiers[0].describe().starts_with("formula effect 'h'"));
        assert_eq!(c.modifiers[1].param(0).name, "k");
        assert_eq!(c.modifiers[1].param(0).value, 0.3);
        assert_eq!(c.modifiers[1].param(0).limits, (-1.0, 1.0));
        assert_eq!(c.modifiers[1].columns(), ["humidity"]);
    }
}
