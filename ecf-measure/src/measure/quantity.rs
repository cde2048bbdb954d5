//! The quantities a measurement file may hold, their spellings and units, and how a header names one.

use std::fmt;

/// A quantity the reader knows. Its canonical column name ([`Quantity::name`]) carries the
/// canonical unit; [`QUANTITIES`] holds its spellings and units, in the order of this enum.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Quantity {
    /// Longitudinal creepage, `cx`.
    Cx,
    /// Measured traction coefficient F_x/F_N, `f`.
    F,
    /// Test / curve name, `series`.
    Series,
    /// Contact condition, `condition`.
    Condition,
    /// Vehicle speed, `v_mps`.
    V,
    /// Normal force per wheel, `fn_kN`.
    Fn,
    /// Semi-axis in rolling direction, `a_mm`.
    A,
    /// Lateral semi-axis, `b_mm`.
    B,
    /// Lateral creepage, `cy`.
    Cy,
    /// Spin creepage, `cs_per_m`.
    Spin,
    /// Time, `t_s`.
    T,
    /// Bulk / ambient temperature, `t_bulk_C`.
    TBulk,
}

impl Quantity {
    /// Every quantity, in the order of [`QUANTITIES`].
    pub const ALL: [Quantity; 12] = [
        Quantity::Cx,
        Quantity::F,
        Quantity::Series,
        Quantity::Condition,
        Quantity::V,
        Quantity::Fn,
        Quantity::A,
        Quantity::B,
        Quantity::Cy,
        Quantity::Spin,
        Quantity::T,
        Quantity::TBulk,
    ];

    /// Its row of [`QUANTITIES`].
    pub fn spec(self) -> &'static QuantitySpec {
        &QUANTITIES[self as usize]
    }

    /// Canonical column name (`cx`, `v_mps`, ...).
    pub fn name(self) -> &'static str {
        self.spec().name
    }

    /// The quantity of a canonical column name.
    pub fn by_name(name: &str) -> Option<Quantity> {
        Quantity::ALL.into_iter().find(|q| q.name() == name)
    }

    /// A creepage (`cx`, `cy`): dimensionless or percent, and `--cx-unit` applies.
    pub fn is_creepage(self) -> bool {
        matches!(self, Quantity::Cx | Quantity::Cy)
    }
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

/// How a quantity is written: canonical name, meaning, accepted base spellings (lower
/// case), accepted units (lower case, factor to the canonical unit, offset added after the
/// factor; "" = no unit written), and whether a unit must be written.
pub struct QuantitySpec {
    /// Canonical column name (carries the canonical unit).
    pub name: &'static str,
    /// Canonical unit in words (`m/s`, `kN`, ..., `dimensionless`).
    pub unit: &'static str,
    /// Meaning.
    pub meaning: &'static str,
    /// Base spellings, lower case.
    pub aliases: &'static [&'static str],
    /// Units: (spelling lower case, factor, offset).
    pub units: &'static [(&'static str, f64, f64)],
    /// A unit must be written (dimensional quantities).
    pub needs_unit: bool,
    /// Text column (no unit).
    pub text: bool,
}

