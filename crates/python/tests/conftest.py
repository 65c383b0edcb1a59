"""Shared helpers: the `contopt` command the results are compared with, and reports without
their timings (the one part of a report that differs between two runs)."""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]


@pytest.fixture(scope="session")
def contopt_bin():
    """The `contopt` command of this build (check.sh builds it and names it)."""
    path = os.environ.get("CONTOPT_BIN")
    if not path or not Path(path).is_file():
        pytest.skip("CONTOPT_BIN names no `contopt` binary (run crates/python/check.sh)")
    return path


def command_json(contopt_bin, scene, out):
    """`contopt run SCENE --json --quiet --jobs 1` as parsed JSON."""
    ran = subprocess.run(
        [contopt_bin, "run", str(scene), "--json", "--quiet", "--jobs", "1", "--out", str(out)],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert ran.returncode in (0, 3), ran.stderr
    return json.loads(ran.stdout)


def without_timings(report):
    """The report with every case's `timings_ms` taken out."""
    report = json.loads(json.dumps(report))
    for case in report["cases"]:
        case.pop("timings_ms", None)
    return report
