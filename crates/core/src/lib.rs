//! Core of contopt: the [`ElasticBody`] trait, the contact [`Interface`] a body exposes, how
//! an iterative method ends ([`Termination`]), what it reports on the way ([`observe`]) and
//! the loop that runs it ([`drive`]), the checks every input passes ([`check`]), and the
//! [`Error`] type shared by every crate of the workspace.
//!
//! Equation numbers refer to I. Páczelt, *Some new developments in contact pressure
//! optimization* (1994). Units throughout: N, mm, MPa.
//!
//! [`faer`] is re-exported: a body that overrides [`ElasticBody::influence_matrix`] returns
//! a `faer::Mat` without a faer dependency of its own.

mod body;
pub mod check;
pub mod drive;
mod error;
mod fields;
mod full_system;
mod gap_shape;
mod interface;
mod material;
pub mod memory;
pub mod observe;
mod rigid;
mod spares;
mod state;
pub mod stress;
mod termination;

pub use body::{block_among, ElasticBody, InfluenceShape, RigidMode};
pub use error::{Error, FieldError, Result};
pub use faer;
pub use fields::{BodyFields, Cell, CellKind};
pub use full_system::FullSystem;
pub use gap_shape::GapShape;
pub use interface::{Geometry, Interface, NormalsView, GEOMETRY_TOLERANCE};
pub use material::{Material, MaterialValues};
pub use rigid::RigidBody;
pub use spares::Spares;
pub use state::{ContactState, Residuals};
pub use stress::{
    Peak, Section, SectionAxis, SectionField, StressPeaks, StressTensor, Subsurface,
    SubsurfaceRequest,
};
pub use termination::{
    Constraint, Infeasibility, InteriorPointStatus, Quantity, Stall, Termination, Unboundedness,
};
