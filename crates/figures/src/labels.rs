//! How figures name what they show: a swept parameter's symbol (α, r, a family's own
//! parameter), the table's title as the paper writes it (F_D with its D, sin 2πt, a
//! file's family with a parameter left free).

use crate::text::plain;
use bouncemap_engine::grid::SweepParam;
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
