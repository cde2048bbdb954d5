//! `ecf compare`, `ecf fit` and `ecf diagnose`: the measurement loop's commands, for creep measurements and high-pressure-torsion curves, and the helpers `ecf report` shares (plots, warnings, writing `--out`).

use crate::plots::{xy_plot, Set, Style};
use creep_core::params::{self, P};
use creep_core::{Config, CreepError, Inputs, Model};
use ecf_measure::evaluate::{predict_warned, regimes, warnings_text, ModelWarning, Prediction};
use ecf_measure::fit::{default_free, fit_params as run_fit, FreeParam};
use ecf_measure::measure::{Data, Dataset};
use ecf_measure::report::{self as rep, compare_rows};
use std::io::Write;
use std::path::Path;

fn io(e: std::io::Error) -> CreepError {
    CreepError::Config {
        source_name: "output".into(),
        message: e.to_string(),
    }
}

/// Compares and reports.
pub fn compare(
    cfg: &Config,
    data: &Dataset,
    threads: usize,
    json: bool,
    plots: Option<&Path>,
    w: &mut Vec<u8>,
) -> Result<(), CreepError> {
    let report = compare_rows(cfg, data, threads)?;
    let (c, warnings) = (&report.comparison, &report.warnings);
    if let Some(dir) = plots {
        write_plots(cfg, data, &report.pred, dir)?;
    }
    if json {
        write_json(w, &report.to_json(cfg, data)?)?;
    } else {
        writeln!(
            w,
            "data {} ({} rows), model {} ({})",
            data.source,
            c.n,
            cfg.model.name(),
            cfg.preset
        )
        .map_err(io)?;
        writeln!(
            w,
            "CV(RMSE) = {:.2} % overall, {}",
            c.cv_rmse_pct,
            ge_1pct_text(c.cv_rmse_pct_cx_ge_1pct, "c_x >= 1 %")
        )
        .map_err(io)?;
        writeln!(
            w,
            "{:<10} {:<16} {:>5} {:>12} {:>14}",
            "group", "value", "n", "CV(RMSE) %", "mean resid."
        )
        .map_err(io)?;
        for g in &c.groups {
            writeln!(
                w,
                "{:<10} {:<16} {:>5} {:>12.2} {:>+14.4}",
                g.by, g.value, g.n, g.cv_rmse_pct, g.mean_residual
            )
            .map_err(io)?;
        }
        write_warnings(w, warnings)?;
    }
    Ok(())
}

/// "X % for `what`" (the CV(RMSE) of the rows at c_x >= 1 %), or "no row at `what`" where
/// there is none (the statistic is NaN then): no "NaN %" in a report.
pub(crate) fn ge_1pct_text(cv: f64, what: &str) -> String {
    if cv.is_finite() {
        format!("{cv:.2} % for {what}")
    } else {
        format!("no row at {what}")
    }
}

/// The model's warnings for the rows, each once with its rows counted per series (nothing
/// when there are none).
pub(crate) fn write_warnings(w: &mut Vec<u8>, ws: &[ModelWarning]) -> Result<(), CreepError> {
    if !ws.is_empty() {
        write!(w, "\n{}", warnings_text(ws)).map_err(io)?;
    }
    Ok(())
}

/// Writes the PNGs; returns (file, caption in words) in report order: measured against model
/// per series first, then the residual plots.
pub(crate) fn write_plots(
    cfg: &Config,
    data: &Dataset,
    pred: &[Prediction],
    dir: &Path,
) -> Result<Vec<(std::path::PathBuf, String)>, CreepError> {
    let mut written = Vec::new();
    crate::cleanup::create_dir_all(dir).map_err(|e| CreepError::Config {
        source_name: dir.display().to_string(),
        message: format!("cannot create: {e}"),
    })?;
    series_plots(cfg, data, pred, dir, &mut written)?;
    residual_plots(data, pred, dir, &mut written)?;
    Ok(written)
}

