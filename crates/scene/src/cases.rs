//! A scene's cases: one per value of its `[sweep]`, one per `[[case]]`, or the scene itself.
//! Each case is the scene's tree with its values put in, keeping the place each value was
//! written (a swept value's errors point at the sweep's line).

use std::collections::BTreeMap;

use contopt_input::{Node, Value};
use contopt_results::words;

use crate::error::Locator;
use crate::{SceneError, MAX_CASES};

/// 2⁵³: below it an f64 holds every whole number exactly, so a swept float becomes an integer
/// key's value without loss.
const MAX_EXACT_INTEGER: f64 = 9_007_199_254_740_992.0;

/// A case before it is read: its label, the numbers it changed, its tree.
pub(crate) struct CaseInput {
    pub label: String,
    /// Whether the scene named it (`[[case]]`, or a sweep's value): a scene of one unnamed
    /// case takes the scene's name as its label.
    pub named: Option<()>,
    pub params: BTreeMap<String, f64>,
    pub tree: Node,
    /// What a `[[case]]` did to the scene's tables ([`put`]), for its errors to say.
    pub tables: Tables,
}

/// The keys of the scene as a whole, which no case sets.
const SCENE_KEYS: [&str; 2] = ["name", "description"];

/// The tables of the scene a `[[case]]` set: merged key by key, or replaced whole.
#[derive(Default)]
pub(crate) struct Tables {
    /// Set to a table of another `kind` than the scene's: the table replaces the scene's
    /// whole, the keys it leaves out gone with it.
    whole: Vec<String>,
    /// Set to a table of the same kind (or of none): its keys merged into the scene's.
    merged: Vec<String>,
}

/// `e`, a reading error of a case's tree, with a word on what the case did to the table it
/// is in: a table of another `kind` replaced the scene's (`set = { contact = { zone = { kind =
/// "rings" } } }` drops the grid's sizes), or the case's keys were merged into the scene's (a
/// choice written under its name, `load = { approach_mm = … }` over `{ force_n = … }`, is then
/// two choices).
pub(crate) fn explain(tables: &Tables, mut e: SceneError) -> SceneError {
    if let SceneError::Invalid(located) = &mut e {
        let path = crate::error::dotted(&located.path);
        let under = |key: &&String| path == **key || path.starts_with(&format!("{key}."));
        if let Some(key) = tables.whole.iter().find(under) {
            located.message.push_str(&format!(
                " (the case sets `{key}` to a table of another `kind`, which replaces the \
                 scene's whole: the scene's keys under it do not carry over to another kind, \
                 so give the new kind's keys in the case)"
            ));
        } else if let Some(key) = tables.merged.iter().find(|key| path == **key) {
            located.message.push_str(&format!(
                " (the case's keys of `{key}` are merged into the scene's, key by key: a choice \
                 written under its name is not switched to another this way; name it by its \
                 `kind`, or set it in each case rather than in the scene)"
            ));
        }
    }
    e
}

/// The cases of `tree`, whose `sweep` and `case` keys it consumes.
pub(crate) fn expand(mut tree: Node, at: &Locator) -> Result<Vec<CaseInput>, SceneError> {
    let sweep = tree.remove("sweep");
    let listed = tree.remove("case");
    let cases = match (sweep, listed) {
        (Some(_), Some(_)) => {
            return Err(at.at("case", "give either a [sweep] or [[case]]s, not both"))
        }
        (Some(sweep), None) => swept(&tree, &sweep, at)?,
        (None, Some(list)) => listed_cases(&tree, &list, at)?,
        (None, None) => vec![CaseInput {
            label: String::new(),
            named: None,
            params: BTreeMap::new(),
            tree,
            tables: Tables::default(),
        }],
    };
    Ok(cases)
}

/// Refuses more than [`MAX_CASES`] cases before any is made, at the key that lists them.
fn at_most(count: usize, path: &str, at: &Locator) -> Result<(), SceneError> {
    if count > MAX_CASES {
        return Err(at.at(
            path,
            format!("{count} cases, at most {MAX_CASES} in one scene"),
        ));
    }
    Ok(())
}

