//! Widened fuzz test: random configurations (presets, effect switches, parameters at and beyond their bounds, configuration files with formulas), states taken in every mode, serialized, restored into fresh instances and corrupted; each case in a child process, so that a crash or hang is counted, not fatal.
//!
//! The parent test runs `ECF_FUZZ_CASES` cases (default 100: a few seconds) from seed
//! `ECF_FUZZ_SEED`, each in a child process (this test binary, filtered to
//! `fuzz_child_case`, with `ECF_FUZZ_CHILD` set to the case's seed) with a time limit of
//! `ECF_FUZZ_LIMIT_S` seconds (default 60), and asserts 0 signals, 0 hangs and 0 failed
//! checks. Each case checks:
//! - every status is OK/Warning/Discard/Error, and every real read with OK is finite;
//! - after a step with OK the area fractions sum to 1 within 1e-9 (or are all 0: no
//!   contact), each within [0, 1] up to 1e-9 (the rounding of summing the cells' areas);
//! - a state taken with OK in any mode (instantiated, initialization, stepping, terminated)
//!   serializes, deserializes with OK and restores with OK into a freshly instantiated
//!   instance; one taken while stepping continues there exactly (bitwise) as in the instance
//!   it was taken from;
//! - after a failed `fmi2ExitInitializationMode`, `fmi2GetFMUstate` returns Error;
//! - corrupted serializations (bit flips, bytes, truncations, extensions, non-finite
//!   numbers) are refused or give a state whose outputs satisfy the checks above, also
//!   after a step.
//!
//! The long run: `bash scripts/fuzz.sh --long` (docs/fmu.md, "Fuzzing").

mod common;
use common::{Fmu, ERROR, OK, WARNING};
use ecf_contact::ffi::*;
use ecf_contact::vars::{self, Causality, Kind, Start};
use fmi_sys::fmi2 as f;
use std::time::{Duration, Instant};

#[path = "fuzz_rng/mod.rs"]
mod fuzz_rng;
use fuzz_rng::{env_num, Rng};

/// Counts of one case, printed by the child as `FUZZCOUNT key=value ...`.
#[derive(Default, Debug)]
struct Counts {
    calls: u64,
    states: u64,
    restored_fresh: u64,
    continued_equal: u64,
    corrupt_refused: u64,
    corrupt_accepted: u64,
    failed_inits: u64,
}

/// A random formula over the parameter `k` and the data column `humidity`: sums, products,
/// quotients, powers and functions, nested to a random depth (sometimes far beyond the
/// parser's limit).
fn formula(rng: &mut Rng, depth: usize) -> String {
    if depth == 0 {
        return match rng.below(5) {
            0 => "k".into(),
            1 => "humidity".into(),
            2 => format!("{}", rng.unit() * 2.0),
            3 => "T".into(),
            _ => "1".into(),
        };
    }
    let a = formula(rng, depth - 1);
    match rng.below(9) {
        0 => format!("({a}) + {}", formula(rng, 0)),
        1 => format!("({a}) * {}", formula(rng, 0)),
        2 => format!("({a}) / {}", formula(rng, 0)),
        3 => format!("({a}) ^ 2"),
        4 => format!("exp(-abs({a}))"),
        5 => format!("sqrt({a})"),
        6 => format!("ln({a})"),
        7 => format!("tanh({a})"),
        _ => format!("max(0.1, min(10, {a}))"),
    }
}

/// A configuration file: a preset, a grid, and a formula effect on a random target.
fn config_text(rng: &mut Rng) -> String {
    let depth = match rng.below(10) {
        0 => 10_000, // far beyond the parser's limit: an error, not a crash
        1 => 60,
        _ => rng.below(6),
    };
    let f = if depth == 10_000 {
        format!("{}1{}", "(".repeat(depth), ")".repeat(depth))
    } else {
        formula(rng, depth)
    };
    let preset = *rng.pick(&["dry", "wet", "table4.1", "twin_disc", "dry_sanded"]);
    let target = *rng.pick(&["tau_c1", "tau_c2", "L_e", "L_p", "mu"]);
    let (lo, hi, k) = (-(rng.unit() * 2.0), rng.unit() * 2.0, rng.unit() - 0.5);
    format!(
        r#"{{"preset": "{preset}", "grid": {{"nx": {}, "ny": {}}},
 "formula_effects": [{{"name": "fz", "target": "{target}", "factor": "{f}",
   "params": {{"k": {{"value": {k}, "min": {lo}, "max": {hi}}}}}}}]}}"#,
        2 + rng.below(14),
        1 + rng.below(6)
    )
}

