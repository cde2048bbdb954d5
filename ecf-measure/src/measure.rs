//! Measurement files: steady characteristics, time series and high-pressure-torsion curves, read completely or refused with file, line, column and reason.
//!
//! A measurement file is CSV with a header row; one row per measured point. The delimiter
//! (`,`, `;` or tab) is detected from the header; with `;` a decimal comma is accepted.
//! Column names are recognised with their usual spellings and units (`v_mps`, `v [m/s]`,
//! `v_kmh`, `FN [kN]`, `Fn_N`, `cx [%]`, `creepage_pct`, ...; table [`QUANTITIES`]) and
//! converted; [`Dataset::columns`] records which column became which quantity in what unit.
//! Required: creepage `cx` and traction coefficient `f`; speed and normal force are required
//! unless [`Defaults`] gives them. Any other column must be numeric and is kept as an extra
//! variable. Rows of one series with `t_s` form a time series. A file is read completely or
//! not at all: the first problem is reported with file, line, column and reason.

use creep_core::engine::Inputs;
use creep_core::error::{CreepError, Result};
use std::collections::BTreeMap;
use std::path::Path;

/// CV(RMSE) lives in [`crate::stats`]; re-exported here, where it was first.
pub use crate::stats::cv_rmse_pct;

/// Canonical column names (the quantities the reader knows).
pub const KNOWN: &[&str] = &[
    "cx",
    "f",
    "series",
    "condition",
    "v_mps",
    "fn_kN",
    "a_mm",
    "b_mm",
    "cy",
    "cs_per_m",
    "t_s",
    "t_bulk_C",
];

/// A quantity the reader knows: canonical name, meaning, accepted base spellings (lower
/// case), accepted units (lower case, factor to the canonical unit, offset added after the
/// factor; "" = no unit written), and whether a unit must be written.
pub struct Quantity {
    /// Canonical column name (carries the canonical unit).
    pub name: &'static str,
    /// Meaning.
    pub meaning: &'static str,
    /// Base spellings, lower case.
    pub aliases: &'static [&'static str],
    /// Units: (spelling lower case, factor, offset).
    pub units: &'static [(&'static str, f64, f64)],
    /// A unit must be written (dimensional quantities).
    pub needs_unit: bool,
    /// Text column (no unit).
    pub text: bool,
}

const CREEPAGE_UNITS: &[(&str, f64, f64)] = &[
    ("", 1.0, 0.0),
    ("-", 1.0, 0.0),
    ("1", 1.0, 0.0),
    ("%", 0.01, 0.0),
    ("pct", 0.01, 0.0),
    ("percent", 0.01, 0.0),
];

/// The known quantities with their spellings and units.
pub const QUANTITIES: &[Quantity] = &[
    Quantity {
        name: "cx",
        meaning: "longitudinal creepage",
        aliases: &[
            "cx",
            "c_x",
            "creepage",
            "creepage_x",
            "longitudinal_creepage",
        ],
        units: CREEPAGE_UNITS,
        needs_unit: false,
        text: false,
    },
    Quantity {
        name: "f",
        meaning: "measured traction coefficient F_x/F_N",
        aliases: &[
            "f",
            "traction",
            "traction_coefficient",
            "adhesion",
            "adhesion_coefficient",
        ],
        units: &[("", 1.0, 0.0), ("-", 1.0, 0.0), ("1", 1.0, 0.0)],
        needs_unit: false,
        text: false,
    },
    Quantity {
        name: "series",
        meaning: "test / curve name",
        aliases: &["series", "curve", "test", "run"],
        units: &[("", 1.0, 0.0)],
        needs_unit: false,
        text: true,
    },
    Quantity {
        name: "condition",
        meaning: "contact condition",
        aliases: &["condition", "cond", "surface"],
        units: &[("", 1.0, 0.0)],
        needs_unit: false,
        text: true,
    },
    Quantity {
        name: "v_mps",
        meaning: "vehicle speed",
        aliases: &["v", "speed", "velocity", "vehicle_speed"],
        units: &[
            ("m/s", 1.0, 0.0),
            ("mps", 1.0, 0.0),
            ("km/h", 1.0 / 3.6, 0.0),
            ("kmh", 1.0 / 3.6, 0.0),
            ("kph", 1.0 / 3.6, 0.0),
        ],
        needs_unit: true,
        text: false,
    },
    Quantity {
        name: "fn_kN",
        meaning: "normal force per wheel",
        aliases: &["fn", "f_n", "normal_force", "load", "wheel_load"],
        units: &[("kn", 1.0, 0.0), ("n", 1e-3, 0.0)],
        needs_unit: true,
        text: false,
    },
    Quantity {
        name: "a_mm",
        meaning: "contact semi-axis in rolling direction",
        aliases: &["a"],
        units: &[("mm", 1.0, 0.0), ("m", 1e3, 0.0)],
        needs_unit: true,
        text: false,
    },
    Quantity {
        name: "b_mm",
        meaning: "lateral contact semi-axis",
        aliases: &["b"],
        units: &[("mm", 1.0, 0.0), ("m", 1e3, 0.0)],
        needs_unit: true,
        text: false,
    },
    Quantity {
        name: "cy",
        meaning: "lateral creepage",
        aliases: &["cy", "c_y", "lateral_creepage"],
        units: CREEPAGE_UNITS,
        needs_unit: false,
        text: false,
    },
    Quantity {
        name: "cs_per_m",
        meaning: "spin creepage",
        aliases: &["cs", "c_s", "spin"],
        units: &[
            ("per_m", 1.0, 0.0),
            ("1/m", 1.0, 0.0),
            ("per_mm", 1e3, 0.0),
            ("1/mm", 1e3, 0.0),
        ],
        needs_unit: true,
        text: false,
    },
    Quantity {
        name: "t_s",
        meaning: "time",
        aliases: &["t", "time"],
        units: &[("s", 1.0, 0.0), ("ms", 1e-3, 0.0)],
        needs_unit: true,
        text: false,
    },
    Quantity {
        name: "t_bulk_C",
        meaning: "bulk / ambient temperature",
        aliases: &[
            "t_bulk",
            "t",
            "t_ambient",
            "t_amb",
            "bulk_temperature",
            "ambient_temperature",
        ],
        units: &[
            ("c", 1.0, 0.0),
            ("degc", 1.0, 0.0),
            ("°c", 1.0, 0.0),
            ("k", 1.0, -273.15),
        ],
        needs_unit: true,
        text: false,
    },
];

