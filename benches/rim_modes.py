"""Why the flat punch's conjugate-gradient steps grow with the grid: the rim's modes.

The rigid flat punch (radius a = N/4 cells on an N x N grid, as `halfspace_peers`) in
contact everywhere under its face is the linear system A p = 1 on the face's cells D, A the
half-space's influence of uniform pressure on square cells (Love's formula, E* = 1). Our
Polonsky-Keer preconditions it with the circulant inverse of the kernel masked to D,
P = R K^-1 R^T. This script measures, on the peers' geometry:

  * dense, N = 32 to 128: the spectrum of P A on D (its condition number, how many
    eigenvalues stand above 1.5 times the least, and the share of the top eigenvector on the
    outermost ring of cells, "the rim");
  * matrix-free (FFT), N = 64 to 1024: the steps of preconditioned conjugate gradients from
    the load spread over the face, to the solver's stop (sum |dp| / sum p < 1e-10), with P
    alone, with the rim deflated (Z: the outermost cells, or 2 x 2 blocks of them; A Z
    restricted by the kernel, each step one product A z more), and from a coarser grid's
    exact answer (nested start);
  * P less the Schur correction with K^-1's kernel cut off beyond 8 cells (local: the
    residual near the rim and a sparse solve on the band);
  * the edge-weighted forms of P (after the modified operators that invert the single layer
    exactly on a disk, Hiptmair, Jerez-Hanckes and Urzua-Torres): W^-1 P W with W = diag(sqrt
    of each cell's distance to the face's edge, d - 1/2 in cells), whose spectrum has a real
    part that stays put but is not symmetric, and its symmetric mean (W^-1 P W + W P W^-1) / 2,
    two masked circulants a step.

Run with numpy and scipy (the peers' venv has both):

    /path/to/venv/bin/python benches/rim_modes.py

Figures from it are in the book's performance chapter ("The flat punch's fine steps").
"""

import numpy as np
from scipy.linalg import cho_factor, cho_solve
from scipy.ndimage import distance_transform_edt
from scipy.sparse import csc_matrix
from scipy.sparse.linalg import factorized

TOLERANCE = 1e-10


def love(x, y, a, b):
    """Displacement at (x, y) under unit pressure on [-a, a] x [-b, b], times pi E*."""

    def f(u, v):
        r = np.sqrt(u * u + v * v)
        return u * np.log(v + r) + v * np.log(u + r)

    return (f(x + a, y + b) - f(x + a, y - b) - f(x - a, y + b) + f(x - a, y - b)) / np.pi


def grid(n):
    """The padded kernel, its spectrum, the face's mask and each face cell's distance in
    cells to the nearest cell outside it (1 on the rim)."""
    m = 2 * n
    idx = np.arange(m)
    idx = np.where(idx < n, idx, idx - m)
    x, y = np.meshgrid(idx * 1.0, idx * 1.0, indexing="ij")
    kernel = love(x, y, 0.5, 0.5)
    c = np.arange(n) - n / 2 + 0.5
    cx, cy = np.meshgrid(c, c, indexing="ij")
    face = cx**2 + cy**2 <= (n / 4) ** 2
    return kernel, np.fft.rfft2(kernel), face, distance_transform_edt(face)


def block(kernel, rows, cols):
    """The kernel's entries between the cells `rows` and `cols` (index pairs) of its padded
    grid."""
    m = kernel.shape[0]
    di = rows[:, 0][:, None] - cols[:, 0][None, :]
    dj = rows[:, 1][:, None] - cols[:, 1][None, :]
    return kernel[di % m, dj % m]


def exterior(n):
    """The inverse kernel of the padded grid and each padded cell's distance in cells to the
    face (0 on it)."""
    _, spectrum, face, _ = grid(n)
    m = 2 * n
    padded = np.zeros((m, m), dtype=bool)
    padded[:n, :n] = face
    return np.fft.irfft2(1.0 / spectrum, s=(m, m)), distance_transform_edt(~padded)


def operators(n):
    kernel, spectrum, face, dist = grid(n)
    m = 2 * n

    def a(x):
        padded = np.zeros((m, m))
        padded[:n, :n] = x
        return np.fft.irfft2(np.fft.rfft2(padded) * spectrum, s=(m, m))[:n, :n] * face

    def p(r):
        padded = np.zeros((m, m))
        padded[:n, :n] = r * face
        return np.fft.irfft2(np.fft.rfft2(padded) / spectrum, s=(m, m))[:n, :n] * face

    return kernel, face, dist, a, p


