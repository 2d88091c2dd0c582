//! How long a step took, printed to stderr when the environment variable `DATAINK_TIMINGS` is
//! set (`timing: LABEL: 12.3 ms`), so anyone can see where a render spends its time.

/// Run `work`; with the environment variable `DATAINK_TIMINGS` set, print how long it took.
pub fn timed<T>(label: &str, work: impl FnOnce() -> T) -> T {
    if std::env::var_os("DATAINK_TIMINGS").is_none() {
        return work();
    }
    let start = std::time::Instant::now();
    let out = work();
    eprintln!("timing: {label}: {:.1} ms", start.elapsed().as_secs_f64() * 1e3);
    out
}
