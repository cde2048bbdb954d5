//! Serialized FMU state: an explicit, versioned little-endian byte format of a [`Snapshot`] (settings, inputs, time, configuration, and the core model's own state bytes).
//!
//! Layout (version 8): magic `ECFFMUST`, u32 version, f64 time, u32 count + per input (its
//! name as in modelDescription.xml, f64 value), settings (model, model_set, preset,
//! config_file, columns, set parameters as u32 count and (name, f64) each, set effects as
//! u32 count and (name, u8) each, nx, ny as u32 (0 = not set), i32 geometry, u32 count + per geometry
//! parameter (name, u8 present, f64)), u8 + configuration (u8 model, u32 count + names of the
//! effects on, u32 count + (name, f64) per parameter, u8 bound, u32 nx, u32 ny, u8 geometry
//! kind + 3 × f64, preset name, u8 + (if formula or Rust effects) the configuration as JSON
//! and, per formula then Rust effect, u32 count + f64 parameter values, u8 the
//! configuration's scheme as the code of the parameter `scheme`), u8 + u32 length +
//! the bytes of `creep_core::Model::save_state` (the whole bristle grid and heat histories),
//! and u8 the mode the state was taken in (0 Instantiated, 1 InitializationMode,
//! 2 StepComplete, 3 Terminated), which fmi2SetFMUstate restores, and u8 the scheme
//! `rel_tol` chose for the model (the code of the parameter `scheme`, 255: none chose one).
//! Version 7 wrote the scheme codes of its day, 0 for cell by cell (today 3; 1 and 2 are
//! the same); version 6 had no scheme byte in the configuration (cells); version 5 had no
//! scheme byte at the end either (none chose one).
//! Inputs, parameters, effects and geometry values are stored by name (those of creep-core's
//! tables), so that a build with another input, parameter or effect reads the state: a value
//! it lacks keeps its default (an effect: off in the configuration, not set in the settings);
//! a name the reading build does not know is refused with that name.
//! Older versions (read, not written): version 4 stored parameters as (u32, f64) and effects
//! as (u8, u8) by index, the configuration's effects as u32 bits and its parameters as a
//! count (26) and values, each index k the parameter with value reference 100 + k, the
//! effect with value reference 50 + k; versions 2 and 3 had no mode byte (a state holding a
//! model is in StepComplete, else Instantiated); version 2 stored the 10 inputs and 5
//! geometry values without names, in the fixed orders `V2_INPUTS`, `V2_GEO`.
//! Strings are u32 length + UTF-8. Nothing follows the last field.

use crate::instance::{validate_snapshot, Phase, Snapshot};
use crate::settings::{extras_for, Settings};
use crate::vars::{Geo, In, N_GEO, N_INPUTS};
use creep_core::bytes::{Reader, Writer};
use creep_core::effects::{self, Effect, EffectSet};
use creep_core::params::{self, Params, P};
use creep_core::{AnyModifier, Bound, Config, Geometry, Grid, Model, ModelKind, Modifier};

/// Magic bytes at the start of a serialized FMU state.
pub const MAGIC: &[u8; 8] = b"ECFFMUST";
/// Magic bytes at the start of a state serialized by the FMI 3.0 FMU: they precede the
/// bytes of [`serialize`], so that each FMU refuses the other's states by name.
pub const MAGIC3: &[u8; 8] = b"ECFFMI3S";
/// Format version written by this build.
pub const VERSION: u32 = 8;

/// The inputs of format version 2, in its fixed order (version 3 stores each with its name).
const V2_INPUTS: [&str; 10] = [
    "cx", "cy", "spin", "v", "FN", "T_bulk", "aux1", "aux2", "aux3", "aux4",
];
/// The geometry parameters of format version 2, in its fixed order.
const V2_GEO: [&str; 5] = ["a_ref", "b_ref", "FN_ref", "Rx", "Ry"];

type W = Writer;
type R<'a> = Reader<'a>;

