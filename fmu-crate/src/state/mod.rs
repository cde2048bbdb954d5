//! Serialized FMU state: an explicit, versioned little-endian byte format of a [`Snapshot`]: the importer's settings by name and the core model's own state bytes.
//!
//! Layout (version 9): magic `ECFFMUST`, u32 version, f64 time, u8 the mode the state was
//! taken in (0 Instantiated, 1 InitializationMode, 2 StepComplete, 3 Terminated; restored by
//! fmi2SetFMUstate), u8 the scheme `rel_tol` chose for the model (the code of the parameter
//! `scheme`, 255: none chose one), u32 count + per input (its name as in
//! modelDescription.xml, f64 value), u32 count + per setting the importer set (the
//! parameter's name as in modelDescription.xml, u8 type: 0 Real as f64, 1 Integer as i32,
//! 2 Boolean as u8, 3 String), u8 + (if the instance holds a model) u32 length + the bytes
//! of `creep_core::Model::save_state` (the configuration as JSON, the run state, the whole
//! bristle grid and heat histories). Strings are u32 length + UTF-8. Nothing follows.
//!
//! The configuration is stored once, in the core's state. The model is rebuilt from it, not
//! resolved again from the settings: the settings name a preset or a configuration file
//! that the restoring instance may not have (or has changed), and `rel_tol` chose the grid
//! at the speed of the initialization, not of the state. The configuration's numbers read
//! back bit for bit but for its geometry, which the document gives in mm and kN: the
//! geometry values the importer set are taken from the settings, where they are exact.
//! Formula and Rust effects come back from the configuration's JSON, with their parameters.
//! The settings `threads`, `scheme`, `temperature_solve` and `rel_tol` are not stored: they
//! are the restoring instance's.
//!
//! Inputs and settings are stored by name, so that a build with another input or parameter
//! reads the state: a value the state lacks keeps its start value, a name the reading build
//! does not know is refused with that name, as is a name stored twice. States of versions 2
//! to 8 are read by [`legacy`].

use crate::instance::{validate_snapshot, Phase, Snapshot};
use crate::settings::{extras_for, Settings};
use crate::vars::{self, Causality, In, Value, Var, N_INPUTS};
use creep_core::bytes::{Reader, Writer};
use creep_core::{Config, Model};
use std::collections::HashSet;
use std::sync::{Arc, Mutex};

mod legacy;
#[cfg(test)]
mod tests;

/// Magic bytes at the start of a serialized FMU state.
pub const MAGIC: &[u8; 8] = b"ECFFMUST";
/// Magic bytes at the start of a state serialized by the FMI 3.0 FMU: they precede the
/// bytes of [`serialize`], so that each FMU refuses the other's states by name.
pub const MAGIC3: &[u8; 8] = b"ECFFMI3S";
/// Format version written by this build.
pub const VERSION: u32 = 9;
/// The oldest format version this build reads.
pub const OLDEST: u32 = 2;

/// The FMU's parameters (the variables a state's settings are stored as), built at the
/// first use (about 30 us) and kept until [`release_parameters`].
static PARAMETERS: Mutex<Option<Arc<Vec<Var>>>> = Mutex::new(None);

/// The FMU's parameters ([`PARAMETERS`]).
fn parameters() -> Arc<Vec<Var>> {
    let mut p = PARAMETERS.lock().unwrap_or_else(|e| e.into_inner());
    p.get_or_insert_with(|| {
        Arc::new(
            vars::table()
                .into_iter()
                .filter(|v| v.causality == Causality::Parameter)
                .collect(),
        )
    })
    .clone()
}

/// Frees the parameter list (the library's last instance was freed): a static's heap would
/// otherwise stay allocated after the importer unloads the library.
pub fn release_parameters() {
    *PARAMETERS.lock().unwrap_or_else(|e| e.into_inner()) = None;
}

/// Refuses a name that a list stored by name holds twice (a reader that let the last one win
/// would load a corrupted state silently); `what` is "an input", "the setting", ...
fn once(seen: &mut HashSet<String>, what: &str, name: &str) -> Result<(), String> {
    if seen.insert(name.to_string()) {
        Ok(())
    } else {
        Err(format!("the state has {what} '{name}' twice"))
    }
}

