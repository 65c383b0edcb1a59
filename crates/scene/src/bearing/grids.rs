//! The grids a bearing's contacts are solved on. The case's own contact problem is laid out
//! for the design load: its cells across are sized for that load's Hertz half-width b. A
//! roller far lighter (a light load case of a duty cycle, a roller at the edge of the loaded
//! zone) touches over a small part of that grid, and one far heavier reaches past it; each is
//! solved instead on a grid of the same cells sized for its load's class ([`grid_load`]), so
//! that every contact's own half-width spans between half and all of the cells the design
//! load's spans (issue 35, point 1).
//!
//! The grids share the design grid's cells along the roller and their ordering, so that a
//! crown designed on the design grid (a gap change extruded across, a function of x alone)
//! is the same vector on each of them.

use contopt_contact::InterfaceProblem;
use contopt_core::{check, ContactState, ElasticBody, Result};
use contopt_roller::{
    bearing_cases, tolerance_band, LoadCase, Roller, RollerCase, RollerEnds, RollerFigures,
};

/// Load classes are this factor apart: a class's contacts have half-widths within a factor
/// √4 = 2 of its grid's (b ∝ √Q, Johnson eq. 4.45).
pub(crate) const CLASS: f64 = 4.0;

/// A contact up to this factor above the design load stays on the design grid (its
/// half-width within √2 of the design load's, well inside the grid's reach of 3 b).
pub(crate) const HEAVIER: f64 = 2.0;

/// The roller load \[N\] of the grid a contact of load `q` is solved on, for the design
/// load `design`: the design load itself when `design`/[`CLASS`] ≤ q ≤ [`HEAVIER`]·design;
/// a lighter contact's class, design/CLASSᵐ with the largest m that still holds q (q within
/// a factor CLASS below its grid's load); a heavier one's own load.
pub(crate) fn grid_load(q: f64, design: f64) -> f64 {
    if q > HEAVIER * design {
        return q;
    }
    let mut load = design;
    while q < load / CLASS {
        load /= CLASS;
    }
    load
}

/// One grid and what it is laid out for.
pub(crate) struct ContactGrid<'a> {
    /// The roller load it is sized for \[N\].
    pub load: f64,
    /// The roller under that load (the case's crown, no tilt).
    pub roller: Roller,
    /// The contact problem on it under that load.
    pub problem: InterfaceProblem<'a>,
    /// Its cell along and across \[mm\].
    pub cell: [f64; 2],
}

impl ContactGrid<'_> {
    /// The grid's points (x along the roller, y across) \[mm\].
    pub fn points(&self) -> &[[f64; 3]] {
        self.problem.interface().points()
    }

    /// How many cells span the Hertz half-width of a roller load `q` \[N\] on it.
    pub fn cells_across(&self, q: f64) -> Result<f64> {
        let mut roller = self.roller.clone();
        roller.load = q;
        Ok(roller.hertz()?.0 / self.cell[1])
    }
}

/// How a grid of the case's layout is built for another load: the cells, the reach across
/// in Hertz half-widths, and the roller's free ends when it has them.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Layout {
    pub cells: [usize; 2],
    pub reach: f64,
    pub ends: Option<RollerEnds>,
}

/// The grids of a bearing's distinct contacts: the design grid (the case's own problem) and
/// the classes' ([`grid_load`]), and each contact's grid.
pub(crate) struct Grids<'a> {
    pub grids: Vec<ContactGrid<'a>>,
    /// Each contact's grid, an index into `grids`.
    pub of: Vec<usize>,
}

impl<'a> Grids<'a> {
    /// The grids of `contacts`: `design` (the case's problem, laid out for `roller`'s load
    /// with cell `cell`) first, then one per further class met, each built as `layout`.
    pub fn new(
        design: &InterfaceProblem<'a>,
        roller: &Roller,
        cell: [f64; 2],
        layout: &Layout,
        contacts: &[RollerCase],
    ) -> Result<Self> {
        let mut grids = vec![ContactGrid {
            load: roller.load,
            roller: roller.clone(),
            problem: design.clone(),
            cell,
        }];
        let mut of = Vec::with_capacity(contacts.len());
        for c in contacts {
            let load = grid_load(c.load_n, roller.load);
            let same = |g: &ContactGrid| (g.load - load).abs() <= SAME_LOAD * load;
            let k = match grids.iter().position(same) {
                Some(k) => k,
                None => {
                    grids.push(built(roller, load, layout, design.dense_limit())?);
                    grids.len() - 1
                }
            };
            of.push(k);
        }
        Ok(Self { grids, of })
    }

