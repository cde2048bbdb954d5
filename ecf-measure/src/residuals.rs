//! Residual correlations: the residuals of a prediction (model - measured) against every variable of the rows and of the model, strongest first.

use crate::evaluate::Prediction;
use crate::measure::Dataset;
use crate::stats::pearson;

/// Correlation of the residuals with one variable.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Correlation {
    /// Variable name.
    pub variable: String,
    /// Pearson correlation coefficient of residual (model - measured) and variable.
    pub r: f64,
    /// Number of rows.
    pub n: usize,
}

/// Residual correlations with every variable, strongest first.
pub fn correlations(data: &Dataset, pred: &[Prediction]) -> Vec<Correlation> {
    let res: Vec<f64> = data.rows.iter().zip(pred).map(|(r, p)| p.f - r.f).collect();
    let mut vars: Vec<(String, Vec<f64>)> = vec![
        ("cx".into(), data.rows.iter().map(|r| r.cx.abs()).collect()),
        (
            "slip_velocity_mps".into(),
            pred.iter().map(|p| p.slip_velocity).collect(),
        ),
        (
            "frictional_power_W".into(),
            pred.iter().map(|p| p.p_fric).collect(),
        ),
        (
            "model_T_max_C".into(),
            pred.iter().map(|p| p.t_max).collect(),
        ),
        ("v_mps".into(), data.rows.iter().map(|r| r.v).collect()),
        (
            "fn_kN".into(),
            data.rows.iter().map(|r| r.fn_n / 1e3).collect(),
        ),
        ("p0_MPa".into(), pred.iter().map(|p| p.p0 / 1e6).collect()),
    ];
    // the bulk temperature, where it varies over the file
    if data.rows.iter().any(|r| r.t_bulk != data.rows[0].t_bulk) {
        vars.push((
            "t_bulk_C".into(),
            data.rows.iter().map(|r| r.t_bulk).collect(),
        ));
    }
    if data.rows.iter().any(|r| r.t.is_some()) {
        vars.push((
            "dcx_dt_per_s".into(),
            pred.iter().map(|p| p.dcx_dt.abs()).collect(),
        ));
    }
    for (k, n) in data.extra_names.iter().enumerate() {
        vars.push((n.clone(), data.rows.iter().map(|r| r.extra[k]).collect()));
    }
    let mut out: Vec<Correlation> = vars
        .into_iter()
        .map(|(v, x)| Correlation {
            variable: v,
            r: pearson(&x, &res),
            n: res.len(),
        })
        .collect();
    out.sort_by(|a, b| b.r.abs().total_cmp(&a.r.abs()));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::Row;

    /// Three rows of a time series with varying inputs, and predictions that vary with them.
    fn series() -> (Dataset, Vec<Prediction>) {
        let rows: Vec<Row> = (0..3)
            .map(|i| Row {
                line: i + 2,
                series: "s".into(),
                condition: String::new(),
                cx: 0.01 * (i + 1) as f64,
                cy: 0.0,
                spin: 0.0,
                v: 5.0 + i as f64,
                fn_n: 1e5 + 1e4 * i as f64,
                ab: None,
                t: Some(1e-3 * i as f64),
                t_bulk: 20.0,
                f: 0.2 + 0.01 * (i * i) as f64,
                extra: vec![],
            })
            .collect();
        let pred = (0..3)
            .map(|i| {
                let x = i as f64;
                Prediction {
                    f: 0.2 + 0.02 * x,
                    t_max: 30.0 + x,
                    p_fric: 100.0 + x,
                    p0: 1e9 + x,
                    slip_velocity: 0.05 + x,
                    dcx_dt: 10.0 * x,
                }
            })
            .collect();
        let data = Dataset {
            source: "test".into(),
            extra_names: vec![],
            rows,
            columns: vec![],
            delimiter: ',',
        };
        (data, pred)
    }

    #[test]
    fn every_catalogue_signature_is_a_correlated_variable() {
        let (data, pred) = series();
        let names: Vec<String> = correlations(&data, &pred)
            .into_iter()
            .map(|c| c.variable)
            .collect();
        for i in creep_core::effects::CATALOGUE {
            for v in i.signature {
                assert!(
                    names.iter().any(|n| n == v),
                    "effect {}: signature variable {v} is not one of {names:?}",
                    i.name
                );
            }
        }
    }
}
