"""The library below the scenes from numpy: Hertz against the closed form, the arrays' shapes
and order, equilibrium Σp·A = F, every solver, stops that are returned, and bad input."""

import math
import os
import signal
import threading
import time
import warnings

import numpy as np
import pytest

import contopt

E, NU = 210e3, 0.3
ESTAR = E / (1 - NU**2)
R = 100.0  # sphere radius [mm]


def hertz(n=128, side=4.0, a=1.0):
    """A rigid sphere on the half-space, the force that gives the contact radius a [mm]."""
    h = side / n
    body = contopt.HalfSpace(nx=n, ny=n, dx_mm=h, dy_mm=h, e_mpa=E, nu=NU)
    gap = (body.x_mm**2 + body.y_mm**2) / (2 * R)
    force = 4 * ESTAR * a**3 / (3 * R)
    return body, gap, force


def test_hertz_from_numpy_against_the_closed_form():
    body, gap, force = hertz()
    solution = contopt.Solver("polonsky_keer", tolerance=1e-10).solve(
        contopt.Contact(body, gap, force_n=force)
    )
    assert solution.converged and solution.termination.kind == "converged"
    a = (3 * force * R / (4 * ESTAR)) ** (1 / 3)
    p0 = 3 * force / (2 * math.pi * a**2)
    # 32 cells per contact radius: the peak within 0.5 %, the approach a²/R within 0.5 %,
    # the contact area within 3 % (a ring of cells either way is 1/16 of πa²).
    assert solution.p_max_mpa == pytest.approx(p0, rel=5e-3)
    assert solution.approach_mm == pytest.approx(a**2 / R, rel=5e-3)
    assert solution.contact_area_mm2 == pytest.approx(math.pi * a**2, rel=3e-2)
    # The pressure along the centre row against p0·√(1 − r²/a²).
    row = solution.pressure_mpa[body.shape[0] // 2]
    x = body.x_mm[body.shape[0] // 2]
    y = body.y_mm[body.shape[0] // 2, 0]
    r2 = (x**2 + y**2) / a**2
    closed = p0 * np.sqrt(np.clip(1 - r2, 0, None))
    assert np.max(np.abs(row - closed)) < 0.03 * p0


def test_a_contact_cut_by_the_grid_edge_is_said():
    # a = 1 mm on a 4 mm square: inside, nothing said.
    body, gap, force = hertz(n=64)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        inside = contopt.Solver().solve(contopt.Contact(body, gap, force_n=force))
    assert inside.warnings == []
    # The force of a = 2.5 mm on the same square: the grid ends inside the contact (its
    # half-side is 2 mm), p_max misses Hertz's by far, and both the solution and Python say so.
    big = 4 * ESTAR * 2.5**3 / (3 * R)
    with pytest.warns(RuntimeWarning, match="reaches the grid's edge"):
        cut = contopt.Solver().solve(contopt.Contact(body, gap, force_n=big))
    assert len(cut.warnings) == 1 and "% of p_max" in cut.warnings[0]
    p0 = 3 * big / (2 * math.pi * 2.5**2)
    assert abs(cut.p_max_mpa / p0 - 1) > 0.1
    # A periodic grid has no edge.
    periodic = contopt.HalfSpace(
        nx=64, ny=64, dx_mm=4 / 64, dy_mm=4 / 64, e_mpa=E, nu=NU, periodic=True
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        repeated = contopt.Solver().solve(contopt.Contact(periodic, gap, force_n=big))
    assert repeated.warnings == []


def test_a_contact_on_too_few_cells_is_said():
    # a = 1 mm over cells of 0.5 mm (2 per radius): p_max 4 % below Hertz's p0, said with
    # the direction and the cell size that resolves it.
    body, gap, force = hertz(n=8)
    with pytest.warns(RuntimeWarning, match="spans 2.0 cells, fewer than 8"):
        coarse = contopt.Solver().solve(contopt.Contact(body, gap, force_n=force))
    assert len(coarse.warnings) == 1 and "cells of at most 0.1250 mm" in coarse.warnings[0]
    p0 = 3 * force / (2 * math.pi)
    assert coarse.p_max_mpa < 0.97 * p0
    # 8 cells per radius: nothing said.
    body, gap, force = hertz(n=32)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fine = contopt.Solver().solve(contopt.Contact(body, gap, force_n=force))
    assert fine.warnings == []
    # A roller as long as the grid touches all along it: only the width across is counted,
    # so nothing is said of its resolution; its straight ends are sharp edges, said alone.
    roller = contopt.HalfSpace(nx=8, ny=64, dx_mm=0.5, dy_mm=0.005, e_mpa=E, nu=NU)
    line = contopt.Contact(roller, roller.y_mm**2 / 10.0, force_n=400.0, indenter_ends="x")
    with pytest.warns(RuntimeWarning, match="ends at a sharp edge") as said:
        assert len(contopt.Solver().solve(line).warnings) == 1
    assert len(said) == 1 and "x = -1.7500 mm" in str(said[0].message)


def test_a_flat_punch_is_said_to_peak_at_its_sharp_rim():
    # A flat punch of radius a = 1 mm on cells of 3/64 mm (21 per radius): its peak is a rim
    # cell, where the row through the peak is a short chord (12 cells); the contact itself
    # spans 43 cells, so nothing is said of its resolution. Its pressure, Sneddon's
    # F/(2πa√(a² − r²)), is singular at the rim: the peak is the rim cell's value, and the
    # solve says so, as a scene's report does, naming the rim's point. Sneddon's approach
    # F/(2aE*): +0.3 % measured.
    n, a, force = 64, 1.0, 1000.0
    body = contopt.HalfSpace(nx=n, ny=n, dx_mm=3 / n, dy_mm=3 / n, e_mpa=E, nu=NU)
    gap = np.where(np.hypot(body.x_mm, body.y_mm) <= a, 0.0, 1.0)
    with pytest.warns(RuntimeWarning, match="the contact ends at a sharp edge") as said:
        punch = contopt.Solver().solve(contopt.Contact(body, gap, force_n=force))
    assert len(said) == 1 and punch.warnings == [str(said[0].message)]
    assert f"{punch.p_max_mpa:.1f} MPa" in punch.warnings[0]
    # The rim's cell stands well above Sneddon's mean F/(πa²) (the 1/√ singularity on cells).
    assert punch.p_max_mpa > 2 * force / (math.pi * a**2)
    assert punch.approach_mm == pytest.approx(force / (2 * a * ESTAR), rel=1e-2)
    # Hertz's pressure falls to nothing at its edge: no sharp edge (test_hertz… above, and
    # the sphere of test_a_contact_on_too_few_cells_is_said on 8 cells per radius).


def test_bodies_that_do_not_touch_are_said():
    body, gap, _ = hertz(n=32)
    with pytest.warns(RuntimeWarning, match="no cell carries pressure"):
        apart = contopt.Solver().solve(contopt.Contact(body, gap, approach_mm=-1e-3))
    assert apart.p_max_mpa == 0 and len(apart.warnings) == 1


def test_equilibrium_units_and_shapes():
    nx, ny, dx, dy = 48, 32, 0.05, 0.04
    body = contopt.HalfSpace(nx=nx, ny=ny, dx_mm=dx, dy_mm=dy, e_mpa=E, nu=NU)
    assert body.shape == (ny, nx) and body.cell_area_mm2 == pytest.approx(dx * dy)
    # Rows are y, columns x: a sphere off the centre towards +x.
    centre = (0.3, -0.1)
    gap = ((body.x_mm - centre[0]) ** 2 + (body.y_mm - centre[1]) ** 2) / (2 * R)
    assert np.allclose(body.x_mm[:, 1] - body.x_mm[:, 0], dx)
    assert np.allclose(body.y_mm[1, :] - body.y_mm[0, :], dy)
    force = 50.0
    solution = contopt.Solver().solve(contopt.Contact(body, gap, force_n=force))
    p = solution.pressure_mpa
    assert p.shape == (ny, nx) and solution.gap_mm.shape == (ny, nx)
    assert p.dtype == np.float64 and solution.contact.dtype == np.bool_
    # Σ p·A = F [MPa·mm² = N].
    assert np.sum(p) * dx * dy == pytest.approx(force, rel=1e-9)
    assert solution.force_n == pytest.approx(force, rel=1e-9)
    j, i = np.unravel_index(np.argmax(p), p.shape)
    assert abs(body.x_mm[j, i] - centre[0]) <= dx and abs(body.y_mm[j, i] - centre[1]) <= dy
    # Complementarity: no gap where pressed, no pressure where open.
    assert np.all(solution.gap_mm[solution.contact] < 1e-9)
    assert np.all(p[~solution.contact] == 0)
    assert solution.method == "polonsky_keer"  # what auto chose for a grid


def test_approach_control_gives_the_hertz_force():
    body, gap, force = hertz(n=64, a=1.0)
    solution = contopt.Solver("polonsky_keer", tolerance=1e-10).solve(
        contopt.Contact(body, gap, approach_mm=1.0**2 / R)
    )
    assert solution.approach_mm == 1.0**2 / R
    assert solution.force_n == pytest.approx(force, rel=2e-2)


def test_every_solver_with_its_defaults_agrees():
    body, gap, force = hertz(n=16, side=4.0, a=1.2)
    contact = contopt.Contact(body, gap, force_n=force)
    reference = contopt.Solver("qp").solve(contact)
    assert reference.converged
    for kind in contopt.Solver.kinds():
        defaults = contopt.Solver.defaults(kind)
        settings = {k: v for k, v in defaults.items() if v is not None}
        if kind == "penalty":
            settings["c_mpa_per_mm"] = 1e9
        if kind == "augmented_lagrangian":
            settings["c_mpa_per_mm"] = 1e7
        solver = contopt.Solver(kind, **settings)
        assert solver.kind == kind
        solution = solver.solve(contact)
        assert solution.converged, (kind, solution.termination)
        # The penalty is exact only as c → ∞: p to 1e-3 of p_max at c = 1e9 MPa/mm.
        tolerance = 1e-3 if kind == "penalty" else 1e-5
        error = np.max(np.abs(solution.pressure_mpa - reference.pressure_mpa))
        assert error < tolerance * reference.p_max_mpa, kind
        assert solution.force_n == pytest.approx(force, rel=1e-6)


def test_settings_and_defaults():
    assert contopt.Solver.defaults("polonsky_keer")["tolerance"] > 0
    assert contopt.Solver.defaults("penalty") == {"c_mpa_per_mm": None}
    solver = contopt.Solver("polonsky_keer", max_steps=7)
    assert solver.settings["max_steps"] == 7
    assert solver.settings["tolerance"] == contopt.Solver.defaults("polonsky_keer")["tolerance"]


def test_a_solve_that_stops_short_is_returned_with_its_termination():
    body, gap, force = hertz(n=64)
    solution = contopt.Solver("polonsky_keer", max_steps=3).solve(
        contopt.Contact(body, gap, force_n=force)
    )
    termination = solution.termination
    assert not solution.converged and termination.kind == "step_limit"
    assert termination.details["steps"] == 3
    assert termination.details["measure"] > termination.details["tolerance"]
    assert np.all(np.isfinite(solution.pressure_mpa))


@pytest.mark.parametrize(
    "make, key",
    [
        (lambda b, g: contopt.Contact(b, np.where(g > 0.001, np.nan, g), force_n=1.0), "gap_mm"),
        (lambda b, g: contopt.Contact(b, g[:, :-1], force_n=1.0), "gap_mm"),
        (lambda b, g: contopt.Contact(b, g), "force_n"),
        (lambda b, g: contopt.Contact(b, g, force_n=1.0, approach_mm=0.1), "force_n"),
        (lambda b, g: contopt.Contact(b, g, force_n=-1.0), "force_n"),
        (lambda b, g: contopt.Contact(b, g, approach_mm=math.inf), "approach_mm"),
        (lambda b, g: contopt.Contact(b, "not an array", force_n=1.0), "gap_mm"),
    ],
)
def test_bad_arrays_and_loads(make, key):
    body, gap, _ = hertz(n=16)
    with pytest.raises(contopt.InputError) as raised:
        make(body, gap)
    assert raised.value.key.startswith(key)
    assert isinstance(raised.value, ValueError)


def test_both_loads_or_neither_are_named_in_pythons_words():
    # The values as Python writes them: it said "force_n=Some(1.0), approach_mm=Some(0.1)".
    body, gap, _ = hertz(n=16)
    for kwargs, value in [
        (dict(force_n=1.0, approach_mm=0.1), "1.0 (and approach_mm = 0.1)"),
        (dict(), "None (and approach_mm = None)"),
    ]:
        with pytest.raises(contopt.InputError) as raised:
            contopt.Contact(body, gap, **kwargs)
        assert raised.value.key == "force_n" and raised.value.value == value
        assert "Some(" not in str(raised.value)


def test_nan_is_located():
    body, gap, _ = hertz(n=16)
    gap[3, 5] = np.nan
    with pytest.raises(contopt.InputError) as raised:
        contopt.Contact(body, gap, force_n=1.0)
    assert raised.value.key == "gap_mm[3, 5]" and raised.value.value == "NaN"


@pytest.mark.parametrize(
    "settings, key",
    [
        (dict(e_mpa=-210e3, nu=0.3), "e_mpa"),
        (dict(e_mpa=math.nan, nu=0.3), "e_mpa"),
        (dict(e_mpa=210e3, nu=0.5), "nu"),
    ],
)
def test_bad_moduli(settings, key):
    with pytest.raises(contopt.InputError) as raised:
        contopt.HalfSpace(nx=8, ny=8, dx_mm=0.1, dy_mm=0.1, **settings)
    assert raised.value.key == key and raised.value.allowed


def test_bad_grids_and_solvers():
    with pytest.raises(contopt.InputError):
        contopt.HalfSpace(nx=0, ny=8, dx_mm=0.1, dy_mm=0.1, e_mpa=E, nu=NU)
    with pytest.raises(contopt.InputError):
        contopt.HalfSpace(nx=8, ny=8, dx_mm=-0.1, dy_mm=0.1, e_mpa=E, nu=NU)
    with pytest.raises(contopt.InputError) as raised:
        contopt.Solver("newton")
    assert "polonsky_keer" in raised.value.allowed
    with pytest.raises(contopt.InputError):
        contopt.Solver("polonsky_keer", tolerence=1e-9)
    with pytest.raises(contopt.InputError):
        contopt.Solver("polonsky_keer", tolerance=-1.0)
    with pytest.raises(contopt.InputError):
        contopt.Solver("penalty")


def test_ctrl_c_stops_a_solve_on_the_calling_thread():
    # The solve runs on this thread with the GIL released; its own iterations run Python's
    # signal handlers, so Ctrl-C stops it and comes back as itself.
    body, gap, force = hertz(n=512)
    contact = contopt.Contact(body, gap, force_n=force)
    solver = contopt.Solver("polonsky_keer", tolerance=1e-12)
    start = time.perf_counter()
    solver.solve(contact)
    whole = time.perf_counter() - start
    timer = threading.Timer(0.2 * whole, os.kill, (os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        solver.solve(contact)
    timer.join()
    assert time.perf_counter() - start < 0.8 * whole


def test_the_gil_is_released_during_a_solve():
    # 512² cells: the solve must outlast 0.05 s for the ticks to tell (256² took 0.037 s in
    # the dev build once Polonsky-Keer's residual moved with the step's product).
    body, gap, force = hertz(n=512)
    contact = contopt.Contact(body, gap, force_n=force)
    solver = contopt.Solver("polonsky_keer", tolerance=1e-12)
    ticks = []
    running = threading.Event()

    def count():
        running.set()
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    done = threading.Event()
    other = threading.Thread(target=count)
    other.start()
    running.wait()
    start = time.perf_counter()
    solver.solve(contact)
    end = time.perf_counter()
    done.set()
    other.join()
    during = [t for t in ticks if start < t < end]
    # A solve that held the GIL would leave the other thread at most a tick or two
    # (sys.getswitchinterval); released, it ticks about every millisecond.
    assert end - start > 0.05
    assert len(during) > 0.2 * (end - start) / 0.001
