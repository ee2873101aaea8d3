//! The terminal application's presets are the headless ones: loading a preset in the
//! picker makes the diagram run exactly the sweep `bouncemap sweep --preset NAME` runs.

use crate::tui_common::{app, size};
use bouncemap::config::flags::{Cli, Command};
use bouncemap::config::presets::PRESETS;
use bouncemap::output::hitgrid::Marker;
use bouncemap::tui::app::Overlay;
use bouncemap::tui::keymap::Action;
use clap::Parser;

#[test]
fn every_preset_in_the_picker_runs_the_headless_sweep() {
    for (i, (name, _)) in PRESETS.iter().enumerate() {
        let Command::Sweep(args) = Cli::try_parse_from(["bouncemap", "sweep", "--preset", name])
            .unwrap()
            .command
            .unwrap()
        else {
            unreachable!()
        };
        let headless = bouncemap::config::sweep::sweep_spec(&args).unwrap();
        let mut a = app(Marker::Braille);
        size(&mut a, 120, 40);
        a.handle(Action::Presets);
        a.shared.overlay = Overlay::Presets { selected: i };
        a.handle(Action::Enter);
        assert_eq!(
            a.shared.message.as_ref().map(|m| m.1),
            Some(false),
            "{name}: {:?}",
            a.shared.message
        );
        let tui = a.panels.diagram.sweep_spec(&a.shared);
        // The same sweep, with every value's largest exponent measured for the strip
        // under the diagram (a measurement after the run: the points are the same).
        assert!(tui.lyapunov, "{name}");
        let points_spec = bouncemap_engine::sweep::SweepSpec {
            lyapunov: false,
            ..tui.clone()
        };
        assert_eq!(points_spec, headless, "{name}");
        assert!(tui.initial.near_fixed_point, "{name}: the paper's start");
    }
}
