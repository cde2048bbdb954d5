//! The checked-in modelDescription/fmi3/modelDescription.xml equals the one generated from the variable table, fmi-schema reads it back with every variable of the FMI 2.0 description (same names, value references, descriptions, causalities, starts) plus time, n_field and the arrays, and both descriptions declare that no output depends on an input.
//!
//! Regenerate after changing the table: `ECF_FMU_WRITE_MD=1 cargo test -p ecf-fmu --test model_description3`.

mod common;
use common::for_fmi_schema;
use ecf_contact::arrays::{ARRAYS, VR_N_FIELD, VR_TIME};
use ecf_contact::model_description::MODEL_IDENTIFIER;
use ecf_contact::model_description3::{self, type_name};
use ecf_contact::vars::{self, Causality, Start};
use fmi_schema::fmi3::{
    AbstractVariableTrait, ArrayableVariableTrait, Fmi3ModelDescription,
    InitializableVariableTrait, Variable, VariableDependency,
};
use fmi_schema::traits::FmiModelDescription;
use std::path::PathBuf;

fn path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../modelDescription/fmi3/modelDescription.xml")
}

#[test]
fn checked_in_xml_is_current() {
    let want = model_description3::xml();
    if std::env::var("ECF_FMU_WRITE_MD").as_deref() == Ok("1") {
        let _ = std::fs::create_dir_all(path().parent().expect("folder"));
        std::fs::write(path(), &want).expect("write modelDescription.xml");
    }
    let have = std::fs::read_to_string(path()).unwrap_or_default();
    assert!(
        have == want,
        "modelDescription/fmi3/modelDescription.xml differs from the variable table; regenerate with ECF_FMU_WRITE_MD=1 cargo test -p ecf-fmu --test model_description3"
    );
}

fn type_of(v: &Variable) -> &'static str {
    match v {
        Variable::Float64(_) => "Float64",
        Variable::Int32(_) => "Int32",
        Variable::Boolean(_) => "Boolean",
        Variable::String(_) => "String",
        Variable::UInt64(_) => "UInt64",
        _ => "other",
    }
}

fn abs(v: &Variable) -> &dyn AbstractVariableTrait {
    match v {
        Variable::Float64(x) => x,
        Variable::Int32(x) => x,
        Variable::Boolean(x) => x,
        Variable::String(x) => x,
        Variable::UInt64(x) => x,
        Variable::Int8(x) => x,
        Variable::UInt8(x) => x,
        Variable::Int16(x) => x,
        Variable::UInt16(x) => x,
        Variable::UInt32(x) => x,
        Variable::Int64(x) => x,
        Variable::Float32(x) => x,
        Variable::Binary(x) => x,
        Variable::Clock(x) => x,
    }
}

