//! One FMU instance as a safe FMI state machine: the call rules (one table, [`Call::allowed_in`]), the inputs, the core model and messages for the logger; the contact settings live in [`crate::settings`].
//!
//! This file holds the state machine (phases, call rules, life cycle, steps, FMU states);
//! `values` gets and sets variables by value reference, `uri` turns the resource URI into
//! a path.

use crate::settings::{extras_for, Settings};
use crate::vars::{
    self, core_inputs, Causality, Geo, In, Kind, Out, Slot, Start, Value, Var, N_INPUTS,
};
use creep_core::engine::io::InputId;
use creep_core::engine::Scheme;
use creep_core::{Config, Model, Outputs};
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

mod uri;
mod values;

pub use uri::uri_to_path;

/// FMI status of a call.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Status {
    /// fmi2OK.
    Ok,
    /// fmi2Warning.
    Warning,
    /// fmi2Discard.
    Discard,
    /// fmi2Error.
    Error,
}

/// State of the FMI 2.0 Co-Simulation state machine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// After fmi2Instantiate or fmi2Reset.
    Instantiated,
    /// Between fmi2EnterInitializationMode and fmi2ExitInitializationMode.
    Initialization,
    /// Initialized: fmi2DoStep may be called.
    StepComplete,
    /// After fmi2Terminate.
    Terminated,
    /// After an internal error (panic): only reset, set state and free are useful.
    Error,
}

impl Phase {
    /// The mode's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            Phase::Instantiated => "Instantiated",
            Phase::Initialization => "InitializationMode",
            Phase::StepComplete => "StepComplete",
            Phase::Terminated => "Terminated",
            Phase::Error => "Error",
        }
    }
}

/// A call whose phase the instance checks (a row of [`Call::allowed_in`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Call {
    /// fmi2SetupExperiment.
    SetupExperiment,
    /// fmi2EnterInitializationMode.
    EnterInitializationMode,
    /// fmi2ExitInitializationMode.
    ExitInitializationMode,
    /// fmi2DoStep.
    DoStep,
    /// fmi2Terminate.
    Terminate,
    /// fmi2GetReal, fmi2GetInteger, fmi2GetBoolean, fmi2GetString.
    Get,
    /// fmi2Set* of an input.
    SetInput,
    /// fmi2Set* of a (fixed) parameter.
    SetParameter,
    /// fmi2Set* of an output.
    SetOutput,
    /// fmi2GetFMUstate.
    GetFMUstate,
}

impl Call {
    /// The FMI 2.0 Co-Simulation call rules, one table (like `MASK_fmi2*` in the Reference
    /// FMUs' src/fmi2Functions.c): the phases in which each call is allowed, in [`Phase`]
    /// order. Calls not listed (fmi2Reset, fmi2FreeInstance, fmi2SetDebugLogging,
    /// fmi2SetFMUstate of an initialized state, the FMU state and status functions) are
    /// allowed in every phase.
    pub const fn allowed_in(self) -> &'static [Phase] {
        use Phase::*;
        match self {
            Call::SetupExperiment => &[Instantiated],
            Call::EnterInitializationMode => &[Instantiated],
            Call::ExitInitializationMode => &[Initialization],
            Call::DoStep => &[StepComplete],
            Call::Terminate => &[StepComplete],
            Call::Get => &[Initialization, StepComplete, Terminated, Error],
            Call::SetInput => &[Instantiated, Initialization, StepComplete],
            Call::SetParameter => &[Instantiated, Initialization],
            Call::SetOutput => &[],
            Call::GetFMUstate => &[Instantiated, Initialization, StepComplete, Terminated],
        }
    }

    /// The call of a set of a variable of this causality.
    pub fn set(c: Causality) -> Call {
        match c {
            Causality::Input => Call::SetInput,
            Causality::Parameter => Call::SetParameter,
            Causality::Output => Call::SetOutput,
        }
    }
}

/// A message for the importer's logger.
#[derive(Clone, Debug, PartialEq)]
pub struct LogMsg {
    /// Status the message reports.
    pub status: Status,
    /// Log category (see `model_description::LOG_CATEGORIES`).
    pub category: &'static str,
    /// The message, already formatted.
    pub text: String,
}

