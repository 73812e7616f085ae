//! Conversions between the solver's SI units and the units on screen
//! (mm, MPa, MPa·√m, GPa, degrees), and number formatting with units.

/// Millimetres per metre.
pub const MM_PER_M: f64 = 1e3;
/// Pascals per megapascal.
pub const PA_PER_MPA: f64 = 1e6;
/// Pascals per gigapascal.
pub const PA_PER_GPA: f64 = 1e9;

/// `value_pa` in MPa with a unit, e.g. `-10.00 MPa`.
pub fn mpa(value_pa: f64) -> String {
    format!("{} MPa", significant(value_pa / PA_PER_MPA))
}

/// A stress intensity factor in MPa·√m.
pub fn mpa_sqrt_m(value: f64) -> String {
    format!("{} MPa·√m", significant(value / PA_PER_MPA))
}

/// A length in mm.
pub fn mm(value_m: f64) -> String {
    format!("{} mm", significant(value_m * MM_PER_M))
}

/// An angle in degrees.
pub fn deg(value_deg: f64) -> String {
    format!("{value_deg:.1}°")
}

/// A duration: µs, ms or s.
pub fn seconds(value_s: f64) -> String {
    if value_s < 1e-3 {
        format!("{:.0} µs", value_s * 1e6)
    } else if value_s < 1.0 {
        format!("{:.1} ms", value_s * 1e3)
    } else {
        format!("{value_s:.2} s")
    }
}

/// Four significant digits without an exponent for everyday magnitudes,
/// scientific notation for very small or very large ones.
pub fn significant(v: f64) -> String {
    let a = v.abs();
    if !v.is_finite() {
        format!("{v}")
    } else if a == 0.0 {
        "0".to_owned()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.3e}")
    } else {
        let decimals = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        format!("{v:.decimals$}")
    }
}

/// [`significant`] without trailing zeros (`0.2`, not `0.2000`): values a
/// user typed, in tables.
pub fn compact(v: f64) -> String {
    let s = significant(v);
    if s.contains('.') && !s.contains('e') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    }
}

/// Growth steps in increasing order, consecutive ones as a range: `2, 5–9`.
pub fn step_list(steps: &[usize]) -> String {
    steps
        .chunk_by(|a, b| b == &(a + 1))
        .map(|run| match run {
            [one] => one.to_string(),
            [first, .., last] => format!("{first}–{last}"),
            [] => String::new(),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn consecutive_steps_read_as_a_range() {
        assert_eq!(step_list(&[2, 5, 6, 7, 8, 9]), "2, 5–9");
        assert_eq!(step_list(&[3]), "3");
        assert_eq!(step_list(&[3, 4]), "3–4");
    }

    #[test]
    fn compact_drops_trailing_zeros_only() {
        assert_eq!(compact(0.2), "0.2");
        assert_eq!(compact(0.0), "0");
        assert_eq!(compact(120.0), "120");
        assert_eq!(compact(1.25e-4), "1.250e-4");
        assert_eq!(compact(-3.5), "-3.5");
    }

    #[test]
    fn stresses_show_in_megapascal() {
        assert_eq!(mpa(-10e6), "-10.00 MPa");
        assert_eq!(mpa(2.5e5), "0.2500 MPa");
    }

    #[test]
    fn lengths_show_in_millimetres() {
        assert_eq!(mm(0.3), "300.0 mm");
        assert_eq!(mm(0.0), "0 mm");
    }

    #[test]
    fn tiny_and_huge_use_exponents() {
        assert_eq!(significant(1.5e-6), "1.500e-6");
        assert_eq!(significant(2.0e7), "2.000e7");
    }
}
