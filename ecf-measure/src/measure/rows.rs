//! The data rows of a measurement file: each record's cells parsed, converted to the canonical units and checked against the physical ranges.

use super::header::Mapping;
use super::quantity::Quantity;
use super::text::{cut, delimiter_name, err, Lines};
use super::{percent_message, Defaults, Row};
use creep_core::error::Result;

/// Reads every data row of `rdr` (the header already read and mapped); the first problem is
/// an error with its line and column.
pub(crate) fn read_rows(
    rdr: &mut csv::Reader<&[u8]>,
    text: &str,
    src: &str,
    delim: u8,
    map: &Mapping,
    defaults: &Defaults,
) -> Result<Vec<Row>> {
    let mut rows = Vec::new();
    let mut rec = csv::StringRecord::new();
    let mut lines = Lines::new(text);
    let mut k = 0usize;
    loop {
        k += 1;
        let more = rdr.read_record(&mut rec).map_err(|e| {
            err(
                src,
                e.position().map(|p| p.line() as usize).unwrap_or(k + 1),
                "-",
                cut(&e.to_string()),
            )
        })?;
        if !more {
            break;
        }
        let line = lines.line_of(rec.position(), k + 1);
        if rec.len() != map.header.len() {
            return Err(err(
                src,
                line,
                "-",
                format!(
                    "{} fields, header has {} (delimiter '{}')",
                    rec.len(),
                    map.header.len(),
                    delimiter_name(delim)
                ),
            ));
        }
        let cells = Cells {
            rec: &rec,
            line,
            src,
            map,
            decimal_comma: delim == b';',
        };
        rows.push(cells.row(defaults)?);
    }
    Ok(rows)
}

/// The cells of one record, read as quantities.
struct Cells<'a> {
    rec: &'a csv::StringRecord,
    line: usize,
    src: &'a str,
    map: &'a Mapping,
    decimal_comma: bool,
}

