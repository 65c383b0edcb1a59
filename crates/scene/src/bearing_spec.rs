//! A cylindrical roller bearing as a scene writes it (`[bearing]`): its geometry, crowns, load
//! cases and what its crown's design minimises. The bearing's part of a case's run (composing
//! the contact, the plan, the ring equilibrium and the lives) is [`crate::bearing`]'s.

use contopt_core::{check, Error, Material, Result};
use contopt_roller::{
    viscosity_at_temperature, BearingLoad, Crown, CrownSettings, CrownTolerances,
    CylindricalRollerBearing, Raceway, Roller, Tilt, ISO_VG_GRADES, MAX_GRID, MIN_GRID,
};
use serde::{Deserialize, Serialize};

/// The image pressure's weight at the roller's free ends unless the scene sets one: the
/// weight with which the image alone matches Hetényi's free end face for pressures that reach
/// the end (1.357 under Lundberg's crown, 1.389 under a straight roller's edge, on a roller's
/// grid of 100 × 41 cells; 1.29 where the pressure stops short of the end, and there the
/// weight hardly matters: `examples/free_ends.rs`, the book's chapter "From the bearing to the
/// crown").
pub const FREE_END_WEIGHT: f64 = 1.37;

/// Time fractions of a duty cycle must sum to 1 within this.
pub(crate) const FRACTIONS: f64 = 1e-9;

/// The largest misalignment a load case may hold \[arc-minutes\]: ten degrees, far past any
/// bearing's, and within the slice model's small angles.
pub(crate) const MAX_MISALIGNMENT_ARCMIN: f64 = 600.0;

/// The largest tolerance band \[µm\]: a millimetre.
pub(crate) const MAX_TOLERANCE_UM: f64 = 1000.0;

/// The largest diametral clearance or preload, as a fraction of the roller's diameter: a
/// tenth of it, far past a bearing's internal clearances (micrometres to tenths of a
/// millimetre) and short of the thousandfold slip of typing micrometres as millimetres.
pub(crate) const MAX_CLEARANCE: f64 = 0.1;

/// Stribeck's factor of the design load: Q₀ = 5·F_r/Z for the heaviest load case.
pub(crate) const STRIBECK: f64 = 5.0;

/// The eighth root of a time fraction's ratio in [`duty_cycle_levels`]: ISO/TS 16281's slice
/// life goes as q^(−4) (its exponents 9/2 and 8/9 of [`contopt_roller::reference_rating_life`]
/// on one slice), and a slice's Hertzian load as p₀² (Johnson eq. 4.45), so a case's damage
/// t·L⁻¹ goes as t·p₀⁸.
pub(crate) const DAMAGE_EXPONENT: f64 = 8.0;

/// The robust crown's pressure level s_i of each load case for the duty-cycle life, relative
/// to the reference case r, the one of the largest time fraction (the first of those):
///
/// s_i = max(1, (Q_i/Q_r)^(1/2) · (t_r/t_i)^(1/8)),
///
/// `heaviest` = Q_i the load case's heaviest roller load on the solved raceway, `fractions` =
/// t_i. (Q_i/Q_r)^(1/2) is the ratio of the cases' Hertzian line-contact pressures
/// (p₀ ∝ √Q, Johnson eq. 4.45): each case is held to its own load's pressure, not to the
/// heaviest's. (t_r/t_i)^(1/8) lets a case the duty cycle spends less time in carry more by
/// the same damage t·p₀⁸ ([`DAMAGE_EXPONENT`]). No case is held below the reference level: a
/// lighter case held to its own small p₀ would shape the crown for damage it hardly does.
/// With one load case every level is 1 and the crown is the p_max one.
pub fn duty_cycle_levels(heaviest: &[f64], fractions: &[f64]) -> Result<Vec<f64>> {
    check::all_positive("heaviest", heaviest)?;
    check::all_positive("fractions", fractions)?;
    if heaviest.len() != fractions.len() {
        return Err(Error::invalid(
            "heaviest",
            format!("{} loads", heaviest.len()),
            format!("one per load case ({})", fractions.len()),
        ));
    }
    let r = (0..fractions.len())
        .reduce(|a, b| if fractions[b] > fractions[a] { b } else { a })
        .ok_or_else(|| Error::invalid("fractions", "none", "at least one load case"))?;
    Ok(heaviest
        .iter()
        .zip(fractions)
        .map(|(q, t)| {
            let level = (q / heaviest[r]).sqrt() * (fractions[r] / t).powf(1.0 / DAMAGE_EXPONENT);
            level.max(1.0)
        })
        .collect())
}

