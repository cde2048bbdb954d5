//! `ecf compare/fit/diagnose` on users' own files: units in headers, delimiters, missing
//! quantities, failed fits, bounds, nothing to try (docs/measurements.md).
mod common;
use common::ecf;
use std::process::Command;

fn dir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("ecf-loop-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// (cx, f) of the dry preset at 10 m/s, 110 kN.
fn points() -> Vec<(f64, f64)> {
    let (code, out, err) = ecf(&[
        "curve",
        "--preset",
        "dry",
        "--grid",
        "20x7",
        "--v-mps",
        "10",
        "--cx",
        "0.002:0.2:8",
    ]);
    assert_eq!(code, 0, "{err}");
    out.lines()
        .skip(1)
        .map(|l| {
            let c: Vec<f64> = l.split(',').take(2).map(|x| x.parse().unwrap()).collect();
            (c[0], c[1])
        })
        .collect()
}

fn cv(out: &str) -> f64 {
    serde_json::from_str::<serde_json::Value>(out).unwrap()["cv_rmse_pct"]
        .as_f64()
        .unwrap()
}

#[test]
fn units_delimiters_and_missing_quantities() {
    let d = dir("units");
    let pts = points();
    let mut plain = String::from("cx,f,v_mps,fn_kN,humidity\n");
    let mut semi = String::from("cx [%];f;v [km/h];Fn_N;humidity\n");
    let mut bare = String::from("cx,f\n");
    let mut pct = String::from("cx,f,v_mps,fn_kN\n");
    for (c, f) in &pts {
        let f = f * 0.97;
        plain += &format!("{c},{f},10,110,40\n");
        semi += &format!("{};{};36;110000;40\n", 100.0 * c, f).replace('.', ",");
        bare += &format!("{c},{f}\n");
        pct += &format!("{},{f},10,110\n", 100.0 * c);
    }
    let write = |n: &str, t: &str| {
        let p = d.join(n);
        std::fs::write(&p, t).unwrap();
        p.to_str().unwrap().to_string()
    };
    let (plain, semi, bare, pct) = (
        write("plain.csv", &plain),
        write("semi.csv", &semi),
        write("bare.csv", &bare),
        write("pct.csv", &pct),
    );
    let run = |f: &str, extra: &[&str]| {
        let mut a = vec!["compare", f, "--preset", "dry", "--grid", "20x7", "--json"];
        a.extend_from_slice(extra);
        ecf(&a)
    };
    let (code, out, err) = run(&plain, &[]);
    assert_eq!(code, 0, "{err}");
    let reference = cv(&out);
    assert!(reference > 1.0, "{reference}");
    // the same data in percent, km/h, N, ';' and decimal comma
    let (code, out, err) = run(&semi, &[]);
    assert_eq!(code, 0, "{err}");
    assert!((cv(&out) - reference).abs() < 1e-6 * reference, "{out}");
    assert!(
        err.contains("'v [km/h]'") && err.contains("v_mps") && err.contains("'Fn_N'"),
        "{err}"
    );
    assert!(err.contains("'humidity'") && err.contains("extra"), "{err}");
    // no speed or load: an error, unless given by flags
    let (code, _, err) = run(&bare, &[]);
    assert_eq!(code, 2);
    assert!(
        err.contains("--v-mps") && err.contains("data file"),
        "{err}"
    );
    let (code, out, err) = run(&bare, &["--v-mps", "10", "--fn-kN", "110"]);
    assert_eq!(code, 0, "{err}");
    assert!((cv(&out) - reference).abs() < 1e-6 * reference);
    // percent without a unit: stop; with --cx-unit percent: the same result
    let (code, _, err) = run(&pct, &[]);
    assert_eq!(code, 2);
    assert!(err.contains("looks like percent"), "{err}");
    let (code, out, err) = run(&pct, &["--cx-unit", "percent"]);
    assert_eq!(code, 0, "{err}");
    assert!((cv(&out) - reference).abs() < 1e-6 * reference);
}

#[test]
fn failed_fits_exit_nonzero_and_leave_out_untouched_and_bounds_hold() {
    let d = dir("fail");
    let pts = points();
    let mut zero = String::from("cx,f,v_mps,fn_kN\n");
    let mut good = String::from("cx,f,v_mps,fn_kN\n");
    for (c, f) in &pts {
        zero += &format!("{c},{f},10,110\n-{c},-{f},10,110\n");
        good += &format!("{c},{},10,110\n", f * 0.9);
    }
    let zp = d.join("zero.csv");
    let gp = d.join("good.csv");
    std::fs::write(&zp, zero).unwrap();
    std::fs::write(&gp, good).unwrap();
    let out = d.join("fitted.json");
    std::fs::write(&out, "previous result\n").unwrap();
    let (code, _, err) = ecf(&[
        "compare",
        zp.to_str().unwrap(),
        "--preset",
        "dry",
        "--grid",
        "20x7",
    ]);
    assert_ne!(code, 0);
    assert!(err.contains("not finite"), "{err}");
    let (code, stdout, err) = ecf(&[
        "fit",
        zp.to_str().unwrap(),
        "--preset",
        "dry",
        "--grid",
        "20x7",
        "--free",
        "tau_c2_0_GPa",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_ne!(code, 0, "{stdout}");
    assert!(err.contains("fit failed"), "{err}");
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "previous result\n");
    // --bound keeps the parameter inside and the result says it sits at the bound
    let (code, stdout, err) = ecf(&[
        "fit",
        gp.to_str().unwrap(),
        "--preset",
        "dry",
        "--grid",
        "20x7",
        "--free",
        "tau_c2_0_GPa",
        "--bound",
        "tau_c2_0_GPa=0.68:2",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let r: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let v = r["params"]["tau_c2_0_GPa"].as_f64().unwrap();
    assert!((0.68..=0.6801).contains(&v), "{v}");
    assert_eq!(r["status"]["tau_c2_0_GPa"], "at_lower_bound");
    let written = std::fs::read_to_string(&out).unwrap();
    assert!(written.contains("\"min\": 0.68"), "{written}");
}

#[test]
fn diagnose_with_every_catalogue_effect_on_says_so() {
    let d = dir("diag");
    let mut t = String::from("cx,f,v_mps,fn_kN\n");
    for v in ["5", "20"] {
        let (code, out, err) = ecf(&[
            "curve",
            "--preset",
            "dry",
            "--grid",
            "20x7",
            "--v-mps",
            v,
            "--cx",
            "0.002:0.2:6",
        ]);
        assert_eq!(code, 0, "{err}");
        for l in out.lines().skip(1) {
            let c: Vec<&str> = l.split(',').collect();
            t += &format!("{},{},{v},110\n", c[0], c[1]);
        }
    }
    let data = d.join("m.csv");
    std::fs::write(&data, t).unwrap();
    let cfg = d.join("all.json");
    std::fs::write(
        &cfg,
        "{\"preset\": \"dry\", \"effects\": [\"+elastic_unloading\"]}",
    )
    .unwrap();
    let (code, out, err) = ecf(&[
        "diagnose",
        data.to_str().unwrap(),
        "--config",
        cfg.to_str().unwrap(),
        "--grid",
        "20x7",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("every catalogue effect is already"), "{out}");
    assert!(!out.contains("candidate effects"), "{out}");
    assert!(!out.contains("try a formula effect"), "{out}");
}

#[test]
fn diagnose_report_does_not_depend_on_the_thread_count() {
    let data = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/measurements/humid.csv"
    );
    let run = |threads: Option<&str>| {
        let mut a = vec![
            "diagnose", data, "--preset", "dry", "--grid", "8x3", "--quiet", "--json",
        ];
        if let Some(t) = threads {
            a.extend(["--threads", t]);
        }
        let (code, out, err) = ecf(&a);
        assert_eq!(code, 0, "{err}");
        // everything but the wall time of the search of formula forms (it runs here: on this
        // grid the best model is not at the data's noise)
        let mut v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let s = v["search"]
            .as_object_mut()
            .expect("a search of formula forms");
        assert!(s.remove("seconds").is_some_and(|t| t.as_f64().is_some()));
        assert!(s
            .remove("cost")
            .is_some_and(|c| c["threads"].as_u64().is_some()));
        // and the verdict's "... with every free parameter, in N s"
        let verdict = v["verdict"].as_str().expect("verdict").to_string();
        let at = verdict
            .find("every free parameter, in ")
            .expect("the search's time")
            + 25;
        let end = at + verdict[at..].find(" s").expect("seconds");
        v["verdict"] = format!("{}{}", &verdict[..at], &verdict[end..]).into();
        v.to_string()
    };
    let one = run(Some("1"));
    assert!(one.contains("\"candidates\""), "{one}");
    assert_eq!(one, run(Some("3")));
    assert_eq!(one, run(None));
}

/// The worked example's files (a formula effect reading the data column `humidity`).
fn worked_example() -> (String, String) {
    let ex = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/measurements");
    (
        ex.join("humid.csv").display().to_string(),
        ex.join("dry-humid.json").display().to_string(),
    )
}

#[test]
fn plots_and_report_of_a_configuration_reading_a_data_column() {
    // the dense model curves of the plots are evaluated at the series' data-column values
    // (they failed with "uses the column 'humidity', which the data do not provide")
    let (data, cfg) = worked_example();
    let d = dir("column-plots");
    let plots = d.join("plots");
    let (code, _, err) = ecf(&[
        "compare",
        &data,
        "--config",
        &cfg,
        "--plots",
        plots.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    let pngs = std::fs::read_dir(&plots)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "png")
        })
        .count();
    assert!(pngs >= 3, "{pngs} PNGs");
    let html = d.join("r.html");
    let (code, _, err) = ecf(&[
        "report",
        &data,
        "--config",
        &cfg,
        "--out",
        html.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&html).unwrap();
    assert!(text.contains("data:image/png;base64,") && text.contains("humid"));
    assert!(
        !text.contains("Fitted parameters"),
        "no fit record, no table"
    );

    // with the fitted configuration: curves, then the fitted parameters (from the "fit"
    // record ecf fit writes), then the residuals, then the diagnosis
    let fitted = d.join("fitted.json");
    let (code, _, err) = ecf(&[
        "fit",
        &data,
        "--config",
        &cfg,
        "--free",
        "humid.k,tau_c2_0_GPa",
        "--out",
        fitted.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    let rec: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&fitted).unwrap()).unwrap();
    let k = &rec["fit"]["params"][0];
    assert_eq!(k["name"], "humid.k");
    let (kv, kse) = (k["value"].as_f64().unwrap(), k["stderr"].as_f64().unwrap());
    assert!(kv > 0.2 && kse > 0.0 && kse < 0.1 * kv, "{k}");
    let (code, _, err) = ecf(&[
        "report",
        &data,
        "--config",
        &cfg,
        "--compare-with",
        fitted.to_str().unwrap(),
        "--out",
        html.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&html).unwrap();
    let at = |s: &str| text.find(s).unwrap_or_else(|| panic!("'{s}' missing"));
    let first_curve = at("Measured traction coefficient (points) and model (line)");
    let table = at("<h2>Fitted parameters</h2>");
    let residuals = at("<h2>Residuals</h2>");
    let diagnosis = at("<h2>Diagnosis");
    assert!(first_curve < table && table < residuals && residuals < diagnosis);
    assert!(
        text.contains(&format!("<b>{kv:.6}</b>")),
        "fitted k in the table"
    );
    assert!(text.contains(&format!("± {kse:.2e}")), "its standard error");
}

#[test]
fn an_interrupted_report_leaves_no_temporary_files() {
    let (data, cfg) = worked_example();
    let d = dir("interrupt");
    let mut interrupted = 0;
    for (k, delay_ms) in [50u64, 150, 400, 900].into_iter().enumerate() {
        let html = d.join(format!("r{k}.html"));
        let mut child = Command::new(env!("CARGO_BIN_EXE_ecf"))
            .args(["report", &data, "--config", &cfg, "--quiet", "--out"])
            .arg(&html)
            .stderr(std::process::Stdio::null())
            .spawn()
            .expect("run ecf");
        std::thread::sleep(std::time::Duration::from_millis(delay_ms));
        let pid = child.id();
        let _ = Command::new("kill")
            .args(["-INT", &pid.to_string()])
            .status();
        let status = child.wait().unwrap();
        let tmp = std::env::temp_dir().join(format!("ecf-report-{pid}"));
        assert!(
            !tmp.exists(),
            "{} left after SIGINT at {delay_ms} ms",
            tmp.display()
        );
        assert!(
            !tmp.with_extension("removing").exists(),
            "the folder moved aside was left"
        );
        assert!(!html.with_extension("html.tmp").exists());
        if status.code() == Some(130) {
            interrupted += 1;
            assert!(
                !html.exists(),
                "an interrupted report wrote {}",
                html.display()
            );
        } else {
            assert_eq!(status.code(), Some(0), "{status:?}");
        }
    }
    assert!(interrupted > 0, "no run was interrupted");
}

/// A configuration JSON of the dry preset with tau_c1 x 1/(1 + k (v - 5)/15).
fn fall_config(k: f64, min: f64, max: f64) -> String {
    format!(
        r#"{{"preset": "dry", "grid": {{"nx": 20, "ny": 7}}, "formula_effects": [{{"name": "fall",
            "target": "tau_c1", "factor": "1 / (1 + k * (v_mps - 5) / 15)",
            "params": {{"k": {{"value": {k}, "min": {min}, "max": {max}}}}}}}]}}"#
    )
}

