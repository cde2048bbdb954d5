//! The operating point of a contact (`Inputs`), its integral results (`Outputs`) and the fields along y = 0 (`FieldPoint`), with units.

use crate::error::{check_range, Result};

/// Speeds below this (m/s) count as standstill: no advection and no frictional heat.
pub const V_STANDSTILL: f64 = 1e-6;

/// Operating point of one contact; may change every step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inputs {
    /// Longitudinal creepage c_x = v_x/|v|, - (Eq. 4.12; positive: traction, force F_x > 0).
    pub cx: f64,
    /// Lateral creepage c_y, -.
    pub cy: f64,
    /// Spin creepage c_s, 1/m.
    pub spin: f64,
    /// Rolling (vehicle) speed v, m/s; negative: rolling backwards (the mirror image of rolling
    /// forwards; creepages are slip velocities over |v|).
    pub v: f64,
    /// Normal force F_N, N.
    pub fn_n: f64,
    /// Bulk temperature T_B, degC.
    pub t_bulk: f64,
}

impl Default for Inputs {
    /// Every input at its [`InputSpec::default`].
    fn default() -> Self {
        let mut i = Inputs {
            cx: 0.0,
            cy: 0.0,
            spin: 0.0,
            v: 0.0,
            fn_n: 0.0,
            t_bulk: 0.0,
        };
        for s in INPUTS {
            (s.set)(&mut i, s.default);
        }
        i
    }
}

impl Inputs {
    /// Checks every input against its [`InputSpec`] range; names the input and the accepted
    /// range on error.
    pub fn validate(&self) -> Result<()> {
        for s in INPUTS {
            let unit = if s.unit == "-" { "(-)" } else { s.unit };
            check_range(s.symbol, (s.get)(self), s.min, s.max, unit)?;
        }
        Ok(())
    }
}

/// Integral results of a step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Outputs {
    /// Longitudinal creep force F_x = int tau_x dA, N.
    pub fx: f64,
    /// Lateral creep force F_y, N.
    pub fy: f64,
    /// Spin moment M_z = int (x tau_y - y tau_x) dA, N m.
    pub mz: f64,
    /// Traction coefficient f = F_x / F_N, -.
    pub f: f64,
    /// Maximum bristle temperature, degC.
    pub t_max: f64,
    /// Area-weighted mean bristle temperature, degC.
    pub t_mean: f64,
    /// Frictional power int q dA (both bodies), W.
    pub p_fric: f64,
    /// Area fraction of elastic (adhering) bristles, -.
    pub frac_elastic: f64,
    /// Area fraction of plastically hardening bristles, -.
    pub frac_plastic: f64,
    /// Area fraction of sliding bristles (Coulomb bound or broken layer), -.
    pub frac_sliding: f64,
    /// Semi-axis in rolling direction, m.
    pub a: f64,
    /// Lateral semi-axis, m.
    pub b: f64,
    /// Maximum Hertz pressure, Pa.
    pub p0: f64,
}

impl Outputs {
    /// The outputs of a contact without load (lift-off): no force, moment or heat, every
    /// bristle elastic at the bulk temperature `t_bulk` (degC), no patch. Every output is
    /// written out, so a new one needs its value here.
    pub fn unloaded(t_bulk: f64) -> Outputs {
        Outputs {
            fx: 0.0,
            fy: 0.0,
            mz: 0.0,
            f: 0.0,
            t_max: t_bulk,
            t_mean: t_bulk,
            p_fric: 0.0,
            frac_elastic: 1.0,
            frac_plastic: 0.0,
            frac_sliding: 0.0,
            a: 0.0,
            b: 0.0,
            p0: 0.0,
        }
    }

    /// The outputs of the mirror image x -> -x (rolling backwards): F_x, f and M_z change
    /// sign, the others do not. Every output is written out, so a new one needs its parity
    /// here. An involution.
    pub fn mirrored(&self) -> Outputs {
        Outputs {
            fx: -self.fx,
            fy: self.fy,
            mz: -self.mz,
            f: -self.f,
            t_max: self.t_max,
            t_mean: self.t_mean,
            p_fric: self.p_fric,
            frac_elastic: self.frac_elastic,
            frac_plastic: self.frac_plastic,
            frac_sliding: self.frac_sliding,
            a: self.a,
            b: self.b,
            p0: self.p0,
        }
    }

    /// The outputs in the order of [`OUTPUTS`].
    pub fn to_array(&self) -> [f64; N_OUTPUTS] {
        std::array::from_fn(|k| (OUTPUTS[k].get)(self))
    }
}