/// A raceway, as a scene names it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RacewaySpec {
    /// The inner ring's raceway (convex; the default).
    #[default]
    Inner,
    /// The outer ring's raceway (concave).
    Outer,
}

impl RacewaySpec {
    pub(crate) fn raceway(self) -> Raceway {
        match self {
            RacewaySpec::Inner => Raceway::Inner,
            RacewaySpec::Outer => Raceway::Outer,
        }
    }

    pub(crate) fn name(self) -> &'static str {
        match self {
            RacewaySpec::Inner => "inner",
            RacewaySpec::Outer => "outer",
        }
    }
}

/// What a design of a bearing's crown minimises.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BearingObjective {
    /// The worst contact's p_max over every loaded roller, load case and the tolerance band
    /// (the default).
    #[default]
    PMax,
    /// The duty cycle's life: ISO/TS 16281's L10r from the half-space contacts' slice loads,
    /// by Palmgren–Miner over the load cases, the band's worst. A profile search maximises it
    /// over its family; the robust crown (`envelope_split`) is designed for it without a
    /// search, by holding each load case i to its duty-cycle pressure level
    /// s_i = max(1, (Q_i/Q_r)^(1/2)·(t_r/t_i)^(1/8)) times p̂ instead of one level for all
    /// (Q_i its heaviest roller load, t_i its time fraction, r the case of the largest).
    Life,
}

