use dicesim::cli::{self, ErrorKind};
use dicesim_setup::output::printable;
use std::process::ExitCode;

/// The exit status of each kind of failure; `dicesim --help` and the README list them.
fn status(kind: ErrorKind) -> ExitCode {
    match kind {
        // `dicesim trace | head`: the reader had enough, which is no failure.
        ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        ErrorKind::Failure => ExitCode::FAILURE,
        ErrorKind::Input => ExitCode::from(2),
        // As a shell reports a process stopped by the signal: 128 + its number.
        ErrorKind::Interrupted => ExitCode::from(cli::interrupted_status()),
    }
}

fn main() -> ExitCode {
    match cli::main() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let kind = e.kind();
            if kind != ErrorKind::BrokenPipe {
                // Messages quote file content: control characters are shown, never sent.
                eprintln!("dicesim: {}", printable(&e.to_string()));
            }
            status(kind)
        }
    }
}
