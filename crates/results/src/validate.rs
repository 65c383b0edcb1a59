//! Checks a JSON document against the schema of [`crate::schema`]: the part of JSON Schema
//! (draft 2020-12) that the derivation uses — `type`, `properties`, `required`,
//! `additionalProperties`, `items`, `minItems`/`maxItems`, `minimum`/`maximum`, `oneOf`/`anyOf`,
//! `const`, `enum`,
//! `$ref` into `$defs`, and `true` — so that a results file can be checked without a
//! general validator. A keyword outside that part is refused, so that the check cannot pass
//! by ignoring it.

use serde_json::{Map, Value};

/// Keywords that describe and do not constrain.
const ANNOTATIONS: [&str; 5] = ["$schema", "title", "description", "format", "default"];

/// The places where `document` breaks `schema` (empty when it conforms), each as
/// `path: what`.
pub fn violations(schema: &Value, document: &Value) -> Vec<String> {
    let mut found = vec![];
    let defs = schema.get("$defs").cloned().unwrap_or(Value::Null);
    check(schema, &defs, document, "$", &mut found);
    found
}

/// Checks `value` at `path` against `schema`, with `defs` the shared definitions.
fn check(schema: &Value, defs: &Value, value: &Value, path: &str, found: &mut Vec<String>) {
    let rules = match schema {
        Value::Bool(true) => return,
        Value::Object(rules) => rules,
        other => return found.push(format!("{path}: the schema {other} is not a schema")),
    };
    for (keyword, rule) in rules {
        match keyword.as_str() {
            "$ref" => reference(rule, defs, value, path, found),
            "type" => type_of(rule, value, path, found),
            "properties" | "required" | "additionalProperties" => {}
            "items" => items(rule, defs, value, path, found),
            "minItems" | "maxItems" => length(keyword, rule, value, path, found),
            "minimum" | "maximum" => bound(keyword, rule, value, path, found),
            "oneOf" | "anyOf" => alternatives(keyword, rule, defs, value, path, found),
            "const" if value != rule => found.push(format!("{path}: {value} is not {rule}")),
            "enum" if !rule.as_array().is_some_and(|a| a.contains(value)) => {
                found.push(format!("{path}: {value} is not one of {rule}"))
            }
            "const" | "enum" | "$defs" => {}
            k if ANNOTATIONS.contains(&k) => {}
            k => found.push(format!(
                "{path}: the schema uses `{k}`, which this check lacks"
            )),
        }
    }
    if let Value::Object(object) = value {
        object_rules(rules, defs, object, path, found);
    }
}

/// `$ref`: `#/$defs/<name>`.
fn reference(rule: &Value, defs: &Value, value: &Value, path: &str, found: &mut Vec<String>) {
    let name = rule.as_str().and_then(|r| r.strip_prefix("#/$defs/"));
    match name.and_then(|n| defs.get(n)) {
        Some(target) => check(target, defs, value, path, found),
        None => found.push(format!("{path}: unresolved reference {rule}")),
    }
}

/// `type`: one name or a list of names.
fn type_of(rule: &Value, value: &Value, path: &str, found: &mut Vec<String>) {
    let names: Vec<&str> = match rule {
        Value::String(name) => vec![name],
        Value::Array(names) => names.iter().filter_map(Value::as_str).collect(),
        _ => vec![],
    };
    let is = |name: &str| match name {
        "null" => value.is_null(),
        "boolean" => value.is_boolean(),
        "object" => value.is_object(),
        "array" => value.is_array(),
        "string" => value.is_string(),
        "number" => value.is_number(),
        "integer" => value.as_f64().is_some_and(|v| v.fract() == 0.0),
        _ => false,
    };
    if !names.iter().any(|n| is(n)) {
        found.push(format!("{path}: {value} is not of type {rule}"));
    }
}

/// `items`: every element.
fn items(rule: &Value, defs: &Value, value: &Value, path: &str, found: &mut Vec<String>) {
    if let Value::Array(elements) = value {
        for (k, element) in elements.iter().enumerate() {
            check(rule, defs, element, &format!("{path}[{k}]"), found);
        }
    }
}

/// `minItems` and `maxItems`.
fn length(keyword: &str, rule: &Value, value: &Value, path: &str, found: &mut Vec<String>) {
    if let (Value::Array(elements), Some(bound)) = (value, rule.as_u64()) {
        let n = elements.len() as u64;
        let ok = if keyword == "minItems" {
            n >= bound
        } else {
            n <= bound
        };
        if !ok {
            found.push(format!("{path}: {n} items break {keyword} = {bound}"));
        }
    }
}

/// `minimum` and `maximum` of a number.
fn bound(keyword: &str, rule: &Value, value: &Value, path: &str, found: &mut Vec<String>) {
    if let (Some(v), Some(limit)) = (value.as_f64(), rule.as_f64()) {
        let ok = if keyword == "minimum" {
            v >= limit
        } else {
            v <= limit
        };
        if !ok {
            found.push(format!("{path}: {v} breaks {keyword} = {limit}"));
        }
    }
}

/// `oneOf` (exactly one alternative) and `anyOf` (at least one).
fn alternatives(
    keyword: &str,
    rule: &Value,
    defs: &Value,
    value: &Value,
    path: &str,
    found: &mut Vec<String>,
) {
    let options = rule.as_array().map(Vec::as_slice).unwrap_or_default();
    let passing = options
        .iter()
        .filter(|option| {
            let mut inner = vec![];
            check(option, defs, value, path, &mut inner);
            inner.is_empty()
        })
        .count();
    let ok = if keyword == "oneOf" {
        passing == 1
    } else {
        passing >= 1
    };
    if !ok {
        found.push(format!(
            "{path}: {value} matches {passing} of the {} alternatives of {keyword}",
            options.len()
        ));
    }
}

/// `properties`, `required` and `additionalProperties` of an object.
fn object_rules(
    rules: &Map<String, Value>,
    defs: &Value,
    object: &Map<String, Value>,
    path: &str,
    found: &mut Vec<String>,
) {
    let properties = rules.get("properties").and_then(Value::as_object);
    for name in rules
        .get("required")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .filter_map(Value::as_str)
    {
        if !object.contains_key(name) {
            found.push(format!("{path}: `{name}` is missing"));
        }
    }
    for (key, member) in object {
        let at = format!("{path}.{key}");
        match (
            properties.and_then(|p| p.get(key)),
            rules.get("additionalProperties"),
        ) {
            (Some(schema), _) => check(schema, defs, member, &at, found),
            (None, Some(Value::Bool(false))) => found.push(format!("{at}: not in the schema")),
            (None, Some(extra)) => check(extra, defs, member, &at, found),
            (None, None) => {}
        }
    }
}