/// An error of the plotting library, named after `--plots`.
fn plot_error(m: String) -> CreepError {
    CreepError::Config {
        source_name: "--plots".into(),
        message: m,
    }
}

/// Measured against model, one plot per series: over creepage with a dense steady model
/// curve at the series' first operating point, or over time for a time series.
fn series_plots(
    cfg: &Config,
    data: &Dataset,
    pred: &[Prediction],
    dir: &Path,
    written: &mut Vec<(std::path::PathBuf, String)>,
) -> Result<(), CreepError> {
    for (k, s) in data.series().iter().enumerate() {
        let idx: Vec<usize> = (0..data.rows.len())
            .filter(|&i| &data.rows[i].series == s)
            .collect();
        let r0 = &data.rows[idx[0]];
        let (xlabel, meas, model) = if r0.t.is_some() {
            (
                "time t (s)",
                idx.iter()
                    .map(|&i| (data.rows[i].t.unwrap_or(0.0), data.rows[i].f))
                    .collect::<Vec<_>>(),
                idx.iter()
                    .map(|&i| (data.rows[i].t.unwrap_or(0.0), pred[i].f))
                    .collect::<Vec<_>>(),
            )
        } else {
            // dense steady model curve at the series' first operating point
            let (lo, hi) = idx.iter().fold((f64::MAX, f64::MIN), |a, &i| {
                (a.0.min(data.rows[i].cx), a.1.max(data.rows[i].cx))
            });
            let mut c = cfg.clone();
            if let Some((a, b)) = r0.ab {
                c.geometry = creep_core::Geometry::SemiAxes {
                    a,
                    b,
                    fn_ref: r0.fn_n,
                };
            }
            let mut m = Model::new(&c)?;
            // the data columns of formula/custom effects at the series' first row
            m.set_extra(&ecf_measure::evaluate::extras(data, r0))?;
            let mut curve = Vec::new();
            for j in 0..=60 {
                let cx = lo + (hi - lo) * (j as f64 / 60.0).powi(2); // dense near the steep rise
                let o = m.steady(&Inputs { cx, ..r0.inputs() })?;
                curve.push((100.0 * cx, o.f));
            }
            (
                "creepage c_x (%)",
                idx.iter()
                    .map(|&i| (100.0 * data.rows[i].cx, data.rows[i].f))
                    .collect(),
                curve,
            )
        };
        let title = format!("series {s}: v = {} m/s, F_N = {} kN", r0.v, r0.fn_n / 1e3);
        let sets = [
            Set {
                label: "measured",
                xy: meas,
                style: Style::Points,
                color: 0,
            },
            Set {
                label: "model",
                xy: model,
                style: Style::Line,
                color: 1,
            },
        ];
        let file = dir.join(format!("series_{k:02}_{}.png", sanitize(s)));
        xy_plot(&file, &title, xlabel, "traction coefficient f (-)", &sets).map_err(plot_error)?;
        written.push((
            file,
            format!(
                "Measured traction coefficient (points) and model (line) of series '{s}' at {} m/s and {} kN, over {}.",
                r0.v,
                r0.fn_n / 1e3,
                if r0.t.is_some() { "time" } else { "creepage" }
            ),
        ));
    }
    Ok(())
}

