//! `ecf report`: one self-contained HTML page of the comparison, the fitted parameters, the residuals and the diagnosis, for one configuration or two side by side.

use crate::measure_cmd::{ge_1pct_text, write_out, write_plots};
use creep_core::{Config, CreepError};
use ecf_measure::evaluate::{compare as cmp, predict_warned};
use ecf_measure::measure::Dataset;
use std::path::Path;

/// Text escaped for HTML.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// One configuration's part of the report, as HTML fragments.
struct Column {
    /// Heading, CV(RMSE) and the measured-against-model curves.
    curves: String,
    /// The CV(RMSE) table by group and the residual plots.
    residuals: String,
    /// CV(RMSE) overall, %.
    cv: f64,
}

/// Comparison table and plots (embedded) of one configuration.
fn report_column(
    cfg: &Config,
    name: &str,
    data: &Dataset,
    threads: usize,
    tmp: &Path,
) -> Result<Column, CreepError> {
    use base64::Engine;
    let (pred, warnings) = predict_warned(cfg, data, threads)?;
    let c = cmp(data, &pred);
    let figures = write_plots(cfg, data, &pred, tmp)?;
    let mut h = format!(
        "<h2>{}</h2><p>model <b>{}</b>, effects {}</p>",
        esc(name),
        cfg.model.name(),
        esc(&format!("{:?}", cfg.effects.to_vec()))
    );
    h += &format!(
        "<p class=big>CV(RMSE) = <b>{:.2} %</b> overall, {} (seed Eq. 2.9)</p>",
        c.cv_rmse_pct,
        ge_1pct_text(c.cv_rmse_pct_cx_ge_1pct, "c<sub>x</sub> &ge; 1 %")
    );
    for wn in &warnings {
        let per: Vec<String> = wn
            .per_series
            .iter()
            .map(|c| format!("series {}: {} row(s)", c.series, c.rows))
            .collect();
        h += &format!(
            "<p class=warn>warning ({} row(s); {}): {}</p>",
            wn.rows,
            esc(&per.join("; ")),
            esc(&wn.message)
        );
    }
    let mut table = String::from("<table><tr><th>group</th><th>value</th><th>n</th><th>CV(RMSE) %</th><th>mean residual</th></tr>");
    for g in &c.groups {
        table += &format!(
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{:.2}</td><td>{:+.4}</td></tr>",
            esc(&g.by),
            esc(&g.value),
            g.n,
            g.cv_rmse_pct,
            g.mean_residual
        );
    }
    table += "</table>";
    let n_series = data.series().len();
    let mut res = format!("<h3>{}: residuals</h3>{table}", esc(name));
    for (k, (p, caption)) in figures.iter().enumerate() {
        let bytes = std::fs::read(p).map_err(|e| CreepError::Config {
            source_name: p.display().to_string(),
            message: e.to_string(),
        })?;
        let b64 = base64::engine::general_purpose::STANDARD.encode(bytes);
        let fig = format!(
            "<figure><img alt=\"{c}\" src=\"data:image/png;base64,{b64}\"><figcaption>{c}</figcaption></figure>",
            c = esc(caption)
        );
        if k < n_series {
            h += &fig;
        } else {
            res += &fig;
        }
    }
    Ok(Column {
        curves: h,
        residuals: res,
        cv: c.cv_rmse_pct,
    })
}

/// The table of fitted parameters from the `"fit"` record `ecf fit` writes into a fitted
/// configuration file (empty when the file has none, e.g. a configuration written by hand).
fn fitted_table(path: &str) -> String {
    let rec = std::fs::read_to_string(path)
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
        .and_then(|v| v.get("fit").cloned());
    let Some(rec) = rec else {
        return String::new();
    };
    let num = |v: &serde_json::Value| -> String {
        match v {
            serde_json::Value::Number(n) => n.as_f64().map_or("-".into(), |x| format!("{x:.6}")),
            serde_json::Value::String(s) => s.clone(),
            _ => "-".into(),
        }
    };
    let mut h = String::from("<h2>Fitted parameters</h2><table><tr><th>parameter</th><th>start</th><th>fitted</th><th>standard error</th><th>unit</th><th>flag</th></tr>");
    for p in rec
        .get("params")
        .and_then(|p| p.as_array())
        .into_iter()
        .flatten()
    {
        let se = match p.get("stderr") {
            Some(serde_json::Value::Number(n)) => {
                n.as_f64().map_or("-".into(), |x| format!("± {x:.2e}"))
            }
            Some(serde_json::Value::String(s)) => format!("± {s}"),
            _ => "-".into(),
        };
        let flag = p.get("flag").and_then(|f| f.as_str()).unwrap_or("");
        h += &format!(
            "<tr><td>{}</td><td>{}</td><td><b>{}</b></td><td>{}</td><td>{}</td><td>{}</td></tr>",
            esc(p.get("name").and_then(|n| n.as_str()).unwrap_or("?")),
            num(p.get("start").unwrap_or(&serde_json::Value::Null)),
            num(p.get("value").unwrap_or(&serde_json::Value::Null)),
            esc(&se),
            esc(p.get("unit").and_then(|u| u.as_str()).unwrap_or("-")),
            esc(flag)
        );
    }
    h += "</table>";
    for w in rec
        .get("warnings")
        .and_then(|w| w.as_array())
        .into_iter()
        .flatten()
    {
        if let Some(w) = w.as_str() {
            h += &format!("<p>warning: {}</p>", esc(w));
        }
    }
    h
}

