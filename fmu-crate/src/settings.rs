//! The contact settings: the parameters as the importer set them, their checks and read-back, and the configuration they resolve to (preset or configuration file, then every value set).

pub use crate::vars::DEFAULT_REL_TOL;
use crate::vars::{Geo, In, Slot, Start, Value, Var, N_AUX, N_GEO, N_INPUTS};
use creep_core::effects::Effect;
use creep_core::params::{self, P};
use creep_core::scheme::Scheme;
use creep_core::thermal::TemperatureSolve;
use creep_core::{Config, Geometry, Grid, ModelKind, Modifier};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Largest configuration file accepted, bytes.
pub const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// Reads a configuration file: a regular file (after following links) of at most
/// [`MAX_CONFIG_BYTES`]; anything else (FIFO, device, directory, socket) is refused without
/// reading from it, so it can neither block nor exhaust memory.
pub fn read_config(path: &Path) -> Result<Config, String> {
    let text = read_config_text(path)?;
    Config::from_json_str(&text, &path.display().to_string()).map_err(|e| e.to_string())
}

/// The text of a configuration file, with the checks of [`read_config`].
fn read_config_text(path: &Path) -> Result<String, String> {
    use std::io::Read;
    let shown = path.display();
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot read '{shown}': {e}"))?;
    if !meta.is_file() {
        return Err(format!(
            "'{shown}' is not a regular file (a directory, FIFO, device or socket); give a JSON file"
        ));
    }
    if meta.len() > MAX_CONFIG_BYTES {
        return Err(format!(
            "'{shown}' has {} bytes; a configuration file may have at most {MAX_CONFIG_BYTES} bytes (1 MiB)",
            meta.len()
        ));
    }
    let f = std::fs::File::open(path).map_err(|e| format!("cannot read '{shown}': {e}"))?;
    let mut text = String::new();
    // the limit holds even if the file grows between the check and the read
    f.take(MAX_CONFIG_BYTES + 1)
        .read_to_string(&mut text)
        .map_err(|e| format!("cannot read '{shown}': {e}"))?;
    if text.len() as u64 > MAX_CONFIG_BYTES {
        return Err(format!(
            "'{shown}' grew beyond {MAX_CONFIG_BYTES} bytes while it was read"
        ));
    }
    Ok(text)
}

/// Path of a configuration file: absolute, or relative to the FMU's resources/ folder.
pub fn config_path(resources: Option<&Path>, file: &str) -> Result<PathBuf, String> {
    let p = Path::new(file);
    if p.is_absolute() {
        return Ok(p.to_path_buf());
    }
    match resources {
        Some(r) => Ok(r.join(p)),
        None => Err(format!(
            "config_file '{file}' is relative, but the importer gave no local fmuResourceLocation to resolve it against"
        )),
    }
}

/// Reads and parses a configuration file: only a regular file of at most
/// [`MAX_CONFIG_BYTES`] (a FIFO, a device or a directory is refused before opening it).
pub fn read_config_file(resources: Option<&Path>, file: &str) -> Result<Config, String> {
    read_config(&config_path(resources, file)?)
}

/// [`read_config_file`], and whether the file gives a `grid` (a top-level key `grid`,
/// whatever its value), from the one read.
fn read_config_file_and_grid(
    resources: Option<&Path>,
    file: &str,
) -> Result<(Config, bool), String> {
    let path = config_path(resources, file)?;
    let text = read_config_text(&path)?;
    let cfg =
        Config::from_json_str(&text, &path.display().to_string()).map_err(|e| e.to_string())?;
    Ok((cfg, names_grid(&text)))
}

/// True if a configuration document has a top-level key `grid` (whatever its value).
fn names_grid(text: &str) -> bool {
    serde_json::from_str::<serde_json::Value>(text).is_ok_and(|v| v.get("grid").is_some())
}

/// Where a data column's value comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ColumnSource {
    /// Auxiliary input (0-based: aux1 = 0).
    Aux(usize),
    /// A constant.
    Const(f64),
}

