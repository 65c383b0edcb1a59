"""The package's stubs (contopt/_contopt.pyi) against the module as built: mypy.stubtest."""

import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent


def test_stubs_match_the_module(tmp_path):
    ran = subprocess.run(
        [
            sys.executable,
            "-m",
            "mypy.stubtest",
            "contopt",
            "--allowlist",
            str(HERE / "stubtest-allowlist.txt"),
        ],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert ran.returncode == 0, ran.stdout + ran.stderr
