//! The header of a measurement file mapped to quantities: each column's quantity and unit conversion, the required and defaulted quantities, the extra columns.

use super::quantity::{recognise, show_unit, split_bracket_unit, Quantity};
use super::text::{cut, err, names};
use super::{ColumnMap, Defaults};
use creep_core::error::Result;

/// A column the reader understood: its index and the conversion to the canonical unit
/// (value x factor + offset).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Col {
    pub idx: usize,
    pub factor: f64,
    pub offset: f64,
}

/// The header mapped to quantities.
#[derive(Debug)]
pub(crate) struct Mapping {
    /// The header as written.
    pub header: Vec<String>,
    /// The column of each quantity, by [`Quantity`].
    cols: [Option<Col>; Quantity::ALL.len()],
    /// Which column became which quantity in what unit, in the order of [`super::Dataset::columns`].
    pub columns: Vec<ColumnMap>,
    /// Indices of the extra (numeric) columns.
    pub extra_idx: Vec<usize>,
    /// Names of the extra columns (a bracketed unit dropped where the name is free).
    pub extra_names: Vec<String>,
    /// Creepage columns without a unit in the header and without --cx-unit: read as
    /// dimensionless, refused where they look like percent.
    pub implicit_creepage: Vec<Quantity>,
}

impl Mapping {
    /// The column of a quantity, if the file has one.
    pub fn col(&self, q: Quantity) -> Option<Col> {
        self.cols[q as usize]
    }

    /// The header of a quantity's column, or its canonical name when the file has none (for
    /// messages).
    pub fn header_of(&self, q: Quantity) -> String {
        self.col(q)
            .map(|c| self.header[c.idx].clone())
            .unwrap_or_else(|| q.name().to_string())
    }
}

/// Maps a header (already checked for empty and duplicate names) to quantities; an error
/// names the column and what is expected.
pub(crate) fn map_header(header: Vec<String>, src: &str, defaults: &Defaults) -> Result<Mapping> {
    let mut m = Mapping {
        header,
        cols: [None; Quantity::ALL.len()],
        columns: Vec::new(),
        extra_idx: Vec::new(),
        extra_names: Vec::new(),
        implicit_creepage: Vec::new(),
    };
    for (i, h) in m.header.iter().enumerate() {
        let Some((q, unit)) = recognise(h) else {
            m.extra_idx.push(i);
            continue;
        };
        if let Some(prev) = m.cols[q as usize] {
            return Err(err(
                src,
                1,
                h,
                format!(
                    "'{}' and '{}' are both {} ({})",
                    cut(&m.header[prev.idx]),
                    cut(h),
                    q.spec().meaning,
                    q.name()
                ),
            ));
        }
        let conv = convert(src, h, q, &unit, defaults)?;
        if conv.implicit {
            m.implicit_creepage.push(q);
        }
        m.cols[q as usize] = Some(Col {
            idx: i,
            factor: conv.factor,
            offset: conv.offset,
        });
        m.columns.push(ColumnMap {
            header: h.clone(),
            quantity: Some(q),
            how: conv.how,
        });
    }
    require(&m, src)?;
    given_or_defaulted(&mut m, src, defaults)?;
    extra_columns(&mut m);
    if m.col(Quantity::A).is_some() != m.col(Quantity::B).is_some() {
        let missing = if m.col(Quantity::A).is_some() {
            Quantity::B
        } else {
            Quantity::A
        };
        return Err(err(
            src,
            1,
            missing.name(),
            "a_mm and b_mm come together".into(),
        ));
    }
    Ok(m)
}

/// How a recognised column's values become the canonical unit.
struct Conversion {
    factor: f64,
    offset: f64,
    /// In words, for the column mapping.
    how: String,
    /// A creepage column read as dimensionless because nothing says its unit.
    implicit: bool,
}

