//! `renderlab`: render relief and textured surfaces, measure the methods, write the lab report.
//!
//! This binary only parses arguments, reports progress and maps errors to exit codes; every
//! algorithm lives in the library crates.

#![warn(missing_docs)]
// The argument structs' doc comments are `--help` texts (with `[:A:B]` syntax), not rustdoc links.
#![allow(rustdoc::broken_intra_doc_links)]

mod args;
mod commands;
mod progress;

use clap::Parser;

fn main() {
    let cli = match args::Cli::try_parse() {
        Ok(cli) => cli,
        // A refused value (a technique name, a kernel): one line and exit 1, like every other
        // bad input; usage errors, help and version keep clap's own output.
        Err(e) if e.kind() == clap::error::ErrorKind::ValueValidation => {
            let text = e.to_string();
            let first = text.lines().next().unwrap_or_default();
            eprintln!("renderlab: error: {}", first.trim_start_matches("error: "));
            std::process::exit(1);
        }
        Err(e) => e.exit(),
    };
    if let Err(e) = commands::run(cli) {
        // One line, naming the file or flag at fault.
        eprintln!("renderlab: error: {}", one_line(&e));
        std::process::exit(1);
    }
}

/// The error and its causes on one line, each cause added only if the text so far does not
/// already contain it (the library errors print their source inside their own message).
fn one_line(e: &anyhow::Error) -> String {
    let mut msg = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if msg.contains(&text) {
            continue;
        }
        if !msg.is_empty() {
            msg.push_str(": ");
        }
        msg.push_str(&text);
    }
    msg.replace('\n', " ")
}
