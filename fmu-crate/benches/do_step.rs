//! Cost of one fmi2DoStep (1 ms, transient ECF under cells-ho, the grid rel_tol's start value chooses) through the exported C API, next to creep-core's Model::step on the same grid in the same run (outputs bit-identical); prints µs per step and the real-time factor.

use creep_core::{Config, Inputs, Model};
use ecf_contact::ffi::*;
use fmi_sys::fmi2 as f;
use std::ffi::CString;
use std::time::Instant;

fn vr(name: &str) -> u32 {
    ecf_contact::vars::table()
        .iter()
        .find(|v| v.name == name)
        .map(|v| v.vr)
        .unwrap_or(u32::MAX)
}

fn main() {
    let h = 1e-3;
    let n: usize = std::env::var("ECF_BENCH_STEPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100);
    for v in [5.0, 20.0] {
        let name = CString::new("bench").unwrap_or_default();
        let guid = CString::new(ecf_contact::model_description::guid()).unwrap_or_default();
        let cx = |k: usize| 0.02 + 0.01 * (k as f64 / 5.0).sin();
        // FMU
        let c = unsafe {
            fmi2Instantiate(
                name.as_ptr(),
                f::fmi2Type_fmi2CoSimulation,
                guid.as_ptr(),
                std::ptr::null(),
                std::ptr::null(),
                0,
                0,
            )
        };
        assert!(!c.is_null());
        let vin = [vr("cx"), vr("v"), vr("FN")];
        unsafe {
            fmi2SetReal(c, vin.as_ptr(), 3, [cx(0), v, 110e3].as_ptr());
            // ECF's default scheme (cells-ho), explicitly: rel_tol then chooses the grid
            // among its rows, and the core model below runs the same grid and scheme
            fmi2SetInteger(c, &vr("scheme"), 1, &2);
            fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0);
            fmi2EnterInitializationMode(c);
            assert_eq!(fmi2ExitInitializationMode(c), f::fmi2Status_fmi2OK);
        }
        let mut grid = [0, 0];
        unsafe { fmi2GetInteger(c, [vr("nx"), vr("ny")].as_ptr(), 2, grid.as_mut_ptr()) };
        let mut t = 0.0;
        let mut fx = 0.0;
        let start = Instant::now();
        for k in 0..n {
            unsafe {
                fmi2SetReal(c, &vin[0], 1, &cx(k));
                assert_eq!(fmi2DoStep(c, t, h, 1), f::fmi2Status_fmi2OK);
                fmi2GetReal(c, &vr("Fx"), 1, &mut fx);
            }
            t += h;
        }
        let fmu = start.elapsed().as_secs_f64() / n as f64;
        unsafe { fmi2FreeInstance(c) };
        // core library directly, on the grid the FMU chose (rel_tol's default)
        let mut cfg = Config::preset("table4.1").expect("preset");
        cfg.grid.nx = grid[0] as usize;
        cfg.grid.ny = grid[1] as usize;
        let mut m = Model::new(&cfg).expect("model");
        let inp = |k: usize| Inputs {
            cx: cx(k),
            v,
            fn_n: 110e3,
            ..Inputs::default()
        };
        m.steady(&inp(0)).expect("steady");
        let start = Instant::now();
        let mut fx_core = 0.0;
        for k in 0..n {
            fx_core = m.step(h, &inp(k)).expect("step").fx;
        }
        let core = start.elapsed().as_secs_f64() / n as f64;
        assert_eq!(fx.to_bits(), fx_core.to_bits());
        println!(
            "doStep(1 ms), transient ECF, grid {}x{}, v = {v} m/s: FMU {:.0} us (real-time factor {:.2}), creep-core Model::step {:.0} us, FMU overhead {:+.1} %",
            grid[0],
            grid[1],
            fmu * 1e6,
            h / fmu,
            core * 1e6,
            100.0 * (fmu - core) / core
        );
    }
}
