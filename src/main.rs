//! The `bouncemap` binary: parse the command line, dispatch, and map failures to exit
//! codes (2 for bad input, 1 for anything else). Messages are one line, no backtrace.

use bouncemap::cli::Cli;
use bouncemap::input::InputError;
use clap::error::ErrorKind;
use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => match e.kind() {
            ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            _ => {
                let text = e.render().to_string();
                let first = text
                    .lines()
                    .find(|l| !l.trim().is_empty())
                    .unwrap_or("error: invalid arguments");
                eprintln!("{}", first.trim_end());
                return ExitCode::from(2);
            }
        },
    };
    let result = match cli.command {
        Some(cmd) => bouncemap::commands::run(cmd),
        None => bouncemap::tui::run(
            bouncemap::tui::Options::from(&cli.tui),
            std::sync::Arc::new(bouncemap::tui::analysis::EngineAnalysis),
        ),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            if is_broken_pipe(&e) {
                return ExitCode::SUCCESS;
            }
            let code = if e.downcast_ref::<InputError>().is_some() {
                2
            } else {
                1
            };
            eprintln!("error: {}", one_line(&e));
            ExitCode::from(code)
        }
    }
}

fn one_line(e: &anyhow::Error) -> String {
    e.to_string().replace('\n', " ")
}

fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.downcast_ref::<std::io::Error>()
        .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
}
