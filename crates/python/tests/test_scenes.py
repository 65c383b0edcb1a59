"""Scenes from Python: the four ways to read one, edits, check(), errors with their place,
results with result.json's names and units, and every bundled scene's report equal to
`contopt run --json`'s except its timings."""

import json
import os
import re
import signal
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import contopt
from conftest import ROOT, command_json, without_timings

# Scenes that take more than a few seconds in the dev profile: compared on coarser grids, the
# same reduced file run by the command and by Python. (name, pattern, replacement)
REDUCED = {
    "roller-study": (r"cells = \[200, 105\]", "cells = [40, 21]"),
    "roller-envelope": (r"cells = \[200, 105\]", "cells = [40, 21]"),
    "bearing": (r"cells = \[80, 49\]", "cells = [16, 9]"),
}


@pytest.mark.parametrize("name", contopt.Scene.bundled_names())
def test_every_bundled_scene_equals_the_command(name, contopt_bin, tmp_path):
    if name in REDUCED:
        pattern, replacement = REDUCED[name]
        text, count = re.subn(pattern, replacement, contopt.Scene.bundled_text(name))
        assert count == 1, "the reduction no longer applies: update REDUCED"
        scene_file = tmp_path / f"{name}.toml"
        scene_file.write_text(text)
        scene = contopt.Scene.from_file(scene_file)
        expected = command_json(contopt_bin, scene_file, tmp_path / "out")
    else:
        scene = contopt.Scene.bundled(name)
        expected = command_json(contopt_bin, name, tmp_path / "out")
    report = scene.run(threads=2)
    assert without_timings(json.loads(report.to_json())) == without_timings(expected)
    assert report.solved == all(c["status"] == "solved" for c in expected["cases"])


def hertz_text():
    return contopt.Scene.bundled_text("hertz")


def test_file_text_dict_and_bundled_agree(tmp_path):
    scene_file = tmp_path / "hertz.toml"
    scene_file.write_text(hertz_text())
    data = contopt.Scene.bundled("hertz").run().to_dict()["cases"][0]["input"]
    scenes = [
        contopt.Scene.bundled("hertz"),
        contopt.Scene.from_file(scene_file),
        contopt.Scene.from_toml(hertz_text()),
        contopt.Scene.from_dict(data),
    ]
    reports = [without_timings(s.run().to_dict()) for s in scenes]
    assert all(r == reports[0] for r in reports)


def test_edits_change_what_is_solved():
    scene = contopt.Scene.bundled("hertz", edits={"contact.load.force_n": 125.0})
    base = contopt.Scene.bundled("hertz").run().cases[0]
    edited = scene.run().cases[0]
    # Hertz: p0 ∝ F^(1/3), so an eighth of the force halves the peak (to the grid's error).
    assert edited.p_max_mpa == pytest.approx(base.p_max_mpa / 2, rel=1e-2)
    assert edited.input["contact"]["load"]["force_n"] == 125.0
    solver = {"kind": "polonsky_keer", "max_steps": 3}
    short = contopt.Scene.from_toml(hertz_text(), edits={"solver": solver}).run().cases[0]
    assert short.input["solver"]["polonsky_keer"]["max_steps"] == 3
    assert not short.solved and short.termination.kind == "step_limit"


def test_check_says_what_each_case_needs():
    checked = contopt.Scene.bundled("paper-table1").check()
    assert [c["label"] for c in checked] == contopt.Scene.bundled("paper-table1").cases
    assert all(0 < c["memory_estimate_bytes"] <= c["memory_limit_bytes"] for c in checked)


def test_results_have_the_schema_names_units_and_equilibrium():
    scene = contopt.Scene.bundled("hertz")
    case = scene.run().cases[0]
    n = len(case.interface)
    assert case.p_mpa.shape == (n,) and case.x_mm.shape == (n, 3)
    assert case.d_um.shape == case.dh_um.shape == case.h_um.shape == (n,)
    assert case.termination.kind == case.to_dict()["termination"]["kind"] == "converged"
    assert case.p_max_mpa == pytest.approx(case.p_mpa.max())
    assert case.approach_um > 0 and case.hertz is not None
    # The grid's cells x fastest; Σ p·A = F over cells of 0.0125 × 0.0125 mm.
    x, y = case.x_mm[:, 0], case.x_mm[:, 1]
    assert np.all(np.diff(x[:64]) > 0) and np.all(y[:64] == y[0])
    assert np.sum(case.p_mpa) * 0.0125**2 == pytest.approx(1000.0, rel=1e-6)
    with pytest.raises(AttributeError):
        case.p_max_psi