/// A cylindrical roller bearing (`[bearing]`): one row, contact angle 0, rings and rollers of
/// one material.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BearingSpec {
    /// Number of rollers Z.
    pub rollers: usize,
    /// Roller diameter D_we \[mm\].
    pub roller_diameter_mm: f64,
    /// Roller length between its sharp corners \[mm\].
    pub roller_length_mm: f64,
    /// Axial width of each end's chamfer \[mm\] (default 0): the effective length L_we is the
    /// length less two chamfers, and the roller's free end faces lie a chamfer beyond it.
    #[serde(default)]
    pub chamfer_mm: f64,
    /// Pitch diameter D_pw \[mm\].
    pub pitch_diameter_mm: f64,
    /// Diametral operating clearance \[mm\] (default 0; negative: a preload).
    #[serde(default)]
    pub clearance_mm: f64,
    /// Slices per roller of ISO/TS 16281's model (default 30, the standard's least).
    #[serde(default = "BearingSpec::default_slices")]
    pub slices: usize,
    /// The roller's crown (default straight; a design of the crown starts straight).
    #[serde(default)]
    pub roller_profile: CrownSettings,
    /// The inner raceway's crown (default straight).
    #[serde(default)]
    pub inner_profile: CrownSettings,
    /// The outer raceway's crown (default straight).
    #[serde(default)]
    pub outer_profile: CrownSettings,
    /// The rings' and rollers' material (ISO/TS 16281's load–deflection constant is steel's).
    pub material: Material,
    /// The raceway whose contacts are solved on the half-space grid (default inner, the
    /// convex one, where the pressure is highest).
    #[serde(default)]
    pub raceway: RacewaySpec,
    /// The ring that rotates against the load (default inner), for the lives.
    #[serde(default)]
    pub rotating: RacewaySpec,
    /// The roller–raceway grid: cells along the effective length, and across (odd, at
    /// least 3).
    pub cells: [usize; 2],
    /// How far the grid's outer cell centres reach across, in Hertz half-widths of the design
    /// load (default 3).
    #[serde(default = "BearingSpec::default_reach")]
    pub reach_b: f64,
    /// The roller load the grid and the load-dependent profiles are built for \[N\]; default
    /// Stribeck's 5·F_r/Z of the heaviest load case.
    #[serde(default)]
    pub design_load_n: Option<f64>,
    /// The roller's end faces as free faces, by the image pressure of weight
    /// `free_end_weight` (default on); off: a half-space roller.
    #[serde(default = "BearingSpec::default_free_ends")]
    pub free_ends: bool,
    /// The image pressure's weight at the free ends (default [`FREE_END_WEIGHT`]).
    #[serde(default = "BearingSpec::default_free_end_weight")]
    pub free_end_weight: f64,
    /// The crown's tolerance band: its end drop may be off by ±t \[µm\] (default 0); every
    /// contact is solved at both ends of the band too, and the worst is taken.
    #[serde(default)]
    pub tolerance_um: f64,
    /// The roller crown's manufacturing tolerances as a box of its parameters
    /// (`crown_tolerance = { drop_um, crowned_length_mm, log_constant, grid }`, default none):
    /// the worst crown in the box is searched and reported.
    #[serde(default)]
    pub crown_tolerance: Option<CrownToleranceSpec>,
    /// What a design of the crown minimises (default the worst p_max).
    #[serde(default)]
    pub objective: BearingObjective,
    /// The angle of roller 0 from the load's direction \[°\] (default 0: a roller on the load
    /// line).
    #[serde(default)]
    pub first_roller_deg: f64,
    /// The rotating ring's speed against the other \[min⁻¹\] (default none: lives in
    /// revolutions only); with it, every life in hours too.
    #[serde(default)]
    pub speed_rpm: Option<f64>,
    /// The lubricant and the contamination, for ISO 281's modified lives
    /// (`[bearing.lubrication]`; needs `speed_rpm`).
    #[serde(default)]
    pub lubrication: Option<LubricationSpec>,
    /// The load cases of the duty cycle (`[[bearing.load]]`).
    pub load: Vec<BearingLoadSpec>,
}

/// A bearing's lubrication for ISO 281's life modification factor a_ISO
/// (`[bearing.lubrication]`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LubricationSpec {
    /// The lubricant's kinematic viscosity at the operating temperature ν \[mm²/s\]; or,
    /// instead, the oil (`iso_vg` or `viscosity_40_mm2_s`, with `viscosity_100_mm2_s`) and
    /// `temperature_c`.
    #[serde(default)]
    pub viscosity_mm2_s: Option<f64>,
    /// The oil's ISO VG grade (ISO 3448: its viscosity at 40 °C, VG 68 is 68 mm²/s).
    #[serde(default)]
    pub iso_vg: Option<f64>,
    /// The oil's viscosity at 40 °C \[mm²/s\] (instead of `iso_vg`, from its data sheet).
    #[serde(default)]
    pub viscosity_40_mm2_s: Option<f64>,
    /// The oil's viscosity at 100 °C \[mm²/s\] (its data sheet; a mineral VG 68 of viscosity
    /// index about 95 has about 8.7).
    #[serde(default)]
    pub viscosity_100_mm2_s: Option<f64>,
    /// The operating temperature \[°C\], −20 to 150: ν there by ASTM D341's
    /// Ubbelohde–Walther relation through the oil's two viscosities.
    #[serde(default)]
    pub temperature_c: Option<f64>,
    /// ISO 281's contamination factor e_C, 0 to 1 (1: extremely clean; about 0.5 to 0.3 for
    /// normal cleanliness; ISO 281 Table 13).
    pub contamination: f64,
    /// The fatigue load limit C_u \[N\] (default ISO 281's from ISO 76's C_0r: C_0r/8.2,
    /// smaller past D_pw = 100 mm); a catalogue's P_u where it gives one.
    #[serde(default)]
    pub fatigue_load_limit_n: Option<f64>,
}

