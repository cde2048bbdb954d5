//! The value references of every released variable stay what they were: a saved model in an importer refers to its variables by value reference, so a changed one breaks it.

use ecf_contact::vars;

/// Every variable of modelDescription.xml as released (main at e5dece1): name and value
/// reference. A new variable may be added with a new value reference; none of these may
/// change or disappear.
const RELEASED: &[(&str, u32)] = &[
    ("cx", 1),
    ("cy", 2),
    ("spin", 3),
    ("v", 4),
    ("FN", 5),
    ("T_bulk", 6),
    ("aux1", 90),
    ("aux2", 91),
    ("aux3", 92),
    ("aux4", 93),
    ("Fx", 10),
    ("Fy", 11),
    ("Mz", 12),
    ("f", 13),
    ("T_max", 14),
    ("T_mean", 15),
    ("P_fric", 16),
    ("frac_elastic", 17),
    ("frac_plastic", 18),
    ("frac_sliding", 19),
    ("a", 20),
    ("b", 21),
    ("p0", 22),
    ("a_ref", 30),
    ("b_ref", 31),
    ("FN_ref", 32),
    ("Rx", 33),
    ("Ry", 34),
    ("geometry", 40),
    ("nx", 41),
    ("ny", 42),
    ("threads", 43),
    ("scheme", 44),
    ("effect_coulomb", 50),
    ("effect_layer_elasticity", 51),
    ("effect_voce_plasticity", 52),
    ("effect_pressure_dependence", 53),
    ("effect_temperature", 54),
    ("effect_transient", 55),
    ("effect_elastic_unloading", 56),
    ("effect_surface_time_flash", 57),
    ("model", 60),
    ("preset", 61),
    ("config_file", 62),
    ("columns", 63),
    ("mu", 100),
    ("G_GPa", 101),
    ("nu", 102),
    ("L_e_0_um_per_GPa", 103),
    ("L_e_p_per_GPa", 104),
    ("L_e_T_per_C", 105),
    ("L_p_0_mm", 106),
    ("L_p_p_per_GPa", 107),
    ("L_p_T_per_C", 108),
    ("tau_c1_0_GPa", 109),
    ("tau_c1_p_per_GPa", 110),
    ("tau_c1_T_per_C", 111),
    ("tau_c2_0_GPa", 112),
    ("tau_c2_p_per_GPa", 113),
    ("tau_c2_T_per_C", 114),
    ("T0_C", 115),
    ("lambda_w_W_per_mK", 116),
    ("kappa_w_mm2_per_s", 117),
    ("lambda_r_W_per_mK", 118),
    ("kappa_r_mm2_per_s", 119),
    ("k_q", 120),
    ("polach_mu0", 121),
    ("polach_A", 122),
    ("polach_B_s_per_m", 123),
    ("polach_kA", 124),
    ("polach_kS", 125),
];

#[test]
fn released_value_references_never_change() {
    let table = vars::table();
    for &(name, vr) in RELEASED {
        let v = table
            .iter()
            .find(|v| v.name == name)
            .unwrap_or_else(|| panic!("released variable {name} is gone"));
        assert_eq!(v.vr, vr, "the value reference of {name} changed");
    }
    // the checked-in XML says the same
    let xml = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../modelDescription/modelDescription.xml"),
    )
    .expect("modelDescription.xml");
    for &(name, vr) in RELEASED {
        let head = format!("<ScalarVariable name=\"{name}\" valueReference=\"{vr}\"");
        assert!(
            xml.contains(&head),
            "{name}: value reference {vr} not in the XML"
        );
    }
}
