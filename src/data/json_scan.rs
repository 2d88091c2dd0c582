//! One linear look over JSON bytes before any parser sees them: how deep the arrays and objects
//! nest (refused past a limit, so a hostile file cannot overflow the stack or make polars build
//! gigabytes of nested types), and the integers too wide for a 64-bit signed integer (read as
//! text, see [`quote_wide_integers`]). Strings are skipped with their escapes, so brackets and
//! digits inside them do not count.

use std::borrow::Cow;
use std::fmt;

/// Deepest nesting of arrays and objects in a JSON record file (`.json`, `.jsonl`, with or
/// without `json_path`) and in GeoJSON: `[{"x": 1}]` is 2 levels deep.
pub const MAX_RECORD_DEPTH: usize = 64;

/// Deepest nesting in a tree file (`format = "tree"`): each tree level takes two (a node object
/// and its `children` array), so about 63 tree levels; serde_json, which parses tree files,
/// stops at 128 itself.
pub const MAX_TREE_DEPTH: usize = 128;

/// A file nested deeper than its limit.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TooDeep {
    /// The deepest nesting in the file.
    pub depth: usize,
    /// Byte offset of the bracket that first went past the limit.
    pub offset: usize,
    /// The limit.
    pub limit: usize,
}

impl fmt::Display for TooDeep {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "arrays and objects nest {} levels deep (level {} opens at byte {}), more than the limit of {} levels",
            self.depth,
            self.limit + 1,
            self.offset,
            self.limit
        )
    }
}

/// The offset just past the string whose opening quote is at `open` (the end of `bytes` for an
/// unterminated string); escapes are passed over.
fn skip_string(bytes: &[u8], open: usize) -> usize {
    let mut i = open + 1;
    // Jump to the next quote or backslash: most of a JSON file is inside strings.
    while let Some(skip) = bytes.get(i..).and_then(|rest| memchr::memchr2(b'"', b'\\', rest)) {
        if bytes[i + skip] == b'"' {
            return i + skip + 1;
        }
        i += skip + 2;
    }
    bytes.len()
}

/// The bytes outside JSON strings, each with its offset: `"` strings (escapes included) are
/// passed over whole, their quotes included.
fn outside_strings(bytes: &[u8]) -> impl Iterator<Item = (usize, u8)> + '_ {
    let mut i = 0;
    std::iter::from_fn(move || {
        while i < bytes.len() {
            let at = i;
            if bytes[at] != b'"' {
                i += 1;
                return Some((at, bytes[at]));
            }
            i = skip_string(bytes, at);
        }
        None
    })
}

/// What one pass over JSON bytes found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Scanned {
    /// A run of at least 19 digits outside strings that may be a whole integer (not after a `.`,
    /// not before `.`, `e` or `E`): only then can [`quote_wide_integers`] find anything.
    pub long_integer: bool,
}

/// Digits a wide integer has at least (`i64::MIN` has 19 after its sign).
const WIDE_DIGITS: usize = 19;

/// Refuse `bytes` when its arrays and objects nest deeper than `limit`.
pub fn check_depth(bytes: &[u8], limit: usize) -> Result<(), TooDeep> {
    scan(bytes, limit).map(|_| ())
}

/// One tight pass over `bytes` (it runs before every JSON read): refuse nesting deeper than
/// `limit`, and note whether an integer may be too wide for an `i64`.
pub fn scan(bytes: &[u8], limit: usize) -> Result<Scanned, TooDeep> {
    let (mut depth, mut deepest, mut first_past) = (0usize, 0usize, None);
    let mut scanned = Scanned::default();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'"' => {
                i = skip_string(bytes, i);
                continue;
            }
            b'[' | b'{' => {
                depth += 1;
                deepest = deepest.max(depth);
                if depth > limit && first_past.is_none() {
                    first_past = Some(i);
                }
            }
            b']' | b'}' => depth = depth.saturating_sub(1),
            b'0'..=b'9' => {
                let start = i;
                while bytes.get(i).is_some_and(u8::is_ascii_digit) {
                    i += 1;
                }
                let fraction = start > 0 && bytes[start - 1] == b'.';
                let mantissa = matches!(bytes.get(i), Some(b'.' | b'e' | b'E'));
                scanned.long_integer |= i - start >= WIDE_DIGITS && !fraction && !mantissa;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    match first_past {
        Some(offset) => Err(TooDeep { depth: deepest, offset, limit }),
        None => Ok(scanned),
    }
}

/// `bytes` with every integer literal that does not fit a 64-bit signed integer (a `u64` id or
/// hash above 9223372036854775807, or anything longer) put in quotes, so that it is read as the
/// text it was written as instead of failing the read or losing digits as a float. Borrowed when
/// there is none.
pub fn quote_wide_integers(bytes: &[u8]) -> Cow<'_, [u8]> {
    let wide = wide_integers(bytes);
    if wide.is_empty() {
        return Cow::Borrowed(bytes);
    }
    let mut out = Vec::with_capacity(bytes.len() + 2 * wide.len());
    let mut from = 0;
    for (start, end) in wide {
        out.extend_from_slice(&bytes[from..start]);
        out.push(b'"');
        out.extend_from_slice(&bytes[start..end]);
        out.push(b'"');
        from = end;
    }
    out.extend_from_slice(&bytes[from..]);
    Cow::Owned(out)
}