impl LubricationSpec {
    /// Checks its numbers; fields are named from the bearing.
    pub(crate) fn check(&self) -> Result<()> {
        self.viscosity()?;
        check::between(
            "lubrication.contamination",
            self.contamination,
            -f64::EPSILON,
            1.0 + f64::EPSILON,
        )?;
        if let Some(c) = self.fatigue_load_limit_n {
            check::positive("lubrication.fatigue_load_limit_n", c)?;
        }
        Ok(())
    }

    /// The viscosity at the operating temperature \[mm²/s\]: the one given, or the oil's at
    /// its temperature ([`viscosity_at_temperature`]).
    pub(crate) fn viscosity(&self) -> Result<f64> {
        let oil = (self.iso_vg.is_some() || self.viscosity_40_mm2_s.is_some())
            || self.viscosity_100_mm2_s.is_some()
            || self.temperature_c.is_some();
        match (self.viscosity_mm2_s, oil) {
            (Some(nu), false) => check::positive("lubrication.viscosity_mm2_s", nu),
            (Some(nu), true) => Err(Error::invalid(
                "lubrication.viscosity_mm2_s",
                nu,
                "give either the viscosity at the operating temperature or the oil \
                 (iso_vg or viscosity_40_mm2_s, viscosity_100_mm2_s) and temperature_c, not both",
            )),
            (None, _) => self.oil_viscosity(),
        }
    }

    /// ν at `temperature_c` of the oil given by its grade or ν₄₀, and ν₁₀₀.
    fn oil_viscosity(&self) -> Result<f64> {
        let nu_40 = match (self.iso_vg, self.viscosity_40_mm2_s) {
            (Some(vg), None) => iso_vg(vg)?,
            (None, Some(nu)) => nu,
            (Some(vg), Some(_)) => {
                return Err(Error::invalid(
                    "lubrication.iso_vg",
                    vg,
                    "give iso_vg or viscosity_40_mm2_s, not both",
                ))
            }
            (None, None) => {
                return Err(Error::invalid(
                    "lubrication.viscosity_mm2_s",
                    "missing",
                    "give the viscosity at the operating temperature, or the oil (iso_vg or \
                     viscosity_40_mm2_s, with viscosity_100_mm2_s) and temperature_c",
                ))
            }
        };
        let needed = |field: &str, value: Option<f64>, why: &str| {
            value.ok_or_else(|| Error::invalid(format!("lubrication.{field}"), "missing", why))
        };
        let nu_100 = needed(
            "viscosity_100_mm2_s",
            self.viscosity_100_mm2_s,
            "the oil's viscosity at 100 °C (its data sheet) sets how it thins with temperature",
        )?;
        let t = needed(
            "temperature_c",
            self.temperature_c,
            "the operating temperature the oil's viscosity is taken at",
        )?;
        viscosity_at_temperature(nu_40, nu_100, t).map_err(|e| match e {
            Error::InvalidInput {
                field,
                value,
                reason,
            } => Error::InvalidInput {
                field: format!("lubrication.{field}"),
                value,
                reason,
            },
            other => other,
        })
    }
}

/// ISO 3448's grade `vg` as its viscosity at 40 °C \[mm²/s\]; an error for a number that is
/// not a grade.
fn iso_vg(vg: f64) -> Result<f64> {
    match ISO_VG_GRADES.contains(&vg) {
        true => Ok(vg),
        false => Err(Error::invalid(
            "lubrication.iso_vg",
            vg,
            format!("is not an ISO 3448 grade: one of {ISO_VG_GRADES:?}"),
        )),
    }
}