/// A value for a real parameter with bounds `lo`, `hi`: at or just beyond a bound, inside,
/// its start value, or not finite.
fn param_value(rng: &mut Rng, v: &vars::Var) -> f64 {
    let (lo, hi) = (v.min.unwrap_or(-1e300), v.max.unwrap_or(1e300));
    let start = match v.start {
        Start::Real(x) => x,
        _ => 0.0,
    };
    match rng.below(10) {
        0 => lo,
        1 => hi,
        2 => lo - lo.abs().max(1.0) * 1e-9,
        3 => hi + hi.abs().max(1.0) * 1e-9,
        4 => f64::NAN,
        5 => f64::INFINITY,
        6 => start,
        _ if lo.is_finite() && hi.is_finite() => lo + rng.unit() * (hi - lo),
        _ => start * (0.5 + rng.unit()),
    }
}

/// Checks the outputs of an instance that reports OK: finite, and (`stepped`) area
/// fractions that sum to 1 or are all 0. Returns false where an output is not readable.
fn check_outputs(c: f::fmi2Component, stepped: bool, what: &str) -> bool {
    let mut o = [0.0f64; 13];
    for (i, n) in common::OUTPUT_NAMES.iter().enumerate() {
        let mut x = f64::NAN;
        let st = unsafe { fmi2GetReal(c, &common::vr(n), 1, &mut x) };
        assert!(st <= ERROR, "{what}: get {n}: status {st}");
        if st != OK {
            return false;
        }
        assert!(x.is_finite(), "{what}: {n} = {x} with OK");
        o[i] = x;
    }
    if stepped {
        let s = o[7] + o[8] + o[9];
        // the model's invariant up to the rounding of summing the cells' areas (n eps, below
        // 1e-9 on the largest grid), the bound the state reader checks
        assert!(
            (s - 1.0).abs() <= 1e-9 || (o[7] == 0.0 && o[8] == 0.0 && o[9] == 0.0),
            "{what}: area fractions {:?} sum to {s}",
            &o[7..10]
        );
        for (k, x) in o[7..10].iter().enumerate() {
            assert!(
                (-1e-9..=1.0 + 1e-9).contains(x),
                "{what}: fraction {k} = {x}"
            );
        }
    }
    true
}

/// Corrupts a serialization: a bit flip, a random byte, a truncation, an extension or a
/// non-finite number written over 8 aligned bytes.
fn corrupt(rng: &mut Rng, b: &[u8]) -> Vec<u8> {
    let mut c = b.to_vec();
    if c.is_empty() {
        return vec![0];
    }
    match rng.below(6) {
        0 => {
            let i = rng.below(c.len());
            c[i] ^= 1 << rng.below(8);
        }
        1 => {
            let i = rng.below(c.len());
            c[i] = rng.next() as u8;
        }
        2 => c.truncate(rng.below(c.len())),
        3 => c.extend((0..1 + rng.below(16)).map(|_| rng.next() as u8)),
        _ => {
            let i = rng.below(c.len() / 8) * 8;
            let x = *rng.pick(&[f64::NAN, f64::INFINITY, -1.0, 1e300, -0.0, 2.0]);
            if i + 8 <= c.len() {
                c[i..i + 8].copy_from_slice(&x.to_le_bytes());
            }
        }
    }
    c
}

