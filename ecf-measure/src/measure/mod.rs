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

mod checks;
mod header;
mod hpt_file;
mod kind;
mod quantity;
mod rows;
mod text;

pub use hpt_file::{read_hpt, HptRow, HPT_COLUMNS};
pub use kind::{file_kind, read_data, read_data_text, Data, FileKind};
pub use quantity::{canonical_unit, recognise, Quantity, QuantitySpec, QUANTITIES};
pub use text::{cut, detect_delimiter, utf8_text};

use creep_core::engine::Inputs;
use creep_core::error::{CreepError, Result};
use std::path::Path;

/// CV(RMSE) lives in [`crate::stats`]; re-exported here, where it was first.
pub use crate::stats::cv_rmse_pct;

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
    pub(crate) fn factor(self) -> f64 {
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
    /// The quantity, or `None` for an extra column.
    pub quantity: Option<Quantity>,
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

    /// Parses measurement CSV text; `src` names it in error messages. The stages: the
    /// delimiter ([`detect_delimiter`]), the header mapped to quantities and units
    /// (`header.rs`), the rows read and checked against physical ranges (`rows.rs`), the
    /// checks over all rows (`checks.rs`).
    pub fn from_csv_str(text: &str, src: &str, defaults: &Defaults) -> Result<Self> {
        let delim = detect_delimiter(text);
        let (mut rdr, names) = text::open_csv(text, src, &[], delim)?;
        let map = header::map_header(names, src, defaults)?;
        let rows = rows::read_rows(&mut rdr, text, src, delim, &map, defaults)?;
        checks::check_rows(&rows, &map, src)?;
        Ok(Dataset {
            source: src.to_string(),
            extra_names: map.extra_names,
            rows,
            columns: map.columns,
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

/// The message for creepage without a unit that looks like percent.
pub(crate) fn percent_message(name: &str, x: f64) -> String {
    format!(
        "{x} looks like percent ({:.0} % creepage if dimensionless); the header gives no unit. If the values are percent, name the column '{name} [%]' or '{name}_pct', or pass --cx-unit percent; if they really are dimensionless (e.g. braking toward a locked wheel, c_x down to -1), name the column '{name} [-]' or '{name} [1]', or pass --cx-unit 1",
        100.0 * x.abs()
    )
}

/// Creepage (no unit written) above this magnitude is taken to be percent and refused.
pub const PERCENT_LOOKING: f64 = 0.5;

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
}