/// Refuses a name that a list stored by name holds twice (a reader that let the last one win
/// would load a corrupted state silently); `what` is "an input", "the parameter", ...
fn once(
    seen: &mut std::collections::HashSet<String>,
    what: &str,
    name: &str,
) -> Result<(), String> {
    if seen.insert(name.to_string()) {
        Ok(())
    } else {
        Err(format!("the state has {what} '{name}' twice"))
    }
}

/// Effect of a value reference (versions up to 4 stored effects by `vr - 50`).
fn effect_of_vr(vr: u32) -> Option<Effect> {
    effects::CATALOGUE
        .iter()
        .find(|i| i.vr == vr)
        .map(|i| i.effect)
}

/// Parameter of a value reference (versions up to 4 stored parameters by `vr - 100`).
fn param_of_vr(vr: u32) -> Option<P> {
    params::SPECS.iter().find(|s| s.vr == vr).map(|s| s.id)
}

/// Effect of a name; a name this build does not know is refused with it.
fn effect_named(name: &str) -> Result<Effect, String> {
    effects::by_name(name)
        .map_err(|_| format!("the state has the effect '{name}' that this build does not know"))
}

/// Parameter of a name; a name this build does not know is refused with it.
fn param_named(name: &str) -> Result<P, String> {
    params::by_name(name).ok_or_else(|| {
        format!("the state has the parameter '{name}' that this build does not know")
    })
}

fn put_config(w: &mut W, c: &Config) {
    w.u8(match c.model {
        ModelKind::Ecf => 0,
        ModelKind::Fastsim => 1,
        ModelKind::Polach => 2,
    });
    let on = c.effects.to_vec();
    w.u32(on.len() as u32);
    for e in on {
        w.str(effects::info(e).name);
    }
    w.u32(params::SPECS.len() as u32);
    for s in params::SPECS {
        w.str(s.name);
        w.f64(c.params.get(s.id));
    }
    w.u8(match c.bound {
        Bound::Elliptic => 0,
        Bound::Parabolic => 1,
    });
    w.u32(c.grid.nx as u32);
    w.u32(c.grid.ny as u32);
    let (k, g) = match c.geometry {
        Geometry::SemiAxes { a, b, fn_ref } => (0, [a, b, fn_ref]),
        Geometry::Curvatures { rx, ry } => (1, [rx, ry, 0.0]),
        Geometry::Line { r, width } => (2, [r, width, 0.0]),
    };
    w.u8(k);
    for x in g {
        w.f64(x);
    }
    w.str(&c.preset);
    // formula and custom effects: the configuration as JSON (for their expressions and
    // names), their parameter values bit-exact beside it
    let has_mod = !c.modifiers.is_empty();
    w.u8(has_mod as u8);
    if has_mod {
        w.str(&c.to_json().to_string());
        // formula effects first, then Rust effects (the order of the JSON above)
        for m in AnyModifier::kind_order(&c.modifiers)
            .into_iter()
            .map(|k| &c.modifiers[k])
        {
            w.u32(m.n_params() as u32);
            for k in 0..m.n_params() {
                w.f64(m.param(k).value);
            }
        }
    }
    w.u8(crate::settings::scheme_code(c.scheme) as u8);
}

/// The scheme of a stored code (the parameter `scheme`'s, [`crate::settings::scheme_code`]) in
/// a state of format `version`: 1 to 3 from version 8, 0 to 2 before (0 cell by cell); None
/// for any other code.
fn scheme_of_byte(c: u8, version: u32) -> Option<creep_core::engine::Scheme> {
    match (c, version) {
        (1..=3, 8..) => Some(crate::settings::scheme_of_code(c as i32)),
        (0..=2, ..=7) => Some(crate::settings::scheme_of_code(c as i32)),
        _ => None,
    }
}