#[test]
fn a_fit_started_on_a_bound_moves_off_it() {
    let d = dir("onbound");
    let truth = d.join("truth.json");
    std::fs::write(&truth, fall_config(2.4, 0.0, 20.0)).unwrap();
    let mut t = String::from("cx,f,v_mps,fn_kN\n");
    for v in ["5", "12", "20"] {
        let (code, out, err) = ecf(&[
            "curve",
            "--config",
            truth.to_str().unwrap(),
            "--v-mps",
            v,
            "--cx",
            "0.002:0.2:8",
        ]);
        assert_eq!(code, 0, "{err}");
        for l in out.lines().skip(1) {
            let c: Vec<&str> = l.split(',').collect();
            t += &format!("{},{},{v},110\n", c[0], c[1]);
        }
    }
    let data = d.join("fall.csv");
    std::fs::write(&data, t).unwrap();
    let out = d.join("fitted.json");
    for (k, min) in [(0.0, 0.0), (0.0, -0.01)] {
        let start = d.join("start.json");
        std::fs::write(&start, fall_config(k, min, 20.0)).unwrap();
        let (code, stdout, err) = ecf(&[
            "fit",
            data.to_str().unwrap(),
            "--config",
            start.to_str().unwrap(),
            "--free",
            "fall.k",
            "--out",
            out.to_str().unwrap(),
            "--json",
        ]);
        assert_eq!(code, 0, "{err}");
        let r: serde_json::Value = serde_json::from_str(&stdout).unwrap();
        let v = r["params"]["fall.k"].as_f64().unwrap();
        assert!((v - 2.4).abs() < 0.01, "min {min}: k = {v}");
        assert_eq!(r["status"]["fall.k"], "determined");
        assert!(r["starts"].as_u64().unwrap() >= 1);
        let written: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
        assert_eq!(written["fit"]["params"][0]["value"], r["params"]["fall.k"]);
    }
}

