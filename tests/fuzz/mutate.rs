//! Seeded mutations: byte edits for binary files, structural and semantic edits for TOML specs
//! and CSV cells. Everything is a pure function of the generator state, so one seed and one
//! iteration number always give the same input.

/// A xorshift64* generator: small, seeded, the same on every platform.
pub struct Rng(u64);

impl Rng {
    /// A generator for one (seed, stream, iteration) triple; streams keep targets apart.
    pub fn new(seed: u64, stream: u64, iteration: u64) -> Rng {
        let mut state =
            seed ^ stream.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ iteration.wrapping_mul(0xD1B5_4A32_D192_ED03);
        if state == 0 {
            state = 0x2545_F491_4F6C_DD1D;
        }
        let mut rng = Rng(state);
        for _ in 0..4 {
            rng.next();
        }
        rng
    }

    /// The next 64 random bits.
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A number in `0..n` (0 when `n` is 0).
    pub fn below(&mut self, n: usize) -> usize {
        if n == 0 { 0 } else { (self.next() % n as u64) as usize }
    }

    /// One element of a non-empty slice.
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// Bytes that often sit at boundaries of length and type fields.
const INTERESTING: [u8; 8] = [0x00, 0x01, 0x7f, 0x80, 0xff, 0x16, 0x36, b'9'];

/// One to four byte edits: bit flips, random or boundary bytes, inserts, deletes and splices.
pub fn mutate_bytes(rng: &mut Rng, input: &[u8]) -> Vec<u8> {
    let mut out = input.to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(out.len().max(1));
        match rng.below(6) {
            0 if !out.is_empty() => out[at] ^= 1 << rng.below(8),
            1 if !out.is_empty() => out[at] = rng.next() as u8,
            2 if !out.is_empty() => out[at] = *rng.pick(&INTERESTING),
            3 => {
                let n = 1 + rng.below(16);
                let bytes: Vec<u8> = (0..n).map(|_| rng.next() as u8).collect();
                out.splice(at.min(out.len())..at.min(out.len()), bytes);
            }
            4 if !out.is_empty() => {
                let end = (at + 1 + rng.below(64)).min(out.len());
                out.drain(at..end);
            }
            _ if !out.is_empty() => {
                let from = rng.below(out.len());
                let len = (1 + rng.below(256)).min(out.len() - from);
                let chunk = out[from..from + len].to_vec();
                out.splice(at..at, chunk);
            }
            _ => out.push(rng.next() as u8),
        }
    }
    out
}

/// Values that size work or sit at the edges of what a number or string can be.
fn extreme_value(rng: &mut Rng) -> String {
    match rng.below(16) {
        0 => "1e308".into(),
        1 => "-1e308".into(),
        2 => "-1".into(),
        3 => "0".into(),
        4 => "1e10".into(),
        5 => "9223372036854775807".into(),
        6 => "-9223372036854775808".into(),
        7 => "nan".into(),
        8 => "inf".into(),
        9 => "1e-300".into(),
        10 => format!("\"{}\"", "x".repeat(1 + rng.below(100_000))),
        11 => "\"\\u0000\\u001b[31m\\u202e\"".into(),
        12 => format!("{}1{}", "[".repeat(1 + rng.below(2000)), "]".repeat(1 + rng.below(2000))),
        13 => "{}".into(),
        14 => "[]".into(),
        _ => format!("{}", rng.next() as i64),
    }
}

/// The `key = value` lines of a TOML text: (line index, byte offset of the value).
fn key_lines(lines: &[String]) -> Vec<(usize, usize)> {
    lines
        .iter()
        .enumerate()
        .filter_map(|(i, l)| {
            let t = l.trim_start();
            if t.starts_with('#') || t.starts_with('[') {
                return None;
            }
            l.find(" = ").map(|eq| (i, eq + 3))
        })
        .collect()
}

/// Quoted strings of a text, for swapping column and source names between keys.
fn quoted_words(text: &str) -> Vec<String> {
    text.split('"').skip(1).step_by(2).filter(|w| w.len() < 40).map(str::to_string).collect()
}

/// One to three edits of a TOML spec: drop or duplicate a key, swap values between keys, set an
/// extreme value, rename a quoted word to another one of the file, or add deep nesting.
pub fn mutate_toml(rng: &mut Rng, text: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let words = quoted_words(text);
    for _ in 0..1 + rng.below(3) {
        let keys = key_lines(&lines);
        if keys.is_empty() || lines.is_empty() {
            break;
        }
        let (line, value_at) = *rng.pick(&keys);
        match rng.below(7) {
            0 => {
                lines.remove(line);
            }
            1 => {
                let copy = lines[line].clone();
                lines.insert(line, copy);
            }
            2 => {
                let (other, other_at) = *rng.pick(&keys);
                let a = lines[line][value_at..].to_string();
                let b = lines[other][other_at..].to_string();
                lines[line].replace_range(value_at.., &b);
                lines[other].replace_range(other_at.., &a);
            }
            3 | 4 => {
                let value = extreme_value(rng);
                lines[line].replace_range(value_at.., &value);
            }
            5 if !words.is_empty() => {
                let from = rng.pick(&words).clone();
                let to = rng.pick(&words).clone();
                lines[line] = lines[line].replace(&format!("\"{from}\""), &format!("\"{to}\""));
            }
            _ => {
                let depth = 1 + rng.below(3000);
                let nested = format!("{}{{ a = 1 }}{}", "[".repeat(depth), "]".repeat(depth));
                lines[line].replace_range(value_at.., &nested);
            }
        }
    }
    let mut out = lines.join("\n");
    out.push('\n');
    out
}

/// CSV cells people and generators write: missing markers, extremes, quotes, long cells.
fn odd_cell(rng: &mut Rng) -> String {
    match rng.below(12) {
        0 => String::new(),
        1 => "nan".into(),
        2 => "NA".into(),
        3 => "1e308".into(),
        4 => "-1e308".into(),
        5 => "18446744073709551616".into(),
        6 => "\"".into(),
        7 => "x".repeat(1 + rng.below(10_000)),
        8 => "0".into(),
        9 => "-0".into(),
        10 => "2015-13-45".into(),
        _ => format!("{}", rng.next() as i64),
    }
}

/// One to eight CSV cells replaced (the header row included), or a row dropped or duplicated.
pub fn mutate_csv(rng: &mut Rng, text: &str) -> String {
    let mut rows: Vec<Vec<String>> = text.lines().map(|l| l.split(',').map(str::to_string).collect()).collect();
    for _ in 0..1 + rng.below(8) {
        if rows.is_empty() {
            break;
        }
        let r = rng.below(rows.len());
        match rng.below(8) {
            0 => {
                rows.remove(r);
            }
            1 => {
                let copy = rows[r].clone();
                rows.insert(r, copy);
            }
            _ => {
                let c = rng.below(rows[r].len());
                rows[r][c] = odd_cell(rng);
            }
        }
    }
    let mut out: String = rows.iter().map(|r| r.join(",")).collect::<Vec<_>>().join("\n");
    out.push('\n');
    out
}
