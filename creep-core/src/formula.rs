//! User-written effects without compiling: a formula that scales a material function (tau_c1, tau_c2, L_e, L_p or mu) by an expression.
//!
//! Configuration entry:
//! `{"name": N, "target": "tau_c1"|"tau_c2"|"L_e"|"L_p"|"mu", "factor": "EXPRESSION",
//!   "params": {"k": {"value": v, "min": lo, "max": hi}}}`.
//! The expression may use numbers, `+ - * / ^`, parentheses, the functions `exp ln sqrt abs
//! tanh min max`, the formula's own parameters, the bristle's local state `p_GPa` (normal
//! pressure), `T_C` (temperature), `u_mm` (|u|), `slip_mps` (rigid slip speed), the operating
//! point `v_mps`, `fn_kN`, `cx`, `cy`, `spin_per_m`, and any extra column of the measurement
//! file by its name. The factor multiplies the target wherever the engine evaluates it.

use crate::error::{CreepError, Result};

/// Material function a formula scales.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// First critical shear stress.
    TauC1,
    /// Second critical shear stress.
    TauC2,
    /// Inverted elastic stiffness of the layer.
    Le,
    /// Plasticity factor.
    Lp,
    /// Coulomb friction coefficient.
    Mu,
}

impl Target {
    /// Parses a target name.
    pub fn parse(s: &str) -> Result<Self> {
        Ok(match s {
            "tau_c1" => Target::TauC1,
            "tau_c2" => Target::TauC2,
            "L_e" => Target::Le,
            "L_p" => Target::Lp,
            "mu" => Target::Mu,
            _ => {
                return Err(CreepError::Unknown {
                    kind: "formula target".into(),
                    name: s.into(),
                    accepted: "tau_c1, tau_c2, L_e, L_p, mu".into(),
                })
            }
        })
    }
    /// Name of the target.
    pub fn name(&self) -> &'static str {
        match self {
            Target::TauC1 => "tau_c1",
            Target::TauC2 => "tau_c2",
            Target::Le => "L_e",
            Target::Lp => "L_p",
            Target::Mu => "mu",
        }
    }
}

/// Local-state variables (indices 0..4 of the evaluation slice).
pub const LOCAL: [&str; 4] = ["p_GPa", "T_C", "u_mm", "slip_mps"];
/// Operating-point variables (indices 4..9).
pub const OPERATING: [&str; 5] = ["v_mps", "fn_kN", "cx", "cy", "spin_per_m"];

#[derive(Clone, Debug, PartialEq)]
enum Node {
    Num(f64),
    Var(usize),
    Param(usize),
    Neg(Box<Node>),
    Bin(char, Box<Node>, Box<Node>),
    Call(String, Vec<Node>),
}

/// One parameter of a formula effect (configuration: `"params": {NAME: {"value": v, "min": lo,
/// "max": hi}}`). Its unit is whatever the expression gives it; fits treat it as "-".
#[derive(Clone, Debug, PartialEq)]
pub struct FormulaParam {
    /// Name, as the factor expression refers to it.
    pub name: String,
    /// Current value; finite and within [`min`, `max`] (checked by [`FormulaEffect::new`]).
    ///
    /// [`min`]: FormulaParam::min
    /// [`max`]: FormulaParam::max
    pub value: f64,
    /// Lower bound of `value`, kept by fits (`f64::MIN` if the configuration gives none).
    pub min: f64,
    /// Upper bound of `value`, kept by fits (`f64::MAX` if the configuration gives none).
    pub max: f64,
}

/// A compiled formula effect.
#[derive(Clone, Debug, PartialEq)]
pub struct FormulaEffect {
    /// Name.
    pub name: String,
    /// Scaled material function.
    pub target: Target,
    /// Source text of the factor.
    pub source: String,
    /// Parameters, in the order the configuration lists them.
    pub params: Vec<FormulaParam>,
    /// Extra (data) columns the expression uses, in variable order after the fixed ones.
    pub columns: Vec<String>,
    expr: Node,
    /// True if the expression uses local bristle state.
    pub local: bool,
}

struct Parser<'a> {
    s: &'a [u8],
    i: usize,
    params: &'a [FormulaParam],
    columns: Vec<String>,
    local: bool,
}

