//! Small problems with exact solutions, on a body defined by its matrices (a user body).

use std::cell::RefCell;
use std::collections::BTreeMap;

use contopt_core::observe::{stopped_by_observer, Flow, Iteration, Observer};
use contopt_core::{ContactState, ElasticBody, Geometry, Interface, RigidBody, RigidMode, Status};
use faer::Mat;

use crate::{
    ActiveSet, AugmentedLagrangian, ContactSolver, FullPenalty, InterfaceProblem, Penalty,
    PolonskyKeer, Qp,
};

/// A body given by its influence matrix, load displacement and rigid modes.
struct MatrixBody {
    interface: Interface,
    a: Mat<f64>,
    f: Vec<f64>,
    modes: Vec<RigidMode>,
}

impl ElasticBody for MatrixBody {
    fn name(&self) -> &str {
        "matrix body"
    }
    fn interface(&self) -> &Interface {
        &self.interface
    }
    fn apply_influence(&self, force: &[f64], out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            *o = (0..force.len()).map(|j| self.a[(i, j)] * force[j]).sum();
        }
    }
    fn load_displacement(&self) -> contopt_core::Result<Vec<f64>> {
        Ok(self.f.clone())
    }
    fn rigid_modes(&self) -> &[RigidMode] {
        &self.modes
    }
}

fn line(n: usize) -> Interface {
    let points = (0..n).map(|i| [i as f64, 0.0, 0.0]).collect();
    Interface::new(
        Geometry::Plane { thickness: 1.0 },
        points,
        vec![1.0; n],
        vec![[0.0, 1.0, 0.0]; n],
    )
    .unwrap()
}

fn body(a: Mat<f64>, modes: Vec<RigidMode>) -> MatrixBody {
    let n = a.nrows();
    MatrixBody {
        interface: line(n),
        a,
        f: vec![0.0; n],
        modes,
    }
}

fn solvers() -> Vec<Box<dyn ContactSolver>> {
    vec![
        Box::new(Qp::default()),
        Box::new(ActiveSet),
        Box::new(AugmentedLagrangian::new(1e3)),
        Box::new(PolonskyKeer::default()),
    ]
}

fn assert_close(got: &[f64], want: &[f64], tol: f64, what: &str) {
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!((g - w).abs() <= tol, "{what}[{i}]: {g} vs {w}");
    }
}

/// Two points, no rigid mode, interference −1 µm at point 0: point 0 closes with
/// p₀ = 1e-3 / 2e-3 = 0.5, point 1 stays open with d₁ = 0.5e-3 + 1e-3·0.5 = 1e-3.
#[test]
fn two_points_one_in_contact() {
    let a = Mat::from_fn(2, 2, |i, j| if i == j { 2e-3 } else { 1e-3 });
    let b = body(a, vec![]);
    let rigid = RigidBody::fixed("rigid", b.interface());
    let problem = InterfaceProblem::new(&b, &rigid, &[-1e-3, 0.5e-3]).unwrap();
    for s in solvers() {
        let st = s.solve(&problem).unwrap();
        assert_close(&st.pressure, &[0.5, 0.0], 1e-10, s.name());
        assert_close(&st.gap, &[0.0, 1e-3], 1e-13, s.name());
        assert_eq!(st.active, vec![true, false], "{}", s.name());
    }
    // The penalty closes the gap only to p/c: p₀ = 1e-3 / (2e-3 + 1/c).
    for c in [1e2, 1e4, 1e8] {
        let st = Penalty { c }.solve(&problem).unwrap();
        let exact = 1e-3 / (2e-3 + 1.0 / c);
        assert!((st.pressure[0] - exact).abs() < 1e-12 * exact, "c = {c}");
        assert!((st.gap[0] + exact / c).abs() < 1e-15, "penetration p/c");
    }
}

/// Three points on a body with one rigid mode loaded by 3 N, compliance 1e-3 on the diagonal
/// and `coupling` off it, gaps (0, 1, 5) µm.
fn floating_three_points(coupling: f64) -> InterfaceProblem<'static> {
    let a = Mat::from_fn(3, 3, |i, j| if i == j { 1e-3 } else { coupling });
    let mode = RigidMode {
        name: "translation".into(),
        interface_displacement: vec![1.0; 3],
        load: -3.0,
    };
    let b = body(a, vec![mode]);
    let rigid = RigidBody::fixed("rigid", b.interface());
    InterfaceProblem::owned(Box::new(b), Box::new(rigid), &[0.0, 1e-3, 5e-3]).unwrap()
}