/// The residuals over creepage, slip velocity, model temperature, frictional power and every
/// extra column, coloured by creepage regime.
fn residual_plots(
    data: &Dataset,
    pred: &[Prediction],
    dir: &Path,
    written: &mut Vec<(std::path::PathBuf, String)>,
) -> Result<(), CreepError> {
    let res: Vec<f64> = data.rows.iter().zip(pred).map(|(r, p)| p.f - r.f).collect();
    let mut vars: Vec<(String, String, Vec<f64>)> = vec![
        (
            "cx".into(),
            "creepage c_x (-)".into(),
            data.rows.iter().map(|r| r.cx).collect(),
        ),
        (
            "slip_velocity".into(),
            "slip velocity |c| v (m/s)".into(),
            pred.iter().map(|p| p.slip_velocity).collect(),
        ),
        (
            "T_max".into(),
            "model temperature T_max (degC)".into(),
            pred.iter().map(|p| p.t_max).collect(),
        ),
        (
            "P_fric".into(),
            "model frictional power (W)".into(),
            pred.iter().map(|p| p.p_fric).collect(),
        ),
    ];
    for (k, n) in data.extra_names.iter().enumerate() {
        vars.push((
            n.clone(),
            format!("{n} (extra column)"),
            data.rows.iter().map(|r| r.extra[k]).collect(),
        ));
    }
    let reg = regimes(data);
    for (name, label, x) in vars {
        let sets: Vec<Set> = ["R1", "R2", "R3"]
            .iter()
            .enumerate()
            .map(|(c, rg)| Set {
                label: rg,
                xy: x
                    .iter()
                    .zip(&res)
                    .zip(&reg)
                    .filter(|(_, r)| *r == rg)
                    .map(|((a, b), _)| (*a, *b))
                    .collect(),
                style: Style::Points,
                color: c,
            })
            .filter(|s| !s.xy.is_empty())
            .collect();
        let file = dir.join(format!("residual_over_{}.png", sanitize(&name)));
        xy_plot(
            &file,
            &format!("residual f_model - f_measured over {name}"),
            &label,
            "residual (-)",
            &sets,
        )
        .map_err(plot_error)?;
        written.push((
            file,
            format!(
                "Residual (model minus measured traction coefficient) over {label}, coloured by creepage regime (R1 steep rise, R2 moderate rise, R3 falling branch)."
            ),
        ));
    }
    Ok(())
}

fn sanitize(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '.' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// What `ecf fit` asks for beyond the data and the configuration.
pub struct FitRequest<'a> {
    /// `--free`: the parameters to fit, comma separated (`None`: the data kind's default).
    pub free: Option<&'a str>,
    /// `--bound NAME=MIN:MAX`, each narrowing a parameter's bounds.
    pub bounds: &'a [String],
    /// `--out`: where the fitted configuration goes.
    pub out: &'a Path,
    /// `--json`: report as JSON.
    pub json: bool,
}

impl FitRequest<'_> {
    /// The set-up both kinds of fit start from: the configuration with the `--bound`s applied,
    /// and the free parameters of `--free` (else `default`).
    fn setup(&self, cfg: &Config, default: Vec<P>) -> Result<(Config, Vec<FreeParam>), CreepError> {
        rep::fit_setup(cfg, self.free, self.bounds, default)
    }
}

/// Fits, writes the fitted configuration (`write_out`) and reports.
pub fn fit(
    cfg: &Config,
    data: &Dataset,
    threads: usize,
    req: &FitRequest,
    w: &mut Vec<u8>,
) -> Result<(), CreepError> {
    let (cfg, free) = req.setup(cfg, default_free(cfg))?;
    let cfg = &cfg;
    let bar = indicatif::ProgressBar::new_spinner();
    bar.set_style(
        indicatif::ProgressStyle::with_template("{spinner} fitting {msg} [{elapsed}]")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
    );
    let names: Vec<String> = free.iter().map(|p| p.name(cfg)).collect();
    bar.set_message(names.join(", "));
    let progress = |n: usize| {
        bar.set_message(format!(
            "{} — {n} model evaluations of {} rows",
            names.join(", "),
            data.rows.len()
        ))
    };
    let r = run_fit(cfg, data, &free, threads, &progress)?;
    bar.finish_and_clear();
    // the model's warnings for the rows under the fitted configuration
    let (_, warnings) = predict_warned(&r.config, data, threads)?;
    report_fit(&r, &warnings, req.out, req.json, w)
}

/// A progress message `STAGE [done/total]` split into its parts.
fn counted_stage(stage: &str) -> Option<(&str, u64, u64)> {
    let (msg, rest) = stage.rsplit_once(" [")?;
    let (done, total) = rest.strip_suffix(']')?.split_once('/')?;
    Some((msg, done.parse().ok()?, total.parse().ok()?))
}

