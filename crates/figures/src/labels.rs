//! How figures name what they show: a swept parameter's symbol (α, r, a family's own
//! parameter), the table's title as the paper writes it (F_D with its D, sin 2πt, a
//! file's family with a parameter left free).

use crate::text::plain;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::Table;

/// The swept parameter's symbol, in markup (a family's parameter by its own name,
/// `w_2` drawn with its subscript).
pub fn param_label(p: SweepParam) -> String {
    match p {
        SweepParam::Alpha => "$\u{3b1}$".into(),
        SweepParam::R => "$r$".into(),
        SweepParam::Table(n) => format!("${}$", n.as_str()),
    }
}

/// The swept parameter's symbol in plain text.
pub fn param_symbol(p: SweepParam) -> String {
    match p {
        SweepParam::Alpha => "\u{3b1}".into(),
        other => other.as_str().to_string(),
    }
}

/// The table's title with `free` left free when it is a parameter of its family: F_D
/// as the paper writes it, a file's family by its name and the other values.
pub fn family_title(table: &Table, free: SweepParam) -> String {
    match free {
        SweepParam::Table(_) if table.d().is_some() => "$F_D$".into(),
        SweepParam::Table(n) => plain(&table.name_with_free(n.as_str())),
        _ => table_title(table),
    }
}

/// The table's name with `free` left free when it is a parameter of its family
/// (`fd:D`), else its name.
pub fn free_name(table: &Table, free: SweepParam) -> String {
    match free {
        SweepParam::Table(n) => table.name_with_free(n.as_str()),
        _ => table.name().to_string(),
    }
}

/// The table's name as the paper writes it: F_D with its D, sin 2πt, or the file's
/// name.
pub fn table_title(table: &Table) -> String {
    match table.d() {
        Some(d) => format!("$F_{{{d}}}$"),
        None if table.name() == "sine" => "$F$ = sin 2\u{3c0}$t$".into(),
        None => plain(table.name()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bouncemap_engine::table::{Family, Param, Variable};
    use std::sync::Arc;

    #[test]
    fn a_swept_family_parameter_is_left_free_in_the_title() {
        let fd = Table::fd(0.1).unwrap();
        assert_eq!(family_title(&fd, SweepParam::D), "$F_D$");
        assert_eq!(family_title(&fd, SweepParam::Alpha), "$F_{0.1}$");
        assert_eq!(free_name(&fd, SweepParam::D), "fd:D");
        let params = vec![Param::new("w", 0.5, 0.0, 1.0).unwrap()];
        let pieces = [("0".to_string(), vec!["w".to_string()])];
        let fam = Arc::new(Family::piecewise("flat", params, Variable::Phase, &pieces).unwrap());
        let t = Family::member(&fam, &[0.5]).unwrap();
        let w = SweepParam::parse("w", &t).unwrap();
        assert_eq!(family_title(&t, w), "flat (w)");
        assert_eq!(family_title(&t, SweepParam::R), "flat (w = 0.5)");
        assert_eq!(param_label(w), "$w$");
    }
}
