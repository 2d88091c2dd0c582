//! Bounded excerpts of user data in messages: a message quotes at most [`MAX_QUOTED_CHARS`]
//! characters of any one value and lists at most [`MAX_LISTED`] names, however large the cell
//! or however wide the table, so an error about a 500 MB cell or a million columns stays a few
//! lines long.

use std::borrow::Cow;

/// Most characters of one value (a cell, a name, a reader's message) quoted in a message.
pub const MAX_QUOTED_CHARS: usize = 200;

/// Most names (columns, keys, options) listed in a message.
pub const MAX_LISTED: usize = 20;

/// `value` as quoted in a message: whole when it has at most [`MAX_QUOTED_CHARS`] characters,
/// else its start followed by `… (N bytes)`, N the length of the whole value.
pub fn quote(value: &str) -> Cow<'_, str> {
    match value.char_indices().nth(MAX_QUOTED_CHARS) {
        None => Cow::Borrowed(value),
        Some((cut, _)) => Cow::Owned(format!("{}… ({} bytes)", &value[..cut], value.len())),
    }
}

/// A message from another library, which may quote a value of any size somewhere inside it:
/// whole when it has at most twice [`MAX_QUOTED_CHARS`] characters, else its first and last
/// [`MAX_QUOTED_CHARS`] characters around `… (N bytes left out) …`, so both what failed and
/// where (often named at the end) stay.
pub fn message(text: &str) -> Cow<'_, str> {
    let count = text.chars().take(2 * MAX_QUOTED_CHARS + 1).count();
    if count <= 2 * MAX_QUOTED_CHARS {
        return Cow::Borrowed(text);
    }
    let head_end = text.char_indices().nth(MAX_QUOTED_CHARS).map_or(text.len(), |(i, _)| i);
    let tail_start = text.char_indices().rev().nth(MAX_QUOTED_CHARS - 1).map_or(0, |(i, _)| i).max(head_end);
    let left_out = tail_start - head_end;
    Cow::Owned(format!("{} … ({left_out} bytes left out) … {}", &text[..head_end], &text[tail_start..]))
}

/// `names` joined with `, ` (each in backticks when `quoted`, each bounded by [`quote`]): at
/// most [`MAX_LISTED`] of them, then `and N more`.
pub fn list<'a>(names: impl IntoIterator<Item = &'a str>, quoted: bool) -> String {
    let mut shown: Vec<String> = Vec::new();
    let mut more = 0usize;
    for name in names {
        if shown.len() == MAX_LISTED {
            more += 1;
            continue;
        }
        let name = quote(name);
        shown.push(if quoted { format!("`{name}`") } else { name.into_owned() });
    }
    let joined = shown.join(", ");
    if more == 0 { joined } else { format!("{joined} and {more} more") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_values_are_quoted_whole_and_long_ones_cut() {
        assert!(matches!(quote("abc"), Cow::Borrowed("abc")));
        let long = "é".repeat(5000);
        let quoted = quote(&long);
        assert!(quoted.starts_with(&"é".repeat(MAX_QUOTED_CHARS)), "{quoted}");
        assert!(quoted.ends_with("é… (10000 bytes)"), "{quoted}");
        assert_eq!(quoted.chars().count(), MAX_QUOTED_CHARS + "… (10000 bytes)".chars().count());
    }

    #[test]
    fn long_messages_keep_both_ends() {
        let text = format!("could not parse `{}` as dtype i64 at column 'x'", "9".repeat(1_000_000));
        let short = message(&text);
        assert!(short.len() < 1000, "{} bytes", short.len());
        assert!(short.starts_with("could not parse `999"), "{short}");
        assert!(short.ends_with("999` as dtype i64 at column 'x'"), "{short}");
        assert!(short.contains("bytes left out"), "{short}");
        assert!(matches!(message("all of it"), Cow::Borrowed(_)));
    }

    #[test]
    fn lists_stop_after_twenty_names() {
        let names: Vec<String> = (0..100_000).map(|i| format!("c{i}")).collect();
        let listed = list(names.iter().map(String::as_str), true);
        assert!(listed.starts_with("`c0`, `c1`, "), "{listed}");
        assert!(listed.ends_with("`c19` and 99980 more"), "{listed}");
        assert_eq!(list(["a", "b"], false), "a, b");
    }
}
