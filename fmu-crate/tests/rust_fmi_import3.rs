//! A second, independent importer of the FMI 3.0 FMU: the rust-fmi `fmi` crate loads the packed dist/ecf_contact_fmi3.fmu (or $ECF_FMU3_PATH), configures n_field, steps it, and matches the core library, outputs and field arrays bit for bit.
//!
//! rust-fmi 0.8 reads modelDescription.xml with fmi-schema 0.8, which refuses two attributes
//! of the standard's schema (see `common::for_fmi_schema`): the test imports the packed FMU with
//! that one file rewritten, in memory, and the binaries, resources and everything else as
//! packed. rust-fmi 0.8 has no FMU state functions for FMI 3.0 (they are compiled out), so
//! states are tested through fmpy and the C driver.

mod common;
use creep_core::{Config, Grid, Inputs, Model};
use ecf_contact::arrays::{self, ARRAYS};
use fmi::fmi3::import::Fmi3Import;
use fmi::fmi3::Fmi3Model;
use fmi::fmi3::{CoSimulation, Common, GetSet};
use fmi::traits::FmiImport;
use std::io::{Cursor, Read, Write};
use std::path::PathBuf;

fn fmu_path() -> PathBuf {
    let p = std::env::var_os("ECF_FMU3_PATH")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../dist/ecf_contact_fmi3.fmu")
        });
    assert!(
        p.is_file(),
        "{} not found: build it first with scripts/build-fmu.sh (or set ECF_FMU3_PATH)",
        p.display()
    );
    p
}

/// The packed FMU with its modelDescription.xml as fmi-schema 0.8 reads it.
fn readable_fmu() -> Vec<u8> {
    let file = std::fs::File::open(fmu_path()).expect("open the .fmu");
    let mut zin = zip::ZipArchive::new(file).expect("a zip archive");
    let mut out = zip::ZipWriter::new(Cursor::new(Vec::new()));
    for i in 0..zin.len() {
        let mut e = zin.by_index(i).expect("entry");
        let name = e.name().to_string();
        let mut data = Vec::new();
        e.read_to_end(&mut data).expect("read entry");
        if name == "modelDescription.xml" {
            let xml = String::from_utf8(data).expect("UTF-8");
            data = common::for_fmi_schema(&xml).into_bytes();
        }
        out.start_file(name, zip::write::SimpleFileOptions::default())
            .expect("entry");
        out.write_all(&data).expect("write entry");
    }
    out.finish().expect("zip").into_inner()
}

fn vr(import: &Fmi3Import, name: &str) -> u32 {
    import
        .model_description()
        .model_variables
        .iter_abstract()
        .find(|v| v.name() == name)
        .unwrap_or_else(|| panic!("no variable {name}"))
        .value_reference()
}

#[test]
fn rust_fmi_loads_the_fmi3_fmu_steps_and_matches_the_core_library() {
    let import: Fmi3Import =
        fmi::import::new(Cursor::new(readable_fmu())).expect("rust-fmi imports the .fmu");
    assert_eq!(
        import.model_description().instantiation_token,
        ecf_contact::model_description3::instantiation_token(),
        "the .fmu is stale: rebuild it"
    );
    let names = ["cx", "cy", "spin", "v", "FN", "T_bulk"];
    let vin: Vec<u32> = names.iter().map(|n| vr(&import, n)).collect();
    let vout: Vec<u32> = common::OUTPUT_NAMES
        .iter()
        .map(|n| vr(&import, n))
        .collect();
    let mut inst = import
        .instantiate_cs("rust-fmi-3", false, false, false, false, &[])
        .expect("instantiate");
    assert_eq!(inst.get_version(), "3.0");
    let n = 21usize;
    inst.enter_configuration_mode().expect("configuration mode");
    inst.set_uint64(&[vr(&import, "n_field")], &[n as u64])
        .expect("n_field");
    inst.exit_configuration_mode()
        .expect("exit configuration mode");
    inst.set_int32(&[vr(&import, "nx"), vr(&import, "ny")], &[20, 7])
        .expect("grid");
    let mut cfg = Config::preset("table4.1").unwrap();
    cfg.grid = Grid { nx: 20, ny: 7 };
    let mut core = Model::new(&cfg).unwrap();
    let input = |k: usize| Inputs {
        cx: 0.003 + 0.004 * k as f64,
        cy: 0.0,
        spin: 0.05 * k as f64,
        v: 15.0,
        fn_n: 100e3 + 1e3 * k as f64,
        t_bulk: 25.0,
    };
    let arr = |i: &Inputs| [i.cx, i.cy, i.spin, i.v, i.fn_n, i.t_bulk];
    inst.set_float64(&vin, &arr(&input(0))).expect("inputs");
    inst.enter_initialization_mode(None, 0.0, None)
        .expect("enter init");
    inst.exit_initialization_mode().expect("exit init");
    core.steady(&input(0)).unwrap();
    let (mut t, mut got) = (0.0, vec![0.0; vout.len()]);
    for k in 1..8 {
        let i = input(k);
        inst.set_float64(&vin, &arr(&i)).expect("inputs");
        let (mut event, mut terminate, mut early, mut last) = (true, true, true, f64::NAN);
        inst.do_step(
            t,
            1e-3,
            true,
            &mut event,
            &mut terminate,
            &mut early,
            &mut last,
        )
        .expect("doStep");
        t += 1e-3;
        assert_eq!((event, terminate, early, last), (false, false, false, t));
        let o = core.step(1e-3, &i).unwrap();
        inst.get_float64(&vout, &mut got).expect("outputs");
        let want = o.to_array();
        for (j, name) in common::OUTPUT_NAMES.iter().enumerate() {
            assert_eq!(got[j].to_bits(), want[j].to_bits(), "step {k}: {name}");
        }
    }
    assert!(got[0] > 0.0, "Fx > 0 for cx > 0");
    // the field arrays, n_field values each, equal the core model's field sampled
    let want = arrays::sample(core.field_y0().as_deref(), core.outputs().a, n);
    for a in &ARRAYS[..5] {
        let mut v = vec![0.0; n];
        inst.get_float64(&[a.vr], &mut v).expect("array");
        let w = want.real(a.field).expect("Float64");
        assert_eq!(
            v.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            w.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            "{}",
            a.name
        );
    }
    let mut r = vec![9; n];
    inst.get_int32(&[ARRAYS[5].vr], &mut r).expect("regime");
    assert_eq!(r, want.regime);
    // a buffer of the wrong size is refused
    let mut short = vec![0.0; n - 1];
    assert!(inst.get_float64(&[ARRAYS[0].vr], &mut short).is_err());
    inst.terminate().expect("terminate");
}