/// Parses the `columns` parameter: `NAME=auxK` or `NAME=VALUE`, comma or semicolon separated.
pub fn parse_columns(text: &str) -> Result<Vec<(String, ColumnSource)>, String> {
    let mut out: Vec<(String, ColumnSource)> = Vec::new();
    for item in text.split([',', ';']) {
        let item = item.trim();
        if item.is_empty() {
            continue;
        }
        let Some((name, src)) = item.split_once('=') else {
            return Err(format!("'{item}': expected NAME=auxK or NAME=VALUE"));
        };
        let (name, src) = (name.trim(), src.trim());
        if name.is_empty() || !name.chars().all(|c| c.is_alphanumeric() || c == '_') {
            return Err(format!(
                "'{item}': the column name must be letters, digits or '_'"
            ));
        }
        if out.iter().any(|(n, _)| n == name) {
            return Err(format!("column '{name}' is mapped twice"));
        }
        let source = if let Some(k) = src.strip_prefix("aux") {
            match k.parse::<usize>() {
                Ok(k) if (1..=N_AUX).contains(&k) => ColumnSource::Aux(k - 1),
                _ => {
                    return Err(format!(
                        "'{item}': there are the auxiliary inputs aux1 ... aux{N_AUX}"
                    ))
                }
            }
        } else {
            match src.parse::<f64>() {
                Ok(x) if x.is_finite() => ColumnSource::Const(x),
                _ => {
                    return Err(format!(
                        "'{item}': '{src}' is neither an auxiliary input (aux1 ... aux{N_AUX}) nor a finite number"
                    ))
                }
            }
        };
        out.push((name.to_string(), source));
    }
    Ok(out)
}

/// The data columns a configuration's formula and custom effects read.
pub fn columns_used(cfg: &Config) -> Vec<String> {
    let mut v: Vec<String> = Vec::new();
    let names = cfg
        .modifiers
        .iter()
        .flat_map(|m| m.columns().into_iter().map(|s| s.to_string()));
    for n in names {
        if !v.contains(&n) {
            v.push(n);
        }
    }
    v
}

/// The data column values of a configuration with formula or custom effects (None
/// without them): each column it reads, from its auxiliary input or constant.
pub fn extras_for(
    cfg: &Config,
    columns: &str,
    inputs: &[f64; N_INPUTS],
) -> Result<Option<Vec<(String, f64)>>, String> {
    if cfg.modifiers.is_empty() {
        return Ok(None);
    }
    let map = parse_columns(columns)?;
    let mut out = Vec::new();
    for name in columns_used(cfg) {
        let Some((_, src)) = map.iter().find(|(n, _)| *n == name) else {
            return Err(format!(
                "the configuration's formula or custom effects read the data column '{name}', which the parameter columns does not map (columns = '{}'); set e.g. columns = \"{name}=aux1\" and feed the input aux1, or columns = \"{name}=50\" for a constant",
                columns
            ));
        };
        let x = match *src {
            ColumnSource::Aux(k) => inputs[In::Aux(k).index()],
            ColumnSource::Const(x) => x,
        };
        out.push((name, x));
    }
    Ok(Some(out))
}

/// Parameter settings as the importer gave them; everything not given comes from the
/// preset or configuration file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Settings {
    /// Model family name.
    pub model: String,
    /// True once `model` was set by the importer.
    pub model_set: bool,
    /// Preset name ("" = the model's default).
    pub preset: String,
    /// Configuration file ("" = none).
    pub config_file: String,
    /// Data columns of formula/custom effects ("" = none), see [`parse_columns`].
    pub columns: String,
    /// Parameters set by the importer (display units).
    pub params: BTreeMap<P, f64>,
    /// Effect switches set by the importer.
    pub effects: BTreeMap<Effect, bool>,
    /// Grid cells per strip, if set.
    pub nx: Option<usize>,
    /// Grid strips, if set.
    pub ny: Option<usize>,
    /// Threads that advance the strips (0 or 1: the calling thread).
    pub threads: usize,
    /// How a step advances the bristles, if set: 1 continuous, 2 cell by cell with the
    /// higher-order rules, 3 cell by cell ([`scheme_code`]). None (the start value 0): the
    /// configuration's `scheme` (its model's default, `cells-ho` for ECF, unless the
    /// configuration file names another).
    pub scheme: Option<i32>,
    /// How the local temperature of a bristle move is solved, if set: 1 exact, 2 the
    /// predictor-corrector ([`temperature_solve_code`]). None (the start value 0): the
    /// configuration's `temperature_solve`.
    pub temperature_solve: Option<i32>,
    /// Relative tolerance on F_x that chooses the grid and scheme at initialization
    /// (fraction; 0 = off), if set to a value other than its start value
    /// [`DEFAULT_REL_TOL`]; see [`Settings::rel_tol`].
    pub rel_tol: Option<f64>,
    /// Geometry mode: 0 configuration, 1 semi-axes, 2 curvatures.
    pub geometry: i32,
    /// Geometry values set by the importer, in the order of [`Geo::ALL`], SI.
    pub geo: [Option<f64>; N_GEO],
}