/// Diagnoses and reports.
pub fn diagnose(
    cfg: &Config,
    data: &Dataset,
    o: &ecf_measure::diagnose::Options,
    json: bool,
    out: Option<&Path>,
    w: &mut Vec<u8>,
) -> Result<(), CreepError> {
    let bar = indicatif::ProgressBar::new_spinner();
    let spinner =
        indicatif::ProgressStyle::with_template("{spinner} diagnosing: {msg} [{elapsed}]")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner());
    let counted = indicatif::ProgressStyle::with_template(
        "{spinner} diagnosing: {msg} {bar:20} {pos}/{len} [{elapsed}]",
    )
    .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
    bar.set_style(spinner.clone());
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    // a stage that ends in "[done/total]" shows a bar, the others a spinner
    let progress = |stage: &str| match counted_stage(stage) {
        Some((msg, done, total)) => {
            bar.set_style(counted.clone());
            bar.set_length(total);
            bar.set_position(done);
            bar.set_message(msg.to_string());
        }
        None => {
            bar.set_style(spinner.clone());
            bar.set_message(stage.to_string());
        }
    };
    let d = ecf_measure::diagnose::diagnose_opts(cfg, data, o, &progress)?;
    bar.finish_and_clear();
    // the proposed configuration, written before anything is reported
    let proposed = d.search.as_ref().and_then(|s| s.proposed_config.as_ref());
    let written = match (out, proposed) {
        (Some(p), Some(c)) => {
            let text = serde_json::to_string_pretty(c)
                .map_err(|e| CreepError::State(e.to_string()))?
                + "\n";
            write_out(p, "json.tmp", text.as_bytes())?;
            Some(p)
        }
        _ => None,
    };
    if json {
        write_json(w, &d)?;
        return Ok(());
    }
    writeln!(
        w,
        "data {} ({} rows), configuration {} {:?}",
        data.source,
        data.rows.len(),
        cfg.model.name(),
        cfg.effects.to_vec()
    )
    .map_err(io)?;
    if let Some(g) = &d.model_grid {
        writeln!(w, "grid: {g}").map_err(io)?;
    }
    writeln!(w, "CV(RMSE) as given {:.2} %; held-out (folds by {}, {} folds) with its own parameters refitted {:.2} %", d.baseline_cv_rmse_pct, d.folds_by, d.folds, d.baseline_heldout_cv_rmse_pct).map_err(io)?;
    if d.catalogue_all_on {
        writeln!(
            w,
            "\nevery catalogue effect is already in the configuration: nothing in the catalogue to add"
        )
        .map_err(io)?;
    }
    writeln!(
        w,
        "\nresidual correlations (model - measured), strongest first:"
    )
    .map_err(io)?;
    for c in &d.correlations {
        writeln!(w, "  {:<22} r = {:+.2}", c.variable, c.r).map_err(io)?;
    }
    if !d.candidates.is_empty() {
        writeln!(w, "\ncandidate effects, best held-out error first:").map_err(io)?;
    }
    for c in &d.candidates {
        writeln!(
            w,
            "  {:<20} held-out {:6.2} %  fitted {:6.2} %\n    {}",
            c.effect, c.heldout_cv_rmse_pct, c.fitted_cv_rmse_pct, c.explanation
        )
        .map_err(io)?;
    }
    if let Some(s) = &d.search {
        let c = &s.cost;
        writeln!(
            w,
            "\nformula forms: {} of {} screened, the best {} refitted on the folds with their own parameters and the target's level, the best {} of those with every free parameter; {:.1} s on {} threads (model evaluations, one row at one configuration: needed factors {} in {:.1} s, shortlist {} in {:.1} s, finalists {} in {:.1} s, {:.2} ms each on one thread; screening {:.1} s). Best first:",
            s.tried, s.total, c.shortlisted, c.finalists, s.seconds, c.threads, c.inverse_evaluations, c.inverse_s, c.shortlist_evaluations, c.shortlist_s, c.final_evaluations, c.final_s, c.ms_per_evaluation(), c.screen_s
        )
        .map_err(io)?;
        for f in s.forms.iter().take(8) {
            let h = if f.heldout_cv_rmse_pct.is_finite() {
                format!("held-out {:6.2} %", f.heldout_cv_rmse_pct)
            } else if f.shortlist_cv_rmse_pct.is_finite() {
                format!("shortlist {:6.2} %", f.shortlist_cv_rmse_pct)
            } else {
                format!("screened {:6.2} %", f.screen_cv_rmse_pct)
            };
            writeln!(
                w,
                "  {:<9} x {:<10} in {:<10} {h}  {}\n    factor {}",
                f.target,
                f.shape,
                f.variable,
                f.params_text(),
                f.factor
            )
            .map_err(io)?;
        }
    }
    write_warnings(w, &d.warnings)?;
    writeln!(w, "\n{}", d.verdict).map_err(io)?;
    match (written, out, proposed) {
        (Some(p), _, _) => writeln!(
            w,
            "configuration with the proposed formula effect written to {}",
            p.display()
        )
        .map_err(io)?,
        (None, Some(p), None) => {
            writeln!(w, "no formula form proposed: {} not written", p.display()).map_err(io)?
        }
        _ => {}
    }
    Ok(())
}

