//! The roller crate's tests, linked as one binary (`cargo test -p contopt-roller --test all`).

mod design;
mod roller;
