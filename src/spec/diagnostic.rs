//! Diagnostics: problems found in a spec, with a place in the file, rendered like rustc or typst.
//!
//! ```text
//! error: unknown key `colour` in chart "iris-scatter"
//!   --> examples/gallery.toml:12:1
//!    |
//! 12 | colour = "species"
//!    | ^^^^^^ did you mean `color`?
//!    = hint: keys allowed here: name, data, kind, x, y, caption, color, ...
//! ```

use std::fmt;
use std::ops::Range;
use std::path::PathBuf;

use serde::Serialize;

/// How bad a problem is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    /// The spec cannot be used.
    Error,
    /// The spec works, but probably not as meant.
    Warning,
}

impl fmt::Display for Severity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
        })
    }
}

/// One problem in a spec: what is wrong, where, and how to fix it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// What is wrong, in one line.
    pub message: String,
    /// Byte offsets of the offending text in the spec, if it has a place.
    pub span: Option<Range<usize>>,
    /// Short text printed after the carets.
    pub label: Option<String>,
    /// How to fix it.
    pub hint: Option<String>,
}

impl Diagnostic {
    /// A new error with a message and nothing else.
    pub fn error(message: impl Into<String>) -> Self {
        Self::new(Severity::Error, message.into())
    }

    /// A new warning with a message and nothing else.
    pub fn warning(message: impl Into<String>) -> Self {
        Self::new(Severity::Warning, message.into())
    }

    fn new(severity: Severity, message: String) -> Self {
        Self { severity, message, span: None, label: None, hint: None }
    }

    /// Points the diagnostic at a byte range of the spec text.
    pub fn at(mut self, span: Range<usize>) -> Self {
        self.span = Some(span);
        self
    }

    /// Points the diagnostic at a byte range when there is one.
    pub fn at_opt(mut self, span: Option<Range<usize>>) -> Self {
        self.span = span;
        self
    }

    /// Adds the short text printed after the carets.
    pub fn with_label(mut self, label: impl Into<String>) -> Self {
        self.label = Some(label.into());
        self
    }

    /// Adds a hint on how to fix the problem.
    pub fn with_hint(mut self, hint: impl Into<String>) -> Self {
        self.hint = Some(hint.into());
        self
    }

    /// Whether this is an error (not a warning).
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

impl fmt::Display for Diagnostic {
    /// One line: `error: message`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.severity, sanitize(&self.message))
    }
}

/// A spec file's name and text; diagnostics' spans are byte offsets into `text`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SourceFile {
    /// Where the text came from (shown in `-->` lines).
    pub path: PathBuf,
    /// The whole file.
    pub text: String,
}

/// Columns a tab advances in rendered source lines.
const TAB_WIDTH: usize = 4;

impl SourceFile {
    /// A source from a path (only shown, never read) and its text.
    pub fn new(path: impl Into<PathBuf>, text: impl Into<String>) -> Self {
        Self { path: path.into(), text: text.into() }
    }

    /// Reads a spec file; fails when it cannot be read or is not UTF-8.
    pub fn read(path: impl Into<PathBuf>) -> std::io::Result<Self> {
        let path = path.into();
        let text = std::fs::read_to_string(&path)?;
        Ok(Self { path, text })
    }