/// Takes a state of `a` in `mode` and checks it: it reloads, restores into a fresh
/// instance, continues there as in `a` (`stepping`), and its corruptions are refused or
/// give valid outputs.
fn check_state(a: &mut Fmu, mode: &str, stepping: bool, rng: &mut Rng, n: &mut Counts) {
    let mut s: f::fmi2FMUstate = std::ptr::null_mut();
    let st = unsafe { fmi2GetFMUstate(a.c, &mut s) };
    n.calls += 1;
    assert!(st <= ERROR, "{mode}: get state: status {st}");
    if st != OK {
        return;
    }
    n.states += 1;
    let bytes = a.serialize(s);
    let s2 = a
        .deserialize(&bytes)
        .unwrap_or_else(|st| panic!("{mode}: own state refused ({st}): {:?}", a.messages()));
    // into a freshly instantiated instance
    let mut b = Fmu::new(&format!("{}-fresh", a.name));
    let sb = b
        .deserialize(&bytes)
        .unwrap_or_else(|st| panic!("{mode}: fresh instance refused the state ({st})"));
    let st = unsafe { fmi2SetFMUstate(b.c, sb) };
    assert_eq!(
        st,
        OK,
        "{mode}: set state in a fresh instance: {:?}",
        b.messages()
    );
    n.restored_fresh += 1;
    if stepping {
        // both continue from the state: bitwise the same
        a.set_state(s2);
        b.set_state(sb);
        let h = 1e-3 * (0.1 + rng.unit());
        let (sa, sb_st) = (a.step(h), b.step(h));
        // a warning is logged once per instance (the fresh one may warn where the original
        // already did): the statuses agree up to that
        assert_eq!(
            sa <= WARNING,
            sb_st <= WARNING,
            "{mode}: step after restore: statuses {sa} and {sb_st}: {:?}",
            b.messages()
        );
        if sa <= WARNING {
            let (oa, ob) = (a.outputs(), b.outputs());
            let same = oa.iter().zip(&ob).all(|(x, y)| x.to_bits() == y.to_bits());
            assert!(same, "{mode}: continued differently: {oa:?} vs {ob:?}");
            n.continued_equal += 1;
        }
    }
    // corruptions, restored into a third instance
    for _ in 0..4 {
        let bad = corrupt(rng, &bytes);
        let c = Fmu::new(&format!("{}-corrupt", a.name));
        match c.deserialize(&bad) {
            Err(st) => {
                assert!(st <= ERROR, "{mode}: corrupt deserialize status {st}");
                n.corrupt_refused += 1;
            }
            Ok(sc) => {
                n.corrupt_accepted += 1;
                let st = unsafe { fmi2SetFMUstate(c.c, sc) };
                assert!(st <= ERROR, "{mode}: corrupt set status {st}");
                if st == OK && stepping {
                    check_outputs(c.c, true, &format!("{mode}: corrupted state"));
                    let mut t = 0.0;
                    unsafe {
                        fmi2GetRealStatus(c.c, f::fmi2StatusKind_fmi2LastSuccessfulTime, &mut t)
                    };
                    let st = unsafe { fmi2DoStep(c.c, t, 1e-3, 1) };
                    assert!(st <= ERROR, "{mode}: step of a corrupted state: {st}");
                    if st <= WARNING {
                        check_outputs(c.c, true, &format!("{mode}: corrupted state, stepped"));
                    }
                }
                let mut sc = sc;
                assert_eq!(unsafe { fmi2FreeFMUstate(c.c, &mut sc) }, OK);
            }
        }
    }
    a.free_state(s);
    // s2 was set into `a` above where stepping; free it in any case
    a.free_state(s2);
    b.free_state(sb);
}

