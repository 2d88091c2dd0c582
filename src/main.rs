//! The `dataink` command-line tool. See `dataink --help`.

mod cli;

fn main() -> std::process::ExitCode {
    cli::run()
}