impl QuantitySpec {
    /// The unit spellings a header may use, for messages ("m/s, mps, km/h, ...").
    pub fn accepted_units(&self) -> String {
        self.units
            .iter()
            .filter(|u| !u.0.is_empty())
            .map(|u| u.0)
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Factor and offset of a unit spelling (normalised as [`recognise`] returns it).
    pub fn unit(&self, unit: &str) -> Option<(f64, f64)> {
        self.units
            .iter()
            .find(|u| u.0 == unit)
            .map(|&(_, factor, offset)| (factor, offset))
    }
}

const CREEPAGE_UNITS: &[(&str, f64, f64)] = &[
    ("", 1.0, 0.0),
    ("-", 1.0, 0.0),
    ("1", 1.0, 0.0),
    ("%", 0.01, 0.0),
    ("pct", 0.01, 0.0),
    ("percent", 0.01, 0.0),
];

/// The known quantities with their spellings and units, in the order of [`Quantity::ALL`].
pub const QUANTITIES: &[QuantitySpec] = &[
    QuantitySpec {
        name: "cx",
        unit: "dimensionless",
        meaning: "longitudinal creepage",
        aliases: &[
            "cx",
            "c_x",
            "creepage",
            "creepage_x",
            "longitudinal_creepage",
        ],
        units: CREEPAGE_UNITS,
        needs_unit: false,
        text: false,
    },
    QuantitySpec {
        name: "f",
        unit: "dimensionless",
        meaning: "measured traction coefficient F_x/F_N",
        aliases: &[
            "f",
            "traction",
            "traction_coefficient",
            "adhesion",
            "adhesion_coefficient",
        ],
        units: &[("", 1.0, 0.0), ("-", 1.0, 0.0), ("1", 1.0, 0.0)],
        needs_unit: false,
        text: false,
    },
    QuantitySpec {
        name: "series",
        unit: "dimensionless",
        meaning: "test / curve name",
        aliases: &["series", "curve", "test", "run"],
        units: &[("", 1.0, 0.0)],
        needs_unit: false,
        text: true,
    },
    QuantitySpec {
        name: "condition",
        unit: "dimensionless",
        meaning: "contact condition",
        aliases: &["condition", "cond", "surface"],
        units: &[("", 1.0, 0.0)],
        needs_unit: false,
        text: true,
    },
    QuantitySpec {
        name: "v_mps",
        unit: "m/s",
        meaning: "vehicle speed",
        aliases: &["v", "speed", "velocity", "vehicle_speed"],
        units: &[
            ("m/s", 1.0, 0.0),
            ("mps", 1.0, 0.0),
            ("km/h", 1.0 / 3.6, 0.0),
            ("kmh", 1.0 / 3.6, 0.0),
            ("kph", 1.0 / 3.6, 0.0),
        ],
        needs_unit: true,
        text: false,
    },
    QuantitySpec {
        name: "fn_kN",
        unit: "kN",
        meaning: "normal force per wheel",
        aliases: &["fn", "f_n", "normal_force", "load", "wheel_load"],
        units: &[("kn", 1.0, 0.0), ("n", 1e-3, 0.0)],
        needs_unit: true,
        text: false,
    },
    QuantitySpec {
        name: "a_mm",
        unit: "mm",
        meaning: "contact semi-axis in rolling direction",
        aliases: &["a"],
        units: &[("mm", 1.0, 0.0), ("m", 1e3, 0.0)],
        needs_unit: true,
        text: false,
    },
    QuantitySpec {
        name: "b_mm",
        unit: "mm",
        meaning: "lateral contact semi-axis",
        aliases: &["b"],
        units: &[("mm", 1.0, 0.0), ("m", 1e3, 0.0)],
        needs_unit: true,
        text: false,
    },
    QuantitySpec {
        name: "cy",
        unit: "dimensionless",
        meaning: "lateral creepage",
        aliases: &["cy", "c_y", "lateral_creepage"],
        units: CREEPAGE_UNITS,
        needs_unit: false,
        text: false,
    },
    QuantitySpec {
        name: "cs_per_m",
        unit: "1/m",
        meaning: "spin creepage",
        aliases: &["cs", "c_s", "spin"],
        units: &[
            ("per_m", 1.0, 0.0),
            ("1/m", 1.0, 0.0),
            ("per_mm", 1e3, 0.0),
            ("1/mm", 1e3, 0.0),
        ],
        needs_unit: true,
        text: false,
    },
    QuantitySpec {
        name: "t_s",
        unit: "s",
        meaning: "time",
        aliases: &["t", "time"],
        units: &[("s", 1.0, 0.0), ("ms", 1e-3, 0.0)],
        needs_unit: true,
        text: false,
    },
    QuantitySpec {
        name: "t_bulk_C",
        unit: "degC",
        meaning: "bulk / ambient temperature",
        aliases: &[
            "t_bulk",
            "t",
            "t_ambient",
            "t_amb",
            "bulk_temperature",
            "ambient_temperature",
        ],
        units: &[
            ("c", 1.0, 0.0),
            ("degc", 1.0, 0.0),
            ("°c", 1.0, 0.0),
            ("k", 1.0, -273.15),
        ],
        needs_unit: true,
        text: false,
    },
];

/// Unit of a canonical column name ("dimensionless" for a name that is not one).
pub fn canonical_unit(name: &str) -> &'static str {
    Quantity::by_name(name).map_or("dimensionless", |q| q.spec().unit)
}

/// A unit spelling as the column mapping shows it (`kn` -> `kN`, `%` -> `percent`, ...).
pub(crate) fn show_unit(u: &str) -> String {
    match u {
        "kn" => "kN".into(),
        "n" => "N".into(),
        "c" | "degc" | "°c" => "degC".into(),
        "k" => "K".into(),
        "%" | "pct" | "percent" => "percent".into(),
        "-" | "1" => "dimensionless".into(),
        _ => u.into(),
    }
}

/// A header "name [unit]" or "name (unit)" split into its trimmed name and unit; a header
/// without a bracketed unit is (header, None).
pub(crate) fn split_bracket_unit(h: &str) -> (&str, Option<&str>) {
    let t = h.trim();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if t.ends_with(close) {
            if let Some(i) = t.rfind(open) {
                return (t[..i].trim(), Some(t[i + 1..t.len() - 1].trim()));
            }
        }
    }
    (t, None)
}