/// Writes `bytes` to the `--out` path `out`, by what is there:
/// - nothing or a regular file: through a temporary file beside it (extension `ext`), renamed
///   over it at the end; the temporary file is removed on an error or an interrupt, and `out`
///   is never half-written;
/// - a symbolic link: the link stays and the file it leads to is written as above (for a
///   dangling link, the file it names is created, when its folder exists);
/// - a device, FIFO or socket (`/dev/null`, the pipe `/dev/fd/N` of a process substitution),
///   also behind a link: the bytes are written straight through it, with no temporary file;
/// - a directory: an error, and nothing is written.
pub(crate) fn write_out(out: &Path, ext: &str, bytes: &[u8]) -> Result<(), CreepError> {
    let err = |message: String| CreepError::Config {
        source_name: format!("--out {}", out.display()),
        message,
    };
    let is_link = std::fs::symlink_metadata(out).is_ok_and(|m| m.file_type().is_symlink());
    // what `out` leads to; a path that cannot be examined (missing, or with a file where a
    // folder should be) goes to the temporary file, whose creation says what is wrong
    let kind = match std::fs::metadata(out) {
        Ok(m) => Some(m),
        Err(e) if is_link && e.kind() != std::io::ErrorKind::NotFound => {
            return Err(err(format!("cannot follow the symbolic link: {e}")))
        }
        Err(_) => None,
    };
    let file = match kind {
        Some(m) if m.is_dir() => return Err(err("is a directory; expected a file path".into())),
        Some(m) if !m.is_file() => {
            // a device, FIFO or socket: written in place (the rename would replace it)
            let mut f = std::fs::OpenOptions::new()
                .write(true)
                .open(out)
                .map_err(|e| err(format!("cannot open for writing: {e}")))?;
            return f
                .write_all(bytes)
                .and_then(|()| f.flush())
                .map_err(|e| err(format!("cannot write: {e}")));
        }
        Some(_) if is_link => std::fs::canonicalize(out)
            .map_err(|e| err(format!("cannot follow the symbolic link: {e}")))?,
        None if is_link => dangling_target(out).map_err(err)?,
        _ => out.to_path_buf(),
    };
    let tmp = crate::cleanup::Pending::new(file.with_extension(ext));
    std::fs::write(tmp.path(), bytes).map_err(|e| CreepError::Config {
        source_name: tmp.path().display().to_string(),
        message: format!("cannot write: {e}"),
    })?;
    std::fs::rename(tmp.path(), &file).map_err(|e| CreepError::Config {
        source_name: file.display().to_string(),
        message: format!("cannot write: {e}"),
    })?;
    tmp.done();
    Ok(())
}