/// Three points on a floating body (one axial mode, load 3 N), diagonal compliance 1e-3 and
/// gaps (0, 1, 5) µm: points 0 and 1 carry p = (2, 1), point 2 stays open by 3 µm, λ = −2 µm.
#[test]
fn three_points_with_a_rigid_mode() {
    let problem = floating_three_points(0.0);
    for s in solvers() {
        let st = s.solve(&problem).unwrap();
        assert_close(&st.pressure, &[2.0, 1.0, 0.0], 1e-10, s.name());
        assert_close(&st.gap, &[0.0, 0.0, 3e-3], 1e-12, s.name());
        assert_close(&st.rigid, &[-2e-3], 1e-12, s.name());
        assert!(
            st.residuals.equilibrium < 1e-9,
            "{}: {:?}",
            s.name(),
            st.residuals
        );
    }
}

/// The augmented Lagrangian reaches the same solution from a small and a large c, and
/// counts Kalker's solves: starting with every point in contact, the open point has tension on
/// the first solve and on no other (`iterp − iterd` = 1).
#[test]
fn augmented_lagrangian_counts_set_changes() {
    let problem = floating_three_points(0.2e-3);
    let reference = Qp::default().solve(&problem).unwrap();
    for c in [1e3, 1e5, 1e9] {
        let st = AugmentedLagrangian::new(c).solve(&problem).unwrap();
        assert_close(&st.pressure, &reference.pressure, 1e-8, &format!("c = {c}"));
        assert_eq!(st.iterp - st.iterd, 1, "c = {c}");
        assert!(st.iterations >= 1);
    }
    // Too small a c for this compliance (ρ = 1/c ≫ A w): each step gains only 1 %; the
    // state says it stopped and how far it got, and `solved` makes that an error.
    let state = AugmentedLagrangian {
        c: 10.0,
        tolerance: 1e-10,
        max_steps: 50,
        accelerate: false,
    }
    .solve(&problem)
    .unwrap();
    assert!(state.residuals.penetration > 1e-4, "{:?}", state.residuals);
    assert!(state.pressure.iter().all(|p| p.is_finite()));
    let err = state
        .solved("augmented Lagrangian")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("did not converge in 50") && err.contains("penetration 3.357e-4 mm"),
        "{err}"
    );
}

#[test]
fn mismatched_interfaces_and_impossible_loads_are_named() {
    let a = Mat::from_fn(2, 2, |i, j| if i == j { 1e-3 } else { 0.0 });
    let b = body(a.clone(), vec![]);
    let mut other = body(a.clone(), vec![]);
    other.interface.points[1][0] = 1.5;
    other.interface.normals = vec![[0.0, -1.0, 0.0]; 2];
    let err = InterfaceProblem::new(&b, &other, &[0.0; 2])
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("[1.0, 0.0, 0.0] of `matrix body` has no partner"),
        "{err}"
    );
    // A load that pulls the floating body away from contact.
    let pull = RigidMode {
        name: "translation".into(),
        interface_displacement: vec![1.0; 2],
        load: 5.0,
    };
    let b = body(a, vec![pull]);
    let rigid = RigidBody::fixed("rigid", b.interface());
    let err = InterfaceProblem::new(&b, &rigid, &[0.0; 2])
        .unwrap_err()
        .to_string();
    assert!(err.contains("pulls the bodies apart"), "{err}");
    assert!(Penalty { c: -1.0 }
        .solve(
            &InterfaceProblem::new(&body(Mat::identity(2, 2), vec![]), &rigid, &[0.0; 2]).unwrap()
        )
        .is_err());
}

/// The dense matrix is refused before allocation past the memory limit, with its size, the
/// memory and the way out; under the limit it is built once and shared by the problems derived
/// by changing the gap.
#[test]
fn dense_matrix_is_refused_past_the_limit_and_shared() {
    let problem = floating_three_points(0.2e-3);
    let small = problem.clone().with_dense_limit(100);
    let err = ActiveSet.solve(&small).unwrap_err().to_string();
    assert!(
        err.contains("dense 3 × 3 influence matrix")
            && err.contains("limit")
            && err.contains("dense_limit_mb"),
        "{err}"
    );
    let first = problem.dense_influence(1).unwrap() as *const _;
    let moved = problem.with_initial_gap(&[1e-3, 0.0, 0.0]).unwrap();
    assert!(std::ptr::eq(first, moved.dense_influence(1).unwrap()));
    // The operator gives what the matrix does.
    let mut u = vec![0.0; 3];
    moved.apply_influence(&[1.0, 2.0, 3.0], &mut u);
    assert_close(
        &u,
        &[1e-3 + 1e-3, 2e-3 + 0.8e-3, 3e-3 + 0.6e-3],
        1e-15,
        "A f",
    );
}

