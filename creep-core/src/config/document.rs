//! The JSON document of a configuration (its keys in [`super`]): reading it over its preset, each key's errors naming it, and writing it back.

use super::{
    AnyModifier, Bound, Config, Geometry, Grid, ModelKind, DEFAULT_GEOMETRY, DEFAULT_GRID,
};
use crate::effects::{self, Effect, EffectSet};
use crate::error::{CreepError, Result};
use crate::modifier::Modifier;
use crate::params::{self, Params};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

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
    temperature_solve: Option<String>,
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

impl Config {
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
            cfg.scheme = crate::scheme::Scheme::by_name(name).ok_or_else(|| {
                cfg_err(
                    src,
                    format!(
                        "scheme: '{name}' is not a scheme (expected {})",
                        crate::scheme::Scheme::NAMES
                    ),
                )
            })?;
        }
        if let Some(name) = &raw.temperature_solve {
            cfg.temperature_solve =
                crate::thermal::TemperatureSolve::by_name(name).ok_or_else(|| {
                    cfg_err(
                        src,
                        format!(
                            "temperature_solve: '{name}' is not a temperature solve (expected {})",
                            crate::thermal::TemperatureSolve::NAMES
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
                    scheme: model.default_scheme(),
                    temperature_solve: crate::thermal::TemperatureSolve::default(),
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
        // written where it is not the default, so that documents and saved states of the
        // default are as before the key existed
        if self.temperature_solve != crate::thermal::TemperatureSolve::default() {
            v["temperature_solve"] = Value::String(self.temperature_solve.name().into());
        }
        if self.preset != "custom" {
            // provenance; every value is given explicitly as well
            v["preset"] = Value::String(self.preset.clone());
        }
        v
    }
}