/// The roller crown's manufacturing tolerances (`[bearing] crown_tolerance`), each ±: the
/// scene's parametric `roller_profile` as made anywhere in their box
/// ([`contopt_roller::worst_in_box`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CrownToleranceSpec {
    /// The end drop's \[µm\] (default 0), 0 to 1000.
    #[serde(default)]
    pub drop_um: f64,
    /// The crowned length's at each end \[mm\] (default 0), below the half-length.
    #[serde(default)]
    pub crowned_length_mm: f64,
    /// The logarithm's constant's, relative (default 0), 0 to below 1.
    #[serde(default)]
    pub log_constant: f64,
    /// Points along each axis of the first grid over the box, its corners among them
    /// (default 3), 2 to 9.
    #[serde(default = "CrownToleranceSpec::default_grid")]
    pub grid: usize,
}

impl CrownToleranceSpec {
    fn default_grid() -> usize {
        3
    }

    /// The library's tolerances, checked; fields named from the bearing.
    pub(crate) fn tolerances(&self, half_length: f64) -> Result<CrownTolerances> {
        let named = "crown_tolerance.";
        check::between(
            &format!("{named}drop_um"),
            self.drop_um,
            -f64::EPSILON,
            MAX_TOLERANCE_UM,
        )?;
        check::between(
            &format!("{named}crowned_length_mm"),
            self.crowned_length_mm,
            -f64::EPSILON,
            half_length,
        )?;
        check::count(&format!("{named}grid"), self.grid, MIN_GRID, MAX_GRID)?;
        let t = CrownTolerances {
            drop: 1e-3 * self.drop_um,
            crowned_length: self.crowned_length_mm,
            log_constant: self.log_constant,
        };
        t.check().map_err(|e| match e {
            Error::InvalidInput {
                field,
                value,
                reason,
            } => Error::InvalidInput {
                field: field.replace("tolerance.", named),
                value,
                reason,
            },
            other => other,
        })?;
        Ok(t)
    }
}

/// One load case of a bearing's duty cycle (`[[bearing.load]]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BearingLoadSpec {
    /// Its name in tables (default `F_r = … N`).
    #[serde(default)]
    pub label: Option<String>,
    /// The radial load F_r \[N\].
    pub radial_n: f64,
    /// The inner ring held misaligned against the outer, in the load's plane
    /// \[arc-minutes\] (default 0).
    #[serde(default)]
    pub misalignment_arcmin: f64,
    /// A moment on the inner ring in the load's plane \[N·mm\]: the ring is then free to tilt
    /// under it (instead of a held misalignment).
    #[serde(default)]
    pub moment_nmm: Option<f64>,
    /// Its time fraction of the duty cycle (default 1; the fractions sum to 1).
    #[serde(default = "BearingLoadSpec::default_fraction")]
    pub fraction: f64,
}

impl BearingSpec {
    pub(crate) fn default_slices() -> usize {
        30
    }

    pub(crate) fn default_reach() -> f64 {
        3.0
    }

    pub(crate) fn default_free_ends() -> bool {
        true
    }

    pub(crate) fn default_free_end_weight() -> f64 {
        FREE_END_WEIGHT
    }

    /// The effective length L_we \[mm\].
    pub(crate) fn effective_length(&self) -> f64 {
        self.roller_length_mm - 2.0 * self.chamfer_mm
    }

    /// The roller load the grid and profiles are built for \[N\].
    pub(crate) fn design_load(&self) -> f64 {
        self.design_load_n.unwrap_or_else(|| {
            let heaviest = self.load.iter().map(|l| l.radial_n).fold(0.0, f64::max);
            STRIBECK * heaviest / self.rollers.max(1) as f64
        })
    }

    /// The solved raceway's diameter, positive for the inner ring, negative for the outer.
    pub(crate) fn raceway_diameter(&self) -> f64 {
        match self.raceway {
            RacewaySpec::Inner => self.pitch_diameter_mm - self.roller_diameter_mm,
            RacewaySpec::Outer => -(self.pitch_diameter_mm + self.roller_diameter_mm),
        }
    }

