//! The measurement loop's results as the command line's JSON documents and the set-up both fronts share (defaults of a data file, bounds and free parameters of a fit), for `ecf` and the Python package alike.

use crate::evaluate::{compare as cmp, predict_warned, Comparison, ModelWarning, Prediction};
use crate::fit::{FitResult, FreeParam, ParamStatus};
use crate::measure::{CreepageUnit, Dataset, Defaults, HptRow};
use creep_core::error::{check_range, CreepError, Result};
use creep_core::params::{self, P};
use creep_core::Config;
use serde_json::{json, Value};

/// Values for quantities a data file omits: speed `v_mps` (m/s) and normal force `fn_kn`
/// (kN) of every row, and the unit of creepage columns whose header gives none (`1` or
/// `percent`), each checked (the messages name the command line's flags).
pub fn data_defaults(
    v_mps: Option<f64>,
    fn_kn: Option<f64>,
    cx_unit: Option<&str>,
) -> Result<Defaults> {
    let mut defaults = Defaults::default();
    if let Some(v) = v_mps {
        defaults.v_mps = Some(check_range("--v-mps", v, 0.0, 200.0, "m/s")?);
    }
    if let Some(f) = fn_kn {
        defaults.fn_kn = Some(check_range("--fn-kN", f, 1e-6, 5000.0, "kN")?);
    }
    if let Some(u) = cx_unit {
        defaults.cx_unit = Some(CreepageUnit::parse(u)?);
    }
    Ok(defaults)
}

/// A configuration compared with creep measurements: the statistics, the prediction of each
/// row and the model's warnings.
pub struct CompareReport {
    /// CV(RMSE) overall, per group and regime.
    pub comparison: Comparison,
    /// The model's prediction of each row.
    pub pred: Vec<Prediction>,
    /// The model's warnings for the rows.
    pub warnings: Vec<ModelWarning>,
}

/// Compares `cfg` with `data`; an error where the CV(RMSE) is not finite.
pub fn compare_rows(cfg: &Config, data: &Dataset, threads: usize) -> Result<CompareReport> {
    let (pred, warnings) = predict_warned(cfg, data, threads)?;
    let c = cmp(data, &pred);
    if !c.cv_rmse_pct.is_finite() {
        let mean = crate::stats::mean(&data.rows.iter().map(|r| r.f).collect::<Vec<_>>());
        return Err(CreepError::Data {
            source_name: data.source.clone(),
            message: format!(
                "CV(RMSE) is not finite ({}): the mean measured traction coefficient is {mean} and CV(RMSE) divides by it (Eq. 2.9)",
                c.cv_rmse_pct
            ),
        });
    }
    Ok(CompareReport {
        comparison: c,
        pred,
        warnings,
    })
}

impl CompareReport {
    /// The JSON document of `ecf compare --json`: the comparison's fields, the data's name,
    /// the configuration, the warnings and every row with its prediction.
    pub fn to_json(&self, cfg: &Config, data: &Dataset) -> Result<Value> {
        let mut v =
            serde_json::to_value(&self.comparison).map_err(|e| CreepError::State(e.to_string()))?;
        v["data"] = json!(data.source);
        v["config"] = cfg.to_json();
        v["warnings"] = json!(self.warnings);
        v["rows"] = json!(data
            .rows
            .iter()
            .zip(&self.pred)
            .map(|(r, p)| json!({"line": r.line, "series": r.series, "cx": r.cx, "f": r.f, "f_model": p.f, "residual": p.f - r.f, "T_max_C": p.t_max, "slip_velocity_mps": p.slip_velocity}))
            .collect::<Vec<_>>());
        Ok(v)
    }
}

/// High-pressure-torsion curves compared with the layer model alone (seed Sec. 5.1).
pub struct HptComparison {
    /// The model's shear stress of each row, Pa.
    pub model: Vec<f64>,
    /// Series names in first-appearance order, each with its CV(RMSE), %.
    pub per_series: Vec<(String, f64)>,
    /// CV(RMSE) over all rows, %.
    pub overall: f64,
}

/// Compares `cfg` with high-pressure-torsion rows.
pub fn compare_hpt(cfg: &Config, rows: &[HptRow]) -> HptComparison {
    let model = crate::hpt::predict(cfg, rows);
    let mut series: Vec<String> = Vec::new();
    for r in rows {
        if !series.contains(&r.series) {
            series.push(r.series.clone());
        }
    }
    let per_series = series
        .iter()
        .map(|s| {
            let idx: Vec<usize> = (0..rows.len()).filter(|&i| rows[i].series == *s).collect();
            (
                s.clone(),
                crate::stats::cv_rmse_pct(
                    &idx.iter().map(|&i| rows[i].tau).collect::<Vec<_>>(),
                    &idx.iter().map(|&i| model[i]).collect::<Vec<_>>(),
                ),
            )
        })
        .collect();
    let overall = crate::hpt::cv_rmse(cfg, rows);
    HptComparison {
        model,
        per_series,
        overall,
    }
}

