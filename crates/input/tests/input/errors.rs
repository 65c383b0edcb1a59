//! Each kind of error in a TOML scene, at the line and column of its key or value.

use contopt_input::Node;

use crate::scene::{edit, read_toml, refusal, sample, SAMPLE_TOML};

/// `line:column path: message` of the error reading the sample with one edit.
fn refused(from: &str, to: &str) -> String {
    let text = edit(SAMPLE_TOML, from, to);
    refusal(&text, read_toml(&text))
}

#[test]
fn the_sample_reads() {
    assert_eq!(read_toml(SAMPLE_TOML).unwrap(), sample());
}

#[test]
fn a_value_of_the_wrong_type_points_at_the_value() {
    assert_eq!(
        refused("force_n = 1000", "force_n = \"1 kN\""),
        "4:11 contact.load.force_n: invalid type: string \"1 kN\", expected f64"
    );
    assert_eq!(
        refused("name = \"ball\"", "name = 5"),
        "15:8 body[0].name: invalid type: integer `5`, expected a string"
    );
}

#[test]
fn a_float_into_an_integer_is_refused_and_an_integer_into_a_float_read() {
    let max = "method = \"active_set\"\nmax_iterations";
    assert_eq!(
        refused("method = \"active_set\"", &format!("{max} = 1.5")),
        "13:18 solver.max_iterations: invalid type: floating point `1.5`, expected u32"
    );
    assert_eq!(
        refused("method = \"active_set\"", &format!("{max} = -3")),
        "13:18 solver.max_iterations: invalid value: integer `-3`, expected u32"
    );
    let text = edit(
        SAMPLE_TOML,
        "method = \"active_set\"",
        &format!("{max} = 40"),
    );
    assert_eq!(read_toml(&text).unwrap().solver.max_iterations, Some(40));
}

#[test]
fn nan_and_infinities_reach_the_type() {
    let text = edit(SAMPLE_TOML, "force_n = 1000", "force_n = nan");
    let text = edit(&text, "angle_deg = 0.0", "angle_deg = -inf");
    let load = read_toml(&text).unwrap().contact.load;
    assert!(load.force_n.is_nan());
    assert_eq!(load.angle_deg, f64::NEG_INFINITY);
}

#[test]
fn a_validated_table_points_at_the_key_its_message_names() {
    assert_eq!(
        refused("nu = 0.3", "nu = 0.5"),
        "17:35 body[0].material.nu: invalid nu = 0.5: Poisson's ratio is above -1 and below 0.5"
    );
    assert_eq!(
        refused("e_mpa = 70000", "e_mpa = -1"),
        "22:22 body[1].material.e_mpa: e_mpa: must be positive, got -1"
    );
}

#[test]
fn a_validation_naming_no_key_points_at_the_table() {
    assert_eq!(
        refused("e_mpa = 210000, nu = 0.3", "e_mpa = 2e8, nu = 0.45"),
        "17:12 body[0].material: a stiff rubber is not a material we know"
    );
}

#[test]
fn an_unknown_field_points_at_its_key_and_lists_the_expected() {
    assert_eq!(
        refused("angle_deg", "angel_deg"),
        "5:1 contact.load.angel_deg: unknown field `angel_deg`, expected `force_n` or `angle_deg`"
    );
}

#[test]
fn a_missing_field_points_at_the_table_that_lacks_it() {
    assert_eq!(
        refused("force_n = 1000\n", ""),
        "3:1 contact.load.force_n: missing field `force_n`"
    );
    assert_eq!(
        refused("name = \"hertz\"\n", ""),
        "1:1 name: missing field `name`"
    );
}

#[test]
fn a_struct_is_not_read_from_an_array() {
    assert_eq!(
        refused("{ e_mpa = 210000, nu = 0.3 }", "[210000, 0.3]"),
        "17:12 body[0].material: invalid type: sequence, expected struct RawMaterial"
    );
}

#[test]
fn a_syntax_error_has_its_place() {
    let text = edit(SAMPLE_TOML, "force_n = 1000", "force_n = = 1000");
    let error = Node::parse_toml(&text).unwrap_err();
    assert_eq!(error.path, "");
    assert_eq!(error.line_column(&text), Some((4, 11)), "{error}");
}

#[test]
fn a_part_of_a_document_reads_with_its_full_path() {
    let text = edit(SAMPLE_TOML, "nu = 0.33", "nu = 0.7");
    let node = Node::parse_toml(&text).unwrap();
    let error = node
        .deserialize_at::<crate::scene::Material>("body.1.material")
        .unwrap_err();
    assert_eq!(error.path, "body[1].material.nu");
    assert_eq!(error.line_column(&text), Some((22, 34)));
    let error = node.deserialize_at::<f64>("body.2.material").unwrap_err();
    assert_eq!(error.to_string(), "body[2]: no element 2: the array has 2");
}
