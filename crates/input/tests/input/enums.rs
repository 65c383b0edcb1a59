//! The three spellings of an enum's variant, and where their errors point.

use contopt_input::Node;
use serde::de::DeserializeOwned;

use crate::scene::{place, Law, Plane, Stiffness};

/// The value at `key` of a one-line TOML document.
fn read<T: DeserializeOwned>(text: &str, key: &str) -> T {
    let node = Node::parse_toml(text).unwrap();
    node.deserialize_at(key)
        .unwrap_or_else(|error| panic!("{}", place(text, &error)))
}

/// `line:column path: message` of the error reading `key` of a one-line TOML document.
fn refused<T: DeserializeOwned + std::fmt::Debug>(text: &str, key: &str) -> String {
    let node = Node::parse_toml(text).unwrap();
    let error = node.deserialize_at::<T>(key).unwrap_err();
    place(text, &error)
}

#[test]
fn a_unit_variant_reads_from_a_string_an_only_key_or_a_kind() {
    for text in [
        "plane = \"plane_strain\"",
        "plane = { plane_strain = {} }",
        "plane = { kind = \"plane_strain\" }",
    ] {
        assert_eq!(read::<Plane>(text, "plane"), Plane::PlaneStrain, "{text}");
    }
}

#[test]
fn a_struct_variant_reads_from_an_only_key_or_a_kind() {
    for text in [
        "plane = { plane_stress = { thickness_mm = 10.0 } }",
        "plane = { kind = \"plane_stress\", thickness_mm = 10 }",
        "[plane]\nkind = \"plane_stress\"\nthickness_mm = 10.0",
        "[plane.plane_stress]\nthickness_mm = 10.0",
    ] {
        let plane = read::<Plane>(text, "plane");
        assert_eq!(plane, Plane::PlaneStress { thickness_mm: 10.0 }, "{text}");
    }
}

#[test]
fn a_newtype_variant_reads_from_an_only_key_or_a_kind() {
    for text in [
        "law = { linear = { k = 5.0 } }",
        "law = { kind = \"linear\", k = 5.0 }",
    ] {
        assert_eq!(read::<Law>(text, "law"), Law::Linear(Stiffness { k: 5.0 }));
    }
}

#[test]
fn a_unit_variant_refuses_content_naming_the_key() {
    assert_eq!(
        refused::<Plane>(
            "plane = { kind = \"plane_strain\", thickness_mm = 1.0 }",
            "plane"
        ),
        "1:34 plane.thickness_mm: the unit variant `plane_strain` takes no content, \
         found the key `thickness_mm`"
    );
    assert_eq!(
        refused::<Plane>("plane = { plane_strain = 3 }", "plane"),
        "1:26 plane.plane_strain: the unit variant `plane_strain` takes no content, \
         found integer `3`"
    );
}

#[test]
fn an_unknown_variant_points_at_its_name_and_lists_the_allowed() {
    let allowed = "expected `plane_strain` or `plane_stress`";
    assert_eq!(
        refused::<Plane>("plane = \"flat\"", "plane"),
        format!("1:9 plane: unknown variant `flat`, {allowed}")
    );
    assert_eq!(
        refused::<Plane>("plane = { flat = {} }", "plane"),
        format!("1:11 plane.flat: unknown variant `flat`, {allowed}")
    );
    assert_eq!(
        refused::<Plane>(
            "plane = { kind = \"plane_stres\", thickness_mm = 1.0 }",
            "plane"
        ),
        format!("1:18 plane.kind: unknown variant `plane_stres`, {allowed}")
    );
}

#[test]
fn errors_in_a_variants_content_point_into_it() {
    assert_eq!(
        refused::<Law>("law = { kind = \"penalty\" }", "law"),
        "1:7 law.c_mpa_per_mm: missing field `c_mpa_per_mm`"
    );
    assert_eq!(
        refused::<Plane>("plane = \"plane_stress\"", "plane"),
        "1:9 plane.thickness_mm: missing field `thickness_mm`"
    );
    assert_eq!(
        refused::<Law>(
            "law = { kind = \"penalty\", c_mpa_per_mm = \"stiff\" }",
            "law"
        ),
        "1:42 law.c_mpa_per_mm: invalid type: string \"stiff\", expected f64"
    );
    assert_eq!(
        refused::<Law>("law = { kind = \"penalty\", c = 1 }", "law"),
        "1:27 law.c: unknown field `c`, expected `c_mpa_per_mm`"
    );
    assert_eq!(
        refused::<Law>("law = { linear = { k = true } }", "law"),
        "1:24 law.linear.k: invalid type: boolean `true`, expected f64"
    );
}

#[test]
fn a_table_naming_no_variant_is_refused() {
    assert_eq!(
        refused::<Plane>("plane = { a = 1, b = 2 }", "plane"),
        "1:9 plane: expected the name of a variant (one of `plane_strain`, `plane_stress`) \
         as a string, as the only key of a table, or as the value of a `kind` key"
    );
    assert_eq!(
        refused::<Plane>("plane = { kind = 1, b = 2 }", "plane"),
        "1:18 plane.kind: invalid type: integer `1`, expected the name of a variant"
    );
    assert_eq!(
        refused::<Plane>("plane = 3", "plane"),
        "1:9 plane: invalid type: integer `3`, expected a variant name"
    );
    // A newtype variant named alone reads its value from an empty table, which names the
    // field it misses.
    assert_eq!(
        refused::<Law>("law = \"linear\"", "law"),
        "1:7 law: missing field `k`"
    );
}

/// What the crate documentation warns of: serde buffers an internally tagged enum's content,
/// and errors inside it can only point at the enclosing table.
#[test]
fn an_internally_tagged_enum_loses_the_inner_position() {
    #[derive(serde::Deserialize, Debug)]
    #[serde(tag = "kind", rename_all = "snake_case")]
    enum Tagged {
        Penalty {
            #[serde(rename = "c_mpa_per_mm")]
            _c_mpa_per_mm: f64,
        },
    }
    assert_eq!(
        refused::<Tagged>(
            "law = { kind = \"penalty\", c_mpa_per_mm = \"stiff\" }",
            "law"
        ),
        "1:7 law: invalid type: string \"stiff\", expected f64"
    );
}
