//! The integration tests of the `bouncemap` binary, one test binary (one link of the
//! crate) with a module per area.

mod architecture;
mod array_and_resume;
mod attractors_cli;
mod check_memory;
mod cli;
mod cli_orbit;
mod continuation_cli;
mod curves_cli;
mod docs;
mod figure_cli;
mod generated_docs;
mod hostile;
mod hostile_three;
mod merge_property;
mod merge_stream;
mod orbits_cli;
mod plane_cli;
mod reliability;
mod sweep_cli;
mod table_families;
mod table_files;
mod trust_cli;
mod tui_attractors;
mod tui_branches;
mod tui_common;
mod tui_e2e;
mod tui_keys;
mod tui_latency;
mod tui_panels;
mod tui_plane;
mod tui_presets;
mod tui_render;
mod tui_screen;
mod tui_small_screens;
mod tui_terminal;