/// Polonsky–Keer from a warm start (another solution's pressure) reaches the same answer, and a
/// start of the wrong length is refused.
#[test]
fn polonsky_keer_warm_start() {
    let problem = floating_three_points(0.2e-3);
    let cold = PolonskyKeer::default().solve(&problem).unwrap();
    let warm = PolonskyKeer::default()
        .solve_from(&problem, &[3.0, 0.0, 1.0])
        .unwrap();
    assert_close(&warm.pressure, &cold.pressure, 1e-10, "warm");
    assert!(PolonskyKeer::default()
        .solve_from(&problem, &[1.0])
        .is_err());
}

/// Free modes replaced by two column translations, each with its own load (the optimiser's
/// load split): points 0–1 carry 2 N, point 2 carries 1 N; every solver agrees with the QP, and
/// each column's multiplier closes its contact points.
#[test]
fn column_modes_carry_their_own_loads() {
    let problem = floating_three_points(0.2e-3);
    let columns = problem
        .with_modes(vec![
            crate::FreeMode {
                name: "column 0".into(),
                points: vec![0, 1],
                displacement: vec![1.0; 2],
                load: -2.0,
            },
            crate::FreeMode {
                name: "column 1".into(),
                points: vec![2],
                displacement: vec![1.0],
                load: -1.0,
            },
        ])
        .unwrap();
    let reference = Qp::default().solve(&columns).unwrap();
    assert!(
        (reference.pressure[2] - 1.0).abs() < 1e-9,
        "{:?}",
        reference.pressure
    );
    for s in solvers() {
        let st = s.solve(&columns).unwrap().solved(s.name()).unwrap();
        assert_close(&st.pressure, &reference.pressure, 1e-9, s.name());
        assert_close(&st.rigid, &reference.rigid, 1e-12, s.name());
        assert!(st.residuals.equilibrium < 1e-9, "{}", s.name());
    }
}

/// A second body that lists its points in another order is paired by position: its influence
/// enters through the permutation, A = A¹ + P A² Pᵀ, in products and in the dense matrix.
#[test]
fn second_body_in_another_order_is_permuted() {
    let a1 = Mat::from_fn(3, 3, |i, j| if i == j { 2e-3 } else { 0.5e-3 });
    let b1 = body(a1, vec![]);
    // Body 2 lists the points backwards; its own compliance is 1e-3·(own index + 1) on the
    // diagonal and 0.1e-3·|i − j| off it.
    let mut b2 = body(
        Mat::from_fn(3, 3, |i, j| {
            if i == j {
                1e-3 * (i + 1) as f64
            } else {
                0.1e-3 * i.abs_diff(j) as f64
            }
        }),
        vec![],
    );
    b2.interface.points.reverse();
    b2.interface.normals = vec![[0.0, -1.0, 0.0]; 3];
    let problem = InterfaceProblem::new(&b1, &b2, &[0.0; 3]).unwrap();
    let f = [1.0, 2.0, 4.0];
    let mut u = vec![0.0; 3];
    problem.apply_influence(&f, &mut u);
    // Point i of body 1 is point 2 − i of body 2.
    let own = [f[2], f[1], f[0]];
    let a2 = &b2.a;
    let expected: Vec<f64> = (0..3)
        .map(|i| {
            let first: f64 = (0..3).map(|j| b1.a[(i, j)] * f[j]).sum();
            let second: f64 = (0..3).map(|j| a2[(2 - i, j)] * own[j]).sum();
            first + second
        })
        .collect();
    assert_close(&u, &expected, 1e-15, "A f");
    let dense = problem.dense_influence(1).unwrap();
    let from_dense: Vec<f64> = (0..3)
        .map(|i| (0..3).map(|j| dense[(i, j)] * f[j]).sum())
        .collect();
    assert_close(&from_dense, &expected, 1e-15, "dense A f");
}

/// n points on a line of a body with a smooth, positive-definite compliance
/// Aᵢⱼ = 10⁻³ e^(−|i−j|/3), floating (one translation loaded by `load` N) over a wavy
/// parabolic gap: the contact set changes several times before it settles.
fn wavy_floating(n: usize, load: f64) -> InterfaceProblem<'static> {
    let a = Mat::from_fn(n, n, |i, j| 1e-3 * (-(i.abs_diff(j) as f64) / 3.0).exp());
    let mode = RigidMode {
        name: "translation".into(),
        interface_displacement: vec![1.0; n],
        load: -load,
    };
    let b = body(a, vec![mode]);
    let rigid = RigidBody::fixed("rigid", b.interface());
    let gap: Vec<f64> = (0..n)
        .map(|i| {
            let x = (i as f64 - n as f64 / 2.0) / (n as f64 / 2.0);
            1e-3 * (x * x + 0.3 * (3.0 * i as f64).sin().abs())
        })
        .collect();
    InterfaceProblem::owned(Box::new(b), Box::new(rigid), &gap).unwrap()
}

