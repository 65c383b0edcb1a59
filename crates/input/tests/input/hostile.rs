//! Hostile input: size, depth, broken strings and numbers, duplicate keys, characters wider
//! than a byte, and random mutations of the sample; every one an error with a place, no panic.

use std::collections::HashMap;

use contopt_input::{
    line_column, InputError, Limits, Node, Value, DEFAULT_MAX_DEPTH, DEPTH_CEILING,
};

use crate::scene::{place, Scene, SAMPLE_JSON, SAMPLE_TOML};

/// `line:column path: message` of the error parsing `text` as JSON.
fn json_refused(text: &str) -> String {
    place(text, &Node::parse_json(text).unwrap_err())
}

/// `line:column path: message` of the error parsing `text` as TOML.
fn toml_refused(text: &str) -> String {
    place(text, &Node::parse_toml(text).unwrap_err())
}

fn nested(open: &str, depth: usize, close: &str) -> String {
    format!("{}{}", open.repeat(depth), close.repeat(depth))
}

#[test]
fn nesting_deeper_than_the_limit_is_refused_where_it_goes_too_deep() {
    let limit = DEFAULT_MAX_DEPTH;
    let too_deep = "tables and arrays are nested more than 32 deep";
    let toml = |depth| format!("a = {}", nested("[", depth, "]"));
    assert!(Node::parse_toml(&toml(limit)).is_ok());
    assert_eq!(toml_refused(&toml(limit + 1)), format!("1:37 {too_deep}"));
    let json = |depth| format!("{{\"a\": {}}}", nested("[", depth, "]"));
    assert!(Node::parse_json(&json(limit)).is_ok());
    assert_eq!(
        json_refused(&json(limit + 1)),
        format!("1:39 a{}: {too_deep}", "[0]".repeat(32))
    );
    let dotted = |segments| format!("{} = 1", vec!["a"; segments].join("."));
    assert!(Node::parse_toml(&dotted(limit + 1)).is_ok());
    let refused = toml_refused(&dotted(limit + 2));
    assert!(refused.starts_with("1:65 a.a.a."), "{refused}");
    assert!(refused.ends_with(too_deep), "{refused}");
}