/// The value of a geometry parameter in a configuration's geometry, if it has one.
fn geo_of(geometry: Geometry, g: Geo) -> Option<f64> {
    match (geometry, g) {
        (Geometry::SemiAxes { a, .. }, Geo::ARef) => Some(a),
        (Geometry::SemiAxes { b, .. }, Geo::BRef) => Some(b),
        (Geometry::SemiAxes { fn_ref, .. }, Geo::FnRef) => Some(fn_ref),
        (Geometry::Curvatures { rx, .. }, Geo::Rx) => Some(rx),
        (Geometry::Curvatures { ry, .. }, Geo::Ry) => Some(ry),
        _ => None,
    }
}

/// The code of the parameter `scheme` for an engine scheme ([`Scheme::fmu_code`], the
/// table [`creep_core::scheme::SCHEMES`]). 0, the start value, is "not set".
pub fn scheme_code(s: Scheme) -> i32 {
    s.fmu_code()
}

/// The engine scheme of a code of the parameter `scheme` ([`scheme_code`]; 0 and any other
/// code: cell by cell).
pub fn scheme_of_code(c: i32) -> Scheme {
    Scheme::by_fmu_code(c).unwrap_or(Scheme::CellsMarch)
}

/// The code of the parameter `temperature_solve` for a solve: 1 exact, 2 the
/// predictor-corrector. 0, the start value, is "not set".
pub fn temperature_solve_code(s: TemperatureSolve) -> i32 {
    match s {
        TemperatureSolve::Exact => 1,
        TemperatureSolve::PredictorCorrector => 2,
    }
}

impl Settings {
    /// The temperature solve of the parameter `temperature_solve`, if set (None: the
    /// configuration's).
    pub fn temperature_solve(&self) -> Option<TemperatureSolve> {
        TemperatureSolve::ALL
            .into_iter()
            .find(|s| Some(temperature_solve_code(*s)) == self.temperature_solve)
    }

    /// The tolerance in force: the value set; at the start value, [`DEFAULT_REL_TOL`] unless
    /// the grid is given, by both `nx` and `ny` or by the configuration file's `grid` (an
    /// explicit grid is the user's: the default tolerance does not apply, so neither the
    /// grid nor the scheme changes; a value set by the user does, among the table's rows
    /// with that grid). `file_grid`: whether the configuration file gives a `grid`, as
    /// [`Self::resolve`] (which reads the file) or [`Self::file_names_grid`] tell.
    pub fn rel_tol(&self, file_grid: bool) -> f64 {
        match self.rel_tol {
            Some(x) => x,
            None if self.nx.is_some() && self.ny.is_some() => 0.0,
            None if file_grid => 0.0,
            None => DEFAULT_REL_TOL,
        }
    }

    /// True if the configuration file, if any, has a `grid` (an unreadable file: false; its
    /// error is reported where the configuration is resolved). Reads the file: for when
    /// [`Self::resolve`] has not (`resources`: where a relative configuration file is).
    pub fn file_names_grid(&self, resources: Option<&Path>) -> bool {
        if self.config_file.is_empty() {
            return false;
        }
        config_path(resources, &self.config_file)
            .ok()
            .and_then(|p| read_config_text(&p).ok())
            .is_some_and(|t| names_grid(&t))
    }

    /// The value `rel_tol` reads back: as set, else its start value.
    pub fn rel_tol_value(&self) -> f64 {
        self.rel_tol.unwrap_or(DEFAULT_REL_TOL)
    }