/// A body given by its stiffness matrix K on the interface displacements u (Lᵢ u = uᵢ), with
/// the given forces f and no rigid mode, as a full system: (K + c W_C) u = f − c W_C h. Its
/// condensed form is the influence A = K⁻¹ and the load displacement K⁻¹ f.
struct StiffnessSystem {
    k: Mat<f64>,
    f: Vec<f64>,
    h: Vec<f64>,
    w: Vec<f64>,
}

impl crate::FullSystem for StiffnessSystem {
    fn points(&self) -> usize {
        self.h.len()
    }
    fn weights(&self) -> &[f64] {
        &self.w
    }
    fn rest_gap(&self) -> &[f64] {
        &self.h
    }
    fn free_modes(&self) -> usize {
        0
    }
    fn solve_springs(
        &mut self,
        active: &[bool],
        c: f64,
        gap: &mut [f64],
    ) -> contopt_core::Result<()> {
        use faer::linalg::solvers::Solve;
        let n = self.h.len();
        let spring = |i: usize| if active[i] { c * self.w[i] } else { 0.0 };
        let m = Mat::from_fn(n, n, |i, j| {
            self.k[(i, j)] + if i == j { spring(i) } else { 0.0 }
        });
        let rhs = Mat::from_fn(n, 1, |i, _| self.f[i] - spring(i) * self.h[i]);
        let u = m.llt(faer::Side::Lower).unwrap().solve(&rhs);
        for (i, d) in gap.iter_mut().enumerate() {
            *d = self.h[i] + u[(i, 0)];
        }
        Ok(())
    }
    fn rigid(&self) -> Vec<f64> {
        vec![]
    }
    fn equilibrium(&self, _: &[f64]) -> f64 {
        0.0
    }
}

/// The stiffness system of n points with K = 10³·(tridiagonal 2, −1) + 10²·I, pushed into a
/// rigid flat by forces that grow from the middle, over a wavy initial gap; with its condensed
/// interface problem.
fn stiffness_pair(n: usize) -> (StiffnessSystem, InterfaceProblem<'static>) {
    let k = Mat::from_fn(n, n, |i, j| match i.abs_diff(j) {
        0 => 2.1e3,
        1 => -1e3,
        _ => 0.0,
    });
    let f: Vec<f64> = (0..n)
        .map(|i| -0.01 * (1.0 - 0.5 * (i as f64 - n as f64 / 2.0).abs() / n as f64))
        .collect();
    let h: Vec<f64> = (0..n)
        .map(|i| 1e-4 * (2.0 * i as f64).sin().abs())
        .collect();
    let a = faer::linalg::solvers::DenseSolveCore::inverse(&k.llt(faer::Side::Lower).unwrap());
    let load: Vec<f64> = (0..n)
        .map(|i| (0..n).map(|j| a[(i, j)] * f[j]).sum())
        .collect();
    let mut b = body(a, vec![]);
    b.f = load;
    let rigid = RigidBody::fixed("rigid", b.interface());
    let problem = InterfaceProblem::owned(Box::new(b), Box::new(rigid), &h).unwrap();
    let w = vec![1.0; n];
    (StiffnessSystem { k, f, h, w }, problem)
}

/// Runs `solve` with an observer that counts the iterations each method reports, checks that
/// each method numbers them 1, 2, … with a finite measure, and asks to stop at `stop`
/// (method, iteration).
fn observed(
    stop: Option<(&str, usize)>,
    solve: impl FnOnce(&dyn Observer) -> contopt_core::Result<ContactState>,
) -> (ContactState, BTreeMap<String, usize>) {
    let counts = RefCell::new(BTreeMap::<String, usize>::new());
    let observer = |it: &Iteration| {
        let mut counts = counts.borrow_mut();
        let k = counts.entry(it.method.to_string()).or_insert(0);
        *k += 1;
        assert_eq!(it.iteration, *k, "{} numbers its iterations", it.method);
        assert!(it.measure.is_finite() && it.tolerance >= 0.0, "{it:?}");
        if stop == Some((it.method, it.iteration)) {
            Flow::Stop
        } else {
            Flow::Continue
        }
    };
    let state = solve(&observer).unwrap();
    (state, counts.into_inner())
}

