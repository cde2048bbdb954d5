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
