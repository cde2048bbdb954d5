//! Fuzz test of the `ecf` command's inputs: random flags and values (NaN, inf, 1e300, 1e-300, negative, malformed) and random configuration files, each run a child process; 0 signals, 0 hangs, and no exit 0 with NaN or inf in the output.
//!
//! `ECF_FUZZ_CLI_RUNS` runs (default 100: about a second) from seed `ECF_FUZZ_SEED`, each
//! limited to `ECF_FUZZ_LIMIT_S` seconds (default 60). The long run: `bash scripts/fuzz.sh
//! --long` (docs/fmu.md, "Fuzzing").
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

#[path = "../../fmu-crate/tests/fuzz_rng/mod.rs"]
mod fuzz_rng;
use fuzz_rng::{env_num, Rng};

/// A value as a user might type it: mostly ordinary; one in three extreme, not finite or
/// not a number.
fn value(rng: &mut Rng, typical: f64) -> String {
    match rng.below(30) {
        0 => "nan".into(),
        1 => "inf".into(),
        2 => "-inf".into(),
        3 => "1e300".into(),
        4 => "1e-300".into(),
        5 => "-1e300".into(),
        6 => "0".into(),
        7 => "abc".into(),
        8 => "".into(),
        9 => format!("{}", -typical * rng.unit()),
        _ => format!("{}", typical * (0.2 + rng.unit())),
    }
}

/// A random configuration file (sometimes malformed, sometimes with a formula, sometimes
/// with two geometries).
fn config(rng: &mut Rng) -> String {
    let preset = *rng.pick(&["dry", "wet", "table4.1", "twin_disc", "bogus"]);
    let geometry = *rng.pick(&[
        "",
        r#", "geometry": {"a_mm": 7, "b_mm": 8, "fn_ref_kN": 110}"#,
        r#", "geometry": {"rx_mm": 460, "ry_mm": 300}"#,
        r#", "geometry": {"a_mm": 7, "b_mm": 8, "fn_ref_kN": 110, "rx_mm": 460, "ry_mm": 300}"#,
        r#", "geometry": {"a_mm": 1e300, "b_mm": 1e-300, "fn_ref_kN": 110}"#,
        r#", "geometry": {"line_radius_mm": 1e300, "line_width_mm": 1e-300}"#,
    ]);
    let factor = *rng.pick(&[
        "1 - k * (humidity - 50) / 50",
        "humidity / 50",
        "sqrt(humidity - 100)",
        "ln(humidity)",
        "exp(humidity)",
        "1 / (humidity - 50)",
    ]);
    let effects = if rng.below(2) == 0 {
        format!(
            r#", "formula_effects": [{{"name": "fz", "target": "{}", "factor": "{factor}", "params": {{"k": {{"value": 0.3, "min": -1, "max": 1}}}}}}]"#,
            rng.pick(&["tau_c1", "tau_c2", "L_e", "L_p", "mu"])
        )
    } else {
        String::new()
    };
    let text = format!(
        r#"{{"preset": "{preset}", "grid": {{"nx": {}, "ny": {}}}{geometry}{effects}}}"#,
        2 + rng.below(20),
        1 + rng.below(8)
    );
    if rng.below(10) == 0 {
        text[..rng.below(text.len())].to_string()
    } else {
        text
    }
}

/// The arguments of one run.
fn args(rng: &mut Rng, cfg_path: &str) -> Vec<String> {
    let cmd = *rng.pick(&["curve", "step", "sine", "field"]);
    let mut a: Vec<String> = vec![cmd.into()];
    let flag = |a: &mut Vec<String>, f: &str, v: String| {
        a.push(f.into());
        a.push(v);
    };
    // a small grid unless the fuzzer draws one
    flag(
        &mut a,
        "--grid",
        format!("{}x{}", 2 + rng.below(20), 1 + rng.below(8)),
    );
    if rng.below(3) == 0 {
        flag(&mut a, "--config", cfg_path.into());
    } else if rng.below(2) == 0 {
        let p = *rng.pick(&[
            "dry",
            "wet",
            "table4.1",
            "twin_disc",
            "fastsim",
            "polach",
            "x",
        ]);
        flag(&mut a, "--preset", p.into());
    }
    let numeric: [(&str, f64); 8] = [
        ("--v-mps", 20.0),
        ("--fn-kN", 110.0),
        ("--cy", 0.01),
        ("--spin", 0.5),
        ("--t-bulk-c", 20.0),
        ("--a-mm", 7.0),
        ("--b-mm", 8.0),
        ("--mu", 0.4),
    ];
    for (f, typical) in numeric {
        if rng.below(4) == 0 {
            let v = value(rng, typical);
            flag(&mut a, f, v);
        }
    }
    if rng.below(3) == 0 {
        let v = value(rng, 60.0);
        flag(&mut a, "--extra", format!("humidity={v}"));
    }
    if rng.below(4) == 0 {
        let p = *rng.pick(&["tau_c2_0_GPa", "L_e_0_um_per_GPa", "mu", "nonexistent"]);
        let v = value(rng, 0.5);
        flag(&mut a, "--param", format!("{p}={v}"));
    }
    match cmd {
        "curve" => {
            let v = if rng.below(3) == 0 {
                value(rng, 0.01)
            } else {
                format!("0.001:{}:{}", 0.01 + rng.unit() * 0.2, 1 + rng.below(4))
            };
            flag(&mut a, "--cx", v);
        }
        "field" => {
            let v = value(rng, 0.01);
            flag(&mut a, "--cx", v);
        }
        "step" => {
            let v = value(rng, 0.001);
            flag(&mut a, "--cx-from", v);
            let v = value(rng, 0.01);
            flag(&mut a, "--cx-to", v);
            let v = format!("{}", 1.0 + rng.unit() * 5.0);
            flag(&mut a, "--duration-ms", v);
            if rng.below(2) == 0 {
                let v = value(rng, 0.5);
                flag(&mut a, "--dt-ms", v);
            }
        }
        _ => {
            let v = value(rng, 0.01);
            flag(&mut a, "--cm", v);
            let v = value(rng, 0.005);
            flag(&mut a, "--ca", v);
            let v = value(rng, 50.0);
            flag(&mut a, "--freq-hz", v);
            flag(&mut a, "--cycles", "1".into());
        }
    }
    a
}