def test_write_gives_the_files_of_the_command(contopt_bin, tmp_path):
    report = contopt.Scene.bundled("paper-table1").run()
    folder = report.write(tmp_path / "py")
    command_json(contopt_bin, "paper-table1", tmp_path / "cli")
    ours = sorted(p.name for p in Path(folder).iterdir())
    theirs = sorted(p.name for p in (tmp_path / "cli" / "paper-table1").iterdir())
    assert ours == theirs and "result.json" in ours
    written = json.loads((Path(folder) / "result.json").read_text())
    assert without_timings(written) == without_timings(report.to_dict())


def test_a_scene_error_says_where_and_what(tmp_path):
    text = hertz_text().replace("nu = 0.3", "nu = 0.7")
    scene_file = tmp_path / "bad.toml"
    scene_file.write_text(text)
    with pytest.raises(contopt.SceneError) as raised:
        contopt.Scene.from_file(scene_file)
    e = raised.value
    assert isinstance(e, ValueError)
    line = next(k for k, l in enumerate(text.splitlines(), 1) if "nu = 0.7" in l)
    assert (e.file, e.line, e.key) == (str(scene_file), line, "body[0].material.nu")
    assert e.column == text.splitlines()[line - 1].index("0.7") + 1
    assert e.value == "0.7" and "0.5" in e.allowed
    assert str(e).startswith(f"{scene_file}:{line}:{e.column}: ")


def test_scene_errors_of_every_source(tmp_path):
    with pytest.raises(FileNotFoundError):
        contopt.Scene.from_file(tmp_path / "missing.toml")
    with pytest.raises(contopt.SceneError) as raised:
        contopt.Scene.bundled("hertz", edits={"contact.zone.cells": [64, -1]})
    assert raised.value.key.startswith("contact.zone.cells")
    with pytest.raises(contopt.SceneError) as raised:
        contopt.Scene.from_dict({"name": "x", "contact": {"zone": {"kind": "moon"}}})
    assert raised.value.file == "<dict>" and "contact.zone" in raised.value.key
    with pytest.raises(contopt.SceneError):
        contopt.Scene.bundled("no-such-scene")
    with pytest.raises(contopt.SceneError):
        contopt.Scene.from_toml("name = ")
    with pytest.raises(contopt.InputError):
        contopt.Scene.bundled("hertz").run(threads=0)


def test_progress_reaches_the_callback_and_its_exception_comes_back():
    seen = []
    contopt.Scene.bundled("paper-table1").run(progress=seen.append)
    assert seen[-1].cases_done == seen[-1].cases == 5

    class Enough(Exception):
        pass

    def stop(progress):
        raise Enough(progress)

    scene = contopt.Scene.bundled("roller-study")
    start = time.perf_counter()
    with pytest.raises(Enough) as raised:
        scene.run(progress=stop)
    assert isinstance(raised.value.args[0], contopt.Progress)
    assert time.perf_counter() - start < 10


def threads_of_this_process():
    return len(os.listdir("/proc/self/task"))


def test_ctrl_c_stops_a_long_run_and_leaves_no_threads():
    before = threads_of_this_process()
    scene = contopt.Scene.bundled("roller-study")
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        scene.run(threads=2)
    timer.join()
    # Stopped at the next iteration, not at the end of the run (30 s in the dev profile).
    assert time.perf_counter() - start < 10
    for _ in range(100):
        if threads_of_this_process() <= before:
            break
        time.sleep(0.01)
    assert threads_of_this_process() <= before


def test_no_thread_pool_is_left_behind():
    before = threads_of_this_process()
    contopt.Scene.bundled("paper-table1").run(threads=2)
    body = contopt.HalfSpace(nx=32, ny=32, dx_mm=0.1, dy_mm=0.1, e_mpa=2e5, nu=0.3)
    gap = (body.x_mm**2 + body.y_mm**2) / 20.0
    contopt.Solver().solve(contopt.Contact(body, gap, force_n=10.0))
    for _ in range(100):
        if threads_of_this_process() <= before:
            break
        time.sleep(0.01)
    # At most as many: a thread of an earlier test (a timer, a GIL probe) may end meanwhile.
    assert threads_of_this_process() <= before
