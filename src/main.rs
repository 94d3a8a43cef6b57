//! The `heightray` command line: thin shells over the library.

mod cli;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = cli::Args::parse();
    if let Some(bytes) = args.memory {
        heightray::heightfield::store::residency::set_budget(bytes);
    }
    // Without a subcommand: the viewer.
    let command = args.command.unwrap_or(cli::Command::View(args.view));
    match cli::run(command) {
        Ok(code) => code,
        // The reader of the output stopped reading (`heightray trace ... | head`): what it
        // read is all it wanted, as with any tool whose output is cut short by a pipe.
        Err(error) if stopped_reading(&error) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("heightray: {}", message(&error));
            ExitCode::FAILURE
        }
    }
}

/// Whether the error is a write to a pipe whose reader has gone.
fn stopped_reading(error: &anyhow::Error) -> bool {
    error.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
    })
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