/// Identifier of an input (index into [`INPUTS`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum InputId {
    /// Longitudinal creepage.
    Cx,
    /// Lateral creepage.
    Cy,
    /// Spin creepage.
    Spin,
    /// Rolling speed.
    V,
    /// Normal force.
    Fn,
    /// Bulk temperature.
    TBulk,
}

/// Description of one input: the row of [`INPUTS`] that every user of inputs (the FMU's
/// variables and modelDescription.xml, validation, both state formats, `ecf info`) reads.
#[derive(Clone, Copy, Debug)]
pub struct InputSpec {
    /// Identifier.
    pub id: InputId,
    /// Name in the FMU, the state formats and `ecf info`.
    pub name: &'static str,
    /// Symbol in the messages of [`Inputs::validate`].
    pub symbol: &'static str,
    /// Value reference of the FMU variable: written here, never derived from a position; a
    /// released one never changes (fmu-crate's test `value_references` pins them).
    pub vr: u32,
    /// Unit ("-": dimensionless).
    pub unit: &'static str,
    /// Default (the FMU's start value; what a saved state without this input keeps).
    pub default: f64,
    /// Smallest accepted value.
    pub min: f64,
    /// Largest accepted value.
    pub max: f64,
    /// One-line meaning (the FMU variable's description).
    pub description: &'static str,
    /// Reads the input from [`Inputs`].
    pub get: fn(&Inputs) -> f64,
    /// Writes the input into [`Inputs`].
    pub set: fn(&mut Inputs, f64),
}

/// The inputs of a contact, in [`InputId`] order (the order of the FMU's variables).
pub const INPUTS: &[InputSpec] = &[
    InputSpec {
        id: InputId::Cx,
        name: "cx",
        symbol: "cx",
        vr: 1,
        unit: "-",
        default: 0.0,
        min: -10.0,
        max: 10.0,
        description: "longitudinal creepage c_x = v_x/|v| (slip velocity of the wheel against the rail along x, the rolling direction, over the rolling speed); > 0 traction (driven wheel turns faster than it rolls), < 0 braking; Fx (force on the wheel) has the sign of cx",
        get: |i| i.cx,
        set: |i, x| i.cx = x,
    },
    InputSpec {
        id: InputId::Cy,
        name: "cy",
        symbol: "cy",
        vr: 2,
        unit: "-",
        default: 0.0,
        min: -10.0,
        max: 10.0,
        description: "lateral creepage c_y = v_y/|v| (lateral slip velocity of the wheel, y = z x x with z the contact normal into the wheel); Fy has its sign (Kalker's eta with the force on the wheel, i.e. Kalker's traction negated)",
        get: |i| i.cy,
        set: |i, x| i.cy = x,
    },
    InputSpec {
        id: InputId::Spin,
        name: "spin",
        symbol: "spin",
        vr: 3,
        unit: "1/m",
        default: 0.0,
        min: -1e4,
        max: 1e4,
        description: "spin creepage omega_z/|v| (relative rotation rate of the wheel about the contact normal z, into the wheel); spin > 0 gives Fy > 0 and Mz > 0 at small creepage",
        get: |i| i.spin,
        set: |i, x| i.spin = x,
    },
    InputSpec {
        id: InputId::V,
        name: "v",
        symbol: "v",
        vr: 4,
        unit: "m/s",
        default: 5.0,
        min: -1000.0,
        max: 1000.0,
        description: "rolling (vehicle) speed; < 0 rolls backwards (the mirror image; the bristles stay in the contact when the sign changes); 0 is standstill (no advection, no heat)",
        get: |i| i.v,
        set: |i, x| i.v = x,
    },
    InputSpec {
        id: InputId::Fn,
        name: "FN",
        symbol: "F_N",
        vr: 5,
        unit: "N",
        default: 110e3,
        min: 0.0,
        max: 1e8,
        description: "normal force on the contact; <= 0 is lift-off (all forces zero)",
        get: |i| i.fn_n,
        set: |i, x| i.fn_n = x,
    },
    InputSpec {
        id: InputId::TBulk,
        name: "T_bulk",
        symbol: "T_bulk",
        vr: 6,
        unit: "degC",
        default: 20.0,
        min: -273.15,
        max: 2000.0,
        description: "bulk (ambient) temperature of wheel and rail",
        get: |i| i.t_bulk,
        set: |i, x| i.t_bulk = x,
    },
];

/// Returns the spec of an input.
pub fn input_spec(id: InputId) -> &'static InputSpec {
    &INPUTS[id as usize]
}

/// A column of the CLI's CSV tables: its place, header, scale from the output's unit and
/// decimals.
#[derive(Clone, Copy, Debug)]
pub struct CsvColumn {
    /// Place among the output columns (0 first), written here like the value reference.
    pub col: usize,
    /// Header (name and CSV unit).
    pub header: &'static str,
    /// Factor from the output's unit to the CSV unit.
    pub scale: f64,
    /// Decimals printed.
    pub decimals: usize,
}