    /// Checks the settings like the set calls do (for a deserialized state).
    pub fn validate(&self) -> Result<(), String> {
        let mut scratch = params::Params::default();
        for (p, x) in &self.params {
            scratch
                .set(*p, *x)
                .map_err(|e| format!("parameters: {e}"))?;
        }
        let rt = self.rel_tol_value();
        if !(rt == 0.0 || (rt > 0.0 && rt <= 1.0)) {
            return Err(format!("rel_tol = {rt} (must be 0 or within (0, 1])"));
        }
        if !(0..=2).contains(&self.geometry) {
            return Err(format!("geometry = {} (must be 0, 1 or 2)", self.geometry));
        }
        for (i, g) in self.geo.iter().enumerate() {
            if let Some(x) = g {
                if !(x.is_finite() && *x > 0.0) {
                    return Err(format!("geometry value {i} = {x} (must be finite and > 0)"));
                }
            }
        }
        let grid_ok =
            |n: Option<usize>, lo: usize, hi: usize| n.is_none_or(|n| (lo..=hi).contains(&n));
        if !grid_ok(self.nx, 2, 2000) || !grid_ok(self.ny, 1, 1000) {
            return Err(format!("grid {:?} x {:?} out of range", self.nx, self.ny));
        }
        if !self.model.is_empty() {
            ModelKind::parse(&self.model).map_err(|e| format!("model: {e}"))?;
        }
        parse_columns(&self.columns).map_err(|e| format!("columns: {e}"))?;
        if !self.preset.is_empty() {
            Config::preset(&self.preset).map_err(|e| format!("preset: {e}"))?;
        }
        Ok(())
    }

    /// Checks one value for a parameter without changing anything: None if the variable is
    /// not a parameter of this type, else the reason of a refusal, if any.
    pub fn check(v: &Var, x: &Value, resources: Option<&Path>) -> Option<Result<(), String>> {
        Some(match (v.slot, x) {
            (Slot::Param(p), Value::Real(x)) => {
                let mut scratch = params::Params::default();
                scratch.set(p, *x).map_err(|e| e.to_string())
            }
            (Slot::Geo(_), Value::Real(x)) => {
                if x.is_finite() && *x > 0.0 {
                    Ok(())
                } else {
                    let unit = v.unit.unwrap_or("");
                    Err(format!("must be finite and > 0 {unit}"))
                }
            }
            (
                Slot::GeometryMode
                | Slot::Nx
                | Slot::Ny
                | Slot::Threads
                | Slot::Scheme
                | Slot::TemperatureSolve,
                Value::Integer(x),
            ) => {
                let (lo, hi) = (v.min.unwrap_or(0.0) as i32, v.max.unwrap_or(1e9) as i32);
                if *x < lo || *x > hi {
                    Err(format!("must be within [{lo}, {hi}] ({})", v.description))
                } else if v.slot == Slot::Nx && *x == 1 {
                    Err(
                        "a strip needs at least 2 cells: give 0 (from the preset) or 2 ... 2000"
                            .into(),
                    )
                } else {
                    Ok(())
                }
            }
            (Slot::RelTol, Value::Real(x)) => {
                if *x == 0.0 {
                    Ok(())
                } else {
                    creep_core::tolerance::check_tol(*x, "rel_tol")
                        .map_err(|e| format!("{e}; or 0: off"))
                        .and_then(|()| {
                            if *x <= 1.0 {
                                Ok(())
                            } else {
                                Err(format!("rel_tol = {x}: must be within [0, 1] (a fraction: 0.01 = 1 %; 0: off)"))
                            }
                        })
                }
            }
            (Slot::Effect(_), Value::Boolean(_)) => Ok(()),
            (Slot::Model, Value::String(x)) if !x.is_empty() => ModelKind::parse(x)
                .map(|_| ())
                .map_err(|e| format!("{e}; or empty: the preset's model")),
            (Slot::Columns, Value::String(x)) => parse_columns(x).map(|_| ()),
            (Slot::Preset, Value::String(x)) if !x.is_empty() => {
                Config::preset(x).map(|_| ()).map_err(|e| e.to_string())
            }
            (Slot::ConfigFile, Value::String(x)) if !x.is_empty() => {
                read_config_file(resources, x).map(|_| ())
            }
            (Slot::Model | Slot::Preset | Slot::ConfigFile, Value::String(_)) => Ok(()),
            _ => return None,
        })
    }

