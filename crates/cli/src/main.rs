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
    let cli = args::Cli::parse();
    if let Err(e) = commands::run(cli) {
        // One line, naming the file or flag at fault.
        let msg = format!("{e:#}").replace('\n', " ");
        eprintln!("renderlab: error: {msg}");
        std::process::exit(1);
    }
}
