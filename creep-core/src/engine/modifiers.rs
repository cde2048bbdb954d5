//! The configuration's modifiers (formula and Rust effects, module [`crate::modifier`]) at the contact's operating point: their factors on the material, once per operating point and, where local, per bristle.

use super::law::Law;
use super::Contact;
use crate::bristle::Material;
use crate::config::AnyModifier;
use crate::custom::{LocalState, OperatingPoint};
use crate::error::{CreepError, Result};
use crate::material::NodeP;
use crate::modifier::Modifier;

/// The modifiers of a contact and what they need at its current operating point: each one's
/// data-column values (looked up by name when the operating point or the data change, not per
/// evaluation), the product of the factors that do not read the bristle's local state, and
/// the list of those that do.
#[derive(Clone, Debug, Default)]
pub(super) struct Modifiers {
    /// The configuration's modifiers, in its order.
    list: Vec<AnyModifier>,
    /// Values of the extra (data) columns, by name, as last given ([`Contact::set_extra`]).
    extra: Vec<(String, f64)>,
    /// Per modifier: the values of its [`Modifier::columns`], in their order.
    cols: Vec<Vec<f64>>,
    /// The user's operating point (v < 0 when rolling backwards, not the mirrored frame's):
    /// v (m/s), F_N (kN), c_x, c_y, spin (1/m), T_B (degC).
    op: [f64; 6],
    /// Product of the factors of the modifiers that do not read the local state, per target
    /// (tau_c1, tau_c2, L_e, L_p, mu).
    fstatic: [f64; 5],
    /// Indices of the modifiers in the order their factors multiply: formula effects, then
    /// Rust effects, each in list order (the order of earlier builds, whatever the list's).
    order: Vec<usize>,
    /// Indices of the modifiers that read the local state, in that order.
    local: Vec<usize>,
}

impl Modifiers {
    /// The collection of a configuration's modifiers, factors 1 until
    /// [`Modifiers::at`] is called.
    pub(super) fn new(list: &[AnyModifier]) -> Self {
        let order = AnyModifier::kind_order(list);
        Modifiers {
            list: list.to_vec(),
            extra: Vec::new(),
            cols: vec![Vec::new(); list.len()],
            op: [0.0; 6],
            fstatic: [1.0; 5],
            local: order
                .iter()
                .copied()
                .filter(|&k| list[k].uses_local_state())
                .collect(),
            order,
        }
    }

    /// True if there are none.
    #[inline]
    pub(super) fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// True if some modifier reads the bristle's local state.
    #[inline]
    pub(super) fn any_local(&self) -> bool {
        !self.local.is_empty()
    }

    fn operating_point(&self) -> OperatingPoint<'_> {
        OperatingPoint {
            v_mps: self.op[0],
            fn_kn: self.op[1],
            cx: self.op[2],
            cy: self.op[3],
            spin_per_m: self.op[4],
            t_bulk_c: self.op[5],
            columns: &self.extra,
        }
    }

    /// Sets the data-column values (by name) the modifiers read.
    pub(super) fn set_extra(&mut self, values: &[(String, f64)]) {
        self.extra = values.to_vec();
    }

    /// Moves the collection to the operating point `op` (v m/s, F_N kN, c_x, c_y, spin 1/m,
    /// T_B degC):
    /// resolves every modifier's columns and multiplies the factors of those that do not
    /// read the local state. Err names a column a modifier reads and the data lack.
    pub(super) fn at(&mut self, op: [f64; 6]) -> Result<()> {
        if self.list.is_empty() {
            return Ok(());
        }
        self.op = op;
        for &k in &self.order {
            let m = &self.list[k];
            let mut vals = Vec::new();
            for c in m.columns() {
                let x = self
                    .extra
                    .iter()
                    .find(|(n, _)| n == c)
                    .map(|(_, x)| *x)
                    .ok_or_else(|| {
                        let (key, verb) = match m {
                            AnyModifier::Formula(_) => ("formula_effects", "uses"),
                            AnyModifier::Rust(_) => ("custom_effects", "needs"),
                        };
                        CreepError::Config {
                            source_name: format!("{key}.{}", m.name()),
                            message: format!(
                                "{verb} the column '{c}', which the data do not provide (have: {})",
                                self.extra
                                    .iter()
                                    .map(|e| e.0.as_str())
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            ),
                        }
                    })?;
                vals.push(x);
            }
            self.cols[k] = vals;
        }
        let mut fstatic = [1.0; 5];
        let op = self.operating_point();
        for &k in &self.order {
            let m = &self.list[k];
            if !m.uses_local_state() {
                let f = m.factor(&LocalState::default(), &op, &self.cols[k]);
                m.target().scale(&mut fstatic, f.max(0.0));
            }
        }
        self.fstatic = fstatic;
        Ok(())
    }

    /// The factors per target at a bristle in state `local`: the operating point's product
    /// times the local modifiers' factors (each clamped to >= 0), in list order.
    #[inline]
    pub(super) fn factors(&self, local: &LocalState) -> [f64; 5] {
        let mut fac = self.fstatic;
        if !self.local.is_empty() {
            let op = self.operating_point();
            for &k in &self.local {
                let m = &self.list[k];
                let f = m.factor(local, &op, &self.cols[k]);
                m.target().scale(&mut fac, f.max(0.0));
            }
        }
        fac
    }
}

