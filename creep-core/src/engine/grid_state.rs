//! The grid's state: exactly what a contact saves and restores, with its byte layout, its reader and its checks.
//!
//! Module [`crate::state`] frames it (magic, version, configuration); the layout from the
//! time on is [`RunState::write`] then, for bristle models, [`GridState::write`]. States of
//! earlier formats are read by `crate::state::legacy`.

use super::io::{INPUTS, OUTPUTS};
use super::{Inputs, Outputs, Partial};
use crate::bristle::{BristleState, Regime};
use crate::bytes::{Reader, Writer};
use crate::error::{CreepError, Result};
use crate::thermal::N_KERNEL;

/// The shared byte reader with the model's error type.
pub(crate) struct StateReader<'a>(pub Reader<'a>);

impl StateReader<'_> {
    /// An f64.
    pub fn f(&mut self) -> Result<f64> {
        self.0.f64().map_err(CreepError::State)
    }
    /// A u32.
    pub fn u(&mut self) -> Result<u32> {
        self.0.u32().map_err(CreepError::State)
    }
    /// A byte.
    pub fn b(&mut self) -> Result<u8> {
        self.0.u8().map_err(CreepError::State)
    }
    /// A length-prefixed string.
    pub fn s(&mut self) -> Result<String> {
        self.0.str().map_err(CreepError::State)
    }
    /// `n` bytes as they are.
    pub fn take(&mut self, n: usize) -> Result<&[u8]> {
        self.0.take(n).map_err(CreepError::State)
    }
}

/// What every model's state holds: the time, the last inputs and outputs and two flags.
/// While the contact rolls backwards, inputs and outputs are those of its mirrored frame,
/// where it rolls forwards.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct RunState {
    /// Simulated time since start, s.
    pub time: f64,
    /// Last inputs, forward frame (v >= 0; units in [`Inputs`]).
    pub inputs: Inputs,
    /// Last outputs, forward frame (units in [`Outputs`]).
    pub out: Outputs,
    /// True once a step or steady state has set the grid (false: the next step starts from
    /// the steady state of its inputs).
    pub initialized: bool,
    /// Rolling backwards (the last non-zero speed was negative).
    pub reversed: bool,
}

/// The state of a contact's bristle grid: [`RunState`] and the bristles. Index of a
/// bristle: `j * (nx + 1) + storage slot` for strip `j`.
#[derive(Clone, Debug)]
pub(crate) struct GridState {
    /// Time, inputs, outputs and flags.
    pub run: RunState,
    /// Ring-buffer head per strip (`ny` values, each in 0..=nx): storage slot of the bristle
    /// nearest the leading edge.
    pub head: Vec<usize>,
    /// Phase per strip (`ny` values in [0, 1)), in cells: how far the strip's bristles have
    /// moved since the last one entered at the leading edge (Eq. 4.17).
    pub phase: Vec<f64>,
    /// Bristle states, `ny * (nx + 1)` (units in [`BristleState`]), at the strip's phase.
    pub st: Vec<BristleState>,
    /// Heat-kernel accumulators A_k per bristle (same index as `st`), J/m^2: the bristle's
    /// frictional heat density history q (W/m^2, both bodies) weighted by exp(-s_k age)
    /// (module [`crate::thermal`]); `[0]` is all heat ever received.
    pub acc: Vec<[f64; N_KERNEL]>,
    /// The bristles' states at their last lattice node (same index and units as `st`): the
    /// committed state of the whole-cell commit, from which the next step moves each bristle
    /// over its whole current cell.
    pub node_st: Vec<BristleState>,
    /// Their heat-kernel accumulators at that node, J/m^2.
    pub node_acc: Vec<[f64; N_KERNEL]>,
    /// Per strip, the part of the current cell travelled since that node ([`Partial`]).
    pub part: Vec<Partial>,
}

fn put_inputs(w: &mut Writer, i: &Inputs) {
    w.u32(INPUTS.len() as u32);
    for s in INPUTS {
        w.str(s.name);
        w.f64((s.get)(i));
    }
}

fn put_outputs(w: &mut Writer, o: &Outputs) {
    w.u32(OUTPUTS.len() as u32);
    for s in OUTPUTS {
        w.str(s.name);
        w.f64((s.get)(o));
    }
}

