//! Writes modelDescription.xml (FMI 2.0 Co-Simulation) from the variable table; the GUID is a hash of the rest of the file.

use crate::vars::{self, Causality, Kind, Start, Var};
use std::fmt::Write;

/// The model identifier (name of the shared library and of the .fmu).
pub const MODEL_IDENTIFIER: &str = "ecf_contact";

/// Default experiment: start, stop and communication step, s.
pub const DEFAULT_EXPERIMENT: (f64, f64, f64) = (0.0, 0.05, 1e-3);

/// Log categories: name and description.
pub const LOG_CATEGORIES: &[(&str, &str)] = &[
    (
        "logEvents",
        "initialization, configuration and state events (debug)",
    ),
    (
        "logStatusWarning",
        "warnings: inputs outside the usual range, lift-off, model validity",
    ),
    (
        "logStatusError",
        "errors: rejected values, wrong call sequence, bad configuration",
    ),
];

/// Escapes text for an XML attribute.
pub fn xml_escape(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&apos;"),
            _ => o.push(c),
        }
    }
    o
}

/// An xs:double literal (INF/-INF for infinities; shortest round-trip digits otherwise).
pub fn xml_double(x: f64) -> String {
    if x.is_infinite() {
        if x > 0.0 {
            "INF".into()
        } else {
            "-INF".into()
        }
    } else if x.is_nan() {
        "NaN".into()
    } else {
        format!("{x:?}")
    }
}