/// Everything an FMU state holds: settings, inputs, time and the whole core model
/// (bristle grid and heat histories).
#[derive(Clone, Debug)]
pub struct Snapshot {
    /// Parameter settings.
    pub settings: Settings,
    /// Input values as set (FN not clamped).
    pub inputs: [f64; N_INPUTS],
    /// Communication time, s.
    pub time: f64,
    /// Resolved configuration (None if it was not resolved when the state was taken).
    pub cfg: Option<Config>,
    /// The core model (None before initialization).
    pub model: Option<Model>,
    /// The mode the instance was in when the state was taken; fmi2SetFMUstate restores it
    /// (as the Modelica Association's reference FMUs do), so an importer can continue a
    /// state in a freshly instantiated instance without initializing it.
    pub phase: Phase,
    /// The scheme `rel_tol` chose for the model (None: none chose one). It travels with the
    /// state as the grid it chose does (in the model's configuration): a state continues
    /// in the scheme it was computed in, also in a fresh instance.
    pub tol_scheme: Option<Scheme>,
}

/// The first non-finite output, as `name = value`.
fn non_finite(o: &Outputs) -> Option<String> {
    Out::ALL
        .iter()
        .map(|k| (k.name(), k.of(o)))
        .find(|(_, x)| !x.is_finite())
        .map(|(n, x)| format!("{n} = {x}"))
}

/// Checks a snapshot like the inputs and parameters of set calls: a deserialized state with
/// a NaN time, an infinite creepage or an out-of-range parameter is refused, not restored.
pub fn validate_snapshot(s: &Snapshot) -> Result<(), String> {
    if !s.time.is_finite() {
        return Err(format!("time = {} s is not finite", s.time));
    }
    for i in In::ALL {
        let x = s.inputs[i.index()];
        if !x.is_finite() {
            return Err(format!("input {} = {x} is not finite", i.name()));
        }
    }
    core_inputs(&s.inputs)
        .validate()
        .map_err(|e| format!("inputs: {e}"))?;
    s.settings.validate()?;
    match (s.phase, &s.model) {
        (Phase::Error, _) => return Err("it was taken in the error state".into()),
        (Phase::StepComplete | Phase::Terminated, None) => {
            return Err(format!(
                "it was taken in mode {} but holds no model",
                s.phase.name()
            ))
        }
        _ => {}
    }
    if let Some(m) = &s.model {
        if !m.time().is_finite() {
            return Err(format!("model time = {} s is not finite", m.time()));
        }
        let o = m.outputs();
        if let Some(x) = o.to_array().iter().find(|x| !x.is_finite()) {
            return Err(format!("an output of the model is {x}"));
        }
        // the area fractions of the bristle regimes: each in [0, 1], together 1 (0 at lift-off),
        // up to the rounding of summing the cells' areas (below 1e-9 on the largest grid,
        // 2000 x 1000: n eps = 2e-10)
        let fr = [o.frac_elastic, o.frac_plastic, o.frac_sliding];
        let sum: f64 = fr.iter().sum();
        if fr.iter().any(|x| !(-1e-9..=1.0 + 1e-9).contains(x))
            || !((sum - 1.0).abs() <= 1e-9 || sum == 0.0)
        {
            return Err(format!(
                "the area fractions elastic/plastic/sliding {}/{}/{} do not sum to 1",
                fr[0], fr[1], fr[2]
            ));
        }
    }
    Ok(())
}

/// One instance of the contact FMU.
pub struct Instance {
    /// Instance name given by the importer.
    pub name: String,
    resources: Option<PathBuf>,
    table: Vec<Var>,
    index: HashMap<u32, usize>,
    settings: Settings,
    inputs: [f64; N_INPUTS],
    phase: Phase,
    time: f64,
    cfg: Option<Config>,
    /// Whether the configuration file gives a `grid` (for rel_tol), as the last read of the
    /// file found; None when it was not read since the settings last changed or a state
    /// was restored.
    file_grid: Option<bool>,
    model: Option<Model>,
    /// True if `model` holds the outputs of the current inputs and settings (Init mode).
    model_current: bool,
    /// The last fmi2ExitInitializationMode failed (no FMU state is handed out until one succeeds).
    init_failed: bool,
    /// The scheme rel_tol chose when the model was built (None: rel_tol off or not applied).
    tol_scheme: Option<Scheme>,
    logs: Vec<LogMsg>,
    log_events: bool,
    seen: HashSet<String>,
}

