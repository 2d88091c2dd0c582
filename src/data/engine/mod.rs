//! Sources that live on a query engine (`engine = "sc://HOST:PORT"`, Spark Connect): the
//! engine's address ([`EngineUrl`]), the source's query as Spark SQL ([`sql`]), and running a
//! query there ([`fetch`]), whose answer comes back as one frame. Only what a chart needs comes
//! back: the counted bins of a density view (`data::density::remote`), or the rows of a chart
//! that draws rows.

pub mod source;
pub mod sql;

#[cfg(feature = "spark")]
mod spark;

use std::fmt;
use std::time::Duration;

use polars::prelude::DataFrame;

/// A Spark Connect address: `sc://HOST:PORT` (port 15002 when left out), with the optional
/// parameters Spark's clients take after `/;`: `token=...` (sent as a bearer token) and
/// `user_id=...`. The token may also come from the `DATAINK_ENGINE_TOKEN` environment variable.
#[derive(Clone, PartialEq, Eq)]
pub struct EngineUrl {
    /// Host name or address.
    pub host: String,
    /// TCP port.
    pub port: u16,
    /// Bearer token, if the server asks for one (never printed).
    pub token: Option<String>,
    /// The user the session runs as.
    pub user: String,
}

impl fmt::Debug for EngineUrl {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "EngineUrl({self})")
    }
}

impl fmt::Display for EngineUrl {
    /// The address without its parameters, so a token never reaches a message or a log.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "sc://{}:{}", self.host, self.port)
    }
}

/// The port Spark Connect listens on unless told otherwise.
pub const DEFAULT_PORT: u16 = 15002;

impl EngineUrl {
    /// Read an engine address; the error says what is wrong with it.
    pub fn parse(text: &str) -> Result<EngineUrl, String> {
        let rest = match text.split_once("://") {
            Some(("sc", rest)) => rest,
            Some(("df", _)) => {
                return Err(format!(
                    "`{text}`: Ballista (`df://`) is not supported; dataink talks to Spark Connect servers (`sc://HOST:PORT`)"
                ));
            }
            _ => return Err(format!("`{text}` is not an engine address; write `sc://HOST:PORT` (Spark Connect)")),
        };
        let (address, params) = rest.split_once('/').unwrap_or((rest, ""));
        let (host, port) = match address.rsplit_once(':') {
            Some((host, port)) => {
                let port = port.parse::<u16>().map_err(|_| format!("`{text}`: `{port}` is not a port number"))?;
                (host, port)
            }
            None => (address, DEFAULT_PORT),
        };
        if host.is_empty() {
            return Err(format!("`{text}` names no host; write `sc://HOST:PORT`"));
        }
        let mut url = EngineUrl { host: host.to_string(), port, token: None, user: "dataink".to_string() };
        for param in params.trim_start_matches(';').split(';').filter(|p| !p.is_empty()) {
            let (key, value) = param.split_once('=').unwrap_or((param, ""));
            match key {
                "token" => url.token = Some(value.to_string()),
                "user_id" => url.user = value.to_string(),
                "use_ssl" if value == "false" => {}
                "use_ssl" => return Err(format!("`{url}`: TLS (`use_ssl=true`) is not supported yet")),
                "session_id" | "user_agent" => {}
                other => {
                    return Err(format!("`{url}`: unknown parameter `{other}`; known: token, user_id, use_ssl"));
                }
            }
        }
        if url.token.is_none() {
            url.token = std::env::var("DATAINK_ENGINE_TOKEN").ok().filter(|t| !t.is_empty());
        }
        Ok(url)
    }
}

/// A query that failed on an engine: which engine, which query, and what went wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct EngineError {
    /// The engine's address (without parameters).
    pub engine: String,
    /// The query sent.
    pub query: String,
    /// What went wrong.
    pub message: String,
}

impl EngineError {
    /// The error of `query` on `url`.
    pub fn new(url: &EngineUrl, query: &str, message: String) -> EngineError {
        EngineError { engine: url.to_string(), query: query.to_string(), message }
    }
}

/// Longest stretch of a query quoted in an error.
const QUOTED_QUERY: usize = 240;

impl fmt::Display for EngineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut shown: String = self.query.chars().take(QUOTED_QUERY).collect();
        if shown.len() < self.query.len() {
            shown.push_str(" …");
        }
        write!(f, "engine {}: {} (query: {shown})", self.engine, self.message)
    }
}

/// Most rows fetched from an engine for a chart that draws rows.
pub const MAX_FETCHED_ROWS: usize = 10_000_000;

/// How long a query may take, unless the source says (`timeout`).
pub const DEFAULT_TIMEOUT: Duration = Duration::from_secs(600);

