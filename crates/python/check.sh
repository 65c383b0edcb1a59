#!/usr/bin/env bash
# The Python package's tests, as CI runs them (after `cargo test --workspace`): a venv
# ($CONTOPT_VENV, by default .venv at the top of the repository) with maturin, pytest, numpy,
# mypy and matplotlib; the package built into it by `maturin develop` in the dev profile, in
# cargo's own target folder, so that only pyo3, numpy and this crate compile again (maturin
# builds pyo3 for an extension module; the rest is the test build's, as long as this package
# alone resolves its dependencies' features as the whole workspace does: Cargo.toml's
# [workspace.dependencies]); the `contopt` command the tests compare with, built with
# --workspace for the same reason (`-p contopt-cli` alone leaves out features that pyo3 and
# numpy add to syn and matrixmultiply, and the workspace would compile again); then pytest
# (the stubs by mypy.stubtest, the book's chapter "From Python" run).
set -euo pipefail
cd "$(dirname "$0")/../.."

venv="${CONTOPT_VENV:-$PWD/.venv}"
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install -q --disable-pip-version-check \
  "maturin>=1.9.4,<2" pytest numpy mypy matplotlib
VIRTUAL_ENV="$venv" "$venv/bin/maturin" develop -q -m crates/python/Cargo.toml
cargo build -q --workspace --bin contopt
CONTOPT_BIN="${CARGO_TARGET_DIR:-$PWD/target}/debug/contopt" \
  "$venv/bin/python" -m pytest -q crates/python/tests "$@"
