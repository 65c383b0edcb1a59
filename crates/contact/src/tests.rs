//! Small problems with exact solutions, on a body defined by its matrices (a user body).

use std::cell::RefCell;
use std::collections::BTreeMap;

use contopt_core::observe::{Event, Flow, Method, Observer};
use contopt_core::{
    ContactState, ElasticBody, Geometry, Interface, RigidBody, RigidMode, Termination,
};
use faer::Mat;

use crate::{
    ActiveSet, ActiveSetSettings, AugmentedLagrangian, AugmentedLagrangianSettings, Auto,
    ContactSolver, FullPenalty, InterfaceProblem, Penalty, PenaltySettings, PolonskyKeer,
    PolonskyKeerSettings, Qp, QpSettings,
};

fn qp() -> Qp {
    Qp::new(QpSettings::default()).unwrap()
}

fn active_set() -> ActiveSet {
    ActiveSet::new(ActiveSetSettings::default()).unwrap()
}

fn penalty(c: f64) -> Penalty {
    Penalty::new(PenaltySettings { c_mpa_per_mm: c }).unwrap()
}

fn augmented(settings: AugmentedLagrangianSettings) -> AugmentedLagrangian {
    AugmentedLagrangian::new(settings).unwrap()
}

fn polonsky_keer() -> PolonskyKeer {
    PolonskyKeer::new(PolonskyKeerSettings::default()).unwrap()
}

fn full_penalty(c: f64) -> FullPenalty {
    FullPenalty::new(PenaltySettings { c_mpa_per_mm: c }).unwrap()
}

