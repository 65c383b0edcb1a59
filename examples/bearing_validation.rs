//! The bearing around the roller, validated: the load distribution of a cylindrical roller
//! bearing by ISO/TS 16281's slice model against Stribeck's constant and a 209-size bearing's
//! closed forms, and its rating lives after ISO 281 and ISO/TS 16281 — per load case, from a
//! half-space contact's pressure, and over a duty cycle.
//!
//! `cargo run --example bearing_validation` (seconds in the dev profile).

use contopt::prelude::*;
use contopt::roller::{
    basic_rating_life, dynamic_load_rating, miner, reference_rating_life,
    slice_loads_from_pressure, slice_ratings, BearingLoad, BearingSettings, Crown,
    CylindricalRollerBearing, LoadDistribution, Raceway, Roller, SliceLoads, Tilt, REDUCTION,
};
use contopt_validation::bearing::{
    axial_integral, bearing_209 as bearing, continuous, discrete, radial_integral,
    stribeck_constant, CLEARANCE_209 as CLEARANCE, LINE, LOAD_209 as LOAD, PRINTED,
};

fn solve(b: &CylindricalRollerBearing, radial_n: f64, tilt: Tilt) -> Result<LoadDistribution> {
    let d = b.solve(&BearingLoad { radial_n, tilt }, &BearingSettings::default())?;
    match d.termination.is_converged() {
        true => Ok(d),
        false => Err(Error::invalid("bearing", d.termination, "must converge")),
    }
}

fn arcmin(a: f64) -> f64 {
    (a / 60.0).to_radians()
}

fn stribeck() -> Result<()> {
    let constant = stribeck_constant();
    println!("## Stribeck: straight rollers, no clearance, aligned\n");
    println!(
        "J_r(ε = 0.5) for q ∝ δ^(10/9): {:.5}, so Q_max = F_r/(Z·J_r) = {constant:.4}·F_r/Z\n",
        radial_integral(0.5, LINE)
    );
    println!("The constants NSK prints for zero clearance (CAT. No. E728g, §5.1, eqs. (4), (5)) against the integrals:\n");
    println!(" contact | n | 1/J_r(½) | printed | J_a(½)/J_r(½) | printed");
    for p in PRINTED {
        let (jr, ja) = (
            radial_integral(0.5, p.exponent),
            axial_integral(0.5, p.exponent),
        );
        println!(
            " {} | {} | {:.4} | {} | {:.4} | {:.3}",
            p.contact,
            p.exponent,
            1.0 / jr,
            p.stribeck,
            ja / jr,
            p.axial
        );
    }
    println!(
        " line, ISO/TS 16281 | 10/9 | {constant:.4} | | {:.4} |\n",
        axial_integral(0.5, LINE) / radial_integral(0.5, LINE)
    );
    println!("Q_max is the peak of the distribution, c_L·δ_r^(10/9) at ψ = 0: the heaviest roller's load when a roller");
    println!(
        "sits on the load line; with two rollers astride it, they carry Q_max·cos^(10/9)(π/Z).\n"
    );
    println!(" Z | roller on the load line: Z·Q_max/F_r | closed form | vs 4.085 | rollers astride: Z·Q_max/F_r | closed form | vs 4.085");
    for z in 10..=20 {
        let mut row = format!("{z:2}");
        for first in [0.0, std::f64::consts::PI / z as f64] {
            let mut b = bearing(z, 0.0, Crown::Straight);
            b.first_roller = first;
            let d = solve(&b, LOAD, Tilt::Held(0.0))?;
            let peak = |approach: f64| b.line_constant() * approach.powf(LINE) * z as f64 / LOAD;
            let ours = peak(d.displacement_mm[0]);
            let theirs = peak(discrete(z, first, b.line_constant(), 0.0, LOAD).approach);
            row += &format!(
                " | {ours:.5} | {theirs:.5} | {:+.2} %",
                100.0 * (ours / constant - 1.0)
            );
        }
        println!("{row}");
    }
    Ok(())
}

