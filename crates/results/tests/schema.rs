//! The committed JSON Schema is the one the types derive, and the check against it catches
//! what it must: a missing field, a field of the wrong type, a field the schema does not know,
//! a tag it does not list.

use contopt_core::Termination;
use contopt_results::{schema, violations, CaseReport, CaseStatus, Point, Report, SCHEMA_VERSION};

/// The schema file in the repository, beside this crate's manifest.
const SCHEMA_FILE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/result.schema.json");

/// The schema derived from the types, as the file holds it (pretty, with a final newline).
fn derived() -> String {
    serde_json::to_string_pretty(&schema()).unwrap() + "\n"
}

/// `CONTOPT_BLESS=1 cargo test -p contopt-results` rewrites the file after a deliberate
/// change of the schema (and SCHEMA_VERSION must then change too).
#[test]
fn the_committed_schema_is_the_derived_one() {
    if std::env::var_os("CONTOPT_BLESS").is_some() {
        std::fs::write(SCHEMA_FILE, derived()).unwrap();
    }
    let committed = std::fs::read_to_string(SCHEMA_FILE).unwrap_or_default();
    assert!(
        committed == derived(),
        "{SCHEMA_FILE} differs from the schema the types derive: rerun with CONTOPT_BLESS=1 \
         after raising SCHEMA_VERSION"
    );
}

fn sample() -> serde_json::Value {
    let mut case = CaseReport::new("L1 = 20 mm", &Default::default(), serde_json::json!({}));
    case.status = CaseStatus::Solved;
    case.termination = Termination::StepLimit {
        steps: 3,
        measure: 0.5,
        tolerance: 1e-3,
    };
    case.interface.push(Point {
        x_mm: [1.0, 0.0, 0.0],
        p_mpa: 2.0,
        d_um: 0.0,
        dh_um: 1.0,
        h_um: 0.0,
    });
    let report = Report {
        schema_version: SCHEMA_VERSION,
        scene: "s".into(),
        description: String::new(),
        cases: vec![case],
    };
    serde_json::to_value(report).unwrap()
}

/// A way to break a report: what the validator must say, and the change.
type Breakage = (&'static str, fn(&mut serde_json::Value));

#[test]
fn a_report_conforms_and_broken_ones_do_not() {
    let schema = schema();
    let good = sample();
    assert_eq!(violations(&schema, &good), Vec::<String>::new());
    let broken: [Breakage; 6] = [
        ("breaks minimum", |v| v["schema_version"] = (-1).into()),
        ("`p_max_mpa` is missing", |v| {
            v["cases"][0].as_object_mut().unwrap().remove("p_max_mpa");
        }),
        ("is not of type", |v| {
            v["cases"][0]["p_max_mpa"] = "high".into()
        }),
        ("not in the schema", |v| v["cases"][0]["p_max"] = 1.0.into()),
        ("alternatives of oneOf", |v| {
            v["cases"][0]["termination"]["kind"] = "gave_up".into()
        }),
        ("break maxItems", |v| {
            v["cases"][0]["interface"][0]["x_mm"] = serde_json::json!([1.0, 2.0, 3.0, 4.0])
        }),
    ];
    for (expected, damage) in broken {
        let mut document = good.clone();
        damage(&mut document);
        let found = violations(&schema, &document);
        assert!(
            found.iter().any(|f| f.contains(expected)),
            "{expected}: {found:?}"
        );
    }
}

/// A plane or axisymmetric body's stresses have no τ_yz: its peak is null in the report, not
/// a value of 0 at the last point searched (an axisymmetric block's bottom, 40 mm down); a
/// grid's τ_yz keeps its value and place.
#[test]
fn a_shear_that_is_zero_everywhere_has_no_peak() {
    use contopt_core::{StressPeaks, StressTensor};
    use contopt_results::Peaks;
    let peaks = |yz: f64| {
        let mut peaks = StressPeaks::default();
        for (k, depth) in [0.25, 40.0].into_iter().enumerate() {
            let s = StressTensor {
                zz: -1.0 - k as f64,
                xz: 0.3,
                yz,
                ..Default::default()
            };
            peaks.record(&s, 0.0, 0.0, depth);
        }
        Peaks::from(peaks)
    };
    assert_eq!(peaks(0.0).shear_yz, None);
    let shear = peaks(0.2).shear_yz.expect("a τ_yz peak");
    assert_eq!((shear.value_mpa, shear.depth_mm), (0.2, 0.25));
    let json = serde_json::to_value(peaks(0.0)).unwrap();
    assert!(json["shear_yz"].is_null(), "{json}");
}