pub(crate) fn fnv1a(data: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in data {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

const GUID_PLACEHOLDER: &str = "@GUID@";

/// The unit, min, max and start attributes of a variable (the same in the FMI 2.0 and 3.0
/// model descriptions); a String's start only if `string_start` (FMI 3.0 gives it as an
/// element).
pub(crate) fn value_attributes(v: &Var, string_start: bool) -> String {
    let mut attrs = String::new();
    if let Some(u) = v.unit {
        let _ = write!(attrs, " unit=\"{}\"", xml_escape(u));
    }
    let bound = |x: f64| match v.kind {
        Kind::Integer => format!("{}", x as i64),
        _ => xml_double(x),
    };
    if matches!(v.kind, Kind::Real | Kind::Integer) {
        if let Some(m) = v.min {
            let _ = write!(attrs, " min=\"{}\"", bound(m));
        }
        if let Some(m) = v.max {
            let _ = write!(attrs, " max=\"{}\"", bound(m));
        }
    }
    match &v.start {
        Start::None => {}
        Start::Real(x) => {
            let _ = write!(attrs, " start=\"{}\"", xml_double(*x));
        }
        Start::Integer(i) => {
            let _ = write!(attrs, " start=\"{i}\"");
        }
        Start::Boolean(b) => {
            let _ = write!(attrs, " start=\"{b}\"");
        }
        Start::String(s) if string_start => {
            let _ = write!(attrs, " start=\"{}\"", xml_escape(s));
        }
        Start::String(_) => {}
    }
    attrs
}

fn scalar_variable(out: &mut String, index: usize, v: &Var) {
    let causality = match v.causality {
        Causality::Parameter => "parameter",
        Causality::Input => "input",
        Causality::Output => "output",
    };
    let variability = match (v.causality, v.kind) {
        (Causality::Parameter, _) => "fixed",
        (_, Kind::Real) => "continuous",
        _ => "discrete",
    };
    let _ = writeln!(out, "    <!-- {index} -->");
    let _ = writeln!(
        out,
        "    <ScalarVariable name=\"{}\" valueReference=\"{}\" description=\"{}\" causality=\"{causality}\" variability=\"{variability}\">",
        xml_escape(&v.name),
        v.vr,
        xml_escape(&v.description)
    );
    let attrs = value_attributes(v, true);
    let _ = writeln!(out, "      <{}{attrs}/>", v.kind.name());
    let _ = writeln!(out, "    </ScalarVariable>");
}

/// The UnitDefinitions, LogCategories and DefaultExperiment elements (the same in the FMI
/// 2.0 and 3.0 model descriptions).
pub(crate) fn common_elements(o: &mut String) {
    let _ = writeln!(o, "  <UnitDefinitions>");
    for u in vars::UNITS {
        let mut attrs = String::new();
        for (name, e) in ["kg", "m", "s", "K"].iter().zip(u.exp) {
            if e != 0 {
                let _ = write!(attrs, " {name}=\"{e}\"");
            }
        }
        if u.factor != 1.0 {
            let _ = write!(attrs, " factor=\"{}\"", xml_double(u.factor));
        }
        if u.offset != 0.0 {
            let _ = write!(attrs, " offset=\"{}\"", xml_double(u.offset));
        }
        let _ = writeln!(
            o,
            "    <Unit name=\"{}\">\n      <BaseUnit{attrs}/>\n    </Unit>",
            xml_escape(u.name)
        );
    }
    let _ = writeln!(o, "  </UnitDefinitions>");
    let _ = writeln!(o, "  <LogCategories>");
    for (n, d) in LOG_CATEGORIES {
        let _ = writeln!(
            o,
            "    <Category name=\"{n}\" description=\"{}\"/>",
            xml_escape(d)
        );
    }
    let _ = writeln!(o, "  </LogCategories>");
    let (t0, t1, h) = DEFAULT_EXPERIMENT;
    let _ = writeln!(
        o,
        "  <DefaultExperiment startTime=\"{}\" stopTime=\"{}\" stepSize=\"{}\"/>",
        xml_double(t0),
        xml_double(t1),
        xml_double(h)
    );
}

fn body(table: &[Var]) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
    let _ = writeln!(o, "<!-- Generated by ecf-fmu from the variable table in fmu-crate/src/vars.rs; do not edit. -->");
    let _ = writeln!(
        o,
        "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"{MODEL_IDENTIFIER}\" guid=\"{GUID_PLACEHOLDER}\" description=\"Extended Creep Force (ECF) wheel-rail contact: transient bristle model with elasto-plastic third body layer and flash temperature; also FASTSIM and Polach\" author=\"ECF project\" version=\"{}\" license=\"Apache-2.0\" generationTool=\"ecf-fmu {}\" variableNamingConvention=\"flat\" numberOfEventIndicators=\"0\">",
        env!("CARGO_PKG_VERSION"),
        env!("CARGO_PKG_VERSION")
    );
    let _ = writeln!(
        o,
        "  <CoSimulation modelIdentifier=\"{MODEL_IDENTIFIER}\" needsExecutionTool=\"false\" canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"false\" maxOutputDerivativeOrder=\"0\" canRunAsynchronuously=\"false\" canBeInstantiatedOnlyOncePerProcess=\"false\" canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"true\" canSerializeFMUstate=\"true\" providesDirectionalDerivative=\"false\"/>"
    );
    common_elements(&mut o);
    let _ = writeln!(o, "  <ModelVariables>");
    for (i, v) in table.iter().enumerate() {
        scalar_variable(&mut o, i + 1, v);
    }
    let _ = writeln!(o, "  </ModelVariables>");
    let _ = writeln!(o, "  <ModelStructure>");
    let outputs: Vec<usize> = table
        .iter()
        .enumerate()
        .filter(|(_, v)| v.causality == Causality::Output)
        .map(|(i, _)| i + 1)
        .collect();
    for section in ["Outputs", "InitialUnknowns"] {
        let _ = writeln!(o, "    <{section}>");
        for i in &outputs {
            // at a communication point the outputs are those of the completed step: they
            // depend on no input set since (dependencies=""); in initialization mode they
            // are the steady state of the inputs (no dependencies attribute: all of them)
            let deps = if section == "Outputs" {
                " dependencies=\"\""
            } else {
                ""
            };
            let _ = writeln!(o, "      <Unknown index=\"{i}\"{deps}/>");
        }
        let _ = writeln!(o, "    </{section}>");
    }
    let _ = writeln!(o, "  </ModelStructure>");
    let _ = writeln!(o, "</fmiModelDescription>");
    o
}

/// The GUID of this build's variable table: a hash of the model description without it.
pub fn guid() -> String {
    guid_of(&body(&vars::table()))
}

fn guid_of(body: &str) -> String {
    let h1 = fnv1a(body.as_bytes());
    let h2 = fnv1a(format!("ecf_contact/{h1:016x}/{body}").as_bytes());
    format!(
        "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
        h1 >> 32,
        (h1 >> 16) & 0xffff,
        h1 & 0xffff,
        h2 >> 48,
        h2 & 0xffff_ffff_ffff
    )
}

/// The complete modelDescription.xml of this build.
pub fn xml() -> String {
    let b = body(&vars::table());
    let g = guid_of(&b);
    b.replacen(GUID_PLACEHOLDER, &g, 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_and_doubles() {
        assert_eq!(xml_escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
        assert_eq!(xml_double(f64::INFINITY), "INF");
        assert_eq!(xml_double(0.001), "0.001");
        assert_eq!(xml_double(110000.0), "110000.0");
        let x = 0.1 + 0.2;
        assert_eq!(xml_double(x).parse::<f64>().ok(), Some(x));
    }

    #[test]
    fn guid_changes_with_the_table() {
        let t = vars::table();
        let g1 = guid_of(&body(&t));
        let mut t2 = t.clone();
        t2[0].description.push('!');
        assert_ne!(g1, guid_of(&body(&t2)));
        assert_eq!(g1, guid());
        assert!(xml().contains(&g1));
    }
}
