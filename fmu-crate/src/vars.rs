//! The one table of FMU variables: name, value reference, type, causality, unit, start, description; drives get/set, the state layout and the XML.
//!
//! Each variable is declared once. The contact's inputs and outputs, the material, friction
//! and thermal parameters and the effect switches are rows of creep-core's tables
//! (`engine::io::INPUTS`, `engine::io::OUTPUTS`, `params::SPECS`, `effects::CATALOGUE`), each
//! with its fixed value reference; the auxiliary inputs and the geometry parameters are
//! declared below (`In::Aux`, `geometry_variables!`); the remaining parameters (geometry
//! mode, nx, ny, threads, scheme, model, preset, config_file, columns) are one [`Var`] each
//! in [`table`].
//!
//! Adding a variable:
//! * an output, an input, a material parameter or an effect: its row in creep-core's table,
//!   nothing here (get/set, validation, the XML and both state formats follow; states store
//!   values by name, so states of earlier builds still load);
//! * a geometry parameter: a line in `geometry_variables!`;
//! * another parameter: a [`Var`] in [`table`] with a new [`Slot`], and what it does in
//!   `settings.rs` (check, apply, get, and its use in `Settings::resolve`).

use creep_core::config::DEFAULT_GEOMETRY;
use creep_core::effects::{self, Effect};
use creep_core::engine::io::{input_spec, InputId, OutputSpec, INPUTS, N_OUTPUTS, OUTPUTS};
use creep_core::params::{self, P};
use creep_core::{Config, Geometry, Inputs};

/// The start value of `rel_tol`: 2 %, the tolerance whose choice runs in real time at 20 m/s
/// with 0.25 ms steps for each of dry, table4.1 and wet (docs/fmu.md, "Grid and scheme for a
/// tolerance").
pub const DEFAULT_REL_TOL: f64 = 0.02;

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

/// One of the inputs of a contact: a row of creep-core's `INPUTS` or an auxiliary input;
/// [`In::ALL`] is their order (the layout of the input values of an instance).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum In {
    /// An input of the core model (its row of creep-core's `INPUTS`).
    Core(InputId),
    /// Auxiliary input 1..[`N_AUX`] (index 0..): a data column of formula or custom effects.
    Aux(usize),
}

/// Number of auxiliary inputs.
pub const N_AUX: usize = 4;
/// Number of contact inputs (those of the core's [`Inputs`]); the auxiliary inputs follow.
pub const N_CORE_INPUTS: usize = INPUTS.len();
/// Number of inputs (the contact inputs and the auxiliary inputs).
pub const N_INPUTS: usize = N_CORE_INPUTS + N_AUX;
/// Value reference of `aux1` (the others follow).
pub const VR_AUX0: u32 = 90;

impl In {
    /// Every input, in layout order.
    pub const ALL: [In; N_INPUTS] = {
        let mut all = [In::Aux(0); N_INPUTS];
        let mut i = 0;
        while i < N_INPUTS {
            all[i] = if i < N_CORE_INPUTS {
                In::Core(INPUTS[i].id)
            } else {
                In::Aux(i - N_CORE_INPUTS)
            };
            i += 1;
        }
        all
    };

    /// Position in the input values of an instance (creep-core's `INPUTS` is indexed by
    /// [`InputId`]; the auxiliary inputs follow).
    pub const fn index(self) -> usize {
        match self {
            In::Core(id) => id as usize,
            In::Aux(k) => N_CORE_INPUTS + k,
        }
    }

    /// Name in modelDescription.xml.
    pub fn name(self) -> String {
        match self {
            In::Core(id) => input_spec(id).name.to_string(),
            In::Aux(k) => format!("aux{}", k + 1),
        }
    }

    /// Start value (modelDescription.xml): the value of an input that a serialized state of
    /// an earlier build does not hold.
    pub fn start(self) -> f64 {
        match self {
            In::Core(id) => input_spec(id).default,
            In::Aux(_) => 0.0,
        }
    }

    fn var(self) -> Var {
        let (vr, unit, description) = match self {
            In::Core(id) => {
                let s = input_spec(id);
                (s.vr, unit_of(s.unit), s.description.to_string())
            }
            In::Aux(k) => (VR_AUX0 + k as u32, None, aux_description(k)),
        };
        real(
            self.name(),
            vr,
            Causality::Input,
            unit,
            Start::Real(self.start()),
            description,
            Slot::Input(self),
        )
    }
}

/// The core inputs of FMU input values, as they are (see [`core_inputs`]).
fn core_fields(x: &[f64; N_INPUTS]) -> Inputs {
    let mut i = Inputs::default();
    for s in INPUTS {
        (s.set)(&mut i, x[In::Core(s.id).index()]);
    }
    i
}

/// One of the outputs of a contact: a row of creep-core's `OUTPUTS` (by its position there).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Out(usize);

impl Out {
    /// Every output, in the order of the table.
    pub const ALL: [Out; N_OUTPUTS] = {
        let mut all = [Out(0); N_OUTPUTS];
        let mut i = 0;
        while i < N_OUTPUTS {
            all[i] = Out(i);
            i += 1;
        }
        all
    };