/// Byte ranges of the integer literals outside strings that do not fit an `i64`.
fn wide_integers(bytes: &[u8]) -> Vec<(usize, usize)> {
    let is_number_byte = |b: u8| b.is_ascii_digit() || matches!(b, b'-' | b'+' | b'.' | b'e' | b'E');
    let mut found = Vec::new();
    let mut number: Option<usize> = None;
    let mut previous = None;
    for (at, b) in outside_strings(bytes) {
        // A string just skipped (a jump in the offsets) ends a number too.
        let contiguous = previous == Some(at.wrapping_sub(1));
        previous = Some(at);
        match number {
            Some(_) if contiguous && is_number_byte(b) => continue,
            Some(start) => {
                push_if_wide(bytes, start, at, &mut found);
                number = None;
            }
            None => {}
        }
        if b == b'-' || b.is_ascii_digit() {
            number = Some(at);
        }
    }
    if let Some(start) = number {
        push_if_wide(bytes, start, bytes.len(), &mut found);
    }
    found
}

/// Record `start..end` when it is a whole integer (no fraction or exponent) outside `i64`.
fn push_if_wide(bytes: &[u8], start: usize, end: usize, found: &mut Vec<(usize, usize)>) {
    let literal = &bytes[start..end];
    if literal.len() < WIDE_DIGITS {
        return;
    }
    let digits = literal.strip_prefix(b"-").unwrap_or(literal);
    let whole = !digits.is_empty() && digits.iter().all(u8::is_ascii_digit);
    let fits = std::str::from_utf8(literal).ok().and_then(|s| s.parse::<i64>().ok()).is_some();
    if whole && !fits {
        found.push((start, end));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depth_counts_brackets_outside_strings_only() {
        assert_eq!(check_depth(br#"[{"x": 1}]"#, 2), Ok(()));
        assert_eq!(check_depth(br#"[{"x": "[[[[\"[[[{{{"}]"#, 2), Ok(()));
        let err = check_depth(br#"[{"x": [[1]]}]"#, 3).expect_err("4 deep");
        assert_eq!(err, TooDeep { depth: 4, offset: 8, limit: 3 });
        assert!(err.to_string().contains("nest 4 levels deep (level 4 opens at byte 8)"), "{err}");
    }

    #[test]
    fn depth_is_found_in_records_one_per_line() {
        let mut text = String::from("{\"x\": 1}\n");
        text.push_str(&format!("{{\"y\": {}{}}}\n", "[".repeat(20_000), "]".repeat(20_000)));
        let err = check_depth(text.as_bytes(), MAX_RECORD_DEPTH).expect_err("deep");
        assert_eq!((err.depth, err.offset), (20_001, 9 + 6 + 63));
    }

    #[test]
    fn the_scan_notes_long_integers_outside_strings_only() {
        let long = |text: &[u8]| scan(text, 64).expect("shallow").long_integer;
        assert!(long(br#"[{"id": 18446744073709551615}]"#));
        assert!(long(br#"[{"id": -9223372036854775809}]"#));
        // Fractions, mantissas and digits inside strings are no integers.
        assert!(!long(br#"[{"f": 0.0012345678901234567890, "m": 12345678901234567890e3}]"#));
        assert!(!long(br#"[{"s": "18446744073709551615", "x": 1}]"#));
    }

    #[test]
    fn integers_wider_than_i64_are_quoted() {
        let text =
            br#"[{"id": 18446744073709551615, "x": -1, "big": -9223372036854775809, "ok": 9223372036854775807}]"#;
        let quoted = quote_wide_integers(text);
        assert_eq!(
            std::str::from_utf8(&quoted).expect("utf-8"),
            r#"[{"id": "18446744073709551615", "x": -1, "big": "-9223372036854775809", "ok": 9223372036854775807}]"#
        );
        // Floats, exponents and digits inside strings stay as they are.
        let floats = br#"[{"f": 18446744073709551615.5, "e": 1e30, "s": "18446744073709551615"}]"#;
        assert!(matches!(quote_wide_integers(floats), Cow::Borrowed(_)));
        assert_eq!(&*quote_wide_integers(b"18446744073709551616"), b"\"18446744073709551616\"");
    }
}