impl Parser<'_> {
    fn ws(&mut self) {
        while self.i < self.s.len() && (self.s[self.i] as char).is_whitespace() {
            self.i += 1;
        }
    }
    fn err(&self, m: &str) -> CreepError {
        CreepError::Config {
            source_name: "formula".into(),
            message: format!("at character {}: {m}", self.i + 1),
        }
    }
    fn peek(&mut self) -> Option<char> {
        self.ws();
        self.s.get(self.i).map(|c| *c as char)
    }
    fn expr(&mut self) -> Result<Node> {
        let mut a = self.term()?;
        while let Some(c) = self.peek() {
            if c == '+' || c == '-' {
                self.i += 1;
                let b = self.term()?;
                a = Node::Bin(c, Box::new(a), Box::new(b));
            } else {
                break;
            }
        }
        Ok(a)
    }
    fn term(&mut self) -> Result<Node> {
        let mut a = self.power()?;
        while let Some(c) = self.peek() {
            if c == '*' || c == '/' {
                self.i += 1;
                let b = self.power()?;
                a = Node::Bin(c, Box::new(a), Box::new(b));
            } else {
                break;
            }
        }
        Ok(a)
    }
    fn power(&mut self) -> Result<Node> {
        let a = self.unary()?;
        if self.peek() == Some('^') {
            self.i += 1;
            let b = self.power()?;
            return Ok(Node::Bin('^', Box::new(a), Box::new(b)));
        }
        Ok(a)
    }
    fn unary(&mut self) -> Result<Node> {
        if self.peek() == Some('-') {
            self.i += 1;
            return Ok(Node::Neg(Box::new(self.unary()?)));
        }
        if self.peek() == Some('+') {
            self.i += 1;
        }
        self.primary()
    }
    fn primary(&mut self) -> Result<Node> {
        match self.peek() {
            Some('(') => {
                self.i += 1;
                let e = self.expr()?;
                if self.peek() != Some(')') {
                    return Err(self.err("expected ')'"));
                }
                self.i += 1;
                Ok(e)
            }
            Some(c) if c.is_ascii_digit() || c == '.' => {
                let st = self.i;
                while self.i < self.s.len()
                    && ((self.s[self.i] as char).is_ascii_digit()
                        || self.s[self.i] == b'.'
                        || self.s[self.i] == b'e'
                        || self.s[self.i] == b'E'
                        || ((self.s[self.i] == b'-' || self.s[self.i] == b'+')
                            && self.i > st
                            && (self.s[self.i - 1] == b'e' || self.s[self.i - 1] == b'E')))
                {
                    self.i += 1;
                }
                let t = std::str::from_utf8(&self.s[st..self.i]).unwrap_or("");
                t.parse::<f64>()
                    .map(Node::Num)
                    .map_err(|_| self.err(&format!("bad number '{t}'")))
            }
            Some(c) if c.is_ascii_alphabetic() || c == '_' => {
                let st = self.i;
                while self.i < self.s.len()
                    && ((self.s[self.i] as char).is_ascii_alphanumeric() || self.s[self.i] == b'_')
                {
                    self.i += 1;
                }
                let name = std::str::from_utf8(&self.s[st..self.i])
                    .unwrap_or("")
                    .to_string();
                if self.peek() == Some('(') {
                    self.i += 1;
                    let mut args = vec![self.expr()?];
                    while self.peek() == Some(',') {
                        self.i += 1;
                        args.push(self.expr()?);
                    }
                    if self.peek() != Some(')') {
                        return Err(self.err("expected ')' after arguments"));
                    }
                    self.i += 1;
                    let n = match name.as_str() {
                        "exp" | "ln" | "sqrt" | "abs" | "tanh" => 1,
                        "min" | "max" => 2,
                        _ => {
                            return Err(self.err(&format!(
                                "unknown function '{name}' (exp, ln, sqrt, abs, tanh, min, max)"
                            )))
                        }
                    };
                    if args.len() != n {
                        return Err(self.err(&format!("{name} takes {n} argument(s)")));
                    }
                    return Ok(Node::Call(name, args));
                }
                if let Some(k) = self.params.iter().position(|p| p.name == name) {
                    return Ok(Node::Param(k));
                }
                if let Some(k) = LOCAL.iter().position(|v| *v == name) {
                    self.local = true;
                    return Ok(Node::Var(k));
                }
                if let Some(k) = OPERATING.iter().position(|v| *v == name) {
                    return Ok(Node::Var(LOCAL.len() + k));
                }
                let k = match self.columns.iter().position(|c| *c == name) {
                    Some(k) => k,
                    None => {
                        self.columns.push(name);
                        self.columns.len() - 1
                    }
                };
                Ok(Node::Var(LOCAL.len() + OPERATING.len() + k))
            }
            Some(c) => Err(self.err(&format!("unexpected '{c}'"))),
            None => Err(self.err("unexpected end of formula")),
        }
    }
}

fn uses_vars(n: &Node) -> bool {
    match n {
        Node::Num(_) | Node::Param(_) => false,
        Node::Var(_) => true,
        Node::Neg(a) => uses_vars(a),
        Node::Bin(_, a, b) => uses_vars(a) || uses_vars(b),
        Node::Call(_, args) => args.iter().any(uses_vars),
    }
}

