//! Whether an imported body (a plane or axisymmetric mesh, a solid) is held: every rigid motion
//! its supports leave free must move its contact faces along their normals (else no
//! frictionless contact holds it), and its loads must press it onto its partner in each motion
//! that moves the faces one way (else the contact cannot carry them). Checked when the scene is
//! read, so that such a body is refused at its file and line rather than when it is solved.

use contopt_core::{Error, Result};

use crate::mesh_surface::FreeMotion;

/// A free motion's normal displacement smaller than this fraction of its largest is zero: it
/// moves the faces one way only (the contact crate's own round-off).
const ONE_WAY: f64 = 1e-12;

/// What a body names of how it is held, for the errors.
pub(crate) struct Holding<'a> {
    /// Its support groups (and symmetry planes), as the value of `supports`.
    pub supports: String,
    /// Its contact group.
    pub contact: &'a str,
    /// Its loads, as the value of `loads`.
    pub loads: String,
}

/// Each of the `free` motions of a body held as `holding` says moves its contact faces, and
/// its loads press it onto the contact along each that moves them one way.
pub(crate) fn check_held(free: &[FreeMotion], holding: &Holding) -> Result<()> {
    for free in free {
        let name = &free.name;
        if !free.moves_faces() {
            return Err(Error::invalid(
                "supports",
                &holding.supports,
                format!(
                    "leave the body free in its {name}, which its contact faces (\"{}\") \
                     cannot hold: a frictionless contact pushes only along their normals; \
                     hold a group there (a symmetry line x = 0: {{ group = …, fix = \
                     [\"x\"] }})",
                    holding.contact
                ),
            ));
        }
        let span = free.along.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let towards = free.along.iter().all(|v| *v >= -ONE_WAY * span);
        let away = free.along.iter().all(|v| *v <= ONE_WAY * span);
        let pulled = (away && free.load > 0.0) || (towards && free.load < 0.0);
        if pulled {
            return Err(Error::invalid(
                "loads",
                &holding.loads,
                format!(
                    "pull the body away from its partner along its free {name} (it moves \
                     its contact faces \"{}\" off their partner), which a contact cannot \
                     hold: turn the load round (a pressure_mpa positive presses into the \
                     body), or hold the body in its {name}{}",
                    holding.contact,
                    hold_hint(name)
                ),
            ));
        }
        if (towards || away) && free.load == 0.0 {
            return Err(Error::invalid(
                "supports",
                &holding.supports,
                format!(
                    "leave the body free in its {name}, and no load presses it onto its \
                     partner along it: hold it{} or press it (loads = [{{ group = …, \
                     pressure_mpa = … }}])",
                    hold_hint(name)
                ),
            ));
        }
    }
    Ok(())
}

/// How to hold a body in its free motion `name` (`"y translation"`, `"rotation"`): a group
/// fixed along that axis, or, for a rotation, two groups.
fn hold_hint(name: &str) -> String {
    let axis = match name {
        "x translation" => "x",
        "y translation" | "axial translation" => "y",
        "z translation" => "z",
        _ => return " (fix a second group, away from the first, across the motion)".into(),
    };
    format!(" ({{ group = …, fix = [\"{axis}\"] }})")
}