/// One fuzz case: a random configuration driven through every mode.
fn run_case(seed: u64) -> Counts {
    let mut rng = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let mut n = Counts::default();
    let of = |k: Kind, c: Causality| common::vars_of(k, &[c]);
    let (params, bools) = (
        of(Kind::Real, Causality::Parameter),
        of(Kind::Boolean, Causality::Parameter),
    );
    let inputs = of(Kind::Real, Causality::Input);
    let mut a = Fmu::new(&format!("wide{seed}"));
    let tmp =
        std::env::temp_dir().join(format!("ecf-fuzz-wide-{}-{seed}.json", std::process::id()));
    let count = |n: &mut Counts, st: f::fmi2Status, what: &str| {
        n.calls += 1;
        assert!(st <= ERROR, "{what}: status {st}");
    };
    // configuration
    if rng.below(3) == 0 {
        std::fs::write(&tmp, config_text(&mut rng)).expect("write config");
        let st = a.set_string("config_file", tmp.to_str().expect("utf-8 path"));
        count(&mut n, st, "config_file");
        let cols = *rng.pick(&[
            "humidity=aux1",
            "humidity=30",
            "",
            "humidity=1e308",
            "T=aux2",
        ]);
        let st = a.set_string("columns", cols);
        count(&mut n, st, "columns");
    } else {
        let p = *rng.pick(&[
            "",
            "dry",
            "wet",
            "table4.1",
            "dry_sanded",
            "wet_sanded",
            "twin_disc",
            "fastsim",
            "polach",
            "bogus",
        ]);
        let st = a.set_string("preset", p);
        count(&mut n, st, "preset");
    }
    for v in &bools {
        if rng.below(3) == 0 {
            let x = rng.below(2) as f::fmi2Boolean;
            let st = unsafe { fmi2SetBoolean(a.c, &v.vr, 1, &x) };
            count(&mut n, st, &v.name);
        }
    }
    for _ in 0..rng.below(8) {
        let v = rng.pick(&params);
        let x = param_value(&mut rng, v);
        let st = unsafe { fmi2SetReal(a.c, &v.vr, 1, &x) };
        count(&mut n, st, &format!("{} = {x:e}", v.name));
    }
    // a small grid keeps each case short
    let st = a.set_int("nx", 2 + rng.below(14) as i32);
    count(&mut n, st, "nx");
    let st = a.set_int("ny", 1 + rng.below(6) as i32);
    count(&mut n, st, "ny");
    let set_inputs = |rng: &mut Rng, a: &Fmu, n: &mut Counts| {
        for v in &inputs {
            if rng.below(2) == 0 {
                let x = match (v.name.as_str(), rng.below(8)) {
                    (_, 0) => *rng.pick(&[f64::NAN, 1e300, -1e300, 0.0]),
                    ("cx" | "cy", _) => (rng.unit() - 0.5) * 0.4,
                    ("spin", _) => (rng.unit() - 0.5) * 2.0,
                    ("v", _) => (rng.unit() - 0.2) * 40.0,
                    ("FN", _) => rng.unit() * 2e5,
                    ("T_bulk", _) => rng.unit() * 100.0,
                    _ => rng.unit() * 100.0,
                };
                let st = unsafe { fmi2SetReal(a.c, &v.vr, 1, &x) };
                n.calls += 1;
                assert!(st <= ERROR, "set {} = {x}: status {st}", v.name);
            }
        }
    };
    set_inputs(&mut rng, &a, &mut n);
    check_state(&mut a, "instantiated", false, &mut rng, &mut n);
    unsafe {
        count(
            &mut n,
            fmi2SetupExperiment(a.c, 0, 0.0, 0.0, 0, 0.0),
            "setup",
        );
        count(&mut n, fmi2EnterInitializationMode(a.c), "enter init");
    }
    check_state(&mut a, "initialization", false, &mut rng, &mut n);
    let st = unsafe { fmi2ExitInitializationMode(a.c) };
    count(&mut n, st, "exit init");
    if st > WARNING {
        n.failed_inits += 1;
        let mut s: f::fmi2FMUstate = std::ptr::null_mut();
        let st = unsafe { fmi2GetFMUstate(a.c, &mut s) };
        n.calls += 1;
        assert_eq!(st, ERROR, "get state after a failed initialization");
        let _ = std::fs::remove_file(&tmp);
        return n;
    }
    for k in 0..1 + rng.below(5) {
        if rng.below(2) == 0 {
            set_inputs(&mut rng, &a, &mut n);
        }
        let st = a.step(rng.unit() * 2e-3);
        count(&mut n, st, "step");
        if st <= WARNING {
            check_outputs(a.c, true, &format!("step {k}"));
        }
        if rng.below(2) == 0 {
            check_state(&mut a, "stepping", true, &mut rng, &mut n);
        }
    }
    let st = unsafe { fmi2Terminate(a.c) };
    count(&mut n, st, "terminate");
    check_state(&mut a, "terminated", false, &mut rng, &mut n);
    let _ = std::fs::remove_file(&tmp);
    n
}