/// Run `query` on the engine at `url` within `timeout`; its answer as one frame.
pub fn fetch(url: &EngineUrl, query: &str, timeout: Duration) -> Result<DataFrame, EngineError> {
    #[cfg(feature = "spark")]
    {
        spark::run(url, query, timeout)
    }
    #[cfg(not(feature = "spark"))]
    {
        let _ = timeout;
        Err(EngineError::new(
            url,
            query,
            "this dataink was built without Spark Connect; build it with `--features spark`".to_string(),
        ))
    }
}

/// A source's query on an engine.
#[derive(Clone, Debug)]
pub struct EngineQuery {
    /// Where it runs.
    pub url: EngineUrl,
    /// The source's rows, as Spark SQL.
    pub query: String,
    /// How long one query may take.
    pub timeout: Duration,
}

impl EngineQuery {
    /// Run `sql` (which reads `self.query`) on the engine; the error names engine and query.
    pub fn run(&self, sql: &str) -> Result<DataFrame, String> {
        let label: String = sql.chars().take(60).collect();
        crate::timing::timed(&format!("engine query `{label}…`"), || fetch(&self.url, sql, self.timeout))
            .map_err(|e| e.to_string())
    }

    /// The query's columns, with no rows.
    pub fn columns(&self) -> Result<DataFrame, String> {
        self.run(&format!("SELECT * FROM ({}) AS rows LIMIT 0", self.query))
    }

    /// How many rows the query yields.
    pub fn rows(&self) -> Result<u64, String> {
        let df = self.run(&format!("SELECT count(*) AS n FROM ({}) AS rows", self.query))?;
        df.column("n")
            .ok()
            .and_then(|c| c.get(0).ok())
            .and_then(|v| v.extract::<u64>())
            .ok_or_else(|| format!("engine {}: the row count came back unreadable (query: {})", self.url, self.query))
    }

    /// The query's rows, only the columns `wanted` (all when `None`), at most `limit` of them:
    /// more is an error that says how to aggregate on the engine instead.
    pub fn rows_of(&self, wanted: Option<&[String]>, limit: usize) -> Result<DataFrame, String> {
        let columns = match wanted {
            Some(names) if !names.is_empty() => names.iter().map(|n| sql::ident(n)).collect::<Vec<_>>().join(", "),
            _ => "*".to_string(),
        };
        let rows = self.run(&format!("SELECT {columns} FROM ({}) AS rows LIMIT {}", self.query, limit + 1))?;
        if rows.height() > limit {
            return Err(format!(
                "engine {}: the query yields more than {limit} rows, and a chart that draws rows needs them all here; \
                 draw a density scatter (`mode = \"density\"`), whose bins are counted on the engine, or aggregate in a `sql` step",
                self.url
            ));
        }
        Ok(rows)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn addresses_parse_with_their_parameters_and_hide_the_token() {
        let url = EngineUrl::parse("sc://10.0.0.5:443/;token=s3cret;user_id=ana").unwrap();
        assert_eq!(
            (url.host.as_str(), url.port, url.token.as_deref(), url.user.as_str()),
            ("10.0.0.5", 443, Some("s3cret"), "ana")
        );
        assert_eq!(url.to_string(), "sc://10.0.0.5:443");
        assert!(!format!("{url:?}").contains("s3cret"));
        assert_eq!(EngineUrl::parse("sc://spark").unwrap().port, DEFAULT_PORT);
        assert!(EngineUrl::parse("df://h:50050").unwrap_err().contains("Ballista"));
        assert!(EngineUrl::parse("http://h").unwrap_err().contains("sc://HOST:PORT"));
        assert!(EngineUrl::parse("sc://h:99999").unwrap_err().contains("port"));
        assert!(EngineUrl::parse("sc://h/;use_ssl=true").unwrap_err().contains("TLS"));
        assert!(EngineUrl::parse("sc://h/;tokn=1").unwrap_err().contains("unknown parameter `tokn`"));
    }

    #[test]
    fn errors_name_the_engine_and_the_query() {
        let url = EngineUrl::parse("sc://h:1/;token=t").unwrap();
        let e = EngineError::new(&url, "SELECT 1", "boom".into());
        assert_eq!(e.to_string(), "engine sc://h:1: boom (query: SELECT 1)");
        let long = "x".repeat(1000);
        assert!(EngineError::new(&url, &long, "m".into()).to_string().ends_with(" …)"));
    }

    #[test]
    fn a_closed_port_is_refused_by_name() {
        let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        let port = listener.local_addr().unwrap().port();
        drop(listener);
        let url = EngineUrl::parse(&format!("sc://127.0.0.1:{port}")).unwrap();
        let err = fetch(&url, "SELECT 1", Duration::from_secs(20)).unwrap_err().to_string();
        assert!(err.contains(&format!("engine sc://127.0.0.1:{port}")) && err.contains("SELECT 1"), "{err}");
        assert!(err.to_lowercase().contains("refused") || err.contains("cannot connect"), "{err}");
    }
}