    /// Contact `k`'s grid.
    pub fn of(&self, k: usize) -> &ContactGrid<'a> {
        &self.grids[self.of[k]]
    }

    /// Every contact solved on its grid by `solve` with the crown's gap change `change` (per
    /// point of the design grid, the same on every grid), the tolerance band's crowns after
    /// the nominal ones when `tolerance` > 0: the states in [`tolerance_band`]'s order over
    /// all contacts (contact k of band j at j·n + k).
    pub fn solve(
        &self,
        contacts: &[RollerCase],
        tolerance: f64,
        change: &[f64],
        solve: impl Fn(&[LoadCase], &[f64]) -> Result<Vec<ContactState>>,
    ) -> Result<Solved> {
        let n = contacts.len();
        let bands = if tolerance > 0.0 { 3 } else { 1 };
        let mut states: Vec<Option<(ContactState, Vec<f64>)>> = vec![None; bands * n];
        for (g, grid) in self.grids.iter().enumerate() {
            let mine: Vec<usize> = (0..n).filter(|&k| self.of[k] == g).collect();
            if mine.is_empty() {
                continue;
            }
            let cases: Vec<RollerCase> = mine.iter().map(|&k| contacts[k]).collect();
            let nominal = bearing_cases(&grid.problem, &grid.roller, &cases)?;
            let all = match tolerance > 0.0 {
                true => tolerance_band(&nominal, grid.roller.length, tolerance)?,
                false => nominal,
            };
            let solved = solve(&all, change)?;
            for (s, (state, case)) in solved.into_iter().zip(&all).enumerate() {
                let (band, j) = (s / mine.len(), s % mine.len());
                states[band * n + mine[j]] = Some((state, case.problem.initial_gap().to_vec()));
            }
        }
        let (states, initial_gaps) = states.into_iter().flatten().unzip();
        Ok(Solved {
            states,
            initial_gaps,
        })
    }

    /// The roller's figures of `contacts` (the contact k of each given by `index`), each on
    /// its grid, with the crown's `drop` per point.
    pub fn figures(
        &self,
        contacts: &[(usize, contopt_roller::CaseContact)],
        drop: &[f64],
    ) -> RollerFigures {
        let cases: Vec<_> = contacts
            .iter()
            .map(|(k, c)| {
                let grid = self.of(*k);
                contopt_roller::CaseFigures::new(c, grid.points(), drop, grid.cell[1])
            })
            .collect();
        let worst_p_max = cases.iter().map(|c| c.p_max).fold(0.0, f64::max);
        RollerFigures { cases, worst_p_max }
    }
}

/// Every contact's solution on its grid ([`Grids::solve`]).
pub(crate) struct Solved {
    /// The states, contact k of band j at j·n + k.
    pub states: Vec<ContactState>,
    /// Each state's initial gap, without the crown's gap change \[mm\].
    pub initial_gaps: Vec<Vec<f64>>,
}

/// Two grid loads within this fraction are one grid (round-off of the classes' division).
const SAME_LOAD: f64 = 1e-9;

/// The case's layout of bodies and gap for `roller` pressed by `load` \[N\]: its grid sized
/// for that load, the roller with its free ends when `layout` has them.
pub(crate) fn built(
    roller: &Roller,
    load: f64,
    layout: &Layout,
    dense_limit: u64,
) -> Result<ContactGrid<'static>> {
    check::positive("load_n", load)?;
    let mut roller = roller.clone();
    roller.load = load;
    let [nx, ny] = layout.cells;
    let cell = roller.cell(nx, ny, layout.reach)?;
    let (raceway, body, gap): (_, Box<dyn ElasticBody>, _) = match &layout.ends {
        Some(ends) => {
            let (r, b, g) = roller.free_end_bodies(nx, ny, layout.reach, ends)?;
            (r, Box::new(b), g)
        }
        None => {
            let (r, b, g) = roller.bodies(nx, ny, layout.reach)?;
            (r, Box::new(b), g)
        }
    };
    let problem =
        InterfaceProblem::owned(Box::new(raceway), body, &gap)?.with_dense_limit(dense_limit);
    Ok(ContactGrid {
        load,
        roller,
        problem,
        cell,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use contopt_core::Material;
    use contopt_roller::Crown;

    /// Loads within a factor 4 below the design load (and up to twice above) stay on its
    /// grid; lighter ones fall in classes a factor 4 apart that hold them; heavier ones get
    /// their own.
    #[test]
    fn load_classes() {
        let d = 1000.0;
        assert_eq!(grid_load(1000.0, d), d);
        assert_eq!(grid_load(250.0, d), d);
        assert_eq!(grid_load(2000.0, d), d);
        assert_eq!(grid_load(249.0, d), 250.0);
        assert_eq!(grid_load(62.5, d), 250.0);
        assert_eq!(grid_load(62.0, d), 62.5);
        assert_eq!(grid_load(3000.0, d), 3000.0);
        for q in [1e-3, 0.7, 13.0, 99.0, 400.0, 1999.0] {
            let g = grid_load(q, d);
            assert!(g >= q.min(d) && q >= g / CLASS, "{q}: {g}");
        }
    }

    /// A grid built for a lighter load has the design grid's points along the roller, its
    /// cells across scaled by √(load ratio) (b ∝ √Q), and its initial gap the roller's
    /// curvature y²/(2R) there.
    #[test]
    fn a_class_grid_is_the_design_grid_scaled_across() {
        let steel = Material::new(2.1e5, 0.3).unwrap();
        let roller = Roller {
            diameter: 10.0,
            length: 9.6,
            raceway_diameter: Some(55.0),
            roller: steel,
            raceway: steel,
            load: 4000.0,
            tilt: 0.0,
            crown: Crown::Straight,
        };
        let layout = Layout {
            cells: [8, 9],
            reach: 3.0,
            ends: None,
        };
        let design = built(&roller, 4000.0, &layout, u64::MAX).unwrap();
        let light = built(&roller, 250.0, &layout, u64::MAX).unwrap();
        assert!((design.cell[1] / light.cell[1] - 4.0).abs() < 1e-12);
        assert_eq!(design.cell[0], light.cell[0]);
        let radius = roller.radius().unwrap();
        for ((a, b), h) in design
            .points()
            .iter()
            .zip(light.points())
            .zip(light.problem.initial_gap())
        {
            assert_eq!(a[0], b[0]);
            assert!((a[1] / 4.0 - b[1]).abs() < 1e-12);
            assert!((h - b[1] * b[1] / (2.0 * radius)).abs() < 1e-15);
        }
        let cells = light.cells_across(250.0).unwrap();
        assert!((cells - design.cells_across(4000.0).unwrap()).abs() < 1e-9);
        assert!((cells - 4.0 / 3.0).abs() < 1e-9, "{cells}");
    }
}
