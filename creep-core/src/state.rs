//! Versioned, explicit byte format of a model's complete hidden state (bristle grid, heat histories) for save/restore.
//!
//! Layout (little endian): magic `ECFSTATE`, format version u32, config JSON (u32 length +
//! UTF-8), time f64, inputs 6 x f64, outputs 13 x f64, flags u8 (bit 0: initialized, bit 1:
//! rolling backwards; version 2 on, version 1 had only bit 0; for a contact rolling backwards
//! inputs, outputs and bristles are those of its mirrored frame), then for bristle
//! models: nx u32, ny u32, kernel size u32, heads ny x u32, phases ny x f64, per bristle
//! u(2) tau(2) sh temp q as 7 x f64 and regime u8, then the heat accumulators n x K x f64.
//! Restoring checks the magic, the version, the configuration and every size, so a state
//! from another configuration or a corrupt buffer is refused with a message, never misread.

use crate::bristle::{BristleState, Regime};
use crate::bytes::{Reader, Writer};
use crate::engine::{Inputs, Outputs, OwnedRawState};
use crate::error::{CreepError, Result};
use crate::model::Model;
use crate::thermal::N_KERNEL;

const MAGIC: &[u8; 8] = b"ECFSTATE";
/// Current version of the byte format.
pub const VERSION: u32 = 2;

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
    fn take(&mut self, n: usize) -> Result<&[u8]> {
        self.0.take(n).map_err(CreepError::State)
    }
}

fn put_inputs(w: &mut W, i: &Inputs) {
    for x in [i.cx, i.cy, i.spin, i.v, i.fn_n, i.t_bulk] {
        w.f64(x);
    }
}
fn get_inputs(r: &mut R) -> Result<Inputs> {
    Ok(Inputs {
        cx: r.f()?,
        cy: r.f()?,
        spin: r.f()?,
        v: r.f()?,
        fn_n: r.f()?,
        t_bulk: r.f()?,
    })
}
fn put_outputs(w: &mut W, o: &Outputs) {
    for x in o.to_array() {
        w.f64(x);
    }
}
fn get_outputs(r: &mut R) -> Result<Outputs> {
    Ok(Outputs {
        fx: r.f()?,
        fy: r.f()?,
        mz: r.f()?,
        f: r.f()?,
        t_max: r.f()?,
        t_mean: r.f()?,
        p_fric: r.f()?,
        frac_elastic: r.f()?,
        frac_plastic: r.f()?,
        frac_sliding: r.f()?,
        a: r.f()?,
        b: r.f()?,
        p0: r.f()?,
    })
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
                for b in s.st {
                    for x in [b.u[0], b.u[1], b.tau[0], b.tau[1], b.sh, b.temp, b.q] {
                        w.f64(x);
                    }
                    w.u8(b.regime as u8);
                }
                for a in s.acc {
                    for x in a {
                        w.f64(*x);
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
        if v != VERSION && v != 1 {
            return Err(CreepError::State(format!(
                "state format version {v}, this build reads versions 1 to {VERSION}"
            )));
        }
        let n = r.u()? as usize;
        let cfg = std::str::from_utf8(r.take(n)?)
            .map_err(|_| CreepError::State("configuration is not UTF-8".into()))?
            .to_string();
        // compared as text: serde_json's default number parser may differ from the printed
        // value in the last bit, so a parsed document can differ from an equal configuration
        let now = self.config().to_json().to_string();
        let same = cfg == now;
        if !same {
            return Err(CreepError::State(
                "the state was saved with a different configuration".into(),
            ));
        }
        let time = r.f()?;
        let inputs = get_inputs(&mut r)?;
        let out = get_outputs(&mut r)?;
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
                let mut st = Vec::with_capacity(nb);
                for _ in 0..nb {
                    let x: [f64; 7] = [r.f()?, r.f()?, r.f()?, r.f()?, r.f()?, r.f()?, r.f()?];
                    if x.iter().any(|v| !v.is_finite()) {
                        return Err(CreepError::State(format!(
                            "bristle {} of the state holds a non-finite value ({x:?})",
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
                                "heat history {} of the state holds {v}",
                                acc.len()
                            )));
                        }
                    }
                    acc.push(a);
                }
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
                    initialized: init,
                    out,
                    reversed,
                })?;
            }
        }
        Ok(())
    }
}