def spectrum_of_pa(n):
    """The face's cells, the eigenvalues of P A, the top eigenvector's share on the rim, the
    rim's cells, and the condition numbers of P A with P less the exact Schur correction
    through a band of exterior cells (K^-1_DE (K^-1_EE)^-1 K^-1_ED, E the cells outside the
    face within 1, 2 and 4 cells of it): how much of the excess lies just outside the rim."""
    kernel, _, face, dist = grid(n)
    inverse, outside = exterior(n)
    pts = np.argwhere(face)
    a = block(kernel, pts, pts)
    prec = block(inverse, pts, pts)
    lower = np.linalg.cholesky(prec)
    values, vectors = np.linalg.eigh(lower.T @ a @ lower)
    top = lower @ vectors[:, -1]
    rim = dist[pts[:, 0], pts[:, 1]] <= 1.0
    share = np.sum(top[rim] ** 2) / np.sum(top**2)
    banded = []
    for width in [1, 2, 4]:
        band = np.argwhere((outside > 0) & (outside <= width))
        coupling = block(inverse, pts, band)
        corrected = prec - coupling @ np.linalg.solve(block(inverse, band, band), coupling.T)
        c = np.linalg.cholesky(0.5 * (corrected + corrected.T))
        e = np.linalg.eigvalsh(c.T @ a @ c)
        banded.append(e.max() / e.min())
    return len(pts), values, share, rim.sum(), banded


