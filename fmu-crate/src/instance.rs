//! One FMU instance as a safe FMI state machine: the call rules (one table, [`Call::allowed_in`]), the inputs, the core model and messages for the logger; the contact settings live in [`crate::settings`].

use crate::settings::{extras_for, Settings};
use crate::vars::{
    self, core_inputs, Causality, Geo, In, Kind, Out, Slot, Start, Value, Var, N_INPUTS,
};
use creep_core::engine::io::InputId;
use creep_core::engine::Scheme;
use creep_core::{Config, Model, Outputs};
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

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

/// Turns a file URI (fmuResourceLocation) into a path of this platform: `file:///a/b%20c/` -> `/a/b c/`.
pub fn uri_to_path(uri: &str) -> Option<PathBuf> {
    uri_to_path_for(uri, cfg!(windows)).map(PathBuf::from)
}

/// [`uri_to_path`] for a given platform. On Windows a drive letter loses the URI's leading
/// slash (`file:///C:/x` -> `C:/x`, as fmpy and the Windows tools write it) and a host names a
/// network share (`file://server/share/x` -> `//server/share/x`, a UNC path); elsewhere only
/// an empty host or `localhost` is local.
fn uri_to_path_for(uri: &str, windows: bool) -> Option<String> {
    let rest = uri
        .strip_prefix("file://")
        .or_else(|| uri.strip_prefix("file:"))?;
    let b = rest.as_bytes();
    let drive = b.len() >= 2 && b[0].is_ascii_alphabetic() && (b[1] == b':' || b[1] == b'|');
    let rest = if let Some(r) = rest.strip_prefix("localhost/") {
        format!("/{r}")
    } else if windows && drive {
        // file://C:/x and file:C:/x (malformed, but written by some Windows tools; | is the
        // old form of the drive colon)
        format!("/{}:{}", &rest[..1], &rest[2..])
    } else if windows && !rest.starts_with('/') && uri.starts_with("file://") && !rest.is_empty() {
        format!("//{rest}")
    } else {
        rest.to_string()
    };
    if !rest.starts_with('/') {
        return None;
    }
    let bytes = rest.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            let hex = std::str::from_utf8(&bytes[i + 1..i + 3]).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    let path = String::from_utf8(out).ok()?;
    let b = path.as_bytes();
    if windows
        && b.len() >= 3
        && b[0] == b'/'
        && b[1].is_ascii_alphabetic()
        && (b[2] == b':' || b[2] == b'|')
    {
        return Some(format!("{}:{}", &path[1..2], &path[3..]));
    }
    Some(path)
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
        let cfg = self
            .model
            .as_ref()
            .map(|m| m.config().to_json().to_string())
            .unwrap_or_default();
        self.event(format!(
            "fmi2ExitInitializationMode: initialized at t = {} s with {cfg}",
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
        if self.settings.rel_tol <= 0.0 {
            return Status::Ok;
        }
        let Some(cfg) = self.model.as_ref().map(|m| m.config().clone()) else {
            return Status::Ok;
        };
        let tol = self.settings.rel_tol;
        match self.settings.tolerance_choice(&cfg, self.speed()) {
            None => self.warn(format!(
                "{F}: rel_tol = {tol} is ignored: the accuracy table is measured for the ECF model, not {}; the grid comes from nx, ny and the configuration",
                cfg.model.name()
            )),
            Some(Err(e)) => self.warn(format!("{F}: {e}")),
            Some(Ok(c)) => {
                let text = format!("{F}: rel_tol = {tol} at v = {} m/s: {}", self.speed(), c.message());
                if c.met {
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

    fn var(&mut self, func: &str, vr: u32, kind: Kind) -> Result<Var, Status> {
        match self.index.get(&vr) {
            None => Err(self.error(format!("{func}: unknown value reference {vr}"))),
            Some(&i) => {
                let v = &self.table[i];
                if v.kind != kind {
                    let msg = format!(
                        "{func}: variable {} (value reference {vr}) is of type {}, not {}",
                        v.name,
                        v.kind.name(),
                        kind.name()
                    );
                    Err(self.error(msg))
                } else {
                    Ok(v.clone())
                }
            }
        }
    }

    fn check_settable(&mut self, func: &str, v: &Var) -> Result<(), Status> {
        if self.allows(Call::set(v.causality)) {
            return Ok(());
        }
        let why = match v.causality {
            Causality::Output => "it is an output".to_string(),
            Causality::Parameter => format!(
                "it is a fixed parameter and the FMU is in state {} (set it before fmi2ExitInitializationMode)",
                self.phase.name()
            ),
            Causality::Input => format!("inputs cannot be set in state {}", self.phase.name()),
        };
        Err(self.error(format!(
            "{func}: cannot set {} (value reference {}): {why}",
            v.name, v.vr
        )))
    }

    fn check_gettable(&mut self, func: &str) -> Result<(), Status> {
        self.check_phase(func, Call::Get)
    }

    fn settings_changed(&mut self) {
        self.cfg = None;
        self.model_current = false;
        if self.phase != Phase::StepComplete {
            self.model = None;
        }
    }

    fn config(&mut self) -> Result<&Config, String> {
        let v = self.inputs[In::Core(InputId::V).index()];
        cached_config(&mut self.cfg, &self.settings, self.resources.as_deref(), v)
    }

    /// The speed input v, m/s (its current value; at initialization, its start value).
    fn speed(&self) -> f64 {
        self.inputs[In::Core(InputId::V).index()]
    }

    /// The scheme the model runs: the one rel_tol chose, else the parameter `scheme`.
    fn scheme(&self) -> Scheme {
        self.tol_scheme.unwrap_or_else(|| self.settings.scheme())
    }

    /// The outputs for the current inputs: after initialization those of the last step; in
    /// initialization mode, the steady state of the current inputs (the model is built).
    fn current_outputs(&mut self) -> Result<Outputs, String> {
        if self.phase == Phase::Error {
            return Err(
                "the instance is in the error state (after a failed step); call fmi2Reset or fmi2SetFMUstate".into(),
            );
        }
        if self.phase != Phase::Initialization {
            return self
                .model
                .as_ref()
                .map(|m| m.outputs())
                .ok_or_else(|| "the model is not initialized".to_string());
        }
        if !self.model_current || self.model.is_none() {
            // a failure leaves no half-built model behind (it would be saved by
            // fmi2GetFMUstate and stepped after a restore)
            if let Err(e) = self.build_steady_model() {
                self.model = None;
                self.model_current = false;
                return Err(e);
            }
        }
        Ok(self.model.as_ref().map(|m| m.outputs()).unwrap_or_default())
    }

    /// Builds (or reuses) the model of the current configuration and sets its grid to the
    /// steady state of the current inputs (initialization mode).
    fn build_steady_model(&mut self) -> Result<(), String> {
        let cfg = self.config()?.clone();
        let rebuild = self
            .model
            .as_ref()
            .map(|m| m.config() != &cfg)
            .unwrap_or(true);
        if rebuild {
            self.model = Some(Model::new(&cfg).map_err(|e| e.to_string())?);
        }
        self.tol_scheme = match self.settings.tolerance_choice(&cfg, self.speed()) {
            Some(Ok(c)) => Some(c.scheme),
            _ => None,
        };
        self.apply_how_to_compute()?;
        let inputs = core_inputs(&self.inputs);
        let extra = self.extras(&cfg)?;
        if let Some(m) = self.model.as_mut() {
            if let Some(x) = &extra {
                m.set_extra(x).map_err(|e| e.to_string())?;
            }
            m.steady(&inputs).map_err(|e| e.to_string())?;
            if let Some(bad) = non_finite(&m.outputs()) {
                self.model = None;
                return Err(format!(
                    "the steady state of these parameters and inputs is not finite ({bad}); the model cannot be used with them"
                ));
            }
        }
        self.model_current = true;
        self.init_failed = false;
        Ok(())
    }

    /// The data column values of a configuration with formula or custom effects (None
    /// without them): each column it reads, from its auxiliary input or constant.
    fn extras(&self, cfg: &Config) -> Result<Option<Vec<(String, f64)>>, String> {
        extras_for(cfg, &self.settings.columns, &self.inputs)
    }

    /// The value of a parameter: as set, or from the resolved configuration.
    fn parameter(&mut self, func: &str, v: &Var) -> Result<Value, Status> {
        if v.slot == Slot::Scheme {
            if let Some(s) = self.tol_scheme {
                // the scheme rel_tol chose, as the parameter's code
                return Ok(Value::Integer(i32::from(s == Scheme::Continuous)));
            }
        }
        let speed = self.speed();
        let Instance {
            settings,
            cfg,
            resources,
            ..
        } = self;
        match settings.get(v, || {
            cached_config(cfg, settings, resources.as_deref(), speed)
        }) {
            Some(Ok(x)) => Ok(x),
            Some(Err(e)) => {
                Err(self.error(format!("{func}: {}: configuration error: {e}", v.name)))
            }
            None => Err(self.error(format!("{func}: {} is not a parameter", v.name))),
        }
    }

    /// fmi2GetReal of one variable.
    pub fn get_real(&mut self, vr: u32) -> Result<f64, Status> {
        const F: &str = "fmi2GetReal";
        self.check_gettable(F)?;
        let v = self.var(F, vr, Kind::Real)?;
        match v.slot {
            Slot::Input(i) => Ok(self.inputs[i.index()]),
            Slot::Output(o) => match self.current_outputs() {
                Ok(out) => Ok(o.of(&out)),
                Err(e) => Err(self.error(format!("{F}: {} cannot be computed: {e}", v.name))),
            },
            _ => match self.parameter(F, &v)? {
                Value::Real(x) => Ok(x),
                _ => Err(self.error(format!("{F}: {} is not a Real", v.name))),
            },
        }
    }

    /// fmi2GetInteger of one variable.
    pub fn get_integer(&mut self, vr: u32) -> Result<i32, Status> {
        const F: &str = "fmi2GetInteger";
        self.check_gettable(F)?;
        let v = self.var(F, vr, Kind::Integer)?;
        match self.parameter(F, &v)? {
            Value::Integer(x) => Ok(x),
            _ => Err(self.error(format!("{F}: {} is not an Integer", v.name))),
        }
    }

    /// fmi2GetBoolean of one variable.
    pub fn get_boolean(&mut self, vr: u32) -> Result<bool, Status> {
        const F: &str = "fmi2GetBoolean";
        self.check_gettable(F)?;
        let v = self.var(F, vr, Kind::Boolean)?;
        match self.parameter(F, &v)? {
            Value::Boolean(x) => Ok(x),
            _ => Err(self.error(format!("{F}: {} is not a Boolean", v.name))),
        }
    }

    /// fmi2GetString of one variable.
    pub fn get_string(&mut self, vr: u32) -> Result<String, Status> {
        const F: &str = "fmi2GetString";
        self.check_gettable(F)?;
        let v = self.var(F, vr, Kind::String)?;
        match self.parameter(F, &v)? {
            Value::String(x) => Ok(x),
            _ => Err(self.error(format!("{F}: {} is not a String", v.name))),
        }
    }

    /// fmi2SetReal of one variable.
    pub fn set_real(&mut self, vr: u32, x: f64) -> Status {
        self.set_values("fmi2SetReal", &[(vr, Value::Real(x))])
    }

    /// fmi2SetInteger of one variable.
    pub fn set_integer(&mut self, vr: u32, x: i32) -> Status {
        self.set_values("fmi2SetInteger", &[(vr, Value::Integer(x))])
    }

    /// fmi2SetBoolean of one variable.
    pub fn set_boolean(&mut self, vr: u32, x: bool) -> Status {
        self.set_values("fmi2SetBoolean", &[(vr, Value::Boolean(x))])
    }

    /// fmi2SetString of one variable.
    pub fn set_string(&mut self, vr: u32, x: &str) -> Status {
        self.set_values("fmi2SetString", &[(vr, Value::String(x.to_string()))])
    }

    /// One fmi2Set* call: every value is checked first; if any is refused, none is applied
    /// (each refusal is logged) and the instance is unchanged.
    pub fn set_values(&mut self, func: &str, items: &[(u32, Value)]) -> Status {
        let mut vars = Vec::with_capacity(items.len());
        let mut refused = 0;
        for (vr, x) in items {
            match self.check_value(func, *vr, x) {
                Ok(v) => vars.push(v),
                Err(_) => refused += 1,
            }
        }
        if refused > 0 {
            if items.len() > 1 {
                self.error(format!(
                    "{func}: {refused} of {} values refused; none of the {} values of this call was applied",
                    items.len(),
                    items.len()
                ));
            }
            return Status::Error;
        }
        let mut st = Status::Ok;
        for (v, (_, x)) in vars.iter().zip(items) {
            st = st.max(self.apply_value(func, v, x));
        }
        st
    }

    /// Checks one value of a set call without changing anything; logs the reason of a refusal.
    fn check_value(&mut self, func: &str, vr: u32, x: &Value) -> Result<Var, Status> {
        let v = self.var(func, vr, x.kind())?;
        self.check_settable(func, &v)?;
        let refuse = |inst: &mut Self, why: String| -> Result<Var, Status> {
            Err(inst.error(format!(
                "{func}: {} = {} rejected (value unchanged): {why}",
                v.name,
                x.show()
            )))
        };
        match (v.slot, x) {
            (Slot::Input(i), Value::Real(x)) => {
                if !x.is_finite() {
                    return refuse(self, "inputs must be finite".into());
                }
                let mut cand = self.inputs;
                cand[i.index()] = *x;
                if let Err(e) = core_inputs(&cand).validate() {
                    // the FMU takes FN <= 0 as lift-off: say so beside the core's range
                    let why = match i {
                        In::Core(InputId::Fn) => format!(
                            "FN = {x} N is above the largest accepted normal force, 1e8 N (FN <= 0 is accepted: lift-off, all forces 0)"
                        ),
                        _ => e.to_string(),
                    };
                    return refuse(self, why);
                }
            }
            _ => match Settings::check(&v, x, self.resources.as_deref()) {
                Some(Ok(())) => {}
                Some(Err(why)) => return refuse(self, why),
                None => {
                    return Err(self.error(format!(
                        "{func}: {} is not settable as {}",
                        v.name,
                        x.kind().name()
                    )))
                }
            },
        }
        Ok(v)
    }

    /// Applies one value that [`Self::check_value`] accepted; returns warnings.
    fn apply_value(&mut self, func: &str, v: &Var, x: &Value) -> Status {
        match (v.slot, x) {
            (Slot::Input(i), Value::Real(x)) => {
                let x = *x;
                self.inputs[i.index()] = x;
                self.model_current = false;
                if i == In::Core(InputId::V)
                    && self.settings.rel_tol > 0.0
                    && matches!(self.phase, Phase::Instantiated | Phase::Initialization)
                {
                    // rel_tol chooses the grid at the speed the initialization ends with
                    self.cfg = None;
                }
                return match i {
                    In::Core(InputId::Cx | InputId::Cy) if x.abs() > 1.0 => self.warn(format!(
                        "{func}: {} = {x} ({:.0} %): |{}| > 1 is beyond the range of rolling contact (the wheel slips more than it rolls); computed anyway",
                        v.name,
                        100.0 * x,
                        v.name
                    )),
                    In::Core(InputId::Fn) if x < 0.0 => self.warn(format!(
                        "{func}: FN = {x} N < 0: the wheel has lifted off; treated as FN = 0 (all forces zero)"
                    )),
                    _ => Status::Ok,
                };
            }
            _ => {
                if !self.settings.apply(v, x) {
                    return self.error(format!("{func}: {} cannot be set", v.name));
                }
            }
        }
        self.settings_changed();
        Status::Ok
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
        }
    }

    /// Gives the model the importer's `threads` and `scheme` (settings of the instance, not
    /// of a state: they say how to compute, not what).
    fn apply_how_to_compute(&mut self) -> Result<(), String> {
        let (n, scheme) = (self.settings.threads.max(1), self.scheme());
        match self.model.as_mut() {
            Some(m) => {
                m.set_scheme(scheme);
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
        // the importer's threads, scheme and rel_tol stay (a serialized state does not carry
        // them), and so does the scheme rel_tol chose
        let (threads, scheme, rel_tol) = (
            self.settings.threads,
            self.settings.scheme,
            self.settings.rel_tol,
        );
        // a state taken before initialization completed holds at most a provisional model (the
        // steady state of the inputs it had then): it is rebuilt from the restored inputs at
        // fmi2ExitInitializationMode, as in the instance that took it
        let live = matches!(s.phase, Phase::StepComplete | Phase::Terminated);
        let mut model = if live { s.model.clone() } else { None };
        if let Some(m) = model.as_mut() {
            m.set_scheme(self.scheme());
            if let Err(e) = m.set_threads(threads.max(1)) {
                return self.error(format!("{F}: {e}; the instance is unchanged"));
            }
        }
        self.settings = s.settings.clone();
        self.settings.threads = threads;
        self.settings.scheme = scheme;
        self.settings.rel_tol = rel_tol;
        self.inputs = s.inputs;
        self.time = s.time;
        self.cfg = s.cfg.clone();
        self.model = model;
        self.model_current = self.model.is_some();
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

/// The configuration resolved from `settings`, computed once into `cache`.
fn cached_config<'a>(
    cache: &'a mut Option<Config>,
    settings: &Settings,
    resources: Option<&Path>,
    v: f64,
) -> Result<&'a Config, String> {
    if cache.is_none() {
        *cache = Some(settings.resolve(resources, v)?);
    }
    cache.as_ref().ok_or_else(|| "no configuration".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use creep_core::effects::Effect;
    use creep_core::params::P;
    use creep_core::Geometry;

    fn vr(name: &str) -> u32 {
        vars::table()
            .iter()
            .find(|v| v.name == name)
            .map(|v| v.vr)
            .expect(name)
    }

    fn initialized() -> Instance {
        let mut i = Instance::new("t", None, false);
        assert_eq!(i.set_integer(vr("nx"), 10), Status::Ok);
        assert_eq!(i.set_integer(vr("ny"), 5), Status::Ok);
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.exit_initialization(), Status::Ok);
        i
    }

    #[test]
    fn threads_give_the_same_steps_and_survive_a_state_restore() {
        let run = |threads: i32| {
            let mut i = Instance::new("t", None, false);
            assert_eq!(i.set_integer(vr("nx"), 20), Status::Ok);
            assert_eq!(i.set_integer(vr("ny"), 9), Status::Ok);
            assert_eq!(i.set_integer(vr("threads"), threads), Status::Ok);
            assert_eq!(i.enter_initialization(), Status::Ok);
            assert_eq!(i.exit_initialization(), Status::Ok);
            assert_eq!(i.get_integer(vr("threads")), Ok(threads));
            let mut fx = Vec::new();
            let mut saved = None;
            for k in 0..20 {
                assert_eq!(i.set_real(vr("cx"), 0.002 + 0.01 * k as f64), Status::Ok);
                assert_eq!(i.do_step(k as f64 * 1e-4, 1e-4), Status::Ok);
                fx.push(i.get_real(vr("Fx")).expect("Fx"));
                if k == 10 {
                    saved = Some(i.get_state());
                }
            }
            assert_eq!(i.set_state(saved.as_ref().expect("state")), Status::Ok);
            assert_eq!(i.get_integer(vr("threads")), Ok(threads));
            assert_eq!(i.set_real(vr("cx"), 0.002 + 0.01 * 11.0), Status::Ok);
            assert_eq!(i.do_step(11e-4, 1e-4), Status::Ok);
            fx.push(i.get_real(vr("Fx")).expect("Fx"));
            fx
        };
        let one = run(1);
        assert_eq!(one[11], one[20], "a restored state repeats its step");
        assert_eq!(one, run(3));
        // the continuous scheme: close to the reference, not equal to it
        let mut i = Instance::new("t", None, false);
        for (n, x) in [("nx", 20), ("ny", 9), ("scheme", 1)] {
            assert_eq!(i.set_integer(vr(n), x), Status::Ok);
        }
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.exit_initialization(), Status::Ok);
        assert_eq!(i.get_integer(vr("scheme")), Ok(1));
        let mut cont = Vec::new();
        for k in 0..20 {
            assert_eq!(i.set_real(vr("cx"), 0.002 + 0.01 * k as f64), Status::Ok);
            assert_eq!(i.do_step(k as f64 * 1e-4, 1e-4), Status::Ok);
            cont.push(i.get_real(vr("Fx")).expect("Fx"));
        }
        assert_ne!(cont[..20], one[..20]);
        for (c, r) in cont.iter().zip(&one) {
            assert!((c - r).abs() <= 0.02 * r.abs(), "{c} vs {r}");
        }
        // out of range
        let mut i = Instance::new("t", None, false);
        assert_eq!(i.set_integer(vr("threads"), 0), Status::Error);
        assert_eq!(i.set_integer(vr("threads"), 65), Status::Error);
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.get_integer(vr("threads")), Ok(1));
    }

    #[test]
    fn uri_paths() {
        assert_eq!(
            uri_to_path("file:///tmp/a%20b/res/"),
            Some(PathBuf::from("/tmp/a b/res/"))
        );
        assert_eq!(uri_to_path("file:/tmp/x"), Some(PathBuf::from("/tmp/x")));
        assert_eq!(
            uri_to_path("file://localhost/tmp/x"),
            Some(PathBuf::from("/tmp/x"))
        );
        assert_eq!(uri_to_path("http://x/y"), None);
        assert_eq!(uri_to_path("file:///tmp/%zz"), None);
    }

    #[test]
    fn windows_file_uris_become_drive_and_unc_paths() {
        let w = |u| uri_to_path_for(u, true);
        assert_eq!(
            w("file:///C:/Users/a%20b/res/").as_deref(),
            Some("C:/Users/a b/res/")
        );
        assert_eq!(
            w("file:/D:/fmu/resources").as_deref(),
            Some("D:/fmu/resources")
        );
        assert_eq!(w("file://localhost/C:/x").as_deref(), Some("C:/x"));
        assert_eq!(
            w("file://server/share/res").as_deref(),
            Some("//server/share/res")
        );
        assert_eq!(w("file:///tmp/x").as_deref(), Some("/tmp/x"));
        assert_eq!(w("file://C:/x/res").as_deref(), Some("C:/x/res"));
        assert_eq!(w("file:///C|/x").as_deref(), Some("C:/x"));
        assert_eq!(w("file://D|/x").as_deref(), Some("D:/x"));
        // elsewhere a drive-letter-like segment is an ordinary folder and a host is not local
        let l = |u| uri_to_path_for(u, false);
        assert_eq!(l("file:///C:/x").as_deref(), Some("/C:/x"));
        assert_eq!(l("file://server/share/res"), None);
    }

    #[test]
    fn wrong_state_and_unknown_reference_are_errors_with_messages() {
        let mut i = Instance::new("t", None, false);
        assert_eq!(i.do_step(0.0, 1e-3), Status::Error);
        assert_eq!(i.set_real(9999, 1.0), Status::Error);
        let logs = i.take_logs();
        assert!(
            logs[0].text.contains("fmi2DoStep") && logs[0].text.contains("Instantiated"),
            "{logs:?}"
        );
        assert!(logs[1].text.contains("9999"), "{logs:?}");
        let mut i = initialized();
        assert_eq!(i.set_real(vr("mu"), 0.3), Status::Error);
        let logs = i.take_logs();
        assert!(
            logs[0].text.contains("mu") && logs[0].text.contains("fixed parameter"),
            "{logs:?}"
        );
    }

    #[test]
    fn nan_input_is_rejected_and_value_kept() {
        let mut i = initialized();
        assert_eq!(i.set_real(vr("cx"), 0.01), Status::Ok);
        assert_eq!(i.set_real(vr("cx"), f64::NAN), Status::Error);
        assert_eq!(i.get_real(vr("cx")), Ok(0.01));
        let logs = i.take_logs();
        assert!(
            logs[0].text.contains("cx") && logs[0].text.contains("finite"),
            "{logs:?}"
        );
        assert_eq!(i.set_real(vr("FN"), -1.0), Status::Warning);
        assert_eq!(i.do_step(0.0, 1e-4), Status::Ok);
        assert_eq!(i.get_real(vr("Fx")), Ok(0.0));
    }

    #[test]
    fn preset_and_model_conflict_is_reported_at_initialization() {
        let mut i = Instance::new("t", None, false);
        assert_eq!(i.set_string(vr("model"), "fastsim"), Status::Ok);
        assert_eq!(i.set_string(vr("preset"), "dry"), Status::Ok);
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.exit_initialization(), Status::Error);
        let logs = i.take_logs();
        assert!(
            logs[0].text.contains("fastsim") && logs[0].text.contains("dry"),
            "{logs:?}"
        );
        // still in initialization mode (a corrected parameter and another exit may follow),
        // but no FMU state is handed out until an exit succeeds or fmi2Reset
        assert_eq!(i.phase(), Phase::Initialization);
        assert!(i.try_get_state().is_err());
        assert_eq!(i.reset(), Status::Ok);
        assert!(i.try_get_state().is_ok());
    }

    #[test]
    fn parameters_read_back_from_the_preset_unless_set() {
        let mut i = Instance::new("t", None, false);
        assert_eq!(i.set_string(vr("preset"), "dry"), Status::Ok);
        assert_eq!(i.enter_initialization(), Status::Ok);
        let dry = Config::preset("dry").unwrap();
        assert_eq!(i.get_real(vr("tau_c1_0_GPa")), Ok(dry.params.get(P::Tc10)));
        assert_eq!(i.set_real(vr("tau_c1_0_GPa"), 0.4), Status::Ok);
        assert_eq!(i.get_real(vr("tau_c1_0_GPa")), Ok(0.4));
        assert_eq!(i.set_boolean(vr("effect_transient"), false), Status::Ok);
        assert_eq!(i.exit_initialization(), Status::Ok);
        let c = i.model().unwrap().config();
        assert_eq!(c.params.get(P::Tc10), 0.4);
        assert!(!c.effects.has(Effect::Transient));
        assert_eq!(c.params.get(P::Tc20), dry.params.get(P::Tc20));
    }

    #[test]
    fn curvature_geometry_gives_hertz_semi_axes() {
        let mut i = Instance::new("t", None, false);
        assert_eq!(i.set_integer(vr("geometry"), 2), Status::Ok);
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.exit_initialization(), Status::Ok);
        let a = i.get_real(vr("a")).unwrap();
        let b = i.get_real(vr("b")).unwrap();
        let expect = creep_core::engine::patch_for(i.model().unwrap().config(), 110e3).unwrap();
        assert!(matches!(
            i.model().unwrap().config().geometry,
            Geometry::Curvatures { .. }
        ));
        assert_eq!((a, b), (expect.a, expect.b));
        assert!(
            a > 1e-3 && a < 2e-2 && b > 1e-3 && b < 2e-2,
            "a = {a}, b = {b}"
        );
    }

    /// An instance with rel_tol, the speed v and the integer settings given, initialized;
    /// returns it with its exit_initialization status and logs.
    fn with_tol(rel_tol: f64, v: f64, ints: &[(&str, i32)]) -> (Instance, Status, Vec<LogMsg>) {
        let mut i = Instance::new("t", None, true);
        assert_eq!(i.set_real(vr("rel_tol"), rel_tol), Status::Ok);
        assert_eq!(i.set_real(vr("v"), v), Status::Ok);
        for (n, x) in ints {
            assert_eq!(i.set_integer(vr(n), *x), Status::Ok);
        }
        assert_eq!(i.enter_initialization(), Status::Ok);
        let st = i.exit_initialization();
        let logs = i.take_logs();
        (i, st, logs)
    }

    #[test]
    fn rel_tol_runs_on_the_grid_and_scheme_the_table_gives_and_logs_them() {
        use creep_core::tolerance::{self, Filter};
        for (tol, v) in [(0.05, 5.0), (0.02, 30.0), (0.01, 5.0)] {
            let c = tolerance::choose(tol, v, None, Filter::default()).expect("choice");
            assert!(c.met, "{tol} at {v}: the test wants a met tolerance");
            let (mut i, st, logs) = with_tol(tol, v, &[]);
            assert_eq!(st, Status::Ok, "{logs:?}");
            assert_eq!(i.get_integer(vr("nx")), Ok(c.nx as i32));
            assert_eq!(i.get_integer(vr("ny")), Ok(c.ny as i32));
            let code = i32::from(c.scheme == Scheme::Continuous);
            assert_eq!(i.get_integer(vr("scheme")), Ok(code));
            assert_eq!(i.get_real(vr("rel_tol")), Ok(tol));
            let m = i.model().expect("model");
            assert_eq!(m.config().grid.nx, c.nx);
            let grid = format!("grid {}x{}", c.nx, c.ny);
            assert!(
                logs.iter().any(|l| l.category == "logEvents"
                    && l.text.contains(&grid)
                    && l.text.contains(&format!("{:.2} %", c.fx_err_pct))),
                "{logs:?}"
            );
            // the chosen scheme is the one that steps: the same Fx as the explicit settings
            let mut j = Instance::new("t", None, false);
            assert_eq!(j.set_real(vr("v"), v), Status::Ok);
            for (n, x) in [("nx", c.nx as i32), ("ny", c.ny as i32), ("scheme", code)] {
                assert_eq!(j.set_integer(vr(n), x), Status::Ok);
            }
            assert_eq!(j.enter_initialization(), Status::Ok);
            assert_eq!(j.exit_initialization(), Status::Ok);
            for inst in [&mut i, &mut j] {
                assert_eq!(inst.set_real(vr("cx"), 0.05), Status::Ok);
                assert_eq!(inst.do_step(0.0, 2.5e-4), Status::Ok);
            }
            assert_eq!(i.get_real(vr("Fx")), j.get_real(vr("Fx")));
        }
    }

    #[test]
    fn rel_tol_off_and_explicit_settings_keep_the_grid() {
        let preset = default_grid();
        // off: the preset's grid
        let (mut i, st, _) = with_tol(0.0, 5.0, &[]);
        assert_eq!(st, Status::Ok);
        assert_eq!(i.get_integer(vr("nx")), Ok(preset.0));
        assert_eq!(i.get_integer(vr("scheme")), Ok(0));
        // explicit nx, ny override a loose tolerance that would choose another grid
        let loose = creep_core::tolerance::choose(0.5, 5.0, None, Default::default()).expect("c");
        assert_ne!((loose.nx, loose.ny), (80, 21));
        let (mut i, st, logs) = with_tol(0.5, 5.0, &[("nx", 80), ("ny", 21)]);
        assert_eq!(st, Status::Ok, "{logs:?}");
        assert_eq!(i.get_integer(vr("nx")), Ok(80));
        assert_eq!(i.get_integer(vr("ny")), Ok(21));
        // an explicit grid the table does not have: used, with a warning
        let (mut i, st, logs) = with_tol(0.01, 5.0, &[("nx", 30), ("ny", 7)]);
        assert_eq!(st, Status::Warning, "{logs:?}");
        assert_eq!(i.get_integer(vr("nx")), Ok(30));
        assert!(logs.iter().any(|l| l.text.contains("nx = 30")), "{logs:?}");
    }

    fn default_grid() -> (i32, i32) {
        let g = vars::default_config().grid;
        (g.nx as i32, g.ny as i32)
    }

    #[test]
    fn a_rel_tol_no_grid_meets_warns_with_the_error_reached() {
        let (mut i, st, logs) = with_tol(1e-5, 20.0, &[]);
        assert_eq!(st, Status::Warning, "{logs:?}");
        let c = creep_core::tolerance::choose(1e-5, 20.0, None, Default::default()).expect("c");
        assert_eq!(i.get_integer(vr("nx")), Ok(c.nx as i32));
        assert!(
            logs.iter()
                .any(|l| l.category == "logStatusWarning" && l.text.contains("NOT met")),
            "{logs:?}"
        );
    }

    #[test]
    fn rel_tol_follows_v_set_during_initialization_not_after() {
        use creep_core::tolerance::choose;
        let (at5, at30) = (
            choose(0.02, 5.0, None, Default::default()).expect("c"),
            choose(0.02, 30.0, None, Default::default()).expect("c"),
        );
        assert_ne!(
            (at5.nx, at5.ny),
            (at30.nx, at30.ny),
            "the test needs two grids"
        );
        let mut i = Instance::new("t", None, false);
        assert_eq!(i.set_real(vr("rel_tol"), 0.02), Status::Ok);
        assert_eq!(i.set_real(vr("v"), 5.0), Status::Ok);
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.get_integer(vr("nx")), Ok(at5.nx as i32));
        assert_eq!(i.set_real(vr("v"), 30.0), Status::Ok);
        assert_eq!(i.exit_initialization(), Status::Ok);
        assert_eq!(i.get_integer(vr("nx")), Ok(at30.nx as i32));
        assert_eq!(i.set_real(vr("v"), 5.0), Status::Ok);
        assert_eq!(i.do_step(0.0, 1e-3), Status::Ok);
        assert_eq!(i.get_integer(vr("nx")), Ok(at30.nx as i32));
    }

    #[test]
    fn bad_rel_tol_is_refused_with_a_message_and_the_value_kept() {
        for bad in [-0.01, f64::NAN, f64::INFINITY, 1.5] {
            let mut i = Instance::new("t", None, false);
            assert_eq!(i.set_real(vr("rel_tol"), bad), Status::Error, "{bad}");
            let logs = i.take_logs();
            assert!(
                logs.iter().any(|l| l.text.contains("rel_tol")),
                "{bad}: {logs:?}"
            );
            assert_eq!(i.enter_initialization(), Status::Ok);
            assert_eq!(i.get_real(vr("rel_tol")), Ok(0.0));
        }
        // fastsim: ignored with a warning
        let mut i = Instance::new("t", None, true);
        assert_eq!(i.set_real(vr("rel_tol"), 0.01), Status::Ok);
        assert_eq!(i.set_string(vr("preset"), "fastsim"), Status::Ok);
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.exit_initialization(), Status::Warning);
        assert!(i.take_logs().iter().any(|l| l.text.contains("ECF model")));
    }
}
