//! The report stage of a bearing's lives: from every load case's slice loads (the slice
//! model's, and the half-space contacts' per crown of the tolerance band) to the rating
//! lives per load case and over the duty cycle, per ring and combined, in revolutions and,
//! at a speed, in hours, and modified by ISO 281's a_ISO when the lubrication is given.
//!
//! Which figure comes from where: L₁₀ = (C_r/F_r)^(10/3) and L_nm = a_ISO·L₁₀ are ISO 281's
//! (a₁ = 1, 90 % reliability); L₁₀r is ISO/TS 16281's reference rating life from the slices,
//! each raceway's [Σ_k (q_c/q_e,k)^(9/2)]^(−8/9) and the bearing's (L_i^(−9/8) + L_e^(−9/8))^(−8/9)
//! ([`reference_rating_life`]); L_nmr is ISO/TS 16281's modified reference life with a_ISO
//! per slice ([`modified_reference_rating_life`]), each slice's e_C·C_u/P taken as e_C·q_u/q_e,k
//! with q_u the slice's fatigue load limit (a Hertzian slice at ISO 281's 1500 MPa: this
//! crate's form, the standard's text could not be read here). The duty cycle's lives are
//! Palmgren–Miner's ([`miner`]).

use contopt_core::Result;
use contopt_results::{LifeHours, Lives, ModifiedLives};
use contopt_roller::{
    basic_rating_life, hours, life_modification_factor, miner, modified_reference_rating_life,
    reference_rating_life, Raceway, ReferenceLife, SliceLoads, SliceRatings,
};

/// One load case's slice loads.
#[derive(Clone, Debug)]
pub(crate) struct CaseSlices {
    /// Its radial load F_r \[N\] (ISO 281's P).
    pub radial_n: f64,
    /// Its time fraction of the duty cycle.
    pub fraction: f64,
    /// The slice model's slice loads.
    pub slice_model: SliceLoads,
    /// Per crown of the tolerance band: the half-space contacts' slice loads, and those
    /// raised to the Hertzian load of each slice's peak pressure.
    pub bands: Vec<[SliceLoads; 2]>,
}

/// ISO 281's lubrication figures for a_ISO: κ = ν/ν₁, and e_C·C_u.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Lubrication {
    pub kappa: f64,
    /// e_C·C_u \[N\].
    pub contaminated_limit_n: f64,
    /// e_C times each raceway's slice fatigue load limit (inner, outer) \[N\]: the load of a
    /// Hertzian slice at ISO 281's 1500 MPa ([`contopt_roller::FATIGUE_STRESS_MPA`]).
    pub contaminated_slice_limits_n: [f64; 2],
}

/// What the stage takes: the ratings, the rotating ring, the load cases' slices, and the
/// speed and lubrication when the scene gives them.
pub(crate) struct LivesInput<'a> {
    /// ISO 281's C_r \[N\].
    pub rating: f64,
    /// ISO/TS 16281's slice ratings.
    pub ratings: &'a SliceRatings,
    /// The ring that rotates against the load.
    pub rotating: Raceway,
    pub cases: &'a [CaseSlices],
    /// The speed \[min⁻¹\].
    pub speed_rpm: Option<f64>,
    pub lubrication: Option<Lubrication>,
}

/// What the stage gives: each load case's lives and hours, and the duty cycle's.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LivesOutput {
    pub per_case: Vec<Lives>,
    pub per_case_hours: Vec<Option<LifeHours>>,
    pub duty: Lives,
    pub duty_hours: Option<LifeHours>,
}

/// The lives of `input`.
pub(crate) fn lives(input: &LivesInput) -> Result<LivesOutput> {
    let per_case = (input.cases.iter())
        .map(|c| case_lives(input, c))
        .collect::<Result<Vec<Lives>>>()?;
    let duty = duty_cycle(input, &per_case)?;
    let in_hours = |l: &Lives| input.speed_rpm.map(|n| life_hours(l, n)).transpose();
    Ok(LivesOutput {
        per_case_hours: per_case.iter().map(in_hours).collect::<Result<_>>()?,
        duty_hours: in_hours(&duty)?,
        per_case,
        duty,
    })
}

/// ISO/TS 16281's reference life of `loads`.
fn reference(input: &LivesInput, loads: &SliceLoads) -> Result<ReferenceLife> {
    reference_rating_life(input.ratings, loads, input.rotating)
}

/// One load case's lives: the half-space's and the raised ones the band's worst.
fn case_lives(input: &LivesInput, case: &CaseSlices) -> Result<Lives> {
    let (mut half_space, mut peak) = (None::<(ReferenceLife, &SliceLoads)>, f64::INFINITY);
    for [loads, raised] in &case.bands {
        let life = reference(input, loads)?;
        if half_space.is_none_or(|h| life.bearing < h.0.bearing) {
            half_space = Some((life, loads));
        }
        peak = peak.min(reference(input, raised)?.bearing);
    }
    let (half_space, loads) = match half_space {
        Some(h) => h,
        None => (reference(input, &case.slice_model)?, &case.slice_model),
    };
    let iso = basic_rating_life(input.rating, case.radial_n)?;
    let modified = match input.lubrication {
        Some(lub) => Some(modified(
            input,
            &lub,
            case.radial_n,
            iso,
            (half_space, loads),
        )?),
        None => None,
    };
    Ok(Lives {
        iso_281_mrev: iso,
        slice_model_mrev: reference(input, &case.slice_model)?.bearing,
        half_space_mrev: half_space.bearing,
        peak_pressure_mrev: peak,
        rings_mrev: [half_space.inner, half_space.outer],
        modified,
    })
}