#[test]
fn fmi_schema_reads_every_variable_of_the_fmi2_description() {
    let xml = model_description3::xml();
    let md = Fmi3ModelDescription::deserialize(&for_fmi_schema(&xml))
        .expect("fmi-schema parses the XML");
    assert_eq!(md.fmi_version, "3.0");
    assert_eq!(
        md.instantiation_token,
        model_description3::instantiation_token()
    );
    assert!(md.model_exchange.is_none() && md.scheduled_execution.is_none());
    let cs = md.co_simulation.as_ref().expect("CoSimulation element");
    assert_eq!(cs.model_identifier, MODEL_IDENTIFIER);
    assert_eq!(cs.can_get_and_set_fmu_state, Some(true));
    assert_eq!(cs.can_serialize_fmu_state, Some(true));
    assert_eq!(cs.has_event_mode, Some(false));
    assert_eq!(cs.provides_directional_derivatives, Some(false));
    let vs = &md.model_variables.variables;
    let table = vars::table();
    // time, n_field, the arrays, then the table in its order
    assert_eq!(vs.len(), 2 + ARRAYS.len() + table.len());
    assert_eq!(
        (abs(&vs[0]).name(), abs(&vs[0]).value_reference()),
        ("time", VR_TIME)
    );
    assert_eq!((abs(&vs[1]).name(), type_of(&vs[1])), ("n_field", "UInt64"));
    for (v, a) in vs[2..].iter().zip(ARRAYS.iter()) {
        let x = abs(v);
        assert_eq!(
            (x.name(), x.value_reference(), type_of(v)),
            (a.name, a.vr, type_name(a.kind))
        );
        let dims = match v {
            Variable::Float64(f) => f.dimensions(),
            Variable::Int32(i) => i.dimensions(),
            _ => panic!("{}: {v:?}", a.name),
        };
        let dims: Vec<Option<u32>> = dims.iter().map(|d| d.as_variable()).collect();
        assert_eq!(dims, vec![Some(VR_N_FIELD)], "{}", a.name);
    }
    for (v, t) in vs[2 + ARRAYS.len()..].iter().zip(table.iter()) {
        let x = abs(v);
        assert_eq!(x.name(), t.name);
        assert_eq!(x.value_reference(), t.vr, "{}", t.name);
        assert_eq!(x.description(), Some(t.description.as_str()), "{}", t.name);
        assert_eq!(type_of(v), type_name(t.kind), "{}", t.name);
        let head = format!("<{} name=\"{}\"", type_name(t.kind), t.name);
        let line = xml
            .lines()
            .find(|l| l.trim_start().starts_with(&head))
            .expect("in the XML");
        let unit = t.unit.map(|u| format!(" unit=\"{u}\""));
        assert_eq!(line.contains(" unit=\""), unit.is_some(), "{line}");
        assert!(unit.is_none_or(|u| line.contains(&u)), "{line}");
        let c = format!("{:?}", x.causality()).to_lowercase();
        let want = match t.causality {
            Causality::Input => "input",
            Causality::Output => "output",
            Causality::Parameter => "parameter",
        };
        assert_eq!(c, want, "{}", t.name);
        match (v, &t.start) {
            (Variable::Float64(f), Start::Real(s)) => {
                assert_eq!(f.start(), Some(&[*s][..]), "{}", t.name)
            }
            (Variable::Float64(f), Start::None) => assert_eq!(f.start(), None, "{}", t.name),
            (Variable::Int32(i), Start::Integer(s)) => {
                assert_eq!(i.start(), Some(&[*s][..]), "{}", t.name)
            }
            (Variable::Boolean(b), Start::Boolean(s)) => {
                assert_eq!(b.start(), Some(&[*s][..]), "{}", t.name)
            }
            (Variable::String(_), Start::String(s)) => {
                let head = format!("<String name=\"{}\"", t.name);
                let at = xml.find(&head).expect("in the XML");
                let elem = &xml[at..at + xml[at..].find("</String>").expect("closed")];
                assert!(elem.contains(&format!("<Start value=\"{s}\"/>")), "{elem}");
            }
            (v, s) => panic!("{}: {v:?} with start {s:?}", t.name),
        }
    }
}

#[test]
fn no_output_depends_on_an_input_at_a_communication_point_in_either_description() {
    let md = Fmi3ModelDescription::deserialize(&for_fmi_schema(&model_description3::xml()))
        .expect("parses");
    let mut outputs: Vec<u32> = vars::table()
        .iter()
        .filter(|v| v.causality == Causality::Output)
        .map(|v| v.vr)
        .chain(ARRAYS.iter().map(|a| a.vr))
        .collect();
    outputs.sort_unstable();
    let mut declared = Vec::new();
    for u in &md.model_structure.unknowns {
        match u {
            VariableDependency::Output(o) => {
                let deps = o.dependencies.as_ref().map(|d| d.0.clone());
                assert_eq!(
                    deps,
                    Some(Vec::new()),
                    "output {}: dependencies=\"\"",
                    o.value_reference
                );
                declared.push(o.value_reference);
            }
            VariableDependency::InitialUnknown(o) => {
                // in initialization mode the outputs are the steady state of the inputs
                assert!(
                    o.dependencies.is_none(),
                    "initial unknown {}",
                    o.value_reference
                );
            }
            other => panic!("unexpected {other:?}"),
        }
    }
    declared.sort_unstable();
    assert_eq!(declared, outputs);
    // FMI 2.0: every <Unknown> of <Outputs> with dependencies="", none of <InitialUnknowns>
    let xml2 = ecf_contact::model_description::xml();
    let section = |name: &str| {
        let a = xml2.find(&format!("<{name}>")).expect("section");
        let b = xml2.find(&format!("</{name}>")).expect("section end");
        xml2[a..b].to_string()
    };
    let outs = section("Outputs");
    assert_eq!(outs.matches("<Unknown ").count(), 13);
    assert_eq!(outs.matches("dependencies=\"\"").count(), 13);
    assert!(!section("InitialUnknowns").contains("dependencies"));
}
