//! Lives as engineers quote them: in hours at a speed, and ISO 281's modified rating life
//! L_nm = a₁·a_ISO·L₁₀ with the life modification factor a_ISO of a radial roller bearing from
//! the lubrication (the viscosity ratio κ = ν/ν₁), the contamination e_C and the fatigue load
//! limit C_u.
//!
//! Sources: ISO 281:2007, *Rolling bearings — Dynamic load ratings and rating life*, clause 9.3
//! (a_ISO for radial roller bearings, the rated viscosity ν₁, the fatigue load limit C_u of
//! Annex B's simplified form) and ISO 76:2006, *Rolling bearings — Static load ratings*
//! (C_0r of radial roller bearings). The standards' texts could not be read here: the
//! constants are those the standard's implementations quote, and the tests hold what the
//! formulas must do whatever their source (a_ISO continuous where its branches meet, 0.1 with
//! nothing of the fatigue limit, capped at 50; ν₁ continuous within 2.5 % at 1000 min⁻¹, where
//! its two forms meet).

use contopt_core::{check, Error, Result};

use crate::CylindricalRollerBearing;

/// a_ISO's cap (ISO 281:2007, 9.3.1: a_ISO ≤ 50).
pub const A_ISO_MAX: f64 = 50.0;

/// The viscosity ratio κ past which a_ISO no longer grows (ISO 281: κ > 4 is taken as 4).
pub const KAPPA_MAX: f64 = 4.0;

/// The least viscosity ratio a_ISO's formula holds for (ISO 281: below κ = 0.1 it does not
/// apply).
pub const KAPPA_MIN: f64 = 0.1;

/// ISO 281:2007's a_ISO of a radial roller bearing (clause 9.3.2.3):
/// a_ISO = 0.1·[1 − (1.5859 − c₁/κ^e)·(e_C·C_u/P)^0.4]^(−9.185), with
/// (c₁, e) = (1.3993, 0.054381) for 0.1 ≤ κ < 0.4, (1.2348, 0.19087) for 0.4 ≤ κ < 1 and
/// (1.2348, 0.071739) for 1 ≤ κ ≤ 4; κ > 4 is taken as 4, and a_ISO is capped at 50 (also
/// where the bracket falls to zero or below). `load_ratio` is e_C·C_u/P ≥ 0. An error below
/// κ = 0.1, where the standard's formula does not apply.
pub fn life_modification_factor(kappa: f64, load_ratio: f64) -> Result<f64> {
    check::non_negative("e_C·C_u/P", load_ratio)?;
    check::finite("kappa", kappa)?;
    if kappa < KAPPA_MIN {
        return Err(Error::invalid(
            "kappa (ν/ν₁)",
            kappa,
            format!(
                "is below {KAPPA_MIN}, where ISO 281's a_ISO does not apply (the lubricant \
                 is far too thin for the speed): a thicker oil or a higher speed"
            ),
        ));
    }
    let kappa = kappa.min(KAPPA_MAX);
    let (c1, e) = if kappa < 0.4 {
        (1.3993, 0.054381)
    } else if kappa < 1.0 {
        (1.2348, 0.19087)
    } else {
        (1.2348, 0.071739)
    };
    let bracket = 1.0 - (1.5859 - c1 / kappa.powf(e)) * load_ratio.powf(0.4);
    if bracket <= 0.0 {
        return Ok(A_ISO_MAX);
    }
    Ok((0.1 * bracket.powf(-9.185)).min(A_ISO_MAX))
}

/// ISO 281:2007's rated viscosity ν₁ \[mm²/s\], the viscosity a lubricant needs at the
/// operating temperature for a bearing of pitch diameter D_pw \[mm\] at `speed_rpm` n
/// \[min⁻¹\]: ν₁ = 45000·n^(−0.83)·D_pw^(−0.5) below 1000 min⁻¹, 4500·n^(−0.5)·D_pw^(−0.5)
/// from 1000 min⁻¹.
pub fn rated_viscosity(speed_rpm: f64, pitch_diameter: f64) -> Result<f64> {
    check::positive("speed_rpm", speed_rpm)?;
    check::positive("pitch_diameter_mm", pitch_diameter)?;
    let per_size = pitch_diameter.powf(-0.5);
    Ok(match speed_rpm < 1000.0 {
        true => 45000.0 * speed_rpm.powf(-0.83) * per_size,
        false => 4500.0 * speed_rpm.powf(-0.5) * per_size,
    })
}

