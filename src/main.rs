//! The `dataink` command-line tool. See `dataink --help`.

mod cli;

/// mimalloc keeps freed pages for reuse instead of returning and faulting them in again.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> std::process::ExitCode {
    cli::run()
}