/// The missing file a dangling symbolic link `link` leads to (through further links), or why
/// it cannot be created: its folder does not exist, or the links go round.
fn dangling_target(link: &Path) -> Result<std::path::PathBuf, String> {
    let mut p = link.to_path_buf();
    // as many links as Linux follows in one path
    for _ in 0..40 {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let t = std::fs::read_link(&p)
                    .map_err(|e| format!("cannot read the symbolic link {}: {e}", p.display()))?;
                // a relative target is relative to the link's folder
                p = match p.parent() {
                    Some(dir) if t.is_relative() => dir.join(t),
                    _ => t,
                };
            }
            Ok(_) => return Ok(p),
            Err(_) => {
                let dir = match p.parent() {
                    Some(d) if !d.as_os_str().is_empty() => d,
                    _ => Path::new("."),
                };
                return if dir.is_dir() {
                    Ok(p)
                } else {
                    Err(format!(
                        "a symbolic link to {}, whose folder does not exist",
                        p.display()
                    ))
                };
            }
        }
    }
    Err("too many levels of symbolic links".into())
}

/// Reads a measurement file once, as its kind (ecf-measure's `file_kind`: a header with
/// `p_MPa`, `u_mm` and `tau_MPa` makes it a high-pressure-torsion file). The column mapping of
/// a file of rows is printed on stderr unless `quiet`.
pub fn read_data(
    path: &Path,
    defaults: &ecf_measure::measure::Defaults,
    quiet: bool,
) -> Result<Data, CreepError> {
    let data = ecf_measure::measure::read_data(path, defaults)?;
    if let (Data::Rows(d), false) = (&data, quiet) {
        eprint!("{}", d.mapping_text());
    }
    Ok(data)
}

/// Writes a value as pretty JSON.
fn write_json<T: serde::Serialize>(w: &mut Vec<u8>, v: &T) -> Result<(), CreepError> {
    let text = serde_json::to_string_pretty(v).map_err(|e| CreepError::State(e.to_string()))?;
    writeln!(w, "{text}").map_err(io)
}

/// Compares the layer model with high-pressure-torsion curves (seed Sec. 5.1).
pub fn compare_hpt(
    cfg: &Config,
    path: &Path,
    rows: &[ecf_measure::measure::HptRow],
    json: bool,
    plots: Option<&Path>,
    w: &mut Vec<u8>,
) -> Result<(), CreepError> {
    let cmp = rep::compare_hpt(cfg, rows);
    let (model, overall) = (&cmp.model, cmp.overall);
    let series: Vec<String> = cmp.per_series.iter().map(|p| p.0.clone()).collect();
    let idx_of =
        |s: &str| -> Vec<usize> { (0..rows.len()).filter(|&i| rows[i].series == s).collect() };
    if let Some(dir) = plots {
        crate::cleanup::create_dir_all(dir).map_err(|e| CreepError::Config {
            source_name: dir.display().to_string(),
            message: e.to_string(),
        })?;
        let labels: Vec<(String, String)> = series
            .iter()
            .map(|s| (format!("{s} measured"), format!("{s} model")))
            .collect();
        let mut sets = Vec::new();
        for (k, s) in series.iter().enumerate() {
            let idx = idx_of(s);
            sets.push(Set {
                label: &labels[k].0,
                xy: idx
                    .iter()
                    .map(|&i| (rows[i].u * 1e3, rows[i].tau / 1e6))
                    .collect(),
                style: Style::Points,
                color: k,
            });
            sets.push(Set {
                label: &labels[k].1,
                xy: idx
                    .iter()
                    .map(|&i| (rows[i].u * 1e3, model[i] / 1e6))
                    .collect(),
                style: Style::Line,
                color: k,
            });
        }
        xy_plot(
            &dir.join("hpt.png"),
            "high-pressure torsion: layer alone (seed Sec. 5.1)",
            "displacement u (mm)",
            "shear stress tau (MPa)",
            &sets,
        )
        .map_err(|m| CreepError::Config {
            source_name: "--plots".into(),
            message: m,
        })?;
    }
    if json {
        write_json(w, &cmp.to_json(rows.len()))?;
    } else {
        writeln!(
            w,
            "HPT data {} ({} rows): CV(RMSE) = {overall:.2} %",
            path.display(),
            rows.len()
        )
        .map_err(io)?;
        for (s, c) in &cmp.per_series {
            writeln!(w, "  series {s:<16} {c:8.2} %").map_err(io)?;
        }
    }
    Ok(())
}

