//! User-written effects without compiling: a formula that scales a material function (tau_c1, tau_c2, both strengths, L_e, L_p or mu) by an expression.
//!
//! Configuration entry:
//! `{"name": N, "target": "tau_c1"|"tau_c2"|"strengths"|"L_e"|"L_p"|"mu", "factor": "EXPRESSION",
//!   "params": {"k": {"value": v, "min": lo, "max": hi}}}`.
//! The expression may use numbers, `+ - * / ^`, parentheses, the functions `exp ln sqrt abs
//! tanh min max`, the formula's own parameters, the bristle's local state `p_GPa` (normal
//! pressure), `T_C` (temperature), `u_mm` (|u|), `slip_mps` (rigid slip speed), the operating
//! point `v_mps`, `fn_kN`, `cx`, `cy`, `spin_per_m`, and any extra column of the measurement
//! file by its name. The factor multiplies the target wherever the engine evaluates it.

use crate::error::{CreepError, Result};
use crate::modifier::{LocalState, Modifier, ModifierParam, OperatingPoint};

pub use crate::modifier::Target;

/// Local-state variables (indices 0..4 of the evaluation slice).
pub const LOCAL: [&str; 4] = ["p_GPa", "T_C", "u_mm", "slip_mps"];
/// Operating-point variables (indices 4..10).
pub const OPERATING: [&str; 6] = ["v_mps", "fn_kN", "cx", "cy", "spin_per_m", "t_bulk_C"];

/// The functions a formula may call, resolved when it is compiled.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Func {
    Exp,
    Ln,
    Sqrt,
    Abs,
    Tanh,
    Min,
    Max,
}

impl Func {
    fn parse(name: &str) -> Option<(Func, usize)> {
        Some(match name {
            "exp" => (Func::Exp, 1),
            "ln" => (Func::Ln, 1),
            "sqrt" => (Func::Sqrt, 1),
            "abs" => (Func::Abs, 1),
            "tanh" => (Func::Tanh, 1),
            "min" => (Func::Min, 2),
            "max" => (Func::Max, 2),
            _ => return None,
        })
    }
}

/// The parsed expression tree (compiled to [`Op`]s, then dropped).
#[derive(Clone, Debug, PartialEq)]
enum Node {
    Num(f64),
    Var(usize),
    Param(usize),
    Neg(Box<Node>),
    Bin(char, Box<Node>, Box<Node>),
    Call(Func, Vec<Node>),
}

/// One instruction of a compiled formula: a stack machine in postfix order (the operands
/// of a node are evaluated in the order the tree evaluation took them, so the result is the
/// same to the bit).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Op {
    Num(f64),
    /// A local-state variable (index into [`LOCAL`]).
    Local(u8),
    /// An operating-point variable (index into [`OPERATING`]).
    Operating(u8),
    /// A data column (index into [`FormulaEffect::columns`]).
    Column(u32),
    Param(u32),
    Neg,
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    Call1(Func),
    Min,
    Max,
}

/// Evaluation stack on the machine stack; a formula that needs more (deeply nested, e.g. a
/// long Horner polynomial) runs on a heap stack instead.
const MAX_STACK: usize = 32;

fn compile(n: &Node, out: &mut Vec<Op>) {
    match n {
        Node::Num(x) => out.push(Op::Num(*x)),
        Node::Var(i) if *i < LOCAL.len() => out.push(Op::Local(*i as u8)),
        Node::Var(i) if *i < LOCAL.len() + OPERATING.len() => {
            out.push(Op::Operating((*i - LOCAL.len()) as u8))
        }
        Node::Var(i) => out.push(Op::Column((*i - LOCAL.len() - OPERATING.len()) as u32)),
        Node::Param(i) => out.push(Op::Param(*i as u32)),
        Node::Neg(a) => {
            compile(a, out);
            out.push(Op::Neg);
        }
        Node::Bin(op, a, b) => {
            compile(a, out);
            compile(b, out);
            out.push(match op {
                '+' => Op::Add,
                '-' => Op::Sub,
                '*' => Op::Mul,
                '/' => Op::Div,
                _ => Op::Pow,
            });
        }
        Node::Call(f, args) => {
            for a in args {
                compile(a, out);
            }
            out.push(match f {
                Func::Min => Op::Min,
                Func::Max => Op::Max,
                f => Op::Call1(*f),
            });
        }
    }
}

