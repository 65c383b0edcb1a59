//! Bearing rollers (§3.1–3.2 of Páczelt 1994, after Páczelt & Szabó): the crown profiles in use
//! ([`Crown`]) and a roller on its raceway as two elastic half-space grids ([`Roller`]), the
//! roller floating under its load, with tilt; the crowns designed for an envelope of load
//! cases, the robust crown of the envelope load split ([`robust_crown`]) and the tuned
//! Fujiwara–Kawase profile ([`tune_fujiwara_kawase`]); the figures a report shows of each
//! case's contact ([`RollerFigures`]); and the bearing around the roller: the load distribution
//! over a cylindrical roller bearing's rollers by ISO/TS 16281's slice model
//! ([`CylindricalRollerBearing::solve`]), its rollers' loads and tilts as load cases
//! ([`bearing_cases`]), and its rating lives after ISO 281 and ISO/TS 16281
//! ([`dynamic_load_rating`], [`reference_rating_life`], [`miner`]), in hours and modified by
//! ISO 281's a_ISO ([`hours`], [`life_modification_factor`]).
//!
//! Coordinates: x along the roller axis (|x| ≤ l/2), y across the contact, z into the raceway.
//! Units: N, mm, MPa.

mod bearing;
mod crown;
mod design;
mod figures;
mod geometry;
mod life;
mod modified;
mod tolerance;

pub use bearing::{
    BearingLoad, BearingSettings, CylindricalRollerBearing, LoadDistribution, Raceway, RollerCase,
    RollerLoad, Tilt, LINE_CONTACT, LINE_EXPONENT,
};
pub use crown::{Crown, CrownSettings, JOHNS_GOHAR_END};
pub use design::{
    bearing_cases, design_case, load_cases, penalised_worst, robust_crown, solve_cases,
    tolerance_band, tune_fujiwara_kawase, tune_profile, tune_profile_coarse_to_fine, Contact,
    Envelope, Grid, LoadCase, Objective, ProfileFamily, RobustCrown, TunedCrown,
};
pub use figures::{end_ratio, CaseContact, CaseFigures, RollerFigures, EDGE_LOADING};
pub use geometry::{Roller, RollerEnds};
pub use life::{
    basic_rating_life, dynamic_load_rating, f_c, hertz_slice_load, miner,
    modified_reference_rating_life, reference_rating_life, slice_loads_from_pressure,
    slice_peaks_from_pressure, slice_ratings, ReferenceLife, SliceLoads, SliceRatings, B_M,
    REDUCTION, ROLLER_LIFE_EXPONENT,
};
pub use modified::{
    fatigue_load_limit, hours, life_modification_factor, rated_viscosity, static_load_rating,
    viscosity_at_temperature, A_ISO_MAX, FATIGUE_STRESS_MPA, ISO_VG_GRADES, KAPPA_MAX, KAPPA_MIN,
    OPERATING_TEMPERATURE_C, WALTHER_MIN_VISCOSITY,
};
pub use tolerance::{worst_in_box, CrownTolerances, WorstCrown, MAX_GRID, MIN_GRID, PARAMETERS};