impl Contact {
    /// Sets the values of extra (data) columns that formula and Rust effects read.
    pub fn set_extra(&mut self, values: &[(String, f64)]) -> Result<()> {
        self.law.modifiers.set_extra(values);
        self.update_modifiers()
    }

    /// Moves the modifiers to the current inputs (the user's operating point).
    pub(super) fn update_modifiers(&mut self) -> Result<()> {
        if self.law.modifiers.is_empty() {
            return Ok(());
        }
        let i = super::mirror_inputs(&self.state.run.inputs, self.state.run.reversed);
        self.law
            .modifiers
            .at([i.v, i.fn_n / 1e3, i.cx, i.cy, i.spin, i.t_bulk])
    }
}

impl Law {
    /// Scales a material by the modifiers' factors (local ones evaluated at this bristle:
    /// pressure `p` Pa, temperature `t` degC, |u| = `u` m, rigid slip speed `slip` m/s).
    #[inline(always)]
    pub(super) fn apply_modifiers(
        &self,
        mut m: Material,
        coulomb: bool,
        p: f64,
        t: f64,
        u: f64,
        slip: f64,
    ) -> Material {
        if self.modifiers.is_empty() {
            return m;
        }
        let fac = self.modifiers.factors(&LocalState {
            p_gpa: p / 1e9,
            t_c: t,
            u_mm: u * 1e3,
            slip_mps: slip,
        });
        if coulomb {
            m.tc1 *= fac[4];
            m.tc2 *= fac[4];
        } else {
            m.tc2 *= fac[1];
            m.tc1 = (m.tc1 * fac[0]).min(m.tc2);
            m.lp *= fac[3];
        }
        m.le *= fac[2];
        m
    }

    /// The material at temperature `t` with the factors of the modifiers that depend on the
    /// operating point only (all of them unless some reads the local bristle state): the
    /// same numbers as [`Law::material`] then (a factor of 1 changes nothing).
    #[inline(always)]
    pub(super) fn material_static(&self, np: &NodeP, t: f64) -> Material {
        let mut m = self.r.material_base(np, t);
        let f = &self.modifiers.fstatic;
        m.tc2 *= f[1];
        m.tc1 = (m.tc1 * f[0]).min(m.tc2);
        m.lp *= f[3];
        m.le *= f[2];
        m
    }

    /// Full material at temperature `t` (Eq. 4.3, 4.4) with the modifiers at a bristle
    /// with displacement |u| = `u` (m) and rigid slip speed `slip` (m/s).
    #[inline]
    pub(super) fn material(&self, np: &NodeP, t: f64, u: f64, slip: f64) -> Material {
        let m = self.r.material_base(np, t);
        self.apply_modifiers(m, self.r.on.coulomb, np.p, t, u, slip)
    }
}
