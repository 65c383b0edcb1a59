//! Fixtures outside the library crates: the paper's printed Tables 1–3 and the runs of the
//! bundled scenes that reproduce them ([`paper`]). The scenes in `scenes/` are the one path to
//! the paper's cases: the tests, the examples and the book's generator use them through here.
//! The closed forms of elasticity the tests compare with are written once, in [`closed_form`];
//! those of a roller bearing's load distribution (Stribeck, Harris), in [`bearing`]; the
//! bearing roller's half-space grid the optimisation benchmarks share, in [`roller`].

pub mod bearing;
pub mod closed_form;
pub mod fixtures;
pub mod paper;
pub mod roller;
pub mod solids;