/// Index of a quantity in [`QUANTITIES`] by canonical name.
fn qi(name: &str) -> usize {
    QUANTITIES
        .iter()
        .position(|q| q.name == name)
        .unwrap_or(usize::MAX)
}

/// Unit of the creepage columns when the header does not give one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CreepageUnit {
    /// Dimensionless (0.01 = 1 %).
    Dimensionless,
    /// Percent.
    Percent,
}

impl CreepageUnit {
    /// Parses `1`, `-`, `dimensionless`, `percent`, `%`, `pct`.
    pub fn parse(s: &str) -> Result<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "1" | "-" | "dimensionless" | "none" => Ok(CreepageUnit::Dimensionless),
            "percent" | "%" | "pct" => Ok(CreepageUnit::Percent),
            _ => Err(CreepError::Unknown {
                kind: "creepage unit (--cx-unit)".into(),
                name: s.into(),
                accepted: "1 (dimensionless), percent".into(),
            }),
        }
    }
    fn factor(self) -> f64 {
        match self {
            CreepageUnit::Dimensionless => 1.0,
            CreepageUnit::Percent => 0.01,
        }
    }
}

/// Values for quantities a file omits. Speed and normal force have no silent default: a
/// file without them is refused unless they are given here.
#[derive(Clone, Copy, Debug)]
pub struct Defaults {
    /// Vehicle speed, m/s, for files without a speed column.
    pub v_mps: Option<f64>,
    /// Normal force, kN, for files without a load column.
    pub fn_kn: Option<f64>,
    /// Bulk temperature, degC.
    pub t_bulk_c: f64,
    /// Unit of creepage columns whose header carries none.
    pub cx_unit: Option<CreepageUnit>,
}

impl Default for Defaults {
    fn default() -> Self {
        Defaults {
            v_mps: None,
            fn_kn: None,
            t_bulk_c: 20.0,
            cx_unit: None,
        }
    }
}

/// One measured point.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Line in the file (1-based, header = 1).
    pub line: usize,
    /// Series name.
    pub series: String,
    /// Contact condition.
    pub condition: String,
    /// Longitudinal creepage, -.
    pub cx: f64,
    /// Lateral creepage, -.
    pub cy: f64,
    /// Spin, 1/m.
    pub spin: f64,
    /// Speed, m/s.
    pub v: f64,
    /// Normal force, N.
    pub fn_n: f64,
    /// Semi-axes (m), when the file gives them.
    pub ab: Option<(f64, f64)>,
    /// Time, s (time series only).
    pub t: Option<f64>,
    /// Bulk temperature, degC.
    pub t_bulk: f64,
    /// Measured traction coefficient, -.
    pub f: f64,
    /// Extra numeric columns, in the order of [`Dataset::extra_names`].
    pub extra: Vec<f64>,
}

impl Row {
    /// Model inputs of the row.
    pub fn inputs(&self) -> Inputs {
        Inputs {
            cx: self.cx,
            cy: self.cy,
            spin: self.spin,
            v: self.v,
            fn_n: self.fn_n,
            t_bulk: self.t_bulk,
        }
    }
}

/// How one column (or a missing quantity) was read.
#[derive(Clone, Debug, PartialEq)]
pub struct ColumnMap {
    /// Header as written; empty for a quantity the file does not have.
    pub header: String,
    /// Canonical quantity name (`v_mps`, ...), or `None` for an extra column.
    pub quantity: Option<&'static str>,
    /// How the values were read, e.g. "km/h, x 0.2778 -> m/s", "default 20 degC".
    pub how: String,
}