impl Instance {
    /// A new instance; `resource_uri` is the importer's fmuResourceLocation.
    pub fn new(name: &str, resource_uri: Option<&str>, logging_on: bool) -> Self {
        let table = vars::table();
        let index = table.iter().enumerate().map(|(i, v)| (v.vr, i)).collect();
        let mut inst = Instance {
            name: name.to_string(),
            resources: resource_uri.and_then(uri_to_path),
            table,
            index,
            settings: Settings::default(),
            inputs: [0.0; N_INPUTS],
            phase: Phase::Instantiated,
            time: 0.0,
            cfg: None,
            file_grid: None,
            model: None,
            model_current: false,
            init_failed: false,
            tol_scheme: None,
            logs: Vec::new(),
            log_events: logging_on,
            seen: HashSet::new(),
        };
        inst.reset_values();
        if let Some(u) = resource_uri {
            if inst.resources.is_none() {
                inst.warn(format!("fmi2Instantiate: fmuResourceLocation '{u}' is not a local file URI; relative config_file paths cannot be resolved"));
            }
        }
        inst
    }

    /// A new instance of the FMI 3.0 FMU; `resource_dir` is the importer's resourcePath (an
    /// absolute path of the resources folder, with or without a trailing separator).
    pub fn new_with_resource_dir(name: &str, resource_dir: Option<&str>, logging_on: bool) -> Self {
        let mut inst = Self::new(name, None, logging_on);
        inst.resources = resource_dir.filter(|d| !d.is_empty()).map(PathBuf::from);
        inst
    }

    fn reset_values(&mut self) {
        self.settings = Settings::default();
        for v in &self.table {
            if let (Slot::Input(i), Start::Real(x)) = (v.slot, &v.start) {
                self.inputs[i.index()] = *x;
            }
        }
        self.phase = Phase::Instantiated;
        self.time = 0.0;
        self.cfg = None;
        self.file_grid = None;
        self.model = None;
        self.model_current = false;
        self.init_failed = false;
        self.tol_scheme = None;
        self.seen.clear();
    }

    /// The current phase.
    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// Communication time, s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The variable table.
    pub fn table(&self) -> &[Var] {
        &self.table
    }

    /// The core model (after initialization).
    pub fn model(&self) -> Option<&Model> {
        self.model.as_ref()
    }

    /// Drains the messages for the logger.
    pub fn take_logs(&mut self) -> Vec<LogMsg> {
        std::mem::take(&mut self.logs)
    }

    /// Logs an error and returns `Status::Error`.
    pub fn error(&mut self, text: String) -> Status {
        self.logs.push(LogMsg {
            status: Status::Error,
            category: "logStatusError",
            text,
        });
        Status::Error
    }

    /// Logs a warning and returns `Status::Warning`.
    pub fn warn(&mut self, text: String) -> Status {
        self.logs.push(LogMsg {
            status: Status::Warning,
            category: "logStatusWarning",
            text,
        });
        Status::Warning
    }

    fn event(&mut self, text: String) {
        if self.log_events {
            self.logs.push(LogMsg {
                status: Status::Ok,
                category: "logEvents",
                text,
            });
        }
    }

    /// An internal failure (a caught panic): the instance goes to the error state.
    pub fn internal_error(&mut self, func: &str, what: &str) -> Status {
        self.phase = Phase::Error;
        self.error(format!("{func}: internal error ({what}); the instance is in the error state, call fmi2Reset or fmi2SetFMUstate"))
    }

    /// fmi2SetDebugLogging: switches categories (all of them if `categories` is empty).
    /// Warnings and errors are always reported; the switch controls the debug category.
    pub fn set_debug_logging(&mut self, on: bool, categories: &[String]) -> Status {
        if categories.is_empty() {
            self.log_events = on;
            return Status::Ok;
        }
        let mut st = Status::Ok;
        for c in categories {
            match c.as_str() {
                "logEvents" => self.log_events = on,
                "logStatusWarning" | "logStatusError" => {}
                _ => {
                    st = st.max(self.error(format!(
                        "fmi2SetDebugLogging: unknown log category '{c}'; accepted: logEvents, logStatusWarning, logStatusError"
                    )))
                }
            }
        }
        st
    }

    /// True if the call table allows `call` in the current phase.
    fn allows(&self, call: Call) -> bool {
        call.allowed_in().contains(&self.phase)
    }

