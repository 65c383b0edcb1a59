//! Small dense kernels against what they replaced, in one run (book, "Design notes: measured
//! choices"):
//!
//! - the principal stresses of a stress tensor: the trigonometric solution of the
//!   characteristic cubic that `StressTensor::principal` used before, nalgebra's symmetric
//!   eigen-solver (`Matrix3::symmetric_eigenvalues`, sorted), and `StressTensor::principal`;
//!   timed over 1000 tensors of random principal stresses and axes, and their largest error
//!   relative to the tensor's norm printed for 10 000 random axes each of distinct, uniaxial,
//!   double and 1e-9-apart principal stresses;
//! - the element stiffness Kₑ = ∫ Bᵀ D B dV of every element of axisymmetric Q8 meshes of 10k
//!   and 50k elements: the hand-written arrays the library used before against
//!   `FeModel::element_stiffness` on nalgebra's fixed-size matrices (which also copies each
//!   Kₑ into a newly allocated faer matrix, as the old code does not), with their largest
//!   difference printed;
//! - the element stiffness of every element of an axisymmetric T6 mesh against a Q8 mesh of
//!   about the same number of nodes (30 401 and 30 625): what an imported triangle mesh costs
//!   to integrate against the structured quadrilaterals;
//! - the influence product of the bundled bearing's contact (80 × 49 cells, a roller with free
//!   ends 0.2 mm beyond its effective length on its raceway's grid): as it was (the raceway's
//!   product and the roller's pressure with its images written out on a grid three times as
//!   long, padded to 492 = 4·3·41 columns), the roller's own product read beyond its grid
//!   (`FreeEnds`), and the contact's one product for both (the raceway added into the
//!   roller's), with their largest difference printed.
//!
//! `cargo bench --bench kernels`

use std::hint::black_box;
use std::time::Duration;

use contopt::contact::InterfaceProblem;
use contopt::fem::element::{GAUSS3, MAX_NODES};
use contopt::fem::{Analysis, ElementKind, FeModel, Material, Mesh, Spacing};
use contopt::greens::{FreeEnds, HalfSpace};
use contopt::ElasticBody;
use contopt::StressTensor;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode};
use nalgebra::Matrix3;

/// The principal stresses by the trigonometric solution of the characteristic cubic (Smith
/// 1961) alone: `StressTensor::principal` before, √ε of the deviator where two are equal.
fn trigonometric(t: &StressTensor) -> [f64; 3] {
    let off = t.xy * t.xy + t.xz * t.xz + t.yz * t.yz;
    let mean = (t.xx + t.yy + t.zz) / 3.0;
    let (a, b, c) = (t.xx - mean, t.yy - mean, t.zz - mean);
    let spread = ((a * a + b * b + c * c + 2.0 * off) / 6.0).sqrt();
    if spread == 0.0 {
        return [mean; 3];
    }
    let det = a * (b * c - t.yz * t.yz) - t.xy * (t.xy * c - t.yz * t.xz)
        + t.xz * (t.xy * t.yz - b * t.xz);
    let cos3 = (det / (2.0 * spread.powi(3))).clamp(-1.0, 1.0);
    let phi = cos3.acos() / 3.0;
    let s1 = mean + 2.0 * spread * phi.cos();
    let s3 = mean + 2.0 * spread * (phi + 2.0 * std::f64::consts::FRAC_PI_3).cos();
    [s1, 3.0 * mean - s1 - s3, s3]
}

/// The principal stresses by nalgebra's symmetric eigen-solver (Householder tridiagonal
/// reduction and implicit QR), sorted σ₁ ≥ σ₂ ≥ σ₃.
fn symmetric_eigen(t: &StressTensor) -> [f64; 3] {
    let m = Matrix3::new(t.xx, t.xy, t.xz, t.xy, t.yy, t.yz, t.xz, t.yz, t.zz);
    let mut l: [f64; 3] = m.symmetric_eigenvalues().into();
    l.sort_by(|a, b| b.total_cmp(a));
    l
}

/// Uniform numbers in [0, 1) by SplitMix64 (Steele, Lea & Flood 2014), seeded.
struct SplitMix(u64);

impl SplitMix {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Euler angles (z, x, z) of a random rotation (not uniform over rotations; any will do).
    fn angles(&mut self) -> [f64; 3] {
        [0; 3].map(|_| std::f64::consts::TAU * self.uniform())
    }
}