    /// 1-based line and column of a byte offset; the column counts characters, not bytes.
    ///
    /// Offsets past the end are clamped to the end; offsets inside a character count from its start.
    /// This scans the text before `offset`; to place many offsets, build a [`LineIndex`] once.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        self.line_col_in(&LineIndex::new(self.text.get(..self.floor_boundary(offset)).unwrap_or("")), offset)
    }

    /// [`SourceFile::line_col`] with a line index of this text (or of a prefix holding `offset`).
    fn line_col_in(&self, index: &LineIndex, offset: usize) -> (usize, usize) {
        let offset = self.floor_boundary(offset);
        let line = index.line_of(offset);
        let line_start = index.starts[line];
        let col = self.text.get(line_start..offset).unwrap_or("").chars().filter(|&c| c != '\u{feff}').count() + 1;
        (line + 1, col)
    }

    /// The largest char boundary at or before `offset`, clamped to the text.
    fn floor_boundary(&self, offset: usize) -> usize {
        let mut offset = offset.min(self.text.len());
        while offset > 0 && !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        offset
    }

    /// Byte range of the line holding `offset`, without its line break.
    fn line_bounds(&self, offset: usize) -> Range<usize> {
        let offset = self.floor_boundary(offset);
        let start = self.text.get(..offset).and_then(|s| s.rfind('\n')).map_or(0, |i| i + 1);
        let end = self.text.get(offset..).and_then(|s| s.find('\n')).map_or(self.text.len(), |i| offset + i);
        let line = self.text.get(start..end).unwrap_or("");
        let end = if line.ends_with('\r') { end - 1 } else { end };
        start..end
    }

    /// Renders one diagnostic: header, `-->` location, the source line, carets, label and hint.
    /// To render many, use [`render_all`], which indexes the lines once.
    pub fn render(&self, diag: &Diagnostic) -> String {
        let end = diag.span.as_ref().map_or(0, |s| self.floor_boundary(s.start));
        self.render_in(&LineIndex::new(self.text.get(..end).unwrap_or("")), diag)
    }

    /// [`SourceFile::render`] with a line index of this text (or of a prefix holding the span start).
    fn render_in(&self, index: &LineIndex, diag: &Diagnostic) -> String {
        let mut out = format!("{}: {}\n", diag.severity, sanitize(&diag.message));
        let mut gutter = 1;
        if let Some(span) = &diag.span {
            let (line, col) = self.line_col_in(index, span.start);
            gutter = line.to_string().len();
            let pad = " ".repeat(gutter);
            out.push_str(&format!("{pad}--> {}:{line}:{col}\n", self.path.display()));
            out.push_str(&format!("{pad} |\n"));

            let bounds = self.line_bounds(span.start);
            // A span may start on a line's `\r`, outside the shown bounds: keep it inside.
            let start = self.floor_boundary(span.start).max(bounds.start).min(bounds.end);
            let end = self.floor_boundary(span.end).min(bounds.end).max(start);
            let before = self.text.get(bounds.start..start).unwrap_or("");
            let marked = self.text.get(start..end).unwrap_or("");
            let after = self.text.get(end..bounds.end).unwrap_or("");
            let (before_shown, before_width) = show_line(before);
            let (marked_shown, marked_width) = show_line(marked);
            let (after_shown, _) = show_line(after);
            let shown = format!("{before_shown}{marked_shown}{after_shown}");
            out.push_str(format!("{line:>gutter$} | {shown}").trim_end());
            out.push('\n');
            let carets = "^".repeat(marked_width.max(1));
            let mut mark_line = format!("{pad} | {}{carets}", " ".repeat(before_width));
            if let Some(label) = &diag.label {
                mark_line.push(' ');
                mark_line.push_str(&sanitize(label));
            }
            out.push_str(&mark_line);
            out.push('\n');
        }
        if let Some(hint) = &diag.hint {
            let pad = " ".repeat(gutter);
            let mut lines = hint.split('\n');
            out.push_str(&format!("{pad} = hint: {}\n", sanitize(lines.next().unwrap_or(""))));
            for more in lines {
                out.push_str(&format!("{pad}         {}\n", sanitize(more)));
            }
        }
        out
    }
}

/// Renders many diagnostics, separated by blank lines.
pub fn render_all(source: &SourceFile, diags: &[Diagnostic]) -> String {
    let index = LineIndex::new(&source.text);
    diags.iter().map(|d| source.render_in(&index, d)).collect::<Vec<_>>().join("\n")
}