#[test]
fn wheel_slide_warnings_reach_compare_diagnose_and_fit() {
    let d = dir("slide");
    let mut t = String::from("cx [-],f,series,v_mps,fn_kN\n");
    for (s, v) in [("A", 10.0), ("B", 20.0)] {
        for c in [-0.002, -0.01, -0.05, -0.3, -0.95] {
            t += &format!(
                "{c},{},{s},{v},110\n",
                -0.3 * (1.0 - (-f64::abs(c) * 300.0).exp())
            );
        }
    }
    let data = d.join("slide.csv");
    std::fs::write(&data, t).unwrap();
    let common = ["--preset", "dry", "--grid", "20x7"];
    let run = |cmd: &[&str]| {
        let mut a: Vec<&str> = cmd.to_vec();
        a.push(data.to_str().unwrap());
        a.extend(common);
        let (code, out, err) = ecf(&a);
        assert_eq!(code, 0, "{cmd:?}: {err}");
        out
    };
    let c: serde_json::Value = serde_json::from_str(&run(&["compare", "--json"])).unwrap();
    let ws = c["warnings"]
        .as_array()
        .expect("compare JSON has 'warnings'");
    let slide = ws
        .iter()
        .find(|w| {
            w["message"]
                .as_str()
                .unwrap()
                .starts_with("wheel surface speed")
        })
        .expect("wheel slide warned");
    assert_eq!(slide["rows"], 2);
    assert_eq!(slide["per_series"][0]["series"], "A");
    assert_eq!(slide["per_series"][1]["rows"], 1);
    let text = run(&["compare"]);
    assert!(
        text.contains("series A: 1 row(s)") && text.contains("surface_time_flash"),
        "{text}"
    );
    let diag = run(&["diagnose"]);
    assert!(
        diag.contains("wheel surface speed") && diag.contains("series B: 1 row(s)"),
        "{diag}"
    );
    let out = d.join("fitted.json");
    let fit = run(&["fit", "--out", out.to_str().unwrap()]);
    assert!(fit.contains("wheel surface speed"), "{fit}");
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(written["fit"]["model_warnings"][0]["rows"], 2);
}

