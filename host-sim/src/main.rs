//! `zrow-sim`: the command-line front end. All the work is in the library (`zrow_sim`); this
//! only maps its result to one stderr line and an exit code.

use std::process::ExitCode;
use zrow_sim::cli::{self, Command};

fn main() -> ExitCode {
    let result = cli::parse_args(std::env::args_os().skip(1)).and_then(|cmd| match cmd {
        Command::Help => {
            println!("{}", cli::USAGE);
            Ok(())
        }
        Command::Render(args) => cli::render(&args),
    });
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}