/// Writes the self-contained HTML report (`write_out`).
pub fn report(
    cfg: &Config,
    name: &str,
    second: Option<&(String, Config)>,
    data: &Dataset,
    threads: usize,
    out: &Path,
) -> Result<(), CreepError> {
    let guard = crate::cleanup::Pending::new(
        std::env::temp_dir().join(format!("ecf-report-{}", std::process::id())),
    );
    let tmp = guard.path().to_path_buf();
    let _ = std::fs::remove_dir_all(&tmp);
    let col1 = report_column(
        cfg,
        &format!("before: {name}"),
        data,
        threads,
        &tmp.join("a"),
    )?;
    let col2 = match second {
        Some((n, c)) => Some(report_column(
            c,
            &format!("after: {n}"),
            data,
            threads,
            &tmp.join("b"),
        )?),
        None => None,
    };
    drop(guard);
    let d = ecf_measure::diagnose::diagnose(cfg, data, threads, &|_| {})?;
    let mut diag = format!(
        "<h2>Diagnosis of the first configuration</h2><p><b>{}</b></p>",
        esc(&d.verdict)
    );
    diag += &format!(
        "<p>held-out folds by {} ({} folds); baseline held-out CV(RMSE) {:.2} %</p>",
        esc(&d.folds_by),
        d.folds,
        d.baseline_heldout_cv_rmse_pct
    );
    if let Some(g) = &d.model_grid {
        diag += &format!("<p>grid: {}</p>", esc(g));
    }
    diag += "<table><tr><th>candidate effect</th><th>held-out CV(RMSE) %</th><th>fitted CV(RMSE) %</th><th>why</th></tr>";
    for c in &d.candidates {
        diag += &format!(
            "<tr><td>{}</td><td>{:.2}</td><td>{:.2}</td><td>{}</td></tr>",
            esc(&c.effect),
            c.heldout_cv_rmse_pct,
            c.fitted_cv_rmse_pct,
            esc(&c.explanation)
        );
    }
    diag += "</table><table><tr><th>variable</th><th>residual correlation r</th></tr>";
    for c in &d.correlations {
        diag += &format!("<tr><td>{}</td><td>{:+.2}</td></tr>", esc(&c.variable), c.r);
    }
    diag += "</table>";
    let cv1 = col1.cv;
    let summary = match &col2 {
        Some(c2) => format!(
            "<p class=big>CV(RMSE): {cv1:.2} % &rarr; {:.2} %</p>",
            c2.cv
        ),
        None => format!("<p class=big>CV(RMSE): {cv1:.2} %</p>"),
    };
    // measured against model first, then the fitted parameters, then the residuals, then
    // the diagnosis
    let side = |a: &str, b: Option<&str>| match b {
        Some(b) => format!("<div class=cols><div>{a}</div><div>{b}</div></div>"),
        None => format!("<div>{a}</div>"),
    };
    let fitted = second.map(|(p, _)| fitted_table(p)).unwrap_or_default();
    let cols = side(&col1.curves, col2.as_ref().map(|c| c.curves.as_str()))
        + &fitted
        + "<h2>Residuals</h2>"
        + &side(&col1.residuals, col2.as_ref().map(|c| c.residuals.as_str()))
        + &diag;
    let html = format!(
        "<!DOCTYPE html><html><head><meta charset=utf-8><title>ECF report: {src}</title><style>body{{font-family:sans-serif;margin:2em;max-width:1900px}} table{{border-collapse:collapse;margin:1em 0}} td,th{{border:1px solid #bbb;padding:3px 8px;text-align:left}} .cols{{display:flex;gap:2em}} .cols>div{{flex:1;min-width:0}} img{{max-width:100%}} .big{{font-size:1.3em}}</style></head><body><h1>Measurements {src} ({n} rows) against the model</h1>{summary}{cols}<p>Generated by ecf {ver}.</p></body></html>\n",
        src = esc(&data.source),
        n = data.rows.len(),
        ver = env!("CARGO_PKG_VERSION"),
    );
    write_out(out, "html.tmp", html.as_bytes())
}
