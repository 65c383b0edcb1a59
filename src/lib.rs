//! # contopt
//!
//! Elastic contact analysis and contact-pressure optimisation after I. Páczelt,
//! *Some new developments in contact pressure optimization* (1994).
//!
//! This facade re-exports the workspace's crates:
//! - [`core`]: the [`ElasticBody`] trait, the contact [`Interface`], the [`Error`] type;
//! - [`fem`]: quadratic isoparametric finite-element bodies (axisymmetric, plane stress,
//!   plane strain) and the structured mesh generator;
//! - [`greens`]: bodies from closed-form Green's functions: the axisymmetric half-space and
//!   the half-plane;
//! - [`contact`]: the [`InterfaceProblem`](contact::InterfaceProblem) of two bodies (their
//!   influence operators; dense matrices on demand) and the
//!   [`ContactSolver`](contact::ContactSolver)s: QP, active set, penalty, augmented Lagrangian,
//!   and the matrix-free Polonsky–Keer;
//! - [`optimise`]: pressure [`Controller`](optimise::Controller)s and the
//!   [`Optimisation`](optimise::Optimisation) of the initial gap (§3): the iteration, the LP
//!   (3.5) and the load split;
//! - [`roller`]: bearing-roller geometry and crown profiles;
//! - [`scene`]: scene files (TOML/JSON) that build the bodies, solve and optimise, the one
//!   path to the paper's Tables 1–3, and the [`Report`](scene::Report) of a run;
//! - [`report`]: what users see of a run: tables, CSV and the plots (SVG and PNG).
//!
//! The paper's printed tables and the closed forms the code is checked against live outside
//! the library, in the `contopt-validation` crate (`validation/`), used by the tests, the
//! examples and `cargo xtask book`.
//!
//! ```
//! use contopt::fem::{Analysis, Component, ElementKind, FeModel, Material, Mesh, Spacing};
//!
//! // A 10 × 10 mm plane-stress plate, 1 mm thick, pulled by 100 MPa.
//! let s = Spacing::uniform(0.0, 10.0, 2)?;
//! let mesh = Mesh::rectangle(ElementKind::Q8, &s, &s)?;
//! let mut model = FeModel::new(mesh, Material::new(2e5, 0.3)?, Analysis::PlaneStress { thickness: 1.0 })?;
//! let left = model.mesh().nodes_on_x(0.0, 0.0, 10.0);
//! let corner = model.mesh().nodes_on_y(0.0, 0.0, 0.0);
//! let right = model.mesh().faces_on_x(10.0, 0.0, 10.0);
//! model.fix(&left, Component::X)?.fix(&corner, Component::Y)?.traction(&right, [100.0, 0.0])?;
//! let u = model.solve()?;
//! let tip = model.mesh().nodes_on_x(10.0, 0.0, 10.0)[0];
//! assert!((u.at(tip)[0] - 100.0 * 10.0 / 2e5).abs() < 1e-12); // σ L / E
//! # Ok::<(), contopt::Error>(())
//! ```

pub use contopt_contact as contact;
pub use contopt_core as core;
pub use contopt_core::{
    ContactState, ElasticBody, Error, GapShape, Geometry, Interface, Material, Peak, Residuals,
    Result, RigidBody, RigidMode, Section, SectionAxis, SectionField, StressPeaks, StressTensor,
    Subsurface, SubsurfaceRequest,
};
pub use contopt_fem as fem;
pub use contopt_greens as greens;
pub use contopt_optimise as optimise;
pub use contopt_optimise::Region;
pub use contopt_report as report;
pub use contopt_roller as roller;
pub use contopt_scene as scene;