/// Fits the layer parameters to high-pressure-torsion curves (written by `write_out`).
pub fn fit_hpt(
    cfg: &Config,
    path: &Path,
    rows: &[ecf_measure::measure::HptRow],
    req: &FitRequest,
    w: &mut Vec<u8>,
) -> Result<(), CreepError> {
    let (cfg, free) = req.setup(cfg, ecf_measure::hpt::default_free())?;
    let r = ecf_measure::hpt::fit(&cfg, &path.display().to_string(), rows, &free, &|_| {})?;
    report_fit(&r, &[], req.out, req.json, w)
}

/// Writes the fitted configuration (`write_out`: atomically for a file) and reports the fit.
fn report_fit(
    r: &ecf_measure::fit::FitResult,
    model_warnings: &[ModelWarning],
    out: &Path,
    json: bool,
    w: &mut Vec<u8>,
) -> Result<(), CreepError> {
    let doc = rep::fitted_document(r, model_warnings);
    let text =
        serde_json::to_string_pretty(&doc).map_err(|e| CreepError::State(e.to_string()))? + "\n";
    write_out(out, "json.tmp", text.as_bytes())?;
    for m in &r.warnings {
        eprintln!("warning: {m}");
    }
    if json {
        let v = rep::fit_json(r, model_warnings, Some(&out.display().to_string()));
        write_json(w, &v)?;
        return Ok(());
    }
    // several starts: the first ended stuck at a bound or worse than it started (docs/measurements.md, "Fits that never end worse than they started")
    let starts = if r.starts > 1 {
        format!(" from {} starts", r.starts)
    } else {
        String::new()
    };
    writeln!(
        w,
        "CV(RMSE) {:.2} % -> {:.2} % ({} model evaluations{starts}, {})",
        r.cv_rmse_pct_before, r.cv_rmse_pct_after, r.evaluations, r.termination
    )
    .map_err(io)?;
    for (p, st) in r.params.iter().zip(&r.status) {
        let (n, s, v, se) = (&p.name, p.start, p.value, p.stderr);
        let unit = params::by_name(n)
            .map(|p| params::spec(p).unit)
            .unwrap_or("-");
        let unc = match st {
            ecf_measure::fit::ParamStatus::Determined => format!("± {se:.2e}"),
            ecf_measure::fit::ParamStatus::NotIdentifiable => "± inf".to_string(),
            _ => "± -".to_string(),
        };
        let note = if st.note().is_empty() {
            String::new()
        } else {
            format!("  ({})", st.note())
        };
        writeln!(w, "  {n:<22} {s:>12.6} -> {v:>12.6} {unc} {unit}{note}").map_err(io)?;
    }
    let det: Vec<usize> = (0..r.params.len())
        .filter(|&k| r.status[k] == ecf_measure::fit::ParamStatus::Determined)
        .collect();
    for (a, &i) in det.iter().enumerate() {
        for &j in &det[a + 1..] {
            let c = r.correlation[i][j];
            if c.abs() > 0.95 {
                writeln!(
                    w,
                    "  correlation {} / {} = {c:+.3}: the data hardly separate them",
                    r.params[i].name, r.params[j].name
                )
                .map_err(io)?;
            }
        }
    }
    write_warnings(w, model_warnings)?;
    writeln!(w, "fitted configuration written to {}", out.display()).map_err(io)?;
    Ok(())
}
