//! User text as it may be shown: the one rule every output (SVG, PNG, the HTML report, the
//! Markdown summary) applies to chart titles, names, descriptions, column names, categories and
//! messages before writing them.
//!
//! Hidden characters are removed, not shown as escapes: control characters (C0 other than tab
//! and line feed, DEL, C1), the non-characters U+FFFE and U+FFFF (not allowed in XML), and every
//! character with the Unicode `Bidi_Control` property (the embeddings and overrides
//! U+202A–U+202E, the isolates U+2066–U+2069, and the marks U+200E, U+200F and U+061C), which
//! could reorder what a reader sees. Nothing dataink draws needs them: text is laid out left to
//! right without bidi reordering (see [`crate::text`]).

use std::borrow::Cow;

/// Whether `c` is never written as it is: a control character (tab, line feed and carriage
/// return included: callers decide what a line break becomes), U+FFFE, U+FFFF or a bidi control.
pub fn is_hidden(c: char) -> bool {
    c.is_control() || matches!(c, '\u{FFFE}' | '\u{FFFF}') || is_bidi_control(c)
}

/// Whether `c` has the Unicode `Bidi_Control` property.
fn is_bidi_control(c: char) -> bool {
    matches!(c, '\u{061C}' | '\u{200E}' | '\u{200F}' | '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}')
}

/// `text` for one line of drawn text: tab, line feed and carriage return become a space each,
/// other hidden characters are removed. Borrowed when nothing changes.
pub fn single_line(text: &str) -> Cow<'_, str> {
    if !text.chars().any(is_hidden) {
        return Cow::Borrowed(text);
    }
    Cow::Owned(single_line_chars(text).collect())
}

/// The characters of [`single_line`]`(text)`, without collecting them.
pub fn single_line_chars(text: &str) -> impl Iterator<Item = char> + '_ {
    text.chars().filter_map(|c| match c {
        '\t' | '\n' | '\r' => Some(' '),
        c if is_hidden(c) => None,
        c => Some(c),
    })
}

/// `text` for a page (report HTML and Markdown): tab and line feed are kept, a carriage return
/// (alone or before a line feed) becomes one line feed, other hidden characters are removed.
/// Borrowed when nothing changes.
pub fn multiline(text: &str) -> Cow<'_, str> {
    if !text.chars().any(|c| is_hidden(c) && !matches!(c, '\t' | '\n')) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\t' | '\n' => out.push(c),
            '\r' => {
                chars.next_if_eq(&'\n');
                out.push('\n');
            }
            c if is_hidden(c) => {}
            c => out.push(c),
        }
    }
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const HOSTILE: &str = "a\u{0}\u{7}\u{1b}[31mb\u{202e}c\u{2066}d\u{200f}e\u{85}f\u{7f}g\u{FFFF}";

    #[test]
    fn single_line_drops_controls_and_bidi() {
        assert_eq!(single_line(HOSTILE), "a[31mbcdefg");
        assert_eq!(single_line("a\nb\tc\r"), "a b c ");
        assert!(matches!(single_line("plain text"), Cow::Borrowed(_)));
    }

    #[test]
    fn multiline_keeps_tabs_and_line_feeds() {
        assert_eq!(multiline(HOSTILE), "a[31mbcdefg");
        assert_eq!(multiline("a\r\nb\rc\n\td"), "a\nb\nc\n\td");
        assert!(matches!(multiline("x\ty\nz"), Cow::Borrowed(_)));
    }

    #[test]
    fn right_to_left_letters_stay() {
        // Only the invisible controls go; Hebrew and Arabic text itself is kept.
        assert_eq!(single_line("שלום \u{202b}مرحبا"), "שלום مرحبا");
    }
}
