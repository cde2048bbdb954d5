//! The one table of FMU variables: name, value reference, type, causality, unit, start, description; drives get/set and the XML.

use creep_core::config::DEFAULT_GEOMETRY;
use creep_core::effects::{self, Effect};
use creep_core::params::{self, P};
use creep_core::{Config, Geometry, Inputs};

/// Base type of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// fmi2Real.
    Real,
    /// fmi2Integer.
    Integer,
    /// fmi2Boolean.
    Boolean,
    /// fmi2String.
    String,
}

impl Kind {
    /// Element name in modelDescription.xml and in messages.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Real => "Real",
            Kind::Integer => "Integer",
            Kind::Boolean => "Boolean",
            Kind::String => "String",
        }
    }
}

/// Causality of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Causality {
    /// Fixed parameter: set before the end of initialization only.
    Parameter,
    /// Continuous input: set at any communication point.
    Input,
    /// Continuous output.
    Output,
}

/// One of the inputs of a contact, in the order of [`INPUT_NAMES`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum In {
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
    /// Auxiliary input 1..4 (index 0..3): a data column of formula or custom effects.
    Aux(usize),
}

/// Number of auxiliary inputs.
pub const N_AUX: usize = 4;
/// Number of inputs (six contact inputs and the auxiliary inputs).
pub const N_INPUTS: usize = 6 + N_AUX;
/// Value reference of `aux1` (the others follow).
pub const VR_AUX0: u32 = 90;

/// One of the outputs of a contact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Out {
    /// Longitudinal creep force.
    Fx,
    /// Lateral creep force.
    Fy,
    /// Spin moment.
    Mz,
    /// Traction coefficient.
    F,
    /// Maximum temperature.
    TMax,
    /// Mean temperature.
    TMean,
    /// Frictional power.
    PFric,
    /// Elastic area fraction.
    FracElastic,
    /// Plastic area fraction.
    FracPlastic,
    /// Sliding area fraction.
    FracSliding,
    /// Semi-axis a.
    A,
    /// Semi-axis b.
    B,
    /// Peak pressure.
    P0,
}

impl Out {
    /// The value of this output in a core [`creep_core::Outputs`].
    pub fn of(self, o: &creep_core::Outputs) -> f64 {
        match self {
            Out::Fx => o.fx,
            Out::Fy => o.fy,
            Out::Mz => o.mz,
            Out::F => o.f,
            Out::TMax => o.t_max,
            Out::TMean => o.t_mean,
            Out::PFric => o.p_fric,
            Out::FracElastic => o.frac_elastic,
            Out::FracPlastic => o.frac_plastic,
            Out::FracSliding => o.frac_sliding,
            Out::A => o.a,
            Out::B => o.b,
            Out::P0 => o.p0,
        }
    }
}

/// Geometry parameters (SI).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Geo {
    /// Semi-axis a at the reference load.
    ARef,
    /// Semi-axis b at the reference load.
    BRef,
    /// Reference load.
    FnRef,
    /// Equivalent radius of curvature in rolling direction.
    Rx,
    /// Equivalent lateral radius of curvature.
    Ry,
}

/// What a variable reads and writes inside an instance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Slot {
    /// An input of the contact.
    Input(In),
    /// An output of the contact.
    Output(Out),
    /// A material, friction or thermal parameter of `creep_core::params::SPECS`.
    Param(P),
    /// A geometry parameter.
    Geo(Geo),
    /// Geometry mode: 0 from the configuration, 1 semi-axes, 2 curvatures (Hertz).
    GeometryMode,
    /// Grid cells per strip.
    Nx,
    /// Grid strips.
    Ny,
    /// Threads that advance the strips.
    Threads,
    /// How a step advances the bristles (0 cells, 1 continuous).
    Scheme,
    /// An effect switch.
    Effect(Effect),
    /// Model family name.
    Model,
    /// Condition preset name.
    Preset,
    /// Configuration JSON file.
    ConfigFile,
    /// Data columns of the configuration: which auxiliary input or constant feeds each.
    Columns,
}

/// Start value of a variable.
#[derive(Clone, Debug, PartialEq)]
pub enum Start {
    /// No start value (calculated outputs).
    None,
    /// Real start.
    Real(f64),
    /// Integer start.
    Integer(i32),
    /// Boolean start.
    Boolean(bool),
    /// String start.
    String(String),
}

