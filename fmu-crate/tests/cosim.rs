//! The exported FMI functions against the core library: same outputs, step-size independence, FMU states, several instances.

mod common;
use common::*;
use creep_core::{Config, Grid, Inputs, Model};

/// A small grid keeps the debug-build tests fast; the checks do not depend on it.
const NX: i32 = 24;
const NY: i32 = 7;

fn fmu(name: &str) -> Fmu {
    let f = Fmu::new(name);
    assert_eq!(f.set_int("nx", NX), OK);
    assert_eq!(f.set_int("ny", NY), OK);
    f
}

fn core_model() -> Model {
    let mut cfg = Config::preset("table4.1").unwrap();
    cfg.grid = Grid {
        nx: NX as usize,
        ny: NY as usize,
    };
    Model::new(&cfg).unwrap()
}

/// Inputs of step k of a changing-input scenario.
fn scenario(k: usize) -> Inputs {
    let t = k as f64;
    Inputs {
        cx: 0.004 + 0.03 * (0.7 * t).sin().abs(),
        cy: 0.002 * (0.3 * t).cos(),
        spin: 0.1 * (0.2 * t).sin(),
        v: 10.0 + 0.5 * t,
        fn_n: 90e3 + 2e3 * t,
        t_bulk: 20.0,
    }
}

fn set(f: &Fmu, i: &Inputs) {
    f.inputs(i.cx, i.cy, i.spin, i.v, i.fn_n);
}

#[test]
fn outputs_equal_the_core_library_bit_for_bit() {
    let mut f = fmu("same-path");
    let mut m = core_model();
    set(&f, &scenario(0));
    assert_eq!(f.init(), OK);
    let o = m.steady(&scenario(0)).unwrap();
    assert_eq!(
        f.outputs().map(f64::to_bits),
        o.to_array().map(f64::to_bits)
    );
    for k in 1..12 {
        let i = scenario(k);
        set(&f, &i);
        let h = 2e-4 * (1 + k % 3) as f64;
        assert_eq!(f.step(h), OK);
        let o = m.step(h, &i).unwrap();
        assert_eq!(
            f.outputs().map(f64::to_bits),
            o.to_array().map(f64::to_bits),
            "step {k}"
        );
    }
    assert!(f.get("Fx") > 0.0 && f.get("T_max") > 20.0);
}

#[test]
fn communication_step_size_does_not_change_the_forces() {
    let mut one = fmu("step-one");
    let mut ten = fmu("step-ten");
    for f in [&mut one, &mut ten] {
        f.inputs(0.002, 0.0, 0.0, 20.0, 110e3);
        assert_eq!(f.init(), OK);
        // a creepage step: the transient response is under way during the compared interval
        f.inputs(0.02, 0.001, 0.0, 20.0, 110e3);
    }
    for _ in 0..3 {
        assert_eq!(one.step(1e-3), OK);
        for _ in 0..10 {
            assert_eq!(ten.step(1e-4), OK);
        }
        for n in ["Fx", "Fy", "P_fric", "T_max"] {
            let (a, b) = (one.get(n), ten.get(n));
            assert!(
                (a - b).abs() <= 5e-3 * a.abs(),
                "{n}: 1 x 1 ms {a} vs 10 x 0.1 ms {b}"
            );
        }
    }
    assert!((one.time - ten.time).abs() < 1e-12);
}

#[test]
fn get_and_set_state_reproduce_bit_for_bit() {
    let mut f = fmu("state");
    set(&f, &scenario(0));
    assert_eq!(f.init(), OK);
    for k in 1..4 {
        set(&f, &scenario(k));
        assert_eq!(f.step(5e-4), OK);
    }
    let s = f.get_state();
    set(&f, &scenario(7));
    assert_eq!(f.step(1e-3), OK);
    let first = f.outputs();
    assert_eq!(f.step(1e-3), OK);
    let second = f.outputs();
    f.set_state(s);
    set(&f, &scenario(7));
    assert_eq!(f.step(1e-3), OK);
    assert_eq!(f.outputs().map(f64::to_bits), first.map(f64::to_bits));
    assert_eq!(f.step(1e-3), OK);
    assert_eq!(f.outputs().map(f64::to_bits), second.map(f64::to_bits));
    // fmi2GetFMUstate into an existing state overwrites it
    let mut s2 = s;
    assert_eq!(
        unsafe { ecf_contact::ffi::fmi2GetFMUstate(f.c, &mut s2) },
        OK
    );
    assert_eq!(s2, s);
    f.free_state(s);
}