fn harris_209() -> Result<()> {
    let b = bearing(14, CLEARANCE, Crown::Straight);
    let d = solve(&b, LOAD, Tilt::Held(0.0))?;
    let closed = discrete(14, 0.0, b.line_constant(), CLEARANCE, LOAD);
    let many = continuous(14, b.line_constant(), CLEARANCE, LOAD);
    let crowned = solve(
        &bearing(14, CLEARANCE, Crown::iso(10.0)?),
        LOAD,
        Tilt::Held(0.0),
    )?;
    println!("\n## A 209 cylindrical roller bearing: Z = 14, D = 10 mm, L_we = 9.6 mm, d_m = 65 mm, s = 40.6 µm, F_r = 8900 N\n");
    println!("Roller loads [N] (rollers at ψ > 0 mirror those at ψ < 0):\n");
    println!(
        "  ψ [°] | slice model, straight | closed form (Σ, bisection) | slice model, ISO crown"
    );
    for j in 0..=3 {
        println!(
            "  {:5.1} | {:9.2} | {:9.2} | {:9.2}",
            d.rollers[j].angle.to_degrees(),
            d.rollers[j].load_n,
            closed.loads[j],
            crowned.rollers[j].load_n
        );
    }
    println!(
        "\n  Q_max {:.1} N = {:.3}·F_r/Z; ε = {:.4}; loaded zone ±{:.2}° (cos ψ_l = s/(2δ_r), δ_r = {:.2} µm)",
        d.max_load(),
        d.max_load() * 14.0 / LOAD,
        d.load_factor(),
        d.load_zone().to_degrees(),
        1e3 * d.displacement_mm[0]
    );
    println!(
        "  Harris's iteration with J_r(ε) (rollers smeared over the ring): Q_max {:.1} N, ε = {:.4}, ±{:.2}°",
        many.max_load,
        many.epsilon,
        many.zone.to_degrees()
    );
    println!("  Harris & Kotzalas's printed roller loads and loaded zone of their 209 bearing: not found to compare.");
    Ok(())
}

/// The reference rating life of `d` with its loaded rollers' inner contacts replaced by a
/// half-space contact's slice loads (a grid of 96 × 31 cells, Polonsky–Keer).
fn half_space_life(b: &CylindricalRollerBearing, d: &LoadDistribution, rating: f64) -> Result<f64> {
    let steel = Material::new(2.1e5, 0.3)?;
    let solver = PolonskyKeer::new(PolonskyKeerSettings::default())?;
    let mut loads = SliceLoads::from_distribution(d)?;
    for case in d.roller_cases(Raceway::Inner) {
        let roller = Roller {
            diameter: b.roller_diameter,
            length: b.effective_length(),
            raceway_diameter: Some(b.pitch_diameter - b.roller_diameter),
            roller: steel,
            raceway: steel,
            load: case.load_n,
            tilt: arcmin(case.tilt_arcmin),
            crown: b.roller_crown.clone(),
        };
        let (raceway, body, gap) = roller.bodies(96, 31, 2.6)?;
        let problem = InterfaceProblem::new(&raceway, &body, &gap)?;
        let state = solver.solve(&problem)?;
        let cell = roller.cell(96, 31, 2.6)?;
        let points = raceway.interface().points();
        let slices =
            slice_loads_from_pressure(points, &state.pressure, cell, roller.length, b.slices)?;
        loads.set(Raceway::Inner, case.roller, &slices)?;
    }
    Ok(reference_rating_life(&slice_ratings(b, rating)?, &loads, Raceway::Inner)?.bearing)
}