/// One FMU variable.
#[derive(Clone, Debug)]
pub struct Var {
    /// Name in modelDescription.xml.
    pub name: String,
    /// Value reference (unique over all types).
    pub vr: u32,
    /// Base type.
    pub kind: Kind,
    /// Causality.
    pub causality: Causality,
    /// Unit name (a `Unit` of the UnitDefinitions) or none for dimensionless values.
    pub unit: Option<&'static str>,
    /// One-line description.
    pub description: String,
    /// Start value.
    pub start: Start,
    /// Lower bound, if any.
    pub min: Option<f64>,
    /// Upper bound, if any.
    pub max: Option<f64>,
    /// What the variable reads and writes.
    pub slot: Slot,
}

/// Names of the inputs, in the order of [`In`].
pub const INPUT_NAMES: [&str; N_INPUTS] = [
    "cx", "cy", "spin", "v", "FN", "T_bulk", "aux1", "aux2", "aux3", "aux4",
];

/// Value reference of the first material parameter (the others follow in `SPECS` order).
pub const VR_PARAM0: u32 = 100;

/// Unit definitions: name, SI exponents (kg, m, s, K) and factor/offset to SI.
pub struct UnitDef {
    /// Unit name.
    pub name: &'static str,
    /// Exponents of kg, m, s, K.
    pub exp: [i32; 4],
    /// SI value = factor * value + offset.
    pub factor: f64,
    /// Offset (temperatures).
    pub offset: f64,
}

/// Every unit the table uses, with its base units.
pub const UNITS: &[UnitDef] = &[
    UnitDef {
        name: "N",
        exp: [1, 1, -2, 0],
        factor: 1.0,
        offset: 0.0,
    },
    UnitDef {
        name: "N.m",
        exp: [1, 2, -2, 0],
        factor: 1.0,
        offset: 0.0,
    },
    UnitDef {
        name: "m",
        exp: [0, 1, 0, 0],
        factor: 1.0,
        offset: 0.0,
    },
    UnitDef {
        name: "1/m",
        exp: [0, -1, 0, 0],
        factor: 1.0,
        offset: 0.0,
    },
    UnitDef {
        name: "m/s",
        exp: [0, 1, -1, 0],
        factor: 1.0,
        offset: 0.0,
    },
    UnitDef {
        name: "s/m",
        exp: [0, -1, 1, 0],
        factor: 1.0,
        offset: 0.0,
    },
    UnitDef {
        name: "degC",
        exp: [0, 0, 0, 1],
        factor: 1.0,
        offset: 273.15,
    },
    UnitDef {
        name: "1/degC",
        exp: [0, 0, 0, -1],
        factor: 1.0,
        offset: 0.0,
    },
    UnitDef {
        name: "W",
        exp: [1, 2, -3, 0],
        factor: 1.0,
        offset: 0.0,
    },
    UnitDef {
        name: "Pa",
        exp: [1, -1, -2, 0],
        factor: 1.0,
        offset: 0.0,
    },
    UnitDef {
        name: "GPa",
        exp: [1, -1, -2, 0],
        factor: 1e9,
        offset: 0.0,
    },
    UnitDef {
        name: "1/GPa",
        exp: [-1, 1, 2, 0],
        factor: 1e-9,
        offset: 0.0,
    },
    UnitDef {
        name: "um/GPa",
        exp: [-1, 2, 2, 0],
        factor: 1e-15,
        offset: 0.0,
    },
    UnitDef {
        name: "mm",
        exp: [0, 1, 0, 0],
        factor: 1e-3,
        offset: 0.0,
    },
    UnitDef {
        name: "mm^2/s",
        exp: [0, 2, -1, 0],
        factor: 1e-6,
        offset: 0.0,
    },
    UnitDef {
        name: "W/(m K)",
        exp: [1, 1, -3, -1],
        factor: 1.0,
        offset: 0.0,
    },
];

/// The default configuration of the FMU (model `ecf`, preset `table4.1`): the start values.
pub fn default_config() -> Config {
    // The shipped preset always parses (creep-core tests every preset); fall back to the
    // parameter defaults of the registry if it ever did not.
    Config::for_model("ecf").unwrap_or_else(|_| Config {
        model: creep_core::ModelKind::Ecf,
        preset: "custom".into(),
        effects: creep_core::effects::EffectSet::empty(),
        params: creep_core::params::Params::default(),
        bound: creep_core::Bound::Elliptic,
        grid: creep_core::config::DEFAULT_GRID,
        geometry: DEFAULT_GEOMETRY,
        formulas: Vec::new(),
        custom: Vec::new(),
    })
}

