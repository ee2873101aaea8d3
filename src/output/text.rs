//! Numbers in aligned text columns: fixed digits for people, never more digits than an
//! f64 holds.

/// `x` with `digits` significant digits in fixed notation (the figures' legends use it
/// too, so it lives in their crate).
pub use bouncemap_figures::significant;

/// A complex number with 12 decimals: `re` or `re±imi`.
pub fn complex(z: bouncemap_engine::Complex) -> String {
    if z.im == 0.0 {
        format!("{:.12}", z.re)
    } else {
        format!("{:.12}{:+.12}i", z.re, z.im)
    }
}

/// The shortest decimal that reads back to the same f64, in exponent form where that is
/// shorter (for messages, labels and captions).
pub fn shortest(x: f64) -> String {
    bouncemap_engine::fmt_value(x)
}

/// `x` to `decimals` decimals, trailing zeros (and a bare point) trimmed.
pub fn decimals(x: f64, decimals: usize) -> String {
    let s = format!("{x:.decimals$}");
    if decimals == 0 {
        return s;
    }
    let s = s.trim_end_matches('0');
    s.strip_suffix('.').unwrap_or(s).to_string()
}

/// An enclosure as `mid ± radius` (the interval [mid − radius, mid + radius] contains
/// it): the middle to the digits its width leaves, the radius rounded up to two digits;
/// a thin interval as its one value.
pub fn interval(i: bouncemap_engine::Interval) -> String {
    let (lo, hi) = (i.lo(), i.hi());
    if lo == hi {
        return shortest(lo);
    }
    if !lo.is_finite() || !hi.is_finite() {
        return format!("[{}, {}]", shortest(lo), shortest(hi));
    }
    let mid = 0.5 * lo + 0.5 * hi;
    let size = lo.abs().max(hi.abs());
    let width = hi - lo;
    // Significant digits down to the width's order.
    let digits = ((size / width).log10().ceil() as i64 + 1).clamp(1, 17) as usize;
    let m = if mid != 0.0 && !(1e-4..1e6).contains(&mid.abs()) {
        format!("{:.*e}", digits - 1, mid)
    } else {
        let whole = if mid == 0.0 {
            0
        } else {
            mid.abs().log10().floor() as i64
        };
        format!(
            "{:.*}",
            (digits as i64 - 1 - whole).clamp(0, 20) as usize,
            mid
        )
    };
    let mv: f64 = m.parse().unwrap_or(mid);
    let rad = (hi - mv).max(mv - lo).max(f64::MIN_POSITIVE);
    let e = rad.log10().floor() as i32;
    let q = (rad / 10f64.powi(e - 1) * (1.0 + 1e-12)).ceil() as i64;
    let (q, e) = if q >= 100 {
        (10, e + 1)
    } else {
        (q.max(10), e)
    };
    format!("{m} ± {}.{}e{e}", q / 10, q % 10)
}

/// `text` with control characters (escape codes, newlines) written as escapes, so a
/// name from a file can never disturb a terminal or break a line of output.
pub fn escape(text: &str) -> String {
    text.chars()
        .flat_map(|c| {
            let esc: Vec<char> = if c.is_control() {
                c.escape_default().collect()
            } else {
                vec![c]
            };
            esc
        })
        .collect()
}

/// What the user typed, for a refusal: quoted, control characters escaped, and cut to
/// at most [`QUOTED_MAX`] characters (an ellipsis marks the cut), so a refusal stays one
/// short line whatever was typed.
pub fn quoted(text: &str) -> String {
    let esc = escape(text);
    if esc.chars().count() > QUOTED_MAX {
        let head: String = esc.chars().take(QUOTED_MAX - 1).collect();
        format!("'{head}…' ({} characters)", text.chars().count())
    } else {
        format!("'{esc}'")
    }
}

/// A path for a message: control characters escaped, cut to 200 characters (an
/// ellipsis marks the cut).
pub fn shown_path(path: &std::path::Path) -> String {
    let text = escape(&path.display().to_string());
    if text.chars().count() > 200 {
        let head: String = text.chars().take(199).collect();
        format!("{head}…")
    } else {
        text
    }
}

/// The table as every output names it when `free` (an axis, the swept parameter) may
/// be a parameter of its family: F_D as `fd` (its D is the axis), a file's family with
/// that parameter left free as figures name it (`asym (w, h = 0.3)`), else the table's
/// own name.
pub fn table_with_free(
    table: &bouncemap_engine::Table,
    free: &[bouncemap_engine::jobs::grid::SweepParam],
) -> String {
    let param = free.iter().copied().find(|p| p.is_table());
    match param {
        Some(_) if table.d().is_some() => "fd".to_string(),
        Some(p) => bouncemap_figures::labels::free_name(table, p),
        None => table.name().to_string(),
    }
}

/// The longest text [`quoted`] shows whole.
pub const QUOTED_MAX: usize = 40;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn significant_digits() {
        assert_eq!(significant(0.5, 15), "0.500000000000000");
        assert_eq!(significant(9_780.139_017_934_653, 15), "9780.13901793465");
        assert_eq!(significant(-0.0123, 3), "-0.0123");
        assert_eq!(significant(0.0, 4), "0.000");
        assert_eq!(significant(1.5e-300, 3), "1.50e-300");
        assert_eq!(shortest(1e300), "1e300");
    }

    #[test]
    fn typed_text_is_quoted_escaped_and_cut() {
        assert_eq!(quoted("0.5"), "'0.5'");
        assert_eq!(quoted("a\nb"), "'a\\nb'");
        let long = quoted(&"1".repeat(5000));
        assert!(long.ends_with("…' (5000 characters)"), "{long}");
        assert!(long.chars().count() < 70, "{long}");
    }
}
