//! contopt from Python: the extension module `contopt._contopt` of the package `contopt`
//! (pyo3, maturin, the stable ABI from CPython 3.9). Scenes from a file, TOML text, a dict or a
//! bundled name, run with the GIL released into results with `result.json`'s names and units
//! (modules `scene`, `report`); below them the half-space grid, a rigid indenter from a numpy
//! gap, every contact solver and its typed termination (`library`), and the optimisation of
//! the initial gap (`optimise`). Errors are `ValueError`s that say where and what (`errors`);
//! long work runs off the calling thread, which keeps Ctrl-C and the progress callback
//! (`watch`).
//!
//! Build and test: `bash crates/python/check.sh` (a venv, maturin, pytest).

mod convert;
mod dense;
mod edge;
mod errors;
mod kinds;
mod library;
mod optimise;
mod report;
mod scene;
mod termination;
mod watch;

use pyo3::prelude::*;

/// contopt: elastic contact analysis and contact-pressure optimisation (Páczelt 1994).
/// Lengths in mm, moduli and pressures in MPa, forces in N; gaps in scene results in µm, as
/// `result.json` names them.
#[pymodule]
#[pyo3(name = "_contopt")]
fn contopt_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add("InputError", py.get_type::<errors::InputError>())?;
    m.add_class::<library::HalfSpace>()?;
    m.add_class::<dense::DenseBody>()?;
    m.add_class::<library::Contact>()?;
    m.add_class::<library::Solver>()?;
    m.add_class::<library::Solution>()?;
    m.add_function(wrap_pyfunction!(library::solve_in_rust, m)?)?;
    m.add_class::<optimise::Optimum>()?;
    m.add_function(wrap_pyfunction!(optimise::optimise, m)?)?;
    m.add_class::<termination::Termination>()?;
    m.add_class::<watch::Progress>()?;
    m.add_class::<kinds::Registry>()?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<report::Report>()?;
    m.add_class::<report::CaseResult>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