/// Description of one output: the row of [`OUTPUTS`] that every user of outputs (the FMU's
/// variables and modelDescription.xml, both state formats, the CLI's CSV tables,
/// `ecf info`) reads. Adding an output: a field of [`Outputs`], a row here, and the lines
/// that compute it (engine/grid.rs, engine/advance.rs, polach.rs).
#[derive(Clone, Copy, Debug)]
pub struct OutputSpec {
    /// Name in the FMU, the state formats and `ecf info`.
    pub name: &'static str,
    /// Value reference of the FMU variable: written here, never derived from a position; a
    /// released one never changes (fmu-crate's test `value_references` pins them).
    pub vr: u32,
    /// Unit ("-": dimensionless).
    pub unit: &'static str,
    /// One-line meaning (the FMU variable's description).
    pub description: &'static str,
    /// Its column in the CLI's CSV tables.
    pub csv: CsvColumn,
    /// Reads the output from [`Outputs`].
    pub get: fn(&Outputs) -> f64,
    /// Writes the output into [`Outputs`] (restoring a saved state).
    pub set: fn(&mut Outputs, f64),
}

/// Number of outputs.
pub const N_OUTPUTS: usize = OUTPUTS.len();

const fn csv(col: usize, header: &'static str, scale: f64, decimals: usize) -> CsvColumn {
    CsvColumn {
        col,
        header,
        scale,
        decimals,
    }
}

/// The outputs of a contact, in the order of the FMU's variables.
pub const OUTPUTS: &[OutputSpec] = &[
    OutputSpec {
        name: "Fx",
        vr: 10,
        unit: "N",
        description: "longitudinal creep force on the wheel (positive with c_x: traction)",
        csv: csv(1, "Fx_N", 1.0, 3),
        get: |o| o.fx,
        set: |o, x| o.fx = x,
    },
    OutputSpec {
        name: "Fy",
        vr: 11,
        unit: "N",
        description: "lateral creep force (positive with c_y)",
        csv: csv(2, "Fy_N", 1.0, 3),
        get: |o| o.fy,
        set: |o, x| o.fy = x,
    },
    OutputSpec {
        name: "Mz",
        vr: 12,
        unit: "N.m",
        description: "spin moment about the contact normal, int (x tau_y - y tau_x) dA",
        csv: csv(3, "Mz_Nm", 1.0, 5),
        get: |o| o.mz,
        set: |o, x| o.mz = x,
    },
    OutputSpec {
        name: "f",
        vr: 13,
        unit: "-",
        description: "traction coefficient Fx/FN (0 at lift-off)",
        csv: csv(0, "f", 1.0, 8),
        get: |o| o.f,
        set: |o, x| o.f = x,
    },
    OutputSpec {
        name: "T_max",
        vr: 14,
        unit: "degC",
        description: "maximum flash temperature in the contact",
        csv: csv(4, "T_max_C", 1.0, 3),
        get: |o| o.t_max,
        set: |o, x| o.t_max = x,
    },
    OutputSpec {
        name: "T_mean",
        vr: 15,
        unit: "degC",
        description: "area-weighted mean temperature in the contact",
        csv: csv(5, "T_mean_C", 1.0, 3),
        get: |o| o.t_mean,
        set: |o, x| o.t_mean = x,
    },
    OutputSpec {
        name: "P_fric",
        vr: 16,
        unit: "W",
        description: "frictional power dissipated in the contact (both bodies)",
        csv: csv(6, "P_fric_W", 1.0, 3),
        get: |o| o.p_fric,
        set: |o, x| o.p_fric = x,
    },
    OutputSpec {
        name: "frac_elastic",
        vr: 17,
        unit: "-",
        description: "area fraction of elastic (adhering) bristles",
        csv: csv(7, "frac_elastic", 1.0, 5),
        get: |o| o.frac_elastic,
        set: |o, x| o.frac_elastic = x,
    },
    OutputSpec {
        name: "frac_plastic",
        vr: 18,
        unit: "-",
        description: "area fraction of plastically hardening bristles",
        csv: csv(8, "frac_plastic", 1.0, 5),
        get: |o| o.frac_plastic,
        set: |o, x| o.frac_plastic = x,
    },
    OutputSpec {
        name: "frac_sliding",
        vr: 19,
        unit: "-",
        description: "area fraction of sliding bristles",
        csv: csv(9, "frac_sliding", 1.0, 5),
        get: |o| o.frac_sliding,
        set: |o, x| o.frac_sliding = x,
    },
    OutputSpec {
        name: "a",
        vr: 20,
        unit: "m",
        description: "contact semi-axis in rolling direction",
        csv: csv(10, "a_mm", 1e3, 5),
        get: |o| o.a,
        set: |o, x| o.a = x,
    },
    OutputSpec {
        name: "b",
        vr: 21,
        unit: "m",
        description: "lateral contact semi-axis (line contact: half width)",
        csv: csv(11, "b_mm", 1e3, 5),
        get: |o| o.b,
        set: |o, x| o.b = x,
    },
    OutputSpec {
        name: "p0",
        vr: 22,
        unit: "Pa",
        description: "maximum Hertz pressure",
        csv: csv(12, "p0_MPa", 1e-6, 3),
        get: |o| o.p0,
        set: |o, x| o.p0 = x,
    },
];