/// The bytes of a snapshot in the FMI 3.0 FMU's format: [`MAGIC3`], then [`serialize`]'s.
pub fn serialize3(s: &Snapshot) -> Vec<u8> {
    let mut out = MAGIC3.to_vec();
    out.extend(serialize(s));
    out
}

/// Reads a state of the FMI 3.0 FMU ([`serialize3`]); a state of the FMI 2.0 FMU is
/// refused by name.
pub fn deserialize3(data: &[u8]) -> Result<Snapshot, String> {
    match data.strip_prefix(&MAGIC3[..]) {
        Some(rest) => deserialize(rest),
        None if data.starts_with(MAGIC) => Err("the state was serialized by the FMI 2.0 FMU (ecf_contact.fmu); the FMI 3.0 FMU reads only its own states: restore it in an instance of the FMI 2.0 FMU".into()),
        None => Err("not a serialized ecf_contact FMU state (bad magic)".into()),
    }
}

/// Serializes a snapshot.
pub fn serialize(s: &Snapshot) -> Vec<u8> {
    let mut w = Writer::new();
    w.raw(MAGIC);
    w.u32(VERSION);
    w.f64(s.time);
    w.u8(phase_code(s.phase));
    w.u8(s
        .tol_scheme
        .map_or(255, |x| crate::settings::scheme_code(x) as u8));
    w.u32(N_INPUTS as u32);
    for (i, x) in In::ALL.iter().zip(s.inputs) {
        w.str(&i.name());
        w.f64(x);
    }
    let params = parameters();
    let set: Vec<(&str, Value)> = params
        .iter()
        .filter_map(|v| s.settings.stored(v.slot).map(|x| (v.name.as_str(), x)))
        .collect();
    w.u32(set.len() as u32);
    for (name, x) in set {
        w.str(name);
        match x {
            Value::Real(x) => {
                w.u8(0);
                w.f64(x);
            }
            Value::Integer(x) => {
                w.u8(1);
                w.i32(x);
            }
            Value::Boolean(x) => {
                w.u8(2);
                w.u8(x as u8);
            }
            Value::String(x) => {
                w.u8(3);
                w.str(&x);
            }
        }
    }
    match &s.model {
        Some(m) => {
            w.u8(1);
            w.bytes(&m.save_state());
        }
        None => w.u8(0),
    }
    w.into_inner()
}

fn phase_code(p: Phase) -> u8 {
    match p {
        Phase::Instantiated => 0,
        Phase::Initialization => 1,
        Phase::StepComplete => 2,
        Phase::Terminated => 3,
        // refused by fmi2GetFMUstate; never serialized
        Phase::Error => 255,
    }
}

fn phase_of(c: u8) -> Result<Phase, String> {
    Ok(match c {
        0 => Phase::Instantiated,
        1 => Phase::Initialization,
        2 => Phase::StepComplete,
        3 => Phase::Terminated,
        _ => return Err(format!("bad mode code {c}")),
    })
}

/// The scheme `rel_tol` chose, of its stored code (255: none).
fn tol_scheme_of(c: u8) -> Result<Option<creep_core::Scheme>, String> {
    match c {
        255 => Ok(None),
        c => creep_core::Scheme::by_fmu_code(c as i32)
            .map(Some)
            .ok_or_else(|| format!("bad scheme code {c}")),
    }
}

/// Reads the inputs stored by name (u32 count, then name and f64 each); an input the state
/// lacks keeps its start value.
fn read_inputs(r: &mut Reader) -> Result<[f64; N_INPUTS], String> {
    let mut inputs = In::ALL.map(|i| i.start());
    let mut seen = HashSet::new();
    for _ in 0..r.u32()? {
        let name = r.str()?;
        once(&mut seen, "an input", &name)?;
        let i = In::ALL
            .iter()
            .position(|i| i.name() == name)
            .ok_or_else(|| {
                format!("the state has an input '{name}' that this build does not know")
            })?;
        inputs[i] = r.f64()?;
    }
    Ok(inputs)
}

