//! The command's tests, linked as one binary (`cargo test -p contopt-cli --test all`; one file's:
//! `cargo test -p contopt-cli --test all hostile::`).

mod bundled;
mod cli;
mod commands;
mod common;
mod hostile;
mod many_cases;
