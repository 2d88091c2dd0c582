//! Parsing of ISO 8601 dates and date-times written as text (JSON and inline data).

use chrono::{DateTime, NaiveDate, NaiveDateTime};

/// Milliseconds since the Unix epoch (UTC) of an ISO 8601 date (`2024-03-05`), date-time
/// (`2024-03-05T14:30:00`, `2024-03-05 14:30`) or RFC 3339 instant with offset; `None` otherwise.
/// Date-times without an offset are read as UTC. `/` may stand for `-` in the date
/// (`2012/01/31`).
///
/// CSV date columns are read as text and converted here (per distinct value), which is much
/// faster than asking the CSV reader to try date parsing on every column.
pub fn parse_iso(text: &str) -> Option<f64> {
    let trimmed = text.trim();
    let slashed;
    let s = if trimmed.as_bytes().get(4) == Some(&b'/') && trimmed.as_bytes().get(7) == Some(&b'/') {
        slashed = format!("{}-{}-{}", &trimmed[..4], &trimmed[5..7], &trimmed[8..]);
        slashed.as_str()
    } else {
        trimmed
    };
    if s.len() < 10 || s.as_bytes().get(4).is_none_or(|&b| b != b'-') {
        return None;
    }
    if let Ok(dt) = DateTime::parse_from_rfc3339(s) {
        return Some(dt.timestamp_millis() as f64);
    }
    for format in ["%Y-%m-%dT%H:%M:%S%.f", "%Y-%m-%d %H:%M:%S%.f", "%Y-%m-%dT%H:%M", "%Y-%m-%d %H:%M"] {
        if let Ok(dt) = NaiveDateTime::parse_from_str(s, format) {
            return Some(dt.and_utc().timestamp_millis() as f64);
        }
    }
    let date = NaiveDate::parse_from_str(s, "%Y-%m-%d").ok()?;
    Some(date.and_hms_opt(0, 0, 0)?.and_utc().timestamp_millis() as f64)
}

#[cfg(test)]
mod tests {
    use super::parse_iso;

    #[test]
    fn iso_forms_parse_to_utc_milliseconds() {
        assert_eq!(parse_iso("1970-01-02"), Some(86_400_000.0));
        assert_eq!(parse_iso("1970/01/02"), Some(86_400_000.0));
        assert_eq!(parse_iso("1970/01/02 00:00:01"), Some(86_401_000.0));
        assert_eq!(parse_iso("1970-01-01T00:00:01"), Some(1000.0));
        assert_eq!(parse_iso("1970-01-01 00:01"), Some(60_000.0));
        assert_eq!(parse_iso("1970-01-01T01:00:00+01:00"), Some(0.0));
        assert_eq!(parse_iso("2024-02-30"), None);
        assert_eq!(parse_iso("setosa"), None);
        assert_eq!(parse_iso("12"), None);
    }
}
