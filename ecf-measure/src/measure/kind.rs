//! Which kind a measurement file is, told from its header, and reading it as that kind.

use super::hpt_file::{read_hpt, HptRow, HPT_COLUMNS};
use super::text::{detect_delimiter, utf8_text};
use super::{Dataset, Defaults};
use creep_core::error::{CreepError, Result};
use std::path::Path;

/// The kinds of measurement file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    /// Steady characteristics and time series (`cx`, `f`, ...), read by [`Dataset`].
    Rows,
    /// High-pressure-torsion curves (`p_MPa`, `u_mm`, `tau_MPa`), read by [`read_hpt`].
    Hpt,
}

/// A measurement file read as its kind.
#[derive(Clone, Debug, PartialEq)]
pub enum Data {
    /// Steady characteristics and time series (`cx`, `f`, ...).
    Rows(Dataset),
    /// High-pressure-torsion curves (`p_MPa`, `u_mm`, `tau_MPa`).
    Hpt(Vec<HptRow>),
}

/// The kind of a measurement file's text: a first non-comment line that names `p_MPa`,
/// `u_mm` and `tau_MPa` makes it a high-pressure-torsion file.
pub fn file_kind(text: &str) -> FileKind {
    let delim = detect_delimiter(text) as char;
    let hpt = text
        .lines()
        .find(|l| !l.trim_start().starts_with('#'))
        .is_some_and(|h| {
            let cols: Vec<&str> = h.split(delim).map(|c| c.trim()).collect();
            HPT_COLUMNS.iter().all(|c| cols.contains(c))
        });
    if hpt {
        FileKind::Hpt
    } else {
        FileKind::Rows
    }
}

/// Reads a measurement file of either kind ([`file_kind`]).
pub fn read_data(path: &Path, defaults: &Defaults) -> Result<Data> {
    let src = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| CreepError::Data {
        source_name: src.clone(),
        message: format!("cannot read: {e}"),
    })?;
    read_data_text(&utf8_text(&bytes, &src)?, &src, defaults)
}

/// Reads measurement CSV text of either kind ([`file_kind`]); `src` names it in messages.
pub fn read_data_text(text: &str, src: &str, defaults: &Defaults) -> Result<Data> {
    Ok(match file_kind(text) {
        FileKind::Hpt => Data::Hpt(read_hpt(text, src)?),
        FileKind::Rows => Data::Rows(Dataset::from_csv_str(text, src, defaults)?),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_header_tells_the_kind() {
        assert_eq!(file_kind("# c\np_MPa;u_mm;tau_MPa\n1;2;3\n"), FileKind::Hpt);
        assert_eq!(file_kind("series,tau_MPa,u_mm,p_MPa\n"), FileKind::Hpt);
        assert_eq!(file_kind("p_MPa,u_mm,cx,f\n"), FileKind::Rows);
        assert_eq!(file_kind("cx,f\n"), FileKind::Rows);
        assert_eq!(file_kind(""), FileKind::Rows);
    }
}