impl Cells<'_> {
    /// The row, its quantities read in a fixed order (the first error is that of the first
    /// in this order): cx, f, speed, load, semi-axes, time, extra columns, cy, spin, bulk
    /// temperature.
    fn row(&self, defaults: &Defaults) -> Result<Row> {
        let cx = self.range(
            Quantity::Cx,
            self.percent_like(Quantity::Cx, self.required(Quantity::Cx)?)?,
            -10.0,
            10.0,
            "(dimensionless creepage: 0.01 = 1 %)",
        )?;
        let f = self.range(
            Quantity::F,
            self.required(Quantity::F)?,
            -2.0,
            2.0,
            "(traction coefficient F_x/F_N)",
        )?;
        let v = self.range(
            Quantity::V,
            self.given_or(Quantity::V, defaults.v_mps)?,
            0.0,
            200.0,
            "m/s",
        )?;
        let fn_kn = self.given_or(Quantity::Fn, defaults.fn_kn)?;
        if fn_kn > 5000.0 {
            return Err(self.error(
                Quantity::Fn,
                format!(
                    "{fn_kn} kN per wheel cannot be right: is the column in N instead of kN? (write 'fn_N' or 'FN [N]')"
                ),
            ));
        }
        let fn_kn = self.range(Quantity::Fn, fn_kn, 1e-6, 5000.0, "kN")?;
        let ab = self.semi_axes()?;
        let t = self.opt(Quantity::T)?;
        let mut extra = Vec::with_capacity(self.map.extra_idx.len());
        for &i in &self.map.extra_idx {
            extra.push(self.number(i)?);
        }
        Ok(Row {
            line: self.line,
            series: self.text(Quantity::Series, "all"),
            condition: self.text(Quantity::Condition, "dry"),
            cx,
            cy: self.range(
                Quantity::Cy,
                self.percent_like(Quantity::Cy, self.opt(Quantity::Cy)?.unwrap_or(0.0))?,
                -10.0,
                10.0,
                "(dimensionless)",
            )?,
            spin: self.range(
                Quantity::Spin,
                self.opt(Quantity::Spin)?.unwrap_or(0.0),
                -1e4,
                1e4,
                "1/m",
            )?,
            v,
            fn_n: fn_kn * 1e3,
            ab,
            t,
            t_bulk: self.range(
                Quantity::TBulk,
                self.opt(Quantity::TBulk)?.unwrap_or(defaults.t_bulk_c),
                -100.0,
                1000.0,
                "degC",
            )?,
            f,
            extra,
        })
    }

    fn error(&self, q: Quantity, reason: String) -> creep_core::error::CreepError {
        err(self.src, self.line, &self.map.header_of(q), reason)
    }

    /// Cell `i` as a finite number (a decimal comma accepted with `;` as delimiter).
    fn number(&self, i: usize) -> Result<f64> {
        let s = &self.rec[i];
        let x: f64 = if self.decimal_comma && s.contains(',') {
            s.replace(',', ".").parse()
        } else {
            s.parse()
        }
        .map_err(|_| {
            err(
                self.src,
                self.line,
                &self.map.header[i],
                format!("'{}' is not a number", cut(s)),
            )
        })?;
        if !x.is_finite() {
            return Err(err(
                self.src,
                self.line,
                &self.map.header[i],
                format!("'{}' is not finite", cut(s)),
            ));
        }
        Ok(x)
    }

    /// A quantity's value in its canonical unit; `None` for no column or an empty cell.
    fn opt(&self, q: Quantity) -> Result<Option<f64>> {
        match self.map.col(q) {
            Some(c) if !self.rec[c.idx].is_empty() => {
                self.number(c.idx).map(|x| Some(x * c.factor + c.offset))
            }
            _ => Ok(None),
        }
    }

    /// A quantity whose cell must not be empty.
    fn required(&self, q: Quantity) -> Result<f64> {
        self.opt(q)?.ok_or_else(|| self.error(q, "empty".into()))
    }

    /// A quantity from its column (whose cells must not be empty) or, without a column, the
    /// value given for every row (NaN where none is: the range check refuses it).
    fn given_or(&self, q: Quantity, given: Option<f64>) -> Result<f64> {
        match self.opt(q)? {
            Some(x) => Ok(x),
            None if self.map.col(q).is_some() => Err(self.error(q, "empty".into())),
            None => Ok(given.unwrap_or(f64::NAN)),
        }
    }

    fn range(&self, q: Quantity, x: f64, lo: f64, hi: f64, what: &str) -> Result<f64> {
        if x < lo || x > hi {
            Err(self.error(q, format!("{x} is outside [{lo}, {hi}] {what}")))
        } else {
            Ok(x)
        }
    }

    /// A creepage without a unit beyond 10 is percent, not a creepage.
    fn percent_like(&self, q: Quantity, x: f64) -> Result<f64> {
        if x.abs() > 10.0 && self.map.implicit_creepage.contains(&q) {
            return Err(self.error(q, percent_message(q.name(), x)));
        }
        Ok(x)
    }

    /// Both semi-axes (m) or neither.
    fn semi_axes(&self) -> Result<Option<(f64, f64)>> {
        match (self.opt(Quantity::A)?, self.opt(Quantity::B)?) {
            (Some(a), Some(b)) => Ok(Some((
                self.range(Quantity::A, a, 1e-3, 500.0, "mm")? * 1e-3,
                self.range(Quantity::B, b, 1e-3, 500.0, "mm")? * 1e-3,
            ))),
            (None, None) => Ok(None),
            _ => Err(err(
                self.src,
                self.line,
                "a_mm/b_mm",
                "give both semi-axes or neither".into(),
            )),
        }
    }

    /// A text cell, or `default` for no column or an empty cell.
    fn text(&self, q: Quantity, default: &str) -> String {
        self.map
            .col(q)
            .map(|c| self.rec[c.idx].to_string())
            .filter(|s| !s.is_empty())
            .unwrap_or_else(|| default.to_string())
    }
}
