//! Named configurations (`fastsim`, `polach`, `ecf` with presets) read from JSON files with serde_json.
//!
//! A configuration file is `{"model": "ecf"|"fastsim"|"polach", "preset": NAME, "effects":
//! [...], "params": {NAME: VALUE, ...}, "bound": "elliptic"|"parabolic", "grid": {"nx": N,
//! "ny": N}, "scheme": "cells"|"cells-ho"|"continuous", "geometry": {...}}`. Everything but
//! `model` is optional. A preset is such a file
//! shipped with the crate (`presets/*.json`); a user file naming a preset starts from it and
//! overrides what it gives. `effects` replaces the preset's list, unless every entry starts
//! with `+` or `-`, which adds or removes effects. Parameter values are numbers in the unit
//! their name carries, or the string "inf". The submodule `document` reads and writes it.

mod document;

use crate::custom::CustomUse;
use crate::effects::{Effect, EffectSet};
use crate::error::{CreepError, Result};
use crate::formula::FormulaEffect;
use crate::modifier::{LocalState, Modifier, ModifierParam, OperatingPoint, Target};
use crate::params::{self, Params};
use crate::scheme::Scheme;
use serde::{Deserialize, Serialize};

/// The three model families.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelKind {
    /// Extended Creep Force model (bristle engine with 3BL effects).
    Ecf,
    /// FASTSIM (bristle engine with the Coulomb bound).
    Fastsim,
    /// Polach's closed-form model.
    Polach,
}

impl ModelKind {
    /// Parses a model name.
    pub fn parse(s: &str) -> Result<Self> {
        match s {
            "ecf" => Ok(ModelKind::Ecf),
            "fastsim" => Ok(ModelKind::Fastsim),
            "polach" => Ok(ModelKind::Polach),
            _ => Err(CreepError::Unknown {
                kind: "model".into(),
                name: s.into(),
                accepted: "ecf, fastsim, polach".into(),
            }),
        }
    }
    /// Name of the model.
    pub fn name(&self) -> &'static str {
        match self {
            ModelKind::Ecf => "ecf",
            ModelKind::Fastsim => "fastsim",
            ModelKind::Polach => "polach",
        }
    }

    /// The scheme a model runs when its configuration names none: `cells-ho` for ECF (on the
    /// default grid 80x21 its steady curves are within 0.2 % of 640x168 for dry, table4.1
    /// and wet at 5-30 m/s where `cells` was up to 1.2 %, for about 10 % more cost in steady
    /// curves and twice the cost in time steps; docs/model.md section 9), `cells` for
    /// FASTSIM and Polach (their layers take the cell-by-cell rules in any case).
    pub fn default_scheme(self) -> Scheme {
        match self {
            ModelKind::Ecf => Scheme::CellsHigher,
            ModelKind::Fastsim | ModelKind::Polach => Scheme::CellsMarch,
        }
    }
}

/// Shape of the Coulomb bound of FASTSIM.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bound {
    /// mu times the elliptic Hertz pressure (consistent with ECF; default).
    Elliptic,
    /// mu times Kalker's parabolic pressure 2 F_N/(pi a b) (1 - x^2/a^2 - y^2/b^2).
    Parabolic,
}

/// Bristle grid size: `nx` cells along each strip (rolling direction), `ny` strips.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Grid {
    /// Cells per strip in rolling direction.
    pub nx: usize,
    /// Number of strips across the contact.
    pub ny: usize,
}

/// Default grid: within 1 % of a 4x refined grid over 0.1 %-30 % creepage (docs/model.md).
pub const DEFAULT_GRID: Grid = Grid { nx: 80, ny: 21 };

impl Grid {
    /// Parses "NXxNY".
    pub fn parse(s: &str) -> Result<Self> {
        let err = || CreepError::Config {
            source_name: "--grid".into(),
            message: format!(
                "'{s}': expected NXxNY with 2 <= NX <= 2000 and 1 <= NY <= 1000, e.g. 40x21"
            ),
        };
        let (a, b) = s.split_once(['x', 'X']).ok_or_else(err)?;
        let g = Grid {
            nx: a.trim().parse().map_err(|_| err())?,
            ny: b.trim().parse().map_err(|_| err())?,
        };
        g.validate().map_err(|_| err())?;
        Ok(g)
    }
    /// Checks the bounds.
    pub fn validate(&self) -> Result<()> {
        if self.nx < 2 || self.nx > 2000 || self.ny < 1 || self.ny > 1000 {
            return Err(CreepError::OutOfRange {
                field: "grid".into(),
                value: (self.nx * 10000 + self.ny) as f64,
                expected: format!(
                    "grid {}x{}: need 2 <= nx <= 2000 and 1 <= ny <= 1000",
                    self.nx, self.ny
                ),
            });
        }
        Ok(())
    }
}