    /// Checks `call` against the call table; logs the refusal.
    fn check_phase(&mut self, func: &str, call: Call) -> Result<(), Status> {
        if self.allows(call) {
            Ok(())
        } else {
            let names: Vec<&str> = call.allowed_in().iter().map(|p| p.name()).collect();
            Err(self.error(format!(
                "{func}: not allowed in state {} (allowed in: {})",
                self.phase.name(),
                names.join(", ")
            )))
        }
    }

    /// fmi2SetupExperiment.
    pub fn setup_experiment(&mut self, start: f64) -> Status {
        if let Err(s) = self.check_phase("fmi2SetupExperiment", Call::SetupExperiment) {
            return s;
        }
        if !start.is_finite() {
            return self.error(format!(
                "fmi2SetupExperiment: startTime = {start} must be finite"
            ));
        }
        self.time = start;
        Status::Ok
    }

    /// fmi2EnterInitializationMode.
    pub fn enter_initialization(&mut self) -> Status {
        if let Err(s) =
            self.check_phase("fmi2EnterInitializationMode", Call::EnterInitializationMode)
        {
            return s;
        }
        self.phase = Phase::Initialization;
        Status::Ok
    }

    /// fmi2ExitInitializationMode: resolves the configuration, builds the model and sets
    /// its bristle grid to the steady state of the current inputs.
    pub fn exit_initialization(&mut self) -> Status {
        if let Err(s) = self.check_phase("fmi2ExitInitializationMode", Call::ExitInitializationMode)
        {
            return s;
        }
        let mut st = Status::Ok;
        let mode = self.settings.geometry;
        for g in Geo::ALL {
            if g.mode() != mode && self.settings.geo[g.index()].is_some() {
                let (n, m) = (g.name(), g.mode());
                let what = if m == 1 { "semi-axes" } else { "curvatures" };
                st = st.max(self.warn(format!("fmi2ExitInitializationMode: {n} was set but geometry = {mode} (not {m}, {what}): {n} is ignored")));
            }
        }
        if let Err(e) = self.current_outputs() {
            // no half-built model stays behind; the instance stays in initialization mode, so
            // that the importer can correct a parameter and call fmi2ExitInitializationMode
            // again, but hands out no FMU state until then (or fmi2Reset)
            self.model = None;
            self.model_current = false;
            self.init_failed = true;
            return self.error(format!("fmi2ExitInitializationMode: {e}"));
        }
        self.init_failed = false;
        self.phase = Phase::StepComplete;
        // the configuration as built, and the scheme the model runs (rel_tol's or the
        // parameter's may differ from the configuration's)
        let (cfg, running) = self
            .model
            .as_ref()
            .map(|m| {
                let running = m
                    .scheme()
                    .map_or(String::new(), |s| format!("; running scheme {}", s.name()));
                (m.config().to_json().to_string(), running)
            })
            .unwrap_or_default();
        self.event(format!(
            "fmi2ExitInitializationMode: initialized at t = {} s with {cfg}{running}",
            self.time
        ));
        st = st.max(self.log_tolerance_choice());
        st.max(self.drain_model_warnings("fmi2ExitInitializationMode"))
    }

    /// Logs what rel_tol chose at initialization: the grid, scheme and tabulated error as an
    /// event (logEvents); a warning when the tolerance is not met, when the table has no row
    /// for the explicit settings, or when the model is not ECF.
    fn log_tolerance_choice(&mut self) -> Status {
        const F: &str = "fmi2ExitInitializationMode";
        let tol = self.rel_tol();
        if tol <= 0.0 {
            return Status::Ok;
        }
        let Some(cfg) = self.model.as_ref().map(|m| m.config().clone()) else {
            return Status::Ok;
        };
        let file_grid = self.file_grid();
        match self
            .settings
            .tolerance_choice(&cfg, self.speed(), file_grid)
        {
            // the start value is no request: FASTSIM and Polach ignore it silently
            None if self.settings.rel_tol.is_none() => Status::Ok,
            None => self.warn(format!(
                "{F}: rel_tol = {tol} is ignored: the accuracy table is measured for the ECF model, not {}; the grid comes from nx, ny and the configuration",
                cfg.model.name()
            )),
            Some(Err(e)) => self.warn(format!("{F}: {e}")),
            Some(Ok(c)) => {
                let text = format!("{F}: rel_tol = {tol} at v = {} m/s: {}", self.speed(), c.message());
                // the start value is no request: not met, it is said as an event
                if c.met || self.settings.rel_tol.is_none() {
                    self.event(text);
                    Status::Ok
                } else {
                    self.warn(text)
                }
            }
        }
    }