fn lives() -> Result<()> {
    let iso = Crown::iso(10.0)?;
    let rating = dynamic_load_rating(&bearing(14, 0.0, Crown::Straight))?;
    let ratings = slice_ratings(&bearing(14, 0.0, Crown::Straight), rating)?;
    println!("\n## Rating lives of the 209 bearing [10⁶ revolutions], inner ring rotating\n");
    println!(
        "ISO 281: C_r = b_m·f_c·L_we^(7/9)·Z^(3/4)·D_we^(29/27) = {rating:.0} N (b_m = 1.1, f_c({:.4}) interpolated)",
        10.0 / 65.0
    );
    println!(
        "ISO/TS 16281: slice ratings q_ci = {:.1} N, q_ce = {:.1} N (n_s = 30)\n",
        ratings.inner, ratings.outer
    );
    println!("  C_r/P | ISO 281 L10 | (C_r/(λν·P))^4 | TS L10r, straight | TS L10r, ISO crown | TS/ISO 281 (crown)");
    for ratio in [1.5, 2.0, 4.0, 8.0] {
        let p = rating / ratio;
        let l10 = basic_rating_life(rating, p)?;
        let mut row = format!(
            "  {ratio:5.1} | {l10:11.2} | {:14.2}",
            (ratio / REDUCTION).powi(4)
        );
        let mut crowned = 0.0;
        for crown in [Crown::Straight, iso.clone()] {
            let b = bearing(14, 0.0, crown);
            let d = solve(&b, p, Tilt::Held(0.0))?;
            crowned = reference_rating_life(
                &ratings,
                &SliceLoads::from_distribution(&d)?,
                Raceway::Inner,
            )?
            .bearing;
            row += &format!(" | {crowned:17.2}");
        }
        println!("{row} | {:.3}", crowned / l10);
    }
    println!(
        "\nAt F_r = 8900 N, ISO crown: ISO 281 L10 = {:.1}",
        basic_rating_life(rating, LOAD)?
    );
    println!("  clearance [µm] | misalignment [′] | Q_max [N] | TS L10r, slice model | TS L10r, inner contacts by the half-space");
    let mut cases = vec![];
    for (clearance, tilt) in [
        (0.0, 0.0),
        (CLEARANCE, 0.0),
        (CLEARANCE, 2.0),
        (CLEARANCE, 4.0),
    ] {
        let b = bearing(14, clearance, iso.clone());
        let d = solve(&b, LOAD, Tilt::Held(arcmin(tilt)))?;
        let slices = reference_rating_life(
            &ratings,
            &SliceLoads::from_distribution(&d)?,
            Raceway::Inner,
        )?
        .bearing;
        let half_space = half_space_life(&b, &d, rating)?;
        println!(
            "  {:14.1} | {tilt:16.0} | {:9.1} | {slices:20.2} | {half_space:.2}",
            1e3 * clearance,
            d.max_load()
        );
        cases.push((b, d));
    }
    let (_, misaligned) = &cases[3];
    println!("\nThe rollers of the 4′ case as load cases on the inner raceway (the robust crown's envelope):");
    for c in misaligned.roller_cases(Raceway::Inner) {
        println!(
            "  roller {:2}: {:7.1} N, tilt {:+.3}′",
            c.roller, c.load_n, c.tilt_arcmin
        );
    }
    duty_cycle(rating, &ratings, &iso)
}

fn duty_cycle(rating: f64, ratings: &contopt::roller::SliceRatings, iso: &Crown) -> Result<()> {
    println!("\n## A duty cycle (Palmgren–Miner, L = 1/Σ t_i/L_i), ISO crown, s = 40.6 µm\n");
    println!("  fraction | F_r [N] | misalignment [′] | ISO 281 L10 | TS L10r");
    let mut iso281 = vec![];
    let mut ts = vec![];
    for (fraction, load, tilt) in [
        (0.5, LOAD, 0.0),
        (0.3, 0.5 * LOAD, 2.0),
        (0.2, 1.5 * LOAD, 4.0),
    ] {
        let b = bearing(14, CLEARANCE, iso.clone());
        let d = solve(&b, load, Tilt::Held(arcmin(tilt)))?;
        let l10 = basic_rating_life(rating, load)?;
        let l10r =
            reference_rating_life(ratings, &SliceLoads::from_distribution(&d)?, Raceway::Inner)?
                .bearing;
        println!("  {fraction:8.1} | {load:7.0} | {tilt:16.0} | {l10:11.2} | {l10r:.2}");
        iso281.push((fraction, l10));
        ts.push((fraction, l10r));
    }
    println!(
        "  duty cycle: ISO 281 {:.2}, ISO/TS 16281 {:.2}",
        miner(&iso281)?,
        miner(&ts)?
    );
    Ok(())
}

fn main() -> Result<()> {
    stribeck()?;
    harris_209()?;
    lives()
}
