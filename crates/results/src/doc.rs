//! The schema as a reader's reference: one table per object of [`crate::schema`], its fields
//! with their types and descriptions, written as Markdown for the book, so that the book's
//! chapter on results cannot drift from the types.

use serde_json::{Map, Value};

/// The schema of `result.json` as Markdown: the report first, then each object it holds, in
/// the order they are first reached.
pub fn schema_markdown() -> String {
    let schema = crate::schema();
    let defs = schema
        .get("$defs")
        .and_then(Value::as_object)
        .cloned()
        .unwrap_or_default();
    let mut out = format!(
        "Schema version {}. Every field is always present; `null` where it does not apply.\n",
        crate::SCHEMA_VERSION
    );
    let mut queue = vec![("Report".to_string(), schema.clone())];
    let mut written: Vec<String> = vec![];
    while let Some((name, object)) = queue.pop() {
        if written.contains(&name) {
            continue;
        }
        written.push(name.clone());
        let mut found = vec![];
        out += &object_table(&name, &object, &mut found);
        for reference in found.into_iter().rev() {
            if let Some(def) = defs.get(&reference) {
                queue.push((reference, def.clone()));
            }
        }
    }
    out
}

/// One object's table; the objects it refers to are added to `found`.
fn object_table(name: &str, object: &Value, found: &mut Vec<String>) -> String {
    let mut out = format!("\n### `{name}`\n\n{}\n", description(object));
    let Some(properties) = object.get("properties").and_then(Value::as_object) else {
        return out + &alternatives(object, found);
    };
    out += "\n| field | type | what |\n| --- | --- | --- |\n";
    for (field, schema) in properties {
        let kind = type_of(schema, found);
        out += &format!(
            "| `{field}` | {kind} | {} |\n",
            one_line(&description(schema))
        );
    }
    out
}

/// The variants of an enum-like object (a tagged termination, a status).
fn alternatives(object: &Value, found: &mut Vec<String>) -> String {
    let options = object
        .get("oneOf")
        .or_else(|| object.get("anyOf"))
        .and_then(Value::as_array);
    let Some(options) = options else {
        return match object.get("enum").and_then(Value::as_array) {
            Some(values) => format!("\nOne of {}.\n", list(values)),
            None => String::new(),
        };
    };
    let mut out = String::from("\n| variant | fields | what |\n| --- | --- | --- |\n");
    for option in options {
        let props = option.get("properties").and_then(Value::as_object);
        let (tag, fields) = variant(option, props, found);
        out += &format!(
            "| {tag} | {fields} | {} |\n",
            one_line(&description(option))
        );
    }
    out
}

/// A variant's tag and its other fields.
fn variant(
    option: &Value,
    props: Option<&Map<String, Value>>,
    found: &mut Vec<String>,
) -> (String, String) {
    let tag = props
        .and_then(|p| {
            p.iter()
                .find_map(|(k, v)| v.get("const").map(|c| format!("`{k}` = {c}")))
        })
        .or_else(|| option.get("const").map(|c| format!("{c}")))
        .or_else(|| {
            option
                .get("enum")
                .and_then(Value::as_array)
                .map(|v| list(v))
        })
        .unwrap_or_default();
    let fields: Vec<String> = props
        .into_iter()
        .flatten()
        .filter(|(_, v)| v.get("const").is_none())
        .map(|(k, v)| format!("`{k}`: {}", type_of(v, found)))
        .collect();
    (tag, fields.join(", "))
}

/// A field's type in words, noting the objects it refers to.
fn type_of(schema: &Value, found: &mut Vec<String>) -> String {
    if let Some(reference) = schema.get("$ref").and_then(Value::as_str) {
        let name = reference.trim_start_matches("#/$defs/").to_string();
        found.push(name.clone());
        return format!("`{name}`");
    }
    if let Some(options) = schema.get("anyOf").and_then(Value::as_array) {
        let kinds: Vec<String> = options.iter().map(|o| type_of(o, found)).collect();
        return kinds.join(" or ");
    }
    let base = match schema.get("type") {
        Some(Value::String(t)) => t.clone(),
        Some(Value::Array(ts)) => ts
            .iter()
            .filter_map(Value::as_str)
            .collect::<Vec<_>>()
            .join(" or "),
        _ => "any".into(),
    };
    match (
        base.as_str(),
        schema.get("items"),
        schema.get("additionalProperties"),
    ) {
        ("array", Some(items), _) => format!("array of {}", type_of(items, found)),
        ("object", _, Some(values)) if values.is_object() => {
            format!("map to {}", type_of(values, found))
        }
        _ => base,
    }
}

/// A schema's description, its rustdoc escapes undone.
fn description(schema: &Value) -> String {
    let text = schema
        .get("description")
        .and_then(Value::as_str)
        .unwrap_or_default();
    unlink(text).replace("\\[", "[").replace("\\]", "]")
}

/// Rustdoc's links as plain code: ``[`X`]`` and ``[`X`](path)`` become `` `X` ``.
fn unlink(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(start) = rest.find("[`") {
        let Some(end) = rest[start + 2..].find("`]").map(|e| start + 2 + e) else {
            break;
        };
        out.push_str(&rest[..start]);
        out.push_str(&rest[start + 1..end + 1]);
        rest = &rest[end + 2..];
        if rest.starts_with('(') {
            if let Some(close) = rest.find(')') {
                rest = &rest[close + 1..];
            }
        }
    }
    out.push_str(rest);
    out
}

/// Text on one line, for a table cell.
fn one_line(text: &str) -> String {
    text.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace('|', "\\|")
}

/// Values listed as code.
fn list(values: &[Value]) -> String {
    values
        .iter()
        .map(|v| format!("`{v}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    /// Every field of a case appears in the reference, with its unit in its description.
    #[test]
    fn every_field_of_a_case_is_documented() {
        let text = super::schema_markdown();
        for field in [
            "`p_max_mpa`",
            "`dh_um`",
            "`termination`",
            "`limit`",
            "`schema_version`",
        ] {
            assert!(text.contains(field), "{field}");
        }
        assert!(text.contains("### `CaseReport`") && text.contains("[MPa]"));
        assert!(!text.contains("\\["));
        assert!(!text.contains("[`"), "a rustdoc link left as written");
    }

    #[test]
    fn rustdoc_links_read_as_code() {
        assert_eq!(
            super::unlink("see [`SCHEMA_VERSION`] and [`Termination`](contopt_core::Termination)."),
            "see `SCHEMA_VERSION` and `Termination`."
        );
        assert_eq!(super::unlink("a [`b"), "a [`b");
    }
}
