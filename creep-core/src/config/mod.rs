//! Named configurations (`fastsim`, `polach`, `ecf` with presets) read from JSON files with serde_json.
//!
//! A configuration file is `{"model": "ecf"|"fastsim"|"polach", "preset": NAME, "effects":
//! [...], "params": {NAME: VALUE, ...}, "bound": "elliptic"|"parabolic", "grid": {"nx": N,
//! "ny": N}, "scheme": "cells"|"cells-ho"|"continuous", "geometry": {...}}`. Everything but
//! `model` is optional. A preset is such a file
//! shipped with the crate (`presets/*.json`); a user file naming a preset starts from it and
//! overrides what it gives. `effects` replaces the preset's list, unless every entry starts
//! with `+` or `-`, which adds or removes effects. Parameter values are numbers in the unit
//! their name carries, or the string "inf".

use crate::custom::CustomUse;
use crate::effects::{self, Effect, EffectSet};
use crate::error::{CreepError, Result};
use crate::formula::FormulaEffect;
use crate::modifier::{LocalState, Modifier, ModifierParam, OperatingPoint, Target};
use crate::params::{self, Params};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

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
    /// `continuous`; default [`crate::engine::Scheme::default_for`] the model: `cells-ho`
    /// for ECF, `cells` for FASTSIM and Polach). How to compute, not what:
    /// [`Model::set_scheme`](crate::Model::set_scheme) changes it for a model, and a saved
    /// state loads into a model of another scheme.
    pub scheme: crate::engine::Scheme,
    /// Contact geometry.
    pub geometry: Geometry,
    /// Modifiers of the material law (module [`crate::modifier`]): formula effects
    /// (configuration key `formula_effects`, module [`crate::formula`]) and effects written in
    /// Rust (`custom_effects`, module [`crate::custom`]), in one list; a configuration file's
    /// formula effects come first, then its Rust effects, each in file order.
    pub modifiers: Vec<AnyModifier>,
}

