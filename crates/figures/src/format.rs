//! Numbers as figures print them: significant digits, fixed decimals with a true minus
//! sign, counts as powers of ten (`5·10⁶`).

/// `x` with `digits` significant digits in fixed notation (scientific beyond 1e15 or
/// below 1e-6), for aligned text columns and legends that show no digits beyond f64
/// precision.
pub fn significant(x: f64, digits: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x:.prec$}", prec = digits.saturating_sub(1));
    }
    let mag = x.abs().log10().floor() as i64;
    if mag >= digits as i64 || mag < -6 {
        return format!("{x:.prec$e}", prec = digits.saturating_sub(1));
    }
    let decimals = (digits as i64 - 1 - mag).max(0) as usize;
    format!("{x:.decimals$}")
}

/// A number with `digits` decimals, with a true minus sign.
pub fn fmt_fixed(v: f64, digits: usize) -> String {
    let s = format!("{v:.digits$}");
    let zero = s
        .trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.');
    if zero {
        s.trim_start_matches('-').to_string()
    } else {
        s.replace('-', "\u{2212}")
    }
}

/// A count such as 5000000 as `5·10⁶` (plain Unicode, no markup), or as it is when
/// short.
pub fn fmt_count(n: u64) -> String {
    if n < 10_000 {
        return n.to_string();
    }
    let exp = (n as f64).log10().floor() as u32;
    let mant = n as f64 / 10f64.powi(exp as i32);
    let sup: String = exp
        .to_string()
        .chars()
        .map(|c| "⁰¹²³⁴⁵⁶⁷⁸⁹".chars().nth(c as usize - '0' as usize).unwrap())
        .collect();
    if (mant - 1.0).abs() < 1e-9 {
        format!("10{sup}")
    } else if (mant - mant.round()).abs() < 1e-9 {
        format!("{}·10{sup}", mant.round())
    } else {
        format!("{}·10{sup}", (mant * 100.0).round() / 100.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_read_as_the_paper_writes_them() {
        assert_eq!(fmt_count(5_000_000), "5·10⁶");
        assert_eq!(fmt_count(20_000), "2·10⁴");
        assert_eq!(fmt_count(100_000), "10⁵");
        assert_eq!(fmt_count(2000), "2000");
        assert_eq!(fmt_count(25_000), "2.5·10⁴");
    }

    #[test]
    fn fixed_numbers_use_a_true_minus_and_no_negative_zero() {
        assert_eq!(fmt_fixed(-0.5, 1), "\u{2212}0.5");
        assert_eq!(fmt_fixed(-0.0001, 2), "0.00");
        assert_eq!(fmt_fixed(2.5, 0), "2");
    }
}
