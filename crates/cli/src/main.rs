//! `renderlab`: render relief and textured surfaces, measure the methods, write the lab report.
//!
//! This binary only parses arguments (each command's flags, their ranges and their help in
//! one file per command under `commands/`, the choices derived from the libraries'
//! catalogues and enums), dispatches, reports progress and maps errors to exit codes: every
//! algorithm, the reference renderings and the labs' policies live in the library crates.

#![warn(missing_docs)]
// The argument structs' doc comments are `--help` texts (with `[:A:B]` syntax), not rustdoc links.
#![allow(rustdoc::broken_intra_doc_links)]

mod args;
mod commands;
mod progress;
mod vulkan_layer;

fn main() {
    // First, while the process has one thread: the environment may only be changed then.
    vulkan_layer::quiet_device_select_layer();
    let cli = match args::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => e.exit(), // --help, --version
        // `renderlab` (or `renderlab relief`) alone: the help, and the usage-error status 2.
        Err(e) if e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => e.exit(),
        Err(e) => {
            // Clap's own message, on one line like every other error: its lines before the
            // usage hint (the first names the flag and the value; a missing argument's name
            // comes on the next).
            let text = e.to_string();
            let body: Vec<&str> = text
                .lines()
                .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
                .map(str::trim)
                .filter(|l| !l.is_empty())
                .collect();
            let message = if body.is_empty() { "invalid arguments".to_string() } else { body.join(" ") };
            eprintln!("renderlab: error: {}", message.trim_start_matches("error: "));
            std::process::exit(1);
        }
    };
    install_interrupt_handler();
    if let Err(e) = commands::run(cli) {
        // One line, naming the file or flag at fault.
        eprintln!("renderlab: error: {}", one_line(&e));
        std::process::exit(1);
    }
}

/// On SIGINT, SIGTERM or SIGHUP: removes every temporary file of the writes in flight (the
/// files already written stay whole, each having been renamed into place complete), says so
/// in one line and exits with 130, as a shell reports an interrupted command. A resumed run
/// then starts from the files that are there.
fn install_interrupt_handler() {
    let installed = ctrlc::set_handler(|| {
        eprintln!("\nrenderlab: interrupted; temporary files removed");
        renderlab_core::tempfiles::remove_all_and_exit(130);
    });
    if let Err(e) = installed {
        eprintln!(
            "renderlab: warning: cannot handle interrupts ({e}): an interrupt may leave temporary files"
        );
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
