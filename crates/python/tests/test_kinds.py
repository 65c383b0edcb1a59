"""Kinds from Python: the library's listed; a body given by a dense compliance matrix from
numpy, in the library (a Winkler bed as a diagonal against the flat punch's closed form, Love's
matrix against the built-in half-space) and in scenes (a factory registered as a body kind);
bad matrices refused by name; a factory's own exception raised as itself."""

import numpy as np
import pytest

import contopt

E, NU = 210e3, 0.3
R = 100.0  # sphere radius [mm]


def test_the_library_kinds_are_listed():
    kinds = contopt.Registry.standard().kinds()
    assert kinds["bodies"][:2] == ["rigid", "half_space"] and "winkler" in kinds["bodies"]
    assert "grid" in kinds["zones"] and "sphere" in kinds["gaps"]
    assert "given_load" in kinds["designs"] and "polonsky_keer" in kinds["solvers"]


def love_matrix(body):
    """The half-space's compliance [mm/N] on `body`'s cells from Love's rectangle (Johnson,
    eq. 3.25): entry [i, j] the deflection at cell i's centre under 1 N spread on cell j."""
    x, y = body.x_mm.ravel(), body.y_mm.ravel()
    dx, dy = body.cell_mm
    a, b = dx / 2, dy / 2
    X, Y = x[:, None] - x[None, :], y[:, None] - y[None, :]

    def term(t, s1, s2):
        at = np.where(t == 0, 1.0, np.abs(t))
        return np.where(t == 0, 0.0, t * (np.arcsinh(s1 / at) - np.arcsinh(s2 / at)))

    love = term(X + a, Y + b, Y - b) + term(Y + b, X + a, X - a)
    love += term(X - a, Y - b, Y + b) + term(Y - b, X - a, X + a)
    return (1 - NU**2) / (np.pi * E) * love / (dx * dy)


def test_love_from_numpy_gives_the_built_in_half_space():
    n, h = 16, 0.2
    grid = contopt.HalfSpace(nx=n, ny=n, dx_mm=h, dy_mm=h, e_mpa=E, nu=NU)
    dense = contopt.DenseBody(love_matrix(grid), nx=n, ny=n, dx_mm=h, dy_mm=h)
    gap = (grid.x_mm**2 + grid.y_mm**2) / (2 * R)
    solver = contopt.Solver("active_set")
    ours = solver.solve(contopt.Contact(grid, gap, force_n=200.0))
    theirs = solver.solve(contopt.Contact(dense, gap, force_n=200.0))
    assert ours.converged and theirs.converged
    p = ours.pressure_mpa
    assert np.max(np.abs(theirs.pressure_mpa - p)) <= 1e-9 * p.max()
    assert theirs.approach_mm == pytest.approx(ours.approach_mm, rel=1e-9)


def test_a_winkler_bed_as_a_diagonal_gives_the_flat_punch():
    n, h, k, force = 8, 0.5, 50.0, 1000.0  # k [MPa/mm]
    area = h * h
    bed = contopt.DenseBody(np.eye(n * n) / (k * area), nx=n, ny=n, dx_mm=h, dy_mm=h)
    solution = contopt.Solver().solve(contopt.Contact(bed, np.zeros((n, n)), force_n=force))
    # A flat punch on springs sinks evenly: p = F/A and δ = p/k.
    p = force / (n * n * area)
    assert np.allclose(solution.pressure_mpa, p, rtol=1e-10, atol=0)
    assert solution.approach_mm == pytest.approx(p / k, rel=1e-10)


@pytest.mark.parametrize(
    "matrix, key, says",
    [
        (np.ones(4), "compliance_mm_per_n", "2-D"),
        (np.ones((2, 3)), "compliance", "a square matrix"),
        (np.eye(3), "compliance", "2 × 2, one row and column per contact point"),
        (np.array([[1.0, np.nan], [np.nan, 1.0]]), "compliance[0, 1]", "must be finite"),
        (np.array([[1.0, 0.5], [0.4, 1.0]]), "compliance[0, 1]", "symmetric"),
        (np.array([[1.0, 2.0], [2.0, 1.0]]), "compliance", "Cholesky pivot 1 is -3e0"),
    ],
)
def test_bad_matrices_are_refused_by_name(matrix, key, says):
    with pytest.raises(contopt.InputError) as raised:
        contopt.DenseBody(matrix, nx=2, ny=1, dx_mm=1.0, dy_mm=1.0)
    assert raised.value.key == key and says in str(raised.value), str(raised.value)


def bed_scene(kind):
    return contopt.Scene.bundled_text("winkler-bed").replace('kind = "winkler"', f'kind = "{kind}"')


def test_a_scene_names_a_body_kind_made_in_numpy():
    seen = {}

    def springs(settings, points_mm, area_mm2):
        seen.update(settings=settings, points=points_mm.shape, area=area_mm2.shape)
        return np.diag(1 / (settings["modulus_mpa_per_mm"] * area_mm2))

    registry = contopt.Registry.standard()
    registry.add_body("my_bed", springs)
    assert "my_bed" in registry.kinds()["bodies"]
    ours = contopt.Scene.from_toml(bed_scene("my_bed"), registry=registry).run().cases[0]
    assert seen == dict(settings={"modulus_mpa_per_mm": 50.0}, points=(200, 3), area=(200,))
    # The library's own bed on the same rings.
    theirs = contopt.Scene.bundled("winkler-bed").run().cases[0]
    assert ours.p_max_mpa == pytest.approx(theirs.p_max_mpa, rel=1e-9)
    # Without the registry the kind is unknown, at its place.
    with pytest.raises(contopt.SceneError) as raised:
        contopt.Scene.from_toml(bed_scene("my_bed"))
    assert raised.value.key == "body[0].kind" and "my_bed" in str(raised.value)


def test_a_factory_exception_comes_back_as_itself():
    class Refused(Exception):
        pass

    def factory(settings, points_mm, area_mm2):
        raise Refused("no matrix today")

    registry = contopt.Registry.standard()
    registry.add_body("my_bed", factory)
    scene = contopt.Scene.from_toml(bed_scene("my_bed"), registry=registry)
    with pytest.raises(Refused, match="no matrix today"):
        scene.run()
