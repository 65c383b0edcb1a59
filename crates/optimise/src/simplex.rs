//! A derivative-free minimiser for a few parameters: the simplex method of Nelder and Mead.
//!
//! It serves the published way of designing a logarithmic crown, tuning its three parameters
//! against a pressure computed for each guess (Fujiwara & Kawase 2007 used Rosenbrock's
//! method), as a baseline for the optimised crowns. Written here rather than taken from a
//! crate: it is forty lines, and argmin would bring a random-number stack for them.

use contopt_core::{Error, Result};

/// Reflection, expansion, contraction and shrink coefficients (the standard 1, 2, ½, ½).
const REFLECT: f64 = 1.0;
const EXPAND: f64 = 2.0;
const CONTRACT: f64 = 0.5;
const SHRINK: f64 = 0.5;

/// The best point a simplex search found.
#[derive(Clone, Debug, PartialEq)]
pub struct Minimum {
    /// The parameters.
    pub x: Vec<f64>,
    /// The objective there.
    pub value: f64,
    /// How many times the objective was evaluated.
    pub evaluations: usize,
}

/// Minimises `objective` from `start` with a first simplex of steps `step` along each
/// parameter, until the values at the simplex's vertices differ by less than `tolerance`
/// (absolute) or `max_evaluations` is reached; the best vertex either way. An error of the
/// objective stops the search and is returned.
pub fn nelder_mead(
    mut objective: impl FnMut(&[f64]) -> Result<f64>,
    start: &[f64],
    step: &[f64],
    tolerance: f64,
    max_evaluations: usize,
) -> Result<Minimum> {
    if start.is_empty() || step.len() != start.len() {
        return Err(Error::invalid(
            "step",
            format!("{} steps for {} parameters", step.len(), start.len()),
            "one step per parameter, at least one parameter",
        ));
    }
    let evaluations = std::cell::Cell::new(0);
    let mut eval = |x: &[f64]| -> Result<f64> {
        evaluations.set(evaluations.get() + 1);
        objective(x).map(|f| if f.is_nan() { f64::INFINITY } else { f })
    };
    let mut simplex: Vec<(Vec<f64>, f64)> = vec![(start.to_vec(), eval(start)?)];
    for (k, s) in step.iter().enumerate() {
        let mut x = start.to_vec();
        x[k] += s;
        let f = eval(&x)?;
        simplex.push((x, f));
    }
    let n = start.len();
    let along = |from: &[f64], to: &[f64], t: f64| -> Vec<f64> {
        from.iter().zip(to).map(|(a, b)| a + t * (b - a)).collect()
    };
    for _ in 0..max_evaluations {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        if simplex[n].1 - simplex[0].1 <= tolerance || evaluations.get() >= max_evaluations {
            break;
        }
        let centroid: Vec<f64> = (0..n)
            .map(|k| simplex[..n].iter().map(|(x, _)| x[k]).sum::<f64>() / n as f64)
            .collect();
        let worst = simplex[n].clone();
        let reflected = along(&centroid, &worst.0, -REFLECT);
        let fr = eval(&reflected)?;
        if fr < simplex[0].1 {
            let expanded = along(&centroid, &worst.0, -EXPAND);
            let fe = eval(&expanded)?;
            simplex[n] = if fe < fr {
                (expanded, fe)
            } else {
                (reflected, fr)
            };
        } else if fr < simplex[n - 1].1 {
            simplex[n] = (reflected, fr);
        } else {
            let towards = if fr < worst.1 { &reflected } else { &worst.0 };
            let contracted = along(&centroid, towards, CONTRACT);
            let fc = eval(&contracted)?;
            if fc < worst.1.min(fr) {
                simplex[n] = (contracted, fc);
            } else {
                let best = simplex[0].0.clone();
                for vertex in simplex.iter_mut().skip(1) {
                    let x = along(&best, &vertex.0, SHRINK);
                    *vertex = (x.clone(), eval(&x)?);
                }
            }
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    let (x, value) = simplex.swap_remove(0);
    Ok(Minimum {
        x,
        value,
        evaluations: evaluations.get(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rosenbrock's valley from (−1.2, 1): the minimum (1, 1) to 1e-4, in a few hundred
    /// evaluations.
    #[test]
    fn finds_the_minimum_of_rosenbrocks_valley() {
        let f = |x: &[f64]| Ok(100.0 * (x[1] - x[0] * x[0]).powi(2) + (1.0 - x[0]).powi(2));
        let m = nelder_mead(f, &[-1.2, 1.0], &[0.5, 0.5], 1e-14, 2000).unwrap();
        assert!(
            (m.x[0] - 1.0).abs() < 1e-4 && (m.x[1] - 1.0).abs() < 1e-4,
            "{m:?}"
        );
        assert!(m.evaluations < 600, "{}", m.evaluations);
    }

    /// The budget holds, the objective's error stops the search, and bad steps are named.
    #[test]
    fn budget_errors_and_bad_input() {
        let f = |x: &[f64]| Ok(x[0] * x[0]);
        let m = nelder_mead(f, &[3.0], &[1.0], 0.0, 10).unwrap();
        assert!(m.evaluations <= 12 && m.value < 9.0, "{m:?}");
        let failing = |_: &[f64]| Err(Error::invalid("k", 1, "no"));
        assert!(nelder_mead(failing, &[0.0], &[1.0], 0.0, 10).is_err());
        let e = nelder_mead(f, &[0.0], &[], 0.0, 10).unwrap_err();
        assert!(e.to_string().contains("one step per parameter"), "{e}");
    }
}