/// A measurement file, read completely.
#[derive(Clone, Debug, PartialEq)]
pub struct Dataset {
    /// File name as given.
    pub source: String,
    /// Names of the extra numeric columns.
    pub extra_names: Vec<String>,
    /// Rows in file order.
    pub rows: Vec<Row>,
    /// Which column became which quantity in what unit (and the quantities given by default).
    pub columns: Vec<ColumnMap>,
    /// Field delimiter found in the header.
    pub delimiter: char,
}

fn err(src: &str, line: usize, column: &str, reason: String) -> CreepError {
    CreepError::Data {
        source_name: src.to_string(),
        message: format!("line {line}, column '{}': {reason}", cut(column)),
    }
}

/// A cell or name cut to 40 characters for messages.
pub fn cut(s: &str) -> String {
    let n = s.chars().count();
    if n <= 40 {
        s.to_string()
    } else {
        format!(
            "{}... ({n} characters)",
            s.chars().take(40).collect::<String>()
        )
    }
}

/// Text of a data file: UTF-8, else an error naming the line of the first bad byte.
pub fn utf8_text(bytes: &[u8], src: &str) -> Result<String> {
    match std::str::from_utf8(bytes) {
        Ok(t) => Ok(t.trim_start_matches('\u{feff}').to_string()),
        Err(e) => {
            let at = e.valid_up_to();
            let line = bytes[..at].iter().filter(|b| **b == b'\n').count() + 1;
            let col = at
                - bytes[..at]
                    .iter()
                    .rposition(|b| *b == b'\n')
                    .map(|p| p + 1)
                    .unwrap_or(0);
            Err(CreepError::Data {
                source_name: src.into(),
                message: format!(
                    "line {line}: not UTF-8 text (byte 0x{:02X} at character {} of the line); save the file as UTF-8",
                    bytes[at],
                    col + 1
                ),
            })
        }
    }
}

/// Delimiter of a CSV text: the most frequent of `,` `;` tab in the first non-comment line.
pub fn detect_delimiter(text: &str) -> u8 {
    let header = text
        .lines()
        .find(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty())
        .unwrap_or("");
    let count = |c: char| header.chars().filter(|x| *x == c).count();
    let (comma, semi, tab) = (count(','), count(';'), count('\t'));
    if semi > comma && semi >= tab {
        b';'
    } else if tab > comma && tab > semi {
        b'\t'
    } else {
        b','
    }
}

/// Splits a header into (base, unit): `v [m/s]`, `v (km/h)`, or `v_kmh` when the suffix is a
/// unit of a quantity whose spelling is the prefix. Returns the quantity index and the unit.
/// A header "name [unit]" or "name (unit)" split into its trimmed name and unit; a header
/// without a bracketed unit is (header, None).
fn split_bracket_unit(h: &str) -> (&str, Option<&str>) {
    let t = h.trim();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if t.ends_with(close) {
            if let Some(i) = t.rfind(open) {
                return (t[..i].trim(), Some(t[i + 1..t.len() - 1].trim()));
            }
        }
    }
    (t, None)
}

fn recognise(h: &str) -> Option<(usize, String)> {
    let norm = |s: &str| s.trim().to_lowercase().replace(' ', "_");
    let unit_norm = |s: &str| s.trim().to_lowercase().replace(' ', "");
    let find = |base: &str, unit: &str| -> Option<usize> {
        QUANTITIES
            .iter()
            .position(|q| q.aliases.contains(&base) && q.units.iter().any(|u| u.0 == unit))
    };
    let t = h.trim();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if t.ends_with(close) {
            if let Some(i) = t.rfind(open) {
                let base = norm(&t[..i]);
                let unit = unit_norm(&t[i + 1..t.len() - 1]);
                let unit = if unit == "1/m" || unit == "/m" {
                    "per_m".to_string()
                } else if unit == "1/mm" {
                    "per_mm".to_string()
                } else {
                    unit
                };
                return QUANTITIES
                    .iter()
                    .position(|q| q.aliases.contains(&base.as_str()))
                    .map(|k| (find(&base, &unit).unwrap_or(k), unit));
            }
        }
    }
    let whole = norm(t);
    // a name with a unit suffix: try every split at '_'
    for (i, _) in whole.match_indices('_') {
        let (base, unit) = (&whole[..i], &whole[i + 1..]);
        if let Some(k) = find(base, unit) {
            return Some((k, unit.to_string()));
        }
    }
    QUANTITIES
        .iter()
        .position(|q| q.aliases.contains(&whole.as_str()))
        .map(|k| (k, String::new()))
}

/// A column the reader understood.
#[derive(Clone, Copy)]
struct Col {
    idx: usize,
    factor: f64,
    offset: f64,
}