/// Every iterative solver reports each iteration it counts in its state: Kalker's solves
/// (`iterp`) for the penalty method and the active set, the Uzawa steps (`iterations`) and the
/// inner solves (`iterp`) for the augmented Lagrangian, the conjugate-gradient steps for
/// Polonsky–Keer; and observing changes nothing.
#[test]
fn observers_see_every_iteration() {
    let problem = wavy_floating(40, 1.0);
    let al = AugmentedLagrangian {
        accelerate: false,
        ..AugmentedLagrangian::new(1e3)
    };
    let solvers: [&dyn ContactSolver; 5] = [
        &Penalty { c: 1e4 },
        &Penalty { c: 1e12 },
        &ActiveSet,
        &al,
        &PolonskyKeer::default(),
    ];
    for s in solvers {
        let silent = s.solve(&problem).unwrap();
        let (st, counts) = observed(None, |o| s.solve_observed(&problem, None, o));
        assert_eq!(st, silent, "{}: observing changes the answer", s.name());
        assert_eq!(st.status, Status::Solved, "{}", s.name());
        let own = counts.get(s.name()).copied().unwrap_or(0);
        if s.name() == al.name() {
            assert_eq!(own, st.iterations, "Uzawa steps");
            assert_eq!(
                counts[AugmentedLagrangian::KALKER],
                st.iterp,
                "inner solves"
            );
        } else if s.name() == "Polonsky-Keer" {
            assert_eq!(own, st.iterations);
        } else {
            assert_eq!(own, st.iterp, "{}: Kalker's solves", s.name());
        }
        assert!(
            own >= 3,
            "{}: {own} iterations are too few for the test",
            s.name()
        );
    }
}

/// A stop after two iterations returns the second iterate, finite, as stopped by the
/// observer; `InterfaceProblem::verify` keeps it so.
#[test]
fn observers_stop_every_solver() {
    let problem = wavy_floating(40, 1.0);
    let al = AugmentedLagrangian {
        accelerate: false,
        ..AugmentedLagrangian::new(1e3)
    };
    let cases: [(&dyn ContactSolver, &str); 6] = [
        (&Penalty { c: 1e4 }, "penalty"),
        (&Penalty { c: 1e12 }, "penalty"),
        (&ActiveSet, "active set"),
        (&al, al.name()),
        (&al, AugmentedLagrangian::KALKER),
        (&PolonskyKeer::default(), "Polonsky-Keer"),
    ];
    for (s, method) in cases {
        let (mut st, counts) = observed(Some((method, 2)), |o| s.solve_observed(&problem, None, o));
        let expected = Status::Stopped(stopped_by_observer(2));
        assert_eq!(st.status, expected, "{} ({method})", s.name());
        assert_eq!(counts[method], 2, "{}: nothing after the stop", s.name());
        assert_eq!(st.non_finite(), None, "{}", s.name());
        problem.verify(&mut st);
        assert_eq!(st.status, expected, "{}", s.name());
    }
}

/// The penalty method on the full system and on its condensed interface agree to round-off,
/// with the same contact set and counts; it reports each of Kalker's solves, and stops when
/// asked.
#[test]
fn full_penalty_matches_the_condensed_one() {
    let (mut system, problem) = stiffness_pair(30);
    let c = 1e6;
    let condensed = Penalty { c }.solve(&problem).unwrap();
    let full = FullPenalty { c }.solve(&mut system).unwrap();
    let p_max = condensed.p_max();
    assert!(p_max > 0.0 && condensed.active.iter().any(|a| !a));
    assert_close(&full.pressure, &condensed.pressure, 1e-9 * p_max, "p");
    assert_close(&full.gap, &condensed.gap, 1e-12, "d");
    assert_eq!(full.active, condensed.active);
    assert_eq!([full.iterp, full.iterd], [condensed.iterp, condensed.iterd]);
    let name = FullPenalty { c }.name().to_string();
    let (st, counts) = observed(None, |o| FullPenalty { c }.solve_observed(&mut system, o));
    assert_eq!(counts[&name], st.iterp);
    assert!(
        st.iterp >= 3,
        "{} solves are too few for the test",
        st.iterp
    );
    let (st, counts) = observed(Some((&name, 2)), |o| {
        FullPenalty { c }.solve_observed(&mut system, o)
    });
    assert_eq!(st.status, Status::Stopped(stopped_by_observer(2)));
    assert_eq!((counts[&name], st.iterp), (2, 2));
    assert_eq!(st.non_finite(), None);
    // A system whose weights do not match its points is refused.
    system.w.pop();
    let err = FullPenalty { c }
        .solve(&mut system)
        .unwrap_err()
        .to_string();
    assert!(err.contains("full system weights"), "{err}");
}
