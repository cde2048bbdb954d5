//! Test helpers: an FMU instance driven through the exported C functions, with the importer's logger routed to the `log` crate and captured per instance name.
#![allow(dead_code, clippy::missing_safety_doc)]

pub use creep_core::engine::io::N_OUTPUTS;
use ecf_contact::ffi::*;
use ecf_contact::model_description::guid;
use fmi_sys::fmi2 as f;
use std::ffi::{CStr, CString};
use std::sync::{Mutex, Once};

pub const OK: f::fmi2Status = f::fmi2Status_fmi2OK;
pub const WARNING: f::fmi2Status = f::fmi2Status_fmi2Warning;
pub const DISCARD: f::fmi2Status = f::fmi2Status_fmi2Discard;
pub const ERROR: f::fmi2Status = f::fmi2Status_fmi2Error;

/// Log records captured: (instance name, level, message).
static RECORDS: Mutex<Vec<(String, log::Level, String)>> = Mutex::new(Vec::new());
struct Capture;
impl log::Log for Capture {
    fn enabled(&self, _: &log::Metadata) -> bool {
        true
    }
    fn log(&self, r: &log::Record) {
        if let Ok(mut v) = RECORDS.lock() {
            v.push((r.target().to_string(), r.level(), r.args().to_string()));
        }
    }
    fn flush(&self) {}
}
static CAPTURE: Capture = Capture;
static INIT: Once = Once::new();

/// Messages the FMU logged for an instance name (through fmi-sys's C logger, which
/// formats them printf-style, as importers do).
pub fn messages(name: &str) -> Vec<(log::Level, String)> {
    RECORDS
        .lock()
        .map(|v| {
            v.iter()
                .filter(|r| r.0 == name)
                .map(|r| (r.1, r.2.clone()))
                .collect()
        })
        .unwrap_or_default()
}

/// The FMU's 13 outputs in the order of creep-core's `OUTPUTS` (and of
/// `Outputs::to_array`), unchanged since FMU state format version 2, whose fixture
/// (`state_format.rs`) records them in this order; a new output would go after them.
pub const OUTPUT_NAMES: [&str; 13] = [
    "Fx",
    "Fy",
    "Mz",
    "f",
    "T_max",
    "T_mean",
    "P_fric",
    "frac_elastic",
    "frac_plastic",
    "frac_sliding",
    "a",
    "b",
    "p0",
];

/// The variables of `kind` with one of the `causalities`, in the table's order.
pub fn vars_of(
    kind: ecf_contact::vars::Kind,
    causalities: &[ecf_contact::vars::Causality],
) -> Vec<ecf_contact::vars::Var> {
    ecf_contact::vars::table()
        .iter()
        .filter(|v| v.kind == kind && causalities.contains(&v.causality))
        .cloned()
        .collect()
}

/// The value reference of a variable by name (panics naming an unknown one).
pub fn vr(name: &str) -> u32 {
    ecf_contact::vars::table()
        .iter()
        .find(|v| v.name == name)
        .unwrap_or_else(|| panic!("no variable {name}"))
        .vr
}

pub fn callbacks() -> Box<f::fmi2CallbackFunctions> {
    INIT.call_once(|| {
        let _ = log::set_logger(&CAPTURE);
        log::set_max_level(log::LevelFilter::Trace);
    });
    Box::new(f::fmi2CallbackFunctions {
        logger: Some(fmi_sys::fmi2::logger::callback_logger_handler),
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: std::ptr::null_mut(),
    })
}

/// One instance driven through the C API.
pub struct Fmu {
    pub c: f::fmi2Component,
    pub name: String,
    _cb: Box<f::fmi2CallbackFunctions>,
    pub time: f64,
}

impl Fmu {
    pub fn new(name: &str) -> Self {
        Self::with_resources(name, None)
    }