fn eval(n: &Node, vars: &[f64], params: &[FormulaParam]) -> f64 {
    match n {
        Node::Num(x) => *x,
        Node::Var(i) => vars.get(*i).copied().unwrap_or(f64::NAN),
        Node::Param(i) => params[*i].value,
        Node::Neg(a) => -eval(a, vars, params),
        Node::Bin(op, a, b) => {
            let (x, y) = (eval(a, vars, params), eval(b, vars, params));
            match op {
                '+' => x + y,
                '-' => x - y,
                '*' => x * y,
                '/' => x / y,
                _ => x.powf(y),
            }
        }
        Node::Call(f, args) => {
            let x = eval(&args[0], vars, params);
            match f.as_str() {
                "exp" => x.exp(),
                "ln" => x.ln(),
                "sqrt" => x.sqrt(),
                "abs" => x.abs(),
                "tanh" => x.tanh(),
                "min" => x.min(eval(&args[1], vars, params)),
                _ => x.max(eval(&args[1], vars, params)),
            }
        }
    }
}

impl FormulaEffect {
    /// Compiles a formula effect.
    pub fn new(
        name: &str,
        target: Target,
        factor: &str,
        params: Vec<FormulaParam>,
    ) -> Result<Self> {
        for FormulaParam {
            name: n,
            value: v,
            min: lo,
            max: hi,
        } in &params
        {
            if !(v.is_finite() && lo <= v && v <= hi) {
                return Err(CreepError::OutOfRange {
                    field: format!("formula_effects.{name}.params.{n}"),
                    value: *v,
                    expected: format!("must be finite and within [{lo}, {hi}]"),
                });
            }
        }
        let mut p = Parser {
            s: factor.as_bytes(),
            i: 0,
            params: &params,
            columns: Vec::new(),
            local: false,
        };
        let expr = p.expr().map_err(|e| CreepError::Config {
            source_name: format!("formula_effects.{name}.factor"),
            message: format!("'{factor}' {e}"),
        })?;
        if p.peek().is_some() {
            return Err(CreepError::Config {
                source_name: format!("formula_effects.{name}.factor"),
                message: format!("'{factor}': unexpected text at character {}", p.i + 1),
            });
        }
        let (columns, local) = (p.columns, p.local);
        // a factor that depends on no variable is known now: finite and >= 0
        if !uses_vars(&expr) {
            let x = eval(&expr, &[], &params);
            if !(x.is_finite() && x >= 0.0) {
                return Err(CreepError::OutOfRange {
                    field: format!("formula_effects.{name}.factor '{factor}'"),
                    value: x,
                    expected: format!("a factor scaling {} must be finite and >= 0", target.name()),
                });
            }
        }
        Ok(FormulaEffect {
            name: name.into(),
            target,
            source: factor.into(),
            params,
            columns,
            expr,
            local,
        })
    }

    /// Evaluates the factor; `vars` = LOCAL values, OPERATING values, then the columns.
    pub fn eval(&self, vars: &[f64]) -> f64 {
        eval(&self.expr, vars, &self.params)
    }

    /// Sets a parameter value (for fitting).
    pub fn set_param(&mut self, k: usize, v: f64) {
        self.params[k].value = v;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_evaluates_with_precedence() {
        let f = FormulaEffect::new(
            "h",
            Target::TauC2,
            "1 - k*(humidity - 50)/50 + 2^3^0 - -1",
            vec![FormulaParam {
                name: "k".into(),
                value: 0.3,
                min: 0.0,
                max: 1.0,
            }],
        )
        .unwrap();
        assert_eq!(f.columns, vec!["humidity"]);
        assert!(!f.local);
        let mut vars = vec![0.0; LOCAL.len() + OPERATING.len()];
        vars.push(100.0);
        assert!((f.eval(&vars) - (1.0 - 0.3 + 2.0 + 1.0)).abs() < 1e-12);
        let g = FormulaEffect::new(
            "t",
            Target::TauC1,
            "exp(-max(T_C - 20, 0) * c)",
            vec![FormulaParam {
                name: "c".into(),
                value: 0.01,
                min: 0.0,
                max: 1.0,
            }],
        )
        .unwrap();
        assert!(g.local);
    }

    #[test]
    fn errors_point_at_the_problem() {
        for (src, needle) in [
            ("1 +", "end"),
            ("foo(1)", "unknown function"),
            ("(1", "')'"),
            ("1 2", "unexpected"),
            ("min(1)", "2 argument"),
        ] {
            let e = FormulaEffect::new("x", Target::Mu, src, vec![])
                .unwrap_err()
                .to_string();
            assert!(e.contains(needle), "{src}: {e}");
        }
        let k = FormulaParam {
            name: "k".into(),
            value: 5.0,
            min: 0.0,
            max: 1.0,
        };
        assert!(FormulaEffect::new("x", Target::Mu, "k", vec![k]).is_err());
    }
}