/// R diag(λ) Rᵀ with R the rotation of Euler angles (α, β, γ) about z, x and z.
fn rotated(lambda: [f64; 3], [a, b, g]: [f64; 3]) -> StressTensor {
    let rz = |t: f64| {
        [
            [t.cos(), -t.sin(), 0.0],
            [t.sin(), t.cos(), 0.0],
            [0.0, 0.0, 1.0],
        ]
    };
    let rx = |t: f64| {
        [
            [1.0, 0.0, 0.0],
            [0.0, t.cos(), -t.sin()],
            [0.0, t.sin(), t.cos()],
        ]
    };
    let mul = |p: [[f64; 3]; 3], q: [[f64; 3]; 3]| {
        std::array::from_fn::<_, 3, _>(|i| {
            std::array::from_fn::<_, 3, _>(|j| (0..3).map(|k| p[i][k] * q[k][j]).sum())
        })
    };
    let r = mul(mul(rz(a), rx(b)), rz(g));
    let s = |i: usize, j: usize| (0..3).map(|k| r[i][k] * lambda[k] * r[j][k]).sum();
    StressTensor {
        xx: s(0, 0),
        yy: s(1, 1),
        zz: s(2, 2),
        xy: s(0, 1),
        xz: s(0, 2),
        yz: s(1, 2),
    }
}

type Principal = fn(&StressTensor) -> [f64; 3];

const PRINCIPAL: [(&str, Principal); 3] = [
    ("trigonometric", trigonometric),
    ("nalgebra", symmetric_eigen),
    ("principal", StressTensor::principal),
];

/// The accuracy table and the timing of [`PRINCIPAL`].
fn principal(c: &mut Criterion) {
    let patterns: [(&str, [f64; 3]); 4] = [
        ("distinct", [300.0, -50.0, -120.0]),
        ("uniaxial", [250.0, 0.0, 0.0]),
        ("double", [300.0, 100.0, 100.0]),
        ("1e-9 apart", [100.0, 100.0 * (1.0 - 1e-9), -200.0]),
    ];
    println!("largest error of the principal stresses / tensor norm, 10 000 random axes");
    print!("{:>12}", "stresses");
    for (name, _) in PRINCIPAL {
        print!(" {name:>14}");
    }
    println!();
    for (pattern, lambda) in patterns {
        let mut rng = SplitMix(11);
        let tensors: Vec<StressTensor> =
            (0..10_000).map(|_| rotated(lambda, rng.angles())).collect();
        let norm = lambda.iter().map(|x| x * x).sum::<f64>().sqrt();
        print!("{pattern:>12}");
        for (_, f) in PRINCIPAL {
            let error = tensors
                .iter()
                .flat_map(|t| f(t).into_iter().zip(lambda).map(|(g, w)| (g - w).abs()))
                .fold(0.0, f64::max);
            print!(" {:>14.1e}", error / norm);
        }
        println!();
    }
    let mut rng = SplitMix(7);
    let tensors: Vec<StressTensor> = (0..1000)
        .map(|_| {
            let lambda = [0; 3].map(|_| 400.0 * rng.uniform() - 200.0);
            rotated(lambda, rng.angles())
        })
        .collect();
    let mut group = c.benchmark_group("principal_x1000");
    for (name, f) in PRINCIPAL {
        group.bench_function(name, |b| {
            b.iter(|| {
                for t in &tensors {
                    black_box(f(black_box(t)));
                }
            })
        });
    }
    group.finish();
}

/// Shape functions, x/y derivatives, position and dV at a Gauss point, as the library
/// computed them before (the Jacobian and its inverse as arrays).
struct OldPoint {
    n: [f64; MAX_NODES],
    dx: [f64; MAX_NODES],
    dy: [f64; MAX_NODES],
    x: [f64; 2],
    dv: f64,
}

/// The Gauss point of element `e` at (ξ, η) with weight `w`, as the library's `Mesh::jacobian`
/// and `point_b` computed it before.
fn old_point(model: &FeModel, e: usize, xi: f64, eta: f64, w: f64) -> OldPoint {
    let mesh = model.mesh();
    let conn = &mesh.elements()[e];
    // Mesh::jacobian evaluates the shape functions, and point_b once more.
    let s = mesh.element_kind(e).shape(xi, eta);
    let mut j = [[0.0; 2]; 2];
    for (a, &n) in conn.iter().enumerate() {
        let p = mesh.nodes()[n];
        for c in 0..2 {
            j[0][c] += s.dxi[a] * p[c];
            j[1][c] += s.deta[a] * p[c];
        }
    }
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let s = mesh.element_kind(e).shape(xi, eta);
    assert!(det > 0.0, "element {e} has a singular Jacobian");
    let jinv = [
        [j[1][1] / det, -j[0][1] / det],
        [-j[1][0] / det, j[0][0] / det],
    ];
    let mut b = OldPoint {
        n: s.n,
        dx: [0.0; MAX_NODES],
        dy: [0.0; MAX_NODES],
        x: [0.0; 2],
        dv: 0.0,
    };
    for (a, &node) in conn.iter().enumerate() {
        b.dx[a] = jinv[0][0] * s.dxi[a] + jinv[0][1] * s.deta[a];
        b.dy[a] = jinv[1][0] * s.dxi[a] + jinv[1][1] * s.deta[a];
        let p = mesh.nodes()[node];
        b.x[0] += s.n[a] * p[0];
        b.x[1] += s.n[a] * p[1];
    }
    b.dv = model.analysis().measure(b.x[0]) * det * w;
    b
}