    /// The bearing without crowns, checked (its dimensions).
    pub(crate) fn bearing(&self) -> Result<CylindricalRollerBearing> {
        check::finite("bearing.first_roller_deg", self.first_roller_deg)?;
        self.check_clearance()?;
        let b = CylindricalRollerBearing {
            rollers: self.rollers,
            roller_diameter: self.roller_diameter_mm,
            roller_length: self.roller_length_mm,
            chamfer: self.chamfer_mm,
            pitch_diameter: self.pitch_diameter_mm,
            clearance: self.clearance_mm,
            roller_crown: Crown::Straight,
            inner_crown: Crown::Straight,
            outer_crown: Crown::Straight,
            slices: self.slices,
            first_roller: self.first_roller_deg.to_radians(),
        };
        b.check()?;
        Ok(b)
    }

    /// A clearance (or preload) of the bearing's size: at most [`MAX_CLEARANCE`] of the
    /// roller's diameter either way; one far past it is a slip of units, named with them.
    fn check_clearance(&self) -> Result<()> {
        let (c, d) = (self.clearance_mm, self.roller_diameter_mm);
        check::finite("bearing.clearance_mm", c)?;
        if d > 0.0 && c.abs() > MAX_CLEARANCE * d {
            return Err(Error::invalid(
                "bearing.clearance_mm",
                format!("{c} mm ({:.0} µm)", 1e3 * c),
                format!(
                    "is {:.0} % of the roller's diameter ({d} mm): a diametral clearance (or, \
                     negative, a preload) is some micrometres to tenths of a millimetre, and \
                     the key is in millimetres (20 µm is 0.02); at most {} mm is taken",
                    100.0 * c.abs() / d,
                    MAX_CLEARANCE * d
                ),
            ));
        }
        Ok(())
    }

    /// The roller on the solved raceway under the design load, its crown straight.
    pub(crate) fn roller(&self) -> Roller {
        Roller {
            diameter: self.roller_diameter_mm,
            length: self.effective_length(),
            raceway_diameter: Some(self.raceway_diameter()),
            roller: self.material,
            raceway: self.material,
            load: self.design_load(),
            tilt: 0.0,
            crown: Crown::Straight,
        }
    }
}

impl BearingLoadSpec {
    pub(crate) fn default_fraction() -> f64 {
        1.0
    }

    /// Its label: the scene's, or `F_r = … N`.
    pub(crate) fn label(&self) -> String {
        self.label
            .clone()
            .unwrap_or_else(|| format!("F_r = {} N", self.radial_n))
    }

    /// The library's load: a held misalignment, or a moment the ring tilts under.
    pub(crate) fn load(&self) -> BearingLoad {
        let tilt = match self.moment_nmm {
            Some(m) => Tilt::Moment(m),
            None => Tilt::Held((self.misalignment_arcmin / 60.0).to_radians()),
        };
        BearingLoad {
            radial_n: self.radial_n,
            tilt,
        }
    }

    /// Checks the case's numbers; fields are named from the case.
    pub(crate) fn check(&self) -> Result<()> {
        check::positive("radial_n", self.radial_n)?;
        check::between(
            "misalignment_arcmin",
            self.misalignment_arcmin,
            -MAX_MISALIGNMENT_ARCMIN,
            MAX_MISALIGNMENT_ARCMIN,
        )?;
        if let Some(m) = self.moment_nmm {
            check::finite("moment_nmm", m)?;
            if self.misalignment_arcmin != 0.0 {
                return Err(Error::invalid(
                    "moment_nmm",
                    m,
                    "a load case holds the ring misaligned or lets it tilt under a moment, \
                     not both: leave misalignment_arcmin out",
                ));
            }
        }
        check::positive("fraction", self.fraction).map(|_| ())
    }
}
