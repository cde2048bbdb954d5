//! Versioned, explicit byte format of a model's complete hidden state (bristle grid, heat histories) for save/restore.
//!
//! Layout (little endian, version 3): magic `ECFSTATE`, format version u32, config JSON (u32
//! length + UTF-8), time f64, inputs and then outputs each as u32 count + per value its name
//! (u32 length + UTF-8, the name of [`INPUTS`] or [`OUTPUTS`]) and f64, flags u8 (bit 0:
//! initialized, bit 1: rolling backwards; for a contact rolling backwards inputs, outputs
//! and bristles are those of its mirrored frame), then for bristle models: nx u32, ny u32,
//! kernel size u32, heads ny x u32, phases ny x f64, per bristle u(2) tau(2) sh temp q as
//! 7 x f64 and regime u8, then the heat accumulators n x K x f64; from version 4 on, the
//! bristles' committed states at their last lattice node in the same two layouts, then per
//! strip the part of the current cell travelled since: distance (m), time (s) and the
//! distance-weighted c_x, c_y (m) and spin (-) as 5 x f64 (the whole-cell commit,
//! docs/model.md section 3).
//!
//! Values are stored by name, so a build with another input or output reads the state: a
//! value the state lacks keeps its default, a name this build does not know is refused. The
//! configuration is compared as text; a state saved before a parameter existed holds no
//! value for it and loads if this build's value is the parameter's default.
//! Versions 1 and 2 (read, not written) stored 6 inputs and 13 outputs without names: those
//! with value references 1 to 6 and 10 to 22, in that order (version 1 had only flag bit 0).
//! Restoring checks the magic, the version, the configuration and every size, so a state
//! from another configuration or a corrupt buffer is refused with a message, never misread.

use crate::bristle::{BristleState, Regime};
use crate::bytes::{Reader, Writer};
use crate::engine::io::{INPUTS, OUTPUTS};
use crate::engine::{Inputs, Outputs, OwnedRawState, Partial};
use crate::error::{CreepError, Result};
use crate::model::Model;
use crate::params::{self, Params};
use crate::thermal::N_KERNEL;
use serde_json::Value;

const MAGIC: &[u8; 8] = b"ECFSTATE";
/// Current version of the byte format.
pub const VERSION: u32 = 4;

type W = Writer;

/// The shared reader with the model's error type.
struct R<'a>(Reader<'a>);
impl R<'_> {
    fn f(&mut self) -> Result<f64> {
        self.0.f64().map_err(CreepError::State)
    }
    fn u(&mut self) -> Result<u32> {
        self.0.u32().map_err(CreepError::State)
    }
    fn b(&mut self) -> Result<u8> {
        self.0.u8().map_err(CreepError::State)
    }
    fn s(&mut self) -> Result<String> {
        self.0.str().map_err(CreepError::State)
    }
    fn take(&mut self, n: usize) -> Result<&[u8]> {
        self.0.take(n).map_err(CreepError::State)
    }
}

fn put_inputs(w: &mut W, i: &Inputs) {
    w.u32(INPUTS.len() as u32);
    for s in INPUTS {
        w.str(s.name);
        w.f64((s.get)(i));
    }
}
fn put_outputs(w: &mut W, o: &Outputs) {
    w.u32(OUTPUTS.len() as u32);
    for s in OUTPUTS {
        w.str(s.name);
        w.f64((s.get)(o));
    }
}