impl Dataset {
    /// Reads a measurement file.
    pub fn from_file(path: &Path, defaults: &Defaults) -> Result<Self> {
        let src = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| CreepError::Data {
            source_name: src.clone(),
            message: format!("cannot read: {e}"),
        })?;
        Self::from_csv_str(&utf8_text(&bytes, &src)?, &src, defaults)
    }

    /// Parses measurement CSV text; `src` names it in error messages.
    pub fn from_csv_str(text: &str, src: &str, defaults: &Defaults) -> Result<Self> {
        let delim = detect_delimiter(text);
        let (mut rdr, header) = open_csv(text, src, &[], delim)?;
        let decimal_comma = delim == b';';
        // map the header
        let mut cols: Vec<Option<Col>> = vec![None; QUANTITIES.len()];
        let mut columns = Vec::new();
        let mut extra_idx = Vec::new();
        let mut implicit_creepage: Vec<&'static str> = Vec::new();
        for (i, h) in header.iter().enumerate() {
            let Some((k, unit)) = recognise(h) else {
                extra_idx.push(i);
                continue;
            };
            let q = &QUANTITIES[k];
            if let Some(prev) = cols[k] {
                return Err(err(
                    src,
                    1,
                    h,
                    format!(
                        "'{}' and '{}' are both {} ({})",
                        cut(&header[prev.idx]),
                        cut(h),
                        q.meaning,
                        q.name
                    ),
                ));
            }
            let accepted = || {
                q.units
                    .iter()
                    .filter(|u| !u.0.is_empty())
                    .map(|u| u.0)
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            if unit.is_empty() && q.needs_unit {
                return Err(err(
                    src,
                    1,
                    h,
                    format!(
                        "{} needs a unit in the header, e.g. '{}' or '{} [{}]' (units: {})",
                        q.meaning,
                        q.name,
                        h.trim(),
                        q.units[0].0,
                        accepted()
                    ),
                ));
            }
            let Some(&(_, mut factor, offset)) = q.units.iter().find(|u| u.0 == unit) else {
                return Err(err(
                    src,
                    1,
                    h,
                    format!(
                        "unit '{}' is not a unit of {} (accepted: {})",
                        cut(&unit),
                        q.meaning,
                        accepted()
                    ),
                ));
            };
            let mut how = if q.text {
                "text".to_string()
            } else if unit.is_empty() {
                "no unit written".to_string()
            } else {
                format!("in {}", show_unit(&unit))
            };
            if q.name == "cx" || q.name == "cy" {
                match (unit.is_empty(), defaults.cx_unit) {
                    (true, Some(u)) => {
                        factor = u.factor();
                        how = format!(
                            "{} (--cx-unit)",
                            if factor == 1.0 {
                                "dimensionless"
                            } else {
                                "percent"
                            }
                        );
                    }
                    (true, None) => {
                        implicit_creepage.push(q.name);
                        how = "dimensionless (no unit written)".into();
                    }
                    (false, Some(u)) if u.factor() != factor => {
                        return Err(err(
                            src,
                            1,
                            h,
                            format!("the header says '{unit}' but --cx-unit says {u:?}"),
                        ))
                    }
                    _ => {}
                }
            }
            if factor != 1.0 || offset != 0.0 {
                how += &format!(", converted to {} (x {factor:.6}", canonical_unit(q.name));
                if offset != 0.0 {
                    how += &format!(" {offset:+}");
                }
                how += ")";
            }
            cols[k] = Some(Col {
                idx: i,
                factor,
                offset,
            });
            columns.push(ColumnMap {
                header: h.clone(),
                quantity: Some(q.name),
                how,
            });
        }
        for req in ["cx", "f"] {
            if cols[qi(req)].is_none() {
                let q = &QUANTITIES[qi(req)];
                return Err(err(
                    src,
                    1,
                    req,
                    format!(
                        "required column missing: {} (spellings: {}; have: {})",
                        q.meaning,
                        q.aliases.join(", "),
                        header.iter().map(|h| cut(h)).collect::<Vec<_>>().join(", ")
                    ),
                ));
            }
        }
        for (name, given, unit) in [
            ("v_mps", defaults.v_mps, "m/s (--v-mps)"),
            ("fn_kN", defaults.fn_kn, "kN (--fn-kN)"),
        ] {
            if cols[qi(name)].is_none() {
                let q = &QUANTITIES[qi(name)];
                let Some(x) = given else {
                    return Err(err(
                        src,
                        1,
                        name,
                        format!(
                            "no {} column (e.g. '{}', '{} [{}]'; have: {}); give it in the file or for every row with {}",
                            q.meaning,
                            q.name,
                            q.aliases[0],
                            q.units[0].0,
                            header.iter().map(|h| cut(h)).collect::<Vec<_>>().join(", "),
                            if name == "v_mps" { "--v-mps" } else { "--fn-kN" }
                        ),
                    ));
                };
                columns.push(ColumnMap {
                    header: String::new(),
                    quantity: Some(q.name),
                    how: format!("not in the file: {x} {unit}"),
                });
            }
        }
        if cols[qi("t_bulk_C")].is_none() {
            columns.push(ColumnMap {
                header: String::new(),
                quantity: Some("t_bulk_C"),
                how: format!("not in the file: {} degC (default)", defaults.t_bulk_c),
            });
        }
        // an extra column's name drops a bracketed unit ("humidity [%]" is the column
        // `humidity` of formula and Rust effects), unless that name is taken
        let extra_names: Vec<String> = extra_idx
            .iter()
            .map(|&i| {
                let (name, unit) = split_bracket_unit(&header[i]);
                let taken = header
                    .iter()
                    .enumerate()
                    .any(|(k, h)| k != i && (h == name || split_bracket_unit(h).0 == name));
                if unit.is_some() && !taken && !name.is_empty() {
                    name.to_string()
                } else {
                    header[i].clone()
                }
            })
            .collect();
        for (&i, name) in extra_idx.iter().zip(&extra_names) {
            let unit = split_bracket_unit(&header[i]).1;
            columns.push(ColumnMap {
                header: header[i].clone(),
                quantity: None,
                how: match unit {
                    Some(u) if *name != header[i] => format!(
                        "extra column '{name}' in {u} (not a known quantity; numeric, taken as written)"
                    ),
                    _ => "extra column (not a known quantity; numeric)".into(),
                },
            });
        }
        let (ia, ib) = (cols[qi("a_mm")], cols[qi("b_mm")]);
        if ia.is_some() != ib.is_some() {
            return Err(err(
                src,
                1,
                if ia.is_some() { "b_mm" } else { "a_mm" },
                "a_mm and b_mm come together".into(),
            ));
        }
        let col_of = |name: &str| cols[qi(name)];
        let mut rows = Vec::new();
        let mut rec = csv::StringRecord::new();
        let mut k = 0usize;
        let bytes = text.as_bytes();
        let (mut seen_byte, mut seen_line) = (0usize, 1usize);
        loop {
            k += 1;
            let more = rdr.read_record(&mut rec).map_err(|e| {
                err(
                    src,
                    e.position().map(|p| p.line() as usize).unwrap_or(k + 1),
                    "-",
                    cut(&e.to_string()),
                )
            })?;
            if !more {
                break;
            }
            // line from the byte offset (the csv crate's line count skips comment lines)
            let line = match rec.position() {
                Some(p) => {
                    let mut b = (p.byte() as usize).min(bytes.len());
                    // the record's position may be that of comment or empty lines before it
                    loop {
                        let rest = &text[b..];
                        let first = rest.split('\n').next().unwrap_or("");
                        let skip = first.trim_start().starts_with('#') || first.trim().is_empty();
                        match rest.find('\n') {
                            Some(n) if skip => b += n + 1,
                            _ => break,
                        }
                    }
                    if b >= seen_byte {
                        seen_line += bytes[seen_byte..b].iter().filter(|c| **c == b'\n').count();
                        seen_byte = b;
                    }
                    seen_line
                }
                None => k + 1,
            };
            if rec.len() != header.len() {
                return Err(err(
                    src,
                    line,
                    "-",
                    format!(
                        "{} fields, header has {} (delimiter '{}')",
                        rec.len(),
                        header.len(),
                        if delim == b'\t' {
                            "tab".to_string()
                        } else {
                            (delim as char).to_string()
                        }
                    ),
                ));
            }
            let parse = |i: usize| -> Result<f64> {
                let s = &rec[i];
                let x: f64 = if decimal_comma && s.contains(',') {
                    s.replace(',', ".").parse()
                } else {
                    s.parse()
                }
                .map_err(|_| {
                    err(
                        src,
                        line,
                        &header[i],
                        format!("'{}' is not a number", cut(s)),
                    )
                })?;
                if !x.is_finite() {
                    return Err(err(
                        src,
                        line,
                        &header[i],
                        format!("'{}' is not finite", cut(s)),
                    ));
                }
                Ok(x)
            };
            let opt = |name: &str| -> Result<Option<f64>> {
                match col_of(name) {
                    Some(c) if !rec[c.idx].is_empty() => {
                        parse(c.idx).map(|x| Some(x * c.factor + c.offset))
                    }
                    _ => Ok(None),
                }
            };
            let hdr = |name: &str| -> String {
                col_of(name)
                    .map(|c| header[c.idx].clone())
                    .unwrap_or_else(|| name.to_string())
            };
            let range = |name: &str, x: f64, lo: f64, hi: f64, what: &str| -> Result<f64> {
                if x < lo || x > hi {
                    Err(err(
                        src,
                        line,
                        &hdr(name),
                        format!("{x} is outside [{lo}, {hi}] {what}"),
                    ))
                } else {
                    Ok(x)
                }
            };
            let required = |name: &str| -> Result<f64> {
                opt(name)?.ok_or_else(|| err(src, line, &hdr(name), "empty".into()))
            };
            let percent_like = |name: &str, x: f64| -> Result<f64> {
                if x.abs() > 10.0 && implicit_creepage.contains(&name) {
                    return Err(err(src, line, &hdr(name), percent_message(name, x)));
                }
                Ok(x)
            };
            let cx = range(
                "cx",
                percent_like("cx", required("cx")?)?,
                -10.0,
                10.0,
                "(dimensionless creepage: 0.01 = 1 %)",
            )?;
            let f = range(
                "f",
                required("f")?,
                -2.0,
                2.0,
                "(traction coefficient F_x/F_N)",
            )?;
            let v = match opt("v_mps")? {
                Some(v) => v,
                None if col_of("v_mps").is_some() => {
                    return Err(err(src, line, &hdr("v_mps"), "empty".into()))
                }
                None => defaults.v_mps.unwrap_or(f64::NAN),
            };
            let v = range("v_mps", v, 0.0, 200.0, "m/s")?;
            let fn_kn = match opt("fn_kN")? {
                Some(x) => x,
                None if col_of("fn_kN").is_some() => {
                    return Err(err(src, line, &hdr("fn_kN"), "empty".into()))
                }
                None => defaults.fn_kn.unwrap_or(f64::NAN),
            };
            if fn_kn > 5000.0 {
                return Err(err(
                    src,
                    line,
                    &hdr("fn_kN"),
                    format!(
                        "{fn_kn} kN per wheel cannot be right: is the column in N instead of kN? (write 'fn_N' or 'FN [N]')"
                    ),
                ));
            }
            let fn_kn = range("fn_kN", fn_kn, 1e-6, 5000.0, "kN")?;
            let ab = match (opt("a_mm")?, opt("b_mm")?) {
                (Some(a), Some(b)) => Some((
                    range("a_mm", a, 1e-3, 500.0, "mm")? * 1e-3,
                    range("b_mm", b, 1e-3, 500.0, "mm")? * 1e-3,
                )),
                (None, None) => None,
                _ => {
                    return Err(err(
                        src,
                        line,
                        "a_mm/b_mm",
                        "give both semi-axes or neither".into(),
                    ))
                }
            };
            let t = opt("t_s")?;
            let text = |name: &str, d: &str| {
                col_of(name)
                    .map(|c| rec[c.idx].to_string())
                    .filter(|s| !s.is_empty())
                    .unwrap_or_else(|| d.to_string())
            };
            let mut extra = Vec::with_capacity(extra_idx.len());
            for &i in &extra_idx {
                extra.push(parse(i)?);
            }
            rows.push(Row {
                line,
                series: text("series", "all"),
                condition: text("condition", "dry"),
                cx,
                cy: range(
                    "cy",
                    percent_like("cy", opt("cy")?.unwrap_or(0.0))?,
                    -10.0,
                    10.0,
                    "(dimensionless)",
                )?,
                spin: range(
                    "cs_per_m",
                    opt("cs_per_m")?.unwrap_or(0.0),
                    -1e4,
                    1e4,
                    "1/m",
                )?,
                v,
                fn_n: fn_kn * 1e3,
                ab,
                t,
                t_bulk: range(
                    "t_bulk_C",
                    opt("t_bulk_C")?.unwrap_or(defaults.t_bulk_c),
                    -100.0,
                    1000.0,
                    "degC",
                )?,
                f,
                extra,
            });
        }
        if rows.is_empty() {
            return Err(err(src, 2, "-", "no data rows".into()));
        }
        // creepage without a unit that looks like percent: stop
        for name in implicit_creepage {
            let get = |r: &Row| if name == "cx" { r.cx } else { r.cy };
            let worst = rows
                .iter()
                .max_by(|a, b| get(a).abs().total_cmp(&get(b).abs()))
                .map(|r| (r.line, get(r)));
            if let Some((line, x)) = worst {
                if x.abs() > PERCENT_LOOKING {
                    let h = col_of(name)
                        .map(|c| header[c.idx].clone())
                        .unwrap_or_default();
                    return Err(err(src, line, &h, percent_message(name, x)));
                }
            }
        }
        // time series: within a series either all rows have t_s or none; times increase
        let mut last: BTreeMap<&str, (Option<f64>, usize)> = BTreeMap::new();
        for r in &rows {
            if let Some((prev, pline)) = last.get(r.series.as_str()) {
                if prev.is_some() != r.t.is_some() {
                    return Err(err(
                        src,
                        r.line,
                        "t_s",
                        format!(
                            "series '{}' mixes rows with and without t_s (line {pline})",
                            cut(&r.series)
                        ),
                    ));
                }
                if let (Some(a), Some(b)) = (prev, r.t) {
                    if b <= *a {
                        return Err(err(
                            src,
                            r.line,
                            "t_s",
                            format!("time {b} s does not increase (line {pline} has {a} s)"),
                        ));
                    }
                }
            }
            last.insert(r.series.as_str(), (r.t, r.line));
        }
        Ok(Dataset {
            source: src.to_string(),
            extra_names,
            rows,
            columns,
            delimiter: delim as char,
        })
    }

    /// Series names in first-appearance order.
    pub fn series(&self) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        let mut seen = std::collections::HashSet::new();
        for r in &self.rows {
            if seen.insert(r.series.as_str()) {
                out.push(r.series.clone());
            }
        }
        out
    }

    /// The column mapping in words, one line per column.
    pub fn mapping_text(&self) -> String {
        let d = match self.delimiter {
            '\t' => "tab".to_string(),
            ';' => "';' (decimal comma accepted)".to_string(),
            c => format!("'{c}'"),
        };
        let mut s = format!(
            "data file {}: {} rows, delimiter {d}; columns:\n",
            self.source,
            self.rows.len()
        );
        for c in &self.columns {
            let h = if c.header.is_empty() {
                "(none)".to_string()
            } else {
                format!("'{}'", cut(&c.header))
            };
            match c.quantity {
                Some(q) => s += &format!("  {h:<22} -> {q:<10} {}\n", c.how),
                None => s += &format!("  {h:<22} -> extra      {}\n", c.how),
            }
        }
        s
    }
}

