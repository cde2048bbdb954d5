//! The checked-in modelDescription/modelDescription.xml equals the one generated from the variable table, and fmi-schema reads it back with the same variables.
//!
//! Regenerate after changing the table: `ECF_FMU_WRITE_MD=1 cargo test -p ecf-fmu --test model_description`.

use ecf_contact::model_description::{self, MODEL_IDENTIFIER};
use ecf_contact::vars::{self, Causality, Kind, Start};
use fmi_schema::fmi2::{self, Fmi2ModelDescription, ScalarVariableElement};
use std::path::PathBuf;
use std::str::FromStr;

fn path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../modelDescription/modelDescription.xml")
}

#[test]
fn checked_in_xml_is_current() {
    let want = model_description::xml();
    if std::env::var("ECF_FMU_WRITE_MD").as_deref() == Ok("1") {
        std::fs::write(path(), &want).expect("write modelDescription.xml");
    }
    let have = std::fs::read_to_string(path()).unwrap_or_default();
    assert!(
        have == want,
        "modelDescription/modelDescription.xml differs from the variable table; regenerate with ECF_FMU_WRITE_MD=1 cargo test -p ecf-fmu --test model_description"
    );
}

#[test]
fn fmi_schema_round_trip() {
    let xml = model_description::xml();
    let md = Fmi2ModelDescription::from_str(&xml).expect("fmi-schema parses the XML");
    assert_eq!(md.fmi_version, "2.0");
    assert_eq!(md.guid, model_description::guid());
    let cs = md.co_simulation.as_ref().expect("CoSimulation element");
    assert_eq!(cs.model_identifier, MODEL_IDENTIFIER);
    assert_eq!(cs.can_handle_variable_communication_step_size, Some(true));
    assert_eq!(cs.can_get_and_set_fmu_state, Some(true));
    assert_eq!(cs.can_serialize_fmu_state, Some(true));
    assert_eq!(cs.can_be_instantiated_only_once_per_process, Some(false));
    assert_eq!(cs.provides_directional_derivative, Some(false));
    let table = vars::table();
    let svs = &md.model_variables.variables;
    assert_eq!(svs.len(), table.len());
    for (sv, v) in svs.iter().zip(table.iter()) {
        assert_eq!(sv.name, v.name);
        assert_eq!(sv.value_reference, v.vr, "{}", v.name);
        assert_eq!(
            sv.description.as_deref(),
            Some(v.description.as_str()),
            "{}",
            v.name
        );
        let (c, var) = match v.causality {
            Causality::Input => (fmi2::Causality::Input, fmi2::Variability::Continuous),
            Causality::Output => (fmi2::Causality::Output, fmi2::Variability::Continuous),
            Causality::Parameter => (fmi2::Causality::Parameter, fmi2::Variability::Fixed),
        };
        assert_eq!(sv.causality, c, "{}", v.name);
        assert_eq!(sv.variability, Some(var), "{}", v.name);
        match (&sv.elem, v.kind) {
            (ScalarVariableElement::Real(r), Kind::Real) => match &v.start {
                Start::Real(x) => assert_eq!(r.start, Some(*x), "{}", v.name),
                _ => assert_eq!(r.start, None, "{}", v.name),
            },
            (ScalarVariableElement::Integer(i), Kind::Integer) => match &v.start {
                Start::Integer(x) => assert_eq!(i.start, Some(*x), "{}", v.name),
                s => panic!("{}: start {s:?}", v.name),
            },
            (ScalarVariableElement::Boolean(b), Kind::Boolean) => match &v.start {
                Start::Boolean(x) => assert_eq!(b.start, Some(*x), "{}", v.name),
                s => panic!("{}: start {s:?}", v.name),
            },
            // fmi-schema 0.8 keeps no attributes of String variables (nor units of Real ones:
            // those are checked on the XML text below)
            (ScalarVariableElement::String, Kind::String) => {}
            (e, k) => panic!("{}: element {e:?} for kind {k:?}", v.name),
        }
    }
    let outputs: Vec<u32> = md
        .model_structure
        .outputs
        .unknowns
        .iter()
        .map(|u| u.index)
        .collect();
    let want: Vec<u32> = table
        .iter()
        .enumerate()
        .filter(|(_, v)| v.causality == Causality::Output)
        .map(|(i, _)| i as u32 + 1)
        .collect();
    assert_eq!(outputs, want);
    let initial: Vec<u32> = md
        .model_structure
        .initial_unknowns
        .unknowns
        .iter()
        .map(|u| u.index)
        .collect();
    assert_eq!(initial, want);
    assert!(md.model_structure.derivatives.unknowns.is_empty());
    let units = md.unit_definitions.as_ref().expect("UnitDefinitions");
    for u in vars::UNITS {
        let d = units
            .units
            .iter()
            .find(|d| d.name == u.name)
            .unwrap_or_else(|| panic!("unit {} missing", u.name));
        let b = d.base_unit.as_ref().expect("BaseUnit");
        let e = |x: Option<i32>| x.unwrap_or(0);
        assert_eq!([e(b.kg), e(b.m), e(b.s), e(b.k)], u.exp, "{}", u.name);
        assert_eq!(b.factor.unwrap_or(1.0), u.factor, "{}", u.name);
        assert_eq!(b.offset.unwrap_or(0.0), u.offset, "{}", u.name);
    }
    // units and string starts, which fmi-schema does not keep, on the text itself
    for v in &table {
        let head = format!("<ScalarVariable name=\"{}\"", v.name);
        let at = xml
            .find(&head)
            .unwrap_or_else(|| panic!("{} not in the XML", v.name));
        let elem = &xml[at..at + xml[at..].find("</ScalarVariable>").expect("closed")];
        assert_eq!(elem.contains(" unit=\""), v.unit.is_some(), "{}", v.name);
        if let Some(u) = v.unit {
            assert!(
                elem.contains(&format!(" unit=\"{u}\"")),
                "{}: {elem}",
                v.name
            );
        }
        if let Start::String(s) = &v.start {
            assert!(
                elem.contains(&format!("<String start=\"{s}\"/>")),
                "{}: {elem}",
                v.name
            );
        }
    }
}