/// The quantity a header names and the unit it writes (lower case, spaces removed; "" for
/// none): `v [m/s]`, `v (km/h)`, or `v_kmh` when the suffix is a unit of a quantity whose
/// spelling is the prefix. A bracketed unit the quantity does not accept is returned as
/// written, for the caller to refuse. `None`: not a known quantity (an extra column).
pub fn recognise(h: &str) -> Option<(Quantity, String)> {
    let norm = |s: &str| s.trim().to_lowercase().replace(' ', "_");
    let unit_norm = |s: &str| s.trim().to_lowercase().replace(' ', "");
    let by_alias = |base: &str| {
        Quantity::ALL
            .into_iter()
            .find(|q| q.spec().aliases.contains(&base))
    };
    let find = |base: &str, unit: &str| -> Option<Quantity> {
        Quantity::ALL.into_iter().find(|q| {
            q.spec().aliases.contains(&base) && q.spec().units.iter().any(|u| u.0 == unit)
        })
    };
    let t = h.trim();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if t.ends_with(close) {
            if let Some(i) = t.rfind(open) {
                let base = norm(&t[..i]);
                let unit = unit_norm(&t[i + 1..t.len() - 1]);
                let unit = if unit == "1/m" || unit == "/m" {
                    "per_m".to_string()
                } else if unit == "1/mm" {
                    "per_mm".to_string()
                } else {
                    unit
                };
                return by_alias(&base).map(|k| (find(&base, &unit).unwrap_or(k), unit));
            }
        }
    }
    let whole = norm(t);
    // a name with a unit suffix: try every split at '_'
    for (i, _) in whole.match_indices('_') {
        let (base, unit) = (&whole[..i], &whole[i + 1..]);
        if let Some(k) = find(base, unit) {
            return Some((k, unit.to_string()));
        }
    }
    by_alias(&whole).map(|k| (k, String::new()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_in_the_order_of_the_enum() {
        assert_eq!(QUANTITIES.len(), Quantity::ALL.len());
        for (k, q) in Quantity::ALL.into_iter().enumerate() {
            assert_eq!(q as usize, k);
            assert_eq!(Quantity::by_name(q.name()), Some(q));
        }
        assert_eq!(Quantity::by_name("humidity"), None);
        assert_eq!(format!("[{:<6}]", Quantity::F), "[f     ]");
    }

    #[test]
    fn headers_name_quantity_and_unit() {
        let cases = [
            ("cx", Some((Quantity::Cx, ""))),
            ("c_x [%]", Some((Quantity::Cx, "%"))),
            ("cx_pct", Some((Quantity::Cx, "pct"))),
            ("v [km/h]", Some((Quantity::V, "km/h"))),
            ("Speed (M/S)", Some((Quantity::V, "m/s"))),
            ("v_kmh", Some((Quantity::V, "kmh"))),
            ("FN [N]", Some((Quantity::Fn, "n"))),
            ("cs [1/mm]", Some((Quantity::Spin, "per_mm"))),
            ("cs [/m]", Some((Quantity::Spin, "per_m"))),
            ("t_ms", Some((Quantity::T, "ms"))),
            ("T [K]", Some((Quantity::TBulk, "k"))),
            ("t", Some((Quantity::T, ""))),
            ("v [furlong]", Some((Quantity::V, "furlong"))),
            ("humidity [%]", None),
            ("humidity", None),
        ];
        for (h, want) in cases {
            let got = recognise(h);
            assert_eq!(got.as_ref().map(|(q, u)| (*q, u.as_str())), want, "{h}");
        }
    }

    #[test]
    fn canonical_units_and_brackets() {
        assert_eq!(canonical_unit("v_mps"), "m/s");
        assert_eq!(canonical_unit("t_bulk_C"), "degC");
        assert_eq!(canonical_unit("cx"), "dimensionless");
        assert_eq!(canonical_unit("humidity"), "dimensionless");
        assert_eq!(split_bracket_unit(" salt (g/m2) "), ("salt", Some("g/m2")));
        assert_eq!(split_bracket_unit("salt"), ("salt", None));
        assert_eq!(show_unit("kn"), "kN");
        assert_eq!(QUANTITIES[4].accepted_units(), "m/s, mps, km/h, kmh, kph");
        assert_eq!(Quantity::Fn.spec().unit("n"), Some((1e-3, 0.0)));
        assert_eq!(Quantity::Fn.spec().unit("lbf"), None);
    }
}