/// Byte offsets where the lines of a text start, built in one pass, so that each offset is placed
/// by binary search instead of a scan from the start of the file.
#[derive(Clone, Debug)]
pub struct LineIndex {
    /// Start of every line; the first is 0.
    starts: Vec<usize>,
}

impl LineIndex {
    /// Indexes the line starts of `text`.
    pub fn new(text: &str) -> Self {
        let starts = std::iter::once(0).chain(text.match_indices('\n').map(|(i, _)| i + 1)).collect();
        Self { starts }
    }

    /// 0-based line holding byte `offset` (offsets past the end fall on the last line).
    pub fn line_of(&self, offset: usize) -> usize {
        self.starts.partition_point(|&s| s <= offset).saturating_sub(1)
    }
}

/// Replaces characters that would garble a terminal (controls, bidi overrides) with `\u{..}` escapes.
fn sanitize(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c == '\t' {
            out.push(' ');
        } else if is_unsafe(c) {
            out.extend(c.escape_unicode());
        } else {
            out.push(c);
        }
    }
    out
}

/// Characters never printed as they are: the hidden characters of [`crate::visible`] (controls,
/// bidirectional formatting) except tab, which callers expand.
fn is_unsafe(c: char) -> bool {
    c != '\t' && crate::visible::is_hidden(c)
}

/// A piece of a source line as printed (tabs expanded, unsafe characters replaced) and its width
/// in terminal columns.
fn show_line(text: &str) -> (String, usize) {
    let mut out = String::with_capacity(text.len());
    let mut width = 0;
    for c in text.chars() {
        if c == '\t' {
            out.push_str(&" ".repeat(TAB_WIDTH));
            width += TAB_WIDTH;
        } else if is_unsafe(c) {
            out.push('\u{fffd}');
            width += 1;
        } else if c == '\u{feff}' {
            // A byte-order mark: invisible, not shown.
        } else {
            out.push(c);
            width += char_width(c);
        }
    }
    (out, width)
}

