//! Bearing rollers (§3.1–3.2 of Páczelt 1994, after Páczelt & Szabó): the crown profiles in use
//! ([`Crown`]) and a roller on its raceway as two elastic half-space grids ([`Roller`]), the
//! roller floating under its load, with tilt; the crowns designed for an envelope of load
//! cases, the robust crown of the envelope load split ([`robust_crown`]) and the tuned
//! Fujiwara–Kawase profile ([`tune_fujiwara_kawase`]); and the figures a report shows of each
//! case's contact ([`RollerFigures`]).
//!
//! Coordinates: x along the roller axis (|x| ≤ l/2), y across the contact, z into the raceway.
//! Units: N, mm, MPa.

mod crown;
mod design;
mod figures;
mod geometry;

pub use crown::{Crown, CrownSettings};
pub use design::{
    design_case, load_cases, penalised_worst, robust_crown, solve_cases, tune_fujiwara_kawase,
    Contact, Envelope, LoadCase, RobustCrown, TunedCrown,
};
pub use figures::{end_ratio, CaseContact, CaseFigures, RollerFigures, EDGE_LOADING};
pub use geometry::Roller;
