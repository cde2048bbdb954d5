//! The FMI 3.0 API through its exported functions: the same outputs as the FMI 2.0 API bit for bit, the field arrays (their length n_field, their values the core model's field), configuration mode, states refused across the two APIs by name, and the unsupported entries.

mod common;
use common::{Fmu, OUTPUT_NAMES};
use creep_core::{Config, Grid, Inputs, Model};
use ecf_contact::arrays::{self, ARRAYS, VR_N_FIELD, VR_TIME};
use ecf_contact::ffi::fmi3::*;
use ecf_contact::model_description3::instantiation_token;
use fmi_sys::fmi3 as f3;
use std::ffi::{c_void, CStr, CString};
use std::sync::Mutex;

const OK: f3::fmi3Status = f3::fmi3Status_fmi3OK;
const ERROR: f3::fmi3Status = f3::fmi3Status_fmi3Error;

/// Messages logged, with the instance environment's name.
static LOGGED: Mutex<Vec<(String, f3::fmi3Status, String)>> = Mutex::new(Vec::new());

unsafe extern "C" fn log3(
    env: *mut c_void,
    st: f3::fmi3Status,
    _cat: f3::fmi3String,
    msg: f3::fmi3String,
) {
    // SAFETY: env is the leaked CString of `Fmu3::new`, msg a NUL-terminated string.
    let (name, text) = unsafe {
        (
            CStr::from_ptr(env as *const std::ffi::c_char)
                .to_string_lossy()
                .to_string(),
            CStr::from_ptr(msg).to_string_lossy().to_string(),
        )
    };
    if let Ok(mut v) = LOGGED.lock() {
        v.push((name, st, text));
    }
}

fn logged(name: &str) -> Vec<String> {
    LOGGED
        .lock()
        .map(|v| {
            v.iter()
                .filter(|m| m.0 == name)
                .map(|m| m.2.clone())
                .collect()
        })
        .unwrap_or_default()
}

struct Fmu3 {
    c: f3::fmi3Instance,
    name: String,
    time: f64,
}

impl Fmu3 {
    fn new(name: &str) -> Self {
        let n = CString::new(name).unwrap();
        let env = CString::new(name).unwrap().into_raw() as *mut c_void;
        let t = CString::new(instantiation_token()).unwrap();
        let c = unsafe {
            fmi3InstantiateCoSimulation(
                n.as_ptr(),
                t.as_ptr(),
                std::ptr::null(),
                false,
                false,
                false,
                false,
                std::ptr::null(),
                0,
                env,
                Some(log3),
                None,
            )
        };
        assert!(!c.is_null(), "instantiate {name}");
        Fmu3 {
            c,
            name: name.into(),
            time: 0.0,
        }
    }
    fn set(&self, name: &str, x: f64) -> f3::fmi3Status {
        unsafe { fmi3SetFloat64(self.c, &common::vr(name), 1, &x, 1) }
    }
    fn set_int(&self, name: &str, x: i32) -> f3::fmi3Status {
        unsafe { fmi3SetInt32(self.c, &common::vr(name), 1, &x, 1) }
    }
    fn init(&mut self) {
        unsafe {
            assert_eq!(
                fmi3EnterInitializationMode(self.c, false, 0.0, 0.0, false, 0.0),
                OK
            );
            assert_eq!(fmi3ExitInitializationMode(self.c), OK);
        }
    }
    fn step(&mut self, h: f64) {
        let (mut e, mut t, mut r, mut last) = (true, true, true, f64::NAN);
        let st = unsafe {
            fmi3DoStep(
                self.c, self.time, h, true, &mut e, &mut t, &mut r, &mut last,
            )
        };
        assert_eq!(st, OK);
        self.time += h;
        assert_eq!((e, t, r, last), (false, false, false, self.time));
    }
    fn get(&self, vrs: &[u32], n: usize) -> Result<Vec<f64>, f3::fmi3Status> {
        let mut out = vec![f64::NAN; n];
        let st = unsafe { fmi3GetFloat64(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr(), n) };
        if st == OK {
            Ok(out)
        } else {
            Err(st)
        }
    }
    fn regime(&self, n: usize) -> Vec<i32> {
        let mut out = vec![9; n];
        let vr = ARRAYS[5].vr;
        assert_eq!(
            unsafe { fmi3GetInt32(self.c, &vr, 1, out.as_mut_ptr(), n) },
            OK
        );
        out
    }
    fn serialize(&self) -> Vec<u8> {
        let mut s: f3::fmi3FMUState = std::ptr::null_mut();
        assert_eq!(unsafe { fmi3GetFMUState(self.c, &mut s) }, OK);
        let mut n = 0usize;
        assert_eq!(unsafe { fmi3SerializedFMUStateSize(self.c, s, &mut n) }, OK);
        let mut b = vec![0u8; n];
        assert_eq!(
            unsafe { fmi3SerializeFMUState(self.c, s, b.as_mut_ptr(), n) },
            OK
        );
        assert_eq!(unsafe { fmi3FreeFMUState(self.c, &mut s) }, OK);
        b
    }
}