/// The conversion of column `h` of quantity `q` written in `unit` ("" for none); an error
/// when the quantity needs a unit, the unit is not one of the quantity's, or a creepage's
/// unit contradicts --cx-unit.
fn convert(src: &str, h: &str, q: Quantity, unit: &str, defaults: &Defaults) -> Result<Conversion> {
    let spec = q.spec();
    if unit.is_empty() && spec.needs_unit {
        return Err(err(
            src,
            1,
            h,
            format!(
                "{} needs a unit in the header, e.g. '{}' or '{} [{}]' (units: {})",
                spec.meaning,
                spec.name,
                h.trim(),
                spec.units[0].0,
                spec.accepted_units()
            ),
        ));
    }
    let Some((mut factor, offset)) = spec.unit(unit) else {
        return Err(err(
            src,
            1,
            h,
            format!(
                "unit '{}' is not a unit of {} (accepted: {})",
                cut(unit),
                spec.meaning,
                spec.accepted_units()
            ),
        ));
    };
    let mut how = if spec.text {
        "text".to_string()
    } else if unit.is_empty() {
        "no unit written".to_string()
    } else {
        format!("in {}", show_unit(unit))
    };
    let mut implicit = false;
    if q.is_creepage() {
        match (unit.is_empty(), defaults.cx_unit) {
            (true, Some(u)) => {
                factor = u.factor();
                how = format!(
                    "{} (--cx-unit)",
                    if factor == 1.0 {
                        "dimensionless"
                    } else {
                        "percent"
                    }
                );
            }
            (true, None) => {
                implicit = true;
                how = "dimensionless (no unit written)".into();
            }
            (false, Some(u)) if u.factor() != factor => {
                return Err(err(
                    src,
                    1,
                    h,
                    format!("the header says '{unit}' but --cx-unit says {u:?}"),
                ))
            }
            _ => {}
        }
    }
    if factor != 1.0 || offset != 0.0 {
        how += &format!(", converted to {} (x {factor:.6}", spec.unit);
        if offset != 0.0 {
            how += &format!(" {offset:+}");
        }
        how += ")";
    }
    Ok(Conversion {
        factor,
        offset,
        how,
        implicit,
    })
}

/// Creepage and traction coefficient must have a column.
fn require(m: &Mapping, src: &str) -> Result<()> {
    for q in [Quantity::Cx, Quantity::F] {
        if m.col(q).is_none() {
            let spec = q.spec();
            return Err(err(
                src,
                1,
                q.name(),
                format!(
                    "required column missing: {} (spellings: {}; have: {})",
                    spec.meaning,
                    spec.aliases.join(", "),
                    names(&m.header)
                ),
            ));
        }
    }
    Ok(())
}

/// Speed and normal force come from a column or from [`Defaults`] (no silent default); the
/// bulk temperature from a column or its default. Records where each came from.
fn given_or_defaulted(m: &mut Mapping, src: &str, defaults: &Defaults) -> Result<()> {
    for (q, given, unit, flag) in [
        (Quantity::V, defaults.v_mps, "m/s (--v-mps)", "--v-mps"),
        (Quantity::Fn, defaults.fn_kn, "kN (--fn-kN)", "--fn-kN"),
    ] {
        if m.col(q).is_none() {
            let spec = q.spec();
            let Some(x) = given else {
                return Err(err(
                    src,
                    1,
                    q.name(),
                    format!(
                        "no {} column (e.g. '{}', '{} [{}]'; have: {}); give it in the file or for every row with {}",
                        spec.meaning,
                        spec.name,
                        spec.aliases[0],
                        spec.units[0].0,
                        names(&m.header),
                        flag
                    ),
                ));
            };
            m.columns.push(ColumnMap {
                header: String::new(),
                quantity: Some(q),
                how: format!("not in the file: {x} {unit}"),
            });
        }
    }
    if m.col(Quantity::TBulk).is_none() {
        m.columns.push(ColumnMap {
            header: String::new(),
            quantity: Some(Quantity::TBulk),
            how: format!("not in the file: {} degC (default)", defaults.t_bulk_c),
        });
    }
    Ok(())
}

/// Names the extra columns and records them in the mapping. An extra column's name drops a
/// bracketed unit ("humidity [%]" is the column `humidity` of formula and Rust effects),
/// unless that name is taken.
fn extra_columns(m: &mut Mapping) {
    let header = &m.header;
    m.extra_names = m
        .extra_idx
        .iter()
        .map(|&i| {
            let (name, unit) = split_bracket_unit(&header[i]);
            let taken = header
                .iter()
                .enumerate()
                .any(|(k, h)| k != i && (h == name || split_bracket_unit(h).0 == name));
            if unit.is_some() && !taken && !name.is_empty() {
                name.to_string()
            } else {
                header[i].clone()
            }
        })
        .collect();
    for (&i, name) in m.extra_idx.iter().zip(&m.extra_names) {
        let unit = split_bracket_unit(&header[i]).1;
        m.columns.push(ColumnMap {
            header: header[i].clone(),
            quantity: None,
            how: match unit {
                Some(u) if *name != header[i] => format!(
                    "extra column '{name}' in {u} (not a known quantity; numeric, taken as written)"
                ),
                _ => "extra column (not a known quantity; numeric)".into(),
            },
        });
    }
}

