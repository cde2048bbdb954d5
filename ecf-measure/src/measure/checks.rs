//! Checks over all rows of a measurement file once they are read: rows at all, creepage without a unit that looks like percent, time series whose times increase.

use super::header::Mapping;
use super::text::{cut, err};
use super::{percent_message, Row, PERCENT_LOOKING};
use creep_core::error::Result;
use std::collections::BTreeMap;

/// Every check over the rows, in order.
pub(crate) fn check_rows(rows: &[Row], map: &Mapping, src: &str) -> Result<()> {
    if rows.is_empty() {
        return Err(err(src, 2, "-", "no data rows".into()));
    }
    percent_looking(rows, map, src)?;
    time_series(rows, src)
}

/// A creepage column without a unit whose largest magnitude exceeds [`PERCENT_LOOKING`] is
/// taken to be percent and refused at the row of that value.
fn percent_looking(rows: &[Row], map: &Mapping, src: &str) -> Result<()> {
    for &q in &map.implicit_creepage {
        let get = |r: &Row| if q == super::Quantity::Cx { r.cx } else { r.cy };
        let worst = rows
            .iter()
            .max_by(|a, b| get(a).abs().total_cmp(&get(b).abs()))
            .map(|r| (r.line, get(r)));
        if let Some((line, x)) = worst {
            if x.abs() > PERCENT_LOOKING {
                return Err(err(
                    src,
                    line,
                    &map.header_of(q),
                    percent_message(q.name(), x),
                ));
            }
        }
    }
    Ok(())
}

/// Within a series either all rows have t_s or none, and times increase.
fn time_series(rows: &[Row], src: &str) -> Result<()> {
    let mut last: BTreeMap<&str, (Option<f64>, usize)> = BTreeMap::new();
    for r in rows {
        if let Some((prev, pline)) = last.get(r.series.as_str()) {
            if prev.is_some() != r.t.is_some() {
                return Err(err(
                    src,
                    r.line,
                    "t_s",
                    format!(
                        "series '{}' mixes rows with and without t_s (line {pline})",
                        cut(&r.series)
                    ),
                ));
            }
            if let (Some(a), Some(b)) = (prev, r.t) {
                if b <= *a {
                    return Err(err(
                        src,
                        r.line,
                        "t_s",
                        format!("time {b} s does not increase (line {pline} has {a} s)"),
                    ));
                }
            }
        }
        last.insert(r.series.as_str(), (r.t, r.line));
    }
    Ok(())
}
