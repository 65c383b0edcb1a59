//! Linear-elastic finite-element bodies with quadratic isoparametric elements (8-node
//! serendipity and 9-node Lagrange quadrilaterals, 6-node triangles, alone or mixed in one
//! mesh), for axisymmetric, plane-stress and plane-strain analysis, as in the paper's examples
//! (§4: "quadratic isoparametric ring element").
//!
//! A [`FeModel`] holds a [`Mesh`], a [`Material`], an [`Analysis`], supports and loads;
//! [`FeModel::solve`] solves a supported model, and [`FeBody`] condenses a model to its contact
//! face as a [`contopt_core::ElasticBody`]. Two bodies whose contact faces are meshed apart
//! (non-matching nodes, curved faces) are paired segment to segment by a [`ContactPairing`].
//! Parts in three dimensions are [`solid`] bodies: quadratic tetrahedra and hexahedra.

mod analysis;
mod body;
pub mod coupled;
mod dissection;
pub mod element;
mod factor;
mod fields;
mod locking;
mod mesh;
mod model;
pub mod pairing;
mod recovery;
mod samples;
pub mod solid;
mod solution;
mod system;

pub use analysis::Analysis;
pub use body::{BuildStats, FeBody};
pub use contopt_core::Material;
pub use element::ElementKind;
pub use factor::{factorisations, Ordering};
pub use locking::{locking_warning, NEARLY_INCOMPRESSIBLE};
pub use mesh::{body_bytes, mesh_bytes, Face, Mesh, Spacing, MAX_AXIS_ELEMENTS};
pub use model::{Component, FeModel};
pub use pairing::{ContactPairing, PairingSettings, PairingSurvey};
pub use samples::FaceSample;
pub use solution::{Solution, Stress};
pub use system::RigidMotion;
