//! Fuzz test: random sequences of legal FMI calls with random values (NaN, ±inf, ±1e300, 0, negative, typical), through the exported C functions.
//!
//! Checked: no signal (a crash fails the test binary), no call over 1 s, every status is
//! OK/Warning/Discard/Error, every output read with OK is finite, and no handle or memory
//! growth (all instances and states freed at the end; resident memory after the run within
//! 64 MiB of that after the first fifth). CI runs `ECF_FUZZ_CALLS` = 4000 calls (a few
//! seconds); a longer run: `ECF_FUZZ_CALLS=200000 ECF_FUZZ_SEED=7 cargo test --release -p
//! ecf-fmu --test fuzz -- --nocapture`. Grids are drawn up to 40 x 20 so that the per-call
//! bound measures the FMU, not the (legal but proportionally slower) 2000 x 1000 grid.

mod common;
use common::{callbacks, ERROR, OK};
use ecf_contact::ffi::*;
use ecf_contact::vars::{Causality, Kind};
use fmi_sys::fmi2 as f;
use std::ffi::CString;
use std::time::{Duration, Instant};

#[path = "fuzz_rng/mod.rs"]
mod fuzz_rng;
use fuzz_rng::Rng;

/// Real values for the setters: NaN, infinities, extremes, zero and ordinary magnitudes.
impl Rng {
    fn real(&mut self) -> f64 {
        match self.below(12) {
            0 => f64::NAN,
            1 => f64::INFINITY,
            2 => f64::NEG_INFINITY,
            3 => 1e300,
            4 => -1e300,
            5 => 0.0,
            6 => -self.unit() * 10f64.powi(self.below(8) as i32 - 3),
            7 => 1e-300,
            _ => self.unit() * 10f64.powi(self.below(8) as i32 - 3),
        }
    }
}

fn rss_kib() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmRSS:"))
                .and_then(|l| l.split_whitespace().nth(1).and_then(|x| x.parse().ok()))
        })
        .unwrap_or(0)
}

#[derive(Clone, Copy, PartialEq, Debug)]
enum Ph {
    Inst,
    Init,
    Step,
    Term,
}

