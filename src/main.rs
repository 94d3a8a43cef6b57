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
            eprintln!("heightray: {}", message(&error));
            ExitCode::FAILURE
        }
    }
}

/// The error and the causes it does not already tell: most of the library's errors name their
/// cause in their own message, and printing the chain would say it twice.
fn message(error: &anyhow::Error) -> String {
    let mut message = error.to_string();
    for cause in error.chain().skip(1) {
        let cause = cause.to_string();
        if !message.contains(&cause) {
            message = format!("{message}: {cause}");
        }
    }
    message
}
