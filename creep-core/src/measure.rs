//! Measurement files (steady characteristics, time series, high-pressure-torsion) and the seed's error metric CV(RMSE) (Eq. 2.8, 2.9).
//!
//! A measurement file is CSV with a header row; one row per measured point. Required
//! columns `cx` (dimensionless) and `f` (measured traction coefficient); optional `series`,
//! `condition`, `v_mps`, `fn_kN`, `a_mm`, `b_mm`, `cy`, `cs_per_m`, `t_s`, `t_bulk_C`; any
//! other column must be numeric and is kept as an extra variable. Rows of one series with
//! `t_s` form a time series. A file is read completely or not at all: the first problem is
//! reported with file, line, column and reason.

use crate::engine::Inputs;
use crate::error::{CreepError, Result};
use std::collections::BTreeMap;
use std::path::Path;

/// Columns with a fixed meaning.
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

/// Defaults for columns a file omits.
#[derive(Clone, Copy, Debug)]
pub struct Defaults {
    /// Vehicle speed, m/s.
    pub v_mps: f64,
    /// Normal force, kN.
    pub fn_kn: f64,
    /// Bulk temperature, degC.
    pub t_bulk_c: f64,
}

impl Default for Defaults {
    fn default() -> Self {
        Defaults {
            v_mps: 20.0,
            fn_kn: 110.0,
            t_bulk_c: 20.0,
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

/// A measurement file, read completely.
#[derive(Clone, Debug, PartialEq)]
pub struct Dataset {
    /// File name as given.
    pub source: String,
    /// Names of the extra numeric columns.
    pub extra_names: Vec<String>,
    /// Rows in file order.
    pub rows: Vec<Row>,
}

fn err(src: &str, line: usize, column: &str, reason: String) -> CreepError {
    CreepError::Config {
        source_name: src.to_string(),
        message: format!("line {line}, column '{column}': {reason}"),
    }
}

impl Dataset {
    /// Reads a measurement file.
    pub fn from_file(path: &Path, defaults: &Defaults) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| CreepError::Config {
            source_name: path.display().to_string(),
            message: format!("cannot read: {e}"),
        })?;
        Self::from_csv_str(&text, &path.display().to_string(), defaults)
    }

    /// Parses measurement CSV text; `src` names it in error messages.
    pub fn from_csv_str(text: &str, src: &str, defaults: &Defaults) -> Result<Self> {
        let (mut rdr, header) = open_csv(text, src, &["cx", "f"])?;
        let col = |name: &str| header.iter().position(|h| h == name);
        let extra_idx: Vec<usize> = (0..header.len())
            .filter(|i| !KNOWN.contains(&header[*i].as_str()))
            .collect();
        let extra_names: Vec<String> = extra_idx.iter().map(|&i| header[i].clone()).collect();
        let (ia, ib) = (col("a_mm"), col("b_mm"));
        if ia.is_some() != ib.is_some() {
            return Err(err(
                src,
                1,
                if ia.is_some() { "b_mm" } else { "a_mm" },
                "a_mm and b_mm come together".into(),
            ));
        }
        let mut rows = Vec::new();
        for (k, rec) in rdr.records().enumerate() {
            let line = k + 2;
            let rec = rec.map_err(|e| {
                err(
                    src,
                    e.position().map(|p| p.line() as usize).unwrap_or(line),
                    "-",
                    format!("{e}"),
                )
            })?;
            if rec.len() != header.len() {
                return Err(err(
                    src,
                    line,
                    "-",
                    format!("{} fields, header has {}", rec.len(), header.len()),
                ));
            }
            let num = |name: &str, i: usize| -> Result<f64> {
                let s = &rec[i];
                let x: f64 = s
                    .parse()
                    .map_err(|_| err(src, line, name, format!("'{s}' is not a number")))?;
                if !x.is_finite() {
                    return Err(err(src, line, name, format!("'{s}' is not finite")));
                }
                Ok(x)
            };
            let opt = |name: &str| -> Result<Option<f64>> {
                match col(name) {
                    Some(i) if !rec[i].is_empty() => num(name, i).map(Some),
                    _ => Ok(None),
                }
            };
            let range = |name: &str, x: f64, lo: f64, hi: f64, what: &str| -> Result<f64> {
                if x < lo || x > hi {
                    Err(err(
                        src,
                        line,
                        name,
                        format!("{x} is outside [{lo}, {hi}] {what}"),
                    ))
                } else {
                    Ok(x)
                }
            };
            let cx = range(
                "cx",
                opt("cx")?.ok_or_else(|| err(src, line, "cx", "empty".into()))?,
                -10.0,
                10.0,
                "(dimensionless creepage: 0.01 = 1 %)",
            )?;
            let f = range(
                "f",
                opt("f")?.ok_or_else(|| err(src, line, "f", "empty".into()))?,
                -2.0,
                2.0,
                "(traction coefficient F_x/F_N)",
            )?;
            let v = range(
                "v_mps",
                opt("v_mps")?.unwrap_or(defaults.v_mps),
                0.0,
                200.0,
                "m/s",
            )?;
            let fn_kn = opt("fn_kN")?.unwrap_or(defaults.fn_kn);
            if fn_kn > 5000.0 {
                return Err(err(
                    src,
                    line,
                    "fn_kN",
                    format!(
                        "{fn_kn} kN per wheel cannot be right: is the column in N instead of kN?"
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
                col(name)
                    .map(|i| rec[i].to_string())
                    .filter(|s| !s.is_empty())
                    .unwrap_or_else(|| d.to_string())
            };
            let mut extra = Vec::with_capacity(extra_idx.len());
            for &i in &extra_idx {
                extra.push(num(&header[i], i)?);
            }
            rows.push(Row {
                line,
                series: text("series", "all"),
                condition: text("condition", "dry"),
                cx,
                cy: range(
                    "cy",
                    opt("cy")?.unwrap_or(0.0),
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
                            r.series
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
        })
    }

    /// Series names in first-appearance order.
    pub fn series(&self) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for r in &self.rows {
            if !out.contains(&r.series) {
                out.push(r.series.clone());
            }
        }
        out
    }
}

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
) -> Result<(csv::Reader<&'a [u8]>, Vec<String>)> {
    let mut rdr = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let header: Vec<String> = rdr
        .headers()
        .map_err(|e| err(src, 1, "-", format!("bad header: {e}")))?
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
                format!("required column missing (have: {})", header.join(", ")),
            ));
        }
    }
    Ok((rdr, header))
}