/// What the start value of a parameter of the preset means (every description says it).
pub const UNSET: &str = "a value equal to the start value means 'not set': the preset's or configuration file's value applies";

/// Start values of the curvature parameters (m): a wheel of radius 0.46 m on a straight rail
/// with a 0.3 m crown radius, which gives a contact of about the default size.
pub const RX_START: f64 = 0.46;
/// See [`RX_START`].
pub const RY_START: f64 = 0.3;

fn unit_of(spec_unit: &'static str) -> Option<&'static str> {
    if spec_unit == "-" {
        None
    } else {
        Some(spec_unit)
    }
}

/// Builds the table. Value references are unique over all types.
pub fn table() -> Vec<Var> {
    let cfg = default_config();
    let inp = Inputs::default();
    let mut v = Vec::new();
    let real = |name: &str, vr, causality, unit, start: Start, description: &str, slot| Var {
        name: name.into(),
        vr,
        kind: Kind::Real,
        causality,
        unit,
        description: description.into(),
        start,
        min: None,
        max: None,
        slot,
    };
    use Causality::*;
    let ins: [(In, Option<&'static str>, f64, &str); 6] = [
        (In::Cx, None, inp.cx, "longitudinal creepage c_x = v_x/|v| (slip velocity of the wheel against the rail along x, the rolling direction, over the rolling speed); > 0 traction (driven wheel turns faster than it rolls), < 0 braking; Fx (force on the wheel) has the sign of cx"),
        (In::Cy, None, inp.cy, "lateral creepage c_y = v_y/|v| (lateral slip velocity of the wheel, y = z x x with z the contact normal into the wheel); Fy has its sign (Kalker's eta with the force on the wheel, i.e. Kalker's traction negated)"),
        (In::Spin, Some("1/m"), inp.spin, "spin creepage omega_z/|v| (relative rotation rate of the wheel about the contact normal z, into the wheel); spin > 0 gives Fy > 0 and Mz > 0 at small creepage"),
        (In::V, Some("m/s"), inp.v, "rolling (vehicle) speed; < 0 rolls backwards (the mirror image; the bristles stay in the contact when the sign changes); 0 is standstill (no advection, no heat)"),
        (In::Fn, Some("N"), inp.fn_n, "normal force on the contact; <= 0 is lift-off (all forces zero)"),
        (In::TBulk, Some("degC"), inp.t_bulk, "bulk (ambient) temperature of wheel and rail"),
    ];
    for (i, (slot, unit, start, d)) in ins.into_iter().enumerate() {
        v.push(real(
            INPUT_NAMES[i],
            1 + i as u32,
            Input,
            unit,
            Start::Real(start),
            d,
            Slot::Input(slot),
        ));
    }
    let outs: [(Out, &str, Option<&'static str>, &str); 13] = [
        (
            Out::Fx,
            "Fx",
            Some("N"),
            "longitudinal creep force on the wheel (positive with c_x: traction)",
        ),
        (
            Out::Fy,
            "Fy",
            Some("N"),
            "lateral creep force (positive with c_y)",
        ),
        (
            Out::Mz,
            "Mz",
            Some("N.m"),
            "spin moment about the contact normal, int (x tau_y - y tau_x) dA",
        ),
        (
            Out::F,
            "f",
            None,
            "traction coefficient Fx/FN (0 at lift-off)",
        ),
        (
            Out::TMax,
            "T_max",
            Some("degC"),
            "maximum flash temperature in the contact",
        ),
        (
            Out::TMean,
            "T_mean",
            Some("degC"),
            "area-weighted mean temperature in the contact",
        ),
        (
            Out::PFric,
            "P_fric",
            Some("W"),
            "frictional power dissipated in the contact (both bodies)",
        ),
        (
            Out::FracElastic,
            "frac_elastic",
            None,
            "area fraction of elastic (adhering) bristles",
        ),
        (
            Out::FracPlastic,
            "frac_plastic",
            None,
            "area fraction of plastically hardening bristles",
        ),
        (
            Out::FracSliding,
            "frac_sliding",
            None,
            "area fraction of sliding bristles",
        ),
        (
            Out::A,
            "a",
            Some("m"),
            "contact semi-axis in rolling direction",
        ),
        (
            Out::B,
            "b",
            Some("m"),
            "lateral contact semi-axis (line contact: half width)",
        ),
        (Out::P0, "p0", Some("Pa"), "maximum Hertz pressure"),
    ];
    for k in 0..N_AUX {
        v.push(real(
            INPUT_NAMES[6 + k],
            VR_AUX0 + k as u32,
            Input,
            None,
            Start::Real(0.0),
            &format!("auxiliary input {}: the value of a data column used by formula or custom effects of the configuration, mapped by the parameter columns (e.g. columns = \"humidity=aux{}\"); unused otherwise", k + 1, k + 1),
            Slot::Input(In::Aux(k)),
        ));
    }
    for (i, (slot, name, unit, d)) in outs.into_iter().enumerate() {
        v.push(real(
            name,
            10 + i as u32,
            Output,
            unit,
            Start::None,
            d,
            Slot::Output(slot),
        ));
    }
    let (a0, b0, f0) = match cfg.geometry {
        Geometry::SemiAxes { a, b, fn_ref } => (a, b, fn_ref),
        _ => (7.63e-3, 7.88e-3, 110e3),
    };
    let geos: [(Geo, &str, &'static str, f64, &str); 5] = [
        (Geo::ARef, "a_ref", "m", a0, "semi-axis in rolling direction at FN_ref (geometry = 1); scales with (FN/FN_ref)^(1/3)"),
        (Geo::BRef, "b_ref", "m", b0, "lateral semi-axis at FN_ref (geometry = 1)"),
        (Geo::FnRef, "FN_ref", "N", f0, "reference normal force of a_ref, b_ref (geometry = 1)"),
        (Geo::Rx, "Rx", "m", RX_START, "equivalent radius of curvature in rolling direction, Hertz (geometry = 2)"),
        (Geo::Ry, "Ry", "m", RY_START, "equivalent lateral radius of curvature, Hertz (geometry = 2)"),
    ];
    for (i, (slot, name, unit, start, d)) in geos.into_iter().enumerate() {
        let mut var = real(
            name,
            30 + i as u32,
            Parameter,
            Some(unit),
            Start::Real(start),
            &format!("{d}; {UNSET}"),
            Slot::Geo(slot),
        );
        var.min = Some(0.0);
        v.push(var);
    }
    v.push(Var {
        name: "geometry".into(),
        vr: 40,
        kind: Kind::Integer,
        causality: Parameter,
        unit: None,
        description: "contact geometry: 0 from the preset or configuration file, 1 semi-axes a_ref, b_ref at FN_ref, 2 Hertz from curvatures Rx, Ry".into(),
        start: Start::Integer(0),
        min: Some(0.0),
        max: Some(2.0),
        slot: Slot::GeometryMode,
    });
    v.push(Var {
        name: "nx".into(),
        vr: 41,
        kind: Kind::Integer,
        causality: Parameter,
        unit: None,
        description: format!(
            "bristle grid: cells per strip in rolling direction; 0 = from the preset or configuration file ({} for the presets)",
            cfg.grid.nx
        ),
        start: Start::Integer(0),
        min: Some(0.0),
        max: Some(2000.0),
        slot: Slot::Nx,
    });
    v.push(Var {
        name: "ny".into(),
        vr: 42,
        kind: Kind::Integer,
        causality: Parameter,
        unit: None,
        description: format!(
            "bristle grid: strips across the contact; 0 = from the preset or configuration file ({} for the presets)",
            cfg.grid.ny
        ),
        start: Start::Integer(0),
        min: Some(0.0),
        max: Some(1000.0),
        slot: Slot::Ny,
    });
    v.push(Var {
        name: "threads".into(),
        vr: 43,
        kind: Kind::Integer,
        causality: Parameter,
        unit: None,
        description: "threads that advance the bristle strips of the contact (the results do not depend on it); 1: the importer's thread alone".into(),
        start: Start::Integer(1),
        min: Some(1.0),
        max: Some(64.0),
        slot: Slot::Threads,
    });
    v.push(Var {
        name: "scheme".into(),
        vr: 44,
        kind: Kind::Integer,
        causality: Parameter,
        unit: None,
        description: "how a step advances the bristles: 0 cell by cell (reference, independent of the communication step within 0.5 %), 1 continuous sub-steps of up to 4 cells (3-5x faster at 0.1-1 ms steps; forces within about 1 %, frictional power and peak temperature depend on the step by up to 2 % and 4 %, docs/fmu.md)".into(),
        start: Start::Integer(0),
        min: Some(0.0),
        max: Some(1.0),
        slot: Slot::Scheme,
    });
    for (i, info) in effects::CATALOGUE.iter().enumerate() {
        let first = info
            .description
            .split(". ")
            .next()
            .unwrap_or(info.description);
        let description = if info.effect == Effect::Transient {
            "transient on/off: the bristle grid persists across steps (off: each step returns the quasi-steady state of its inputs)".to_string()
        } else {
            format!(
                "effect {} on/off: {}",
                info.name,
                first.trim_end_matches('.')
            )
        };
        let description = format!("{description}; {UNSET}");
        v.push(Var {
            name: format!("effect_{}", info.name),
            vr: 50 + i as u32,
            kind: Kind::Boolean,
            causality: Parameter,
            unit: None,
            description,
            start: Start::Boolean(cfg.effects.has(info.effect)),
            min: None,
            max: None,
            slot: Slot::Effect(info.effect),
        });
    }
    let strings: [(Slot, &str, &str, &str); 4] = [
        (Slot::Model, "model", "", "model family: ecf, fastsim or polach; empty (default): the model of the preset or configuration file (ecf if neither is set)"),
        (Slot::Preset, "preset", "", "condition preset (table4.1, dry, wet, dry_sanded, wet_sanded, twin_disc, fastsim, polach); empty: the model's default"),
        (Slot::ConfigFile, "config_file", "", "configuration JSON file (creep-core format, a regular file of at most 1 MiB); relative paths are resolved against the FMU's resources/ folder; empty: none"),
        (Slot::Columns, "columns", "", "data columns of formula/custom effects: NAME=auxK feeds column NAME from input auxK, NAME=VALUE holds it constant; comma separated, e.g. humidity=aux1, salt=0.2; empty: none"),
    ];
    for (i, (slot, name, start, d)) in strings.into_iter().enumerate() {
        v.push(Var {
            name: name.into(),
            vr: 60 + i as u32,
            kind: Kind::String,
            causality: Parameter,
            unit: None,
            description: d.into(),
            start: Start::String(start.into()),
            min: None,
            max: None,
            slot,
        });
    }
    for (i, s) in params::SPECS.iter().enumerate() {
        v.push(Var {
            name: s.name.into(),
            vr: VR_PARAM0 + i as u32,
            kind: Kind::Real,
            causality: Parameter,
            unit: unit_of(s.unit),
            description: format!("{} [{}]; {UNSET}", s.description, s.effect),
            start: Start::Real(cfg.params.get(s.id)),
            min: Some(s.min),
            max: if s.max.is_finite() { Some(s.max) } else { None },
            slot: Slot::Param(s.id),
        });
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    #[test]
    fn value_references_and_names_are_unique_and_units_defined() {
        let t = table();
        let mut vrs = HashSet::new();
        let mut names = HashSet::new();
        for v in &t {
            assert!(vrs.insert(v.vr), "duplicate value reference {}", v.vr);
            assert!(names.insert(v.name.clone()), "duplicate name {}", v.name);
            if let Some(u) = v.unit {
                assert!(
                    UNITS.iter().any(|d| d.name == u),
                    "{}: unit {u} not defined",
                    v.name
                );
            }
            assert!(!v.description.is_empty(), "{} has no description", v.name);
        }
        for s in params::SPECS {
            assert!(
                t.iter().any(|v| v.name == s.name),
                "parameter {} missing",
                s.name
            );
        }
    }

    #[test]
    fn unit_factors_match_the_parameter_registry() {
        for s in params::SPECS {
            if let Some(u) = unit_of(s.unit) {
                let d = UNITS.iter().find(|d| d.name == u).expect("unit defined");
                if u != "degC" {
                    let rel = (d.factor - s.to_si).abs() / s.to_si.abs();
                    assert!(
                        rel < 1e-12,
                        "{}: unit {u} factor {} vs to_si {}",
                        s.name,
                        d.factor,
                        s.to_si
                    );
                }
            }
        }
    }
}
