//! The contact's complete hidden state as module [`crate::state`] serializes it: borrowed out of a [`Contact`] and restored into one, with its checks.

use super::{Contact, Inputs, Outputs, Partial};
use crate::bristle::BristleState;
use crate::error::{CreepError, Result};
use crate::thermal::N_KERNEL;

/// The complete hidden state of a [`Contact`], borrowed for serialization
/// ([`Contact::raw_state`], module [`crate::state`]). The grid, `inputs` and `out` are those
/// of the frame the contact rolls forwards in (mirrored x -> -x while `reversed`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct RawState<'a> {
    /// Simulated time since start, s.
    pub time: f64,
    /// Last inputs, forward frame (v >= 0; units in [`Inputs`]).
    pub inputs: Inputs,
    /// Ring-buffer head per strip (`ny` values, each in 0..=nx): storage slot of the
    /// bristle nearest the leading edge.
    pub head: &'a [usize],
    /// Phase per strip (`ny` values in [0, 1)), in cells: how far the strip's bristles have
    /// moved since the last one entered at the leading edge (Eq. 4.17).
    pub phase: &'a [f64],
    /// Bristle states, `ny * (nx + 1)`, index `j * (nx + 1) + storage slot` (units in
    /// [`BristleState`]).
    pub st: &'a [BristleState],
    /// Heat-kernel accumulators A_k per bristle (same index as `st`), J/m^2: the bristle's
    /// frictional heat density history q (W/m^2, both bodies) weighted by exp(-s_k age)
    /// (module [`crate::thermal`]); `[0]` is all heat ever received.
    pub acc: &'a [[f64; N_KERNEL]],
    /// The bristles' states and accumulators at their last lattice node (same index and
    /// units as `st`, `acc`): the committed state of the whole-cell commit, from which the
    /// next step moves each bristle over its whole current cell.
    pub node_st: &'a [BristleState],
    /// Their heat-kernel accumulators at that node, J/m^2.
    pub node_acc: &'a [[f64; N_KERNEL]],
    /// Per strip, the part of the current cell travelled since that node ([`Partial`]).
    pub part: &'a [Partial],
    /// True once a step or steady state has set the grid (false: the next step starts
    /// from the steady state of its inputs).
    pub initialized: bool,
    /// Last outputs, forward frame (units in [`Outputs`]).
    pub out: Outputs,
    /// Rolling backwards (the last non-zero speed was negative), -.
    pub reversed: bool,
}

/// The owned counterpart of [`RawState`], read from bytes and handed to
/// [`Contact::set_raw_state`]; the fields mean the same, with the same units.
#[derive(Clone, Debug)]
pub(crate) struct OwnedRawState {
    /// Simulated time since start, s.
    pub time: f64,
    /// Last inputs, forward frame (v >= 0).
    pub inputs: Inputs,
    /// Ring-buffer head per strip (`ny` values in 0..=nx).
    pub head: Vec<usize>,
    /// Phase per strip (`ny` values in [0, 1)), cells (Eq. 4.17).
    pub phase: Vec<f64>,
    /// Bristle states, `ny * (nx + 1)`.
    pub st: Vec<BristleState>,
    /// Heat-kernel accumulators per bristle, J/m^2.
    pub acc: Vec<[f64; N_KERNEL]>,
    /// The node states, node accumulators and per-strip parts of [`RawState`]; None for a
    /// state saved before the whole-cell commit (format version 3 and older): its bristles
    /// then count as at their node, and their next move ends the current cell.
    pub nodes: Option<NodeStates>,
    /// True once a step or steady state has set the grid.
    pub initialized: bool,
    /// Last outputs, forward frame.
    pub out: Outputs,
    /// Rolling backwards, -.
    pub reversed: bool,
}

/// The committed node states, node accumulators and per-strip parts of a contact's grid
/// ([`RawState`]).
pub(crate) type NodeStates = (Vec<BristleState>, Vec<[f64; N_KERNEL]>, Vec<Partial>);
impl Contact {
    /// The complete hidden state, borrowed for serialization (module [`crate::state`]).
    pub(crate) fn raw_state(&self) -> RawState<'_> {
        RawState {
            time: self.time,
            inputs: self.inputs,
            head: &self.head,
            phase: &self.phase,
            st: &self.st,
            acc: &self.acc,
            node_st: &self.node_st,
            node_acc: &self.node_acc,
            part: &self.part,
            initialized: self.initialized,
            out: self.out,
            reversed: self.reversed,
        }
    }

    /// Restores a state read by module [`crate::state`]; checks the sizes, the ring-buffer
    /// heads and phases and that the inputs are in the forward frame.
    pub(crate) fn set_raw_state(&mut self, state: OwnedRawState) -> Result<()> {
        let OwnedRawState {
            time,
            inputs,
            head,
            phase,
            st,
            acc,
            nodes,
            initialized,
            out,
            reversed,
        } = state;
        if head.len() != self.ny
            || phase.len() != self.ny
            || st.len() != self.st.len()
            || acc.len() != self.acc.len()
        {
            return Err(CreepError::State(format!(
                "grid mismatch: state has {} strips / {} bristles, contact has {} / {}",
                head.len(),
                st.len(),
                self.ny,
                self.st.len()
            )));
        }
        if head.iter().any(|&h| h > self.nx) || phase.iter().any(|p| !(0.0..1.0).contains(p)) {
            return Err(CreepError::State(
                "corrupt ring-buffer head or phase".into(),
            ));
        }
        if inputs.v < 0.0 {
            return Err(CreepError::State(
                "negative speed in a state (its inputs are held in the forward frame)".into(),
            ));
        }
        if let Some((ns, na, part)) = &nodes {
            if ns.len() != st.len() || na.len() != acc.len() || part.len() != self.ny {
                return Err(CreepError::State(format!(
                    "grid mismatch: state has {} node bristles / {} strip parts, contact has {} / {}",
                    ns.len(),
                    part.len(),
                    self.st.len(),
                    self.ny
                )));
            }
        }
        self.time = time;
        self.reversed = reversed;
        self.set_inputs(&inputs)?;
        self.head = head;
        self.phase = phase;
        self.st = st;
        self.acc = acc;
        match nodes {
            Some((ns, na, part)) => {
                self.node_st = ns;
                self.node_acc = na;
                self.part = part;
            }
            None => self.reset_nodes(),
        }
        self.initialized = initialized;
        self.out = out;
        self.node_acc_zero = false;
        self.set_mirrored(self.strips_equal());
        Ok(())
    }
}