/// ISO 76's basic static radial load rating of a radial roller bearing \[N\] (one row,
/// α = 0): C_0r = 44·(1 − D_we/D_pw)·Z·L_we·D_we.
pub fn static_load_rating(bearing: &CylindricalRollerBearing) -> Result<f64> {
    bearing.check()?;
    let d = bearing.roller_diameter;
    Ok(44.0
        * (1.0 - d / bearing.pitch_diameter)
        * bearing.rollers as f64
        * bearing.effective_length()
        * d)
}

/// The contact stress at which ISO 281 sets the fatigue load limit \[MPa\]: C_u is the load
/// under which the most heavily loaded raceway contact reaches 1500 MPa (bearing steel of
/// common quality). ISO/TS 16281's modified reference life takes a_ISO per slice; this crate
/// gives each slice the fatigue load limit of a Hertzian slice at this stress (scaled by
/// √(C_u/C_u,ISO) when a catalogue's C_u replaces ISO 281's), since a line contact's load goes
/// as the square of its peak pressure.
pub const FATIGUE_STRESS_MPA: f64 = 1500.0;

/// The pitch diameter past which ISO 281's C_u falls with size \[mm\].
const FATIGUE_SIZE: f64 = 100.0;

/// ISO 281:2007's fatigue load limit of a roller bearing \[N\] from its C_0r (Annex B's
/// simplified form): C_u = C_0r/8.2 up to D_pw = 100 mm, C_0r/8.2·(100/D_pw)^0.3 above.
pub fn fatigue_load_limit(bearing: &CylindricalRollerBearing) -> Result<f64> {
    let c0 = static_load_rating(bearing)?;
    let size = (FATIGUE_SIZE / bearing.pitch_diameter).min(1.0);
    Ok(c0 / 8.2 * size.powf(0.3))
}

/// ISO 3448's viscosity grades: an ISO VG grade is the lubricant's mid-point kinematic
/// viscosity at 40 °C \[mm²/s\].
pub const ISO_VG_GRADES: [f64; 20] = [
    2.0, 3.0, 5.0, 7.0, 10.0, 15.0, 22.0, 32.0, 46.0, 68.0, 100.0, 150.0, 220.0, 320.0, 460.0,
    680.0, 1000.0, 1500.0, 2200.0, 3200.0,
];

/// The Ubbelohde–Walther constant of ASTM D341: log log(ν + 0.7), ν \[mm²/s\], is linear in
/// log T; the 0.7 holds for ν from 2 mm²/s up (below, D341 adds correction terms this
/// crate does not).
const WALTHER: f64 = 0.7;

/// The least kinematic viscosity the Ubbelohde–Walther relation with the constant 0.7 holds for
/// \[mm²/s\].
pub const WALTHER_MIN_VISCOSITY: f64 = 2.0;

/// The operating temperatures a viscosity is carried to \[°C\]: from −20 °C to 150 °C, where
/// mineral and synthetic bearing oils are used and ASTM D341's charts reach.
pub const OPERATING_TEMPERATURE_C: [f64; 2] = [-20.0, 150.0];

/// Absolute zero on the Celsius scale.
const KELVIN: f64 = 273.15;

