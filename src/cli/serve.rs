//! `dataink serve`: its options and the server's start (in builds with the `serve` feature).

use std::path::PathBuf;
use std::process::ExitCode;

use super::output::errln;

/// Options of `dataink serve`.
#[derive(clap::Args, Debug)]
pub struct ServeArgs {
    /// Folder the specs' data paths resolve in.
    #[arg(long, default_value = ".")]
    root: PathBuf,
    /// Address to listen on (loopback unless told otherwise).
    #[arg(long, default_value = "127.0.0.1:8700")]
    addr: std::net::SocketAddr,
    /// Largest request (spec and uploads together), in MiB.
    #[arg(long, default_value_t = 64)]
    max_upload_mib: usize,
    /// Most rows any one data source may have.
    #[arg(long, default_value_t = 5_000_000)]
    max_rows: u64,
    /// Most pixels of one PNG.
    #[arg(long, default_value_t = 40_000_000)]
    max_pixels: u64,
    /// Longest a request may take, in seconds (waiting for a render slot, then rendering).
    #[arg(long, default_value_t = 20.0)]
    render_seconds: f64,
}

/// Start the server and serve until Ctrl-C.
#[cfg(feature = "serve")]
pub fn serve(args: ServeArgs) -> ExitCode {
    use super::output::outln;
    use dataink::serve::{Limits, Server, run};
    if !(args.render_seconds.is_finite() && args.render_seconds > 0.0) {
        errln!("error: --render-seconds must be a positive number of seconds");
        return ExitCode::from(2);
    }
    let limits = Limits {
        upload_bytes: args.max_upload_mib.saturating_mul(1 << 20),
        rows: args.max_rows,
        pixels: args.max_pixels,
        render_time: std::time::Duration::from_secs_f64(args.render_seconds),
        ..Limits::default()
    };
    let server = match Server::new(args.root.clone(), limits) {
        Ok(server) => server,
        Err(e) => {
            errln!("error: cannot serve `{}`: {e}", args.root.display());
            return ExitCode::from(2);
        }
    };
    let runtime = match tokio::runtime::Builder::new_multi_thread().enable_all().build() {
        Ok(runtime) => runtime,
        Err(e) => {
            errln!("error: cannot start the server's runtime: {e}");
            return ExitCode::from(2);
        }
    };
    let root = args.root.display().to_string();
    let served = runtime.block_on(run(args.addr, server, |addr| {
        outln!("dataink serve: listening on http://{addr} (data from `{root}`); API at http://{addr}/api/openapi.json");
    }));
    // Renders past their time may still run on blocking threads: do not wait for them.
    runtime.shutdown_timeout(std::time::Duration::from_secs(1));
    match served {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            errln!("error: cannot serve on {}: {e}", args.addr);
            errln!("hint: is another server using the port? give another with --addr 127.0.0.1:PORT");
            ExitCode::from(2)
        }
    }
}

/// `dataink serve` in a build without the server: say how to get it.
#[cfg(not(feature = "serve"))]
pub fn serve(_args: ServeArgs) -> ExitCode {
    errln!("error: this dataink was built without the server");
    errln!("hint: build it with the `serve` feature:");
    errln!("  cargo run --release --features serve -- serve --root DIR");
    errln!("  cargo install --path . --features serve");
    ExitCode::from(2)
}
