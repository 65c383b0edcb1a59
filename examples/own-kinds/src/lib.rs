//! A crate of one's own that adds a body kind and a design to contopt's scenes, without
//! editing contopt: the book's chapter "Write your own body" ends here.
//!
//! - [`PasternakBed`] (`kind = "pasternak"`): the library's [`Pasternak`] foundation — springs
//!   tied by a shear layer — as a body a scene may name under a row of strips;
//! - [`ParabolicRelief`] (`method = { kind = "parabolic_relief", … }`): a design that relieves
//!   the initial gap by a given parabola, Δh(x) = depth·(x/half_length)², and solves the
//!   contact under it;
//! - [`ProjectedGaussSeidel`] (`solver = { kind = "projected_gauss_seidel" }`): a contact
//!   solver of its own on the dense influence matrix, run by the library's iteration driver.
//!
//! [`registry`] is the library's kinds and these two; the binary `contopt-own` is the
//! `contopt` command over it ([`contopt_cli::main_with`]), every command kept.

mod solver;

pub use solver::ProjectedGaussSeidel;

use contopt_core::observe::Method;
use contopt_core::{ElasticBody, Interface, Result};
use contopt_greens::Pasternak;
use contopt_results::CaseReport;
use contopt_scene::{
    misplaced, own_surface, BodyKind, Check, Chosen, Context, Design, Designed, Placement,
    Registry, StripsZone, Takes, ZoneKind,
};
use serde::{Deserialize, Serialize};

/// Memory per strip of a bed \[bytes\]: its surface, and the factor of its stiffness.
const STRIP_BYTES: u64 = 128;

// ANCHOR: registry
/// The library's kinds, the Pasternak bed, the parabolic relief and projected Gauss–Seidel.
pub fn registry() -> Registry {
    Registry::standard()
        .with_body::<PasternakBed>("pasternak")
        .with_design::<ParabolicRelief>("parabolic_relief")
        .with_solver::<ProjectedGaussSeidel>("projected_gauss_seidel")
}
// ANCHOR_END: registry

// ANCHOR: kind
/// A Pasternak bed under a row of strips, held by the ground: springs of modulus k tied by a
/// shear layer of stiffness G_p (p = k·w − G_p·w'').
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PasternakBed {
    /// Its name in reports (default `bed`).
    #[serde(default)]
    pub name: Option<String>,
    /// Spring modulus k \[MPa/mm\].
    pub modulus_mpa_per_mm: f64,
    /// Shear stiffness of the layer G_p \[N/mm\] (0: a Winkler bed).
    pub shear_n_per_mm: f64,
}

impl BodyKind for PasternakBed {
    fn name(&self) -> String {
        self.name.clone().unwrap_or_else(|| "bed".into())
    }

    /// Strips only (the layer ties neighbours along x); the moduli checked as the library
    /// checks them.
    fn check(&self, at: &Placement) -> Result<()> {
        if at.zone.downcast::<StripsZone>().is_none() {
            return Err(misplaced(
                at,
                "a Pasternak bed lies under strips (zone kind \"strips\")",
            ));
        }
        contopt_core::check::positive("modulus_mpa_per_mm", self.modulus_mpa_per_mm)?;
        contopt_core::check::non_negative("shear_n_per_mm", self.shear_n_per_mm)?;
        Ok(())
    }

    fn memory(&self, at: &Placement) -> Option<u64> {
        at.layout
            .points()
            .and_then(|n| contopt_core::memory::bytes(&[n], STRIP_BYTES))
    }

    /// It stands on the zone's strips.
    fn owns_surface(&self) -> bool {
        false
    }

    /// The ground holds it.
    fn takes(&self, _zone: &Chosen<dyn ZoneKind>) -> Takes {
        Takes::Nothing
    }

    fn build(&self, at: &Placement, surface: Option<&Interface>) -> Result<Box<dyn ElasticBody>> {
        let own = own_surface(at, surface)?;
        let bed = Pasternak::on(
            self.name(),
            own,
            self.modulus_mpa_per_mm,
            self.shear_n_per_mm,
        )?;
        Ok(Box::new(bed))
    }
}
// ANCHOR_END: kind

// ANCHOR: design
/// A parabolic relief of the initial gap, Δh(x) = depth·(x/half_length)² along the zone's
/// first axis, and the contact solved under it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParabolicRelief {
    /// The relief at |x| = half_length \[mm\].
    pub depth_mm: f64,
    /// Where the relief reaches its depth \[mm\].
    pub half_length_mm: f64,
}

impl ParabolicRelief {
    /// Δh at `x` \[mm\].
    fn relief(&self, x: [f64; 3]) -> f64 {
        self.depth_mm * (x[0] / self.half_length_mm).powi(2)
    }
}

impl Design for ParabolicRelief {
    fn check(&self, _c: &Check) -> Result<()> {
        contopt_core::check::non_negative("depth_mm", self.depth_mm)?;
        contopt_core::check::positive("half_length_mm", self.half_length_mm)?;
        Ok(())
    }

    fn run(&self, c: &Context, report: &mut CaseReport) -> Result<Designed> {
        let started = std::time::Instant::now();
        let points = c.problem.interface().points();
        let change: Vec<f64> = points.iter().map(|&x| self.relief(x)).collect();
        let gap: Vec<f64> = (c.problem.initial_gap().iter())
            .zip(&change)
            .map(|(h, dh)| h + dh)
            .collect();
        let relieved = c.problem.with_initial_gap(&gap)?;
        let state = c.solver.solve_observed(&relieved, None, c.observer)?;
        report.time("solve", started);
        let dh_max = change.iter().copied().fold(0.0, f64::max);
        Ok(Designed {
            method: Some(Method::Other("parabolic_relief")),
            dh_max: Some(dh_max),
            gap_change: change,
            ..Designed::contact(state)
        })
    }
}
// ANCHOR_END: design