    pub fn with_resources(name: &str, resources: Option<&str>) -> Self {
        let cb = callbacks();
        let n = CString::new(name).unwrap();
        let g = CString::new(guid()).unwrap();
        let r = resources.map(|r| CString::new(r).unwrap());
        let c = unsafe {
            fmi2Instantiate(
                n.as_ptr(),
                f::fmi2Type_fmi2CoSimulation,
                g.as_ptr(),
                r.as_ref().map(|r| r.as_ptr()).unwrap_or(std::ptr::null()),
                &*cb,
                0,
                0,
            )
        };
        assert!(!c.is_null(), "instantiate {name}");
        Fmu {
            c,
            name: name.into(),
            _cb: cb,
            time: 0.0,
        }
    }

    pub fn set_real(&self, name: &str, x: f64) -> f::fmi2Status {
        unsafe { fmi2SetReal(self.c, &vr(name), 1, &x) }
    }
    pub fn set_int(&self, name: &str, x: i32) -> f::fmi2Status {
        unsafe { fmi2SetInteger(self.c, &vr(name), 1, &x) }
    }
    pub fn set_bool(&self, name: &str, x: bool) -> f::fmi2Status {
        let b = x as f::fmi2Boolean;
        unsafe { fmi2SetBoolean(self.c, &vr(name), 1, &b) }
    }
    pub fn set_string(&self, name: &str, x: &str) -> f::fmi2Status {
        let s = CString::new(x).unwrap();
        let p = s.as_ptr();
        unsafe { fmi2SetString(self.c, &vr(name), 1, &p) }
    }
    pub fn get_string(&self, name: &str) -> String {
        let mut p: f::fmi2String = std::ptr::null();
        assert_eq!(unsafe { fmi2GetString(self.c, &vr(name), 1, &mut p) }, OK);
        unsafe { CStr::from_ptr(p) }.to_str().unwrap().to_string()
    }
    pub fn get(&self, name: &str) -> f64 {
        let mut x = f64::NAN;
        let st = unsafe { fmi2GetReal(self.c, &vr(name), 1, &mut x) };
        assert_eq!(st, OK, "get {name}");
        x
    }
    pub fn init(&mut self) -> f::fmi2Status {
        unsafe {
            assert_eq!(fmi2SetupExperiment(self.c, 0, 0.0, 0.0, 0, 0.0), OK);
            assert_eq!(fmi2EnterInitializationMode(self.c), OK);
            fmi2ExitInitializationMode(self.c)
        }
    }
    pub fn step(&mut self, h: f64) -> f::fmi2Status {
        let st = unsafe { fmi2DoStep(self.c, self.time, h, 1) };
        if st <= WARNING {
            self.time += h;
        }
        st
    }
    pub fn inputs(&self, cx: f64, cy: f64, spin: f64, v: f64, fn_n: f64) {
        for (n, x) in [
            ("cx", cx),
            ("cy", cy),
            ("spin", spin),
            ("v", v),
            ("FN", fn_n),
        ] {
            assert!(self.set_real(n, x) <= WARNING, "set {n} = {x}");
        }
    }
    /// All outputs, in the order of creep-core's `OUTPUTS`.
    pub fn outputs(&self) -> [f64; N_OUTPUTS] {
        std::array::from_fn(|k| self.get(creep_core::OUTPUTS[k].name))
    }
    pub fn get_state(&self) -> f::fmi2FMUstate {
        let mut s: f::fmi2FMUstate = std::ptr::null_mut();
        assert_eq!(unsafe { fmi2GetFMUstate(self.c, &mut s) }, OK);
        s
    }
    pub fn set_state(&mut self, s: f::fmi2FMUstate) {
        assert_eq!(unsafe { fmi2SetFMUstate(self.c, s) }, OK);
        let mut t = 0.0;
        assert_eq!(
            unsafe { fmi2GetRealStatus(self.c, f::fmi2StatusKind_fmi2LastSuccessfulTime, &mut t) },
            OK
        );
        self.time = t;
    }
    pub fn free_state(&self, mut s: f::fmi2FMUstate) {
        assert_eq!(unsafe { fmi2FreeFMUstate(self.c, &mut s) }, OK);
        assert!(s.is_null());
    }
    pub fn serialize(&self, s: f::fmi2FMUstate) -> Vec<u8> {
        let mut n = 0usize;
        assert_eq!(unsafe { fmi2SerializedFMUstateSize(self.c, s, &mut n) }, OK);
        let mut buf = vec![0u8; n];
        assert_eq!(
            unsafe { fmi2SerializeFMUstate(self.c, s, buf.as_mut_ptr() as *mut f::fmi2Byte, n) },
            OK
        );
        buf
    }
    pub fn deserialize(&self, b: &[u8]) -> Result<f::fmi2FMUstate, f::fmi2Status> {
        let mut s: f::fmi2FMUstate = std::ptr::null_mut();
        let st = unsafe {
            fmi2DeSerializeFMUstate(self.c, b.as_ptr() as *const f::fmi2Byte, b.len(), &mut s)
        };
        if st == OK {
            Ok(s)
        } else {
            Err(st)
        }
    }
    pub fn messages(&self) -> Vec<(log::Level, String)> {
        messages(&self.name)
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        unsafe { fmi2FreeInstance(self.c) };
    }
}

