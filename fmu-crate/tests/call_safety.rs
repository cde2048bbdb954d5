//! Call safety: a set call with one bad value changes nothing; freed, doubly freed and unknown instance and state handles are refused with a message instead of crashing; deserialized states are checked like inputs; config_file reads only regular files up to 1 MiB.

mod common;
use common::*;
use ecf_contact::ffi::*;
use fmi_sys::fmi2 as f;
use std::ffi::CString;
use std::time::{Duration, Instant};

fn has(fmu: &Fmu, words: &[&str]) -> bool {
    fmu.messages()
        .iter()
        .any(|(l, m)| *l == log::Level::Error && words.iter().all(|w| m.contains(w)))
}

fn ready(name: &str) -> Fmu {
    let mut f = Fmu::new(name);
    assert_eq!(f.set_int("nx", 12), OK);
    assert_eq!(f.set_int("ny", 5), OK);
    f.inputs(0.01, 0.0, 0.0, 20.0, 110e3);
    assert_eq!(f.init(), OK);
    f
}

#[test]
fn a_set_call_with_one_bad_value_applies_none() {
    let mut f = ready("atomic-real");
    // FN is a valid input, mu a fixed parameter after initialization
    let vrs = [vr("FN"), vr("mu")];
    assert_eq!(
        unsafe { fmi2SetReal(f.c, vrs.as_ptr(), 2, [50e3, 0.3].as_ptr()) },
        ERROR
    );
    assert_eq!(f.get("FN"), 110e3, "FN unchanged");
    assert!(has(&f, &["mu", "fixed parameter"]), "{:?}", f.messages());
    assert!(
        has(&f, &["1 of 2 values refused", "none of the 2 values"]),
        "{:?}",
        f.messages()
    );
    // a NaN after a valid creepage
    let vrs = [vr("cx"), vr("cy")];
    assert_eq!(
        unsafe { fmi2SetReal(f.c, vrs.as_ptr(), 2, [0.05, f64::NAN].as_ptr()) },
        ERROR
    );
    assert_eq!(f.get("cx"), 0.01);
    // the instance computes with the old inputs
    let mut g = ready("atomic-real-ref");
    assert_eq!(f.step(1e-3), OK);
    assert_eq!(g.step(1e-3), OK);
    assert_eq!(f.outputs(), g.outputs());

    let f = Fmu::new("atomic-int");
    let vrs = [vr("nx"), vr("ny")];
    assert_eq!(
        unsafe { fmi2SetInteger(f.c, vrs.as_ptr(), 2, [30, -1].as_ptr()) },
        ERROR
    );
    assert!(has(&f, &["ny = -1", "[0, 1000]"]), "{:?}", f.messages());
    assert_eq!(unsafe { fmi2SetupExperiment(f.c, 0, 0.0, 0.0, 0, 0.0) }, OK);
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, OK);
    let mut n = [0i32; 2];
    assert_eq!(
        unsafe { fmi2GetInteger(f.c, vrs.as_ptr(), 2, n.as_mut_ptr()) },
        OK
    );
    let g = default_grid(&creep_core::Config::preset("table4.1").unwrap(), 5.0);
    assert_eq!(
        n,
        [g.nx as i32, g.ny as i32],
        "nx unchanged (the grid the start value of rel_tol chooses at v = 5 m/s)"
    );

    let f = Fmu::new("atomic-bool");
    // the second reference is a Real: the Boolean before it is not applied either
    let vrs = [vr("effect_transient"), vr("cx")];
    assert_eq!(
        unsafe { fmi2SetBoolean(f.c, vrs.as_ptr(), 2, [0, 1].as_ptr()) },
        ERROR
    );
    assert!(has(&f, &["cx", "Real, not Boolean"]), "{:?}", f.messages());

    let f = Fmu::new("atomic-string");
    let a = CString::new("wet").unwrap();
    let b = CString::new("brush").unwrap();
    let vrs = [vr("preset"), vr("model")];
    let ps = [a.as_ptr(), b.as_ptr()];
    assert_eq!(
        unsafe { fmi2SetString(f.c, vrs.as_ptr(), 2, ps.as_ptr()) },
        ERROR
    );
    assert!(has(&f, &["model = 'brush'"]), "{:?}", f.messages());
    assert_eq!(unsafe { fmi2SetupExperiment(f.c, 0, 0.0, 0.0, 0, 0.0) }, OK);
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, OK);
    assert_eq!(f.get_string("preset"), "", "preset unchanged");
}

#[test]
fn freed_and_unknown_state_handles_are_refused() {
    let mut f = ready("states");
    let s = f.get_state();
    let mut copy = s;
    f.free_state(s);
    // freed twice, set after free, serialized after free
    assert_eq!(unsafe { fmi2FreeFMUstate(f.c, &mut copy) }, ERROR);
    assert!(
        has(&f, &["fmi2FreeFMUstate", "not a live FMU state"]),
        "{:?}",
        f.messages()
    );
    assert_eq!(unsafe { fmi2SetFMUstate(f.c, copy) }, ERROR);
    assert!(
        has(&f, &["fmi2SetFMUstate", "not a live FMU state"]),
        "{:?}",
        f.messages()
    );
    let mut n = 0usize;
    assert_eq!(
        unsafe { fmi2SerializedFMUstateSize(f.c, copy, &mut n) },
        ERROR
    );
    // a made-up handle and an instance handle passed as a state
    let fake = 0x1234usize as f::fmi2FMUstate;
    assert_eq!(unsafe { fmi2SetFMUstate(f.c, fake) }, ERROR);
    assert_eq!(
        unsafe { fmi2SetFMUstate(f.c, f.c as f::fmi2FMUstate) },
        ERROR
    );
    let mut slot = fake;
    assert_eq!(
        unsafe { fmi2GetFMUstate(f.c, &mut slot) },
        ERROR,
        "overwrite of an unknown state"
    );
    // the instance still works
    assert_eq!(f.step(1e-3), OK);
    let s2 = f.get_state();
    f.set_state(s2);
    f.free_state(s2);
}