/// The child's entry: runs the case whose seed `ECF_FUZZ_CHILD` holds; without it (an
/// ordinary test run) it does nothing.
#[test]
fn fuzz_child_case() {
    let Ok(seed) = std::env::var("ECF_FUZZ_CHILD") else {
        return;
    };
    let seed: u64 = seed.parse().expect("ECF_FUZZ_CHILD: a seed");
    let n = run_case(seed);
    println!(
        "FUZZCOUNT calls={} states={} restored_fresh={} continued_equal={} corrupt_refused={} corrupt_accepted={} failed_inits={}",
        n.calls,
        n.states,
        n.restored_fresh,
        n.continued_equal,
        n.corrupt_refused,
        n.corrupt_accepted,
        n.failed_inits
    );
}

#[test]
fn widened_fuzz_no_signal_no_hang_no_failed_check() {
    if std::env::var("ECF_FUZZ_CHILD").is_ok() {
        return;
    }
    use std::os::unix::process::ExitStatusExt;
    let cases: u64 = env_num("ECF_FUZZ_CASES", 100);
    let seed0: u64 = env_num("ECF_FUZZ_SEED", 0xEC_F25);
    let limit = Duration::from_secs_f64(env_num("ECF_FUZZ_LIMIT_S", 60.0));
    let exe = std::env::current_exe().expect("test binary");
    let (mut signals, mut hangs, mut failed) = (Vec::new(), Vec::new(), Vec::new());
    let mut totals = std::collections::BTreeMap::<String, u64>::new();
    let t0 = Instant::now();
    for i in 0..cases {
        let seed = seed0 + i;
        let mut child = std::process::Command::new(&exe)
            .args([
                "--exact",
                "fuzz_child_case",
                "--nocapture",
                "--test-threads=1",
            ])
            .env("ECF_FUZZ_CHILD", seed.to_string())
            .env("RUST_BACKTRACE", "0")
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("spawn child");
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
        let out = child.wait_with_output().expect("child output");
        let stdout = String::from_utf8_lossy(&out.stdout);
        match status {
            None => hangs.push(seed),
            Some(s) if s.signal().is_some() => signals.push((seed, s.signal())),
            Some(s) if !s.success() => {
                let err = String::from_utf8_lossy(&out.stderr);
                let msg = stdout
                    .lines()
                    .chain(err.lines())
                    .filter(|l| l.contains("panicked") || l.contains(": "))
                    .take(6)
                    .collect::<Vec<_>>()
                    .join("\n");
                failed.push((seed, msg));
            }
            Some(_) => {}
        }
        // the harness may print the test's name on the same line before it
        for l in stdout.lines().filter_map(|l| l.split_once("FUZZCOUNT ")) {
            for kv in l.1.split_whitespace() {
                if let Some((k, v)) = kv.split_once('=') {
                    *totals.entry(k.into()).or_default() += v.parse::<u64>().unwrap_or(0);
                }
            }
        }
    }
    eprintln!(
        "[fuzz_wide] {cases} cases from seed {seed0} in {:.1} s: {} signals, {} hangs, {} failed; {totals:?}",
        t0.elapsed().as_secs_f64(),
        signals.len(),
        hangs.len(),
        failed.len()
    );
    assert!(signals.is_empty(), "cases ended by a signal: {signals:?}");
    assert!(hangs.is_empty(), "cases over {limit:?}: {hangs:?}");
    assert!(failed.is_empty(), "failed checks: {failed:#?}");
    // the cases did what they are for: states were taken and restored in fresh instances
    assert!(
        totals.get("restored_fresh").copied().unwrap_or(0) > 0,
        "no state was restored: {totals:?}"
    );
}
