//! Readers of the state formats of earlier builds, versions 1 to 3 (read, not written), and what their configurations leave unsaid.
//!
//! Versions 1 and 2 stored the 6 inputs and 13 outputs without names, in the order of their
//! value references (1 to 6 and 10 to 22; released value references never change);
//! version 1 had only flag bit 0 (initialized). Versions 1 to 3 stored no node states: their
//! bristles count as at their node, and their next move ends the current cell.
//! Configurations saved before they had a `scheme` ran cell by cell.

use crate::engine::grid_state::{set_input, set_output, RunState, StateReader};
use crate::engine::io::{INPUTS, OUTPUTS};
use crate::engine::{Inputs, Outputs};
use crate::error::{CreepError, Result};
use serde_json::Value;

/// Names of the values with value references in `vrs` in ascending order: the layout of
/// versions 1 and 2.
fn by_vr(
    specs: impl Iterator<Item = (&'static str, u32)>,
    vrs: std::ops::RangeInclusive<u32>,
) -> Vec<&'static str> {
    let mut v: Vec<_> = specs.filter(|(_, vr)| vrs.contains(vr)).collect();
    v.sort_by_key(|(_, vr)| *vr);
    v.into_iter().map(|(name, _)| name).collect()
}

/// Reads the values of `names` without names, in their order; `set(name, value)` is false
/// for a name this build lacks (`what`: "input"), which is refused.
fn get_unnamed(
    r: &mut StateReader,
    names: &[&str],
    what: &str,
    mut set: impl FnMut(&str, f64) -> bool,
) -> Result<()> {
    for name in names {
        let x = r.f()?;
        if !set(name, x) {
            return Err(CreepError::State(format!(
                "this build has no {what} '{name}'"
            )));
        }
    }
    Ok(())
}

/// Reads the run state of a state of version `v` (1 to 3): version 3 is laid out as today.
pub(super) fn read_run(r: &mut StateReader, v: u32) -> Result<RunState> {
    if v >= 3 {
        return RunState::read(r);
    }
    let time = r.f()?;
    let mut inputs = Inputs::default();
    let names = by_vr(INPUTS.iter().map(|s| (s.name, s.vr)), 1..=6);
    get_unnamed(r, &names, "input", |n, x| set_input(&mut inputs, n, x))?;
    let mut out = Outputs::default();
    let names = by_vr(OUTPUTS.iter().map(|s| (s.name, s.vr)), 10..=22);
    get_unnamed(r, &names, "output", |n, x| set_output(&mut out, n, x))?;
    let flags = r.b()?;
    RunState::checked(time, inputs, out, flags, if v == 1 { 1 } else { 3 })
}

/// The configuration's JSON with a `scheme`: a configuration saved without one ran cell by
/// cell (any other text is returned as it is, for the reader's message).
pub(super) fn with_scheme(json: &str) -> std::borrow::Cow<'_, str> {
    /// The top-level key `scheme`, if any (the rest skipped unparsed).
    #[derive(serde::Deserialize)]
    struct Scheme {
        scheme: Option<serde::de::IgnoredAny>,
    }
    if let Ok(Scheme { scheme: None }) = serde_json::from_str(json) {
        if let Ok(Value::Object(mut o)) = serde_json::from_str::<Value>(json) {
            o.insert("scheme".into(), Value::String("cells".into()));
            return Value::Object(o).to_string().into();
        }
    }
    json.into()
}
