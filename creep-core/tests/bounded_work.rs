//! The work of a step is bounded: a step that rolls past the contact is the steady state of its inputs, a vanishing load is lift-off, and the continuous scheme follows the cell-by-cell reference.
mod common;
use common::*;
use creep_core::engine::{Scheme, F_LIFT_OFF};
use creep_core::{Contact, Inputs, Model};

#[test]
fn a_step_longer_than_the_contact_is_the_steady_state_of_its_inputs() {
    for name in ["dry", "fastsim", "table4.1"] {
        let cfg = preset(name);
        let mut m = Model::new(&cfg).unwrap();
        m.steady(&vectron(0.01, 20.0)).unwrap();
        m.step(1e-4, &vectron(0.05, 20.0)).unwrap();
        let i = Inputs {
            cx: 0.2,
            cy: 0.01,
            ..vectron(0.2, 30.0)
        };
        // 1000 s at 30 m/s: 30 km of rolling, 2e6 contact lengths
        let o = m.step(1e3, &i).unwrap();
        let s = steady(&cfg, &i);
        assert_eq!(o, s, "{name}");
    }
}

#[test]
fn a_vanishing_load_is_lift_off_and_a_small_one_is_cheap() {
    let cfg = preset("dry");
    for fn_n in [1e-30, 1e-10, F_LIFT_OFF] {
        let mut m = Model::new(&cfg).unwrap();
        m.steady(&vectron(0.05, 20.0)).unwrap();
        let i = Inputs {
            fn_n,
            ..vectron(0.05, 20.0)
        };
        let o = m.step(1e-3, &i).unwrap();
        assert_eq!((o.fx, o.fy, o.p_fric), (0.0, 0.0, 0.0), "F_N = {fn_n}");
        let o = m.steady(&i).unwrap();
        assert_eq!(o.fx, 0.0, "F_N = {fn_n}");
    }
    // just above lift-off the contact is 4 um long and a 1 ms step rolls 5000 contact lengths:
    // one steady march, with the Coulomb-like saturation of a fully sliding contact
    let mut m = Model::new(&cfg).unwrap();
    let i = Inputs {
        fn_n: 0.01,
        ..vectron(0.05, 20.0)
    };
    m.steady(&vectron(0.0, 20.0)).unwrap();
    let o = m.step(1e-3, &i).unwrap();
    assert!(o.f.is_finite() && o.f > 0.0, "{o:?}");
}

#[test]
fn continuous_scheme_follows_the_cell_by_cell_reference() {
    // varying creepage, speed and load; step lengths from a tenth of a cell to many cells
    for name in ["dry", "table4.1", "fastsim"] {
        let cfg = preset(name);
        let mut cont = Contact::new(&cfg).unwrap();
        let mut cells = Contact::new(&cfg).unwrap();
        cells.set_scheme(Scheme::CellsMarch);
        let i0 = vectron(0.01, 10.0);
        cont.steady(&i0).unwrap();
        cells.steady(&i0).unwrap();
        let mut worst: f64 = 0.0;
        let mut k = 0u32;
        for (dt, v) in [(2e-6, 5.0), (1e-4, 20.0), (2.5e-4, 30.0), (1e-3, 5.0)] {
            for _ in 0..40 {
                k += 1;
                let i = Inputs {
                    cx: 0.02 + 0.1 * (k as f64 * 0.21).sin().abs(),
                    v,
                    fn_n: 100e3 + 10e3 * (k as f64 * 0.1).sin(),
                    ..Inputs::default()
                };
                let a = cont.step(dt, &i).unwrap();
                let b = cells.step(dt, &i).unwrap();
                worst = worst.max((a.f - b.f).abs() / b.f.abs());
            }
        }
        eprintln!("{name}: worst relative difference {worst:.4}");
        assert!(worst < 0.02, "{name}: {worst}");
    }
}
