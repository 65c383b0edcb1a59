//! A small scene-like schema and a sample document in TOML and JSON.

use contopt_input::{InputError, Node};
use serde::Deserialize;

#[derive(Deserialize, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    pub name: String,
    pub contact: Contact,
    pub solver: Solver,
    pub body: Vec<Body>,
}

#[derive(Deserialize, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Contact {
    pub load: Load,
    pub law: Law,
}

#[derive(Deserialize, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Load {
    pub force_n: f64,
    #[serde(default)]
    pub angle_deg: f64,
}

#[derive(Deserialize, Debug, PartialEq)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Law {
    Rigid,
    Penalty { c_mpa_per_mm: f64 },
    Linear(Stiffness),
}

#[derive(Deserialize, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Stiffness {
    pub k: f64,
}

#[derive(Deserialize, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Solver {
    pub method: Method,
    #[serde(default)]
    pub max_iterations: Option<u32>,
}

#[derive(Deserialize, Debug, PartialEq)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    ActiveSet,
    Lemke,
}

#[derive(Deserialize, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Body {
    pub name: String,
    pub plane: Plane,
    pub material: Material,
}

#[derive(Deserialize, Debug, PartialEq)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Plane {
    PlaneStrain,
    PlaneStress { thickness_mm: f64 },
}

/// A material validated as a whole: its refusals name the key at fault.
#[derive(Deserialize, Debug, PartialEq)]
#[serde(try_from = "RawMaterial")]
pub struct Material {
    pub e_mpa: f64,
    pub nu: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    e_mpa: f64,
    nu: f64,
}

impl TryFrom<RawMaterial> for Material {
    type Error = String;

    fn try_from(raw: RawMaterial) -> Result<Self, String> {
        if raw.e_mpa.is_nan() || raw.e_mpa <= 0.0 {
            return Err(format!("e_mpa: must be positive, got {}", raw.e_mpa));
        }
        if raw.nu.is_nan() || raw.nu <= -1.0 || raw.nu >= 0.5 {
            return Err(format!(
                "invalid nu = {}: Poisson's ratio is above -1 and below 0.5",
                raw.nu
            ));
        }
        if raw.e_mpa > 1e7 && raw.nu > 0.4 {
            return Err("a stiff rubber is not a material we know".into());
        }
        Ok(Self {
            e_mpa: raw.e_mpa,
            nu: raw.nu,
        })
    }
}

pub const SAMPLE_TOML: &str = r#"name = "hertz"

[contact.load]
force_n = 1000
angle_deg = 0.0

[contact.law]
kind = "penalty"
c_mpa_per_mm = 2e9

[solver]
method = "active_set"

[[body]]
name = "ball"
plane = { plane_stress = { thickness_mm = 10.0 } }
material = { e_mpa = 210000, nu = 0.3 }

[[body]]
name = "block"
plane = "plane_strain"
material = { e_mpa = 70000, nu = 0.33 }
"#;

pub const SAMPLE_JSON: &str = r#"{
  "name": "hertz",
  "contact": {
    "load": { "force_n": 1000, "angle_deg": 0.0 },
    "law": { "kind": "penalty", "c_mpa_per_mm": 2e9 }
  },
  "solver": { "method": "active_set" },
  "body": [
    {
      "name": "ball",
      "plane": { "plane_stress": { "thickness_mm": 10.0 } },
      "material": { "e_mpa": 210000, "nu": 0.3 }
    },
    {
      "name": "block",
      "plane": "plane_strain",
      "material": { "e_mpa": 70000, "nu": 0.33 }
    }
  ]
}
"#;

/// The sample's value.
pub fn sample() -> Scene {
    Scene {
        name: "hertz".into(),
        contact: Contact {
            load: Load {
                force_n: 1000.0,
                angle_deg: 0.0,
            },
            law: Law::Penalty { c_mpa_per_mm: 2e9 },
        },
        solver: Solver {
            method: Method::ActiveSet,
            max_iterations: None,
        },
        body: vec![
            Body {
                name: "ball".into(),
                plane: Plane::PlaneStress { thickness_mm: 10.0 },
                material: Material {
                    e_mpa: 210000.0,
                    nu: 0.3,
                },
            },
            Body {
                name: "block".into(),
                plane: Plane::PlaneStrain,
                material: Material {
                    e_mpa: 70000.0,
                    nu: 0.33,
                },
            },
        ],
    }
}

/// `text` with `from` (which must be there) replaced by `to`.
pub fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from:?} is not in the sample");
    text.replacen(from, to, 1)
}

/// Reads a TOML scene.
pub fn read_toml(text: &str) -> Result<Scene, InputError> {
    Node::parse_toml(text)?.deserialize()
}

/// Reads a JSON scene.
pub fn read_json(text: &str) -> Result<Scene, InputError> {
    Node::parse_json(text)?.deserialize()
}

/// `line:column path: message` of the error reading `text`, which must fail.
pub fn refusal(text: &str, result: Result<Scene, InputError>) -> String {
    let error = result.expect_err("the document should be refused");
    place(text, &error)
}

/// `line:column path: message` of `error` in `text`.
pub fn place(text: &str, error: &InputError) -> String {
    let (line, column) = error.line_column(text).expect("the error has a span");
    format!("{line}:{column} {error}")
}
