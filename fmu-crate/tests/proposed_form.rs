//! The configuration `ecf diagnose --out` proposed for the worked example (examples/measurements/speed-proposed.json, a formula effect in v_mps) runs in the FMU as it stands and gives the model's values (docs/measurements.md, "An effect outside the catalogue: from the first `compare` to the FMU").

mod common;
use common::*;
use creep_core::{Config, Inputs, Model};

#[test]
fn the_proposed_configuration_runs_in_the_fmu() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/measurements/speed-proposed.json"
    );
    let cfg = Config::from_file(std::path::Path::new(path)).unwrap();
    assert!(
        !cfg.modifiers.is_empty(),
        "the proposal has its formula effect"
    );
    let mut last = None;
    for v in [5.0, 25.0] {
        let i = Inputs {
            cx: 0.02,
            v,
            fn_n: 110e3,
            ..Inputs::default()
        };
        let want = Model::new(&cfg).unwrap().steady(&i).unwrap().to_array();
        let mut f = Fmu::new(&format!("proposed-{v}"));
        assert_eq!(f.set_string("config_file", path), OK);
        assert_eq!(f.set_bool("effect_transient", false), OK);
        f.inputs(i.cx, i.cy, i.spin, i.v, i.fn_n);
        assert_eq!(f.init(), OK, "{:?}", f.messages());
        assert_eq!(f.outputs(), want, "v = {v} m/s");
        // the layer weakens with speed: the traction coefficient differs between the speeds
        if let Some(prev) = last {
            assert_ne!(prev, want[0]);
        }
        last = Some(want[0]);
    }
}