#[cfg(test)]
mod tests {
    use super::super::CreepageUnit;
    use super::*;

    fn map(h: &str, d: &Defaults) -> Result<Mapping> {
        map_header(h.split(',').map(String::from).collect(), "h.csv", d)
    }

    #[test]
    fn columns_convert_to_the_canonical_unit() {
        let m = map(
            "c_x [%],f,v [km/h],FN [N],T [K],humidity [%]",
            &Defaults::default(),
        )
        .unwrap();
        let cx = m.col(Quantity::Cx).unwrap();
        assert_eq!((cx.idx, cx.factor), (0, 0.01));
        assert_eq!(m.col(Quantity::V).unwrap().factor, 1.0 / 3.6);
        assert_eq!(m.col(Quantity::Fn).unwrap().factor, 1e-3);
        assert_eq!(m.col(Quantity::TBulk).unwrap().offset, -273.15);
        assert_eq!(m.extra_idx, vec![5]);
        assert_eq!(m.extra_names, vec!["humidity"]);
        assert!(m.implicit_creepage.is_empty());
        assert_eq!(m.header_of(Quantity::V), "v [km/h]");
        assert_eq!(m.header_of(Quantity::Cy), "cy");
        assert_eq!(m.columns[2].how, "in km/h, converted to m/s (x 0.277778)");
        assert_eq!(
            m.columns[4].how,
            "in K, converted to degC (x 1.000000 -273.15)"
        );
    }

    #[test]
    fn creepage_without_unit_follows_cx_unit_or_is_implicit() {
        let m = map("cx,f,v_mps,fn_kN", &Defaults::default()).unwrap();
        assert_eq!(m.implicit_creepage, vec![Quantity::Cx]);
        let d = Defaults {
            cx_unit: Some(CreepageUnit::Percent),
            ..Defaults::default()
        };
        let m = map("cx,f,v_mps,fn_kN", &d).unwrap();
        assert!(m.implicit_creepage.is_empty());
        assert_eq!(m.col(Quantity::Cx).unwrap().factor, 0.01);
        assert_eq!(
            m.columns[0].how,
            "percent (--cx-unit), converted to dimensionless (x 0.010000)"
        );
        let e = map("cx [-],f,v_mps,fn_kN", &d).unwrap_err().to_string();
        assert!(
            e.contains("the header says '-' but --cx-unit says Percent"),
            "{e}"
        );
    }

    #[test]
    fn header_errors_name_the_column_and_the_expectation() {
        let d = Defaults::default();
        let cases = [
            ("cx,creepage,f,v_mps,fn_kN", "column 'creepage': 'cx' and 'creepage' are both longitudinal creepage (cx)"),
            ("cx,f,v,fn_kN", "column 'v': vehicle speed needs a unit in the header, e.g. 'v_mps' or 'v [m/s]' (units: m/s, mps, km/h, kmh, kph)"),
            ("cx,f,v [furlong],fn_kN", "unit 'furlong' is not a unit of vehicle speed (accepted: m/s, mps, km/h, kmh, kph)"),
            ("f,v_mps,fn_kN", "column 'cx': required column missing: longitudinal creepage (spellings: cx, c_x, creepage, creepage_x, longitudinal_creepage; have: f, v_mps, fn_kN)"),
            ("cx,f,fn_kN", "column 'v_mps': no vehicle speed column (e.g. 'v_mps', 'v [m/s]'; have: cx, f, fn_kN); give it in the file or for every row with --v-mps"),
            ("cx,f,v_mps", "give it in the file or for every row with --fn-kN"),
            ("cx,f,v_mps,fn_kN,b_mm", "column 'a_mm': a_mm and b_mm come together"),
        ];
        for (h, want) in cases {
            let e = map(h, &d).err().map(|e| e.to_string()).unwrap_or_default();
            assert!(e.contains(want), "{h}: {e}");
        }
        let d = Defaults {
            v_mps: Some(7.0),
            fn_kn: Some(90.0),
            ..Defaults::default()
        };
        let m = map("cx,f", &d).unwrap();
        let hows: Vec<&str> = m.columns.iter().map(|c| c.how.as_str()).collect();
        assert_eq!(
            &hows[2..],
            [
                "not in the file: 7 m/s (--v-mps)",
                "not in the file: 90 kN (--fn-kN)",
                "not in the file: 20 degC (default)"
            ]
        );
    }
}
