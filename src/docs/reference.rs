//! The command reference (markdown) and the man pages, from the clap definitions.

use super::Document;
use crate::config::flags::Cli;
use clap::CommandFactory;

/// Every command with its full help, in the order `bouncemap --help` lists them.
pub fn markdown() -> String {
    let cmd = Cli::command();
    let mut out = String::from(
        "# Command reference\n\n\
         Every command and flag of `bouncemap`, as `bouncemap COMMAND --help` prints it.\n\
         This page is generated from the command-line definitions (`bouncemap generate-docs`);\n\
         a test keeps it equal to what the binary says. For what the commands are for, with\n\
         examples, see [commands.md](commands.md).\n",
    );
    let mut toc = String::from("\n");
    let mut body = String::new();
    section(&cmd, "bouncemap", 2, &mut toc, &mut body);
    out.push_str(&toc);
    out.push_str(&body);
    out
}

fn anchor(title: &str) -> String {
    title
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c.to_ascii_lowercase()),
            _ => None,
        })
        .collect()
}

fn section(cmd: &clap::Command, path: &str, level: usize, toc: &mut String, body: &mut String) {
    let indent = "  ".repeat(level - 2);
    toc.push_str(&format!("{indent}- [`{path}`](#{})\n", anchor(path)));
    let mut c = cmd.clone().bin_name(path);
    let help = c.render_long_help().to_string();
    body.push_str(&format!(
        "\n{} `{path}`\n\n```text\n{}\n```\n",
        "#".repeat(level.min(4)),
        help.trim_end()
    ));
    for sub in cmd.get_subcommands() {
        if sub.is_hide_set() || sub.get_name() == "help" {
            continue;
        }
        section(
            sub,
            &format!("{path} {}", sub.get_name()),
            level + 1,
            toc,
            body,
        );
    }
}

/// `man/bouncemap.1` and one page per command (`man/bouncemap-orbit.1`, ...).
pub fn man_pages() -> Vec<Document> {
    let mut cmd = Cli::command();
    cmd.build();
    let mut out = Vec::new();
    pages(&cmd, "bouncemap", &mut out);
    out
}

fn pages(cmd: &clap::Command, name: &str, out: &mut Vec<Document>) {
    // A page names its command as `bouncemap-orbit` (clap keeps names as static text).
    let page = cmd
        .clone()
        .name(&*Box::leak(name.to_string().into_boxed_str()));
    let mut bytes = Vec::new();
    clap_mangen::Man::new(page)
        .render(&mut bytes)
        .expect("writing to memory");
    out.push(Document {
        path: format!("man/{name}.1"),
        bytes,
    });
    for sub in cmd.get_subcommands() {
        if sub.is_hide_set() || sub.get_name() == "help" {
            continue;
        }
        pages(sub, &format!("{name}-{}", sub.get_name()), out);
    }
}