/// The outputs in the order of the CLI's CSV columns ([`CsvColumn::col`]).
pub fn csv_outputs() -> Vec<&'static OutputSpec> {
    let mut v: Vec<&OutputSpec> = OUTPUTS.iter().collect();
    v.sort_by_key(|s| s.csv.col);
    v
}

/// One point of the fields along the strip nearest y = 0 (seed Fig. 4.9, 4.10).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldPoint {
    /// Position along x, m (leading edge at +a; at -a when rolling backwards).
    pub x: f64,
    /// Shear stress |tau|, Pa.
    pub tau: f64,
    /// Longitudinal shear stress tau_x, Pa.
    pub tau_x: f64,
    /// First critical shear stress (or Coulomb bound), Pa.
    pub tau_c1: f64,
    /// Second critical shear stress (or Coulomb bound), Pa.
    pub tau_c2: f64,
    /// Normal pressure, Pa.
    pub p: f64,
    /// Temperature, degC.
    pub t: f64,
    /// Regime: 0 elastic, 1 plastic, 2 sliding.
    pub regime: u8,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mirror image changes the sign of F_x, f and M_z and of nothing else, and twice
    /// is the identity; the unloaded outputs are zero but for the temperatures and the
    /// elastic fraction.
    #[test]
    fn mirrored_flips_fx_f_mz_and_unloaded_holds_only_temperature_and_adhesion() {
        let mut o = Outputs::default();
        for (k, s) in OUTPUTS.iter().enumerate() {
            (s.set)(&mut o, 1.0 + k as f64);
        }
        let m = o.mirrored();
        for s in OUTPUTS {
            let odd = matches!(s.name, "Fx" | "f" | "Mz");
            let want = if odd { -(s.get)(&o) } else { (s.get)(&o) };
            assert_eq!((s.get)(&m), want, "{}", s.name);
        }
        assert_eq!(m.mirrored(), o);
        let u = Outputs::unloaded(35.0);
        for s in OUTPUTS {
            let want = match s.name {
                "T_max" | "T_mean" => 35.0,
                "frac_elastic" => 1.0,
                _ => 0.0,
            };
            assert_eq!((s.get)(&u), want, "{}", s.name);
        }
    }

    #[test]
    fn every_input_has_one_row_that_reads_its_own_field() {
        let mut i = Inputs::default();
        for (k, s) in INPUTS.iter().enumerate() {
            assert_eq!(s.id as usize, k, "{} out of order", s.name);
            assert!(s.min <= s.default && s.default <= s.max, "{}", s.name);
            assert_eq!((s.get)(&Inputs::default()), s.default, "{}", s.name);
            (s.set)(&mut i, 1000.0 + k as f64);
        }
        for (k, s) in INPUTS.iter().enumerate() {
            assert_eq!(
                (s.get)(&i),
                1000.0 + k as f64,
                "{} reads another field",
                s.name
            );
        }
        // a field of `Inputs` without a row would still be 0
        assert!(!format!("{i:?}").contains(": 0.0"), "{i:?}");
        assert!(i.validate().is_err(), "1000 is beyond the creepage range");
    }

    #[test]
    fn every_output_has_one_row_that_reads_its_own_field() {
        let mut o = Outputs::default();
        for (k, s) in OUTPUTS.iter().enumerate() {
            (s.set)(&mut o, k as f64 + 1.0);
        }
        let want: Vec<f64> = (1..=N_OUTPUTS).map(|k| k as f64).collect();
        assert_eq!(o.to_array().to_vec(), want);
        assert!(!format!("{o:?}").contains(": 0.0"), "{o:?}");
        let mut cols: Vec<usize> = OUTPUTS.iter().map(|s| s.csv.col).collect();
        cols.sort_unstable();
        assert_eq!(cols, (0..N_OUTPUTS).collect::<Vec<_>>(), "CSV columns");
        assert_eq!(csv_outputs()[0].name, "f");
    }
}
