//! A server on a loopback address answers only requests naming it by a loopback name: a web page
//! whose domain is made to resolve to 127.0.0.1 (DNS rebinding) sends its own domain in `Host`
//! and is refused, so it cannot read what the server reads.

use axum::extract::{Request, State};
use axum::http::{StatusCode, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use super::reply::Problem;

/// Which `Host` headers a server accepts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HostCheck {
    /// Only `localhost`, `127.0.0.1` (any 127.x.y.z) and `[::1]`, with any port: for a server
    /// bound to a loopback address.
    Loopback,
    /// Any: for a server bound where others reach it by their own names.
    Any,
}

/// Whether `host` (a `Host` header's value) names this machine's loopback interface.
pub fn is_loopback_name(host: &str) -> bool {
    let name = match host.strip_prefix('[') {
        Some(rest) => rest.split(']').next().unwrap_or(""),
        None => host
            .rsplit_once(':')
            .map_or(host, |(name, port)| if port.chars().all(|c| c.is_ascii_digit()) { name } else { host }),
    };
    let name = name.trim_end_matches('.').to_ascii_lowercase();
    name == "localhost"
        || name.ends_with(".localhost")
        || name.parse::<std::net::IpAddr>().is_ok_and(|ip| ip.is_loopback())
}

/// Refuse a request whose `Host` is not a loopback name, under [`HostCheck::Loopback`]. A request
/// without `Host` (not one a browser sends) passes.
pub async fn check(State(check): State<HostCheck>, request: Request, next: Next) -> Response {
    if check == HostCheck::Loopback
        && let Some(host) = request.headers().get(header::HOST)
        && !host.to_str().is_ok_and(is_loopback_name)
    {
        return Problem::new(
            StatusCode::FORBIDDEN,
            "this server answers only requests to localhost, 127.0.0.1 or [::1]; bind it elsewhere with --addr to serve other names",
        )
        .into_response();
    }
    next.run(request).await
}

#[cfg(test)]
mod tests {
    use super::is_loopback_name;

    #[test]
    fn loopback_names_with_any_port_pass_and_other_names_do_not() {
        for host in [
            "localhost",
            "localhost:8700",
            "127.0.0.1:8700",
            "127.1.2.3",
            "[::1]:8700",
            "[::1]",
            "LOCALHOST.",
            "a.localhost:1",
        ] {
            assert!(is_loopback_name(host), "{host}");
        }
        for host in
            ["evil.example:8700", "10.0.0.1", "localhost.evil.example", "[::2]:80", "127.0.0.1.evil.example", ""]
        {
            assert!(!is_loopback_name(host), "{host}");
        }
    }
}