    /// fmi2Terminate.
    pub fn terminate(&mut self) -> Status {
        if let Err(s) = self.check_phase("fmi2Terminate", Call::Terminate) {
            return s;
        }
        self.phase = Phase::Terminated;
        Status::Ok
    }

    /// fmi2Reset: back to the state after instantiation, with start values.
    pub fn reset(&mut self) -> Status {
        self.reset_values();
        Status::Ok
    }

    fn drain_model_warnings(&mut self, func: &str) -> Status {
        let ws = self
            .model
            .as_mut()
            .map(|m| m.take_warnings())
            .unwrap_or_default();
        let mut st = Status::Ok;
        for w in ws {
            if self.seen.insert(w.clone()) {
                st = st.max(self.warn(format!("{func}: {w} (reported once)")));
            }
        }
        st
    }

    /// fmi2DoStep: advances the contact by `h` seconds with the inputs held constant.
    ///
    /// A call refused for the call sequence (the instance is not in StepComplete) leaves the
    /// mode as it is. Any other fmi2Error (an argument that is refused, a step of the model
    /// that fails or gives non-finite outputs) puts the instance in the error state, as the
    /// FMI 2.0 standard says of fmi2Error ("the simulation cannot be continued with this FMU
    /// instance"; the Reference FMUs go to their terminal state on every error of fmi2DoStep):
    /// only fmi2Get* (inputs and parameters; outputs are refused, the last step did not
    /// complete), fmi2GetStatus and fmi2GetRealStatus for diagnosis, fmi2SetFMUstate of an
    /// earlier state, fmi2Reset and fmi2FreeInstance are accepted there.
    pub fn do_step(&mut self, t: f64, h: f64) -> Status {
        if let Err(s) = self.check_phase("fmi2DoStep", Call::DoStep) {
            return s;
        }
        match self.try_step(t, h) {
            Ok(()) => {
                self.time = t + h;
                self.drain_model_warnings("fmi2DoStep")
            }
            Err(e) => {
                self.phase = Phase::Error;
                self.error(format!(
                    "fmi2DoStep: {e}; the instance is in the error state (call fmi2Reset, or fmi2SetFMUstate to an earlier state)"
                ))
            }
        }
    }

    /// The work of fmi2DoStep in StepComplete; an error is the message (without the function's
    /// name).
    fn try_step(&mut self, t: f64, h: f64) -> Result<(), String> {
        if !(h.is_finite() && h >= 0.0) {
            return Err(format!(
                "communicationStepSize = {h} must be finite and >= 0 s"
            ));
        }
        let tol = 1e-9 * self.time.abs().max(1.0);
        if !t.is_finite() || (t - self.time).abs() > tol {
            return Err(format!(
                "currentCommunicationPoint = {t} s, but the FMU is at t = {} s (set an FMU state to go back in time)",
                self.time
            ));
        }
        let inputs = core_inputs(&self.inputs);
        let extra = match self.model.as_ref().map(|m| self.extras(m.config())) {
            Some(x) => x?,
            None => None,
        };
        let Some(model) = self.model.as_mut() else {
            return Err("no model (not initialized)".into());
        };
        if let Some(x) = &extra {
            model.set_extra(x).map_err(|e| e.to_string())?;
        }
        model
            .step(h, &inputs)
            .map_err(|e| format!("step of {h} s from t = {t} s failed: {e}"))?;
        if let Some(bad) = non_finite(&model.outputs()) {
            return Err(format!(
                "the step of {h} s from t = {t} s gave non-finite outputs ({bad})"
            ));
        }
        Ok(())
    }

    /// fmi2GetRealStatus(fmi2LastSuccessfulTime).
    pub fn last_successful_time(&self) -> f64 {
        self.time
    }

    /// fmi2GetFMUstate: a copy of everything the instance holds (refused in the error
    /// state, whose outputs are not valid).
    pub fn try_get_state(&mut self) -> Result<Snapshot, Status> {
        if !self.allows(Call::GetFMUstate) {
            return Err(self.error(
                "fmi2GetFMUstate: the instance is in the error state; its state is not saved (fmi2Reset or fmi2SetFMUstate first)".into(),
            ));
        }
        if self.init_failed {
            return Err(self.error(
                "fmi2GetFMUstate: the last fmi2ExitInitializationMode failed; its state is not saved (correct the parameters and call fmi2ExitInitializationMode again, or fmi2Reset)".into(),
            ));
        }
        Ok(self.get_state())
    }