/// The grid the FMU runs `cfg` on when neither nx, ny nor the configuration file set it: the
/// one the start value of `rel_tol` chooses at speed `v` (m/s) for the ECF model (from the
/// preset's own rows when `cfg` is a tabulated preset unchanged), else the configuration's.
#[allow(dead_code)]
pub fn default_grid(cfg: &creep_core::Config, v: f64) -> creep_core::config::Grid {
    use creep_core::tolerance::{choose, scope_of, Filter};
    if cfg.model != creep_core::ModelKind::Ecf {
        return cfg.grid;
    }
    let f = Filter {
        preset: scope_of(cfg),
        ..Filter::default()
    };
    let c = choose(ecf_contact::settings::DEFAULT_REL_TOL, v, None, f).expect("choice");
    creep_core::config::Grid { nx: c.nx, ny: c.ny }
}

/// The scheme the start value of `rel_tol` chooses with [`default_grid`] (the engine's
/// default for any other model).
#[allow(dead_code)]
pub fn default_scheme(cfg: &creep_core::Config, v: f64) -> creep_core::engine::Scheme {
    use creep_core::tolerance::{choose, scope_of, Filter};
    if cfg.model != creep_core::ModelKind::Ecf {
        return creep_core::engine::Scheme::CellsMarch;
    }
    let f = Filter {
        preset: scope_of(cfg),
        ..Filter::default()
    };
    choose(ecf_contact::settings::DEFAULT_REL_TOL, v, None, f)
        .expect("choice")
        .scheme
}

/// The XML as fmi-schema 0.8 reads it (the file itself follows the standard's schema): its
/// FMI 3.0 BaseUnit takes the exponents of kelvin and ampere as `k` and `a`, where
/// fmi3Unit.xsd (and fmpy) name them `K` and `A`, and its Float64 variables refuse the
/// attribute `unit` of fmi3RealBaseAttributes. The units are checked on the text.
pub fn for_fmi_schema(xml: &str) -> String {
    let mut out = String::with_capacity(xml.len());
    for line in xml.replace(" K=\"", " k=\"").lines() {
        let l = match (
            line.trim_start().starts_with("<Float64 "),
            line.find(" unit=\""),
        ) {
            (true, Some(a)) => {
                let b = a + 7 + line[a + 7..].find('"').unwrap_or(0) + 1;
                format!("{}{}", &line[..a], &line[b..])
            }
            _ => line.to_string(),
        };
        out.push_str(&l);
        out.push('\n');
    }
    out
}