/// Reads values stored by name: a u32 count, then per value its name and f64. `set(name,
/// value)` is false for a name this build does not know (`what`: "an input"), which is
/// refused, as is a name stored twice.
fn get_named(
    r: &mut StateReader,
    what: &str,
    mut set: impl FnMut(&str, f64) -> bool,
) -> Result<()> {
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

/// Sets the input `name` of `i` to `x`; false for a name this build does not know.
pub(crate) fn set_input(i: &mut Inputs, name: &str, x: f64) -> bool {
    match INPUTS.iter().find(|s| s.name == name) {
        Some(s) => {
            (s.set)(i, x);
            true
        }
        None => false,
    }
}

/// Sets the output `name` of `o` to `x`; false for a name this build does not know.
pub(crate) fn set_output(o: &mut Outputs, name: &str, x: f64) -> bool {
    match OUTPUTS.iter().find(|s| s.name == name) {
        Some(s) => {
            (s.set)(o, x);
            true
        }
        None => false,
    }
}

impl RunState {
    /// Writes time f64, inputs and then outputs each as u32 count + per value its name (u32
    /// length + UTF-8, the name of [`INPUTS`] or [`OUTPUTS`]) and f64, and the flags u8 (bit
    /// 0: initialized, bit 1: rolling backwards).
    pub fn write(&self, w: &mut Writer) {
        w.f64(self.time);
        put_inputs(w, &self.inputs);
        put_outputs(w, &self.out);
        w.u8(self.initialized as u8 | (self.reversed as u8) << 1);
    }

    /// Reads what [`RunState::write`] wrote, refusing non-finite values and inputs out of
    /// their ranges.
    pub fn read(r: &mut StateReader) -> Result<RunState> {
        let time = r.f()?;
        let mut inputs = Inputs::default();
        get_named(r, "an input", |n, x| set_input(&mut inputs, n, x))?;
        let mut out = Outputs::default();
        get_named(r, "an output", |n, x| set_output(&mut out, n, x))?;
        let flags = r.b()?;
        RunState::checked(time, inputs, out, flags, 3)
    }

    /// The run state of the values read, checked: `flags` at most `max_flags`, finite
    /// values, inputs in their ranges.
    pub fn checked(
        time: f64,
        inputs: Inputs,
        out: Outputs,
        flags: u8,
        max_flags: u8,
    ) -> Result<RunState> {
        if flags > max_flags {
            return Err(CreepError::State(format!("bad flags byte {flags}")));
        }
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
        Ok(RunState {
            time,
            inputs,
            out,
            initialized: flags & 1 != 0,
            reversed: flags & 2 != 0,
        })
    }
}

/// Writes bristle states (u(2) tau(2) sh temp q as 7 x f64 and the regime byte each) and
/// then their accumulators (K x f64 each).
fn put_bristles(w: &mut Writer, st: &[BristleState], acc: &[[f64; N_KERNEL]]) {
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
    r: &mut StateReader,
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

impl GridState {
    /// The grid of a new contact: `ny` strips of `nx + 1` unloaded bristles at phase 0.
    pub fn new(nx: usize, ny: usize) -> Self {
        let n = ny * (nx + 1);
        GridState {
            run: RunState::default(),
            head: vec![0; ny],
            phase: vec![0.0; ny],
            st: vec![BristleState::default(); n],
            acc: vec![[0.0; N_KERNEL]; n],
            node_st: vec![BristleState::default(); n],
            node_acc: vec![[0.0; N_KERNEL]; n],
            part: vec![Partial::default(); ny],
        }
    }

    /// Takes the bristles where they are as their committed node states, with nothing of
    /// the current cell travelled since.
    pub fn reset_nodes(&mut self) {
        self.node_st.copy_from_slice(&self.st);
        self.node_acc.copy_from_slice(&self.acc);
        self.part.iter_mut().for_each(|p| *p = Partial::default());
    }

    /// Writes [`RunState::write`] and then nx u32, ny u32, kernel size u32, heads ny x u32,
    /// phases ny x f64, the bristles (`put_bristles`), the node bristles in the same layout
    /// and per strip the part of the current cell: distance (m), time (s) and the
    /// distance-weighted c_x, c_y (m) and spin (-) as 5 x f64.
    pub fn write(&self, w: &mut Writer, (nx, ny): (usize, usize)) {
        self.run.write(w);
        // per bristle 7 f64 and a byte and K f64, twice (node states); per strip a head,
        // a phase and 5 f64
        let nb = ny * (nx + 1);
        w.reserve(12 + 2 * nb * (57 + 8 * N_KERNEL) + ny * (4 + 8 + 40));
        w.u32(nx as u32);
        w.u32(ny as u32);
        w.u32(N_KERNEL as u32);
        for h in &self.head {
            w.u32(*h as u32);
        }
        for p in &self.phase {
            w.f64(*p);
        }
        put_bristles(w, &self.st, &self.acc);
        put_bristles(w, &self.node_st, &self.node_acc);
        for p in &self.part {
            for x in [p.d, p.h, p.dcx, p.dcy, p.dcs] {
                w.f64(x);
            }
        }
    }

    /// Reads the grid [`GridState::write`] wrote after `run`, for a contact of grid
    /// `(nx, ny)`.
    pub fn read(r: &mut StateReader, run: RunState, grid: (usize, usize)) -> Result<GridState> {
        let mut g = GridState::read_bristles(r, run, grid)?;
        let nb = g.st.len();
        (g.node_st, g.node_acc) = get_bristles(r, nb, "node ")?;
        for (j, part) in g.part.iter_mut().enumerate() {
            let x = [r.f()?, r.f()?, r.f()?, r.f()?, r.f()?];
            if x.iter().any(|v| !v.is_finite()) || x[0] < 0.0 || x[1] < 0.0 {
                return Err(CreepError::State(format!(
                    "the part of the current cell of strip {j} is not a distance and a time ({x:?})"
                )));
            }
            *part = Partial {
                d: x[0],
                h: x[1],
                dcx: x[2],
                dcy: x[3],
                dcs: x[4],
            };
        }
        Ok(g)
    }

    /// Reads the grid up to and including the bristles (sizes, heads, phases, bristle
    /// states and heat histories), with the bristles as their own node states and nothing
    /// of the current cell travelled.
    pub fn read_bristles(
        r: &mut StateReader,
        run: RunState,
        grid: (usize, usize),
    ) -> Result<GridState> {
        let nx = r.u()? as usize;
        let ny = r.u()? as usize;
        let k = r.u()? as usize;
        if (nx, ny) != grid || k != N_KERNEL {
            return Err(CreepError::State(format!(
                "grid {nx}x{ny} (kernel {k}) does not match {grid:?} (kernel {N_KERNEL})"
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
        let (st, acc) = get_bristles(r, nb, "")?;
        Ok(GridState {
            run,
            head,
            phase,
            node_st: st.clone(),
            node_acc: acc.clone(),
            st,
            acc,
            part: vec![Partial::default(); ny],
        })
    }

    /// Checks a state for a contact of grid `(nx, ny)`: its sizes, the ring-buffer heads and
    /// phases, and that the inputs are in the forward frame.
    pub fn check(&self, (nx, ny): (usize, usize)) -> Result<()> {
        let nb = ny * (nx + 1);
        if self.head.len() != ny
            || self.phase.len() != ny
            || self.st.len() != nb
            || self.acc.len() != nb
        {
            return Err(CreepError::State(format!(
                "grid mismatch: state has {} strips / {} bristles, contact has {} / {}",
                self.head.len(),
                self.st.len(),
                ny,
                nb
            )));
        }
        if self.head.iter().any(|&h| h > nx) || self.phase.iter().any(|p| !(0.0..1.0).contains(p)) {
            return Err(CreepError::State(
                "corrupt ring-buffer head or phase".into(),
            ));
        }
        if self.run.inputs.v < 0.0 {
            return Err(CreepError::State(
                "negative speed in a state (its inputs are held in the forward frame)".into(),
            ));
        }
        if self.node_st.len() != nb || self.node_acc.len() != nb || self.part.len() != ny {
            return Err(CreepError::State(format!(
                "grid mismatch: state has {} node bristles / {} strip parts, contact has {} / {}",
                self.node_st.len(),
                self.part.len(),
                nb,
                ny
            )));
        }
        Ok(())
    }
}