#[test]
fn random_legal_call_sequences_never_crash_hang_or_leak() {
    let calls: usize = std::env::var("ECF_FUZZ_CALLS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(4000);
    let seed: u64 = std::env::var("ECF_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x5EED_ECF1);
    let mut rng = Rng(seed | 1);
    let of = common::vars_of;
    let inputs = of(Kind::Real, &[Causality::Input]);
    let real_params = of(Kind::Real, &[Causality::Parameter]);
    let outputs = of(Kind::Real, &[Causality::Output]);
    let ints = of(Kind::Integer, &[Causality::Parameter]);
    let bools = of(Kind::Boolean, &[Causality::Parameter]);
    let strings = of(Kind::String, &[Causality::Parameter]);
    let string_pool = [
        "",
        "ecf",
        "fastsim",
        "polach",
        "table4.1",
        "dry",
        "wet",
        "dry_sanded",
        "wet_sanded",
        "twin_disc",
        "brush",
        "/dev/zero",
        "/nonexistent.json",
        "presets/wet.json",
        "%s%n",
        "aux1=humidity",
        "humidity=aux1",
        "humidity=30",
    ];
    let cb = callbacks();
    let name = CString::new("fuzz").unwrap();
    let guid = CString::new(ecf_contact::model_description::guid()).unwrap();
    let new = || unsafe {
        fmi2Instantiate(
            name.as_ptr(),
            f::fmi2Type_fmi2CoSimulation,
            guid.as_ptr(),
            std::ptr::null(),
            &*cb,
            0,
            0,
        )
    };
    let mut c = new();
    let mut ph = Ph::Inst;
    let mut t = 0.0f64;
    let mut states: Vec<f::fmi2FMUstate> = Vec::new();
    let mut rss_early = 0;
    let mut worst = (Duration::ZERO, String::new());
    // calls since the last instantiate/reset (printed when a check fails)
    let mut history: Vec<String> = Vec::new();
    for k in 0..calls {
        if k == calls / 5 {
            rss_early = rss_kib();
        }
        let t0 = Instant::now();
        let (what, st): (String, f::fmi2Status) = unsafe {
            match rng.below(16) {
                0 | 1 if ph != Ph::Term => {
                    let v = &inputs[rng.below(inputs.len())];
                    let x = rng.real();
                    (
                        format!("set {} = {x:e}", v.name),
                        fmi2SetReal(c, &v.vr, 1, &x),
                    )
                }
                2 if matches!(ph, Ph::Inst | Ph::Init) => {
                    let v = &real_params[rng.below(real_params.len())];
                    let x = rng.real();
                    (
                        format!("set {} = {x:e}", v.name),
                        fmi2SetReal(c, &v.vr, 1, &x),
                    )
                }
                3 if matches!(ph, Ph::Inst | Ph::Init) => {
                    let v = &ints[rng.below(ints.len())];
                    let x = match v.name.as_str() {
                        "nx" => rng.below(42) as i32 - 1,
                        "ny" => rng.below(22) as i32 - 1,
                        _ => rng.below(5) as i32 - 1,
                    };
                    (
                        format!("set {} = {x}", v.name),
                        fmi2SetInteger(c, &v.vr, 1, &x),
                    )
                }
                4 if matches!(ph, Ph::Inst | Ph::Init) => {
                    let v = &bools[rng.below(bools.len())];
                    let x = rng.below(2) as f::fmi2Boolean;
                    (
                        format!("set {} = {x}", v.name),
                        fmi2SetBoolean(c, &v.vr, 1, &x),
                    )
                }
                5 if matches!(ph, Ph::Inst | Ph::Init) => {
                    let v = &strings[rng.below(strings.len())];
                    let s = string_pool[rng.below(string_pool.len())];
                    let cs = CString::new(s).unwrap();
                    let p = cs.as_ptr();
                    (
                        format!("set {} = '{s}'", v.name),
                        fmi2SetString(c, &v.vr, 1, &p),
                    )
                }
                6 if ph == Ph::Inst => {
                    ph = Ph::Init;
                    t = 0.0;
                    fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0);
                    ("enter init".into(), fmi2EnterInitializationMode(c))
                }
                7 if ph == Ph::Init => {
                    let st = fmi2ExitInitializationMode(c);
                    if st <= f::fmi2Status_fmi2Warning {
                        ph = Ph::Step;
                    }
                    ("exit init".into(), st)
                }
                8..=10 if ph == Ph::Step => {
                    let h = match rng.below(4) {
                        0 => rng.real().abs(),
                        _ => rng.unit() * 2e-3,
                    };
                    let st = fmi2DoStep(c, t, h, 0);
                    if st <= f::fmi2Status_fmi2Warning {
                        t += h;
                    }
                    (format!("doStep(t = {t}, h = {h})"), st)
                }
                11 if ph != Ph::Inst => {
                    let v = &outputs[rng.below(outputs.len())];
                    let mut x = f64::NAN;
                    let st = fmi2GetReal(c, &v.vr, 1, &mut x);
                    assert!(
                        st != OK || x.is_finite(),
                        "call {k}: {} = {x} with OK after {history:#?}",
                        v.name
                    );
                    (format!("get {}", v.name), st)
                }
                12 => {
                    let mut s: f::fmi2FMUstate = std::ptr::null_mut();
                    let st = fmi2GetFMUstate(c, &mut s);
                    if st == OK {
                        if rng.below(2) == 0 {
                            // serialize and read back
                            let mut n = 0usize;
                            assert_eq!(fmi2SerializedFMUstateSize(c, s, &mut n), OK);
                            let mut buf = vec![0u8; n];
                            assert_eq!(
                                fmi2SerializeFMUstate(
                                    c,
                                    s,
                                    buf.as_mut_ptr() as *mut f::fmi2Byte,
                                    n
                                ),
                                OK
                            );
                            let mut s2: f::fmi2FMUstate = std::ptr::null_mut();
                            assert_eq!(
                                fmi2DeSerializeFMUstate(
                                    c,
                                    buf.as_ptr() as *const f::fmi2Byte,
                                    n,
                                    &mut s2
                                ),
                                OK,
                                "call {k}: deserialize own state: {:?}",
                                common::messages("fuzz").last()
                            );
                            states.push(s2);
                        }
                        states.push(s);
                    }
                    ("get state".into(), st)
                }
                13 if !states.is_empty() => {
                    let s = states[rng.below(states.len())];
                    let st = fmi2SetFMUstate(c, s);
                    if st == OK {
                        let mut tt = 0.0;
                        fmi2GetRealStatus(c, f::fmi2StatusKind_fmi2LastSuccessfulTime, &mut tt);
                        t = tt;
                        // the phase after a restore: Step if the state was initialized
                        let mut x = 0.0;
                        let probe = fmi2DoStep(c, t, 0.0, 0);
                        ph = if probe <= f::fmi2Status_fmi2Warning {
                            Ph::Step
                        } else if fmi2GetReal(c, &common::vr("cx"), 1, &mut x) == OK {
                            Ph::Init
                        } else {
                            ph
                        };
                    }
                    ("set state".into(), st)
                }
                14 if !states.is_empty() => {
                    let mut s = states.swap_remove(rng.below(states.len()));
                    ("free state".into(), fmi2FreeFMUstate(c, &mut s))
                }
                15 => match rng.below(3) {
                    0 if ph == Ph::Step => {
                        ph = Ph::Term;
                        ("terminate".into(), fmi2Terminate(c))
                    }
                    1 => {
                        ph = Ph::Inst;
                        ("reset".into(), fmi2Reset(c))
                    }
                    _ => {
                        fmi2FreeInstance(c);
                        states.clear(); // freed with the instance
                        c = new();
                        ph = Ph::Inst;
                        ("free + instantiate".into(), OK)
                    }
                },
                _ => ("no call".into(), OK),
            }
        };
        let dt = t0.elapsed();
        if what == "reset" || what.starts_with("free +") {
            history.clear();
        } else if st != ERROR && !what.starts_with("get ") {
            history.push(format!("{what} -> {st}"));
        }
        assert!(st <= ERROR, "call {k} ({what}): status {st}");
        assert!(
            dt < Duration::from_secs(1),
            "call {k} ({what}) took {dt:?} (seed {seed})"
        );
        if dt > worst.0 {
            worst = (dt, what);
        }
    }
    unsafe {
        for mut s in states.drain(..) {
            assert_eq!(fmi2FreeFMUstate(c, &mut s), OK);
        }
        fmi2FreeInstance(c);
    }
    let rss_end = rss_kib();
    eprintln!(
        "[fuzz] {calls} calls, seed {seed}, slowest {:?} ({}), RSS {rss_early} -> {rss_end} KiB",
        worst.0, worst.1
    );
    let (comps, sts) = live_handles();
    // other tests of this binary may run in parallel; this one is alone in its file
    assert_eq!(
        (comps, sts),
        (0, 0),
        "handles left after freeing everything"
    );
    assert!(
        rss_end < rss_early + 64 * 1024,
        "resident memory grew from {rss_early} to {rss_end} KiB"
    );
}
