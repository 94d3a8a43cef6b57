//! The `heightray` command line: thin shells over the library.

mod cli;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = cli::Args::parse();
    // Without a subcommand: the viewer (DESIGN 4).
    let command = args.command.unwrap_or(cli::Command::View(args.view));
    match cli::run(command) {
        Ok(code) => code,
        Err(error) => {
            eprintln!("heightray: {error:#}");
            ExitCode::FAILURE
        }
    }
}
