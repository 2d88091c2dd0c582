//! "Did you mean" suggestions for misspelt keys and values.

/// Smallest similarity (0..=1) for a candidate to be suggested.
const THRESHOLD: f64 = 0.8;

/// The candidate closest to `input`, if one is close enough to be a likely typo.
///
/// Case and `-`/`_` differences count as exact matches (`Font-Size` → `font_size`); otherwise the
/// Jaro–Winkler similarity must reach 0.8, or (for inputs of 3+ characters) one edit or swap apart.
/// Ties go to the earlier candidate.
pub fn did_you_mean<'a, I>(input: &str, candidates: I) -> Option<&'a str>
where
    I: IntoIterator<Item = &'a str>,
{
    let mut best: Option<(f64, &'a str)> = None;
    for candidate in candidates {
        if candidate == input {
            continue;
        }
        let score = similarity(input, candidate);
        if score >= THRESHOLD && best.is_none_or(|(b, _)| score > b) {
            best = Some((score, candidate));
        }
    }
    best.map(|(_, c)| c)
}

/// A hint listing what exists, led by a "did you mean" when one name is close to `wanted`:
/// "did you mean `b`? columns: `a`, `b`" (names in backticks when `quoted`; at most
/// [`crate::excerpt::MAX_LISTED`] of them, each cut like any quoted value).
pub fn hint(wanted: &str, names: &[&str], label: &str, quoted: bool) -> String {
    let listing = crate::excerpt::list(names.iter().copied(), quoted);
    match did_you_mean(wanted, names.iter().copied()) {
        Some(best) => format!("did you mean `{}`? {label}: {listing}", crate::excerpt::quote(best)),
        None => format!("{label}: {listing}"),
    }
}

/// How alike two names are, 0..=1, ignoring case and `-`/`_` differences.
///
/// Exact matches after normalising score 1; one edit or swap apart in names of 3+ characters scores
/// at least 0.8.
pub fn similarity(a: &str, b: &str) -> f64 {
    let a = normalize(a);
    let b = normalize(b);
    if a == b {
        return 1.0;
    }
    let jw = strsim::jaro_winkler(&a, &b);
    let short = a.chars().count().min(b.chars().count());
    if short >= 3 && strsim::damerau_levenshtein(&a, &b) <= 1 { jw.max(THRESHOLD) } else { jw }
}

fn normalize(s: &str) -> String {
    s.chars().map(|c| if c == '-' { '_' } else { c }).flat_map(char::to_lowercase).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggests_typos_and_case_and_dashes() {
        let keys = ["name", "data", "color", "font_size", "size", "title"];
        assert_eq!(did_you_mean("colour", keys), Some("color"));
        assert_eq!(did_you_mean("Color", keys), Some("color"));
        assert_eq!(did_you_mean("font-size", keys), Some("font_size"));
        assert_eq!(did_you_mean("ttile", keys), Some("title"));
        assert_eq!(did_you_mean("nmae", keys), Some("name"));
        assert_eq!(did_you_mean("logarithmic", ["linear", "log", "time", "band"]), Some("log"));
        assert_eq!(did_you_mean("scater", ["scatter", "line"]), Some("scatter"));
    }

    #[test]
    fn no_suggestion_for_unrelated_words() {
        let keys = ["name", "data", "color", "font_size", "size", "title"];
        assert_eq!(did_you_mean("zebra", keys), None);
        assert_eq!(did_you_mean("q", ["x", "y"]), None);
        assert_eq!(did_you_mean("", keys), None);
        assert_eq!(did_you_mean("größe", keys), None);
        assert_eq!(did_you_mean("name", keys), None, "an exact match is not a suggestion");
    }
}
