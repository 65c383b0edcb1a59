//! Core of contopt: the [`ElasticBody`] trait, the contact [`Interface`] a body exposes, and the
//! [`Error`] type shared by every crate of the workspace.
//!
//! Equation numbers refer to I. Páczelt, *Some new developments in contact pressure
//! optimization* (1994). Units throughout: N, mm, MPa.

mod body;
mod error;
mod gap_shape;
mod interface;
mod material;
pub mod memory;
pub mod observe;
mod rigid;
mod state;
pub mod stress;

pub use body::{ElasticBody, RigidMode};
pub use error::{Error, Result};
pub use gap_shape::GapShape;
pub use interface::{Geometry, Interface, GEOMETRY_TOLERANCE};
pub use material::Material;
pub use rigid::RigidBody;
pub use state::{ContactState, Residuals, Status};
pub use stress::{
    Peak, Section, SectionAxis, SectionField, StressPeaks, StressTensor, Subsurface,
    SubsurfaceRequest,
};