/// Stack depth the ops need.
fn stack_depth(ops: &[Op]) -> usize {
    let (mut d, mut max) = (0usize, 0usize);
    for op in ops {
        match op {
            Op::Num(_) | Op::Local(_) | Op::Operating(_) | Op::Column(_) | Op::Param(_) => d += 1,
            Op::Neg | Op::Call1(_) => {}
            _ => d -= 1,
        }
        max = max.max(d);
    }
    max
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
    /// The expression compiled to postfix instructions (functions and variables resolved).
    ops: Vec<Op>,
    /// The evaluation stack the instructions need.
    depth: usize,
    /// True if the expression uses local bristle state.
    pub local: bool,
}

/// Deepest nesting of a formula in the parser's recursion (parentheses, function arguments,
/// signs, `^` chains): 50 levels take less than 96 KiB of stack in a release build (test
/// `nesting_is_bounded_so_that_no_formula_exhausts_a_small_stack`); a Horner polynomial of
/// degree 20 needs 21.
pub const MAX_NESTING: usize = 50;

/// Deepest expression tree (operations along one path from the result to a leaf; a flat sum
/// of n terms has depth n - 1), bounded because its compilation and drop recurse: cheap
/// frames, so far more than [`MAX_NESTING`].
pub const MAX_TREE_DEPTH: usize = 1000;

/// A parsed node and its depth.
type D = (Node, usize);