/// ISO 281's and ISO/TS 16281's modified lives of a load case: L_nm = a_ISO(e_C·C_u/F_r)·L₁₀,
/// and L_nmr with a_ISO per slice ([`modified_reference_rating_life`]): slice k of a raceway
/// at a_ISO(κ, e_C·q_u/q_e,k), q_u the raceway's slice fatigue load limit and q_e,k the
/// slice's equivalent load, `reference` = (L₁₀r, the slice loads it was taken from). The
/// reported a_ISO of L_nmr is L_nmr/L₁₀r.
fn modified(
    input: &LivesInput,
    lub: &Lubrication,
    radial: f64,
    l10: f64,
    (l10r, loads): (ReferenceLife, &SliceLoads),
) -> Result<ModifiedLives> {
    let a_iso = life_modification_factor(lub.kappa, lub.contaminated_limit_n / radial)?;
    let per_slice = |raceway: Raceway, q: f64| {
        let limit = match raceway {
            Raceway::Inner => lub.contaminated_slice_limits_n[0],
            Raceway::Outer => lub.contaminated_slice_limits_n[1],
        };
        life_modification_factor(lub.kappa, limit / q)
    };
    let nmr =
        modified_reference_rating_life(input.ratings, loads, input.rotating, per_slice)?.bearing;
    Ok(ModifiedLives {
        a_iso,
        modified_mrev: a_iso * l10,
        a_iso_reference: nmr / l10r.bearing,
        modified_reference_mrev: nmr,
    })
}

/// Palmgren–Miner's lives over the load cases, each life on its own; a duty cycle's a_ISO
/// are the ratios of its modified lives to their basic ones.
fn duty_cycle(input: &LivesInput, per_case: &[Lives]) -> Result<Lives> {
    let cycle = |f: &dyn Fn(&Lives) -> f64| -> Result<f64> {
        let cases: Vec<(f64, f64)> = (input.cases.iter().zip(per_case))
            .map(|(c, l)| (c.fraction, f(l)))
            .collect();
        miner(&cases)
    };
    let iso = cycle(&|l| l.iso_281_mrev)?;
    let half_space = cycle(&|l| l.half_space_mrev)?;
    let modified = match input.lubrication {
        Some(_) => {
            let m = |l: &Lives| l.modified.map_or(f64::NAN, |m| m.modified_mrev);
            let r = |l: &Lives| l.modified.map_or(f64::NAN, |m| m.modified_reference_mrev);
            let (nm, nmr) = (cycle(&m)?, cycle(&r)?);
            Some(ModifiedLives {
                a_iso: nm / iso,
                modified_mrev: nm,
                a_iso_reference: nmr / half_space,
                modified_reference_mrev: nmr,
            })
        }
        None => None,
    };
    Ok(Lives {
        iso_281_mrev: iso,
        slice_model_mrev: cycle(&|l| l.slice_model_mrev)?,
        half_space_mrev: half_space,
        peak_pressure_mrev: cycle(&|l| l.peak_pressure_mrev)?,
        rings_mrev: [cycle(&|l| l.rings_mrev[0])?, cycle(&|l| l.rings_mrev[1])?],
        modified,
    })
}