/// How the contact size follows the normal force.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Geometry {
    /// Semi-axes `a`, `b` (m) at the reference load `fn_ref` (N); other loads scale them by
    /// (F_N / fn_ref)^(1/3) (Hertz).
    SemiAxes {
        /// Semi-axis in rolling direction at the reference load, m.
        a: f64,
        /// Lateral semi-axis at the reference load, m.
        b: f64,
        /// Reference load, N.
        fn_ref: f64,
    },
    /// Exact elliptic Hertz from equivalent radii of curvature (m).
    Curvatures {
        /// Equivalent radius in rolling direction, m.
        rx: f64,
        /// Equivalent lateral radius, m.
        ry: f64,
    },
    /// Line contact (twin disc): equivalent radius `r` (m), contact width `width` (m);
    /// F_N is the total force over the width.
    Line {
        /// Equivalent radius, m.
        r: f64,
        /// Contact width, m.
        width: f64,
    },
}

/// Default geometry: the seed's Vectron wheel, a = 7.63 mm, b = 7.88 mm at 110 kN (Tab. 4.1).
pub const DEFAULT_GEOMETRY: Geometry = Geometry::SemiAxes {
    a: 7.63e-3,
    b: 7.88e-3,
    fn_ref: 110e3,
};

/// A resolved configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    /// Model family.
    pub model: ModelKind,
    /// Name of the preset it came from (or "custom").
    pub preset: String,
    /// Effects switched on (bristle models).
    pub effects: EffectSet,
    /// Parameter values.
    pub params: Params,
    /// Coulomb bound shape.
    pub bound: Bound,
    /// Bristle grid.
    pub grid: Grid,
    /// How a model built from this configuration integrates the bristles' moves, in steady
    /// marches and time steps (configuration key `scheme`: `cells`, `cells-ho` or
    /// `continuous`; default [`ModelKind::default_scheme`]: `cells-ho`
    /// for ECF, `cells` for FASTSIM and Polach). How to compute, not what:
    /// [`Model::set_scheme`](crate::Model::set_scheme) changes it for a model, and a saved
    /// state loads into a model of another scheme.
    pub scheme: Scheme,
    /// How the local temperature of a bristle move (Eq. 4.35) is solved (configuration key
    /// `temperature_solve`: `exact`, the implicit solve to its tolerance, or `predictor`, the
    /// predictor-corrector of [`crate::thermal::solve_predictor_corrector`]; default
    /// [`crate::thermal::TemperatureSolve::default`]). How to compute, not what, as `scheme`:
    /// [`Model::set_temperature_solve`](crate::Model::set_temperature_solve) changes it for a
    /// model.
    pub temperature_solve: crate::thermal::TemperatureSolve,
    /// Contact geometry.
    pub geometry: Geometry,
    /// Modifiers of the material law (module [`crate::modifier`]): formula effects
    /// (configuration key `formula_effects`, module [`crate::formula`]) and effects written in
    /// Rust (`custom_effects`, module [`crate::custom`]), in one list; a configuration file's
    /// formula effects come first, then its Rust effects, each in file order.
    pub modifiers: Vec<AnyModifier>,
}

/// The presets shipped with the crate: (name, JSON text).
pub const PRESETS: &[(&str, &str)] = &[
    ("fastsim", include_str!("../../presets/fastsim.json")),
    ("polach", include_str!("../../presets/polach.json")),
    ("table4.1", include_str!("../../presets/table4.1.json")),
    ("dry", include_str!("../../presets/dry.json")),
    ("wet", include_str!("../../presets/wet.json")),
    ("dry_sanded", include_str!("../../presets/dry_sanded.json")),
    ("wet_sanded", include_str!("../../presets/wet_sanded.json")),
    ("twin_disc", include_str!("../../presets/twin_disc.json")),
];

fn preset_text(name: &str) -> Result<&'static str> {
    PRESETS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| *t)
        .ok_or_else(|| CreepError::Unknown {
            kind: "preset".into(),
            name: name.into(),
            accepted: PRESETS
                .iter()
                .map(|(n, _)| *n)
                .collect::<Vec<_>>()
                .join(", "),
        })
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
    /// Indices of `list` in the order the factors multiply and the FMU state stores their
    /// parameters: formula effects, then Rust effects, each in list order.
    pub fn kind_order(list: &[AnyModifier]) -> Vec<usize> {
        let formula = |k: &usize| matches!(list[*k], AnyModifier::Formula(_));
        (0..list.len())
            .filter(formula)
            .chain((0..list.len()).filter(|k| !formula(k)))
            .collect()
    }

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

impl Config {
    /// The formula effects among the modifiers, in list order.
    pub fn formulas(&self) -> impl Iterator<Item = &crate::formula::FormulaEffect> {
        self.modifiers.iter().filter_map(|m| match m {
            AnyModifier::Formula(f) => Some(f),
            AnyModifier::Rust(_) => None,
        })
    }

    /// The Rust effects among the modifiers, in list order.
    pub fn rust_effects(&self) -> impl Iterator<Item = &crate::custom::CustomUse> {
        self.modifiers.iter().filter_map(|m| match m {
            AnyModifier::Rust(c) => Some(c),
            AnyModifier::Formula(_) => None,
        })
    }

