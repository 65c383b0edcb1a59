//! The paper's words for a scene's keys, which a case's label is made of:
//! `optimisation.controller.l1_mm = 20` reads `L1 = 20 mm`, `body.0.material.nu = 0.3` reads
//! `ν = 0.3`, `e_mpa = 200000` reads `E = 2·10⁵ MPa`.

/// A scene key (its last dotted part), its symbol and its unit.
const QUANTITIES: &[(&str, &str, &str)] = &[
    ("l1_mm", "L1", "mm"),
    ("l2_mm", "L2", "mm"),
    ("nu", "ν", ""),
    ("e_mpa", "E", "MPa"),
    ("force_n", "F", "N"),
    ("load_n", "Q", "N"),
    ("pressure_mpa", "p", "MPa"),
    ("displacement_mm", "u", "mm"),
    ("approach_mm", "δ", "mm"),
    ("radius_mm", "R", "mm"),
    ("punch_radius_mm", "R", "mm"),
    ("base_radius_mm", "R_base", "mm"),
    ("height_mm", "H", "mm"),
    ("thickness_mm", "b", "mm"),
    ("diameter_mm", "D", "mm"),
    ("length_mm", "l", "mm"),
    ("tilt_arcmin", "γ", "′"),
    ("c_mpa_per_mm", "c", "MPa/mm"),
    ("tolh_mm2", "TOLH", "mm²"),
    ("k1", "K1", ""),
    ("k2", "K2", ""),
    ("z_m_mm", "z_m", "mm"),
    ("level", "v", ""),
];

/// Unit suffixes of keys without an entry above, longest first.
const SUFFIXES: &[(&str, &str)] = &[
    ("_mpa_per_mm", "MPa/mm"),
    ("_arcmin", "′"),
    ("_mm2", "mm²"),
    ("_mpa", "MPa"),
    ("_mm", "mm"),
    ("_um", "µm"),
    ("_mb", "MB"),
    ("_n", "N"),
];

/// `key = value` in the paper's words: the key's symbol, the value (m·10ⁿ when large or
/// small) and its unit. A key may be dotted (`optimisation.controller.l1_mm`); one without
/// a symbol keeps its name, its unit suffix turned into the unit.
pub fn quantity(key: &str, value: f64) -> String {
    let name = key.rsplit('.').next().unwrap_or(key);
    let (symbol, unit) = QUANTITIES
        .iter()
        .find(|(k, _, _)| *k == name)
        .map(|&(_, s, u)| (s, u))
        .or_else(|| {
            SUFFIXES.iter().find_map(|&(suffix, unit)| {
                name.strip_suffix(suffix)
                    .filter(|s| !s.is_empty())
                    .map(|s| (s, unit))
            })
        })
        .unwrap_or((name, ""));
    let value = number(value);
    match unit {
        "" => format!("{symbol} = {value}"),
        "′" => format!("{symbol} = {value}′"),
        unit => format!("{symbol} = {value} {unit}"),
    }
}

/// Significant digits of a value in a legend.
const DIGITS: usize = 6;

/// A number as a reader writes it: `20`, `0.3`, `2·10⁵`, `1.5·10⁻⁴`, `−3`; at most six
/// significant digits, no trailing zeros.
pub fn number(v: f64) -> String {
    significant(v, DIGITS)
}

/// [`number`] to at most `digits` significant digits (at least one).
pub fn significant(v: f64, digits: usize) -> String {
    let digits = digits.max(1);
    if v == 0.0 {
        return "0".into();
    }
    if !v.is_finite() {
        return "not finite".into();
    }
    let n = v.abs().log10().floor() as i32;
    let text = if (-3..4).contains(&n) {
        let decimals = (digits as i32 - 1 - n).max(0) as usize;
        trim(format!("{v:.decimals$}"))
    } else {
        let mantissa = trim(format!("{:.*}", digits - 1, v / 10f64.powi(n)));
        match mantissa.as_str() {
            "1" => power_of_ten(n),
            "-1" => format!("-{}", power_of_ten(n)),
            m => format!("{m}·{}", power_of_ten(n)),
        }
    };
    text.replace('-', "−")
}

/// 10 to the power `n`, written `10ⁿ`.
pub fn power_of_ten(n: i32) -> String {
    format!("10{}", superscript(n))
}

/// An integer in superscript digits (`⁻³`).
pub fn superscript(n: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    n.to_string()
        .chars()
        .map(|c| c.to_digit(10).map_or('⁻', |d| DIGITS[d as usize]))
        .collect()
}

/// A decimal without trailing zeros (and without a trailing point).
fn trim(text: String) -> String {
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweep_keys_read_as_the_paper_writes_them() {
        assert_eq!(
            quantity("optimisation.controller.l1_mm", 20.0),
            "L1 = 20 mm"
        );
        assert_eq!(quantity("body.0.material.nu", 0.3), "ν = 0.3");
        assert_eq!(quantity("e_mpa", 2e5), "E = 2·10⁵ MPa");
        assert_eq!(quantity("e_mpa", 2.1e5), "E = 2.1·10⁵ MPa");
        assert_eq!(quantity("tilt_arcmin", -2.0), "γ = −2′");
        assert_eq!(quantity("solver.c_mpa_per_mm", 2e9), "c = 2·10⁹ MPa/mm");
        assert_eq!(quantity("body.0.datum_mm", 100.0), "datum = 100 mm");
        assert_eq!(quantity("reach_b", 2.6), "reach_b = 2.6");
        assert_eq!(quantity("tolh_mm2", 5e-7), "TOLH = 5·10⁻⁷ mm²");
    }

    #[test]
    fn numbers_are_short() {
        assert_eq!(number(0.0), "0");
        assert_eq!(number(31415.93), "3.14159·10⁴");
        assert_eq!(number(1000.0), "1000");
        assert_eq!(number(0.001), "0.001");
        assert_eq!(number(0.1 + 0.2), "0.3");
        assert_eq!(number(1e-4), "10⁻⁴");
        assert_eq!(number(-1.5e-4), "−1.5·10⁻⁴");
        assert_eq!(significant(2960.67, 4), "2961");
        assert_eq!(significant(0.123456, 2), "0.12");
    }
}