/// The entries of a table, refusing any key outside `allowed`.
fn entries<'n>(
    node: &'n Node,
    path: &str,
    allowed: &[&str],
    at: &Locator,
) -> Result<&'n [(contopt_input::Key, Node)], SceneError> {
    let Value::Table(entries) = node.value() else {
        return Err(at.at(
            path,
            format!("must be a table, not a {}", node.value().kind()),
        ));
    };
    if let Some((key, _)) = entries.iter().find(|(k, _)| !allowed.contains(&k.name())) {
        return Err(at.at(
            &format!("{path}.{}", key.name()),
            format!("unknown key, expected one of {}", allowed.join(", ")),
        ));
    }
    Ok(entries)
}

/// One case per value of `[sweep]`: `key` a dotted path to a number of the scene, `values`
/// its values (whole numbers where the scene has an integer).
fn swept(tree: &Node, sweep: &Node, at: &Locator) -> Result<Vec<CaseInput>, SceneError> {
    entries(sweep, "sweep", &["key", "values"], at)?;
    let key = match sweep.get("key").map(Node::value) {
        Some(Value::String(key)) => key.clone(),
        _ => return Err(at.at("sweep.key", "give the dotted path of a number of the scene")),
    };
    let values = match sweep.get("values").map(Node::value) {
        Some(Value::Array(values)) if !values.is_empty() => values,
        _ => return Err(at.at("sweep.values", "give at least one value")),
    };
    at_most(values.len(), "sweep.values", at)?;
    let current = tree
        .get(&key)
        .ok_or_else(|| at.at("sweep.key", format!("the scene has no `{key}`")))?;
    let integer = matches!(current.value(), Value::Integer(_));
    values
        .iter()
        .enumerate()
        .map(|(k, value)| {
            let place = format!("sweep.values[{k}]");
            let (node, number) = swept_value(value, integer).map_err(|m| at.at(&place, m))?;
            let mut case = tree.clone();
            case.set(&key, node).map_err(|e| at.input(e))?;
            Ok(CaseInput {
                label: words::quantity(&key, number),
                named: Some(()),
                params: [(key.clone(), number)].into(),
                tree: case,
                tables: Tables::default(),
            })
        })
        .collect()
}

/// A swept value as the scene's key takes it: an integer key takes whole numbers only.
fn swept_value(value: &Node, integer: bool) -> Result<(Node, f64), String> {
    let number = match *value.value() {
        Value::Integer(i) => i as f64,
        Value::Float(f) => f,
        ref other => {
            return Err(format!(
                "a sweep's values are numbers, not a {}",
                other.kind()
            ))
        }
    };
    if !integer {
        return Ok((value.clone(), number));
    }
    if number.fract() != 0.0 || number.abs() >= MAX_EXACT_INTEGER {
        return Err(format!(
            "{number}: the swept key holds an integer, so give whole numbers"
        ));
    }
    Ok((Node::from(number as i64).with_span(value.span()), number))
}

/// Puts a case's `value` at `path` of its tree: a table where the scene has a table of the
/// same kind sets its keys one by one, keeping the scene's others (`optimisation = { controller
/// = { l1_mm = 20.0 } }` keeps the method and L2); any other value, or a table naming another
/// `kind` than the scene's, replaces the scene's value; `tables` notes which it did.
fn put(
    case: &mut Node,
    path: &str,
    value: &Node,
    tables: &mut Tables,
) -> Result<(), contopt_input::InputError> {
    let (Value::Table(entries), Some(Value::Table(_))) =
        (value.value(), case.get(path).map(Node::value))
    else {
        return case.insert(path, value.clone()).map(drop);
    };
    let kind = |node: Option<&Node>| node.and_then(|n| n.get("kind")).map(Node::value).cloned();
    let named = kind(Some(value));
    if named.is_some() && named != kind(case.get(path)) {
        tables.whole.push(path.to_string());
        return case.set(path, value.clone()).map(drop);
    }
    tables.merged.push(path.to_string());
    entries
        .iter()
        .try_for_each(|(key, entry)| put(case, &format!("{path}.{}", key.name()), entry, tables))
}

/// Refuses a case's `changes` that set one key twice, written two ways (`"contact.gap.radius_mm"
/// = 20.0` beside `contact = { gap = { radius_mm = 40.0 } }`): the last would win, while the
/// case's numbers reported the first.
fn twice(changes: &[(contopt_input::Key, Node)]) -> Result<(), String> {
    let mut set: Vec<String> = vec![];
    for (key, value) in changes {
        for leaf in leaves(key.name(), value) {
            let overlaps = |other: &String| {
                *other == leaf
                    || other.starts_with(&format!("{leaf}."))
                    || leaf.starts_with(&format!("{other}."))
            };
            if let Some(other) = set.iter().find(|o| overlaps(o)) {
                return Err(format!(
                    "sets `{leaf}` and `{other}`, one key twice: write each key of the case once"
                ));
            }
            set.push(leaf);
        }
    }
    Ok(())
}