/// The kinematic viscosity \[mm²/s\] at `temperature_c` of a lubricant of `nu_40` at 40 °C
/// and `nu_100` at 100 °C, by the Ubbelohde–Walther relation of ASTM D341:
/// log₁₀ log₁₀(ν + 0.7) = A − B·log₁₀ T (T in kelvin), A and B through the two given points.
/// Errors: ν₁₀₀ not below ν₄₀, either below 2 mm²/s ([`WALTHER_MIN_VISCOSITY`]), a
/// temperature outside [`OPERATING_TEMPERATURE_C`], or a result below 2 mm²/s.
pub fn viscosity_at_temperature(nu_40: f64, nu_100: f64, temperature_c: f64) -> Result<f64> {
    for (field, nu) in [
        ("viscosity_40_mm2_s", nu_40),
        ("viscosity_100_mm2_s", nu_100),
    ] {
        if !(nu >= WALTHER_MIN_VISCOSITY && nu.is_finite()) {
            return Err(Error::invalid(
                field,
                nu,
                format!("must be at least {WALTHER_MIN_VISCOSITY} mm²/s (ASTM D341's relation)"),
            ));
        }
    }
    if nu_100 >= nu_40 {
        return Err(Error::invalid(
            "viscosity_100_mm2_s",
            nu_100,
            format!("must be below the viscosity at 40 °C ({nu_40} mm²/s): oils thin when warm"),
        ));
    }
    let [low, high] = OPERATING_TEMPERATURE_C;
    if !(low..=high).contains(&temperature_c) {
        return Err(Error::invalid(
            "temperature_c",
            temperature_c,
            format!("must lie in {low} to {high} °C"),
        ));
    }
    let walther = |nu: f64| (nu + WALTHER).log10().log10();
    let log_t = |c: f64| (c + KELVIN).log10();
    let slope = (walther(nu_40) - walther(nu_100)) / (log_t(100.0) - log_t(40.0));
    let w = walther(nu_40) - slope * (log_t(temperature_c) - log_t(40.0));
    let nu = 10f64.powf(10f64.powf(w)) - WALTHER;
    if nu < WALTHER_MIN_VISCOSITY {
        return Err(Error::invalid(
            "temperature_c",
            temperature_c,
            format!("thins the oil to {nu:.2} mm²/s, below ASTM D341's 2 mm²/s"),
        ));
    }
    Ok(nu)
}