    /// A copy of everything the instance holds.
    pub fn get_state(&mut self) -> Snapshot {
        let cfg = self
            .model
            .as_ref()
            .map(|m| m.config().clone())
            .or_else(|| self.cfg.clone());
        Snapshot {
            settings: self.settings.clone(),
            inputs: self.inputs,
            time: self.time,
            cfg,
            model: self.model.clone(),
            phase: self.phase,
            tol_scheme: self.tol_scheme,
        }
    }

    /// Gives the model the importer's `threads`, `scheme` and `temperature_solve` (settings
    /// of the instance, not of a state: they say how to compute, not what).
    fn apply_how_to_compute(&mut self) -> Result<(), String> {
        let (n, scheme) = (self.settings.threads.max(1), self.scheme());
        let solve = self.settings.temperature_solve();
        match self.model.as_mut() {
            Some(m) => {
                m.set_scheme(scheme.unwrap_or(m.config().scheme));
                m.set_temperature_solve(solve.unwrap_or(m.config().temperature_solve));
                m.set_threads(n).map_err(|e| e.to_string())
            }
            None => Ok(()),
        }
    }

    /// fmi2SetFMUstate: restores a snapshot.
    pub fn set_state(&mut self, s: &Snapshot) -> Status {
        const F: &str = "fmi2SetFMUstate";
        if let Err(e) = validate_snapshot(s) {
            return self.error(format!(
                "{F}: the state is refused ({e}); the instance is unchanged"
            ));
        }
        // the importer's threads, scheme, temperature_solve and rel_tol stay (a serialized
        // state does not carry them); the scheme rel_tol chose comes with the state, as the
        // grid does
        let (threads, scheme, rel_tol) = (
            self.settings.threads,
            self.settings.scheme,
            self.settings.rel_tol,
        );
        let solve = self.settings.temperature_solve;
        // a state taken before initialization completed holds at most a provisional model (the
        // steady state of the inputs it had then): it is rebuilt from the restored inputs at
        // fmi2ExitInitializationMode, as in the instance that took it
        let live = matches!(s.phase, Phase::StepComplete | Phase::Terminated);
        let mut model = if live { s.model.clone() } else { None };
        if let Some(m) = model.as_mut() {
            // else the configuration's (that of the state)
            let scheme = s.tol_scheme.or(self.settings.scheme());
            m.set_scheme(scheme.unwrap_or(m.config().scheme));
            let by_code = self.settings.temperature_solve();
            m.set_temperature_solve(by_code.unwrap_or(m.config().temperature_solve));
            if let Err(e) = m.set_threads(threads.max(1)) {
                return self.error(format!("{F}: {e}; the instance is unchanged"));
            }
        }
        self.settings = s.settings.clone();
        self.settings.threads = threads;
        self.settings.scheme = scheme;
        self.settings.temperature_solve = solve;
        self.settings.rel_tol = rel_tol;
        self.inputs = s.inputs;
        self.time = s.time;
        self.cfg = s.cfg.clone();
        self.file_grid = None;
        self.model = model;
        self.model_current = self.model.is_some();
        self.tol_scheme = s.tol_scheme;
        // the mode the state was taken in, whatever this instance's mode
        self.phase = s.phase;
        self.init_failed = false;
        self.event(format!(
            "{F}: state at t = {} s restored (mode {})",
            self.time,
            self.phase.name()
        ));
        Status::Ok
    }
}

/// The configuration resolved from `settings`, computed once into `cache`; resolving it
/// (the one read of the configuration file) also records in `file_grid` whether the file
/// gives a `grid`.
fn cached_config<'a>(
    cache: &'a mut Option<Config>,
    file_grid: &mut Option<bool>,
    settings: &Settings,
    resources: Option<&Path>,
    v: f64,
) -> Result<&'a Config, String> {
    if cache.is_none() {
        let (cfg, grid) = settings.resolve(resources, v)?;
        *cache = Some(cfg);
        *file_grid = Some(grid);
    }
    cache.as_ref().ok_or_else(|| "no configuration".to_string())
}

#[cfg(test)]
mod tests;