def deflation(kernel, dist, n, side):
    """The rim's cells grouped in side x side squares: their indices, each one's group and
    E = Z^T A Z."""
    ij = np.argwhere(dist == 1.0)
    label = (ij[:, 0] // side) * (n // side + 1) + (ij[:, 1] // side)
    _, group = np.unique(label, return_inverse=True)
    groups = group.max() + 1
    z = np.zeros((len(ij), groups))
    z[np.arange(len(ij)), group] = 1.0
    e = z.T @ block(kernel, ij, ij) @ z
    return (ij[:, 0], ij[:, 1]), group, groups, e


def pcg(a, p, b, x, defl=None, tolerance=TOLERANCE):
    """Preconditioned conjugate gradients (deflated when `defl` is given) to `tolerance` on
    the step's change, conjugated by Polak-Ribiere as the solver (which a preconditioner
    that is not symmetric needs); returns the steps and the answer."""

    def project(z):
        if defl is None:
            return z
        at, group, groups, e = defl
        mu = np.linalg.solve(e, np.bincount(group, weights=a(z)[at], minlength=groups))
        z = z.copy()
        z[at] -= mu[group]
        return z

    if defl is not None:
        at, group, groups, e = defl
        mu = np.linalg.solve(e, np.bincount(group, weights=(b - a(x))[at], minlength=groups))
        x = x.copy()
        x[at] += mu[group]
    r = b - a(x)
    z = project(p(r))
    d, rz = z.copy(), np.sum(r * z)
    for step in range(1, 500):
        ad = a(d)
        alpha = rz / np.sum(d * ad)
        x = x + alpha * d
        r, last = r - alpha * ad, r
        if np.abs(alpha * d).sum() / np.abs(x).sum() < tolerance:
            return step, x
        z = project(p(r))
        beta = np.sum(z * (r - last)) / rz
        rz = np.sum(r * z)
        d = z + beta * d
    return step, x


def edge_weights(dist):
    """sqrt of each face cell's distance to the face's edge (d - 1/2 cells), 0 off it: the
    rigid punch's pressure falls as its inverse, 1/sqrt(d), at the rim."""
    return np.sqrt(np.maximum(dist - 0.5, 0.0))


def weighted_spectra(n):
    """The edge-weighted forms of P on the face, dense: the real parts' range and the largest
    imaginary part of W^-1 P W A's eigenvalues, and the condition number with the symmetric
    mean (W^-1 P W + W P W^-1) / 2."""
    kernel, _, face, dist = grid(n)
    inverse, _ = exterior(n)
    pts = np.argwhere(face)
    a = block(kernel, pts, pts)
    prec = block(inverse, pts, pts)
    w = edge_weights(dist)[pts[:, 0], pts[:, 1]]
    left = prec * w[None, :] / w[:, None]
    values = np.linalg.eigvals(left @ a)
    lower = np.linalg.cholesky(a)
    mean = np.linalg.eigvalsh(lower.T @ (0.5 * (left + left.T)) @ lower)
    return values.real.min(), values.real.max(), np.abs(values.imag).max(), mean.max() / mean.min()


def weighted(p, face, dist):
    """W^-1 P W and the symmetric mean (W^-1 P W + W P W^-1) / 2 as functions of the residual."""
    w = edge_weights(dist)
    inv = np.where(face, 1.0 / np.where(w > 0, w, 1.0), 0.0)
    return (lambda r: inv * p(w * r)), (lambda r: 0.5 * (inv * p(w * r) + w * p(inv * r)))


def schur_band(n, width):
    """P less its coupling through the exterior cells within `width` of the face (the exact
    Schur correction through that band: K^-1_DE (K^-1_EE)^-1 K^-1_ED, the band's own block
    factorised densely), as a function of the residual."""
    _, spectrum, face, _ = grid(n)
    m = 2 * n
    inverse, outside = exterior(n)
    band = np.argwhere((outside > 0) & (outside <= width))
    at = (band[:, 0], band[:, 1])
    factor = cho_factor(block(inverse, band, band))

    def inverse_of(field):
        return np.fft.irfft2(np.fft.rfft2(field) / spectrum, s=(m, m))

    def apply(r):
        field = np.zeros((m, m))
        field[:n, :n] = r * face
        y = inverse_of(field)
        through = np.zeros((m, m))
        through[at] = cho_solve(factor, y[at])
        return (y[:n, :n] - inverse_of(through)[:n, :n]) * face

    return apply


def local_schur_band(n, width, reach):
    """`schur_band` with K^-1's kernel cut off beyond `reach` cells (it falls like 1/r^3): the
    correction then reads the residual on the face's cells within `reach` of the band only,
    and the band's own block is sparse."""
    _, spectrum, face, dist = grid(n)
    m = 2 * n
    inverse, outside = exterior(n)
    band = np.argwhere((outside > 0) & (outside <= width))
    near = np.argwhere(face & (dist <= reach + 1))

    def cut(rows, cols):
        di = rows[:, 0][:, None] - cols[:, 0][None, :]
        dj = rows[:, 1][:, None] - cols[:, 1][None, :]
        values = inverse[di % m, dj % m]
        values[di * di + dj * dj > reach * reach] = 0.0
        return csc_matrix(values)

    solve = factorized(cut(band, band))
    coupling = cut(band, near)
    at = (near[:, 0], near[:, 1])

    def p(r):
        padded = np.zeros((m, m))
        padded[:n, :n] = r * face
        y = np.fft.irfft2(np.fft.rfft2(padded) / spectrum, s=(m, m))[:n, :n] * face
        y[at] -= coupling.T @ solve(coupling @ r[at])
        return y

    return p


def nested_start(n):
    """The coarser grid's answer (its own face, cells twice as wide, solved to 1e-13), each
    fine cell taking its coarse cell's pressure or, off the coarse face, the nearest coarse
    face cell's."""
    _, face_c, _, a_c, p_c = operators(n // 2)
    b = face_c * 1.0
    _, coarse = pcg(a_c, p_c, b, b, tolerance=1e-13)
    _, nearest = distance_transform_edt(~face_c, return_indices=True)
    return np.kron(coarse[nearest[0], nearest[1]], np.ones((2, 2)))


def main():
    print(
        "dense: N, face cells, rim cells, cond(PA), eigenvalues > 1.5 min, top's share on the"
        " rim; cond with the Schur correction through 1, 2, 4 exterior cells"
    )
    for n in [32, 64, 96, 128]:
        cells, values, share, rim, banded = spectrum_of_pa(n)
        print(
            f"{n:5d} {cells:6d} {rim:5d} {values.max() / values.min():7.3f}"
            f" {np.sum(values > 1.5 * values.min()):4d} {share:6.3f} "
            + " ".join(f"{c:6.3f}" for c in banded)
        )
    print(
        "dense, edge-weighted: N, W^-1 P W A's real parts (least, largest) and largest imaginary"
        " part, cond with the symmetric mean"
    )
    for n in [32, 64, 96]:
        low, high, imag, mean = weighted_spectra(n)
        print(f"{n:5d} {low:6.3f} {high:6.3f} {imag:6.3f} {mean:6.3f}")
    print(
        "steps to 1e-10: N, P alone, rim deflated (cells), (2 x 2 blocks: groups), nested start,"
        " P with the Schur correction through 4 exterior cells (up to 512: its band is dense),"
        " the same with K^-1 cut off beyond 8 cells, W^-1 P W, the symmetric mean"
    )
    for n in [64, 128, 256, 512, 1024]:
        kernel, face, dist, a, p = operators(n)
        b = face * 1.0
        uniform = face * (face.sum() / a(b).sum())
        steps = lambda start, defl=None: pcg(a, p, b, start, defl)[0]
        cells = deflation(kernel, dist, n, 1)
        blocks = deflation(kernel, dist, n, 2)
        start = nested_start(n) * face
        start *= np.sum(b * start) / np.sum(start * a(start))
        schur = pcg(a, schur_band(n, 4), b, uniform)[0] if n <= 512 else "-"
        left, mean = weighted(p, face, dist)
        print(
            f"{n:5d} {steps(uniform):4d} {steps(uniform, cells):4d} ({cells[2]})"
            f" {steps(uniform, blocks):4d} ({blocks[2]}) {steps(start):4d} {schur:>4}"
            f" {pcg(a, local_schur_band(n, 4, 8), b, uniform)[0]:4d}"
            f" {pcg(a, left, b, uniform)[0]:4d} {pcg(a, mean, b, uniform)[0]:4d}"
        )

if __name__ == "__main__":
    main()