/// Reads the settings stored by name (u32 count, then name, type and value each).
fn read_settings(r: &mut Reader) -> Result<Settings, String> {
    let params = parameters();
    let mut st = Settings::default();
    let mut seen = HashSet::new();
    for _ in 0..r.u32()? {
        let name = r.str()?;
        once(&mut seen, "the setting", &name)?;
        let x = match r.u8()? {
            0 => Value::Real(r.f64()?),
            1 => Value::Integer(r.i32()?),
            2 => Value::Boolean(r.bool()?),
            3 => Value::String(r.str()?),
            t => return Err(format!("the setting '{name}' has the bad type code {t}")),
        };
        let v = params
            .iter()
            .find(|v| v.name == name && carried(v))
            .ok_or_else(|| {
                format!("the state has the setting '{name}' that this build does not know")
            })?;
        if !st.apply(v, &x) {
            return Err(format!(
                "the state's setting '{name}' is a {}, not a {}",
                x.kind().name(),
                v.kind.name()
            ));
        }
    }
    Ok(st)
}

/// True for a parameter whose setting a state carries ([`Settings::stored`]).
fn carried(v: &Var) -> bool {
    use crate::vars::Slot;
    !matches!(
        v.slot,
        Slot::Threads | Slot::Scheme | Slot::TemperatureSolve | Slot::RelTol
    )
}

/// The model of a state's core bytes: built from the configuration they hold (with the
/// geometry values the importer set, exact in `st`), given the data columns of its formula
/// and Rust effects, and then its state.
fn rebuild_model(bytes: &[u8], st: &Settings, inputs: &[f64; N_INPUTS]) -> Result<Model, String> {
    let mut cfg: Config = creep_core::state::saved_config(bytes).map_err(|e| e.to_string())?;
    st.apply_geometry(&mut cfg);
    let mut m = Model::new(&cfg).map_err(|e| e.to_string())?;
    if let Some(x) = extras_for(&cfg, &st.columns, inputs)? {
        m.set_extra(&x).map_err(|e| e.to_string())?;
    }
    m.load_state(bytes).map_err(|e| e.to_string())?;
    Ok(m)
}

/// Reads a snapshot written by [`serialize`] (or by an earlier build: versions 2 to 8);
/// checks everything, including the core state.
pub fn deserialize(data: &[u8]) -> Result<Snapshot, String> {
    let mut r = Reader::new(data);
    if data.starts_with(MAGIC3) {
        return Err("the state was serialized by the FMI 3.0 FMU (ecf_contact_fmi3.fmu); the FMI 2.0 FMU reads only its own states: restore it in an instance of the FMI 3.0 FMU".into());
    }
    if r.take(8).ok() != Some(&MAGIC[..]) {
        return Err("not a serialized ecf_contact FMU state (bad magic)".into());
    }
    let v = r.u32()?;
    let snap = match v {
        VERSION => read_current(&mut r)?,
        OLDEST..VERSION => legacy::read(&mut r, v)?,
        _ => {
            return Err(format!(
            "serialized FMU state has format version {v}; this build reads versions {OLDEST} to {VERSION}"
        ))
        }
    };
    if r.position() != data.len() {
        return Err(format!("{} trailing bytes", data.len() - r.position()));
    }
    validate_snapshot(&snap).map_err(|e| format!("invalid state: {e}"))?;
    Ok(snap)
}

/// Reads what follows the version in the current format.
fn read_current(r: &mut Reader) -> Result<Snapshot, String> {
    let time = r.f64()?;
    let phase = phase_of(r.u8()?)?;
    let tol_scheme = tol_scheme_of(r.u8()?)?;
    let inputs = read_inputs(r)?;
    let settings = read_settings(r)?;
    let model = if r.bool()? {
        Some(rebuild_model(r.bytes()?, &settings, &inputs)?)
    } else {
        None
    };
    Ok(Snapshot {
        cfg: model.as_ref().map(|m| m.config().clone()),
        settings,
        inputs,
        time,
        model,
        phase,
        tol_scheme,
    })
}
