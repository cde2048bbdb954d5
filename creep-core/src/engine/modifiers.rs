//! Formula and custom effects: modifiers of the material at a bristle, evaluated per operating point and, where local, per bristle.

use super::Contact;
use crate::bristle::Material;
use crate::error::{CreepError, Result};
use crate::material::NodeP;

impl Contact {
    /// True if formula or custom effects modify the material.
    #[inline]
    pub(super) fn has_modifiers(&self) -> bool {
        !(self.cfg.formulas.is_empty() && self.cfg.custom.is_empty())
    }

    /// Sets the values of extra (data) columns that formula effects use.
    pub fn set_extra(&mut self, values: &[(String, f64)]) -> Result<()> {
        self.extra = values.to_vec();
        self.update_formula_vars()
    }

    pub(super) fn update_formula_vars(&mut self) -> Result<()> {
        if self.cfg.formulas.is_empty() && self.cfg.custom.is_empty() {
            return Ok(());
        }
        // the user's operating point (v < 0 when rolling backwards), not the mirrored frame's
        let i = &super::mirror_inputs(&self.inputs, self.reversed);
        let mut v = vec![0.0; crate::formula::LOCAL.len()];
        v.extend([i.v, i.fn_n / 1e3, i.cx, i.cy, i.spin]);
        let mut fstatic = [1.0; 5];
        for f in &self.cfg.formulas {
            let mut vars = v.clone();
            for c in &f.columns {
                let x = self
                    .extra
                    .iter()
                    .find(|(n, _)| n == c)
                    .map(|(_, x)| *x)
                    .ok_or_else(|| CreepError::Config {
                        source_name: format!("formula_effects.{}", f.name),
                        message: format!(
                            "uses the column '{c}', which the data do not provide (have: {})",
                            self.extra
                                .iter()
                                .map(|e| e.0.as_str())
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    })?;
                vars.push(x);
            }
            if !f.local {
                fstatic[f.target as usize] *= f.eval(&vars).max(0.0);
            }
        }
        for c in &self.cfg.custom {
            for col in c.effect.columns() {
                if !self.extra.iter().any(|(n, _)| n == col) {
                    return Err(CreepError::Config {
                        source_name: format!("custom_effects.{}", c.effect.name()),
                        message: format!(
                            "needs the column '{col}', which the data do not provide (have: {})",
                            self.extra
                                .iter()
                                .map(|e| e.0.as_str())
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    });
                }
            }
            if !c.effect.uses_local_state() {
                fstatic[c.effect.target() as usize] *= c
                    .effect
                    .factor(
                        &c.params,
                        &crate::custom::LocalState::default(),
                        &self.operating_point(),
                    )
                    .max(0.0);
            }
        }
        self.fstatic = fstatic;
        self.fvars = v;
        Ok(())
    }

    pub(super) fn operating_point(&self) -> crate::custom::OperatingPoint<'_> {
        let i = &self.inputs;
        crate::custom::OperatingPoint {
            v_mps: i.v,
            fn_kn: i.fn_n / 1e3,
            cx: i.cx,
            cy: i.cy,
            spin_per_m: i.spin,
            columns: &self.extra,
        }
    }

    /// Scales a material by the formula effects (local ones evaluated at this bristle).
    #[inline]
    pub(super) fn apply_formulas(
        &self,
        mut m: Material,
        coulomb: bool,
        p: f64,
        t: f64,
        u: f64,
        slip: f64,
    ) -> Material {
        if self.cfg.formulas.is_empty() && self.cfg.custom.is_empty() {
            return m;
        }
        let mut fac = self.fstatic;
        if self.flocal {
            let mut vars = self.fvars.clone();
            vars[0] = p / 1e9;
            vars[1] = t;
            vars[2] = u * 1e3;
            vars[3] = slip;
            for f in self.cfg.formulas.iter().filter(|f| f.local) {
                let mut vv = vars.clone();
                for c in &f.columns {
                    vv.push(
                        self.extra
                            .iter()
                            .find(|(n, _)| n == c)
                            .map(|(_, x)| *x)
                            .unwrap_or(f64::NAN),
                    );
                }
                fac[f.target as usize] *= f.eval(&vv).max(0.0);
            }
            let local = crate::custom::LocalState {
                p_gpa: p / 1e9,
                t_c: t,
                u_mm: u * 1e3,
                slip_mps: slip,
            };
            for c in self
                .cfg
                .custom
                .iter()
                .filter(|c| c.effect.uses_local_state())
            {
                fac[c.effect.target() as usize] *= c
                    .effect
                    .factor(&c.params, &local, &self.operating_point())
                    .max(0.0);
            }
        }
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

    /// The material at temperature `t` with the factors of the formula and custom effects that
    /// depend on the operating point only (all of them unless some reads the local bristle
    /// state): the same numbers as [`Self::material`] then (a factor of 1 changes nothing).
    #[inline(always)]
    pub(super) fn material_static(&self, np: &NodeP, t: f64) -> Material {
        let mut m = self.r.material_base(np, t);
        let f = &self.fstatic;
        m.tc2 *= f[1];
        m.tc1 = (m.tc1 * f[0]).min(m.tc2);
        m.lp *= f[3];
        m.le *= f[2];
        m
    }

    /// Full material at temperature `t` (Eq. 4.3, 4.4) with the formula effects at a bristle
    /// with displacement |u| = `u` (m) and rigid slip speed `slip` (m/s).
    #[inline]
    pub(super) fn material(&self, np: &NodeP, t: f64, u: f64, slip: f64) -> Material {
        let m = self.r.material_base(np, t);
        self.apply_formulas(m, self.r.coulomb, np.p, t, u, slip)
    }
}
