//! The nested start's prolongation: a coarse grid's pressure carried to the finer grid it
//! was coarsened from ([`InterfaceProblem::coarsen`](crate::InterfaceProblem::coarsen)).

/// Writes to `out` the pressure of each point of a fine problem from the coarse pressure
/// `coarse`, through `parent` (each fine point's coarse point). On an `nx` × `ny` cell grid
/// coarsened to `cx` × `cy` (`grids`, both x fastest), each fine cell inside the coarse
/// contact set takes the bilinear interpolation of the coarse cells about its centre, over
/// those that carry pressure (the weights of the others dropped and the rest rescaled), so
/// that the rim of the set keeps its coarse level instead of being pulled toward zero; a
/// point whose parent carries none stays at zero. Without grids, each point takes its
/// parent's pressure (piecewise constant).
///
/// Piecewise constant, the start is off by O(h) wherever the pressure varies; interpolated,
/// by O(h²) where it is smooth, and the fine grid's steps start nearer.
pub(crate) fn prolong(
    coarse: &[f64],
    parent: &[usize],
    grids: Option<([usize; 2], [usize; 2])>,
    out: &mut Vec<f64>,
) {
    out.clear();
    let Some(([nx, ny], [cx, cy])) = grids.filter(|g| fits(g, parent.len(), coarse.len())) else {
        out.extend(parent.iter().map(|&c| coarse[c]));
        return;
    };
    // Room for the whole: grown step by step, the vector would hold its old and new
    // buffers at once.
    out.reserve(nx * ny);
    let (fx, fy) = (nx.div_ceil(cx), ny.div_ceil(cy));
    for j in 0..ny {
        let (j0, j1, t) = between(j, fy, cy);
        for i in 0..nx {
            let here = coarse[parent[j * nx + i]];
            if here <= 0.0 {
                out.push(0.0);
                continue;
            }
            let (i0, i1, s) = between(i, fx, cx);
            let (mut sum, mut weight) = (0.0, 0.0);
            for (c, w) in [
                (j0 * cx + i0, (1.0 - s) * (1.0 - t)),
                (j0 * cx + i1, s * (1.0 - t)),
                (j1 * cx + i0, (1.0 - s) * t),
                (j1 * cx + i1, s * t),
            ] {
                if coarse[c] > 0.0 {
                    sum += w * coarse[c];
                    weight += w;
                }
            }
            out.push(if weight > 0.0 { sum / weight } else { here });
        }
    }
}

/// Whether the grids are an `nx` × `ny` grid of `fine` points and a `cx` × `cy` one of
/// `coarse` points, each side coarsened by one or two.
fn fits(&([nx, ny], [cx, cy]): &([usize; 2], [usize; 2]), fine: usize, coarse: usize) -> bool {
    let side = |n: usize, c: usize| c > 0 && (c == n || c == n.div_ceil(2));
    nx * ny == fine && cx * cy == coarse && side(nx, cx) && side(ny, cy)
}

/// The coarse cells k₀ ≤ k₁ about fine cell `i`'s centre along a side of `c` coarse cells
/// each `f` fine ones wide, and the weight of k₁: the centre lies at (i + ½)/f − ½ in coarse
/// cells; beyond the first or last coarse centre it takes that cell's value.
fn between(i: usize, f: usize, c: usize) -> (usize, usize, f64) {
    let u = (i as f64 + 0.5) / f as f64 - 0.5;
    let k0 = (u.floor().max(0.0) as usize).min(c - 1);
    let k1 = (k0 + 1).min(c - 1);
    let t = if k1 == k0 {
        0.0
    } else {
        (u - k0 as f64).clamp(0.0, 1.0)
    };
    (k0, k1, t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A linear pressure on a 4 × 3 coarse grid is carried exactly to the 8 × 6 fine grid's
    /// cells between the coarse centres (bilinear interpolation is exact on it), and held at
    /// the edge cells beyond them; a coarse cell without pressure leaves its fine cells at 0.
    #[test]
    fn linear_pressure_carried_exactly() {
        let (cx, cy, nx, ny) = (4, 3, 8, 6);
        let linear = |x: f64, y: f64| 10.0 + 2.0 * x + 3.0 * y;
        let coarse: Vec<f64> = (0..cx * cy)
            .map(|k| linear((k % cx) as f64, (k / cx) as f64))
            .collect();
        let parent: Vec<usize> = (0..nx * ny)
            .map(|k| (k / nx / 2) * cx + (k % nx) / 2)
            .collect();
        let mut out = vec![];
        prolong(&coarse, &parent, Some(([nx, ny], [cx, cy])), &mut out);
        for (k, &p) in out.iter().enumerate() {
            let u = ((k % nx) as f64 + 0.5) / 2.0 - 0.5;
            let v = ((k / nx) as f64 + 0.5) / 2.0 - 0.5;
            let want = linear(u.clamp(0.0, 3.0), v.clamp(0.0, 2.0));
            assert!((p - want).abs() < 1e-12, "cell {k}: {p} against {want}");
        }
        let mut holed = coarse.clone();
        holed[5] = 0.0;
        prolong(&holed, &parent, Some(([nx, ny], [cx, cy])), &mut out);
        for (k, &c) in parent.iter().enumerate() {
            assert_eq!(out[k] == 0.0, c == 5, "cell {k}");
        }
        prolong(&coarse, &parent, None, &mut out);
        assert!(parent.iter().zip(&out).all(|(&c, &p)| p == coarse[c]));
    }
}
