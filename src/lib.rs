//! # contopt
//!
//! Elastic contact analysis and contact-pressure optimisation after I. Páczelt,
//! *Some new developments in contact pressure optimization* (1994).
//!
//! This facade re-exports the workspace's crates, and [`prelude`] the names a program needs:
//! - [`core`]: the [`ElasticBody`] trait, the contact [`Interface`], [`Termination`], the
//!   observers ([`core::observe`]), the checks, the [`Error`] type, and [`faer`] (a body that
//!   returns its own influence matrix needs no faer of its own);
//! - [`fem`]: quadratic isoparametric finite-element bodies (axisymmetric, plane stress,
//!   plane strain) and the structured mesh generator;
//! - [`greens`]: bodies from closed-form Green's functions (half-space grids, rings, strips) and
//!   the Winkler bed;
//! - [`contact`]: the [`InterfaceProblem`](contact::InterfaceProblem) of two bodies and the
//!   [`ContactSolver`](contact::ContactSolver)s, each built from its settings
//!   ([`SolverSettings`](contact::SolverSettings));
//! - [`optimise`]: pressure [`Controller`](optimise::Controller)s and the
//!   [`Optimisation`](optimise::Optimisation) of the initial gap (§3);
//! - [`roller`]: bearing rollers: crowns, and the designs of a crown for an envelope of loads;
//! - [`scene`] (feature `scene`, on by default): scene files composed of a zone, two bodies, a
//!   gap, a load, a solver and a design, and their run;
//! - [`results`] (with `scene` or `plot`): what a run reports, its schema and JSON Schema;
//! - [`report`] (feature `plot`, on by default): tables, CSV files and charts.
//!
//! `contopt = { …, default-features = false }` leaves the scene reader and the charts out.
//!
//! ```
//! use contopt::prelude::*;
//! use contopt::fem::{Analysis, Component, ElementKind, FeModel, Mesh, Spacing};
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
pub use contopt_core::faer;
pub use contopt_core::{
    ContactState, ElasticBody, Error, GapShape, Geometry, Interface, Material, Peak, Residuals,
    Result, RigidBody, RigidMode, Section, SectionAxis, SectionField, StressPeaks, StressTensor,
    Subsurface, SubsurfaceRequest, Termination,
};
pub use contopt_fem as fem;
pub use contopt_greens as greens;
pub use contopt_optimise as optimise;
pub use contopt_optimise::Region;
#[cfg(feature = "plot")]
pub use contopt_report as report;
#[cfg(any(feature = "scene", feature = "plot"))]
pub use contopt_results as results;
pub use contopt_roller as roller;
#[cfg(feature = "scene")]
pub use contopt_scene as scene;

/// The names a program that builds bodies, solves contacts and optimises gaps needs:
/// `use contopt::prelude::*;`.
pub mod prelude {
    pub use contopt_contact::{
        ActiveSet, ActiveSetSettings, AugmentedLagrangian, AugmentedLagrangianSettings, Auto,
        ContactSolver, FullPenalty, InterfaceProblem, Penalty, PenaltySettings, PolonskyKeer,
        PolonskyKeerSettings, Qp, QpSettings, SolverSettings,
    };
    pub use contopt_core::observe::{Event, Flow, Method, Nested, Observer, Silent};
    pub use contopt_core::{
        ContactState, ElasticBody, Error, GapShape, Geometry, Interface, Material, Result,
        RigidBody, RigidMode, Section, SectionAxis, StressTensor, Subsurface, SubsurfaceRequest,
        Termination,
    };
    pub use contopt_greens::{AxisymmetricHalfSpace, HalfPlane, HalfSpace, Winkler};
    pub use contopt_optimise::{
        Constant, Controller, ControllerSettings, IterationSettings, LinearProgrammeSettings,
        LoadSplitSettings, Mode, Optimisation, OptimisationMethod, Optimum, Profile, Reference,
        Region, SearchSettings,
    };
    #[cfg(any(feature = "scene", feature = "plot"))]
    pub use contopt_results::CaseReport;
    #[cfg(feature = "scene")]
    pub use contopt_scene::{Case, Scene, SceneError};
}