/// The solver's method, as a test message.
fn name(s: &dyn ContactSolver) -> String {
    s.method().to_string()
}

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
        Box::new(qp()),
        Box::new(active_set()),
        Box::new(augmented(AugmentedLagrangianSettings::new(1e3))),
        Box::new(polonsky_keer()),
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
        assert_close(&st.pressure, &[0.5, 0.0], 1e-10, &name(s.as_ref()));
        assert_close(&st.gap, &[0.0, 1e-3], 1e-13, &name(s.as_ref()));
        assert_eq!(st.active, vec![true, false], "{}", &name(s.as_ref()));
    }
    // The penalty closes the gap only to p/c: p₀ = 1e-3 / (2e-3 + 1/c).
    for c in [1e2, 1e4, 1e8] {
        let st = penalty(c).solve(&problem).unwrap();
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

/// A body of diagonal compliance that offers its exact inverse.
struct Springs(MatrixBody);

impl ElasticBody for Springs {
    fn name(&self) -> &str {
        "springs"
    }
    fn interface(&self) -> &Interface {
        &self.0.interface
    }
    fn apply_influence(&self, force: &[f64], out: &mut [f64]) {
        self.0.apply_influence(force, out)
    }
    fn precondition(&self, displacement: &[f64], force: &mut [f64]) -> bool {
        for (i, f) in force.iter_mut().enumerate() {
            *f = displacement[i] / self.0.a[(i, i)];
        }
        true
    }
    fn load_displacement(&self) -> contopt_core::Result<Vec<f64>> {
        self.0.load_displacement()
    }
    fn rigid_modes(&self) -> &[RigidMode] {
        &self.0.modes
    }
}

/// `auto` picks Polonsky–Keer for a body that offers its inverse and the active set for one
/// that does not (on the same three floating points), says so, and both give the exact
/// p = (2, 1, 0); past `Auto::DENSE_POINTS` points the choice is Polonsky–Keer whatever the
/// bodies.
#[test]
fn auto_chooses_by_the_bodies() {
    let auto = Auto::new().unwrap();
    let plain = floating_three_points(0.0);
    let mode = RigidMode {
        name: "translation".into(),
        interface_displacement: vec![1.0; 3],
        load: -3.0,
    };
    let a = Mat::from_fn(3, 3, |i, j| if i == j { 1e-3 } else { 0.0 });
    let springs = Springs(body(a, vec![mode]));
    let rigid = RigidBody::fixed("rigid", springs.interface());
    let inverted = InterfaceProblem::new(&springs, &rigid, &[0.0, 1e-3, 5e-3]).unwrap();
    for (problem, method) in [
        (&plain, Method::ActiveSet),
        (&inverted, Method::PolonskyKeer),
    ] {
        assert_eq!(auto.method_for(problem), method);
        let st = auto.solve(problem).unwrap();
        assert_eq!(st.method, method);
        assert_close(&st.pressure, &[2.0, 1.0, 0.0], 1e-10, &method.to_string());
    }
    let large = Auto::DENSE_POINTS + 1;
    assert_eq!(auto.choice(large).method(), Method::PolonskyKeer);
    assert_eq!(auto.choice(Auto::DENSE_POINTS).method(), Method::ActiveSet);
}

/// Three points on a floating body (one axial mode, load 3 N), diagonal compliance 1e-3 and
/// gaps (0, 1, 5) µm: points 0 and 1 carry p = (2, 1), point 2 stays open by 3 µm, λ = −2 µm.
#[test]
fn three_points_with_a_rigid_mode() {
    let problem = floating_three_points(0.0);
    for s in solvers() {
        let st = s.solve(&problem).unwrap();
        assert_close(&st.pressure, &[2.0, 1.0, 0.0], 1e-10, &name(s.as_ref()));
        assert_close(&st.gap, &[0.0, 0.0, 3e-3], 1e-12, &name(s.as_ref()));
        assert_close(&st.rigid, &[-2e-3], 1e-12, &name(s.as_ref()));
        assert!(
            st.residuals.equilibrium < 1e-9,
            "{}: {:?}",
            &name(s.as_ref()),
            st.residuals
        );
    }
}

/// A solution's λ maps back to each body's own modes: a mode that does not move the
/// interface is dropped from the problem and gets amplitude 0, the translation its λ; a
/// problem whose modes were replaced refuses.
#[test]
fn solution_amplitudes_map_back_to_the_bodies_modes() {
    let a = Mat::from_fn(3, 3, |i, j| if i == j { 1e-3 } else { 0.0 });
    let idle = RigidMode {
        name: "sideways".into(),
        interface_displacement: vec![0.0; 3],
        load: 0.0,
    };
    let translation = RigidMode {
        name: "translation".into(),
        interface_displacement: vec![1.0; 3],
        load: -3.0,
    };
    let b = body(a, vec![idle, translation]);
    let rigid = RigidBody::fixed("rigid", b.interface());
    let problem =
        InterfaceProblem::owned(Box::new(b), Box::new(rigid), &[0.0, 1e-3, 5e-3]).unwrap();
    assert_eq!(problem.modes().len(), 1);
    let st = qp().solve(&problem).unwrap();
    let own = problem.body_rigid(&st.rigid).unwrap();
    assert_eq!(own, [vec![0.0, st.rigid[0]], vec![]]);
    assert!((st.rigid[0] + 2e-3).abs() < 1e-12, "{:?}", st.rigid);
    let e = problem.body_rigid(&[]).unwrap_err();
    assert!(e.to_string().contains("rigid.len()"), "{e}");
    let replaced = problem.with_modes(vec![]).unwrap();
    assert!(replaced.body_rigid(&[]).is_err());
}

/// The augmented Lagrangian reaches the same solution from a small and a large c, and
/// counts Kalker's solves: starting with every point in contact, the open point has tension on
/// the first solve and on no other (`iterp − iterd` = 1).
#[test]
fn augmented_lagrangian_counts_set_changes() {
    let problem = floating_three_points(0.2e-3);
    let reference = qp().solve(&problem).unwrap();
    for c in [1e3, 1e5, 1e9] {
        let st = augmented(AugmentedLagrangianSettings::new(c))
            .solve(&problem)
            .unwrap();
        assert_close(&st.pressure, &reference.pressure, 1e-8, &format!("c = {c}"));
        assert_eq!(st.iterp - st.iterd, 1, "c = {c}");
        assert!(st.iterations >= 1);
    }
    // Too small a c for this compliance (ρ = 1/c ≫ A w): each step gains only 1 %; the
    // state says it stopped at its step limit and how far it got.
    let state = augmented(AugmentedLagrangianSettings {
        max_steps: 50,
        accelerate: false,
        ..AugmentedLagrangianSettings::new(10.0)
    })
    .solve(&problem)
    .unwrap();
    assert!(
        (state.residuals.penetration - 3.357e-4).abs() < 1e-7,
        "{:?}",
        state.residuals
    );
    assert!(state.pressure.iter().all(|p| p.is_finite()));
    match &state.termination {
        Termination::StepLimit {
            steps: 50,
            measure,
            tolerance,
        } => assert!(*measure > *tolerance && *tolerance == 1e-10, "{measure}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn mismatched_interfaces_and_impossible_loads_are_named() {
    let a = Mat::from_fn(2, 2, |i, j| if i == j { 1e-3 } else { 0.0 });
    let b = body(a.clone(), vec![]);
    let mut other = body(a.clone(), vec![]);
    let mut points = other.interface.points().to_vec();
    points[1][0] = 1.5;
    other.interface = Interface::new(
        Geometry::Surface,
        points,
        other.interface.weights().to_vec(),
        vec![[0.0, -1.0, 0.0]; 2],
    )
    .unwrap();
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
    let err = Penalty::new(PenaltySettings { c_mpa_per_mm: -1.0 })
        .unwrap_err()
        .to_string();
    assert_eq!(
        err,
        "invalid c_mpa_per_mm = -1: must be positive and finite"
    );
}

/// The dense matrix is refused before allocation past the memory limit, with its size, the
/// memory and the way out; under the limit it is built once and shared by the problems derived
/// by changing the gap.
#[test]
fn dense_matrix_is_refused_past_the_limit_and_shared() {
    let problem = floating_three_points(0.2e-3);
    let small = problem.clone().with_dense_limit(100);
    let err = active_set().solve(&small).unwrap_err().to_string();
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
    let cold = polonsky_keer().solve(&problem).unwrap();
    let warm = polonsky_keer()
        .solve_from(&problem, &[3.0, 0.0, 1.0])
        .unwrap();
    assert_close(&warm.pressure, &cold.pressure, 1e-10, "warm");
    assert!(polonsky_keer().solve_from(&problem, &[1.0]).is_err());
}

/// A loosened Polonsky–Keer stops at the looser tolerance: on the wavy contact of 40 points
/// its steps report 10⁻⁴ and it takes fewer of them than at its own 10⁻¹², its pressure within
/// 10⁻³ of the exact one; a tolerance not looser than its own, or not below 1, gives none, nor
/// does a direct method. `Auto` loosens only its iterative choice: its dense one (chosen for
/// these 40 points) solves as before.
#[test]
fn a_loosened_solver_stops_at_its_tolerance() {
    let problem = wavy_floating(40, 1.0);
    let pk = polonsky_keer();
    let exact = pk.solve(&problem).unwrap();
    let loose = pk.loosened(1e-4).unwrap();
    let tolerances = RefCell::new(vec![]);
    let (state, _) = observed(None, |o| {
        let o = |e: &Event| {
            tolerances.borrow_mut().push(e.tolerance);
            o.observe(e)
        };
        loose.solve_observed(&problem, None, &o)
    });
    let tolerances = tolerances.into_inner();
    assert!(tolerances[..tolerances.len() - 1]
        .iter()
        .all(|&t| t == 1e-4));
    assert!(state.is_converged() && state.iterations < exact.iterations);
    let scale = exact.pressure.iter().fold(0.0, |m: f64, p| m.max(*p));
    assert_close(&state.pressure, &exact.pressure, 1e-3 * scale, "loosened");
    for t in [1e-12, 1e-13, 1.0] {
        assert!(pk.loosened(t).is_none(), "{t}");
    }
    assert!(active_set().loosened(1e-4).is_none());
    let auto = Auto::new().unwrap();
    let loose_auto = auto.loosened(1e-4).unwrap();
    assert_eq!(loose_auto.method_for(&problem), Method::ActiveSet);
    assert_eq!(loose_auto.solve(&problem).ok(), auto.solve(&problem).ok());
    assert!(auto.loosened(1e-13).is_none());
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
    let reference = qp().solve(&columns).unwrap();
    assert!(
        (reference.pressure[2] - 1.0).abs() < 1e-9,
        "{:?}",
        reference.pressure
    );
    for s in solvers() {
        let st = s.solve(&columns).unwrap();
        assert!(
            st.is_converged(),
            "{}: {}",
            name(s.as_ref()),
            st.termination
        );
        assert_close(&st.pressure, &reference.pressure, 1e-9, &name(s.as_ref()));
        assert_close(&st.rigid, &reference.rigid, 1e-12, &name(s.as_ref()));
        assert!(st.residuals.equilibrium < 1e-9, "{}", &name(s.as_ref()));
    }
}

/// A free mode's load and displacements are checked finite, each named.
#[test]
fn modes_with_infinite_values_are_named() {
    let problem = floating_three_points(0.0);
    let mode = |load: f64, r: f64| crate::FreeMode {
        name: "column".into(),
        points: vec![0, 1],
        displacement: vec![1.0, r],
        load,
    };
    let err = problem
        .with_modes(vec![mode(f64::INFINITY, 1.0)])
        .unwrap_err()
        .to_string();
    assert_eq!(err, "invalid mode `column`.load = inf: must be finite");
    let err = problem
        .with_modes(vec![mode(-1.0, f64::NAN)])
        .unwrap_err()
        .to_string();
    assert_eq!(
        err,
        "invalid mode `column`.displacement[1] = NaN: must be finite"
    );
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
    let mut points = b2.interface.points().to_vec();
    points.reverse();
    b2.interface = Interface::new(
        Geometry::Surface,
        points,
        b2.interface.weights().to_vec(),
        vec![[0.0, -1.0, 0.0]; 3],
    )
    .unwrap();
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

impl contopt_core::FullSystem for StiffnessSystem {
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
/// The last event of the outermost method carries its termination, and is not counted.
fn observed(
    stop: Option<(Method, usize)>,
    solve: impl FnOnce(&dyn Observer) -> contopt_core::Result<ContactState>,
) -> (ContactState, BTreeMap<Method, usize>) {
    let counts = RefCell::new(BTreeMap::<Method, usize>::new());
    let end = RefCell::new(None);
    let observer = |e: &Event| {
        if let Some(termination) = e.end {
            assert_eq!(
                e.level, 0,
                "only the outermost method announces its end here"
            );
            *end.borrow_mut() = Some(termination.clone());
            return Flow::Continue;
        }
        let mut counts = counts.borrow_mut();
        let k = counts.entry(e.method).or_insert(0);
        *k += 1;
        assert_eq!(e.iteration, *k, "{} numbers its iterations", e.method);
        assert!(e.measure.is_finite() && e.tolerance >= 0.0, "{e:?}");
        let inner = e.method == Method::Kalker;
        assert_eq!(e.level, usize::from(inner), "{e:?}");
        if stop == Some((e.method, e.iteration)) {
            Flow::Stop
        } else {
            Flow::Continue
        }
    };
    let state = solve(&observer).unwrap();
    assert_eq!(end.into_inner().as_ref(), Some(&state.termination));
    (state, counts.into_inner())
}

/// Every iterative solver reports each iteration it counts in its state: Kalker's solves
/// (`iterp`) for the penalty method and the active set, the Uzawa steps (`iterations`) and the
/// inner solves (`iterp`) for the augmented Lagrangian, the conjugate-gradient steps for
/// Polonsky–Keer; and observing changes nothing.
#[test]
fn observers_see_every_iteration() {
    let problem = wavy_floating(40, 1.0);
    let al = augmented(AugmentedLagrangianSettings {
        accelerate: false,
        ..AugmentedLagrangianSettings::new(1e3)
    });
    let (soft, stiff, exact, pk) = (penalty(1e4), penalty(1e12), active_set(), polonsky_keer());
    let solvers: [&dyn ContactSolver; 5] = [&soft, &stiff, &exact, &al, &pk];
    for s in solvers {
        let silent = s.solve(&problem).unwrap();
        let (st, counts) = observed(None, |o| s.solve_observed(&problem, None, o));
        assert_eq!(st, silent, "{}: observing changes the answer", name(s));
        assert_eq!(st.termination, Termination::Converged, "{}", name(s));
        assert_eq!(st.method, s.method());
        let own = counts.get(&s.method()).copied().unwrap_or(0);
        match s.method() {
            Method::AugmentedLagrangian => {
                assert_eq!(own, st.iterations, "Uzawa steps");
                assert_eq!(counts[&Method::Kalker], st.iterp, "inner solves");
            }
            Method::PolonskyKeer => assert_eq!(own, st.iterations),
            _ => assert_eq!(own, st.iterp, "{}: Kalker's solves", name(s)),
        }
        assert!(
            own >= 3,
            "{}: {own} iterations are too few for the test",
            name(s)
        );
    }
}

/// A stop after two iterations returns the second iterate, finite, as stopped by the
/// observer; `InterfaceProblem::verify` keeps it so.
#[test]
fn observers_stop_every_solver() {
    let problem = wavy_floating(40, 1.0);
    let al = augmented(AugmentedLagrangianSettings {
        accelerate: false,
        ..AugmentedLagrangianSettings::new(1e3)
    });
    let (soft, stiff, exact, pk) = (penalty(1e4), penalty(1e12), active_set(), polonsky_keer());
    let cases: [(&dyn ContactSolver, Method); 6] = [
        (&soft, Method::Penalty),
        (&stiff, Method::Penalty),
        (&exact, Method::ActiveSet),
        (&al, Method::AugmentedLagrangian),
        (&al, Method::Kalker),
        (&pk, Method::PolonskyKeer),
    ];
    for (s, method) in cases {
        let (mut st, counts) = observed(Some((method, 2)), |o| s.solve_observed(&problem, None, o));
        let expected = Termination::Stopped { after: 2 };
        assert_eq!(st.termination, expected, "{} ({method})", name(s));
        assert_eq!(counts[&method], 2, "{}: nothing after the stop", name(s));
        assert_eq!(st.non_finite(), None, "{}", name(s));
        problem.verify(&mut st);
        assert_eq!(st.termination, expected, "{}", name(s));
    }
}

/// The penalty method on the full system and on its condensed interface agree to round-off,
/// with the same contact set and counts; it reports each of Kalker's solves, and stops when
/// asked.
#[test]
fn full_penalty_matches_the_condensed_one() {
    let (mut system, problem) = stiffness_pair(30);
    let c = 1e6;
    let condensed = penalty(c).solve(&problem).unwrap();
    let full = full_penalty(c).solve(&mut system).unwrap();
    let p_max = condensed.p_max();
    assert!(p_max > 0.0 && condensed.active.iter().any(|a| !a));
    assert_close(&full.pressure, &condensed.pressure, 1e-9 * p_max, "p");
    assert_close(&full.gap, &condensed.gap, 1e-12, "d");
    assert_eq!(full.active, condensed.active);
    assert_eq!([full.iterp, full.iterd], [condensed.iterp, condensed.iterd]);
    let method = Method::FullPenalty;
    let (st, counts) = observed(None, |o| full_penalty(c).solve_observed(&mut system, o));
    assert_eq!(counts[&method], st.iterp);
    assert!(
        st.iterp >= 3,
        "{} solves are too few for the test",
        st.iterp
    );
    let (st, counts) = observed(Some((method, 2)), |o| {
        full_penalty(c).solve_observed(&mut system, o)
    });
    assert_eq!(st.termination, Termination::Stopped { after: 2 });
    assert_eq!((counts[&method], st.iterp), (2, 2));
    assert_eq!(st.non_finite(), None);
    // A system whose weights do not match its points is refused.
    system.w.pop();
    let err = full_penalty(c).solve(&mut system).unwrap_err().to_string();
    assert!(err.contains("full system weights"), "{err}");
}

/// Dense solves at once hold the shared matrix and their own copies within the dense limit:
/// the active set's five own copies (six with the shared one) fit three times in 16
/// matrices, not four; the matrix-free solver is not bounded.
#[test]
fn dense_solves_at_once_fit_the_dense_limit() {
    let n = 8;
    let matrix = (n * n * 8) as u64;
    let problem = wavy_floating(n, 1.0).with_dense_limit(16 * matrix);
    assert_eq!(crate::parallel::at_once(&active_set(), &problem), 3);
    let problem = problem.with_dense_limit(15 * matrix);
    assert_eq!(crate::parallel::at_once(&active_set(), &problem), 2);
    let problem = problem.with_dense_limit(matrix);
    assert_eq!(crate::parallel::at_once(&active_set(), &problem), 1);
    assert_eq!(
        crate::parallel::at_once(&polonsky_keer(), &problem),
        usize::MAX
    );
}

/// A body whose influence is not symmetric (a coupling written one way only) or not positive
/// (its sign turned) is refused when the problem is built, naming the body: each solver
/// reached its own "converged" answer for the one-way coupling (on a bed of 41² cells under a
/// sphere: p_max 1.633 by the active set, 1.773 by Polonsky–Keer, 1.760 by the augmented
/// Lagrangian, 2.060 by the penalty method).
#[test]
fn a_body_that_is_not_reciprocal_or_not_positive_is_refused() {
    let n = 6;
    let one_way = Mat::from_fn(n, n, |i, j| match j as isize - i as isize {
        0 => 1.0,
        1 => 0.5,
        _ => 0.0,
    });
    let turned = Mat::from_fn(n, n, |i, j| if i == j { -1.0 } else { 0.0 });
    for (a, says) in [(one_way, "symmetric"), (turned, "positive")] {
        let b = body(a, vec![]);
        let rigid = RigidBody::pressed("punch", b.interface(), [0.0, 1.0, 0.0], 1.0).unwrap();
        let gap = vec![0.0; n];
        let refused = InterfaceProblem::new(&b, &rigid, &gap)
            .unwrap_err()
            .to_string();
        assert!(
            refused.contains("influence of `matrix body`") && refused.contains(says),
            "{refused}"
        );
    }
    // Reciprocal and positive: built.
    let a = Mat::from_fn(n, n, |i, j| if i == j { 1.0 } else { 0.1 });
    let b = body(a, vec![]);
    let rigid = RigidBody::pressed("punch", b.interface(), [0.0, 1.0, 0.0], 1.0).unwrap();
    assert!(InterfaceProblem::new(&b, &rigid, &[0.0; 6]).is_ok());
}