fn get_config(r: &mut R, version: u32) -> Result<Config, String> {
    let model = match r.u8()? {
        0 => ModelKind::Ecf,
        1 => ModelKind::Fastsim,
        2 => ModelKind::Polach,
        b => return Err(format!("bad model byte {b}")),
    };
    let (effects, p) = if version >= 5 {
        get_config_named(r)?
    } else {
        get_config_v4(r)?
    };
    let bound = match r.u8()? {
        0 => Bound::Elliptic,
        1 => Bound::Parabolic,
        b => return Err(format!("bad bound byte {b}")),
    };
    let grid = Grid {
        nx: r.u32()? as usize,
        ny: r.u32()? as usize,
    };
    grid.validate().map_err(|e| e.to_string())?;
    let k = r.u8()?;
    let g = [r.f64()?, r.f64()?, r.f64()?];
    let geometry = match k {
        0 => Geometry::SemiAxes {
            a: g[0],
            b: g[1],
            fn_ref: g[2],
        },
        1 => Geometry::Curvatures { rx: g[0], ry: g[1] },
        2 => Geometry::Line {
            r: g[0],
            width: g[1],
        },
        b => return Err(format!("bad geometry byte {b}")),
    };
    let preset = r.str()?;
    let mut modifiers = Vec::new();
    if r.bool()? {
        let json = r.str()?;
        let full = Config::from_json_str(&json, "FMU state").map_err(|e| e.to_string())?;
        modifiers = full.modifiers;
        for k in AnyModifier::kind_order(&modifiers) {
            let m = &mut modifiers[k];
            let n = r.u32()? as usize;
            if n != m.n_params() {
                return Err(format!(
                    "{}: {n} parameters, it has {}",
                    m.describe(),
                    m.n_params()
                ));
            }
            for j in 0..n {
                let x = r.f64()?;
                if !x.is_finite() {
                    return Err(format!("{}: parameter {j} = {x}", m.describe()));
                }
                m.set_param(j, x);
            }
        }
    }
    let scheme = if version >= 7 {
        let c = r.u8()?;
        scheme_of_byte(c, version).ok_or_else(|| format!("bad configuration scheme code {c}"))?
    } else {
        creep_core::engine::Scheme::CellsMarch
    };
    Ok(Config {
        model,
        preset,
        effects,
        params: p,
        bound,
        grid,
        scheme,
        // not stored: how to compute, the restoring instance's own choice applies
        temperature_solve: Default::default(),
        geometry,
        modifiers,
    })
}

/// The effects and parameters of a configuration, stored by name (version 5 on).
fn get_config_named(r: &mut R) -> Result<(EffectSet, Params), String> {
    let mut effects = EffectSet::empty();
    let mut seen = std::collections::HashSet::new();
    for _ in 0..r.u32()? {
        let name = r.str()?;
        once(&mut seen, "the configuration's effect", &name)?;
        effects.insert(effect_named(&name)?);
    }
    let mut p = Params::default();
    let mut seen = std::collections::HashSet::new();
    for _ in 0..r.u32()? {
        let name = r.str()?;
        once(&mut seen, "the configuration's parameter", &name)?;
        let id = param_named(&name)?;
        p.set(id, r.f64()?).map_err(|e| e.to_string())?;
    }
    Ok((effects, p))
}

