//! Bearing rollers (§3.1–3.2 of Páczelt 1994, after Páczelt & Szabó): the crown profiles in use
//! ([`Crown`]) and a roller on its raceway as two elastic half-space grids ([`Roller`]), the
//! roller floating under its load, with tilt.
//!
//! Coordinates: x along the roller axis (|x| ≤ l/2), y across the contact, z into the raceway.
//! Units: N, mm, MPa.

// Input checks are written `!(x > 0.0)` on purpose: the negation also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod crown;
mod geometry;

pub use crown::Crown;
pub use geometry::Roller;
