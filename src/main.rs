//! The `heightray` command line: thin shells over the library.

mod cli;

use clap::{CommandFactory, Parser};
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = cli::Args::parse();
    let Some(command) = args.command else {
        // The viewer comes next; until then the default prints what there is.
        let _ = cli::Args::command().print_long_help();
        return ExitCode::SUCCESS;
    };
    match cli::run(command) {
        Ok(code) => code,
        Err(error) => {
            eprintln!("heightray: {error:#}");
            ExitCode::FAILURE
        }
    }
}