#[test]
fn freed_and_unknown_instances_are_refused() {
    let cb = callbacks();
    let name = CString::new("twice").unwrap();
    let g = CString::new(ecf_contact::model_description::guid()).unwrap();
    let c = unsafe {
        fmi2Instantiate(
            name.as_ptr(),
            f::fmi2Type_fmi2CoSimulation,
            g.as_ptr(),
            std::ptr::null(),
            &*cb,
            0,
            0,
        )
    };
    assert!(!c.is_null());
    let mut s: f::fmi2FMUstate = std::ptr::null_mut();
    assert_eq!(unsafe { fmi2GetFMUstate(c, &mut s) }, OK);
    unsafe { fmi2FreeInstance(c) };
    // freed twice: refused (message on stderr), no abort
    unsafe { fmi2FreeInstance(c) };
    let mut x = 0.0;
    unsafe {
        assert_eq!(fmi2DoStep(c, 0.0, 1e-3, 1), ERROR);
        assert_eq!(fmi2GetReal(c, &vr("cx"), 1, &mut x), ERROR);
        assert_eq!(fmi2SetReal(c, &vr("cx"), 1, &0.1), ERROR);
        assert_eq!(fmi2Reset(c), ERROR);
        fmi2FreeInstance(0x77usize as f::fmi2Component);
    }
    // the state went with its instance: another instance refuses it
    let f = ready("other");
    assert_eq!(unsafe { fmi2SetFMUstate(f.c, s) }, ERROR);
    assert!(has(&f, &["not a live FMU state"]), "{:?}", f.messages());
}

fn patch_f64(bytes: &mut [u8], at: usize, x: f64) {
    bytes[at..at + 8].copy_from_slice(&x.to_le_bytes());
}

#[test]
fn deserialized_states_are_checked_like_inputs() {
    let mut f = ready("badstate");
    assert_eq!(f.step(1e-3), OK);
    let s = f.get_state();
    let good = f.serialize(s);
    f.free_state(s);
    // layout: magic (8), version (4), time (8), inputs cx, cy, spin, v, FN, T_bulk (8 each)
    for (what, at, x) in [
        ("time", 12, f64::NAN),
        ("cx", 20, f64::INFINITY),
        ("v", 20 + 3 * 8, -5000.0), // negative speeds roll backwards; beyond 1000 m/s is invalid
        ("FN", 20 + 4 * 8, f64::NAN),
    ] {
        let mut b = good.clone();
        patch_f64(&mut b, at, x);
        assert_eq!(f.deserialize(&b).err(), Some(ERROR), "{what} = {x}");
        assert!(
            has(&f, &["fmi2DeSerializeFMUstate", "invalid state"]),
            "{what}: {:?}",
            f.messages()
        );
    }
    // the core state inside: every stored bristle value must be finite
    let mut b = good.clone();
    let n = b.len();
    patch_f64(&mut b, n - 8, f64::NAN);
    assert_eq!(f.deserialize(&b).err(), Some(ERROR));
    // the instance is untouched and the good state still restores
    let before = f.outputs();
    let s = f.deserialize(&good).expect("good state");
    f.set_state(s);
    f.free_state(s);
    assert_eq!(f.outputs(), before);
}

#[test]
fn config_file_accepts_only_regular_files_up_to_1_mib() {
    let dir = std::env::temp_dir().join(format!("ecf-cfg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join("fifo.json");
    let _ = std::fs::remove_file(&fifo);
    let ok = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .map(|s| s.success())
        .unwrap_or(false);
    let big = dir.join("big.json");
    // a valid JSON document of 1 MiB + 1 byte (whitespace padding)
    let mut text = String::from("{\"preset\": \"dry\"}");
    text.push_str(&" ".repeat((1 << 20) + 1 - text.len()));
    std::fs::write(&big, &text).unwrap();
    let small = dir.join("small.json");
    std::fs::write(&small, "{\"preset\": \"dry\"}").unwrap();
    let f = Fmu::new("cfgfile");
    let mut cases = vec![
        ("/dev/zero".to_string(), "not a regular file"),
        (dir.display().to_string(), "not a regular file"),
        (big.display().to_string(), "at most 1048576 bytes"),
    ];
    if ok {
        cases.push((fifo.display().to_string(), "not a regular file"));
    }
    for (p, why) in cases {
        let (tx, rx) = std::sync::mpsc::channel();
        let c = f.c as usize;
        let p2 = p.clone();
        // a call that blocked (the FIFO) would fail the test instead of hanging it
        std::thread::spawn(move || {
            let s = CString::new(p2).unwrap();
            let ptr = s.as_ptr();
            let st = unsafe { fmi2SetString(c as f::fmi2Component, &vr("config_file"), 1, &ptr) };
            let _ = tx.send(st);
        });
        let t0 = Instant::now();
        let st = rx
            .recv_timeout(Duration::from_secs(5))
            .unwrap_or_else(|_| panic!("fmi2SetString({p}) blocked"));
        assert_eq!(st, ERROR, "{p}");
        assert!(
            t0.elapsed() < Duration::from_secs(1),
            "{p}: {:?}",
            t0.elapsed()
        );
        assert!(has(&f, &["config_file", why]), "{p}: {:?}", f.messages());
    }
    assert_eq!(
        f.set_string("config_file", &small.display().to_string()),
        OK
    );
    let _ = std::fs::remove_dir_all(&dir);
}
