//! High-pressure-torsion files (`p_MPa`, `u_mm`, `tau_MPa`, optional `series`, `condition`): the layer alone, seed Sec. 3.3, 5.1.

use super::text::{cut, detect_delimiter, err, open_csv};
use creep_core::error::Result;

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

/// The columns a high-pressure-torsion file must have (they make a file one).
pub const HPT_COLUMNS: [&str; 3] = ["p_MPa", "u_mm", "tau_MPa"];

/// Largest values a high-pressure-torsion file may hold, per column (column, value, unit):
/// 100 GPa of normal or shear stress, 10 m of displacement.
const HPT_MAX: [(&str, f64, &str); 3] = [
    ("p_MPa", 1e5, "MPa"),
    ("u_mm", 1e4, "mm"),
    ("tau_MPa", 1e5, "MPa"),
];

/// Reads a high-pressure-torsion file (`p_MPa`, `u_mm`, `tau_MPa`, optional `series`, `condition`).
pub fn read_hpt(text: &str, src: &str) -> Result<Vec<HptRow>> {
    let (mut rdr, header) = open_csv(text, src, &HPT_COLUMNS, detect_delimiter(text))?;
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
    fn reads_hpt_files() {
        let r = read_hpt("p_MPa,u_mm,tau_MPa,series\n500,0.1,200,s1\n", "h.csv").unwrap();
        assert_eq!(r[0].p, 500e6);
        assert!(read_hpt("p_MPa,u_mm\n1,2\n", "h.csv")
            .unwrap_err()
            .to_string()
            .contains("tau_MPa"));
    }
}