/// Unit of a canonical column name.
pub fn canonical_unit(name: &str) -> &'static str {
    match name {
        "v_mps" => "m/s",
        "fn_kN" => "kN",
        "a_mm" | "b_mm" => "mm",
        "cs_per_m" => "1/m",
        "t_s" => "s",
        "t_bulk_C" => "degC",
        _ => "dimensionless",
    }
}

fn show_unit(u: &str) -> String {
    match u {
        "kn" => "kN".into(),
        "n" => "N".into(),
        "c" | "degc" | "°c" => "degC".into(),
        "k" => "K".into(),
        "%" | "pct" | "percent" => "percent".into(),
        "-" | "1" => "dimensionless".into(),
        _ => u.into(),
    }
}

fn percent_message(name: &str, x: f64) -> String {
    format!(
        "{x} looks like percent ({:.0} % creepage if dimensionless); the header gives no unit. If the values are percent, name the column '{name} [%]' or '{name}_pct', or pass --cx-unit percent; if they really are dimensionless (e.g. braking toward a locked wheel, c_x down to -1), name the column '{name} [-]' or '{name} [1]', or pass --cx-unit 1",
        100.0 * x.abs()
    )
}

/// Creepage (no unit written) above this magnitude is taken to be percent and refused.
pub const PERCENT_LOOKING: f64 = 0.5;