#[test]
fn random_cli_inputs_never_crash_hang_or_print_nan_with_exit_0() {
    use std::os::unix::process::ExitStatusExt;
    let runs: u64 = env_num("ECF_FUZZ_CLI_RUNS", 100);
    let seed: u64 = env_num("ECF_FUZZ_SEED", 0xEC_F25);
    let limit = Duration::from_secs_f64(env_num("ECF_FUZZ_LIMIT_S", 60.0));
    let mut rng = Rng(seed | 1);
    let cfg = std::env::temp_dir().join(format!("ecf-fuzz-cli-{}.json", std::process::id()));
    let cfg_path = cfg.to_str().expect("utf-8 temp path").to_string();
    let (mut ok, mut refused) = (0u64, 0u64);
    let (mut signals, mut hangs, mut nan_ok) = (Vec::new(), Vec::new(), Vec::new());
    let t0 = Instant::now();
    for _ in 0..runs {
        std::fs::write(&cfg, config(&mut rng)).expect("write config");
        let a = args(&mut rng, &cfg_path);
        let mut child = Command::new(env!("CARGO_BIN_EXE_ecf"))
            .args(&a)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("run ecf");
        // read the pipes on threads: a large table must not block the child
        let mut so = child.stdout.take().expect("stdout");
        let mut se = child.stderr.take().expect("stderr");
        let ro = std::thread::spawn(move || {
            let mut s = String::new();
            let _ = std::io::Read::read_to_string(&mut so, &mut s);
            s
        });
        let re = std::thread::spawn(move || {
            let mut s = String::new();
            let _ = std::io::Read::read_to_string(&mut se, &mut s);
            s
        });
        let started = Instant::now();
        let status = loop {
            if let Some(s) = child.try_wait().expect("wait") {
                break Some(s);
            }
            if started.elapsed() > limit {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            std::thread::sleep(Duration::from_millis(5));
        };
        let (out, err) = (ro.join().unwrap_or_default(), re.join().unwrap_or_default());
        match status {
            None => hangs.push(a),
            Some(s) if s.signal().is_some() => signals.push((a, s.signal(), err)),
            Some(s) if s.success() => {
                ok += 1;
                let lower = out.to_lowercase();
                if lower.contains("nan") || lower.contains("inf") {
                    nan_ok.push((a, out.lines().take(3).collect::<Vec<_>>().join("\n")));
                }
            }
            Some(s) => {
                refused += 1;
                // a refusal says why, on one line or a few, and is not a panic
                assert!(
                    !err.contains("panicked"),
                    "{a:?}: exit {:?} with a panic: {err}",
                    s.code()
                );
                assert!(
                    !err.trim().is_empty(),
                    "{a:?}: exit {:?} without a message",
                    s.code()
                );
            }
        }
    }
    let _ = std::fs::remove_file(&cfg);
    eprintln!(
        "[fuzz_cli] {runs} runs from seed {seed} in {:.1} s: {ok} exit 0, {refused} refused, {} signals, {} hangs, {} exit 0 with NaN/inf",
        t0.elapsed().as_secs_f64(),
        signals.len(),
        hangs.len(),
        nan_ok.len()
    );
    assert!(signals.is_empty(), "runs ended by a signal: {signals:#?}");
    assert!(hangs.is_empty(), "runs over {limit:?}: {hangs:#?}");
    assert!(nan_ok.is_empty(), "exit 0 with NaN or inf: {nan_ok:#?}");
    // both kinds of run happened: the fuzzer reaches the model, not only the parser
    assert!(ok > 0 && refused > 0, "{ok} ran, {refused} refused");
}