impl HptComparison {
    /// The JSON document of `ecf compare --json` for high-pressure-torsion data.
    pub fn to_json(&self, n: usize) -> Value {
        json!({"cv_rmse_pct": self.overall, "n": n, "groups": self.per_series.iter().map(|(s, c)| json!({"by": "series", "value": s, "cv_rmse_pct": c})).collect::<Vec<_>>()})
    }
}

/// The configuration with bounds `NAME=MIN:MAX` applied (`inf`/`-inf` for no bound).
pub fn with_bounds(cfg: &Config, bounds: &[String]) -> Result<Config> {
    let mut c = cfg.clone();
    for b in bounds {
        let bad = || CreepError::Config {
            source_name: "--bound".into(),
            message: format!("'{b}': expected NAME=MIN:MAX, e.g. tau_c2_0_GPa=0.2:2"),
        };
        let (n, r) = b.split_once('=').ok_or_else(bad)?;
        let (lo, hi) = r.split_once(':').ok_or_else(bad)?;
        let num = |t: &str| -> Result<f64> {
            match t.trim() {
                "inf" => Ok(f64::INFINITY),
                "-inf" => Ok(f64::NEG_INFINITY),
                t => t.parse().map_err(|_| bad()),
            }
        };
        let id = FreeParam::resolve(&c, n.trim())?;
        id.set_bounds(&mut c, num(lo)?, num(hi)?)?;
    }
    Ok(c)
}

/// The set-up a fit starts from: the configuration with `bounds` applied, and the free
/// parameters named in `free` (comma separated; None: `default`).
pub fn fit_setup(
    cfg: &Config,
    free: Option<&str>,
    bounds: &[String],
    default: Vec<P>,
) -> Result<(Config, Vec<FreeParam>)> {
    let cfg = with_bounds(cfg, bounds)?;
    let free = FreeParam::list(&cfg, free, default)?;
    Ok((cfg, free))
}

/// A JSON number, or "inf" for an infinity (a standard error of a parameter the data do not
/// identify), or null for NaN (an uncertainty not computed).
pub fn json_num(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else if x.is_infinite() {
        json!("inf")
    } else {
        Value::Null
    }
}

/// The unit of a fitted parameter's display value ("-" for formula/custom parameters).
pub fn param_unit(name: &str) -> &'static str {
    params::by_name(name)
        .map(|p| params::spec(p).unit)
        .unwrap_or("-")
}

/// The `"fit"` record of a fitted configuration: what `ecf report` shows as the table of
/// fitted parameters (values in display units, standard errors, flags).
pub fn fit_record(r: &FitResult, model_warnings: &[ModelWarning]) -> Value {
    let params: Vec<Value> = r
        .params
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let st = r.status.get(k);
            json!({
                "name": p.name,
                "unit": param_unit(&p.name),
                "start": json_num(p.start),
                "value": json_num(p.value),
                "stderr": match st {
                    Some(ParamStatus::Determined) => json_num(p.stderr),
                    Some(ParamStatus::NotIdentifiable) => json_num(f64::INFINITY),
                    _ => Value::Null,
                },
                "flag": st.map(|s| s.note()).unwrap_or(""),
            })
        })
        .collect();
    json!({
        "cv_rmse_pct_before": json_num(r.cv_rmse_pct_before),
        "cv_rmse_pct_after": json_num(r.cv_rmse_pct_after),
        "params": params,
        "warnings": r.warnings,
        "termination": r.termination,
        "starts": r.starts,
        "model_warnings": model_warnings,
    })
}

/// The fitted configuration's JSON document, with its `"fit"` record: what `ecf fit --out`
/// writes.
pub fn fitted_document(r: &FitResult, model_warnings: &[ModelWarning]) -> Value {
    let mut doc = r.config.to_json();
    if let Some(o) = doc.as_object_mut() {
        o.insert("fit".into(), fit_record(r, model_warnings));
    }
    doc
}

/// The JSON document of `ecf fit --json`; `out` names where the fitted configuration went
/// (null: nowhere).
pub fn fit_json(r: &FitResult, model_warnings: &[ModelWarning], out: Option<&str>) -> Value {
    let map = |k: usize| -> serde_json::Map<String, Value> {
        r.params
            .iter()
            .map(|p| (p.name.clone(), json_num([p.start, p.value, p.stderr][k])))
            .collect()
    };
    json!({
        "cv_rmse_pct_before": r.cv_rmse_pct_before,
        "cv_rmse_pct_after": r.cv_rmse_pct_after,
        "params": map(1),
        "stderr": map(2),
        "start": map(0),
        "status": r.params.iter().zip(&r.status).map(|(p, s)| (p.name.clone(), json!(s))).collect::<serde_json::Map<_, _>>(),
        "free": r.params.iter().map(|p| p.name.clone()).collect::<Vec<_>>(),
        "correlation": r.correlation.iter().map(|row| row.iter().map(|x| json_num(*x)).collect::<Vec<_>>()).collect::<Vec<_>>(),
        "warnings": r.warnings,
        "evaluations": r.evaluations,
        "termination": r.termination,
        "starts": r.starts,
        "model_warnings": model_warnings,
        "out": out,
    })
}