/// Reads values stored by name (version 3 on) or, in versions 1 and 2, `legacy` values
/// without names in the fixed order of the value references `vrs`. `set(name, value)` is
/// false for a name this build does not know (`what`: "an input"), which is refused, as is a
/// name stored twice.
fn get_named(
    r: &mut R,
    version: u32,
    legacy: &[(&'static str, u32)],
    what: &str,
    mut set: impl FnMut(&str, f64) -> bool,
) -> Result<()> {
    if version < 3 {
        for (name, _) in legacy {
            let x = r.f()?;
            if !set(name, x) {
                return Err(CreepError::State(format!(
                    "this build has no {what} '{name}'"
                )));
            }
        }
        return Ok(());
    }
    let n = r.u()?;
    let mut seen = std::collections::HashSet::new();
    for _ in 0..n {
        let name = r.s()?;
        let x = r.f()?;
        // a name stored twice is a corrupted state, not "the last one wins"
        if !seen.insert(name.clone()) {
            return Err(CreepError::State(format!(
                "the state has {what} '{name}' twice"
            )));
        }
        if !set(&name, x) {
            return Err(CreepError::State(format!(
                "the state has {what} '{name}' that this build does not know"
            )));
        }
    }
    Ok(())
}

/// Names of the values with value references in `vrs` in ascending order: the layout of
/// versions 1 and 2 (released value references never change).
fn legacy_order(
    specs: impl Iterator<Item = (&'static str, u32)>,
    vrs: std::ops::RangeInclusive<u32>,
) -> Vec<(&'static str, u32)> {
    let mut v: Vec<_> = specs.filter(|(_, vr)| vrs.contains(vr)).collect();
    v.sort_by_key(|(_, vr)| *vr);
    v
}

fn get_inputs(r: &mut R, version: u32) -> Result<Inputs> {
    let mut i = Inputs::default();
    let legacy = legacy_order(INPUTS.iter().map(|s| (s.name, s.vr)), 1..=6);
    get_named(r, version, &legacy, "an input", |name, x| {
        match INPUTS.iter().find(|s| s.name == name) {
            Some(s) => {
                (s.set)(&mut i, x);
                true
            }
            None => false,
        }
    })?;
    Ok(i)
}
fn get_outputs(r: &mut R, version: u32) -> Result<Outputs> {
    let mut o = Outputs::default();
    let legacy = legacy_order(OUTPUTS.iter().map(|s| (s.name, s.vr)), 10..=22);
    get_named(r, version, &legacy, "an output", |name, x| {
        match OUTPUTS.iter().find(|s| s.name == name) {
            Some(s) => {
                (s.set)(&mut o, x);
                true
            }
            None => false,
        }
    })?;
    Ok(o)
}

/// True if the configuration `saved` (JSON text of a state) is `now`'s: equal as text, or
/// equal but for the `scheme`, or saved before some parameters (or the scheme) existed, which
/// hold their defaults in `now`. A parameter of
/// `saved` that this build does not know is refused with its name.
fn same_config(saved: &str, now: &str) -> Result<bool> {
    // compared as text: serde_json's default number parser may differ from the printed
    // value in the last bit, so a parsed document can differ from an equal configuration
    if saved == now {
        return Ok(true);
    }
    let (Ok(mut a), Ok(mut b)) = (
        serde_json::from_str::<Value>(saved),
        serde_json::from_str::<Value>(now),
    ) else {
        return Ok(false);
    };
    // the scheme and the temperature solve say how to compute, not what: a state loads into
    // a model of another scheme or solve (and states saved before the configuration had one
    // have none)
    for c in [&mut a, &mut b] {
        if let Some(o) = c.as_object_mut() {
            o.remove("scheme");
            o.remove("temperature_solve");
        }
    }
    let Some(ps) = a.get_mut("params").and_then(Value::as_object_mut) else {
        return Ok(false);
    };
    if let Some(k) = ps.keys().find(|k| params::by_name(k).is_none()) {
        return Err(CreepError::State(format!(
            "the state's configuration has the parameter '{k}' that this build does not know"
        )));
    }
    // a parameter the state lacks: its default, printed and parsed as `now` was
    let defaults = Params::default();
    for s in params::SPECS {
        if !ps.contains_key(s.name) {
            let d = defaults.get(s.id);
            let text = if d.is_infinite() {
                format!("\"{}inf\"", if d < 0.0 { "-" } else { "" })
            } else {
                serde_json::json!(d).to_string()
            };
            let v = serde_json::from_str(&text).unwrap_or(Value::Null);
            ps.insert(s.name.into(), v);
        }
    }
    Ok(a == b)
}

/// Writes bristle states (7 x f64 and the regime byte each) and then their accumulators.
fn put_bristles(w: &mut W, st: &[BristleState], acc: &[[f64; N_KERNEL]]) {
    for b in st {
        for x in [b.u[0], b.u[1], b.tau[0], b.tau[1], b.sh, b.temp, b.q] {
            w.f64(x);
        }
        w.u8(b.regime as u8);
    }
    for a in acc {
        for x in a {
            w.f64(*x);
        }
    }
}

/// Reads `nb` bristle states and then their accumulators (`what`: "" or "node ", for the
/// messages), refusing non-finite values and unknown regimes.
#[allow(clippy::type_complexity)]
fn get_bristles(
    r: &mut R,
    nb: usize,
    what: &str,
) -> Result<(Vec<BristleState>, Vec<[f64; N_KERNEL]>)> {
    let mut st = Vec::with_capacity(nb);
    for _ in 0..nb {
        let x: [f64; 7] = [r.f()?, r.f()?, r.f()?, r.f()?, r.f()?, r.f()?, r.f()?];
        if x.iter().any(|v| !v.is_finite()) {
            return Err(CreepError::State(format!(
                "{what}bristle {} of the state holds a non-finite value ({x:?})",
                st.len()
            )));
        }
        let regime = match r.b()? {
            0 => Regime::Elastic,
            1 => Regime::Plastic,
            2 => Regime::Sliding,
            b => return Err(CreepError::State(format!("bad regime byte {b}"))),
        };
        st.push(BristleState {
            u: [x[0], x[1]],
            tau: [x[2], x[3]],
            sh: x[4],
            temp: x[5],
            q: x[6],
            regime,
        });
    }
    let mut acc = Vec::with_capacity(nb);
    for _ in 0..nb {
        let mut a = [0.0; N_KERNEL];
        for v in a.iter_mut() {
            *v = r.f()?;
            if !v.is_finite() {
                return Err(CreepError::State(format!(
                    "{what}heat history {} of the state holds {v}",
                    acc.len()
                )));
            }
        }
        acc.push(a);
    }
    Ok((st, acc))
}

impl Model {
    /// Serializes the complete state.
    pub fn save_state(&self) -> Vec<u8> {
        let mut w = W::new();
        w.raw(MAGIC);
        w.u32(VERSION);
        let cfg = self.config().to_json().to_string();
        w.str(&cfg);
        match self {
            Model::Polach {
                inputs, out, time, ..
            } => {
                w.f64(*time);
                put_inputs(&mut w, inputs);
                put_outputs(&mut w, out);
                w.u8(1);
            }
            Model::Bristle(c) => {
                let s = c.raw_state();
                w.f64(s.time);
                put_inputs(&mut w, &s.inputs);
                put_outputs(&mut w, &s.out);
                w.u8(s.initialized as u8 | (s.reversed as u8) << 1);
                let (nx, ny) = c.grid_size();
                w.u32(nx as u32);
                w.u32(ny as u32);
                w.u32(N_KERNEL as u32);
                for h in s.head {
                    w.u32(*h as u32);
                }
                for p in s.phase {
                    w.f64(*p);
                }
                put_bristles(&mut w, s.st, s.acc);
                put_bristles(&mut w, s.node_st, s.node_acc);
                for p in s.part {
                    for x in [p.d, p.h, p.dcx, p.dcy, p.dcs] {
                        w.f64(x);
                    }
                }
            }
        }
        w.into_inner()
    }

    /// Restores a state saved by [`Model::save_state`] of a model with the same configuration.
    pub fn load_state(&mut self, data: &[u8]) -> Result<()> {
        let mut r = R(Reader::new(data));
        if r.take(8)? != MAGIC {
            return Err(CreepError::State("not an ECF state (bad magic)".into()));
        }
        let v = r.u()?;
        if !(1..=VERSION).contains(&v) {
            return Err(CreepError::State(format!(
                "state format version {v}, this build reads versions 1 to {VERSION}"
            )));
        }
        let n = r.u()? as usize;
        let cfg = std::str::from_utf8(r.take(n)?)
            .map_err(|_| CreepError::State("configuration is not UTF-8".into()))?
            .to_string();
        let now = self.config().to_json().to_string();
        if !same_config(&cfg, &now)? {
            return Err(CreepError::State(
                "the state was saved with a different configuration".into(),
            ));
        }
        let time = r.f()?;
        let inputs = get_inputs(&mut r, v)?;
        let out = get_outputs(&mut r, v)?;
        let flags = r.b()?;
        if flags > 3 || (v == 1 && flags > 1) {
            return Err(CreepError::State(format!("bad flags byte {flags}")));
        }
        let init = flags & 1 != 0;
        let reversed = flags & 2 != 0;
        // a state is checked like inputs: a NaN or infinite value would poison every later step
        if !time.is_finite() {
            return Err(CreepError::State(format!("time = {time} s is not finite")));
        }
        inputs
            .validate()
            .map_err(|e| CreepError::State(format!("inputs of the state: {e}")))?;
        if let Some(x) = out.to_array().iter().find(|x| !x.is_finite()) {
            return Err(CreepError::State(format!("an output of the state is {x}")));
        }
        match self {
            Model::Polach {
                inputs: i,
                out: o,
                time: t,
                ..
            } => {
                *i = inputs;
                *o = out;
                *t = time;
            }
            Model::Bristle(c) => {
                let nx = r.u()? as usize;
                let ny = r.u()? as usize;
                let k = r.u()? as usize;
                if (nx, ny) != c.grid_size() || k != N_KERNEL {
                    return Err(CreepError::State(format!(
                        "grid {nx}x{ny} (kernel {k}) does not match {:?} (kernel {N_KERNEL})",
                        c.grid_size()
                    )));
                }
                let nb = ny * (nx + 1);
                let mut head = Vec::with_capacity(ny);
                for _ in 0..ny {
                    head.push(r.u()? as usize);
                }
                let mut phase = Vec::with_capacity(ny);
                for _ in 0..ny {
                    phase.push(r.f()?);
                }
                let (st, acc) = get_bristles(&mut r, nb, "")?;
                let nodes = if v >= 4 {
                    let (ns, na) = get_bristles(&mut r, nb, "node ")?;
                    let mut part = Vec::with_capacity(ny);
                    for j in 0..ny {
                        let x = [r.f()?, r.f()?, r.f()?, r.f()?, r.f()?];
                        if x.iter().any(|v| !v.is_finite()) || x[0] < 0.0 || x[1] < 0.0 {
                            return Err(CreepError::State(format!(
                                "the part of the current cell of strip {j} is not a distance and a time ({x:?})"
                            )));
                        }
                        part.push(Partial {
                            d: x[0],
                            h: x[1],
                            dcx: x[2],
                            dcy: x[3],
                            dcs: x[4],
                        });
                    }
                    Some((ns, na, part))
                } else {
                    None
                };
                if r.0.position() != data.len() {
                    return Err(CreepError::State(format!(
                        "{} trailing bytes",
                        data.len() - r.0.position()
                    )));
                }
                c.set_raw_state(OwnedRawState {
                    time,
                    inputs,
                    head,
                    phase,
                    st,
                    acc,
                    nodes,
                    initialized: init,
                    out,
                    reversed,
                })?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;

    /// The position of the output count: after magic, version, configuration, time, inputs.
    fn outputs_at(bytes: &[u8]) -> usize {
        let n = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        let mut at = 16 + n + 8 + 4;
        for s in INPUTS {
            at += 4 + s.name.len() + 8;
        }
        at
    }

    #[test]
    fn outputs_are_stored_by_name() {
        let cfg = Config::preset("polach").unwrap();
        let mut m = Model::new(&cfg).unwrap();
        let out = m
            .steady(&Inputs {
                cx: 0.01,
                ..Inputs::default()
            })
            .unwrap();
        let bytes = m.save_state();
        let at = outputs_at(&bytes);
        assert_eq!(
            u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize,
            OUTPUTS.len()
        );
        // a build with one output less wrote this: the last output keeps its default (0)
        let last = OUTPUTS[OUTPUTS.len() - 1];
        let entry = 4 + last.name.len() + 8;
        let flags_at = bytes.len() - 1;
        let mut short = bytes[..flags_at - entry].to_vec();
        short.push(bytes[flags_at]);
        short[at..at + 4].copy_from_slice(&(OUTPUTS.len() as u32 - 1).to_le_bytes());
        let mut fresh = Model::new(&cfg).unwrap();
        fresh
            .load_state(&short)
            .expect("a state without the last output loads");
        assert_ne!((last.get)(&out), 0.0);
        assert_eq!((last.get)(&fresh.outputs()), 0.0);
        assert_eq!(fresh.outputs().fx, out.fx);
        // a name this build does not know is refused with it
        let mut odd = bytes.clone();
        let name_at = flags_at - entry + 4;
        odd[name_at] = b'#';
        let e = fresh.load_state(&odd).unwrap_err().to_string();
        assert!(e.contains(&format!("'#{}'", &last.name[1..])), "{e}");
    }

    /// An input or output stored twice is refused with its name (not "the last one wins").
    #[test]
    fn a_name_stored_twice_is_refused() {
        let cfg = Config::preset("polach").unwrap();
        let mut m = Model::new(&cfg).unwrap();
        m.steady(&Inputs {
            cx: 0.01,
            ..Inputs::default()
        })
        .unwrap();
        let bytes = m.save_state();
        let n = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        let inputs_at = 16 + n + 8;
        for (count_at, first, what) in [
            (inputs_at, INPUTS[0].name, "an input"),
            (outputs_at(&bytes), OUTPUTS[0].name, "an output"),
        ] {
            // the first entry a second time, the count one more
            let entry = 4 + first.len() + 8;
            let at = count_at + 4;
            let mut twice = bytes[..at + entry].to_vec();
            twice.extend_from_slice(&bytes[at..]);
            let k = u32::from_le_bytes(bytes[count_at..at].try_into().unwrap());
            twice[count_at..at].copy_from_slice(&(k + 1).to_le_bytes());
            let e = Model::new(&cfg)
                .unwrap()
                .load_state(&twice)
                .unwrap_err()
                .to_string();
            assert!(e.contains(&format!("{what} '{first}' twice")), "{e}");
        }
        assert!(Model::new(&cfg).unwrap().load_state(&bytes).is_ok());
    }

    #[test]
    fn a_model_runs_its_configurations_scheme_and_its_state_loads_under_another() {
        use crate::engine::Scheme;
        let cells = Config::from_json_str(r#"{"preset": "dry", "scheme": "cells"}"#, "x").unwrap();
        let ho = Config::from_json_str(r#"{"preset": "dry", "grid": {"nx": 20, "ny": 5}}"#, "x")
            .unwrap();
        assert_eq!(ho.scheme, Scheme::CellsHigher, "ECF's default");
        let mut small = cells.clone();
        small.grid = ho.grid;
        let at = Inputs {
            cx: 0.01,
            v: 20.0,
            fn_n: 110e3,
            ..Inputs::default()
        };
        let fx = |c: &Config, set: Option<Scheme>| {
            let mut m = Model::new(c).unwrap();
            if let Some(s) = set {
                m.set_scheme(s);
            }
            (m.steady(&at).unwrap().fx, m)
        };
        // the configuration's scheme is the one set on a model built cell by cell
        let (f_ho, m_ho) = fx(&ho, None);
        let (f_set, _) = fx(&small, Some(Scheme::CellsHigher));
        let (f_cells, mut m_cells) = fx(&small, None);
        assert_eq!(f_ho.to_bits(), f_set.to_bits());
        assert!((f_ho / f_cells - 1.0).abs() > 1e-4, "{f_ho} {f_cells}");
        // a model set back to cells computes what a cells configuration does
        let (f_back, _) = fx(&ho, Some(Scheme::CellsMarch));
        assert_eq!(f_back.to_bits(), f_cells.to_bits());
        // the scheme says how to compute, not what: the state loads into a cells model
        m_cells.load_state(&m_ho.save_state()).unwrap();
        assert_eq!(m_cells.outputs().fx.to_bits(), f_ho.to_bits());
        // and steps on in its own scheme: as a cells model set to ho's state would, not as ho
        let (mut m_ho, mut twin) = (m_ho, Model::new(&small).unwrap());
        twin.load_state(&m_ho.save_state()).unwrap();
        let next = Inputs { cx: 0.02, ..at };
        let a = m_cells.step(1e-4, &next).unwrap().fx;
        assert_eq!(a.to_bits(), twin.step(1e-4, &next).unwrap().fx.to_bits());
        assert_ne!(a.to_bits(), m_ho.step(1e-4, &next).unwrap().fx.to_bits());
        // but not into a model of another grid
        assert!(Model::new(&cells)
            .unwrap()
            .load_state(&m_ho.save_state())
            .is_err());
    }

    #[test]
    fn a_configuration_saved_before_a_parameter_existed_loads_at_its_default() {
        let cfg = Config::preset("table4.1").unwrap();
        let d = Params::default();
        let s = params::SPECS
            .iter()
            .find(|s| cfg.params.get(s.id) == d.get(s.id) && s.default.is_finite())
            .expect("a parameter at its default");
        let now = cfg.to_json().to_string();
        let mut v: Value = serde_json::from_str(&now).unwrap();
        v["params"].as_object_mut().unwrap().remove(s.name);
        let saved = v.to_string();
        assert_ne!(saved, now);
        assert!(same_config(&saved, &now).unwrap(), "{}", s.name);
        // not if this build's value is another
        let mut other = cfg.clone();
        let x = if s.default < s.max {
            (s.default + s.max.min(s.default + 1.0)) / 2.0
        } else {
            (s.default + s.min) / 2.0
        };
        other.params.set(s.id, x).unwrap();
        assert!(!same_config(&saved, &other.to_json().to_string()).unwrap());
        // a parameter this build does not know is refused with its name
        v["params"]["no_such_param"] = serde_json::json!(1.0);
        let e = same_config(&v.to_string(), &now).unwrap_err().to_string();
        assert!(e.contains("'no_such_param'"), "{e}");
    }
}