/// Curves of a configuration file at the given speeds, 110 kN, 10 creepages each.
fn curves_of(cfg: &std::path::Path, speeds: &[&str]) -> String {
    let mut t = String::from("cx,f,series,v_mps,fn_kN\n");
    for v in speeds {
        let (code, out, err) = ecf(&[
            "curve",
            "--config",
            cfg.to_str().unwrap(),
            "--v-mps",
            v,
            "--cx",
            "0.002:0.2:10",
        ]);
        assert_eq!(code, 0, "{err}");
        for l in out.lines().skip(1) {
            let c: Vec<&str> = l.split(',').collect();
            t += &format!("{},{},v{v},{v},110\n", c[0], c[1]);
        }
    }
    t
}

#[test]
fn diagnose_proposes_a_formula_form_and_writes_a_configuration_fit_takes() {
    let d = dir("forms");
    let truth = d.join("truth.json");
    std::fs::write(&truth, fall_config(1.5, 0.0, 20.0)).unwrap();
    let data = d.join("fall.csv");
    std::fs::write(&data, curves_of(&truth, &["5", "10", "15", "20"])).unwrap();
    let prop = d.join("proposed.json");
    let (code, out, err) = ecf(&[
        "diagnose",
        data.to_str().unwrap(),
        "--preset",
        "dry",
        "--grid",
        "20x7",
        "--out",
        prop.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("formula forms: ") && out.contains("Proposed: tau_c1 x "),
        "{out}"
    );
    assert!(out.contains("in v_mps (factor "), "{out}");
    assert!(out.contains("written to"), "{out}");
    // the proposed configuration is taken by ecf fit as it stands, its form's parameters free
    let j: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&prop).unwrap()).unwrap();
    let free: Vec<String> = j["formula_effects"][0]["params"]
        .as_object()
        .expect("the form's parameters")
        .keys()
        .map(|k| format!("form_tau_c1.{k}"))
        .collect();
    let free = free.join(",");
    let fitted = d.join("fitted.json");
    let (code, fit, err) = ecf(&[
        "fit",
        data.to_str().unwrap(),
        "--config",
        prop.to_str().unwrap(),
        "--free",
        &free,
        "--out",
        fitted.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let r: serde_json::Value = serde_json::from_str(&fit).unwrap();
    assert!(r["cv_rmse_pct_after"].as_f64().unwrap() < 1.0, "{fit}");
    // nothing missing: nothing proposed, nothing written
    let plain = d.join("plain.json");
    std::fs::write(
        &plain,
        "{\"preset\": \"dry\", \"grid\": {\"nx\": 20, \"ny\": 7}}",
    )
    .unwrap();
    std::fs::write(&data, curves_of(&plain, &["5", "10", "15", "20"])).unwrap();
    let none = d.join("none.json");
    let (code, out, err) = ecf(&[
        "diagnose",
        data.to_str().unwrap(),
        "--config",
        plain.to_str().unwrap(),
        "--out",
        none.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("not written") && !none.exists(), "{out}");
}
