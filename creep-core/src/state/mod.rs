//! Versioned, explicit byte format of a model's complete hidden state (bristle grid, heat histories) for save/restore.
//!
//! Layout (little endian, version 4): magic `ECFSTATE`, format version u32, config JSON (u32
//! length + UTF-8), then the run state (time, inputs and outputs by name, flags;
//! `RunState::write` in module `engine::grid_state`) and, for bristle models, the grid
//! (`GridState::write` there: ring-buffer heads and phases, the bristles, their committed
//! node states and each strip's part of the current cell, docs/model.md section 3).
//!
//! Values are stored by name, so a build with another input or output reads the state: a
//! value the state lacks keeps its default, a name this build does not know is refused. The
//! configuration is compared as text; a state saved before a parameter existed holds no
//! value for it and loads if this build's value is the parameter's default.
//! States of versions 1 to 3 are read by [`legacy`].
//! Restoring checks the magic, the version, the configuration and every size, so a state
//! from another configuration or a corrupt buffer is refused with a message, never misread.

use crate::bytes::{Reader, Writer};
use crate::config::Config;
use crate::engine::grid_state::{GridState, RunState, StateReader};
use crate::error::{CreepError, Result};
use crate::model::Model;
use crate::params::{self, Params};
use serde_json::Value;

mod legacy;

const MAGIC: &[u8; 8] = b"ECFSTATE";
/// Current version of the byte format.
pub const VERSION: u32 = 4;

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

/// Reads the magic, the version and the configuration's JSON text of a state.
fn header(r: &mut StateReader) -> Result<(u32, String)> {
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
    Ok((v, cfg))
}

/// The configuration a state was saved with, read from its JSON: a model built from it
/// loads the state. Numbers round-trip bit for bit through the JSON (shortest printing,
/// correctly rounded parsing), but for geometry values, which the document gives in mm or
/// kN and may come back one unit in the last place off.
pub fn saved_config(data: &[u8]) -> Result<Config> {
    let (_, json) = header(&mut StateReader(Reader::new(data)))?;
    Config::from_json_str(
        &legacy::with_scheme(&json),
        "the configuration of a saved state",
    )
}

impl Model {
    /// Serializes the complete state.
    pub fn save_state(&self) -> Vec<u8> {
        let mut w = Writer::new();
        w.raw(MAGIC);
        w.u32(VERSION);
        let cfg = self.config().to_json().to_string();
        w.str(&cfg);
        match self {
            Model::Polach {
                inputs, out, time, ..
            } => RunState {
                time: *time,
                inputs: *inputs,
                out: *out,
                initialized: true,
                reversed: false,
            }
            .write(&mut w),
            Model::Bristle(c) => c.grid_state().write(&mut w, c.grid_size()),
        }
        w.into_inner()
    }

    /// Restores a state saved by [`Model::save_state`] of a model with the same configuration.
    pub fn load_state(&mut self, data: &[u8]) -> Result<()> {
        let mut r = StateReader(Reader::new(data));
        let (v, cfg) = header(&mut r)?;
        let now = self.config().to_json().to_string();
        if !same_config(&cfg, &now)? {
            return Err(CreepError::State(
                "the state was saved with a different configuration".into(),
            ));
        }
        let run = if v == VERSION {
            RunState::read(&mut r)?
        } else {
            legacy::read_run(&mut r, v)?
        };
        match self {
            Model::Polach {
                inputs, out, time, ..
            } => {
                *inputs = run.inputs;
                *out = run.out;
                *time = run.time;
            }
            Model::Bristle(c) => {
                let g = if v == VERSION {
                    GridState::read(&mut r, run, c.grid_size())?
                } else {
                    GridState::read_bristles(&mut r, run, c.grid_size())?
                };
                if r.0.position() != data.len() {
                    return Err(CreepError::State(format!(
                        "{} trailing bytes",
                        data.len() - r.0.position()
                    )));
                }
                c.restore(g)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::io::{INPUTS, OUTPUTS};
    use crate::engine::Inputs;

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