    /// Applies one value that [`Self::check`] accepted; false if the variable is not a
    /// parameter of this type. A value equal to the start value is 'not set' (an importer
    /// writes every start value; the preset's value must stay in force): see vars::UNSET.
    pub fn apply(&mut self, v: &Var, x: &Value) -> bool {
        match (v.slot, x) {
            (Slot::Param(p), Value::Real(x)) => {
                if v.start == Start::Real(*x) {
                    self.params.remove(&p);
                } else {
                    self.params.insert(p, *x);
                }
            }
            (Slot::Geo(g), Value::Real(x)) => {
                self.geo[g.index()] = (v.start != Start::Real(*x)).then_some(*x)
            }
            (Slot::GeometryMode, Value::Integer(x)) => self.geometry = *x,
            (Slot::Nx, Value::Integer(x)) => self.nx = (*x > 0).then_some(*x as usize),
            (Slot::Ny, Value::Integer(x)) => self.ny = (*x > 0).then_some(*x as usize),
            (Slot::Threads, Value::Integer(x)) => self.threads = (*x).max(1) as usize,
            (Slot::TemperatureSolve, Value::Integer(x)) => {
                self.temperature_solve = (*x != 0).then_some(*x)
            }
            (Slot::Scheme, Value::Integer(x)) => {
                self.scheme = (v.start != Start::Integer(*x)).then_some(*x)
            }
            (Slot::RelTol, Value::Real(x)) => self.rel_tol = (*x != DEFAULT_REL_TOL).then_some(*x),
            (Slot::Effect(e), Value::Boolean(x)) => {
                if v.start == Start::Boolean(*x) {
                    self.effects.remove(&e);
                } else {
                    self.effects.insert(e, *x);
                }
            }
            (Slot::Model, Value::String(x)) => {
                self.model = x.clone();
                self.model_set = !x.is_empty();
            }
            (Slot::Columns, Value::String(x)) => self.columns = x.clone(),
            (Slot::Preset, Value::String(x)) => self.preset = x.clone(),
            (Slot::ConfigFile, Value::String(x)) => self.config_file = x.clone(),
            _ => return false,
        }
        true
    }

    /// The value of a setting that a state carries, if the importer set it: every parameter
    /// but `threads`, `scheme`, `temperature_solve` and `rel_tol`, which are the restoring
    /// instance's (they say how to compute, not what). None: not set (its start value), or
    /// not carried. [`Self::apply`] of the value sets it again.
    pub fn stored(&self, slot: Slot) -> Option<Value> {
        match slot {
            Slot::Param(p) => self.params.get(&p).map(|x| Value::Real(*x)),
            Slot::Geo(g) => self.geo[g.index()].map(Value::Real),
            Slot::GeometryMode => (self.geometry != 0).then_some(Value::Integer(self.geometry)),
            Slot::Nx => self.nx.map(|n| Value::Integer(n as i32)),
            Slot::Ny => self.ny.map(|n| Value::Integer(n as i32)),
            Slot::Effect(e) => self.effects.get(&e).map(|on| Value::Boolean(*on)),
            Slot::Model => self.model_set.then(|| Value::String(self.model.clone())),
            Slot::Preset => (!self.preset.is_empty()).then(|| Value::String(self.preset.clone())),
            Slot::ConfigFile => {
                (!self.config_file.is_empty()).then(|| Value::String(self.config_file.clone()))
            }
            Slot::Columns => {
                (!self.columns.is_empty()).then(|| Value::String(self.columns.clone()))
            }
            Slot::Threads
            | Slot::Scheme
            | Slot::TemperatureSolve
            | Slot::RelTol
            | Slot::Input(_)
            | Slot::Output(_) => None,
        }
    }

