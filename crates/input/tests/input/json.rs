//! The sample in JSON: the same values, and errors at the same paths with JSON's own lines and
//! columns.

use contopt_input::Node;

use crate::scene::{edit, read_json, read_toml, refusal, sample, SAMPLE_JSON, SAMPLE_TOML};

/// `line:column path: message` of the error reading the JSON sample with one edit.
fn refused(from: &str, to: &str) -> String {
    let text = edit(SAMPLE_JSON, from, to);
    refusal(&text, read_json(&text))
}

#[test]
fn the_sample_reads_as_in_toml() {
    assert_eq!(read_json(SAMPLE_JSON).unwrap(), sample());
    let json = Node::parse_json(SAMPLE_JSON).unwrap();
    let toml = Node::parse_toml(SAMPLE_TOML).unwrap();
    assert_eq!(json, toml);
}

#[test]
fn errors_point_at_json_lines_and_columns() {
    assert_eq!(
        refused("\"force_n\": 1000", "\"force_n\": \"1 kN\""),
        "4:26 contact.load.force_n: invalid type: string \"1 kN\", expected f64"
    );
    assert_eq!(
        refused("\"nu\": 0.3", "\"nu\": 0.5"),
        "12:44 body[0].material.nu: invalid nu = 0.5: Poisson's ratio is above -1 and below 0.5"
    );
    assert_eq!(
        refused("\"angle_deg\"", "\"angel_deg\""),
        "4:32 contact.load.angel_deg: unknown field `angel_deg`, expected `force_n` or `angle_deg`"
    );
    assert_eq!(
        refused("\"force_n\": 1000, ", ""),
        "4:13 contact.load.force_n: missing field `force_n`"
    );
    assert_eq!(
        refused("\"active_set\"", "\"active_sets\""),
        "7:25 solver.method: unknown variant `active_sets`, expected `active_set` or `lemke`"
    );
    assert_eq!(
        refused("\"force_n\": 1000", "\"force_n\": null"),
        "4:26 contact.load.force_n: invalid type: null, expected f64"
    );
}

#[test]
fn the_same_errors_have_the_same_paths_and_messages_in_both_formats() {
    let edits = [
        (
            ("force_n = 1000", "force_n = true"),
            ("\"force_n\": 1000", "\"force_n\": true"),
        ),
        (("nu = 0.33", "nu = -2"), ("\"nu\": 0.33", "\"nu\": -2")),
        (
            ("kind = \"penalty\"", "kind = \"rigid\""),
            ("\"kind\": \"penalty\"", "\"kind\": \"rigid\""),
        ),
        (
            ("plane_stress", "plane_stres"),
            ("\"plane_stress\"", "\"plane_stres\""),
        ),
        (
            ("thickness_mm", "thickness"),
            ("\"thickness_mm\"", "\"thickness\""),
        ),
    ];
    for ((toml_from, toml_to), (json_from, json_to)) in edits {
        let toml = read_toml(&edit(SAMPLE_TOML, toml_from, toml_to)).unwrap_err();
        let json = read_json(&edit(SAMPLE_JSON, json_from, json_to)).unwrap_err();
        assert_eq!(toml.to_string(), json.to_string());
    }
}

#[test]
fn null_reads_as_none() {
    let text = edit(
        SAMPLE_JSON,
        "\"method\": \"active_set\"",
        "\"method\": \"lemke\", \"max_iterations\": null",
    );
    assert_eq!(read_json(&text).unwrap().solver.max_iterations, None);
}
