//! bouncemap, the binary: command-line input, the configuration stage, the headless
//! commands, the terminal application and every output format, on top of the
//! `bouncemap-engine` crate (the science).
//!
//! * [`config`]: the configuration stage: the flags (clap definitions), the one table
//!   of parameter rules, the one table-spec parser, typed presets, and the conversion of
//!   all of them into validated engine values.
//! * `commands`: one file per headless subcommand.
//! * [`output`]: typed records written as csv and json, the hit-count grid and its text
//!   form.
//! * [`tui`]: the terminal application.
//! * [`docs`]: the documents made from the code (command reference, man pages, keys,
//!   the README's screenshot).
//!
//! [`main`] is the whole binary; `config`, `output` and `tui` are public for the
//! integration tests (the headless commands are tested by running the binary).
//! See ARCHITECTURE.md for the bird's-eye view.

mod commands;
pub mod config;
pub mod docs;
pub mod output;
pub mod tui;

use clap::error::ErrorKind;
use clap::{CommandFactory, FromArgMatches};
use config::InputError;
use std::process::ExitCode;

/// Parse the command line, dispatch, and map failures to exit codes: 2 for bad input
/// (one line naming the problem and the valid range), 1 for anything else; a closed
/// output pipe ends quietly with 0.
pub fn main() -> ExitCode {
    if let Some(msg) = non_utf8_argument(std::env::args_os().skip(1)) {
        output::to_stderr(&format!("{msg}\n"));
        return ExitCode::from(2);
    }
    let parsed = config::flags::Cli::command()
        .try_get_matches()
        .and_then(|m| {
            let mut cli = config::flags::Cli::from_arg_matches(&m)?;
            config::flags::keep_written(&mut cli, &m);
            Ok(cli)
        });
    let cli = match parsed {
        Ok(c) => c,
        Err(e) => match e.kind() {
            ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
                return print_help(&e);
            }
            _ => {
                let args: Vec<String> = std::env::args().skip(1).collect();
                let msg = refusal(&e, &args);
                output::to_stderr(&format!("{msg}\n"));
                return ExitCode::from(2);
            }
        },
    };
    let result = match cli.command {
        Some(cmd) => commands::run(cmd),
        None => {
            let a = cli.tui;
            tui::run(tui::Options {
                table: a.tui_table,
                alpha: a.tui_alpha,
                r: a.tui_r,
                fps: a.fps,
                color: a.color,
                marker: a.marker,
                mouse: a.mouse,
                config: a.config,
            })
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            if output::sink::is_closed_output(&e) {
                return ExitCode::SUCCESS;
            }
            let code = if e.downcast_ref::<InputError>().is_some() {
                2
            } else {
                1
            };
            output::to_stderr(&format!("error: {}\n", e.to_string().replace('\n', " ")));
            ExitCode::from(code)
        }
    }
}

/// The refusal of the first argument that is not UTF-8 text, naming its flag (every
/// value, paths included, is text: names are shown in outputs and file headers).
fn non_utf8_argument(args: impl Iterator<Item = std::ffi::OsString>) -> Option<String> {
    let mut previous: Option<String> = None;
    for a in args {
        match a.to_str() {
            Some(t) => previous = Some(t.to_string()),
            None => {
                let lossy = a.to_string_lossy();
                // `--out=PATH`, `--out PATH`, or a positional argument.
                let (flag, value) = match lossy.split_once('=') {
                    Some((f, v)) if f.starts_with("--") => (f.to_string(), v),
                    _ => match previous {
                        Some(p) if p.starts_with('-') && !p.contains('=') => (p, &*lossy),
                        _ => ("an argument".to_string(), &*lossy),
                    },
                };
                let shown = output::text::quoted(value);
                return Some(format!(
                    "error: {flag}: {shown} is not UTF-8 text: valid a value (or a path) in UTF-8"
                ));
            }
        }
    }
    None
}

/// The help or version text on stdout (in colour on a terminal); a failed write is
/// reported as any command's is (a closed pipe is a quiet end).
fn print_help(e: &clap::Error) -> ExitCode {
    use std::io::{IsTerminal, Write};
    if std::io::stdout().is_terminal() {
        let _ = e.print();
        return ExitCode::SUCCESS;
    }
    let mut out = output::sink::Sink::stdout();
    let written = write!(out, "{}", e.render()).map_err(anyhow::Error::from);
    match out.end(written) {
        Err(e) if !output::sink::is_closed_output(&e) => {
            output::to_stderr(&format!("error: {e}\n"));
            ExitCode::from(1)
        }
        _ => ExitCode::SUCCESS,
    }
}

/// The command that `args` (the arguments after the program's name) ask for, parsed
/// and checked as the binary parses its own, or the one line the binary would print
/// refusing them (without its `error: `): the command line for another front end (the
/// Python module builds its calls' arguments and runs them through this).
pub fn parse_command(args: &[String]) -> Result<config::flags::Command, String> {
    let strip = |m: String| m.strip_prefix("error: ").map(String::from).unwrap_or(m);
    let all = std::iter::once("bouncemap").chain(args.iter().map(String::as_str));
    let m = config::flags::Cli::command()
        .try_get_matches_from(all)
        .map_err(|e| strip(refusal(&e, args)))?;
    let mut cli = config::flags::Cli::from_arg_matches(&m).map_err(|e| strip(refusal(&e, args)))?;
    config::flags::keep_written(&mut cli, &m);
    cli.command
        .ok_or_else(|| "no command: valid a subcommand (sweep, orbit, basins, ...)".into())
}