impl Drop for Fmu3 {
    fn drop(&mut self) {
        unsafe { fmi3FreeInstance(self.c) };
    }
}

fn input(k: usize) -> Inputs {
    Inputs {
        cx: 0.002 + 0.003 * k as f64,
        cy: 0.001 * k as f64,
        spin: 0.1,
        v: 20.0,
        fn_n: 100e3 + 2e3 * k as f64,
        t_bulk: 20.0,
    }
}

fn set_inputs2(f: &Fmu, i: &Inputs) {
    for (n, x) in [
        ("cx", i.cx),
        ("cy", i.cy),
        ("spin", i.spin),
        ("v", i.v),
        ("FN", i.fn_n),
    ] {
        assert_eq!(f.set_real(n, x), common::OK);
    }
}

fn set_inputs3(f: &Fmu3, i: &Inputs) {
    for (n, x) in [
        ("cx", i.cx),
        ("cy", i.cy),
        ("spin", i.spin),
        ("v", i.v),
        ("FN", i.fn_n),
    ] {
        assert_eq!(f.set(n, x), OK);
    }
}

#[test]
fn the_two_apis_give_the_same_outputs_bit_for_bit() {
    for preset in ["table4.1", "wet", "fastsim", "polach"] {
        let mut a = Fmu::new(&format!("two-apis-2-{preset}"));
        let mut b = Fmu3::new(&format!("two-apis-3-{preset}"));
        assert_eq!(a.set_string("preset", preset), common::OK);
        let p = CString::new(preset).unwrap();
        let pp = p.as_ptr();
        assert_eq!(
            unsafe { fmi3SetString(b.c, &common::vr("preset"), 1, &pp, 1) },
            OK
        );
        assert_eq!(a.set_int("nx", 30), common::OK);
        assert_eq!(b.set_int("nx", 30), OK);
        set_inputs2(&a, &input(0));
        set_inputs3(&b, &input(0));
        assert_eq!(a.init(), common::OK);
        b.init();
        let vrs: Vec<u32> = OUTPUT_NAMES.iter().map(|n| common::vr(n)).collect();
        for k in 1..12 {
            set_inputs2(&a, &input(k));
            set_inputs3(&b, &input(k));
            assert_eq!(a.step(5e-4), common::OK);
            b.step(5e-4);
            let x = a.outputs();
            let y = b.get(&vrs, vrs.len()).expect("outputs");
            for (j, n) in OUTPUT_NAMES.iter().enumerate() {
                assert_eq!(
                    x[j].to_bits(),
                    y[j].to_bits(),
                    "{preset} step {k}: {n} {} vs {}",
                    x[j],
                    y[j]
                );
            }
        }
        assert!(a.get("Fx") > 0.0);
        assert_eq!(b.get(&[VR_TIME], 1), Ok(vec![b.time]));
    }
}