/// Reads a high-pressure-torsion file (`p_MPa`, `u_mm`, `tau_MPa`, optional `series`, `condition`).
pub fn read_hpt(text: &str, src: &str) -> Result<Vec<HptRow>> {
    let (mut rdr, header) = open_csv(text, src, &["p_MPa", "u_mm", "tau_MPa"])?;
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
                .map_err(|_| err(src, line, n, format!("'{s}' is not a number")))?;
            if !x.is_finite() || x < 0.0 {
                return Err(err(src, line, n, format!("{x}: must be finite and >= 0")));
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

/// CV(RMSE) in percent (Eq. 2.9): 100 sqrt(mean((k - k_hat)^2)) / mean(k).
pub fn cv_rmse_pct(measured: &[f64], model: &[f64]) -> f64 {
    let n = measured.len().min(model.len());
    if n == 0 {
        return f64::NAN;
    }
    let mse = measured
        .iter()
        .zip(model)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        / n as f64;
    let mean = measured.iter().take(n).sum::<f64>() / n as f64;
    100.0 * mse.sqrt() / mean.abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_a_good_file_with_extra_columns() {
        let t = "cx,f,series,v_mps,fn_kN,humidity\n0.01,0.3,a,5,110,40\n0.02,0.32,a,5,110,41\n";
        let d = Dataset::from_csv_str(t, "x.csv", &Defaults::default()).unwrap();
        assert_eq!(d.extra_names, vec!["humidity"]);
        assert_eq!(d.rows.len(), 2);
        assert_eq!(d.rows[1].line, 3);
        assert_eq!(d.rows[1].extra, vec![41.0]);
        assert_eq!(d.rows[0].fn_n, 110e3);
    }

    #[test]
    fn errors_name_file_line_column_and_reason() {
        let cases = [
            ("f,v_mps\n0.3,5\n", "column 'cx'"),
            ("cx,f,v_mps\n0.01,0.3,-5\n", "line 2, column 'v_mps'"),
            ("cx,f\n0.01,0.3\n0.02,nan\n", "line 3, column 'f'"),
            ("cx,f,fn_kN\n0.01,0.3,110000\n", "kN"),
            (
                "cx,f,series,t_s\n0.01,0.3,a,0.1\n0.01,0.3,a,0.1\n",
                "line 3, column 't_s'",
            ),
            ("cx,f,humidity\n0.01,0.3,wet\n", "column 'humidity'"),
            ("cx,f,a_mm\n0.01,0.3,7\n", "b_mm"),
            ("cx,f\n", "no data"),
        ];
        for (text, needle) in cases {
            let e = Dataset::from_csv_str(text, "m.csv", &Defaults::default())
                .unwrap_err()
                .to_string();
            assert!(e.contains("m.csv") && e.contains(needle), "{text:?}: {e}");
        }
    }

    #[test]
    fn cv_rmse_is_eq_2_9() {
        assert!((cv_rmse_pct(&[1.0, 3.0], &[1.0, 3.0])).abs() < 1e-12);
        // rmse = 1, mean = 2 -> 50 %
        assert!((cv_rmse_pct(&[1.0, 3.0], &[2.0, 2.0]) - 50.0).abs() < 1e-12);
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