#[test]
fn serialized_state_continues_identically_in_a_fresh_instance() {
    let mut a = fmu("ser-a");
    assert_eq!(a.set_real("mu", 0.31), OK);
    assert_eq!(a.set_string("preset", "dry"), OK);
    set(&a, &scenario(0));
    assert_eq!(a.init(), OK);
    for k in 1..5 {
        set(&a, &scenario(k));
        assert_eq!(a.step(5e-4), OK);
    }
    let s = a.get_state();
    let bytes = a.serialize(s);
    // a fresh instance with default parameters, initialized, then given the state
    let mut b = Fmu::new("ser-b");
    assert_eq!(b.init(), OK);
    let sb = b.deserialize(&bytes).expect("deserialize");
    b.set_state(sb);
    assert_eq!(b.get("mu"), 0.31);
    assert_eq!(b.get_string("preset"), "dry");
    assert_eq!(b.time, a.time);
    for k in 5..10 {
        set(&a, &scenario(k));
        set(&b, &scenario(k));
        assert_eq!(a.step(7e-4), OK);
        assert_eq!(b.step(7e-4), OK);
        assert_eq!(
            a.outputs().map(f64::to_bits),
            b.outputs().map(f64::to_bits),
            "step {k}"
        );
    }
    // serializing the deserialized state gives the same bytes
    assert_eq!(b.serialize(sb), bytes);
    // corrupt or truncated bytes are refused with a message
    let mut bad = bytes.clone();
    bad[0] ^= 0xff;
    assert_eq!(b.deserialize(&bad), Err(ERROR));
    assert_eq!(b.deserialize(&bytes[..bytes.len() - 3]), Err(ERROR));
    let msgs = b.messages();
    assert!(
        msgs.iter()
            .any(|(_, m)| m.contains("fmi2DeSerializeFMUstate") && m.contains("magic")),
        "{msgs:?}"
    );
    assert!(
        msgs.iter().any(|(_, m)| m.contains("truncated")),
        "{msgs:?}"
    );
    a.free_state(s);
    b.free_state(sb);
}

#[test]
fn rollback_and_retry_with_smaller_steps_is_consistent() {
    // master: try 2 ms, reject it, go back, take 2 x 1 ms; reference: 2 x 1 ms directly
    let mut f = fmu("rollback");
    let mut r = fmu("rollback-ref");
    for x in [&mut f, &mut r] {
        set(x, &scenario(0));
        assert_eq!(x.init(), OK);
        set(x, &scenario(3));
        assert_eq!(x.step(1e-3), OK);
        set(x, &scenario(4));
    }
    let s = f.get_state();
    assert_eq!(f.step(2e-3), OK);
    let rejected = f.outputs();
    f.set_state(s);
    assert_eq!(f.time, r.time);
    for _ in 0..2 {
        assert_eq!(f.step(1e-3), OK);
        assert_eq!(r.step(1e-3), OK);
        assert_eq!(f.outputs().map(f64::to_bits), r.outputs().map(f64::to_bits));
    }
    // after the retry, the FMU is at the same time as the rejected step ended
    assert!((f.time - 3e-3).abs() < 1e-15);
    // the rejected step's outputs were a (slightly) different path: not reused by accident
    assert!(rejected.iter().all(|x| x.is_finite()));
    f.free_state(s);
}

#[test]
fn two_instances_do_not_talk_to_each_other() {
    let mut a = fmu("pair-a");
    let mut b = fmu("pair-b");
    let mut solo_a = fmu("solo-a");
    let mut solo_b = fmu("solo-b");
    let ia = |k: usize| scenario(k);
    let ib = |k: usize| Inputs {
        cx: -0.5 * scenario(k).cx,
        fn_n: 60e3,
        v: 30.0,
        ..scenario(k)
    };
    set(&a, &ia(0));
    set(&solo_a, &ia(0));
    set(&b, &ib(0));
    set(&solo_b, &ib(0));
    for x in [&mut a, &mut b, &mut solo_a, &mut solo_b] {
        assert_eq!(x.init(), OK);
    }
    let mut out_a = Vec::new();
    let mut out_b = Vec::new();
    for k in 1..6 {
        set(&a, &ia(k));
        set(&b, &ib(k));
        assert_eq!(a.step(1e-3), OK);
        assert_eq!(b.step(1e-3), OK);
        out_a.push(a.outputs());
        out_b.push(b.outputs());
    }
    for k in 1..6 {
        set(&solo_a, &ia(k));
        assert_eq!(solo_a.step(1e-3), OK);
        assert_eq!(
            solo_a.outputs().map(f64::to_bits),
            out_a[k - 1].map(f64::to_bits)
        );
    }
    for k in 1..6 {
        set(&solo_b, &ib(k));
        assert_eq!(solo_b.step(1e-3), OK);
        assert_eq!(
            solo_b.outputs().map(f64::to_bits),
            out_b[k - 1].map(f64::to_bits)
        );
    }
    assert!(
        out_a[4][0] > 0.0 && out_b[4][0] < 0.0,
        "Fx follows the sign of cx"
    );
}