/// The effects and parameters of a configuration of versions up to 4: effect bits (bit k the
/// effect with value reference 50 + k) and the 26 parameters of value references 100 to 125.
fn get_config_v4(r: &mut R) -> Result<(EffectSet, Params), String> {
    let bits = r.u32()?;
    let mut effects = EffectSet::empty();
    for k in 0..32 {
        if bits & (1 << k) != 0 {
            effects
                .insert(effect_of_vr(50 + k).ok_or_else(|| format!("bad effect bits {bits:#x}"))?);
        }
    }
    let n = r.u32()?;
    if n != 26 {
        return Err(format!("{n} parameters, format version 4 has 26"));
    }
    let mut p = Params::default();
    for k in 0..n {
        let id = param_of_vr(100 + k)
            .ok_or_else(|| format!("this build has no parameter {k} of version 4"))?;
        p.set(id, r.f64()?).map_err(|e| e.to_string())?;
    }
    Ok((effects, p))
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
    let mut w = W::new();
    w.raw(MAGIC);
    w.u32(VERSION);
    w.f64(s.time);
    // each input with its name: a build with more inputs reads this state
    w.u32(N_INPUTS as u32);
    for (i, x) in In::ALL.iter().zip(s.inputs) {
        w.str(&i.name());
        w.f64(x);
    }
    let st = &s.settings;
    w.str(&st.model);
    w.u8(st.model_set as u8);
    w.str(&st.preset);
    w.str(&st.config_file);
    w.str(&st.columns);
    w.u32(st.params.len() as u32);
    for (p, x) in &st.params {
        w.str(params::spec(*p).name);
        w.f64(*x);
    }
    w.u32(st.effects.len() as u32);
    for (e, on) in &st.effects {
        w.str(effects::info(*e).name);
        w.u8(*on as u8);
    }
    w.u32(st.nx.unwrap_or(0) as u32);
    w.u32(st.ny.unwrap_or(0) as u32);
    w.i32(st.geometry);
    w.u32(N_GEO as u32);
    for (g, x) in Geo::ALL.iter().zip(st.geo) {
        w.str(g.name());
        w.u8(x.is_some() as u8);
        w.f64(x.unwrap_or(0.0));
    }
    match &s.cfg {
        Some(c) => {
            w.u8(1);
            put_config(&mut w, c);
        }
        None => w.u8(0),
    }
    match &s.model {
        Some(m) => {
            w.u8(1);
            w.bytes(&m.save_state());
        }
        None => w.u8(0),
    }
    w.u8(phase_code(s.phase));
    w.u8(s
        .tol_scheme
        .map_or(255, |x| crate::settings::scheme_code(x) as u8));
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

/// Reads a list of named values: version 3 a u32 count and per entry its name and value,
/// version 2 the values alone in the fixed order `v2`. `value(r, i)` reads the value of the
/// entry whose name is `names[i]`; a name this build does not know (`what`: "an input") is
/// refused.
fn read_named(
    r: &mut R,
    version: u32,
    v2: &[&str],
    names: &[String],
    what: &str,
    mut value: impl FnMut(&mut R, usize) -> Result<(), String>,
) -> Result<(), String> {
    let n = if version == 2 {
        v2.len()
    } else {
        r.u32()? as usize
    };
    let mut seen = std::collections::HashSet::new();
    for k in 0..n {
        let name = match v2.get(k) {
            Some(n) if version == 2 => n.to_string(),
            _ => r.str()?,
        };
        once(&mut seen, what, &name)?;
        let i = names.iter().position(|n| *n == name).ok_or_else(|| {
            format!("the state has {what} '{name}' that this build does not know")
        })?;
        value(r, i)?;
    }
    Ok(())
}

/// Reads a snapshot written by [`serialize`]; checks everything, including the core state.
pub fn deserialize(data: &[u8]) -> Result<Snapshot, String> {
    let mut r = R::new(data);
    if data.starts_with(MAGIC3) {
        return Err("the state was serialized by the FMI 3.0 FMU (ecf_contact_fmi3.fmu); the FMI 2.0 FMU reads only its own states: restore it in an instance of the FMI 3.0 FMU".into());
    }
    if r.take(8).ok() != Some(&MAGIC[..]) {
        return Err("not a serialized ecf_contact FMU state (bad magic)".into());
    }
    let v = r.u32()?;
    if !(2..=VERSION).contains(&v) {
        return Err(format!(
            "serialized FMU state has format version {v}; this build reads versions 2 to {VERSION}"
        ));
    }
    let time = r.f64()?;
    // inputs by name (version 2: its fixed list); an input the state lacks keeps its start
    let mut inputs = In::ALL.map(|i| i.start());
    let names: Vec<String> = In::ALL.iter().map(|i| i.name()).collect();
    read_named(&mut r, v, &V2_INPUTS, &names, "an input", |r, i| {
        inputs[i] = r.f64()?;
        Ok(())
    })?;
    let mut st = Settings {
        model: r.str()?,
        model_set: r.bool()?,
        preset: r.str()?,
        config_file: r.str()?,
        columns: r.str()?,
        ..Settings::default()
    };
    // set parameters and effects: by name from version 5, by index before; either way an
    // entry that comes twice is refused
    let n = r.u32()?;
    let mut seen = std::collections::HashSet::new();
    for _ in 0..n {
        let p = if v >= 5 {
            param_named(&r.str()?)?
        } else {
            let i = r.u32()?;
            param_of_vr(100 + i).ok_or_else(|| format!("bad parameter index {i}"))?
        };
        once(&mut seen, "the set parameter", params::spec(p).name)?;
        st.params.insert(p, r.f64()?);
    }
    let n = r.u32()?;
    let mut seen = std::collections::HashSet::new();
    for _ in 0..n {
        let e = if v >= 5 {
            effect_named(&r.str()?)?
        } else {
            let i = r.u8()?;
            effect_of_vr(50 + i as u32).ok_or_else(|| format!("bad effect index {i}"))?
        };
        once(&mut seen, "the set effect", effects::info(e).name)?;
        st.effects.insert(e, r.bool()?);
    }
    let nx = r.u32()? as usize;
    let ny = r.u32()? as usize;
    st.nx = (nx > 0).then_some(nx);
    st.ny = (ny > 0).then_some(ny);
    st.geometry = r.i32()?;
    let names: Vec<String> = Geo::ALL.iter().map(|g| g.name().to_string()).collect();
    read_named(
        &mut r,
        v,
        &V2_GEO,
        &names,
        "a geometry parameter",
        |r, g| {
            let present = r.bool()?;
            let x = r.f64()?;
            st.geo[g] = present.then_some(x);
            Ok(())
        },
    )?;
    let cfg = if r.bool()? {
        Some(get_config(&mut r, v)?)
    } else {
        None
    };
    let model = if r.bool()? {
        let bytes = r.bytes()?;
        let cfg = cfg
            .as_ref()
            .ok_or_else(|| "a model state without a configuration".to_string())?;
        let mut m = Model::new(cfg).map_err(|e| e.to_string())?;
        // formula/custom effects read their data columns when the inputs are restored
        if let Some(x) = extras_for(cfg, &st.columns, &inputs)? {
            m.set_extra(&x).map_err(|e| e.to_string())?;
        }
        m.load_state(bytes).map_err(|e| e.to_string())?;
        Some(m)
    } else {
        None
    };
    let phase = if v >= 4 {
        phase_of(r.u8()?)?
    } else if model.is_some() {
        Phase::StepComplete
    } else {
        Phase::Instantiated
    };
    let tol_scheme = if v >= 6 {
        match r.u8()? {
            255 => None,
            c => Some(scheme_of_byte(c, v).ok_or_else(|| format!("bad scheme code {c}"))?),
        }
    } else {
        None
    };
    if r.position() != data.len() {
        return Err(format!("{} trailing bytes", data.len() - r.position()));
    }
    let snap = Snapshot {
        settings: st,
        inputs,
        time,
        cfg,
        model,
        phase,
        tol_scheme,
    };
    validate_snapshot(&snap).map_err(|e| format!("invalid state: {e}"))?;
    Ok(snap)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::instance::{Instance, Status};

    fn last_name() -> String {
        In::ALL[N_INPUTS - 1].name()
    }

    #[test]
    fn inputs_and_geometry_are_stored_by_name() {
        // version 2's fixed lists name today's inputs and geometry parameters
        for n in V2_INPUTS {
            assert!(In::ALL.iter().any(|i| i.name() == n), "{n}");
        }
        for n in V2_GEO {
            assert!(Geo::ALL.iter().any(|g| g.name() == n), "{n}");
        }
        let mut i = Instance::new("t", None, false);
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.exit_initialization(), Status::Ok);
        assert_eq!(
            i.set_real(
                crate::vars::table()
                    .iter()
                    .find(|v| v.name == last_name())
                    .unwrap()
                    .vr,
                7.5,
            ),
            Status::Ok
        );
        let snap = i.get_state();
        let mut bytes = serialize(&snap);
        let back = deserialize(&bytes).expect("round trip");
        assert_eq!(serialize(&back), bytes);
        // a state of a build with one input less (here: without the last one) loads, that
        // input at its start value; a name this build does not know is refused
        let last = In::ALL[N_INPUTS - 1];
        let tail = {
            let mut w = W::new();
            w.str(&last.name());
            w.f64(snap.inputs[N_INPUTS - 1]);
            w.into_inner()
        };
        let at = bytes
            .windows(tail.len())
            .position(|w| w == tail.as_slice())
            .expect("the last input in the state");
        let mut short = bytes[..at].to_vec();
        short.extend_from_slice(&bytes[at + tail.len()..]);
        // the count before the first input: 8 magic + 4 version + 8 time
        short[20..24].copy_from_slice(&((N_INPUTS - 1) as u32).to_le_bytes());
        let s = deserialize(&short).expect("a state without the last input loads");
        assert_eq!(snap.inputs[N_INPUTS - 1], 7.5);
        assert_eq!(s.inputs[N_INPUTS - 1], last.start());
        let name_at = at + 4; // the name's bytes after its length
        bytes[name_at] = b'#';
        let e = deserialize(&bytes).unwrap_err();
        assert!(e.contains("does not know"), "{e}");
    }

    #[test]
    fn the_configurations_scheme_is_its_last_byte_version_7_coded_cells_0_and_version_6_has_cells()
    {
        use creep_core::engine::Scheme;
        let cfg = Config::from_json_str(r#"{"preset": "dry", "scheme": "cells-ho"}"#, "x").unwrap();
        let mut w = W::new();
        put_config(&mut w, &cfg);
        let bytes = w.into_inner();
        assert_eq!(bytes.last(), Some(&2));
        let mut r = R::new(&bytes);
        assert_eq!(get_config(&mut r, VERSION).unwrap(), cfg);
        assert_eq!(r.position(), bytes.len());
        // version 6 wrote no scheme byte: the same configuration, cell by cell
        let v6 = &bytes[..bytes.len() - 1];
        let mut r = R::new(v6);
        let old = get_config(&mut r, 6).unwrap();
        assert_eq!((old.scheme, r.position()), (Scheme::CellsMarch, v6.len()));
        assert_eq!(
            Config {
                scheme: cfg.scheme,
                ..old
            },
            cfg
        );
        // a code no scheme has is refused
        let mut bad = bytes.clone();
        *bad.last_mut().unwrap() = 7;
        let e = get_config(&mut R::new(&bad), VERSION).unwrap_err();
        assert!(e.contains("scheme code 7"), "{e}");
        // cell by cell is 3 since version 8 and was 0 in version 7, where 3 meant nothing
        let mut cells = bytes.clone();
        *cells.last_mut().unwrap() = 3;
        assert_eq!(
            get_config(&mut R::new(&cells), VERSION).unwrap().scheme,
            Scheme::CellsMarch
        );
        assert!(get_config(&mut R::new(&cells), 7).is_err());
        *cells.last_mut().unwrap() = 0;
        assert_eq!(
            get_config(&mut R::new(&cells), 7).unwrap().scheme,
            Scheme::CellsMarch
        );
        assert!(get_config(&mut R::new(&cells), VERSION).is_err());
    }

    #[test]
    fn round_trip_continues_bit_for_bit_and_corruption_is_refused() {
        let mut i = Instance::new("t", None, false);
        let vr = |n: &str| {
            crate::vars::table()
                .iter()
                .find(|v| v.name == n)
                .unwrap()
                .vr
        };
        assert_eq!(i.set_integer(vr("nx"), 12), Status::Ok);
        assert_eq!(i.set_real(vr("mu"), 0.3), Status::Ok);
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.exit_initialization(), Status::Ok);
        assert_eq!(i.set_real(vr("cx"), 0.02), Status::Ok);
        assert_eq!(i.do_step(0.0, 1e-3), Status::Ok);
        let bytes = serialize(&i.get_state());
        let snap = deserialize(&bytes).unwrap();
        assert_eq!(serialize(&snap), bytes);
        assert_eq!(i.do_step(1e-3, 1e-3), Status::Ok);
        let fx1 = i.get_real(vr("Fx")).unwrap();
        assert_eq!(i.set_state(&snap), Status::Ok);
        assert_eq!(i.do_step(1e-3, 1e-3), Status::Ok);
        assert_eq!(i.get_real(vr("Fx")).unwrap().to_bits(), fx1.to_bits());
        for cut in [0, 7, 12, bytes.len() / 2, bytes.len() - 1] {
            assert!(deserialize(&bytes[..cut]).is_err(), "cut at {cut}");
        }
        let mut bad = bytes.clone();
        bad[8] = 99;
        assert!(deserialize(&bad).unwrap_err().contains("version 99"));
        let mut longer = bytes.clone();
        longer.push(0);
        assert!(deserialize(&longer).unwrap_err().contains("trailing"));
        // a state whose area fractions do not sum to 1 is refused (the model's invariant):
        // the stored elastic fraction, found by its bit pattern, raised by 0.25
        let fe = snap.model.as_ref().unwrap().outputs().frac_elastic;
        let pat = fe.to_le_bytes();
        let at: Vec<usize> = (0..bytes.len() - 8)
            .filter(|&k| bytes[k..k + 8] == pat)
            .collect();
        assert!(
            !at.is_empty(),
            "the elastic fraction {fe} is stored in the state"
        );
        // raised by 0.25, and by 1e-7 (a flipped low mantissa bit: the fuzzer's find, accepted
        // while the sum was allowed 1e-6 off)
        for d in [0.25, 1e-7] {
            let mut odd = bytes.clone();
            for &k in &at {
                odd[k..k + 8].copy_from_slice(&(fe + d).to_le_bytes());
            }
            let e = deserialize(&odd).unwrap_err();
            assert!(e.contains("area fractions"), "+{d}: {e}");
        }
    }

    /// An initialized instance with a parameter (tau_c1_0_GPa = 0.35) and an effect
    /// (elastic unloading) set, so that its state holds both lists.
    fn initialized_with_a_parameter_and_an_effect() -> Instance {
        let mut i = Instance::new("t", None, false);
        let vr = |n: &str| {
            crate::vars::table()
                .iter()
                .find(|v| v.name == n)
                .unwrap()
                .vr
        };
        assert_eq!(i.set_real(vr("tau_c1_0_GPa"), 0.35), Status::Ok);
        assert_eq!(
            i.set_boolean(vr("effect_elastic_unloading"), true),
            Status::Ok
        );
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.exit_initialization(), Status::Ok);
        i
    }

    #[test]
    fn parameters_and_effects_are_stored_by_name() {
        let mut i = initialized_with_a_parameter_and_an_effect();
        let snap = i.get_state();
        let bytes = serialize(&snap);
        let entry = |name: &str| {
            let mut w = W::new();
            w.str(name);
            w.into_inner()
        };
        let find = |b: &[u8], name: &str| {
            let e = entry(name);
            b.windows(e.len()).position(|w| w == e.as_slice())
        };
        // a parameter or effect this build does not know is refused with its name
        for name in ["tau_c1_0_GPa", "elastic_unloading"] {
            let at = find(&bytes, name).expect(name);
            let mut odd = bytes.clone();
            odd[at + 4] = b'#';
            let e = deserialize(&odd).unwrap_err();
            assert!(e.contains(&format!("'#{}'", &name[1..])), "{e}");
        }
        // a configuration of a build without the last parameter: it keeps its default
        let last = params::SPECS[params::SPECS.len() - 1];
        let first = find(&bytes, params::SPECS[0].name).expect("the first parameter");
        let at = find(&bytes, last.name).expect("the last parameter");
        let mut short = bytes[..at].to_vec();
        short.extend_from_slice(&bytes[at + entry(last.name).len() + 8..]);
        let n = u32::from_le_bytes(bytes[first - 4..first].try_into().unwrap());
        assert_eq!(n as usize, params::SPECS.len());
        short[first - 4..first].copy_from_slice(&(n - 1).to_le_bytes());
        let s = deserialize(&short).expect("a state without the last parameter loads");
        let cfg = s.cfg.expect("a configuration");
        assert_eq!(cfg.params.get(last.id), last.default);
        assert_eq!(cfg.params.get(P::Tc10), 0.35);
        assert!(cfg.effects.has(Effect::ElasticUnloading));
    }

    /// A list stored by name that holds a name twice is refused with that name (a reader
    /// where the last one wins would load such a corrupted state silently).
    #[test]
    fn a_name_stored_twice_is_refused() {
        let mut i = initialized_with_a_parameter_and_an_effect();
        let bytes = serialize(&i.get_state());
        assert!(deserialize(&bytes).is_ok());
        let name = |n: &str| {
            let mut w = W::new();
            w.str(n);
            w.into_inner()
        };
        let find = |n: &str| {
            let e = name(n);
            bytes
                .windows(e.len())
                .position(|w| w == e.as_slice())
                .unwrap_or_else(|| panic!("{n} in the state"))
        };
        // the entry at `at` (`len` bytes) a second time, the count at `count_at` one more
        let twice = |at: usize, len: usize, count_at: usize| {
            let mut b = bytes[..at + len].to_vec();
            b.extend_from_slice(&bytes[at..]);
            let n = u32::from_le_bytes(bytes[count_at..count_at + 4].try_into().unwrap());
            b[count_at..count_at + 4].copy_from_slice(&(n + 1).to_le_bytes());
            b
        };
        let first_input = In::ALL[0].name();
        let first_param = params::SPECS[0].name;
        let at_param = {
            // the configuration's parameter list (the set parameters come first)
            let e = name(first_param);
            bytes
                .windows(e.len())
                .rposition(|w| w == e.as_slice())
                .expect("the first parameter in the configuration")
        };
        let cases = [
            // the inputs: their count after magic, version, time
            (
                twice(24, name(&first_input).len() + 8, 20),
                format!("an input '{first_input}' twice"),
            ),
            // the set parameters, one of them: its count just before it
            (
                twice(
                    find("tau_c1_0_GPa"),
                    name("tau_c1_0_GPa").len() + 8,
                    find("tau_c1_0_GPa") - 4,
                ),
                "the set parameter 'tau_c1_0_GPa' twice".to_string(),
            ),
            (
                twice(
                    find("elastic_unloading"),
                    name("elastic_unloading").len() + 1,
                    find("elastic_unloading") - 4,
                ),
                "the set effect 'elastic_unloading' twice".to_string(),
            ),
            // the geometry values: the first of them, its count just before it
            (
                twice(
                    find(Geo::ALL[0].name()),
                    name(Geo::ALL[0].name()).len() + 9,
                    find(Geo::ALL[0].name()) - 4,
                ),
                format!("a geometry parameter '{}' twice", Geo::ALL[0].name()),
            ),
            (
                twice(at_param, name(first_param).len() + 8, at_param - 4),
                format!("the configuration's parameter '{first_param}' twice"),
            ),
        ];
        for (b, want) in cases {
            let e = deserialize(&b).expect_err(&want);
            assert!(e.contains(&want), "{want}: {e}");
        }
    }
}
