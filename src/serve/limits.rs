//! What one request may ask of the server: bytes in, rows loaded, pixels drawn and time spent.

use std::time::Duration;

/// The server's limits per request (the `dataink serve` options set them).
#[derive(Clone, Debug)]
pub struct Limits {
    /// Largest request body: the spec and every uploaded file together.
    pub upload_bytes: usize,
    /// Largest spec text.
    pub spec_bytes: usize,
    /// Most uploaded files in one request.
    pub files: usize,
    /// Most rows any one data source may load.
    pub rows: u64,
    /// Most pixels of one PNG (width × height after `scale`).
    pub pixels: u64,
    /// Longest a request may wait for a render slot and then render.
    pub render_time: Duration,
    /// Renders running at once.
    pub concurrent_renders: usize,
    /// Bytes of answers kept for repeated requests.
    pub cache_bytes: usize,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            upload_bytes: 64 << 20,
            spec_bytes: 256 << 10,
            files: 16,
            rows: 5_000_000,
            pixels: 40_000_000,
            render_time: Duration::from_secs(20),
            concurrent_renders: std::thread::available_parallelism().map_or(2, |n| n.get()),
            cache_bytes: 128 << 20,
        }
    }
}
