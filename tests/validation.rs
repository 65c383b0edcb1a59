//! The workspace's validation suites against closed forms and converged references, linked as
//! one test binary (`cargo test --test validation`; one suite: `cargo test --test validation
//! solid_validation::`). `mesh_budget` stays a binary of its own: it measures the process's peak
//! heap with a global allocator, which other tests running beside it would disturb.

mod bearing_validation;
mod contact_validation;
mod fe_stresses;
mod fem_validation;
mod fields_vtk;
mod greens_validation;
mod mesh_scenes;
mod optimise_validation;
mod pairing_validation;
mod solid_validation;
mod stress_suite;