    /// The value of a parameter: as set, else from the resolved configuration `cfg` (called
    /// only when needed). None if the variable is not a parameter.
    pub fn get<'c>(
        &self,
        v: &Var,
        cfg: impl FnOnce() -> Result<&'c Config, String>,
    ) -> Option<Result<Value, String>> {
        Some(Ok(match v.slot {
            Slot::Param(p) => Value::Real(match self.params.get(&p) {
                Some(x) => *x,
                None => match cfg() {
                    Ok(c) => c.params.get(p),
                    Err(e) => return Some(Err(e)),
                },
            }),
            Slot::Geo(g) => Value::Real(match self.geo[g.index()] {
                Some(x) => x,
                None => match cfg() {
                    Ok(c) => geo_of(c.geometry, g).unwrap_or(g.start()),
                    Err(e) => return Some(Err(e)),
                },
            }),
            Slot::GeometryMode => Value::Integer(self.geometry),
            Slot::Threads => Value::Integer(self.threads.max(1) as i32),
            Slot::TemperatureSolve => Value::Integer(match self.temperature_solve {
                Some(x) => x,
                None => match cfg() {
                    Ok(c) => temperature_solve_code(c.temperature_solve),
                    Err(e) => return Some(Err(e)),
                },
            }),
            Slot::Scheme => Value::Integer(match self.scheme {
                Some(x) => x,
                None => match cfg() {
                    Ok(c) => scheme_code(c.scheme),
                    Err(e) => return Some(Err(e)),
                },
            }),
            Slot::RelTol => Value::Real(self.rel_tol_value()),
            Slot::Nx | Slot::Ny => match cfg() {
                Ok(c) => Value::Integer(if v.slot == Slot::Nx {
                    c.grid.nx
                } else {
                    c.grid.ny
                } as i32),
                Err(e) => return Some(Err(e)),
            },
            Slot::Effect(e) => Value::Boolean(match self.effects.get(&e) {
                Some(on) => *on,
                None => match cfg() {
                    Ok(c) => c.effects.has(e),
                    Err(err) => return Some(Err(err)),
                },
            }),
            Slot::Model => Value::String(if self.model_set {
                self.model.clone()
            } else {
                match cfg() {
                    Ok(c) => c.model.name().to_string(),
                    Err(_) => self.model.clone(),
                }
            }),
            Slot::Preset => Value::String(self.preset.clone()),
            Slot::Columns => Value::String(self.columns.clone()),
            Slot::ConfigFile => Value::String(self.config_file.clone()),
            Slot::Input(_) | Slot::Output(_) => return None,
        }))
    }

    /// The engine's scheme of the parameter `scheme` ([`scheme_code`]), if set (None: the
    /// configuration's).
    pub fn scheme(&self) -> Option<Scheme> {
        self.scheme.map(scheme_of_code)
    }

    /// The preset's or configuration file's configuration, and whether the file gives a
    /// `grid` (false without a file).
    fn base_config(&self, resources: Option<&Path>) -> Result<(Config, bool), String> {
        let s = self;
        let check_model = |c: &Config, what: &str| -> Result<(), String> {
            if s.model_set && c.model.name() != s.model {
                let of_model: Vec<&str> = creep_core::config::PRESETS
                    .iter()
                    .filter(|(n, _)| {
                        Config::preset(n)
                            .map(|p| p.model.name() == s.model)
                            .unwrap_or(false)
                    })
                    .map(|(n, _)| *n)
                    .collect();
                Err(format!(
                    "model = '{}' but {what} is a '{}' configuration: leave model empty (it then follows the preset or file) or choose a configuration of model '{}' (presets: {})",
                    s.model,
                    c.model.name(),
                    s.model,
                    of_model.join(", ")
                ))
            } else {
                Ok(())
            }
        };
        if !s.config_file.is_empty() {
            if !s.preset.is_empty() {
                return Err(format!(
                    "preset = '{}' and config_file = '{}' are both set; set one of them (a configuration file can name a preset itself)",
                    s.preset, s.config_file
                ));
            }
            let (c, grid) = read_config_file_and_grid(resources, &s.config_file)
                .map_err(|e| format!("config_file: {e}"))?;
            check_model(&c, &format!("config_file '{}'", s.config_file))?;
            Ok((c, grid))
        } else if !s.preset.is_empty() {
            let c = Config::preset(&s.preset).map_err(|e| format!("preset: {e}"))?;
            check_model(&c, &format!("preset '{}'", s.preset))?;
            Ok((c, false))
        } else if s.model_set {
            let c = Config::for_model(&s.model).map_err(|e| format!("model: {e}"))?;
            Ok((c, false))
        } else {
            let c = Config::for_model("ecf").map_err(|e| format!("model: {e}"))?;
            Ok((c, false))
        }
    }

    /// The grid and scheme that `rel_tol` chooses at speed `v` (m/s), None when rel_tol = 0
    /// or the model is not ECF (the table is measured for it). Explicit nx, ny and scheme = 1
    /// or 2 restrict the choice to the table's rows with them; when the table has none, Err for
    /// a value set by the user, None for the start value. `file_grid` as for
    /// [`Self::rel_tol`].
    pub fn tolerance_choice(
        &self,
        cfg: &Config,
        v: f64,
        file_grid: bool,
    ) -> Option<Result<creep_core::tolerance::Choice, String>> {
        let rel_tol = self.rel_tol(file_grid);
        if rel_tol <= 0.0 || cfg.model != ModelKind::Ecf {
            return None;
        }
        // parsed once here: the compiled-in table is not cached (creep_core::tolerance::table)
        let rows = match creep_core::tolerance::table() {
            Ok(rows) => rows,
            Err(e) => return Some(Err(format!("rel_tol = {rel_tol}: {e}"))),
        };
        let filter = creep_core::tolerance::Filter {
            preset: creep_core::tolerance::scope_in(&rows, cfg),
            nx: self.nx,
            ny: self.ny,
            // the parameter's scheme, else the configuration's (as the CLI's --tol)
            scheme: self
                .scheme()
                .or(creep_core::tolerance::restricting_scheme(cfg, false)),
            steady: false,
        };
        match creep_core::tolerance::choose_in(&rows, rel_tol, v, None, filter) {
            Ok(c) => Some(Ok(c)),
            // the start value is no request: with explicit settings the table lacks, they
            // are used as they are, without a word
            Err(_) if self.rel_tol.is_none() => None,
            Err(e) => Some(Err(format!(
                "rel_tol = {rel_tol}: {e}; the explicit settings are used"
            ))),
        }
    }

    /// Sets the geometry of `cfg` from the geometry mode (1 semi-axes, 2 curvatures; 0
    /// leaves it): each value as set, else `cfg`'s, else its start value.
    pub fn apply_geometry(&self, cfg: &mut Config) {
        let base = cfg.geometry;
        let g = |g: Geo| {
            self.geo[g.index()]
                .or(geo_of(base, g))
                .unwrap_or_else(|| g.start())
        };
        match self.geometry {
            1 => {
                cfg.geometry = Geometry::SemiAxes {
                    a: g(Geo::ARef),
                    b: g(Geo::BRef),
                    fn_ref: g(Geo::FnRef),
                }
            }
            2 => {
                cfg.geometry = Geometry::Curvatures {
                    rx: g(Geo::Rx),
                    ry: g(Geo::Ry),
                }
            }
            _ => {}
        }
    }

    /// Resolves the configuration: preset or file (relative paths against `resources`),
    /// then every parameter the importer set; with rel_tol > 0, the grid it chooses at the
    /// speed `v` (m/s, the input's current value). Also returns whether the configuration
    /// file gives a `grid` (for [`Self::rel_tol`]; false without a file), from the same read.
    pub fn resolve(&self, resources: Option<&Path>, v: f64) -> Result<(Config, bool), String> {
        let s = self;
        let (mut cfg, file_grid) = self.base_config(resources)?;
        for (p, x) in &s.params {
            cfg.params.set(*p, *x).map_err(|e| e.to_string())?;
        }
        for (e, on) in &s.effects {
            if *on {
                cfg.effects.insert(*e);
            } else {
                cfg.effects.remove(*e);
            }
        }
        let grid = Grid {
            nx: s.nx.unwrap_or(cfg.grid.nx),
            ny: s.ny.unwrap_or(cfg.grid.ny),
        };
        grid.validate().map_err(|e| e.to_string())?;
        cfg.grid = grid;
        self.apply_geometry(&mut cfg);
        if cfg.model == ModelKind::Fastsim && !cfg.effects.has(Effect::Coulomb) {
            return Err("model fastsim needs effect_coulomb = true".into());
        }
        if let Some(Ok(c)) = self.tolerance_choice(&cfg, v, file_grid) {
            cfg.grid = Grid { nx: c.nx, ny: c.ny };
        }
        Ok((cfg, file_grid))
    }
}