#[test]
fn brackets_in_toml_strings_and_comments_do_not_nest() {
    let brackets = nested("[", 40, "");
    for text in [
        format!(r#"a = """x " {brackets} """"#),
        format!("a = '''it's {brackets}'''"),
        format!(r#"a = "\" {brackets}""#),
        format!(r"a = '\' # {brackets}"),
    ] {
        assert!(Node::parse_toml(&text).is_ok(), "{text}");
    }
    let after = |string: &str| format!("a = {string}\nb = {}", nested("[", 33, "]"));
    for string in [r#""""x"""""#, "'''x'''''", r#""x\"""#, "''"] {
        let refused = toml_refused(&after(string));
        assert!(refused.starts_with("2:37 "), "{string}: {refused}");
    }
}

#[test]
fn very_deep_nesting_is_refused_without_recursing() {
    let depth = 100_000;
    assert!(json_refused(&nested("[", depth, "]")).starts_with("1:34 "));
    assert!(json_refused(&nested("{\"a\":", depth, "}")).ends_with("deep"));
    assert!(toml_refused(&format!("a = {}", nested("[", depth, "]"))).starts_with("1:37 "));
    assert!(toml_refused(&format!("a = {}", nested("{b=", depth, "}"))).ends_with("deep"));
}

#[test]
fn a_text_over_the_size_limit_is_refused_before_parsing() {
    let limit = 1_000_000;
    let comment = format!("#{}", "x".repeat(limit - 1));
    assert!(Node::parse_toml(&comment).is_ok());
    let over = format!("{comment}x");
    let message = "the document is 1000001 bytes, over the limit of 1000000 bytes";
    let error = Node::parse_toml(&over).unwrap_err();
    assert_eq!((error.to_string().as_str(), error.span), (message, None));
    let blank = format!("{}{{}}", " ".repeat(limit - 2));
    assert!(Node::parse_json(&blank).is_ok());
    let error = Node::parse_json(&format!(" {blank}")).unwrap_err();
    assert_eq!(error.to_string(), message);
}

/// Arrays of arrays, as deep as they come.
#[derive(serde::Deserialize)]
struct Deep(Vec<Deep>);

#[test]
fn limits_are_the_callers() {
    let limits = Limits {
        max_bytes: 12,
        max_depth: 1,
    };
    assert!(Node::parse_toml_with("a = [1]", &limits).is_ok());
    assert!(Node::parse_toml_with("a = [[1]]", &limits).is_err());
    assert!(Node::parse_json_with("{\"a\": [[1]]}", &limits).is_err());
    assert!(Node::parse_json_with("[1, 2, 3, 4, 5]", &limits).is_err());
    let unbounded = Limits {
        max_bytes: u64::MAX,
        max_depth: usize::MAX,
    };
    let deep = nested("[", 100_000, "]");
    let error = Node::parse_json_with(&deep, &unbounded).unwrap_err();
    let ceiling = DEPTH_CEILING + 1;
    assert_eq!(error.span, Some(ceiling..ceiling + 1), "{error}");
    assert!(Node::parse_toml_with(&format!("a = {deep}"), &unbounded).is_err());
    let deepest = Node::parse_json_with(&nested("[", DEPTH_CEILING + 1, "]"), &unbounded);
    assert_eq!(deepest.unwrap().deserialize::<Deep>().unwrap().0.len(), 1);
}

#[test]
fn columns_count_characters_not_bytes() {
    let text = "a😀b\nc";
    assert_eq!(line_column(text, 2), (1, 2), "inside the 😀");
    assert_eq!(line_column(text, 5), (1, 3));
    assert_eq!(line_column(text, 7), (2, 1));
    assert_eq!(line_column(text, 100), (2, 2));
    let json = "{\"ü€😀\": 1, \"force_n\": \"1 kN\"}";
    let error = Node::parse_json(json)
        .unwrap()
        .deserialize::<HashMap<String, f64>>()
        .unwrap_err();
    assert_eq!(
        place(json, &error),
        "1:23 force_n: invalid type: string \"1 kN\", expected f64"
    );
    let toml = "\"ü€😀\" = 1\nb = { \"ü\" = 2, force_n = \"1 kN\" }";
    let error = Node::parse_toml(toml)
        .unwrap()
        .deserialize_at::<HashMap<String, f64>>("b")
        .unwrap_err();
    assert_eq!(
        place(toml, &error),
        "2:26 b.force_n: invalid type: string \"1 kN\", expected f64"
    );
}

#[test]
fn unterminated_strings_are_refused() {
    assert_eq!(json_refused("{\"a\": \"abc"), "1:7 unterminated string");
    assert_eq!(json_refused("{\"ab"), "1:2 unterminated string");
    assert_eq!(
        json_refused("\"a\\"),
        "1:4 unexpected end of text after `\\` in a string"
    );
    let toml = toml_refused("a = 1\nname = \"abc");
    assert!(toml.starts_with("2:"), "{toml}");
}

#[test]
fn json_numbers_beyond_i64_are_floats() {
    let number = |text: &str| Node::parse_json(text).unwrap().value().clone();
    assert_eq!(number("1e400"), Value::Float(f64::INFINITY));
    assert_eq!(number("-1e400"), Value::Float(f64::NEG_INFINITY));
    assert_eq!(number("99999999999999999999"), Value::Float(1e20));
    assert_eq!(number("9223372036854775807"), Value::Integer(i64::MAX));
    assert_eq!(number("-9223372036854775808"), Value::Integer(i64::MIN));
    assert_eq!(number("-0.5e-3"), Value::Float(-0.0005));
    for bad in [
        "01", "-", "1.", "1e", "1e+", ".5", "+1", "0x10", "NaN", "Infinity",
    ] {
        assert!(Node::parse_json(bad).is_err(), "{bad}");
    }
}

#[test]
fn toml_numbers_beyond_i64_or_f64_are_refused() {
    let refused = toml_refused("a = 99999999999999999999");
    assert!(
        refused.starts_with("1:5 a: the integer 99999999999999999999 is out of range"),
        "{refused}"
    );
    let refused = toml_refused("a = 1e400");
    assert_eq!(
        refused,
        "1:5 a: the float 1e400 is out of range of f64 (write inf for infinity)"
    );
    let node = Node::parse_toml("a = 0xff\nb = -9_223_372_036_854_775_808\nc = +inf").unwrap();
    assert_eq!(node.get("a").unwrap().value(), &Value::Integer(255));
    assert_eq!(node.get("b").unwrap().value(), &Value::Integer(i64::MIN));
    assert_eq!(node.get("c").unwrap().value(), &Value::Float(f64::INFINITY));
}

#[test]
fn duplicate_keys_are_refused() {
    assert_eq!(
        json_refused("{\"a\": 1,\n \"a\": 2}"),
        "2:2 a: duplicate key, first at line 1, column 2"
    );
    let toml = toml_refused("a = 1\na = 2");
    assert!(toml.starts_with("2:1 "), "{toml}");
}

#[test]
fn json_syntax_errors_have_their_place() {
    let cases = [
        ("", "1:1 unexpected end of text where a value should be"),
        ("{} x", "1:4 unexpected 'x' after the document"),
        ("[1,]", "1:4 unexpected ']' where a value should be"),
        (
            "[1 2]",
            "1:4 unexpected '2' in an array: expected `,` or `]`",
        ),
        ("{\"a\" 1}", "1:6 unexpected '1' after a key: expected `:`"),
        (
            "{\"a\": 1,}",
            "1:9 unexpected '}' in an object: expected a key in quotes",
        ),
        ("tru", "1:1 unexpected 't' where a value should be"),
        (
            "\"a\nb\"",
            "1:3 unexpected '\\n' in a string: control characters must be escaped",
        ),
        ("\"\\x\"", "1:3 unexpected 'x' after `\\` in a string"),
        ("\"\\u12\"", "1:2 `\\u` needs four hex digits"),
        ("\"\\ud83d\"", "1:2 unpaired UTF-16 surrogate in a string"),
        ("\"\\ude00\"", "1:2 unpaired UTF-16 surrogate in a string"),
        (
            "\"\\ud83d\\u0041\"",
            "1:2 unpaired UTF-16 surrogate in a string",
        ),
        ("[😀]", "1:2 unexpected '😀' where a value should be"),
    ];
    for (text, expected) in cases {
        assert_eq!(json_refused(text), expected, "{text:?}");
    }
}

#[test]
fn json_escapes_resolve() {
    let text = r#""\"\\\/\b\f\n\r\t\u00e9\ud83d\ude00é""#;
    let node = Node::parse_json(text).unwrap();
    let expected = "\"\\/\u{8}\u{c}\n\r\té😀é";
    assert_eq!(node.value(), &Value::String(expected.into()));
}

/// A small deterministic generator (xorshift64).
struct XorShift(u64);

impl XorShift {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Characters that matter to the parsers, and some wider than a byte.
const PALETTE: &[char] = &[
    '[', ']', '{', '}', '"', '\'', '=', ',', '.', ':', '#', '\\', '\n', '\r', '\t', ' ', '0', '9',
    'e', 'E', '-', '+', '_', 'a', 'u', 'n', 'i', 'f', 'k', 'é', '€', '😀', '\0', '\u{7f}',
];

/// One random edit of `chars`: a deletion, an insertion, a replacement or a repeated slice.
fn mutate(rng: &mut XorShift, chars: &mut Vec<char>) {
    let at = rng.below(chars.len() + 1);
    match rng.below(4) {
        0 => {
            let end = (at + 1 + rng.below(8)).min(chars.len());
            chars.drain(at.min(end)..end);
        }
        1 => chars.insert(at, PALETTE[rng.below(PALETTE.len())]),
        2 if at < chars.len() => chars[at] = PALETTE[rng.below(PALETTE.len())],
        _ => {
            let end = (at + rng.below(16)).min(chars.len());
            let slice: Vec<char> = chars[at..end].to_vec();
            let to = rng.below(chars.len() + 1);
            chars.splice(to..to, slice);
        }
    }
}

/// The error's span lies in `text` and has a line and column.
fn check_error(text: &str, error: &InputError) {
    if let Some(span) = &error.span {
        assert!(
            span.start <= span.end && span.end <= text.len(),
            "{error:?} in {text:?}"
        );
        let (line, column) = error.line_column(text).unwrap();
        assert!(line >= 1 && column >= 1 && line <= text.lines().count() + 1);
    }
    assert!(!error.message.is_empty());
}

/// A parser of one format.
type Parse = fn(&str) -> Result<Node, InputError>;

/// Parses, reads and edits a mutated document, every error well placed; whether it parsed.
fn exercise(text: &str, parse: Parse) -> bool {
    let mut node = match parse(text) {
        Ok(node) => node,
        Err(error) => {
            check_error(text, &error);
            return false;
        }
    };
    if let Err(error) = node.deserialize::<Scene>() {
        check_error(text, &error);
    }
    for path in [
        "contact.load.force_n",
        "body.1.material",
        "body.0.plane",
        "solver",
    ] {
        if let Err(error) = node.set(path, Node::from(f64::NAN)) {
            check_error(text, &error);
        }
        if let Err(error) = node.deserialize_at::<Scene>(path) {
            check_error(text, &error);
        }
    }
    true
}

#[test]
fn random_mutations_of_the_sample_never_panic() {
    const CASES: usize = 20_000;
    const MAX_EDITS: usize = 3;
    let mut rng = XorShift(0x9E37_79B9_7F4A_7C15);
    let formats: [(&str, Parse); 2] = [
        (SAMPLE_TOML, Node::parse_toml),
        (SAMPLE_JSON, Node::parse_json),
    ];
    for (sample, parse) in formats {
        let mut parsed = 0;
        for _ in 0..CASES {
            let mut chars: Vec<char> = sample.chars().collect();
            for _ in 0..=rng.below(MAX_EDITS) {
                mutate(&mut rng, &mut chars);
            }
            let text: String = chars.into_iter().collect();
            parsed += usize::from(exercise(&text, parse));
        }
        assert!(
            parsed > CASES / 10,
            "only {parsed} of {CASES} mutants parsed: a weak test"
        );
    }
}