#[test]
fn the_arrays_are_the_core_models_field_sampled_at_n_field_points() {
    let mut cfg = Config::preset("table4.1").unwrap();
    cfg.grid = Grid { nx: 24, ny: 5 };
    let mut core = Model::new(&cfg).unwrap();
    for n_field in [arrays::n_field_start(), 25, 7] {
        let mut b = Fmu3::new(&format!("arrays-{n_field}"));
        assert_eq!(unsafe { fmi3EnterConfigurationMode(b.c) }, OK);
        // only the structural parameter in configuration mode
        assert_eq!(b.set_int("nx", 24), ERROR);
        assert_eq!(
            unsafe { fmi3SetUInt64(b.c, &VR_N_FIELD, 1, &n_field, 1) },
            OK
        );
        assert_eq!(unsafe { fmi3ExitConfigurationMode(b.c) }, OK);
        assert_eq!(b.set_int("nx", 24), OK);
        assert_eq!(b.set_int("ny", 5), OK);
        set_inputs3(&b, &input(0));
        b.init();
        core = Model::new(&cfg).unwrap();
        core.steady(&input(0)).unwrap();
        for k in 1..6 {
            set_inputs3(&b, &input(k));
            b.step(1e-3);
            core.step(1e-3, &input(k)).unwrap();
        }
        let n = n_field as usize;
        let vrs: Vec<u32> = ARRAYS[..5].iter().map(|a| a.vr).collect();
        let got = b.get(&vrs, 5 * n).expect("arrays");
        let want = arrays::sample(core.field_y0().as_deref(), core.outputs().a, n);
        for (j, a) in ARRAYS[..5].iter().enumerate() {
            let w = want.real(a.field).expect("Float64");
            let g = &got[j * n..(j + 1) * n];
            assert_eq!(
                g.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                w.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                "{} with n_field = {n}",
                a.name
            );
        }
        assert_eq!(b.regime(n), want.regime);
        // leading edge first, the pressure positive inside
        assert!(
            got[0] > got[n - 1] && got[n + n / 2] > 0.0,
            "{:?}",
            &got[..n]
        );
        // a wrong count is refused with the count it needs
        assert_eq!(b.get(&vrs[..1], n + 1), Err(ERROR));
        assert!(
            logged(&b.name)
                .iter()
                .any(|m| m.contains(&format!("hold {n} values"))),
            "{:?}",
            logged(&b.name)
        );
        // n_field is structural: fixed after initialization
        assert_eq!(unsafe { fmi3SetUInt64(b.c, &VR_N_FIELD, 1, &5, 1) }, ERROR);
        assert_eq!(unsafe { fmi3EnterConfigurationMode(b.c) }, ERROR);
    }
    // a node per point: with n_field = the node count the arrays are the nodes
    let nodes = core.field_y0().unwrap();
    let s = arrays::sample(Some(&nodes), core.outputs().a, nodes.len());
    assert!(s
        .x
        .iter()
        .zip(&nodes)
        .all(|(x, p)| x.to_bits() == p.x.to_bits()));
}

