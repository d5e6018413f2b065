//! `zrow-sim`: the command-line front end. All the work is in the library (`zrow_sim`); this
//! only maps its result to one stderr line and an exit code.

use std::process::ExitCode;
use zrow_sim::cli::{self, Command};

fn main() -> ExitCode {
    let args: Vec<_> = std::env::args_os().skip(1).collect();
    // No arguments or the demo's flags: the demo window, or its PNG when there is none.
    let result = if zrow_sim::demo::is_demo(&args) {
        zrow_sim::demo::run(&args)
    } else {
        cli::parse_args(args).and_then(|cmd| match cmd {
            Command::Help => zrow_sim::output::print(cli::USAGE),
            Command::Render(args) => cli::render(&args),
        })
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            match e {
                zrow_sim::SimError::Usage(_) => eprintln!("error: {e} (see `zrow-sim --help`)"),
                _ => eprintln!("error: {e}"),
            }
            ExitCode::from(e.exit_code())
        }
    }
}
