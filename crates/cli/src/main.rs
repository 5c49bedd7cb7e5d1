//! `renderlab`: render relief and textured surfaces, measure the methods, write the lab report.
//!
//! This binary only parses arguments, reports progress and maps errors to exit codes; every
//! algorithm lives in the library crates.

#![warn(missing_docs)]
// The argument structs' doc comments are `--help` texts (with `[:A:B]` syntax), not rustdoc links.
#![allow(rustdoc::broken_intra_doc_links)]

mod args;
mod commands;
mod gpu;
mod progress;

fn main() {
    let cli = match args::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => e.exit(), // --help, --version
        Err(e) => {
            // Clap's own message, on one line like every other error (its first line names the
            // flag and the value; the rest is a usage hint).
            let text = e.to_string();
            let first = text.lines().find(|l| !l.trim().is_empty()).unwrap_or("invalid arguments");
            eprintln!("renderlab: error: {}", first.trim_start_matches("error: "));
            std::process::exit(1);
        }
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
