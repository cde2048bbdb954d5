//! Readers of the FMU state formats of earlier builds, versions 2 to 8 (read, not written); each layout as it was written.
//!
//! Version 8: after magic and version, f64 time, u32 count + per input (name, f64), settings
//! (model, u8 model_set, preset, config_file, columns, set parameters as u32 count and
//! (name, f64) each, set effects as u32 count and (name, u8) each, nx, ny as u32 (0 = not
//! set), i32 geometry, u32 count + per geometry parameter (name, u8 present, f64)), u8 +
//! configuration (u8 model, u32 count + names of the effects on, u32 count + (name, f64) per
//! parameter, u8 bound, u32 nx, u32 ny, u8 geometry kind + 3 x f64, preset name, u8 + (if
//! formula or Rust effects) the configuration as JSON and, per formula then Rust effect, u32
//! count + f64 parameter values, u8 the configuration's scheme as the code of the parameter
//! `scheme`), u8 + u32 length + the bytes of `creep_core::Model::save_state`, u8 the mode,
//! u8 the scheme `rel_tol` chose (255: none).
//! Version 7 wrote the scheme codes of its day, 0 for cell by cell (today 3; 1 and 2 are
//! the same); version 6 had no scheme byte in the configuration (cells); version 5 had no
//! scheme byte at the end either (none chose one).
//! Version 4 stored parameters as (u32, f64) and effects as (u8, u8) by index, the
//! configuration's effects as u32 bits and its parameters as a count (26) and values, each
//! index k the parameter with value reference 100 + k, the effect with value reference
//! 50 + k; versions 2 and 3 had no mode byte (a state holding a model is in StepComplete,
//! else Instantiated); version 2 stored the 10 inputs and 5 geometry values without names,
//! in the fixed orders `V2_INPUTS`, `V2_GEO`.
//! The configuration's temperature solve is not stored (the restoring instance's applies).

use super::{once, phase_of};
use crate::instance::{Phase, Snapshot};
use crate::settings::{extras_for, Settings};
use crate::vars::{Geo, In};
use creep_core::bytes::Reader;
#[cfg(test)]
use creep_core::bytes::Writer;
use creep_core::effects::{self, Effect, EffectSet};
use creep_core::params::{self, Params, P};
use creep_core::{AnyModifier, Bound, Config, Geometry, Grid, Model, ModelKind, Modifier};

/// The inputs of format version 2, in its fixed order (version 3 stores each with its name).
const V2_INPUTS: [&str; 10] = [
    "cx", "cy", "spin", "v", "FN", "T_bulk", "aux1", "aux2", "aux3", "aux4",
];
/// The geometry parameters of format version 2, in its fixed order.
const V2_GEO: [&str; 5] = ["a_ref", "b_ref", "FN_ref", "Rx", "Ry"];

#[cfg(test)]
type W = Writer;
type R<'a> = Reader<'a>;

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

/// Writes a configuration as version 8 did (for the tests of the reader).
#[cfg(test)]
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

/// Reads what follows the version `v` (2 to 8) in a state of that format.
pub(super) fn read(r: &mut R, v: u32) -> Result<Snapshot, String> {
    let time = r.f64()?;
    // inputs by name (version 2: its fixed list); an input the state lacks keeps its start
    let mut inputs = In::ALL.map(|i| i.start());
    let names: Vec<String> = In::ALL.iter().map(|i| i.name()).collect();
    read_named(r, v, &V2_INPUTS, &names, "an input", |r, i| {
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
    read_named(r, v, &V2_GEO, &names, "a geometry parameter", |r, g| {
        let present = r.bool()?;
        let x = r.f64()?;
        st.geo[g] = present.then_some(x);
        Ok(())
    })?;
    let cfg = if r.bool()? {
        Some(get_config(r, v)?)
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
    Ok(Snapshot {
        settings: st,
        inputs,
        time,
        cfg,
        model,
        phase,
        tol_scheme,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn version_2s_fixed_lists_name_todays_inputs_and_geometry_parameters() {
        for n in V2_INPUTS {
            assert!(In::ALL.iter().any(|i| i.name() == n), "{n}");
        }
        for n in V2_GEO {
            assert!(Geo::ALL.iter().any(|g| g.name() == n), "{n}");
        }
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
        assert_eq!(get_config(&mut r, 8).unwrap(), cfg);
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
        let e = get_config(&mut R::new(&bad), 8).unwrap_err();
        assert!(e.contains("scheme code 7"), "{e}");
        // cell by cell is 3 since version 8 and was 0 in version 7, where 3 meant nothing
        let mut cells = bytes.clone();
        *cells.last_mut().unwrap() = 3;
        assert_eq!(
            get_config(&mut R::new(&cells), 8).unwrap().scheme,
            Scheme::CellsMarch
        );
        assert!(get_config(&mut R::new(&cells), 7).is_err());
        *cells.last_mut().unwrap() = 0;
        assert_eq!(
            get_config(&mut R::new(&cells), 7).unwrap().scheme,
            Scheme::CellsMarch
        );
        assert!(get_config(&mut R::new(&cells), 8).is_err());
    }
}
