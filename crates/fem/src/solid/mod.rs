//! Solid bodies in three dimensions: 10-node tetrahedra and 20- and 27-node hexahedra (Gmsh's
//! types 11, 17 and 12), linear-elastic and isotropic, with supports and symmetry planes on
//! nodes, pressures and tractions on faces; a [`SolidBody`] is one side of a 2-D contact
//! region, sampled at its faces' Gauss points (against a rigid body or a partner sampled
//! there) or over cells, each read as its mean over the faces (a half-space grid's,
//! [`SolidSample::cells`]; another solid's, [`SolidSample::facing`]).

mod body;
mod element;
mod fields;
mod fill;
mod mesh;
mod model;
mod precondition;
mod rank;
mod sample;
mod system;

pub use body::{Condensation, SolidBody, SolidSettings, SolidStats, DENSE_POINTS};
pub use element::{FaceKind, SolidKind, MAX_FACE_NODES, MAX_SOLID_NODES};
pub use mesh::{element_fault, ElementFault, FacePoint, SolidFace, SolidMesh};
pub use model::{Axis, SolidModel};
pub use precondition::PRECONDITIONED_POINTS;
pub use rank::{dependent_samples, DEPENDENT};
pub use sample::{Cell, SolidSample, SubSample, MAX_SUB_PARTS, SUB_PARTS_PER_FACE};