/// The dotted paths of the values `value` at `path` sets: its own, or its entries' where it is
/// a table.
fn leaves(path: &str, value: &Node) -> Vec<String> {
    match value.value() {
        Value::Table(entries) if !entries.is_empty() => entries
            .iter()
            .flat_map(|(key, entry)| leaves(&format!("{path}.{}", key.name()), entry))
            .collect(),
        _ => vec![path.to_string()],
    }
}

/// One case per `[[case]]`: its `label` and the dotted keys it `set`s, with their values.
fn listed_cases(tree: &Node, list: &Node, at: &Locator) -> Result<Vec<CaseInput>, SceneError> {
    let Value::Array(items) = list.value() else {
        return Err(at.at("case", "write the cases as [[case]] tables"));
    };
    if items.is_empty() {
        return Err(at.at("case", "give at least one [[case]] (or leave the key out)"));
    }
    at_most(items.len(), "case", at)?;
    let mut seen = std::collections::HashSet::new();
    items
        .iter()
        .enumerate()
        .map(|(k, item)| {
            let path = format!("case[{k}]");
            entries(item, &path, &["label", "set"], at)?;
            let label = match item.get("label").map(Node::value) {
                Some(Value::String(label)) if !label.trim().is_empty() => label.clone(),
                _ => return Err(at.at(&format!("{path}.label"), "give each case a label")),
            };
            if let Some(c) = label.chars().find(|c| c.is_control()) {
                return Err(at.at(
                    &format!("{path}.label"),
                    format!(
                        "{c:?} in {label:?}: a label is one line of text, without control \
                         characters (it heads the printed table's rows)"
                    ),
                ));
            }
            if !seen.insert(label.clone()) {
                return Err(at.at(&format!("{path}.label"), format!("a second case {label:?}")));
            }
            let changes = match item.get("set").map(Node::value) {
                Some(Value::Table(entries)) => entries.as_slice(),
                _ => return Err(at.at(&format!("{path}.set"), "give the keys the case sets")),
            };
            if let Some((key, _)) = changes.iter().find(|(k, _)| SCENE_KEYS.contains(&k.name())) {
                return Err(at.at(
                    &format!("{path}.set.{}", key.name()),
                    "is the scene's, one for all its cases (the name names the results folder, \
                     the description heads the report): set it at the top of the scene, and \
                     tell the cases apart by their labels",
                ));
            }
            twice(changes).map_err(|m| at.at(&format!("{path}.set"), m))?;
            let mut case = tree.clone();
            let mut params = BTreeMap::new();
            let mut tables = Tables::default();
            for (key, value) in changes {
                put(&mut case, key.name(), value, &mut tables).map_err(|e| at.input(e))?;
                numbers(key.name(), value, &mut params);
            }
            Ok(CaseInput {
                label,
                named: Some(()),
                params,
                tree: case,
                tables,
            })
        })
        .collect()
}

/// Each number a case's `value` at `path` sets, into `params` by its dotted path: a table's
/// key by key, an array's by index, as a dotted path reaches them (`set = { optimisation =
/// { method = { max_iterations = 7 } } }` is `optimisation.method.max_iterations`,
/// `contact.zone.cells = [32, 48]` is `contact.zone.cells.0` and `.1`). Values that are not
/// numbers (a kind, a name, a flag) are the case's `input`'s only.
fn numbers(path: &str, value: &Node, params: &mut BTreeMap<String, f64>) {
    match value.value() {
        Value::Integer(i) => {
            params.insert(path.to_string(), *i as f64);
        }
        Value::Float(f) => {
            params.insert(path.to_string(), *f);
        }
        Value::Table(entries) => {
            for (key, entry) in entries {
                numbers(&format!("{path}.{}", key.name()), entry, params);
            }
        }
        Value::Array(items) => {
            for (k, item) in items.iter().enumerate() {
                numbers(&format!("{path}.{k}"), item, params);
            }
        }
        _ => {}
    }
}
