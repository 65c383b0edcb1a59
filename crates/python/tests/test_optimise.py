"""The optimisation of the initial gap from numpy against the closed form: a rigid flat punch
on the half-space whose gap is designed for a uniform pressure (v = 1 on a disc)."""

import math

import numpy as np
import pytest

import contopt

E, NU = 210e3, 0.3


def punch(n=48, side=4.0, a=1.5):
    h = side / n
    body = contopt.HalfSpace(nx=n, ny=n, dx_mm=h, dy_mm=h, e_mpa=E, nu=NU)
    r = np.hypot(body.x_mm, body.y_mm)
    disc = r < a
    gap = np.where(disc, 0.0, 1.0)  # open for good outside the punch
    return body, gap, disc, r, h


def elliptic_e(k):
    """The complete elliptic integral of the second kind E(k), by quadrature."""
    theta = np.linspace(0, math.pi / 2, 2001)
    values = np.sqrt(1 - np.multiply.outer(np.asarray(k) ** 2, np.sin(theta) ** 2))
    return np.trapezoid(values, theta, axis=-1)


@pytest.mark.parametrize("method", ["given_load", "linear_programme"])
def test_a_uniform_pressure_design_against_the_closed_form(method):
    body, gap, disc, r, h = punch()
    force = 1000.0
    contact = contopt.Contact(body, gap, force_n=force)
    optimum = contopt.optimise(
        contact,
        np.ones(body.shape),
        method=method,
        omega_v=disc,
        omega_opt=disc,
    )
    assert optimum.converged, optimum.termination
    area = disc.sum() * h * h
    p = force / area
    # v = 1 on Ω_v: the pressure is uniform there, p_max = F / A.
    assert optimum.p_max_mpa == pytest.approx(p, rel=1e-4)
    assert np.allclose(optimum.pressure_mpa[disc], p, rtol=1e-3)
    # The gap change that holds the pressure uniform is w(0) − w(r), with the deflection of a
    # uniform load p on a disc w(r) = 4(1 − ν²)pa/(πE)·E(r/a) inside it (Johnson eq. 3.39),
    # within 3 % of Δh_max on the disc of cells (a of the cells' area).
    a = math.sqrt(area / math.pi)
    w = 4 * (1 - NU**2) * p * a / (math.pi * E) * elliptic_e(np.clip(r[disc] / a, 0, 1))
    expected = w.max() - w
    change = optimum.gap_change_mm[disc]
    assert np.max(np.abs(change - expected)) < 0.03 * expected.max()
    assert np.all(optimum.gap_change_mm[~disc] == 0)


def test_a_crown_along_x_by_the_load_split_and_bad_input():
    # A cylinder (R = 5 mm) along x on a grid that covers its length: one design node per
    # column ("x"), Ω_v the centre row, v = 1 — the roller's crown of the book, small.
    nx, ny, h = 40, 21, 0.1
    body = contopt.HalfSpace(nx=nx, ny=ny, dx_mm=h, dy_mm=h / 4, e_mpa=E, nu=NU)
    # The cylinder ends where the grid does along x: its contact reaching there is its end.
    contact = contopt.Contact(body, body.y_mm**2 / 10.0, force_n=400.0, indenter_ends="x")
    centre = np.abs(body.y_mm) < 1e-12
    straight = contopt.Solver().solve(contact)
    optimum = contopt.optimise(contact, np.ones(body.shape), gap_shape="x", omega_v=centre)
    assert optimum.converged and optimum.method == "load_split"
    p = optimum.pressure_mpa[centre]
    assert np.allclose(p, optimum.p_max_mpa, rtol=1e-6)
    # The straight cylinder's ends carry the peaks (edge loading); the crown removes them.
    assert optimum.p_max_mpa < 0.9 * straight.p_max_mpa
    change = optimum.gap_change_mm
    assert np.all(change == change[0]) and optimum.dh_mm.shape == (nx,)
    assert np.argmax(optimum.dh_mm) in (0, nx - 1)
    with pytest.raises(contopt.InputError):
        contopt.optimise(contact, np.ones((3, 3)))
    with pytest.raises(contopt.InputError):
        contopt.optimise(contact, np.ones(body.shape), method="simplex")
    with pytest.raises(contopt.InputError):
        contopt.optimise(contact, np.ones(body.shape), tolerance=-1.0)
    assert contopt.Optimum.defaults("load_split")["tolerance"] > 0
    # A mask holds booleans (or 1/0): a controller's values given as Ω_v are refused with the
    # index, where every nonzero value used to count as True.
    with pytest.raises(contopt.InputError, match=r"omega_v\[0, 0\] = 0.5"):
        contopt.optimise(
            contact, np.ones(body.shape), gap_shape="x", omega_v=np.full(body.shape, 0.5)
        )
    ones = contopt.optimise(
        contact, np.ones(body.shape), gap_shape="x", omega_v=centre.astype(int)
    )
    assert np.array_equal(ones.pressure_mpa, optimum.pressure_mpa)
