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
                eprintln!("{}", one_line_clap_error(&e.render().to_string()));
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

/// Clap's message cut to one line, keeping the list of valid values if it gives one.
fn one_line_clap_error(text: &str) -> String {
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    let mut msg = lines
        .next()
        .unwrap_or("error: invalid arguments")
        .to_string();
    if let Some(valid) = lines.find(|l| l.starts_with("[possible values")) {
        msg.push(' ');
        msg.push_str(valid);
    }
    msg
}

fn one_line(e: &anyhow::Error) -> String {
    e.to_string().replace('\n', " ")
}

fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.downcast_ref::<std::io::Error>()
        .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
}
