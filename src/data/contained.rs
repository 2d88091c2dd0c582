//! Reader panics contained at the reader boundary.
//!
//! A malformed file can make a dependency's reader panic (polars-parquet asserts on a flipped
//! byte, the Arrow reader overflows on a bad length). Validation catches what it can first; what
//! is left is caught here and becomes an error naming the file, so the user gets a message and an
//! exit code instead of a crash. While a contained call runs, the default panic message is not
//! printed (the error says what happened).

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Once;
use std::sync::atomic::{AtomicUsize, Ordering};

/// How many contained calls are running now; while any is, panic messages are not printed.
static QUIET: AtomicUsize = AtomicUsize::new(0);
static HOOK: Once = Once::new();

/// Run `read`; a panic inside it becomes `Err` with the panic's message.
pub fn contain<T>(read: impl FnOnce() -> T) -> Result<T, String> {
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if QUIET.load(Ordering::SeqCst) == 0 {
                previous(info);
            }
        }));
    });
    QUIET.fetch_add(1, Ordering::SeqCst);
    let result = catch_unwind(AssertUnwindSafe(read));
    QUIET.fetch_sub(1, Ordering::SeqCst);
    result.map_err(|payload| {
        let text = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "an unknown failure".into());
        let first: String = text.lines().next().unwrap_or("").chars().take(200).collect();
        format!("the reader failed on malformed content ({first})")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_an_error_and_values_pass_through() {
        assert_eq!(contain(|| 7), Ok(7));
        let err = contain(|| -> i32 { panic!("thrift bool field") }).expect_err("contained");
        assert!(err.contains("thrift bool field"), "{err}");
        let err = contain(|| -> i32 { panic!("{}", "x".repeat(10_000)) }).expect_err("contained");
        assert!(err.len() < 300, "the message is bounded: {} bytes", err.len());
    }
}