/// The strain rows of node `a` as the library computed them before.
fn old_strain_rows(analysis: Analysis, b: &OldPoint, a: usize) -> [[f64; 2]; 4] {
    match analysis {
        Analysis::Axisymmetric => [
            [b.dx[a], 0.0],
            [0.0, b.dy[a]],
            [b.n[a] / b.x[0], 0.0],
            [b.dy[a], b.dx[a]],
        ],
        _ => [
            [b.dx[a], 0.0],
            [0.0, b.dy[a]],
            [b.dy[a], b.dx[a]],
            [0.0, 0.0],
        ],
    }
}

/// The element stiffness as the library computed it before.
fn old_element_stiffness(
    model: &FeModel,
    e: usize,
    d: &[[f64; 4]; 4],
    ke: &mut [[f64; 2 * MAX_NODES]; 2 * MAX_NODES],
) {
    let nn = model.mesh().element_kind(e).n_nodes();
    let ns = model.analysis().n_strain();
    for row in ke.iter_mut() {
        row.fill(0.0);
    }
    for &(xi, wx) in &GAUSS3 {
        for &(eta, wy) in &GAUSS3 {
            let b = old_point(model, e, xi, eta, wx * wy);
            let rows: [[[f64; 2]; 4]; MAX_NODES] =
                std::array::from_fn(|a| old_strain_rows(model.analysis(), &b, a));
            let rows = &rows[..nn];
            for a in 0..nn {
                for ca in 0..2 {
                    let mut db = [0.0; 4];
                    for (i, dbi) in db.iter_mut().enumerate().take(ns) {
                        *dbi = (0..ns).map(|k| d[i][k] * rows[a][k][ca]).sum::<f64>() * b.dv;
                    }
                    for (bn, row_b) in rows.iter().enumerate() {
                        for cb in 0..2 {
                            ke[2 * bn + cb][2 * a + ca] +=
                                (0..ns).map(|k| row_b[k][cb] * db[k]).sum::<f64>();
                        }
                    }
                }
            }
        }
    }
}

/// An axisymmetric model of `nr` × `nz` cells of `kind` (a T6 cell is two triangles): r from
/// the axis to 100 mm graded 8:1, z over 50 mm.
fn axisymmetric(kind: ElementKind, nr: usize, nz: usize) -> FeModel {
    let r = Spacing::geometric(0.0, 100.0, nr, 8.0).unwrap();
    let z = Spacing::uniform(0.0, 50.0, nz).unwrap();
    let mesh = Mesh::rectangle(kind, &r, &z).unwrap();
    FeModel::new(
        mesh,
        Material::new(2e5, 0.3).unwrap(),
        Analysis::Axisymmetric,
    )
    .unwrap()
}

/// The difference and the timing of the old and the library's element stiffness.
fn elements(c: &mut Criterion) {
    let models = [
        ("10k", axisymmetric(ElementKind::Q8, 100, 100)),
        ("50k", axisymmetric(ElementKind::Q8, 250, 200)),
    ];
    println!("largest difference, new against old / largest entry (bit-identical share)");
    for (label, model) in &models {
        let d = model.analysis().elasticity(model.material());
        let (mut largest, mut diff, mut same, mut count) = (0.0f64, 0.0f64, 0, 0);
        let mut old = [[0.0; 2 * MAX_NODES]; 2 * MAX_NODES];
        for e in 0..model.mesh().elements().len() {
            old_element_stiffness(model, e, &d, &mut old);
            let new = model.element_stiffness(e).unwrap();
            for (i, row) in old.iter().enumerate().take(new.nrows()) {
                for (j, &o) in row.iter().enumerate().take(new.ncols()) {
                    largest = largest.max(o.abs());
                    diff = diff.max((o - new[(i, j)]).abs());
                    same += usize::from(o.to_bits() == new[(i, j)].to_bits());
                    count += 1;
                }
            }
        }
        println!(
            "{label:>4} element stiffness  {:.1e} ({same}/{count})",
            diff / largest
        );
    }
    let mut group = c.benchmark_group("elements");
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500));
    for (label, model) in &models {
        let n = model.mesh().elements().len();
        group.bench_with_input(BenchmarkId::new("stiffness_old", label), model, |b, m| {
            let d = m.analysis().elasticity(m.material());
            let mut ke = [[0.0; 2 * MAX_NODES]; 2 * MAX_NODES];
            b.iter(|| {
                (0..n).fold(0.0, |t, e| {
                    old_element_stiffness(m, e, &d, &mut ke);
                    t + ke[0][0]
                })
            })
        });
        group.bench_with_input(BenchmarkId::new("stiffness", label), model, |b, m| {
            b.iter(|| (0..n).fold(0.0, |t, e| t + m.element_stiffness(e).unwrap()[(0, 0)]))
        });
    }
    group.finish();
}

