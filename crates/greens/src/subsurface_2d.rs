//! Stresses below the surface of the bodies whose only section is their own plane: the
//! half-plane (strips) and the axisymmetric half-space (rings). Each body supplies the stress
//! at one point, `stress_at(x, depth)`; this module checks the input, sweeps the points and
//! gathers the peaks and the section, so that the two bodies share one sweep.

use contopt_core::{
    check, Error, Result, Section, SectionAxis, SectionField, StressPeaks, StressTensor,
    Subsurface, SubsurfaceRequest,
};

/// Checks that `pressure` has one finite value per contact point (`points` of them).
pub(crate) fn check_pressure(body: &str, pressure: &[f64], points: usize) -> Result<()> {
    if pressure.len() != points {
        return Err(Error::invalid(
            format!("{body}.subsurface.pressure"),
            format!("{} values", pressure.len()),
            format!("give one pressure per contact point ({points})"),
        ));
    }
    check::all_finite(&format!("{body}.subsurface.pressure"), pressure)
}

/// Checks one evaluation point: `x` finite (and ≥ 0 when `radial`), `depth` finite and > 0.
pub(crate) fn check_point(body: &str, x: f64, depth: f64, radial: bool) -> Result<()> {
    if radial {
        check::non_negative(&format!("{body}.stress_at.x"), x)?;
    } else {
        check::finite(&format!("{body}.stress_at.x"), x)?;
    }
    // Positive: the surface itself (depth 0) is the contact pressure.
    check::positive(&format!("{body}.stress_at.depth"), depth)?;
    Ok(())
}

/// The stress `stress_at(x, depth)` checked to be finite.
fn finite_stress(
    body: &str,
    stress_at: &impl Fn(f64, f64) -> StressTensor,
    x: f64,
    depth: f64,
) -> Result<StressTensor> {
    let s = stress_at(x, depth);
    if s.is_finite() {
        Ok(s)
    } else {
        Err(not_finite(
            body,
            format!("{s:?} at x = {x}, depth = {depth}"),
        ))
    }
}

/// The error of a stress `value` (and where) that is not finite.
pub(crate) fn not_finite(body: &str, value: String) -> Error {
    Error::invalid(
        format!("{body}.subsurface"),
        value,
        "a stress below the surface is not finite (pressures too large for f64?)",
    )
}

/// Evaluates `stress_at(x, depth)` at every requested depth under every `x` of `positions`
/// (the section, also swept for the peaks) and of `extra` (swept for the peaks only), and
/// returns the peaks and one copy of the section per requested section: a plane or
/// axisymmetric body has one section, its own plane, reported as `axis: X, at: 0`. The request
/// and the `pressure` (one value per contact point, `points` of them) are checked first.
pub(crate) fn sweep(
    body: &str,
    request: &SubsurfaceRequest,
    (pressure, points): (&[f64], usize),
    positions: &[f64],
    extra: &[f64],
    stress_at: impl Fn(f64, f64) -> StressTensor,
) -> Result<Subsurface> {
    request.check()?;
    check_pressure(body, pressure, points)?;
    let mut peaks = StressPeaks::default();
    let mut tensors = Vec::with_capacity(positions.len() * request.depths.len());
    for &depth in &request.depths {
        for &x in positions {
            let s = finite_stress(body, &stress_at, x, depth)?;
            peaks.record(&s, x, 0.0, depth);
            tensors.push(s);
        }
        for &x in extra {
            let s = finite_stress(body, &stress_at, x, depth)?;
            peaks.record(&s, x, 0.0, depth);
        }
    }
    let peaks = peaks.finite(body)?;
    let field = SectionField {
        section: Section {
            axis: SectionAxis::X,
            at: 0.0,
        },
        positions: positions.to_vec(),
        depths: request.depths.clone(),
        tensors,
    };
    Ok(Subsurface {
        peaks,
        sections: vec![field; request.sections.len()],
    })
}

#[cfg(test)]
mod tests {
    use contopt_core::{ElasticBody, Error, Material, SubsurfaceRequest};

    use crate::{AxisymmetricHalfSpace, HalfPlane, PlaneState};

    fn bodies() -> Vec<Box<dyn ElasticBody>> {
        let steel = Material::new(2.1e5, 0.3).unwrap();
        let edges = [0.0, 0.5, 1.0];
        vec![
            Box::new(HalfPlane::new("hp", steel, PlaneState::Strain, 1.0, &edges, 10.0).unwrap()),
            Box::new(AxisymmetricHalfSpace::new("hs", steel, &edges).unwrap()),
        ]
    }

    /// The field an `InvalidInput` error names.
    fn field(result: contopt_core::Result<Option<contopt_core::Subsurface>>) -> String {
        match result {
            Err(Error::InvalidInput { field, .. }) => field,
            other => panic!("expected an invalid input, got {other:?}"),
        }
    }

    /// Depths that are not positive or finite, and pressures of the wrong length or not
    /// finite, are refused with the field that holds them.
    #[test]
    fn bad_requests_and_pressures_are_refused() {
        let depths = |depths: Vec<f64>| SubsurfaceRequest {
            depths,
            sections: vec![],
        };
        for body in bodies() {
            let p = [1.0, 2.0];
            let name = body.name().to_string();
            assert_eq!(
                field(body.subsurface(&p, &depths(vec![]))),
                "subsurface.depths"
            );
            for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
                let got = field(body.subsurface(&p, &depths(vec![0.5, bad])));
                assert_eq!(got, "subsurface.depths[1]", "{name}, depth {bad}");
            }
            let good = depths(vec![0.5]);
            let got = field(body.subsurface(&[1.0], &good));
            assert_eq!(got, format!("{name}.subsurface.pressure"));
            let got = field(body.subsurface(&[1.0, f64::NAN], &good));
            assert_eq!(got, format!("{name}.subsurface.pressure[1]"));
            // Finite input that overflows f64 is refused, not returned as infinity.
            let got = field(body.subsurface(&[1e308, 1e308], &good));
            assert_eq!(got, format!("{name}.subsurface"));
            assert!(body.subsurface(&p, &good).is_ok());
        }
    }
}