/// A life of `mrev` millions of revolutions in hours at `speed_rpm`: 10⁶·L/(60·n).
pub fn hours(mrev: f64, speed_rpm: f64) -> Result<f64> {
    check::non_negative("life_mrev", mrev)?;
    check::positive("speed_rpm", speed_rpm)?;
    Ok(1e6 * mrev / (60.0 * speed_rpm))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::basic_rating_life;
    use crate::bearing::bearing_209;

    /// The branches of a_ISO meet where κ changes branch (0.4 and 1: the constants' pairs
    /// give 1.3993/0.4^0.054381 = 1.2348/0.4^0.19087 = 1.4708 within 2e-5), a_ISO is 0.1
    /// when the fatigue limit counts for nothing (e_C = 0), it grows with κ and with e_C·C_u/P,
    /// κ past 4 is 4, and a_ISO is capped at 50; κ below 0.1 is refused.
    #[test]
    fn a_iso_is_continuous_and_bounded() {
        for ratio in [0.05, 0.2, 0.5] {
            for at in [0.4, 1.0] {
                let below = life_modification_factor(at * (1.0 - 1e-12), ratio).unwrap();
                let above = life_modification_factor(at, ratio).unwrap();
                assert!((below / above - 1.0).abs() < 1e-4, "{at}: {below} {above}");
            }
            assert!(life_modification_factor(0.2, 0.0).unwrap() == 0.1);
            // At κ = 0.1 the lubrication leaves nothing to the fatigue limit: 1.5859 =
            // 1.3993/0.1^0.054381 within 1e-4, and a_ISO is 0.1.
            let least = life_modification_factor(KAPPA_MIN, ratio).unwrap();
            assert!((least / 0.1 - 1.0).abs() < 1e-3, "{least}");
            let mut last = 0.0;
            for kappa in [0.1, 0.2, 0.5, 1.0, 2.0, 4.0] {
                let a = life_modification_factor(kappa, ratio).unwrap();
                assert!(a > last, "{kappa}: {a}");
                last = a;
            }
            assert_eq!(life_modification_factor(9.0, ratio).unwrap(), last);
        }
        assert_eq!(life_modification_factor(4.0, 5.0).unwrap(), A_ISO_MAX);
        let e = life_modification_factor(0.05, 0.1).unwrap_err().to_string();
        assert!(e.contains("kappa") && e.contains("0.1"), "{e}");
    }

    /// ν₁'s two forms nearly meet at 1000 min⁻¹ (145.6 and 142.3 mm²/s·√mm: 2.3 % apart),
    /// and ν₁ falls with speed and size.
    #[test]
    fn rated_viscosity_falls_with_speed() {
        let below = rated_viscosity(999.999, 100.0).unwrap();
        let above = rated_viscosity(1000.0, 100.0).unwrap();
        assert!((below / above - 1.0).abs() < 0.025, "{below} {above}");
        assert!(rated_viscosity(3000.0, 100.0).unwrap() < above);
        assert!(rated_viscosity(3000.0, 200.0).unwrap() < rated_viscosity(3000.0, 100.0).unwrap());
    }

    /// The Ubbelohde–Walther line goes through its two points (40 and 100 °C), and between
    /// and beyond them log log(ν + 0.7) is linear in log T: at 70 °C written out by hand for
    /// an oil of 68 and 8.7 mm²/s (an ISO VG 68 mineral oil of viscosity index about 95):
    /// W(68) = 0.26410, W(8.7) = −0.01183, log T = 2.49575, 2.57188 and 2.53548 at 40, 100 and
    /// 70 °C, so W(70 °C) = 0.26410 − 0.27593·(0.03973/0.07613) = 0.12010 and ν = 20.12 mm²/s
    /// (the bundled bearing's "about 20 mm²/s at 70 °C"); at 0 °C, 1033 mm²/s. Outside its
    /// ranges it refuses (an oil of 2.5 and 2.1 mm²/s thins below 2 mm²/s at 150 °C).
    #[test]
    fn viscosity_follows_ubbelohde_walther() {
        for (t, want) in [(40.0, 68.0), (100.0, 8.7)] {
            let nu = viscosity_at_temperature(68.0, 8.7, t).unwrap();
            assert!((nu - want).abs() < 1e-9 * want, "{t}: {nu}");
        }
        let nu = viscosity_at_temperature(68.0, 8.7, 70.0).unwrap();
        assert!((nu - 20.12).abs() < 0.01, "{nu}");
        let cold = viscosity_at_temperature(68.0, 8.7, 0.0).unwrap();
        assert!((cold - 1033.2).abs() < 0.1, "{cold}");
        for (a, b, t, field) in [
            (68.0, 80.0, 70.0, "viscosity_100"),
            (68.0, 1.0, 70.0, "viscosity_100"),
            (68.0, 8.7, 200.0, "temperature_c"),
            (2.5, 2.1, 150.0, "temperature_c"),
        ] {
            let e = viscosity_at_temperature(a, b, t).unwrap_err().to_string();
            assert!(e.contains(field), "{e}");
        }
    }

    /// NTN CAT.No.2203/E, Example 6: an NUP312 (C_r = 137 kN, the catalogue's) under
    /// F_r = 10 kN at 2000 min⁻¹ has L₁₀h = 10⁶/(60·2000)·(137/10)^(10/3) = 51 300 h, which
    /// the catalogue prints as about 51 000 h.
    #[test]
    fn ntn_example_6_in_hours() {
        let l10 = basic_rating_life(137e3, 10e3).unwrap();
        let h = hours(l10, 2000.0).unwrap();
        assert!((h / 51_000.0 - 1.0).abs() < 0.01, "{h}");
    }

    /// ISO 76's C_0r and ISO 281's C_u of the bundled 209-size bearing (Z = 14,
    /// D_we = 10 mm, L_we = 9.6 mm, D_pw = 65 mm): 44·(1 − 10/65)·14·9.6·10 = 50 035 N and
    /// C_u = C_0r/8.2 = 6 102 N (D_pw below 100 mm); a pitch diameter of 200 mm lowers C_u by
    /// (100/200)^0.3 beside its larger C_0r.
    #[test]
    fn static_rating_and_fatigue_limit() {
        let mut b = bearing_209(30);
        let c0 = static_load_rating(&b).unwrap();
        assert!((c0 - 44.0 * (55.0 / 65.0) * 14.0 * 9.6 * 10.0).abs() < 1e-9 * c0);
        assert!((fatigue_load_limit(&b).unwrap() - c0 / 8.2).abs() < 1e-9 * c0);
        b.pitch_diameter = 200.0;
        let c0 = static_load_rating(&b).unwrap();
        let cu = fatigue_load_limit(&b).unwrap();
        assert!((cu - c0 / 8.2 * 0.5f64.powf(0.3)).abs() < 1e-9 * c0);
    }
}