/// The element stiffness of every element of a T6 mesh against a Q8 mesh of about as many
/// nodes: 100 × 100 Q8 (10 000 elements, 30 401 nodes) and 87 × 87 cells of two T6 (15 138
/// elements, 30 625 nodes).
fn triangles(c: &mut Criterion) {
    let models = [
        ("Q8", axisymmetric(ElementKind::Q8, 100, 100)),
        ("T6", axisymmetric(ElementKind::T6, 87, 87)),
    ];
    for (label, model) in &models {
        let mesh = model.mesh();
        println!(
            "{label}: {} elements, {} nodes",
            mesh.elements().len(),
            mesh.nodes().len()
        );
    }
    let mut group = c.benchmark_group("triangles");
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500));
    for (label, model) in &models {
        let n = model.mesh().elements().len();
        group.bench_with_input(BenchmarkId::new("stiffness", label), model, |b, m| {
            b.iter(|| (0..n).fold(0.0, |t, e| t + m.element_stiffness(e).unwrap()[(0, 0)]))
        });
    }
    group.finish();
}

/// The bearing's contact product three ways (see the module's account): each timed, and the
/// largest difference of the last two from the first printed relative to its largest value.
fn bearing_product(c: &mut Criterion) {
    let steel = Material::new(2.1e5, 0.3).unwrap();
    let (nx, ny, dx, dy) = (80, 49, 0.12, 0.0107);
    let origin = [-4.74, -24.0 * dy];
    // Faces 0.2 mm beyond the cells' edges at ±4.8 mm: m = 3 half-cells out.
    let (m, faces) = (3, [Some(-5.0), Some(5.0)]);
    let raceway = HalfSpace::grid("raceway", steel, nx, ny, dx, dy, origin).unwrap();
    let roller = FreeEnds::grid("roller", steel, nx, ny, dx, dy, origin, faces, 1.0)
        .unwrap()
        .upper();
    let (first, n) = (m + nx, nx * ny);
    let width = first + 2 * nx + m;
    let long_origin = [origin[0] - first as f64 * dx, origin[1]];
    let long = HalfSpace::grid("long", steel, width, ny, dx, dy, long_origin).unwrap();
    let force: Vec<f64> = (0..n)
        .map(|k| 1.0 + ((k * 37 % 101) as f64).sin())
        .collect();
    let mut written = vec![0.0; width * ny];
    for j in 0..ny {
        for i in 0..nx {
            let (f, row) = (force[j * nx + i], j * width);
            written[row + first + i] += f;
            written[row + first - m - 1 - i] += f;
            written[row + first + 2 * nx + m - 1 - i] += f;
        }
    }
    let problem = InterfaceProblem::new(&raceway, &roller, &vec![0.0; n]).unwrap();
    let (mut u, mut v, mut out) = (vec![0.0; n], vec![0.0; n], vec![0.0; width * ny]);
    let as_it_was = |u: &mut [f64], out: &mut [f64]| {
        raceway.apply_influence(&force, u);
        long.apply_influence(&written, out);
        for (k, u) in u.iter_mut().enumerate() {
            *u += out[(k / nx) * width + first + k % nx];
        }
    };
    as_it_was(&mut u, &mut out);
    let scale = u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    roller.apply_influence(&force, &mut v);
    let mut sum = vec![0.0; n];
    raceway.apply_influence(&force, &mut sum);
    let read: f64 = (0..n)
        .map(|k| (sum[k] + v[k] - u[k]).abs())
        .fold(0.0, f64::max);
    problem.apply_influence(&force, &mut v);
    let added: f64 = (0..n).map(|k| (v[k] - u[k]).abs()).fold(0.0, f64::max);
    println!(
        "bearing product: read beyond the grid {:.1e}, raceway added {:.1e} of the largest value",
        read / scale,
        added / scale
    );
    let mut group = c.benchmark_group("bearing_product");
    group.bench_function("written_out_and_raceway", |b| {
        b.iter(|| as_it_was(&mut u, &mut out))
    });
    group.bench_function("roller_read_beyond_and_raceway", |b| {
        b.iter(|| {
            raceway.apply_influence(&force, &mut u);
            roller.apply_influence(&force, &mut v);
        })
    });
    group.bench_function("raceway_added", |b| {
        b.iter(|| problem.apply_influence(&force, &mut v))
    });
    group.finish();
}

criterion_group!(benches, principal, elements, triangles, bearing_product);
criterion_main!(benches);
