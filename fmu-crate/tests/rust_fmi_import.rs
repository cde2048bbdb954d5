//! A second, independent importer: the rust-fmi `fmi` crate loads the packed .fmu (dist/ecf_contact.fmu from scripts/build-fmu.sh, or $ECF_FMU_PATH), steps it, and matches the core library.

mod common;
use creep_core::{Config, Grid, Model};
use fmi::fmi2::import::Fmi2Import;
use fmi::fmi2::instance::{CoSimulation, Common};
use fmi::traits::FmiImport;
use std::path::PathBuf;

fn fmu_path() -> PathBuf {
    let p = std::env::var_os("ECF_FMU_PATH")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../dist/ecf_contact.fmu")
        });
    assert!(
        p.is_file(),
        "{} not found: build it first with scripts/build-fmu.sh (or set ECF_FMU_PATH)",
        p.display()
    );
    p
}

fn vr(import: &Fmi2Import, name: &str) -> u32 {
    import
        .model_description()
        .model_variables
        .variables
        .iter()
        .find(|v| v.name == name)
        .unwrap_or_else(|| panic!("no variable {name}"))
        .value_reference
}

#[test]
fn rust_fmi_loads_steps_and_matches_the_core_library() {
    let import: Fmi2Import = fmi::import::from_path(fmu_path()).expect("rust-fmi imports the .fmu");
    let md = import.model_description();
    assert_eq!(
        md.guid,
        ecf_contact::model_description::guid(),
        "the .fmu is stale: rebuild it"
    );
    let names = ["cx", "cy", "spin", "v", "FN", "T_bulk"];
    let vin: Vec<u32> = names.iter().map(|n| vr(&import, n)).collect();
    let outs = common::OUTPUT_NAMES;
    let vout: Vec<u32> = outs.iter().map(|n| vr(&import, n)).collect();

    let mut inst = import
        .instantiate_cs("rust-fmi", false, false)
        .expect("instantiate");
    assert_eq!(inst.get_version(), "2.0");
    assert_eq!(inst.get_types_platform(), "default");
    inst.set_integer(&[vr(&import, "nx"), vr(&import, "ny")], &[20, 7])
        .expect("grid");
    let mut cfg = Config::preset("table4.1").unwrap();
    cfg.grid = Grid { nx: 20, ny: 7 };
    let mut core = Model::new(&cfg).unwrap();

    let (input, arr) = (common::importer_inputs, common::input_values);
    inst.set_real(&vin, &arr(&input(0))).expect("inputs");
    inst.setup_experiment(None, 0.0, None).expect("setup");
    inst.enter_initialization_mode().expect("enter init");
    inst.exit_initialization_mode().expect("exit init");
    core.steady(&input(0)).unwrap();
    let mut t = 0.0;
    let mut got = vec![0.0; vout.len()];
    for k in 1..8 {
        let i = input(k);
        inst.set_real(&vin, &arr(&i)).expect("inputs");
        inst.do_step(t, 1e-3, true).expect("doStep");
        t += 1e-3;
        let o = core.step(1e-3, &i).unwrap();
        inst.get_real(&vout, &mut got).expect("outputs");
        let want = o.to_array();
        for (j, n) in outs.iter().enumerate() {
            assert_eq!(
                got[j].to_bits(),
                want[j].to_bits(),
                "step {k}: {n} = {} vs core {}",
                got[j],
                want[j]
            );
        }
    }
    assert!(got[0] > 0.0, "Fx > 0 for cx > 0");
    assert_eq!(inst.last_successful_time().expect("status"), t);

    // FMU state through rust-fmi: get, step, set, step again: identical
    let s = inst.get_fmu_state().expect("get state");
    inst.do_step(t, 2e-3, true).expect("doStep");
    let mut a = vec![0.0; vout.len()];
    inst.get_real(&vout, &mut a).expect("outputs");
    let bytes = inst.serialize_fmu_state(&s).expect("serialize");
    assert!(
        bytes.len() > 1000,
        "the state holds the bristle grid ({} bytes)",
        bytes.len()
    );
    let _ = inst.set_fmu_state(&s);
    inst.do_step(t, 2e-3, true).expect("doStep");
    let mut b = vec![0.0; vout.len()];
    inst.get_real(&vout, &mut b).expect("outputs");
    assert_eq!(
        a.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
        b.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
    );

    // a second instance of the same import, given the serialized state, continues identically
    let mut other = import
        .instantiate_cs("rust-fmi-2", false, false)
        .expect("instantiate");
    other.setup_experiment(None, 0.0, None).expect("setup");
    other.enter_initialization_mode().expect("enter init");
    other.exit_initialization_mode().expect("exit init");
    let s2 = other.deserialize_fmu_state(&bytes).expect("deserialize");
    let _ = other.set_fmu_state(&s2);
    other.do_step(t, 2e-3, true).expect("doStep");
    let mut c = vec![0.0; vout.len()];
    other.get_real(&vout, &mut c).expect("outputs");
    assert_eq!(
        a.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
        c.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
    );
    inst.terminate().expect("terminate");
    other.terminate().expect("terminate");
}
