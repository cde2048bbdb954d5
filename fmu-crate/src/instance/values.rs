//! Getting and setting variables by value reference: the lookup, the phase and causality checks, parameters as set or resolved, outputs of the last step or of the steady state in initialization mode.

use super::*;
use creep_core::FieldPoint;

impl Instance {
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
        self.file_grid = None;
        self.model_current = false;
        if self.phase != Phase::StepComplete {
            self.model = None;
        }
    }

    fn config(&mut self) -> Result<&Config, String> {
        let v = self.inputs[In::Core(InputId::V).index()];
        cached_config(
            &mut self.cfg,
            &mut self.file_grid,
            &self.settings,
            self.resources.as_deref(),
            v,
        )
    }

    /// Whether the configuration file gives a `grid`: as the configuration's resolution
    /// read it, else (not resolved since the settings changed, e.g. after a state was
    /// restored) from a read of the file here.
    pub(super) fn file_grid(&mut self) -> bool {
        match self.file_grid {
            Some(g) => g,
            None => {
                let g = self.settings.file_names_grid(self.resources.as_deref());
                self.file_grid = Some(g);
                g
            }
        }
    }

    /// The tolerance in force ([`Settings::rel_tol`]).
    pub(super) fn rel_tol(&mut self) -> f64 {
        let g = self.file_grid();
        self.settings.rel_tol(g)
    }

    /// The speed input v, m/s (its current value; at initialization, its start value).
    pub(super) fn speed(&self) -> f64 {
        self.inputs[In::Core(InputId::V).index()]
    }

    /// The scheme the instance asks the model to run: the one rel_tol chose, else the
    /// parameter `scheme` if set; None: the configuration's.
    pub(super) fn scheme(&self) -> Option<Scheme> {
        self.tol_scheme.or(self.settings.scheme())
    }

    /// The outputs for the current inputs: after initialization those of the last step; in
    /// initialization mode, the steady state of the current inputs (the model is built).
    pub(super) fn current_outputs(&mut self) -> Result<Outputs, String> {
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
        let file_grid = self.file_grid();
        self.tol_scheme = match self
            .settings
            .tolerance_choice(&cfg, self.speed(), file_grid)
        {
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
    pub(super) fn extras(&self, cfg: &Config) -> Result<Option<Vec<(String, f64)>>, String> {
        extras_for(cfg, &self.settings.columns, &self.inputs)
    }

    /// The value of a parameter: as set, or from the resolved configuration.
    fn parameter(&mut self, func: &str, v: &Var) -> Result<Value, Status> {
        if v.slot == Slot::Scheme {
            if let Some(s) = self.tol_scheme {
                // the scheme rel_tol chose, as the parameter's code
                return Ok(Value::Integer(crate::settings::scheme_code(s)));
            }
        }
        let speed = self.speed();
        let Instance {
            settings,
            cfg,
            file_grid,
            resources,
            ..
        } = self;
        match settings.get(v, || {
            cached_config(cfg, file_grid, settings, resources.as_deref(), speed)
        }) {
            Some(Ok(x)) => Ok(x),
            Some(Err(e)) => {
                Err(self.error(format!("{func}: {}: configuration error: {e}", v.name)))
            }
            None => Err(self.error(format!("{func}: {} is not a parameter", v.name))),
        }
    }

    /// The field of the strip nearest y = 0 at its nodes (None for Polach, which has no
    /// bristle grid) and the semi-axis a, m, as the outputs are read: after initialization
    /// those of the last step, in initialization mode those of the steady state.
    pub fn field(&mut self, func: &str) -> Result<(Option<Vec<FieldPoint>>, f64), Status> {
        self.check_gettable(func)?;
        match self.current_outputs() {
            Ok(o) => Ok((self.model.as_ref().and_then(|m| m.field_y0()), o.a)),
            Err(e) => Err(self.error(format!("{func}: the fields cannot be computed: {e}"))),
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
                // (a configuration not resolved yet has nothing to forget: no file read then)
                if i == In::Core(InputId::V)
                    && self.cfg.is_some()
                    && matches!(self.phase, Phase::Instantiated | Phase::Initialization)
                    && self.rel_tol() > 0.0
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
}