/// `lives` in hours at `speed_rpm`.
fn life_hours(lives: &Lives, speed_rpm: f64) -> Result<LifeHours> {
    let h = |mrev: f64| hours(mrev, speed_rpm);
    Ok(LifeHours {
        iso_281_h: h(lives.iso_281_mrev)?,
        half_space_h: h(lives.half_space_mrev)?,
        modified_h: lives.modified.map(|m| h(m.modified_mrev)).transpose()?,
        modified_reference_h: (lives.modified)
            .map(|m| h(m.modified_reference_mrev))
            .transpose()?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Slices of 2 rollers × 3 slices, each ring's load `q` on every slice of roller 0.
    fn slices(inner: f64, outer: f64) -> SliceLoads {
        let mut loads = SliceLoads::new(2, 3).unwrap();
        loads.set(Raceway::Inner, 0, &[inner; 3]).unwrap();
        loads.set(Raceway::Outer, 0, &[outer; 3]).unwrap();
        loads
    }

    fn case(radial: f64, fraction: f64, bands: Vec<[SliceLoads; 2]>) -> CaseSlices {
        CaseSlices {
            radial_n: radial,
            fraction,
            slice_model: slices(100.0, 100.0),
            bands,
        }
    }

    const RATINGS: SliceRatings = SliceRatings {
        inner: 2000.0,
        outer: 2500.0,
    };

    fn input<'a>(cases: &'a [CaseSlices], lubrication: Option<Lubrication>) -> LivesInput<'a> {
        LivesInput {
            rating: 50e3,
            ratings: &RATINGS,
            rotating: Raceway::Inner,
            cases,
            speed_rpm: Some(1500.0),
            lubrication,
        }
    }

    /// The half-space life is the band's worst and its rings are that band's; the combined
    /// life is ISO/TS 16281's of the rings, (L_i^(−9/8) + L_e^(−9/8))^(−8/9); the raised
    /// slices never live longer; hours are 10⁶·L/(60·n).
    #[test]
    fn a_load_case_takes_its_bands_worst() {
        let bands = vec![
            [slices(120.0, 110.0), slices(130.0, 110.0)],
            [slices(150.0, 100.0), slices(150.0, 100.0)],
        ];
        let cases = [case(5000.0, 1.0, bands)];
        let out = lives(&input(&cases, None)).unwrap();
        let l = &out.per_case[0];
        let worst = reference_rating_life(&RATINGS, &slices(150.0, 100.0), Raceway::Inner).unwrap();
        assert_eq!(l.half_space_mrev, worst.bearing);
        assert_eq!(l.rings_mrev, [worst.inner, worst.outer]);
        let [li, le] = l.rings_mrev;
        let combined = (li.powf(-9.0 / 8.0) + le.powf(-9.0 / 8.0)).powf(-8.0 / 9.0);
        assert!((combined / l.half_space_mrev - 1.0).abs() < 1e-12);
        assert!(l.peak_pressure_mrev <= l.half_space_mrev);
        assert_eq!(l.iso_281_mrev, (50.0f64 / 5.0).powf(10.0 / 3.0));
        let h = out.per_case_hours[0].unwrap();
        assert!((h.iso_281_h - 1e6 * l.iso_281_mrev / 90_000.0).abs() < 1e-9 * h.iso_281_h);
        assert!(l.modified.is_none() && h.modified_h.is_none());
    }

    /// With lubrication, L_nm = a_ISO·L₁₀ at P = F_r, and L_nmr with a_ISO per slice: here
    /// every loaded slice of a ring carries the same equivalent load q_e (the inner ring
    /// rotates: q·(1/2)^(1/4) over the 2 rollers, the outer q·(1/2)^(2/9)), so each ring's
    /// life is multiplied by a_ISO(κ, e_C·q_u/q_e) of its own, and the bearing's is the rings'
    /// combined ((a_i·L_i)^(−9/8) + (a_e·L_e)^(−9/8))^(−8/9); over a duty cycle every life,
    /// the modified ones too, is Palmgren–Miner's of the load cases'.
    #[test]
    fn modified_lives_and_the_duty_cycle() {
        let lub = Lubrication {
            kappa: 1.5,
            contaminated_limit_n: 0.5 * 6000.0,
            contaminated_slice_limits_n: [40.0, 60.0],
        };
        let bands = |q: f64| vec![[slices(q, q), slices(q, q)]];
        let cases = [
            case(5000.0, 0.75, bands(120.0)),
            case(9000.0, 0.25, bands(200.0)),
        ];
        let out = lives(&input(&cases, Some(lub))).unwrap();
        for (l, c) in out.per_case.iter().zip(&cases) {
            let m = l.modified.unwrap();
            let a = life_modification_factor(1.5, 3000.0 / c.radial_n).unwrap();
            assert_eq!(m.a_iso, a);
            assert!((m.modified_mrev / (a * l.iso_281_mrev) - 1.0).abs() < 1e-12);
            let q = c.bands[0][0].roller(Raceway::Inner, 0)[0];
            let a_ring = |limit: f64, mean: f64| {
                life_modification_factor(1.5, limit / (q * 0.5f64.powf(1.0 / mean))).unwrap()
            };
            let (a_i, a_e) = (a_ring(40.0, 4.0), a_ring(60.0, 4.5));
            assert!(a_i != a_e && a_i > 0.1);
            let [l_i, l_e] = l.rings_mrev;
            let want =
                ((a_i * l_i).powf(-9.0 / 8.0) + (a_e * l_e).powf(-9.0 / 8.0)).powf(-8.0 / 9.0);
            assert!((m.modified_reference_mrev / want - 1.0).abs() < 1e-12);
            assert!((m.a_iso_reference - want / l.half_space_mrev).abs() < 1e-12);
        }
        let miner = |f: &dyn Fn(&Lives) -> f64| {
            1.0 / (0.75 / f(&out.per_case[0]) + 0.25 / f(&out.per_case[1]))
        };
        let duty = &out.duty;
        let m = duty.modified.unwrap();
        assert!(
            (m.modified_mrev / miner(&|l| l.modified.unwrap().modified_mrev) - 1.0).abs() < 1e-12
        );
        assert!((duty.rings_mrev[1] / miner(&|l| l.rings_mrev[1]) - 1.0).abs() < 1e-12);
        assert!((m.a_iso - m.modified_mrev / duty.iso_281_mrev).abs() < 1e-12);
        let h = out.duty_hours.unwrap();
        assert!((h.modified_h.unwrap() - 1e6 * m.modified_mrev / 90_000.0).abs() < 1e-6);
    }
}