/// One high-pressure-torsion point (seed Sec. 3.3, 5.1): the 3BL alone.
#[derive(Clone, Debug, PartialEq)]
pub struct HptRow {
    /// Line in the file.
    pub line: usize,
    /// Series name.
    pub series: String,
    /// Condition.
    pub condition: String,
    /// Normal stress, Pa.
    pub p: f64,
    /// Displacement, m.
    pub u: f64,
    /// Measured shear stress, Pa.
    pub tau: f64,
}

/// Opens CSV text (trimmed fields, `#` comments) and checks its header: no empty or duplicate
/// column names, every `required` column present.
fn open_csv<'a>(
    text: &'a str,
    src: &str,
    required: &[&str],
    delim: u8,
) -> Result<(csv::Reader<&'a [u8]>, Vec<String>)> {
    let mut rdr = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .delimiter(delim)
        .flexible(true)
        .from_reader(text.as_bytes());
    let header: Vec<String> = rdr
        .headers()
        .map_err(|e| err(src, 1, "-", format!("bad header: {}", cut(&e.to_string()))))?
        .iter()
        .map(|s| s.to_string())
        .collect();
    for (i, h) in header.iter().enumerate() {
        if h.is_empty() {
            return Err(err(
                src,
                1,
                &format!("#{}", i + 1),
                "empty column name".into(),
            ));
        }
        if header[..i].contains(h) {
            return Err(err(src, 1, h, "duplicate column".into()));
        }
    }
    for req in required {
        if !header.iter().any(|h| h == req) {
            return Err(err(
                src,
                1,
                req,
                format!(
                    "required column missing (have: {})",
                    header.iter().map(|h| cut(h)).collect::<Vec<_>>().join(", ")
                ),
            ));
        }
    }
    Ok((rdr, header))
}