/// Terminal columns a printable character takes: 0 for combining marks, 2 for wide East Asian
/// characters and emoji, else 1.
fn char_width(c: char) -> usize {
    let u = u32::from(c);
    let zero = matches!(u,
        0x0300..=0x036f | 0x0483..=0x0489 | 0x0591..=0x05bd | 0x0610..=0x061a | 0x064b..=0x065f
        | 0x0e31 | 0x0e34..=0x0e3a | 0x1ab0..=0x1aff | 0x1dc0..=0x1dff | 0x200b..=0x200f
        | 0x20d0..=0x20ff | 0xfe00..=0xfe0f | 0xfe20..=0xfe2f | 0xfeff | 0xe0100..=0xe01ef);
    if zero {
        return 0;
    }
    let wide = matches!(u,
        0x1100..=0x115f | 0x231a..=0x231b | 0x2329..=0x232a | 0x23e9..=0x23ec | 0x23f0 | 0x23f3
        | 0x25fd..=0x25fe | 0x2614..=0x2615 | 0x2648..=0x2653 | 0x267f | 0x2693 | 0x26a1
        | 0x26aa..=0x26ab | 0x26bd..=0x26be | 0x26c4..=0x26c5 | 0x26ce | 0x26d4 | 0x26ea
        | 0x26f2..=0x26f3 | 0x26f5 | 0x26fa | 0x26fd | 0x2705 | 0x270a..=0x270b | 0x2728 | 0x274c
        | 0x274e | 0x2753..=0x2755 | 0x2757 | 0x2795..=0x2797 | 0x27b0 | 0x27bf | 0x2b1b..=0x2b1c
        | 0x2b50 | 0x2b55 | 0x2e80..=0x303e | 0x3041..=0x33ff | 0x3400..=0x4dbf | 0x4e00..=0x9fff
        | 0xa000..=0xa4cf | 0xa960..=0xa97f | 0xac00..=0xd7a3 | 0xf900..=0xfaff | 0xfe10..=0xfe19
        | 0xfe30..=0xfe6f | 0xff00..=0xff60 | 0xffe0..=0xffe6 | 0x16fe0..=0x16fe4 | 0x17000..=0x18cff
        | 0x1b000..=0x1b2ff | 0x1f004 | 0x1f0cf | 0x1f18e | 0x1f191..=0x1f19a | 0x1f200..=0x1f251
        | 0x1f300..=0x1f64f | 0x1f680..=0x1f6ff | 0x1f7e0..=0x1f7eb | 0x1f90c..=0x1f9ff
        | 0x1fa70..=0x1faff | 0x20000..=0x2fffd | 0x30000..=0x3fffd);
    if wide { 2 } else { 1 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn src(text: &str) -> SourceFile {
        SourceFile::new("spec.toml", text)
    }

    #[test]
    fn line_col_counts_chars_and_clamps() {
        let s = src("a = 1\näö = 2\n");
        assert_eq!(s.line_col(0), (1, 1));
        assert_eq!(s.line_col(6), (2, 1));
        // `=` after two two-byte characters and a space.
        assert_eq!(s.line_col(11), (2, 4));
        // Inside a character, and past the end.
        assert_eq!(s.line_col(7), (2, 1));
        assert_eq!(s.line_col(999), (3, 1));
    }

    #[test]
    fn renders_carets_under_the_span() {
        let s = src("title = \"x\"\ncolour = \"species\"\n");
        let d = Diagnostic::error("unknown key `colour`")
            .at(12..18)
            .with_label("did you mean `color`?")
            .with_hint("keys allowed here: color");
        assert_eq!(
            s.render(&d),
            "error: unknown key `colour`\n --> spec.toml:2:1\n  |\n2 | colour = \"species\"\n  | ^^^^^^ did you mean `color`?\n  = hint: keys allowed here: color\n"
        );
    }

    #[test]
    fn tabs_and_wide_chars_line_up() {
        let s = src("\t名前 = 1\n");
        let d = Diagnostic::error("bad").at(8..9); // the `=`
        let out = s.render(&d);
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines.get(3), Some(&"1 |     名前 = 1"));
        // 4 columns for the tab, 4 for the two wide characters, 1 for the space.
        assert_eq!(lines.get(4), Some(&"  |          ^"));
        assert_eq!(lines.get(1), Some(&" --> spec.toml:1:5"));
    }

    #[test]
    fn multi_line_span_underlines_first_line_only() {
        let s = src("x = [\n  1,\n]\n");
        let out = s.render(&Diagnostic::warning("w").at(4..12));
        assert!(out.contains("1 | x = [\n  |     ^\n"), "{out}");
        assert!(out.starts_with("warning: w\n"));
    }

    #[test]
    fn no_span_prints_header_and_hint() {
        let s = src("");
        let d = Diagnostic::error("the spec has no charts").with_hint("add one");
        assert_eq!(s.render(&d), "error: the spec has no charts\n  = hint: add one\n");
        assert_eq!(d.to_string(), "error: the spec has no charts");
    }

    #[test]
    fn odd_spans_never_panic() {
        let s = src("é\r\nb\t\u{1b}[31m");
        for start in 0..12 {
            for end in 0..12 {
                let _ = s.render(&Diagnostic::error("m\u{1b}").at(start..end).with_label("l"));
            }
        }
        let out = s.render(&Diagnostic::error("m").at(4..5));
        assert!(!out.contains('\u{1b}'));
        assert!(!out.contains('\r'));
        let empty = src("");
        assert!(empty.render(&Diagnostic::error("e").at(0..0)).contains("1 |\n  | ^\n"));
    }

    #[test]
    fn serializes_to_json() {
        let d = Diagnostic::error("bad").at(1..3).with_hint("h");
        let v = serde_json::to_value(&d).unwrap_or_default();
        assert_eq!(v["severity"], "error");
        assert_eq!(v["span"]["start"], 1);
        assert_eq!(v["label"], serde_json::Value::Null);
    }
}