    /// The configuration of a preset by name.
    pub fn preset(name: &str) -> Result<Self> {
        let text = preset_text(name)?;
        let mut c = Self::from_json_str(text, &format!("preset '{name}'"))?;
        c.preset = name.to_string();
        Ok(c)
    }

    /// Default configuration of a model family (`ecf` -> preset `table4.1`).
    pub fn for_model(model: &str) -> Result<Self> {
        match ModelKind::parse(model)? {
            ModelKind::Ecf => Self::preset("table4.1"),
            ModelKind::Fastsim => Self::preset("fastsim"),
            ModelKind::Polach => Self::preset("polach"),
        }
    }

    /// True if the effect is on.
    pub fn has(&self, e: Effect) -> bool {
        self.effects.has(e)
    }

    /// Names of all parameters (for help texts).
    pub fn param_names() -> Vec<&'static str> {
        params::SPECS.iter().map(|s| s.name).collect()
    }
}

#[cfg(test)]
mod tests {

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

    use super::*;

    #[test]
    fn every_preset_parses() {
        for (name, _) in PRESETS {
            let c = Config::preset(name).unwrap_or_else(|e| panic!("{name}: {e}"));
            let back = Config::from_json_str(&c.to_json().to_string(), "roundtrip").unwrap();
            assert_eq!(back.params, c.params, "{name}");
            assert_eq!(back.effects, c.effects, "{name}");
        }
    }

    #[test]
    fn errors_name_the_problem() {
        let e = Config::from_json_str("{\"preset\": \"moist\"}", "x.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains("moist") && e.contains("table4.1"), "{e}");
        let e = Config::from_json_str("{\"model\": \"ecf\",\n \"params\": {\"mu\": }}", "x.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 2"), "{e}");
        let e = Config::from_json_str("{\"model\": \"ecf\", \"params\": {\"nu\": 0.9}}", "x.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains("nu") && e.contains("0.5"), "{e}");
        let e = Config::from_json_str("{\"preset\": \"dry\", \"effects\": [\"-heat\"]}", "x.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains("heat") && e.contains("temperature"), "{e}");
    }

    #[test]
    fn a_configuration_names_its_temperature_solve() {
        use crate::thermal::TemperatureSolve;
        let c = Config::preset("dry").unwrap();
        assert_eq!(c.temperature_solve, TemperatureSolve::default());
        // the default is not written (documents and saved states as before the key)
        assert!(c.to_json().get("temperature_solve").is_none());
        for s in TemperatureSolve::ALL {
            let json = format!(
                r#"{{"preset": "dry", "temperature_solve": "{}"}}"#,
                s.name()
            );
            let c = Config::from_json_str(&json, "x.json").unwrap();
            assert_eq!(c.temperature_solve, s);
            assert_eq!(
                c.to_json().get("temperature_solve").is_some(),
                s != TemperatureSolve::default()
            );
            assert_eq!(
                Config::from_json_str(&c.to_json().to_string(), "y").unwrap(),
                c
            );
        }
        let e = Config::from_json_str(r#"{"preset": "dry", "temperature_solve": "pc"}"#, "x.json")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("temperature_solve: 'pc'") && e.contains("predictor"),
            "{e}"
        );
    }

    #[test]
    fn a_configuration_names_its_scheme() {
        // a configuration that names no scheme runs its model's default
        let c = Config::preset("dry").unwrap();
        assert_eq!(c.scheme, Scheme::CellsHigher);
        assert_eq!(c.to_json()["scheme"], "cells-ho");
        let c = Config::from_json_str(r#"{"model": "ecf"}"#, "x").unwrap();
        assert_eq!(c.scheme, Scheme::CellsHigher);
        for m in ["fastsim", "polach"] {
            assert_eq!(
                Config::for_model(m).unwrap().scheme,
                Scheme::CellsMarch,
                "{m}"
            );
        }
        for s in [Scheme::CellsMarch, Scheme::CellsHigher, Scheme::Continuous] {
            let json = format!(r#"{{"preset": "dry", "scheme": "{}"}}"#, s.name());
            let c = Config::from_json_str(&json, "x").unwrap();
            assert_eq!(c.scheme, s);
            let back = Config::from_json_str(&c.to_json().to_string(), "roundtrip").unwrap();
            assert_eq!(back, c);
        }
        let e = Config::from_json_str(r#"{"preset": "dry", "scheme": "ho"}"#, "x.json")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("x.json") && e.contains("scheme: 'ho'") && e.contains("cells-ho"),
            "{e}"
        );
    }

    #[test]
    fn relative_effects_modify_the_preset() {
        let c = Config::from_json_str(
            "{\"preset\": \"dry\", \"effects\": [\"-temperature\", \"+elastic_unloading\"]}",
            "x",
        )
        .unwrap();
        assert!(
            !c.has(Effect::Temperature)
                && c.has(Effect::ElasticUnloading)
                && c.has(Effect::VocePlasticity)
        );
    }
}