#[test]
fn a_state_of_one_api_is_refused_by_the_other_by_name() {
    let mut a = Fmu::new("cross-state-2");
    let mut b = Fmu3::new("cross-state-3");
    set_inputs2(&a, &input(1));
    set_inputs3(&b, &input(1));
    assert_eq!(a.init(), common::OK);
    b.init();
    assert_eq!(a.step(1e-3), common::OK);
    b.step(1e-3);
    let s2 = a.get_state();
    let bytes2 = a.serialize(s2);
    a.free_state(s2);
    let bytes3 = b.serialize();
    // the same state after the 8 bytes of the FMI 3.0 magic
    assert_eq!(&bytes3[8..], &bytes2[..]);
    assert_eq!(a.deserialize(&bytes3), Err(common::ERROR));
    assert!(
        a.messages()
            .iter()
            .any(|m| m.1.contains("serialized by the FMI 3.0 FMU")),
        "{:?}",
        a.messages()
    );
    let mut s: f3::fmi3FMUState = std::ptr::null_mut();
    assert_eq!(
        unsafe { fmi3DeserializeFMUState(b.c, bytes2.as_ptr(), bytes2.len(), &mut s) },
        ERROR
    );
    assert!(
        logged(&b.name)
            .iter()
            .any(|m| m
                .contains("fmi3DeserializeFMUState: the state was serialized by the FMI 2.0 FMU")),
        "{:?}",
        logged(&b.name)
    );
    // its own state continues in a fresh instance, bit for bit
    let mut c = Fmu3::new("cross-state-3b");
    assert_eq!(
        unsafe { fmi3DeserializeFMUState(c.c, bytes3.as_ptr(), bytes3.len(), &mut s) },
        OK
    );
    assert_eq!(unsafe { fmi3SetFMUState(c.c, s) }, OK);
    assert_eq!(unsafe { fmi3FreeFMUState(c.c, &mut s) }, OK);
    c.time = b.time;
    let vrs: Vec<u32> = OUTPUT_NAMES.iter().map(|n| common::vr(n)).collect();
    b.step(1e-3);
    c.step(1e-3);
    assert_eq!(b.get(&vrs, vrs.len()), c.get(&vrs, vrs.len()));
}

#[test]
fn model_exchange_and_scheduled_execution_are_refused_with_a_message() {
    let env = CString::new("me-se").unwrap().into_raw() as *mut c_void;
    let t = CString::new(instantiation_token()).unwrap();
    let me = unsafe {
        fmi3InstantiateModelExchange(
            c"me".as_ptr(),
            t.as_ptr(),
            std::ptr::null(),
            false,
            false,
            env,
            Some(log3),
        )
    };
    let se = unsafe {
        fmi3InstantiateScheduledExecution(
            c"se".as_ptr(),
            t.as_ptr(),
            std::ptr::null(),
            false,
            false,
            env,
            Some(log3),
            None,
            None,
            None,
        )
    };
    assert!(me.is_null() && se.is_null());
    let m = logged("me-se");
    assert!(
        m.iter()
            .any(|x| x.contains("fmi3InstantiateModelExchange: not supported")),
        "{m:?}"
    );
    assert!(
        m.iter()
            .any(|x| x.contains("fmi3InstantiateScheduledExecution: not supported")),
        "{m:?}"
    );
    let b = Fmu3::new("unsupported");
    assert_eq!(unsafe { fmi3EnterEventMode(b.c) }, ERROR);
    assert_eq!(unsafe { fmi3SetTime(b.c, 0.0) }, ERROR);
    assert_eq!(unsafe { fmi3ActivateModelPartition(b.c, 0, 0.0) }, ERROR);
    let m = logged("unsupported");
    assert!(
        m.iter()
            .any(|x| x.starts_with("fmi3EnterEventMode: not supported")),
        "{m:?}"
    );
    // a wrong token is refused
    let bad = unsafe {
        fmi3InstantiateCoSimulation(
            c"x".as_ptr(),
            c"{0}".as_ptr(),
            std::ptr::null(),
            false,
            false,
            false,
            false,
            std::ptr::null(),
            0,
            env,
            Some(log3),
            None,
        )
    };
    assert!(bad.is_null());
    // the instance's messages name FMI 3.0 functions
    let x = f64::NAN;
    assert_eq!(
        unsafe { fmi3SetFloat64(b.c, &common::vr("v"), 1, &x, 1) },
        ERROR
    );
    let m = logged("unsupported");
    assert!(
        m.iter()
            .any(|x| x.starts_with("fmi3SetFloat64: v = NaN rejected")),
        "{m:?}"
    );
    assert!(m.iter().all(|x| !x.contains("fmi2")), "{m:?}");
}

#[test]
fn every_function_of_the_standard_is_exported_once() {
    let mut names = EXPORTED.to_vec();
    assert_eq!(names.len(), 75);
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), 75);
    assert!(names.iter().all(|n| n.starts_with("fmi3")));
    assert_eq!(
        unsafe { CStr::from_ptr(fmi3GetVersion()) }.to_str(),
        Ok("3.0")
    );
}
