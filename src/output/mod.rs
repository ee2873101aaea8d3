//! Everything the headless commands and the terminal application's exports write.
//!
//! * [`records`]: one `Serialize` record type per output, shared by the commands and
//!   the terminal application's export, written through the `csv` crate (quoting done
//!   right) and `serde_json`. Numbers are the shortest strings that read back to the
//!   same f64 (exponent form where shorter).
//! * [`part_file`]: the one format of the files `sweep` and `plane` write and `merge`
//!   joins: provenance, hashes, shards, csv and json layouts, the streaming writer and
//!   the reader that checks a part, a value at a time (over byte-level pieces, never the
//!   whole file), and the join, merging the parts' values
//!   into index order as they are read again; [`sweep_file`] and [`plane_file`] are its
//!   two kinds (their rows, and where a row belongs).
//! * [`attractors_file`]: the part file of `attractors --shard` (a part of a
//!   continuation of attractors whole, in json) that `merge` reads back and joins.
//! * [`sink`]: the one output layer: standard output (a closed pipe ends the run
//!   quietly, any other write error fails it) or a file written atomically (temporary,
//!   then rename), and the `--out` rule (never an input of the run). Notes and
//!   progress go to stderr through [`to_stderr`], which never fails.
//! * [`signals`]: the signals that end a process, answered by the headless commands
//!   (temporaries removed) and the terminal application (terminal restored).
//! * [`hitgrid`]: the one hit-count grid behind every text picture; [`diagram`]: its
//!   text form with axes and labels (`sweep --format braille`).
//! * [`basin_map`]: a basin picture on character cells, and each attractor's texture
//!   and legend line (`basins --format braille`, the basins panel).
//! * [`plane_map`]: a two-parameter map on character cells (glyphs per class, curve
//!   marks, axes, legend).
//! * [`classes`]: what a value's orbit is (period 1, 2, 4, 8, other, sticking, chaotic),
//!   as the pictures colour it; it is the figures crate's, re-exported here for the text
//!   pictures and the terminal application.
//! * [`text`]: number formatting for aligned text columns.
//! * [`figure_file`]: a figure (drawn by the `bouncemap_figures` crate: SVG, and PNG
//!   rendered with the fonts compiled in) written to a file atomically.

pub mod attractors_file;
pub mod basin_map;
pub mod diagram;
pub mod figure_file;
pub mod hitgrid;
pub mod part_file;
pub mod plane_file;
pub mod plane_map;
pub mod records;
pub mod signals;
pub mod sink;
pub mod sweep_file;
pub mod text;

pub use bouncemap_figures::classes;
use clap::ValueEnum;
use std::io::Write;

/// `text` on stderr (a note, a refusal, progress): a stderr that cannot be written
/// (closed, full) loses the text, it never fails or stops the run.
pub fn to_stderr(text: &str) {
    let _ = std::io::stderr().lock().write_all(text.as_bytes());
}

/// Output format of a headless command.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Default)]
pub enum Format {
    /// Aligned columns for people.
    #[default]
    Text,
    /// Comma-separated values with a header row.
    Csv,
    /// JSON.
    Json,
}
