//! The roller pair against the equivalent single half-space, Hertz's line contact with the
//! local line load, and a finer grid under tilt.

use contopt_contact::{ContactSolver, InterfaceProblem, PolonskyKeer, PolonskyKeerSettings};
use contopt_core::{ContactState, ElasticBody, Material, RigidBody};
use contopt_greens::HalfSpace;
use contopt_roller::{Crown, Roller};

/// The roller: D = 10 mm, l = 10 mm, Q = 5446 N, steel on steel, flat raceway.
fn roller(tilt: f64, crown: Crown) -> Roller {
    let steel = Material::new(2.1e5, 0.3).unwrap();
    Roller {
        diameter: 10.0,
        length: 10.0,
        raceway_diameter: None,
        roller: steel,
        raceway: steel,
        load: 5446.0,
        tilt,
        crown,
    }
}

fn polonsky_keer() -> PolonskyKeer {
    PolonskyKeer::new(PolonskyKeerSettings::default()).unwrap()
}

fn solve(r: &Roller, nx: usize, ny: usize) -> (HalfSpace, ContactState) {
    let (raceway, body, gap) = r.bodies(nx, ny, 2.6).unwrap();
    let state = {
        let problem = InterfaceProblem::new(&raceway, &body, &gap).unwrap();
        let state = polonsky_keer().solve(&problem).unwrap();
        assert!(state.is_converged(), "{}", state.termination);
        state
    };
    (raceway, state)
}

/// Steel on steel as two half-space grids is the rigid cylinder on one half-space of the pair's
/// modulus (E = 1.05·10⁵ MPa at ν = 0.3): the same pressure to 1e-8 of p_max. Hertz: b and p₀ of
/// the nominal line load are the 0.17334 mm and 2000.1 MPa.
#[test]
fn steel_pair_is_the_rigid_roller_on_the_combined_half_space() {
    let r = roller(0.0, Crown::Straight);
    let (b, p0) = r.hertz().unwrap();
    assert!(
        (b / 0.17334 - 1.0).abs() < 1e-4 && (p0 / 2000.1 - 1.0).abs() < 1e-4,
        "{b} {p0}"
    );
    let (raceway, pair) = solve(&r, 50, 27);
    let single = Material::new(1.05e5, 0.3).unwrap();
    let (nx, ny) = raceway.cells();
    let iface = raceway.interface();
    let (dx, dy) = (
        10.0 / nx as f64,
        iface.points()[nx][1] - iface.points()[0][1],
    );
    let origin = [iface.points()[0][0], iface.points()[0][1]];
    let half_space = HalfSpace::grid("half-space", single, nx, ny, dx, dy, origin).unwrap();
    let cylinder =
        RigidBody::pressed("roller", half_space.interface(), [0.0, 0.0, 1.0], 5446.0).unwrap();
    let gap: Vec<f64> = iface.points().iter().map(|x| x[1] * x[1] / 10.0).collect();
    let problem = InterfaceProblem::new(&half_space, &cylinder, &gap).unwrap();
    let rigid = polonsky_keer().solve(&problem).unwrap();
    let dp = pair
        .pressure
        .iter()
        .zip(&rigid.pressure)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
        / rigid.p_max();
    assert!(dp < 1e-8, "{dp:e}");
}

/// The load's centre Σ x p w / Q of the tilted straight roller (γ = 1 arc-minute: the gap grows
/// by 2.9 µm over the length, against an approach of about 4 µm): it moves towards −x, where
/// the gap closes, and agrees between 100 × 53 and 200 × 105 cells within 1 %.
#[test]
fn tilted_roller_converges_with_the_grid() {
    let gamma = (1.0f64 / 60.0).to_radians();
    let centre = |nx: usize, ny: usize| {
        let (raceway, st) = solve(&roller(gamma, Crown::Straight), nx, ny);
        let iface = raceway.interface();
        (0..iface.len())
            .map(|i| iface.points()[i][0] * st.pressure[i] * iface.weights()[i])
            .sum::<f64>()
            / 5446.0
    };
    let (coarse, fine) = (centre(100, 53), centre(200, 105));
    eprintln!("tilted roller: load centre {coarse:.4} mm (100 × 53), {fine:.4} mm (200 × 105)");
    assert!(fine < -0.1, "{fine}");
    assert!((coarse / fine - 1.0).abs() < 0.01, "{coarse} vs {fine}");
}
