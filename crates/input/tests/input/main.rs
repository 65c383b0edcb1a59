//! Whole documents read through `contopt-input`: where each kind of error points, enums, JSON,
//! editing a tree, hostile input.

mod enums;
mod errors;
mod json;

mod scene;