struct Parser<'a> {
    s: &'a [u8],
    i: usize,
    /// Current recursion depth of the parser.
    nest: usize,
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
    /// Runs `f` one level deeper in the parser's recursion (parentheses, function arguments,
    /// unary signs, `^` chains); refuses more than [`MAX_NESTING`] levels, so that a formula
    /// cannot exhaust the stack of the importer's thread.
    fn descend<T>(&mut self, f: impl FnOnce(&mut Self) -> Result<T>) -> Result<T> {
        self.nest += 1;
        if self.nest > MAX_NESTING {
            return Err(self.too_deep());
        }
        let r = f(self);
        self.nest -= 1;
        r
    }
    fn too_deep(&self) -> CreepError {
        self.err(&format!(
            "the formula nests deeper than {MAX_NESTING} levels (parentheses, function calls, signs, ^ chains); write it with fewer nested levels"
        ))
    }
    /// A node of depth `d` (the longest path to a leaf), refused beyond [`MAX_TREE_DEPTH`].
    fn node(&self, n: Node, d: usize) -> Result<D> {
        if d > MAX_TREE_DEPTH {
            return Err(self.err(&format!(
                "the formula has more than {MAX_TREE_DEPTH} operations along one path; split it into several effects"
            )));
        }
        Ok((n, d))
    }
    fn bin(&self, c: char, a: D, b: D) -> Result<D> {
        self.node(Node::Bin(c, Box::new(a.0), Box::new(b.0)), 1 + a.1.max(b.1))
    }
    fn expr(&mut self) -> Result<D> {
        let mut a = self.term()?;
        while let Some(c) = self.peek() {
            if c == '+' || c == '-' {
                self.i += 1;
                let b = self.term()?;
                a = self.bin(c, a, b)?;
            } else {
                break;
            }
        }
        Ok(a)
    }
    fn term(&mut self) -> Result<D> {
        let mut a = self.power()?;
        while let Some(c) = self.peek() {
            if c == '*' || c == '/' {
                self.i += 1;
                let b = self.power()?;
                a = self.bin(c, a, b)?;
            } else {
                break;
            }
        }
        Ok(a)
    }
    fn power(&mut self) -> Result<D> {
        let a = self.unary()?;
        if self.peek() == Some('^') {
            self.i += 1;
            let b = self.descend(|p| p.power())?;
            return self.bin('^', a, b);
        }
        Ok(a)
    }
    fn unary(&mut self) -> Result<D> {
        if self.peek() == Some('-') {
            self.i += 1;
            let (a, d) = self.descend(|p| p.unary())?;
            return self.node(Node::Neg(Box::new(a)), d + 1);
        }
        if self.peek() == Some('+') {
            self.i += 1;
        }
        self.primary()
    }
    fn primary(&mut self) -> Result<D> {
        match self.peek() {
            Some('(') => {
                self.i += 1;
                let e = self.descend(|p| p.expr())?;
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
                    .map(|x| (Node::Num(x), 0))
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
                    let mut args = vec![self.descend(|p| p.expr())?];
                    while self.peek() == Some(',') {
                        self.i += 1;
                        args.push(self.descend(|p| p.expr())?);
                    }
                    if self.peek() != Some(')') {
                        return Err(self.err("expected ')' after arguments"));
                    }
                    self.i += 1;
                    let Some((func, n)) = Func::parse(&name) else {
                        // point at the name, not past the call
                        self.i = st;
                        return Err(self.err(&format!(
                            "unknown function '{name}' (exp, ln, sqrt, abs, tanh, min, max)"
                        )));
                    };
                    if args.len() != n {
                        return Err(self.err(&format!("{name} takes {n} argument(s)")));
                    }
                    let d = 1 + args.iter().map(|a| a.1).max().unwrap_or(0);
                    return self.node(Node::Call(func, args.into_iter().map(|a| a.0).collect()), d);
                }
                if let Some(k) = self.params.iter().position(|p| p.name == name) {
                    return Ok((Node::Param(k), 0));
                }
                if let Some(k) = LOCAL.iter().position(|v| *v == name) {
                    self.local = true;
                    return Ok((Node::Var(k), 0));
                }
                if let Some(k) = OPERATING.iter().position(|v| *v == name) {
                    return Ok((Node::Var(LOCAL.len() + k), 0));
                }
                let k = match self.columns.iter().position(|c| *c == name) {
                    Some(k) => k,
                    None => {
                        self.columns.push(name);
                        self.columns.len() - 1
                    }
                };
                Ok((Node::Var(LOCAL.len() + OPERATING.len() + k), 0))
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

/// Runs compiled ops that need a stack of `depth` values; `var(op)` gives the value of a
/// variable instruction.
#[inline]
fn run(ops: &[Op], depth: usize, params: &[FormulaParam], var: impl Fn(Op) -> f64) -> f64 {
    if depth <= MAX_STACK {
        run_on(ops, params, var, &mut [0.0f64; MAX_STACK])
    } else {
        run_on(ops, params, var, &mut vec![0.0f64; depth])
    }
}

#[inline]
fn run_on(ops: &[Op], params: &[FormulaParam], var: impl Fn(Op) -> f64, st: &mut [f64]) -> f64 {
    let mut n = 0usize;
    for &op in ops {
        match op {
            Op::Num(x) => {
                st[n] = x;
                n += 1;
            }
            Op::Param(i) => {
                st[n] = params[i as usize].value;
                n += 1;
            }
            Op::Local(_) | Op::Operating(_) | Op::Column(_) => {
                st[n] = var(op);
                n += 1;
            }
            Op::Neg => st[n - 1] = -st[n - 1],
            Op::Call1(f) => {
                let x = st[n - 1];
                st[n - 1] = match f {
                    Func::Exp => x.exp(),
                    Func::Ln => x.ln(),
                    Func::Sqrt => x.sqrt(),
                    Func::Abs => x.abs(),
                    _ => x.tanh(),
                };
            }
            _ => {
                n -= 1;
                let (x, y) = (st[n - 1], st[n]);
                st[n - 1] = match op {
                    Op::Add => x + y,
                    Op::Sub => x - y,
                    Op::Mul => x * y,
                    Op::Div => x / y,
                    Op::Pow => x.powf(y),
                    Op::Min => x.min(y),
                    _ => x.max(y),
                };
            }
        }
    }
    st[0]
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
            nest: 0,
            params: &params,
            columns: Vec::new(),
            local: false,
        };
        // a long formula is quoted by its start in messages
        let quoted = match factor.char_indices().nth(80) {
            Some((k, _)) => format!("{}...", &factor[..k]),
            None => factor.to_string(),
        };
        let (expr, _) = p.expr().map_err(|e| CreepError::Config {
            source_name: format!("formula_effects.{name}.factor"),
            // the parser's own message ("at character N: ..."), without a second prefix
            message: format!(
                "'{quoted}' {}",
                match e {
                    CreepError::Config { message, .. } => message,
                    other => other.to_string(),
                }
            ),
        })?;
        if p.peek().is_some() {
            return Err(CreepError::Config {
                source_name: format!("formula_effects.{name}.factor"),
                message: format!("'{quoted}': unexpected text at character {}", p.i + 1),
            });
        }
        let (columns, local) = (p.columns, p.local);
        let mut ops = Vec::new();
        compile(&expr, &mut ops);
        let depth = stack_depth(&ops);
        // a factor that depends on no variable is known now: finite and >= 0
        if !uses_vars(&expr) {
            let x = run(&ops, depth, &params, |_| f64::NAN);
            if !(x.is_finite() && x >= 0.0) {
                return Err(CreepError::OutOfRange {
                    field: format!("formula_effects.{name}.factor '{quoted}'"),
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
            ops,
            depth,
            local,
        })
    }

    /// Evaluates the factor; `vars` = LOCAL values, OPERATING values, then the columns
    /// (a missing value reads as NaN).
    pub fn eval(&self, vars: &[f64]) -> f64 {
        let at = |i: usize| vars.get(i).copied().unwrap_or(f64::NAN);
        run(&self.ops, self.depth, &self.params, |op| match op {
            Op::Local(i) => at(i as usize),
            Op::Operating(i) => at(LOCAL.len() + i as usize),
            Op::Column(i) => at(LOCAL.len() + OPERATING.len() + i as usize),
            _ => f64::NAN,
        })
    }

    /// Sets a parameter value (for fitting).
    pub fn set_param(&mut self, k: usize, v: f64) {
        self.params[k].value = v;
    }
}

impl Modifier for FormulaEffect {
    fn name(&self) -> &str {
        &self.name
    }
    fn describe(&self) -> String {
        // long factors shortened to their first 40 characters, as reports quote them
        let n = self.source.chars().count();
        let src = if n <= 40 {
            self.source.clone()
        } else {
            let head: String = self.source.chars().take(40).collect();
            format!("{head}... ({n} characters)")
        };
        format!("formula effect '{}' (factor '{src}')", self.name)
    }
    fn target(&self) -> Target {
        self.target
    }
    fn uses_local_state(&self) -> bool {
        self.local
    }
    fn columns(&self) -> Vec<&str> {
        self.columns.iter().map(|c| c.as_str()).collect()
    }
    fn n_params(&self) -> usize {
        self.params.len()
    }
    fn param(&self, k: usize) -> ModifierParam {
        let q = &self.params[k];
        ModifierParam {
            name: q.name.clone(),
            value: q.value,
            min: q.min,
            max: q.max,
            limits: (q.min, q.max),
        }
    }
    fn set_param(&mut self, k: usize, v: f64) {
        self.params[k].value = v;
    }
    fn set_bounds(&mut self, k: usize, lo: f64, hi: f64) {
        (self.params[k].min, self.params[k].max) = (lo, hi);
    }
    #[inline]
    fn factor(&self, local: &LocalState, op: &OperatingPoint, cols: &[f64]) -> f64 {
        run(&self.ops, self.depth, &self.params, |o| match o {
            Op::Local(0) => local.p_gpa,
            Op::Local(1) => local.t_c,
            Op::Local(2) => local.u_mm,
            Op::Local(_) => local.slip_mps,
            Op::Operating(0) => op.v_mps,
            Op::Operating(1) => op.fn_kn,
            Op::Operating(2) => op.cx,
            Op::Operating(3) => op.cy,
            Op::Operating(4) => op.spin_per_m,
            Op::Operating(_) => op.t_bulk_c,
            Op::Column(i) => cols.get(i as usize).copied().unwrap_or(f64::NAN),
            _ => f64::NAN,
        })
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
    fn factor_reads_each_variable_from_its_slot() {
        // every variable with its own weight: a variable read from the wrong slot changes
        // the sum
        let src = "p_GPa + 10*T_C + 100*u_mm + 1e3*slip_mps + 1e4*v_mps + 1e5*fn_kN \
                   + 1e6*cx + 1e7*cy + 1e8*spin_per_m + 1e9*rain + 1e10*snow + 1e11*t_bulk_C + k";
        let k = FormulaParam {
            name: "k".into(),
            value: 0.5,
            min: 0.0,
            max: 1.0,
        };
        let f = FormulaEffect::new("all", Target::Mu, src, vec![k]).unwrap();
        assert_eq!(f.columns, ["rain", "snow"]);
        let local = LocalState {
            p_gpa: 1.0,
            t_c: 2.0,
            u_mm: 3.0,
            slip_mps: 4.0,
        };
        let named = [("snow".to_string(), 8.0), ("rain".to_string(), 7.0)];
        let op = OperatingPoint {
            v_mps: 5.0,
            fn_kn: 6.0,
            cx: 1.0,
            cy: 2.0,
            spin_per_m: 3.0,
            t_bulk_c: 9.0,
            columns: &named,
        };
        let want = 1.0 + 20.0 + 300.0 + 4e3 + 5e4 + 6e5 + 1e6 + 2e7 + 3e8 + 7e9 + 8e10 + 9e11 + 0.5;
        // the columns come in the formula's order, resolved by the caller
        assert_eq!(f.factor(&local, &op, &[7.0, 8.0]), want);
        let vars = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 1.0, 2.0, 3.0, 9.0, 7.0, 8.0];
        assert_eq!(f.eval(&vars), want);
        // a missing column reads as NaN
        assert!(f.factor(&local, &op, &[7.0]).is_nan());
        // min/max/power keep their operand order
        let g = FormulaEffect::new(
            "o",
            Target::Mu,
            "max(1, 2 - 3) + 2^3 / min(4, 8) - min(2, 1)",
            vec![],
        )
        .unwrap();
        assert_eq!(g.eval(&[]), 1.0 + 8.0 / 4.0 - 1.0);
        // the precedence docs/measurements.md states
        for (src, want) in [
            ("2^3^2", 512.0),
            ("-2^2", 4.0),
            ("-(2^2) + 5", 1.0),
            ("2*3^2", 18.0),
            ("1e-3*1e3", 1.0),
        ] {
            let f = FormulaEffect::new("p", Target::Mu, src, vec![]).unwrap();
            assert_eq!(f.eval(&[]), want, "{src}");
        }
    }

    #[test]
    fn nesting_is_bounded_so_that_no_formula_exhausts_a_small_stack() {
        // on a thread with 128 KiB of stack (half of the 256 KiB a tool's worker thread may
        // have; the release build needs less than 96 KiB for MAX_NESTING levels; an unoptimized
        // build's frames are several times larger)
        let r = std::thread::Builder::new()
            .stack_size(if cfg!(debug_assertions) { 1024 } else { 128 } * 1024)
            .spawn(|| {
                let deep = [
                    format!("{}1{}", "(".repeat(10_000), ")".repeat(10_000)),
                    format!("{}1", "2^".repeat(10_000)),
                    format!("{}1", "-".repeat(10_000)),
                    format!("{}1{}", "exp(".repeat(10_000), ")".repeat(10_000)),
                    format!(
                        "{}1{}",
                        "(1+".repeat(MAX_NESTING + 1),
                        ")".repeat(MAX_NESTING + 1)
                    ),
                ];
                let errs: Vec<String> = deep
                    .iter()
                    .map(|f| match FormulaEffect::new("d", Target::Mu, f, vec![]) {
                        Ok(_) => "accepted".to_string(),
                        Err(e) => e.to_string(),
                    })
                    .collect();
                // the deepest accepted: MAX_NESTING levels
                let ok = format!(
                    "{}1{}",
                    "(1+".repeat(MAX_NESTING - 1),
                    ")".repeat(MAX_NESTING - 1)
                );
                let f = FormulaEffect::new("d", Target::Mu, &ok, vec![]).map(|f| f.eval(&[]));
                // a flat sum is not nested: MAX_TREE_DEPTH + 1 terms are accepted, 10,000
                // refused by the tree depth (the compile and drop recursion)
                let flat = |n: usize| {
                    let src = format!("{}1", "1+".repeat(n - 1));
                    FormulaEffect::new("s", Target::Mu, &src, vec![])
                        .map(|f| f.eval(&[]))
                        .map_err(|e| e.to_string())
                };
                (errs, f.ok(), (flat(MAX_TREE_DEPTH + 1), flat(10_000)))
            })
            .unwrap()
            .join()
            .expect("no stack overflow");
        assert_eq!(r.2 .0, Ok((MAX_TREE_DEPTH + 1) as f64));
        let e = r.2 .1.clone().unwrap_err();
        assert!(
            e.contains("more than 1000 operations along one path"),
            "{e}"
        );
        assert!(e.len() < 400, "{e}");
        for e in &r.0 {
            assert!(e.contains("nests deeper than 50 levels"), "{e}");
            assert!(
                e.len() < 400,
                "the message quotes the start of the formula only: {e}"
            );
        }
        assert_eq!(r.1, Some(MAX_NESTING as f64));
    }

    #[test]
    fn a_deeply_nested_formula_runs_on_a_heap_stack() {
        // 40 pending additions (a Horner polynomial nests the same way): deeper than the
        // machine-stack buffer
        let deep = format!("{}1{}", "(1+".repeat(40), ")".repeat(40));
        let f = FormulaEffect::new("d", Target::Mu, &deep, vec![]).unwrap();
        assert!(f.depth > MAX_STACK);
        assert_eq!(f.eval(&[]), 41.0);
        let horner = format!("{}1{}", "1 + v_mps*(".repeat(20), ")".repeat(20));
        let g = FormulaEffect::new("h", Target::Mu, &horner, vec![]).unwrap();
        let mut vars = [0.0; 9];
        vars[4] = 0.5;
        let want = (0..=20).map(|k| 0.5f64.powi(k)).sum::<f64>();
        assert!((g.eval(&vars) - want).abs() < 1e-12);
        let ok = format!("{}1{}", "(1+".repeat(20), ")".repeat(20));
        assert_eq!(
            FormulaEffect::new("d", Target::Mu, &ok, vec![])
                .unwrap()
                .eval(&[]),
            21.0
        );
    }

    #[test]
    fn errors_point_at_the_problem() {
        for (src, needle) in [
            ("1 +", "end"),
            ("foo(1)", "at character 1: unknown function"),
            ("2 * foo(1)", "at character 5: unknown function"),
            ("(1", "')'"),
            ("1 2", "unexpected"),
            ("min(1)", "2 argument"),
        ] {
            let e = FormulaEffect::new("x", Target::Mu, src, vec![])
                .unwrap_err()
                .to_string();
            assert!(e.contains(needle), "{src}: {e}");
            assert_eq!(e.matches("configuration").count(), 1, "{src}: {e}");
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