/// Why a command run for another front end ([`run_captured`]) gave no output.
#[derive(Debug)]
pub enum Refused {
    /// Bad input: the one line the binary prints (status 2), without its `error: `.
    Input(String),
    /// Anything else: the binary's message (status 1).
    Failed(String),
}

/// Run the command `args` (the arguments after the program's name) as the binary
/// runs it, keeping what it writes to standard output: for another front end (the
/// Python module reads the json of `--format json`). Progress and notes still go to
/// standard error.
pub fn run_captured(args: &[String]) -> Result<Vec<u8>, Refused> {
    let cmd = parse_command(args).map_err(Refused::Input)?;
    let (result, bytes) = output::sink::capture(|| commands::run(cmd));
    match result {
        Ok(()) => Ok(bytes),
        Err(e) => {
            let msg = e.to_string().replace('\n', " ");
            Err(if e.downcast_ref::<InputError>().is_some() {
                Refused::Input(msg)
            } else {
                Refused::Failed(msg)
            })
        }
    }
}

/// The one line refusing a command line `args` that clap refused with `e`.
fn refusal(e: &clap::Error, args: &[String]) -> String {
    let mut msg = value_error(e, args).unwrap_or_else(|| {
        one_line_clap_error(&e.render().to_string()).replace(
            "requires a subcommand but one was not provided",
            "needs a NAME",
        )
    });
    if matches!(
        e.kind(),
        ErrorKind::InvalidSubcommand | ErrorKind::MissingSubcommand
    ) {
        let names = subcommand_names(args.iter().cloned());
        if !names.is_empty() {
            msg.push_str(": valid ");
            msg.push_str(&names.join(", "));
        }
    }
    msg
}

/// A refused value as one line naming the flag, the value and the valid form (for
/// values our parsers refuse, their own message; for a value missing or not among the
/// possible ones, those or the flag's help), rebuilt from clap's context so no parser
/// internals and no raw typed text reach the user.
fn value_error(e: &clap::Error, args: &[String]) -> Option<String> {
    use clap::error::{ContextKind, ContextValue};
    let ContextValue::String(arg) = e.get(ContextKind::InvalidArg)? else {
        return None;
    };
    // "--alpha <A>" → "--alpha"; a positional argument keeps its "<FILE>".
    let flag = if arg.starts_with('-') {
        arg.split_whitespace().next().unwrap_or(arg)
    } else {
        arg.as_str()
    };
    match e.kind() {
        ErrorKind::ValueValidation => {
            let why = std::error::Error::source(e)?.to_string();
            Some(format!("error: {flag}: {}", why.replace('\n', " ")))
        }
        ErrorKind::InvalidValue => {
            let value = match e.get(ContextKind::InvalidValue) {
                Some(ContextValue::String(v)) => v.clone(),
                _ => String::new(),
            };
            let valid = match e.get(ContextKind::ValidValue) {
                Some(ContextValue::Strings(v)) if !v.is_empty() => {
                    format!("valid {}", v.join(", "))
                }
                _ => flag_help(flag, args)?,
            };
            Some(if value.is_empty() {
                format!("error: {flag} needs a value: {valid}")
            } else {
                format!(
                    "error: {flag}: {} is not a possible value: {valid}",
                    output::text::quoted(&value)
                )
            })
        }
        _ => None,
    }
}

/// What the help of `flag` (`--alpha`), in the subcommand the command line reached, says
/// its values are: "valid …" where it states them, else its first line.
fn flag_help(flag: &str, args: &[String]) -> Option<String> {
    use clap::CommandFactory;
    let long = flag.strip_prefix("--")?;
    let mut cmd = config::flags::Cli::command();
    for a in args {
        if let Some(sub) = cmd.find_subcommand(a).cloned() {
            cmd = sub;
        }
    }
    let arg = cmd.get_arguments().find(|a| a.get_long() == Some(long))?;
    let help = arg.get_help()?.to_string();
    let first = help
        .lines()
        .next()?
        .trim()
        .trim_end_matches('.')
        .to_string();
    Some(match first.split_once("valid ") {
        Some((_, valid)) => format!("valid {valid}"),
        None => first,
    })
}

/// Clap's message cut to one line: the first line, the items it introduces (the
/// missing arguments after "...not provided:"), and the list of valid values if it
/// gives one.
fn one_line_clap_error(text: &str) -> String {
    let mut lines = text.lines();
    let mut msg = lines
        .next()
        .unwrap_or("error: invalid arguments")
        .trim()
        .to_string();
    if msg.ends_with(':') {
        let items: Vec<&str> = lines
            .by_ref()
            .take_while(|l| l.starts_with(' ') && !l.trim().is_empty())
            .map(str::trim)
            .collect();
        msg.push(' ');
        msg.push_str(&items.join(", "));
    }
    for l in lines.map(str::trim) {
        if l.starts_with("[possible values") {
            msg.push(' ');
            msg.push_str(l);
        } else if let Some(tip) = l.strip_prefix("tip: ") {
            // "a similar argument exists: '--steps'"
            msg.push_str(&format!(" ({tip})"));
        }
    }
    msg
}

/// The subcommands the command line `args` had reached (those of `bouncemap figure`
/// after `figure`, ...): the valid names where an unknown or missing one was refused.
fn subcommand_names(args: impl Iterator<Item = String>) -> Vec<String> {
    use clap::CommandFactory;
    let mut cmd = config::flags::Cli::command();
    for a in args {
        let Some(sub) = cmd.find_subcommand(&a).cloned() else {
            continue;
        };
        cmd = sub;
    }
    cmd.get_subcommands()
        .map(|c| c.get_name().to_string())
        .filter(|n| n != "help")
        .collect()
}
