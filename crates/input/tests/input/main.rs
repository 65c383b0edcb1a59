//! Whole documents read through `contopt-input`: where each kind of error points, enums, JSON,
//! editing a tree, hostile input.

mod enums;
mod errors;
mod hostile;
mod json;
mod nodes;

mod scene;