    /// Its row of creep-core's `OUTPUTS`.
    pub fn spec(self) -> &'static OutputSpec {
        &OUTPUTS[self.0]
    }

    /// The value of this output in a core [`creep_core::Outputs`].
    pub fn of(self, o: &creep_core::Outputs) -> f64 {
        (self.spec().get)(o)
    }

    /// Name in modelDescription.xml.
    pub fn name(self) -> &'static str {
        self.spec().name
    }

    fn var(self) -> Var {
        let s = self.spec();
        real(
            s.name.into(),
            s.vr,
            Causality::Output,
            unit_of(s.unit),
            Start::None,
            s.description.into(),
            Slot::Output(self),
        )
    }
}

/// Generates, from the one declaration of the geometry parameters below, the enum [`Geo`]
/// with each parameter's name, value reference, unit, mode, start and description.
macro_rules! geometry_variables {
    (
        $( $(#[$geo_doc:meta])* $geo:ident = $geo_vr:literal, $geo_name:literal, $geo_unit:literal, mode $geo_mode:literal, start $geo_start:expr, $geo_desc:literal; )*
    ) => {
        /// Geometry parameters (SI); [`Geo::ALL`] is their order (of `Settings::geo` and of
        /// the serialized state).
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum Geo {
            $( $(#[$geo_doc])* $geo, )*
        }

        /// Number of geometry parameters.
        pub const N_GEO: usize = [$(Geo::$geo),*].len();

        impl Geo {
            /// Every geometry parameter, in layout order.
            pub const ALL: [Geo; N_GEO] = [$(Geo::$geo),*];

            /// Position in `Settings::geo`.
            pub const fn index(self) -> usize {
                self as usize
            }

            /// Name in modelDescription.xml.
            pub fn name(self) -> &'static str {
                match self {
                    $( Geo::$geo => $geo_name, )*
                }
            }

            /// The value of the parameter `geometry` under which this parameter applies.
            pub fn mode(self) -> i32 {
                match self {
                    $( Geo::$geo => $geo_mode, )*
                }
            }

            /// Start value (a value equal to it means 'not set', see [`UNSET`]).
            pub fn start(self) -> f64 {
                match self {
                    $( Geo::$geo => $geo_start, )*
                }
            }

            fn var(self) -> Var {
                let (vr, unit, description) = match self {
                    $( Geo::$geo => ($geo_vr, $geo_unit, $geo_desc), )*
                };
                let mut v = real(self.name().into(), vr, Causality::Parameter, Some(unit), Start::Real(self.start()), format!("{description}; {UNSET}"), Slot::Geo(self));
                v.min = Some(0.0);
                v
            }
        }
    };
}

// The geometry parameters, each declared once: the order here is the order of
// modelDescription.xml; value references are fixed.
geometry_variables! {
    /// Semi-axis a at the reference load.
    ARef = 30, "a_ref", "m", mode 1, start semi_axes_start()[0], "semi-axis in rolling direction at FN_ref (geometry = 1); scales with (FN/FN_ref)^(1/3)";
    /// Semi-axis b at the reference load.
    BRef = 31, "b_ref", "m", mode 1, start semi_axes_start()[1], "lateral semi-axis at FN_ref (geometry = 1)";
    /// Reference load.
    FnRef = 32, "FN_ref", "N", mode 1, start semi_axes_start()[2], "reference normal force of a_ref, b_ref (geometry = 1)";
    /// Equivalent radius of curvature in rolling direction.
    Rx = 33, "Rx", "m", mode 2, start RX_START, "equivalent radius of curvature in rolling direction, Hertz (geometry = 2)";
    /// Equivalent lateral radius of curvature.
    Ry = 34, "Ry", "m", mode 2, start RY_START, "equivalent lateral radius of curvature, Hertz (geometry = 2)";
}

/// The core inputs of FMU input values (FN <= 0 is lift-off: F_N = 0).
pub fn core_inputs(x: &[f64; N_INPUTS]) -> Inputs {
    let mut i = core_fields(x);
    // NaN stays NaN so that validation rejects it
    if i.fn_n < 0.0 {
        i.fn_n = 0.0;
    }
    i
}

fn aux_description(k: usize) -> String {
    format!("auxiliary input {}: the value of a data column used by formula or custom effects of the configuration, mapped by the parameter columns (e.g. columns = \"humidity=aux{}\"); unused otherwise", k + 1, k + 1)
}

/// Start values of a_ref, b_ref, FN_ref: the semi-axes of the default configuration.
fn semi_axes_start() -> [f64; 3] {
    match default_config().geometry {
        Geometry::SemiAxes { a, b, fn_ref } => [a, b, fn_ref],
        _ => [7.63e-3, 7.88e-3, 110e3],
    }
}

/// A Real variable without bounds.
fn real(
    name: String,
    vr: u32,
    causality: Causality,
    unit: Option<&'static str>,
    start: Start,
    description: String,
    slot: Slot,
) -> Var {
    Var {
        name,
        vr,
        kind: Kind::Real,
        causality,
        unit,
        description,
        start,
        min: None,
        max: None,
        slot,
    }
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
    /// Relative tolerance on F_x that chooses the grid and scheme (0: off).
    RelTol,
    /// How the local temperature of a bristle move is solved (0 the configuration's, 1
    /// exact, 2 predictor-corrector).
    TemperatureSolve,
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

/// A value of an fmi2Set* or fmi2Get* call.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// fmi2Real.
    Real(f64),
    /// fmi2Integer.
    Integer(i32),
    /// fmi2Boolean.
    Boolean(bool),
    /// fmi2String.
    String(String),
}

impl Value {
    /// Base type of the value.
    pub fn kind(&self) -> Kind {
        match self {
            Value::Real(_) => Kind::Real,
            Value::Integer(_) => Kind::Integer,
            Value::Boolean(_) => Kind::Boolean,
            Value::String(_) => Kind::String,
        }
    }

    /// The value as it appears in messages.
    pub fn show(&self) -> String {
        match self {
            Value::Real(x) => x.to_string(),
            Value::Integer(x) => x.to_string(),
            Value::Boolean(x) => x.to_string(),
            Value::String(x) => format!("'{x}'"),
        }
    }
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
        scheme: creep_core::ModelKind::Ecf.default_scheme(),
        temperature_solve: Default::default(),
        geometry: DEFAULT_GEOMETRY,
        modifiers: Vec::new(),
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
    let mut v: Vec<Var> = In::ALL.iter().map(|i| i.var()).collect();
    v.extend(Out::ALL.iter().map(|o| o.var()));
    v.extend(Geo::ALL.iter().map(|g| g.var()));
    use Causality::*;
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
        description: "how a step advances the bristles (the start value 0 means 'not set': the scheme rel_tol chooses, else a configuration file's `scheme`, else the model's default: 2 for ECF, 3 for FASTSIM and Polach): 1 continuous sub-steps of up to 8 cells, one-cell pieces at the trailing edge and at the end of each step (2-4x faster than 3 at 0.1-1 ms steps on 80 x 21; its step dependence up to about 1 %, forces within 1.5 % of 3 under inputs that jump at every step), 2 cell by cell with higher-order rules along each move (about 2x the cost of 3 on the same grid, 2-4x smaller errors; ECF's same-characteristic layer only, others run 3; docs/fmu.md), 3 cell by cell (the first-order reference, independent of the communication step within 0.5 %)".into(),
        start: Start::Integer(0),
        min: Some(0.0),
        max: Some(3.0),
        slot: Slot::Scheme,
    });
    for info in effects::CATALOGUE {
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
            vr: info.vr,
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
    for s in params::SPECS {
        v.push(Var {
            name: s.name.into(),
            vr: s.vr,
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
    // added after the released variables, so that none of their indices moves
    v.push(Var {
        name: "rel_tol".into(),
        vr: 45,
        kind: Kind::Real,
        causality: Parameter,
        unit: None,
        description: format!("relative tolerance on F_x, a fraction (0.01 = 1 %), ECF model only (FASTSIM, Polach: ignored). > 0: at fmi2ExitInitializationMode the grid and scheme are the cheapest in the accuracy benchmark's table (creep-core/data/accuracy.csv) whose largest F_x error, measured for the preset (unchanged; else the worst over dry, table4.1 and wet) at the nearest tabulated speed not below |v| (the value of v then), meets it, else the cheapest that cannot be ranked below the most accurate (with a warning). Start {DEFAULT_REL_TOL}: real time at 20 m/s with 0.25 ms steps; it does not apply when nx and ny are both given. 0 = off: the grid comes from nx, ny and the preset (80 x 21). A value set explicitly with nx, ny or scheme = 1 or 2 (or a configuration file's scheme other than cells) chooses among the table's rows with them (docs/fmu.md)"),
        start: Start::Real(DEFAULT_REL_TOL),
        min: Some(0.0),
        max: Some(1.0),
        slot: Slot::RelTol,
    });
    v.push(temperature_solve_var());
    v
}

/// The parameter `temperature_solve` (added after `rel_tol`, so that no earlier index moves).
fn temperature_solve_var() -> Var {
    Var {
    name: "temperature_solve".into(),
    vr: 46,
    kind: Kind::Integer,
    causality: Causality::Parameter,
    unit: None,
    description: "how the local temperature of each bristle move (seed Eq. 4.35) is solved (the start value 0 means 'not set': a configuration file's `temperature_solve`, else the predictor-corrector): 1 exact, the implicit solve to 1e-10 relative change of the softening factors (the reference); 2 the predictor-corrector, two or three evaluations of the material law per move, within 0.025 % of 1 in F_x, P_fric and the T_max rise on the accuracy benchmark (docs/model.md section 6). A setting of the instance like threads: a restored state keeps it".into(),
    start: Start::Integer(0),
    min: Some(0.0),
    max: Some(2.0),
    slot: Slot::TemperatureSolve,
}
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