#[derive(Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RawConfig {
    #[serde(default)]
    model: Option<String>,
    #[serde(default)]
    preset: Option<String>,
    #[serde(default)]
    description: Option<String>,
    #[serde(default)]
    effects: Option<Vec<String>>,
    #[serde(default)]
    params: Option<Map<String, Value>>,
    #[serde(default)]
    bound: Option<String>,
    #[serde(default)]
    grid: Option<Grid>,
    #[serde(default)]
    scheme: Option<String>,
    #[serde(default)]
    geometry: Option<Map<String, Value>>,
    #[serde(default)]
    formula_effects: Option<Vec<RawFormula>>,
    #[serde(default)]
    custom_effects: Option<Vec<RawCustom>>,
    /// The record `ecf fit` writes beside a fitted configuration (start and fitted values,
    /// standard errors, flags, CV(RMSE) before and after); read by `ecf report`, not by the
    /// model.
    #[serde(default, skip_serializing)]
    #[allow(dead_code)]
    fit: Option<Value>,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RawCustom {
    name: String,
    #[serde(default)]
    params: Map<String, Value>,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RawFormula {
    name: String,
    target: String,
    factor: String,
    #[serde(default)]
    params: Map<String, Value>,
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

fn cfg_err(src: &str, message: String) -> CreepError {
    CreepError::Config {
        source_name: src.into(),
        message,
    }
}

fn param_value(src: &str, name: &str, v: &Value) -> Result<f64> {
    match v {
        Value::Number(n) => n.as_f64().ok_or_else(|| cfg_err(src, format!("params.{name}: not a finite number"))),
        Value::String(s) if s == "inf" || s == "Infinity" => Ok(f64::INFINITY),
        Value::String(s) if s == "-inf" => Ok(f64::NEG_INFINITY),
        _ => Err(cfg_err(src, format!("params.{name}: expected a number (in the unit the name carries) or \"inf\", got {v}"))),
    }
}

fn geo_num(src: &str, m: &Map<String, Value>, key: &str) -> Result<Option<f64>> {
    match m.get(key) {
        None => Ok(None),
        Some(Value::Number(n)) => {
            let x = n.as_f64().unwrap_or(f64::NAN);
            if x.is_finite() && x > 0.0 {
                Ok(Some(x))
            } else {
                Err(cfg_err(src, format!("geometry.{key} = {x}: must be > 0")))
            }
        }
        Some(v) => Err(cfg_err(
            src,
            format!("geometry.{key}: expected a number > 0, got {v}"),
        )),
    }
}

fn parse_geometry(src: &str, m: &Map<String, Value>) -> Result<Geometry> {
    for k in m.keys() {
        if ![
            "a_mm",
            "b_mm",
            "fn_ref_kN",
            "rx_mm",
            "ry_mm",
            "line_radius_mm",
            "line_width_mm",
        ]
        .contains(&k.as_str())
        {
            return Err(cfg_err(src, format!("geometry.{k}: unknown key; accepted: a_mm, b_mm, fn_ref_kN | rx_mm, ry_mm | line_radius_mm, line_width_mm")));
        }
    }
    // one way of giving the geometry: keys of two groups (e.g. semi-axes and radii) are
    // refused rather than one group silently taking precedence
    let groups: [&[&str]; 3] = [
        &["a_mm", "b_mm", "fn_ref_kN"],
        &["rx_mm", "ry_mm"],
        &["line_radius_mm", "line_width_mm"],
    ];
    let used: Vec<String> = groups
        .iter()
        .filter(|g| g.iter().any(|k| m.contains_key(*k)))
        .map(|g| {
            g.iter()
                .filter(|k| m.contains_key(**k))
                .copied()
                .collect::<Vec<_>>()
                .join(", ")
        })
        .collect();
    if used.len() > 1 {
        return Err(cfg_err(
            src,
            format!(
                "geometry: give one of a_mm, b_mm and fn_ref_kN | rx_mm and ry_mm | line_radius_mm and line_width_mm; got {}",
                used.join(" and ")
            ),
        ));
    }
    if let (Some(r), Some(w)) = (
        geo_num(src, m, "line_radius_mm")?,
        geo_num(src, m, "line_width_mm")?,
    ) {
        return Ok(Geometry::Line {
            r: r * 1e-3,
            width: w * 1e-3,
        });
    }
    if let (Some(rx), Some(ry)) = (geo_num(src, m, "rx_mm")?, geo_num(src, m, "ry_mm")?) {
        return Ok(Geometry::Curvatures {
            rx: rx * 1e-3,
            ry: ry * 1e-3,
        });
    }
    match (geo_num(src, m, "a_mm")?, geo_num(src, m, "b_mm")?, geo_num(src, m, "fn_ref_kN")?) {
        (Some(a), Some(b), Some(f)) => Ok(Geometry::SemiAxes { a: a * 1e-3, b: b * 1e-3, fn_ref: f * 1e3 }),
        _ => Err(cfg_err(src, "geometry: give a_mm, b_mm and fn_ref_kN, or rx_mm and ry_mm, or line_radius_mm and line_width_mm".into())),
    }
}

/// The document's `bound`: "elliptic" or "parabolic".
fn parse_bound(src: &str, b: &str) -> Result<Bound> {
    match b {
        "elliptic" => Ok(Bound::Elliptic),
        "parabolic" => Ok(Bound::Parabolic),
        _ => Err(cfg_err(
            src,
            format!("bound '{b}': expected \"elliptic\" or \"parabolic\""),
        )),
    }
}

/// The parameters of a formula effect, each {"value", "min", "max"} (what it leaves out:
/// NaN, and no bound).
fn formula_params(src: &str, f: &RawFormula) -> Result<Vec<crate::formula::FormulaParam>> {
    let mut ps = Vec::new();
    for (n, v) in &f.params {
        let get = |k: &str, d: f64| -> Result<f64> {
            match v.get(k) {
                None => Ok(d),
                Some(x) => x.as_f64().ok_or_else(|| {
                    cfg_err(
                        src,
                        format!(
                            "formula_effects.{}.params.{n}.{k}: expected a number",
                            f.name
                        ),
                    )
                }),
            }
        };
        if !v.is_object() {
            return Err(cfg_err(src, format!("formula_effects.{}.params.{n}: expected {{\"value\": v, \"min\": lo, \"max\": hi}}", f.name)));
        }
        ps.push(crate::formula::FormulaParam {
            name: n.clone(),
            value: get("value", f64::NAN)?,
            min: get("min", f64::MIN)?,
            max: get("max", f64::MAX)?,
        });
    }
    Ok(ps)
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

    /// Reads a configuration file.
    pub fn from_file(path: &std::path::Path) -> Result<Self> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| cfg_err(&path.display().to_string(), format!("cannot read: {e}")))?;
        Self::from_json_str(&text, &path.display().to_string())
    }

    /// Parses a configuration document; `src` names it in error messages.
    pub fn from_json_str(text: &str, src: &str) -> Result<Self> {
        let raw: RawConfig = serde_json::from_str(text).map_err(|e| {
            cfg_err(
                src,
                format!("line {}, column {}: {}", e.line(), e.column(), e),
            )
        })?;
        let mut cfg = Self::start_of(&raw, src)?;
        if let Some(list) = &raw.effects {
            cfg.apply_effects(list, src)?;
        }
        if let Some(ps) = &raw.params {
            for (name, v) in ps {
                cfg.apply_param(name, v, src)?;
            }
        }
        if let Some(b) = &raw.bound {
            cfg.bound = parse_bound(src, b)?;
        }
        if let Some(g) = raw.grid {
            g.validate().map_err(|e| cfg_err(src, e.to_string()))?;
            cfg.grid = g;
        }
        if let Some(name) = &raw.scheme {
            cfg.scheme = crate::engine::Scheme::by_name(name).ok_or_else(|| {
                cfg_err(
                    src,
                    format!(
                        "scheme: '{name}' is not a scheme (expected {})",
                        crate::engine::Scheme::NAMES
                    ),
                )
            })?;
        }
        if let Some(g) = &raw.geometry {
            cfg.geometry = parse_geometry(src, g)?;
        }
        if let Some(list) = &raw.formula_effects {
            for f in list {
                cfg.add_formula(f, src)?;
            }
        }
        if let Some(list) = &raw.custom_effects {
            for c in list {
                cfg.add_custom(c, src)?;
            }
        }
        cfg.check_model(src)?;
        Ok(cfg)
    }

    /// The configuration a document starts from: its preset, or its model with no effects and
    /// the default parameters, grid and geometry; a model given beside a preset must be the
    /// preset's.
    fn start_of(raw: &RawConfig, src: &str) -> Result<Self> {
        let mut cfg = match &raw.preset {
            Some(p) => {
                let base = Self::preset(p).map_err(|e| cfg_err(src, format!("preset: {e}")))?;
                Config {
                    preset: p.clone(),
                    ..base
                }
            }
            None => {
                let model = raw.model.as_deref().ok_or_else(|| {
                    cfg_err(
                        src,
                        "missing \"model\" (ecf, fastsim or polach) or \"preset\"".into(),
                    )
                })?;
                let model = ModelKind::parse(model).map_err(|e| cfg_err(src, e.to_string()))?;
                Config {
                    model,
                    preset: "custom".into(),
                    effects: EffectSet::empty(),
                    params: Params::default(),
                    bound: Bound::Elliptic,
                    grid: DEFAULT_GRID,
                    scheme: crate::engine::Scheme::default_for(model),
                    geometry: DEFAULT_GEOMETRY,
                    modifiers: Vec::new(),
                }
            }
        };
        if let Some(m) = &raw.model {
            let kind = ModelKind::parse(m).map_err(|e| cfg_err(src, e.to_string()))?;
            if raw.preset.is_some() && kind != cfg.model {
                return Err(cfg_err(
                    src,
                    format!(
                        "model '{m}' does not match preset '{}' (model '{}')",
                        cfg.preset,
                        cfg.model.name()
                    ),
                ));
            }
            cfg.model = kind;
        }
        Ok(cfg)
    }

    /// The document's `effects`: a full list replaces the effects, a list of only +NAME/-NAME
    /// switches them on and off.
    fn apply_effects(&mut self, list: &[String], src: &str) -> Result<()> {
        let signed = |e: &String| e.starts_with('+') || e.starts_with('-');
        let relative = !list.is_empty() && list.iter().all(signed);
        if list.iter().any(signed) && !relative {
            return Err(cfg_err(
                src,
                format!(
                    "effects {list:?} mixes names with and without +/-: write either a full list (replaces the preset's) or only +NAME/-NAME changes"
                ),
            ));
        }
        if !relative {
            self.effects = EffectSet::empty();
        }
        let by_name =
            |n: &str| effects::by_name(n).map_err(|e| cfg_err(src, format!("effects: {e}")));
        for e in list {
            if let Some(n) = e.strip_prefix('-') {
                self.effects.remove(by_name(n)?);
                continue;
            }
            let n = e.strip_prefix('+').unwrap_or(e);
            self.effects.insert(by_name(n)?);
        }
        Ok(())
    }

    /// One entry of the document's `params`: a value, or {"value", "min", "max"} (the bounds
    /// a fit keeps it in).
    fn apply_param(&mut self, name: &str, v: &Value, src: &str) -> Result<()> {
        let id = params::by_name(name).ok_or_else(|| {
            cfg_err(
                src,
                format!(
                    "params.{name}: unknown parameter; accepted: {}",
                    Config::param_names().join(", ")
                ),
            )
        })?;
        let (x, bounds) = match v {
            Value::Object(m) => {
                let (x, lo, hi) = self.param_with_bounds(id, name, m, src)?;
                (x, Some((lo, hi)))
            }
            _ => (param_value(src, name, v)?, None),
        };
        let err = |e: CreepError| cfg_err(src, format!("params.{name}: {e}"));
        if let Some((lo, hi)) = bounds {
            // widen first so that a value outside the old bounds can be set
            let s = params::spec(id);
            self.params.set_bounds(id, s.min, s.max).map_err(err)?;
            self.params.set(id, x).map_err(err)?;
            self.params.set_bounds(id, lo, hi).map_err(err)?;
        } else {
            self.params.set(id, x).map_err(err)?;
        }
        Ok(())
    }

    /// (value, min, max) of a parameter given as an object `m`; what it leaves out keeps its
    /// current value.
    fn param_with_bounds(
        &self,
        id: params::P,
        name: &str,
        m: &Map<String, Value>,
        src: &str,
    ) -> Result<(f64, f64, f64)> {
        for k in m.keys() {
            if !["value", "min", "max"].contains(&k.as_str()) {
                return Err(cfg_err(
                    src,
                    format!("params.{name}.{k}: unknown key; accepted: value, min, max"),
                ));
            }
        }
        let x = m
            .get("value")
            .map(|v| param_value(src, &format!("{name}.value"), v))
            .transpose()?
            .unwrap_or(self.params.get(id));
        let (rlo, rhi) = self.params.bounds(id);
        let lo = m
            .get("min")
            .map(|v| param_value(src, &format!("{name}.min"), v))
            .transpose()?
            .unwrap_or(rlo);
        let hi = m
            .get("max")
            .map(|v| param_value(src, &format!("{name}.max"), v))
            .transpose()?
            .unwrap_or(rhi);
        Ok((x, lo, hi))
    }

    /// Adds one formula effect of the document's `formula_effects` to the modifiers.
    fn add_formula(&mut self, f: &RawFormula, src: &str) -> Result<()> {
        let target = crate::formula::Target::parse(&f.target)
            .map_err(|e| cfg_err(src, format!("formula_effects.{}: {e}", f.name)))?;
        let ps = formula_params(src, f)?;
        let fe = crate::formula::FormulaEffect::new(&f.name, target, &f.factor, ps)
            .map_err(|e| cfg_err(src, e.to_string()))?;
        if self.modifiers.iter().any(|g| g.name() == fe.name) {
            return Err(cfg_err(
                src,
                format!("formula_effects: duplicate name '{}'", fe.name),
            ));
        }
        self.modifiers.push(AnyModifier::Formula(fe));
        Ok(())
    }

    /// Adds one Rust effect of the document's `custom_effects`, with its parameter values,
    /// to the modifiers.
    fn add_custom(&mut self, c: &RawCustom, src: &str) -> Result<()> {
        let mut u = crate::custom::CustomUse::by_name(&c.name)
            .map_err(|e| cfg_err(src, format!("custom_effects: {e}")))?;
        for (n, v) in &c.params {
            let x = param_value(src, &format!("{}.{n}", c.name), v)?;
            u.set(n, x)
                .map_err(|e| cfg_err(src, format!("custom_effects: {e}")))?;
        }
        if self.modifiers.iter().any(|k| k.name() == c.name) {
            return Err(cfg_err(
                src,
                format!(
                    "custom_effects: '{}' given twice (formula and Rust effects share one name space: their parameters are NAME.PARAM)",
                    c.name
                ),
            ));
        }
        self.modifiers.push(AnyModifier::Rust(u));
        Ok(())
    }

    /// Refuses what the model family cannot run: modifiers on Polach, FASTSIM without the
    /// Coulomb bound.
    fn check_model(&self, src: &str) -> Result<()> {
        if self.model == ModelKind::Polach && !self.modifiers.is_empty() {
            return Err(cfg_err(
                src,
                "formula_effects act on the bristle engine (ecf, fastsim), not on polach".into(),
            ));
        }
        if self.model == ModelKind::Fastsim && !self.effects.has(Effect::Coulomb) {
            return Err(cfg_err(
                src,
                "model fastsim needs the effect \"coulomb\"".into(),
            ));
        }
        Ok(())
    }

    /// The configuration as a JSON document that [`Config::from_json_str`] reads back.
    pub fn to_json(&self) -> Value {
        let mut ps = Map::new();
        let num = |v: f64| {
            if v.is_infinite() {
                Value::String(if v > 0.0 { "inf" } else { "-inf" }.into())
            } else {
                serde_json::json!(v)
            }
        };
        for s in params::SPECS {
            let v = self.params.get(s.id);
            let val = if self.params.narrowed(s.id) {
                let (lo, hi) = self.params.bounds(s.id);
                serde_json::json!({"value": num(v), "min": num(lo), "max": num(hi)})
            } else {
                num(v)
            };
            ps.insert(s.name.into(), val);
        }
        let geometry = match self.geometry {
            Geometry::SemiAxes { a, b, fn_ref } => {
                serde_json::json!({"a_mm": a * 1e3, "b_mm": b * 1e3, "fn_ref_kN": fn_ref * 1e-3})
            }
            Geometry::Curvatures { rx, ry } => {
                serde_json::json!({"rx_mm": rx * 1e3, "ry_mm": ry * 1e3})
            }
            Geometry::Line { r, width } => {
                serde_json::json!({"line_radius_mm": r * 1e3, "line_width_mm": width * 1e3})
            }
        };
        let formulas: Vec<Value> = self
            .formulas()
            .map(|f| {
                let ps: Map<String, Value> = f.params.iter().map(|q| (q.name.clone(), serde_json::json!({"value": q.value, "min": q.min, "max": q.max}))).collect();
                serde_json::json!({"name": f.name, "target": f.target.name(), "factor": f.source, "params": ps})
            })
            .collect();
        let mut v = serde_json::json!({
            "formula_effects": formulas,
            "custom_effects": self.rust_effects().map(|c| {
                let ps: Map<String, Value> = c.effect.params().iter().zip(&c.params).map(|(d, v)| (d.0.to_string(), serde_json::json!(v))).collect();
                serde_json::json!({"name": c.effect.name(), "params": ps})
            }).collect::<Vec<_>>(),
            "model": self.model.name(),
            "effects": self.effects.to_vec().iter().map(|e| effects::info(*e).name).collect::<Vec<_>>(),
            "params": ps,
            "bound": match self.bound { Bound::Elliptic => "elliptic", Bound::Parabolic => "parabolic" },
            "grid": self.grid,
            "scheme": self.scheme.name(),
            "geometry": geometry,
        });
        if self.preset != "custom" {
            // provenance; every value is given explicitly as well
            v["preset"] = Value::String(self.preset.clone());
        }
        v
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
    fn a_configuration_names_its_scheme() {
        use crate::engine::Scheme;
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
