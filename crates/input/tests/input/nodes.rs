//! Finding, replacing and removing values of a tree, and trees made in code.

use contopt_input::{Node, Value};

use crate::scene::{place, Load, Scene, SAMPLE_TOML};

fn sample() -> Node {
    Node::parse_toml(SAMPLE_TOML).unwrap()
}

#[test]
fn get_follows_keys_and_array_indices() {
    let node = sample();
    let nu = node.get("body.1.material.nu").unwrap();
    assert_eq!(nu.value(), &Value::Float(0.33));
    assert_eq!(
        contopt_input::line_column(SAMPLE_TOML, nu.span().unwrap().start),
        (22, 34)
    );
    assert_eq!(node.get("").unwrap(), &node);
    for missing in ["body.2", "body.x", "body.1.material.nu.x", "solver.methods"] {
        assert!(node.get(missing).is_none(), "{missing}");
    }
}

#[test]
fn set_replaces_a_value_and_returns_the_old_one() {
    let mut node = sample();
    let old = node
        .set("contact.load.force_n", Node::from(2000.0))
        .unwrap();
    assert_eq!(old.value(), &Value::Integer(1000));
    assert_eq!(node.get("contact.load.force_n").unwrap().span(), None);
    let scene: Scene = node.deserialize().unwrap();
    assert_eq!(scene.contact.load.force_n, 2000.0);
    node.set("body.0.name", Node::from("sphere")).unwrap();
    assert_eq!(node.deserialize::<Scene>().unwrap().body[0].name, "sphere");
}

#[test]
fn a_set_value_keeps_its_own_span() {
    let other = "force_n = \"much\"";
    let replacement = Node::parse_toml(other)
        .unwrap()
        .get("force_n")
        .unwrap()
        .clone();
    let mut node = sample();
    node.set("contact.load.force_n", replacement).unwrap();
    let error = node.deserialize::<Scene>().unwrap_err();
    assert_eq!(
        place(other, &error),
        "1:11 contact.load.force_n: invalid type: string \"much\", expected f64"
    );
}

#[test]
fn set_refuses_a_missing_path_naming_the_segment() {
    let mut node = sample();
    let refused = |node: &mut Node, path: &str| {
        let error = node.set(path, Node::from(1)).unwrap_err();
        place(SAMPLE_TOML, &error)
    };
    assert_eq!(
        refused(&mut node, "contact.load.forse_n"),
        "3:1 contact.load.forse_n: no key `forse_n` in this table"
    );
    assert_eq!(
        refused(&mut node, "body.2.name"),
        "14:1 body[2]: no element 2: the array has 2"
    );
    assert_eq!(
        refused(&mut node, "body.first"),
        "14:1 body.first: `first` is not an index into an array"
    );
    assert_eq!(
        refused(&mut node, "name.first"),
        "1:8 name.first: no `first` in this string"
    );
    assert_eq!(node, sample());
}

#[test]
fn remove_takes_a_top_level_key() {
    let mut node = sample();
    assert!(node.remove("solver").is_some());
    assert!(node.remove("solver").is_none());
    assert!(node.remove("force_n").is_none());
    let error = node.deserialize::<Scene>().unwrap_err();
    assert_eq!(
        place(SAMPLE_TOML, &error),
        "1:1 solver: missing field `solver`"
    );
    let mut leaf = Node::from(1.0);
    assert!(leaf.remove("x").is_none());
}

#[test]
fn a_tree_made_in_code_reads_and_its_errors_have_no_place() {
    let load = Node::table([("force_n", Node::from(5)), ("angle_deg", Node::from(1.5))]);
    let read: Load = load.deserialize().unwrap();
    assert_eq!((read.force_n, read.angle_deg), (5.0, 1.5));
    let error = Node::table([("force_n", Node::from("x"))])
        .deserialize::<Load>()
        .unwrap_err();
    assert_eq!(error.path, "force_n");
    assert_eq!(error.line_column(SAMPLE_TOML), None);
    let items = Node::from(vec![Node::from(true), Node::from(Value::Null)]);
    assert_eq!(
        items.deserialize::<Vec<Option<bool>>>().unwrap(),
        [Some(true), None]
    );
}

#[test]
fn a_tuple_takes_exactly_its_elements() {
    let node = Node::parse_toml("pair = [1, 2, 3]").unwrap();
    let error = node.deserialize_at::<(i64, i64)>("pair").unwrap_err();
    assert_eq!(
        error.to_string(),
        "pair: invalid length 3, expected 2 elements"
    );
    assert_eq!(node.deserialize_at::<[i64; 3]>("pair").unwrap(), [1, 2, 3]);
}
