//! The scene crate's tests, linked as one binary (`cargo test -p contopt-scene --test all`; one
//! file's: `cargo test -p contopt-scene --test all solids::`). `fuzz` stays a binary of its own:
//! it bounds the process's heap with a global allocator.

mod bearing;
mod meshes;
mod new_user;
mod scenes;
mod solids;