/// Largest values a high-pressure-torsion file may hold, per column (column, value, unit):
/// 100 GPa of normal or shear stress, 10 m of displacement.
const HPT_MAX: [(&str, f64, &str); 3] = [
    ("p_MPa", 1e5, "MPa"),
    ("u_mm", 1e4, "mm"),
    ("tau_MPa", 1e5, "MPa"),
];

/// Reads a high-pressure-torsion file (`p_MPa`, `u_mm`, `tau_MPa`, optional `series`, `condition`).
pub fn read_hpt(text: &str, src: &str) -> Result<Vec<HptRow>> {
    let (mut rdr, header) = open_csv(
        text,
        src,
        &["p_MPa", "u_mm", "tau_MPa"],
        detect_delimiter(text),
    )?;
    let col = |n: &str| header.iter().position(|h| h == n);
    let mut out = Vec::new();
    for (k, rec) in rdr.records().enumerate() {
        let line = k + 2;
        let rec = rec.map_err(|e| err(src, line, "-", format!("{e}")))?;
        let num = |n: &str| -> Result<f64> {
            let i = col(n).unwrap_or(0);
            let s = rec.get(i).unwrap_or("");
            let x: f64 = s
                .parse()
                .map_err(|_| err(src, line, n, format!("'{}' is not a number", cut(s))))?;
            if !x.is_finite() || x < 0.0 {
                return Err(err(src, line, n, format!("{x}: must be finite and >= 0")));
            }
            // a pressure-shear test's range (far beyond any steel's strength, and short of
            // where the squares of a CV(RMSE) would overflow)
            let (max, unit) = HPT_MAX
                .iter()
                .find(|(c, _, _)| *c == n)
                .map_or((f64::INFINITY, ""), |m| (m.1, m.2));
            if x > max {
                return Err(err(
                    src,
                    line,
                    n,
                    format!("{x:e}: outside a pressure-shear test's range [0, {max:e}] {unit}"),
                ));
            }
            Ok(x)
        };
        let text = |n: &str, d: &str| {
            col(n)
                .and_then(|i| rec.get(i))
                .filter(|s| !s.is_empty())
                .unwrap_or(d)
                .to_string()
        };
        out.push(HptRow {
            line,
            series: text("series", "all"),
            condition: text("condition", "dry"),
            p: num("p_MPa")? * 1e6,
            u: num("u_mm")? * 1e-3,
            tau: num("tau_MPa")? * 1e6,
        });
    }
    if out.is_empty() {
        return Err(err(src, 2, "-", "no data rows".into()));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_a_good_file_with_extra_columns() {
        let t =
            "cx,f,series,v_mps,fn_kN,humidity\n0.01,0.3,a,5,110,40\n# note\n0.02,0.32,a,5,110,41\n";
        let d = Dataset::from_csv_str(t, "x.csv", &Defaults::default()).unwrap();
        assert_eq!(d.extra_names, vec!["humidity"]);
        assert_eq!(d.rows.len(), 2);
        assert_eq!(d.rows[1].line, 4);
        assert_eq!(d.rows[1].extra, vec![41.0]);
        assert_eq!(d.rows[0].fn_n, 110e3);
    }

    #[test]
    fn errors_name_file_line_column_and_reason() {
        let cases = [
            ("f,v_mps,fn_kN\n0.3,5,110\n", "column 'cx'"),
            (
                "cx,f,v_mps,fn_kN\n0.01,0.3,-5,110\n",
                "line 2, column 'v_mps'",
            ),
            (
                "cx,f,v_mps,fn_kN\n0.01,0.3,5,110\n0.02,nan,5,110\n",
                "line 3, column 'f'",
            ),
            ("cx,f,v_mps,fn_kN\n0.01,0.3,5,110000\n", "kN"),
            (
                "cx,f,series,t_s,v_mps,fn_kN\n0.01,0.3,a,0.1,5,110\n0.01,0.3,a,0.1,5,110\n",
                "line 3, column 't_s'",
            ),
            (
                "cx,f,humidity,v_mps,fn_kN\n0.01,0.3,wet,5,110\n",
                "column 'humidity'",
            ),
            ("cx,f,a_mm,v_mps,fn_kN\n0.01,0.3,7,5,110\n", "b_mm"),
            ("cx,f,v_mps,fn_kN\n", "no data"),
        ];
        for (text, needle) in cases {
            let e = Dataset::from_csv_str(text, "m.csv", &Defaults::default())
                .unwrap_err()
                .to_string();
            assert!(
                e.starts_with("data file m.csv") && e.contains(needle),
                "{text:?}: {e}"
            );
        }
    }

    #[test]
    fn extra_columns_drop_a_bracketed_unit_unless_the_name_is_taken() {
        let t = "cx,f,v_mps,fn_kN,humidity [%],salt (g/m2)\n0.01,0.3,5,110,40,0.2\n";
        let d = Dataset::from_csv_str(t, "x.csv", &Defaults::default()).unwrap();
        assert_eq!(d.extra_names, vec!["humidity", "salt"]);
        assert_eq!(d.rows[0].extra, vec![40.0, 0.2]);
        assert!(d.mapping_text().contains("extra column 'humidity' in %"));
        // both spellings present: each keeps its whole header
        let t = "cx,f,v_mps,fn_kN,humidity,humidity [%]\n0.01,0.3,5,110,40,41\n";
        let d = Dataset::from_csv_str(t, "x.csv", &Defaults::default()).unwrap();
        assert_eq!(d.extra_names, vec!["humidity", "humidity [%]"]);
    }

    #[test]
    fn reads_hpt_files() {
        let r = read_hpt("p_MPa,u_mm,tau_MPa,series\n500,0.1,200,s1\n", "h.csv").unwrap();
        assert_eq!(r[0].p, 500e6);
        assert!(read_hpt("p_MPa,u_mm\n1,2\n", "h.csv")
            .unwrap_err()
            .to_string()
            .contains("tau_MPa"));
    }
}
