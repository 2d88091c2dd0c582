//! A bounded load test of `dataink serve` on loopback: the server in this process on
//! 127.0.0.1, CLIENTS concurrent clients (200 by default) each sending REQUESTS requests
//! (10 by default) over one keep-alive connection, and the latency of every request.
//!
//! Two rounds: every client asking for the same small chart (answered from the cache after the
//! first), and every request a different chart (its title carries the client and request
//! number, so each is drawn and rendered). Prints p50, p90, p99, max, errors and requests per
//! second for each.
//!
//!   cargo bench --bench serve_load
//!   CLIENTS=50 REQUESTS=20 cargo bench --bench serve_load

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use dataink::serve::{Limits, Server, run};
use tokio::io::{AsyncBufReadExt, AsyncReadExt, AsyncWriteExt, BufReader};
use tokio::net::TcpStream;

const CSV: &str = "a,b\n1,2\n2,4\n3,5\n4,3\n5,6\n6,5\n7,8\n8,7\n";

fn spec(title: &str) -> String {
    format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"pts\"\nkind = \"scatter\"\ndata = \"d\"\n\
         title = \"{title}\"\nsize = [320, 240]\nx = \"a\"\ny = \"b\"\n"
    )
}

fn env(name: &str, default: usize) -> usize {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// One response read from `reader`: its status, or an error.
async fn response(reader: &mut BufReader<TcpStream>) -> std::io::Result<u16> {
    let mut line = String::new();
    reader.read_line(&mut line).await?;
    let status: u16 =
        line.split(' ').nth(1).and_then(|s| s.parse().ok()).ok_or_else(|| std::io::Error::other(line.clone()))?;
    let mut length = 0usize;
    loop {
        let mut header = String::new();
        reader.read_line(&mut header).await?;
        let header = header.trim_end();
        if header.is_empty() {
            break;
        }
        if let Some((name, value)) = header.split_once(':')
            && name.eq_ignore_ascii_case("content-length")
        {
            length = value.trim().parse().unwrap_or(0);
        }
    }
    let mut body = vec![0; length];
    reader.read_exact(&mut body).await?;
    Ok(status)
}

/// `requests` requests from one client over one connection; the latency of each (`None` for an
/// error).
async fn client(addr: SocketAddr, id: usize, requests: usize, distinct: bool) -> Vec<Option<Duration>> {
    let mut out = Vec::with_capacity(requests);
    let Ok(stream) = TcpStream::connect(addr).await else { return vec![None; requests] };
    let mut reader = BufReader::new(stream);
    for k in 0..requests {
        let body = if distinct { spec(&format!("Client {id}, request {k}")) } else { spec("The same chart") };
        let request = format!(
            "POST /api/render?format=svg HTTP/1.1\r\nHost: {addr}\r\nContent-Type: application/toml\r\n\
             Content-Length: {}\r\n\r\n{body}",
            body.len()
        );
        let started = Instant::now();
        let sent = reader.get_mut().write_all(request.as_bytes()).await;
        let status = match sent {
            Ok(()) => response(&mut reader).await.ok(),
            Err(_) => None,
        };
        out.push((status == Some(200)).then(|| started.elapsed()));
        if status.is_none() {
            break;
        }
    }
    out.resize(requests, None);
    out
}

fn percentile(sorted: &[Duration], p: f64) -> Duration {
    if sorted.is_empty() {
        return Duration::ZERO;
    }
    let rank = ((p / 100.0) * sorted.len() as f64).ceil() as usize;
    sorted[rank.clamp(1, sorted.len()) - 1]
}

fn main() {
    let (clients, requests) = (env("CLIENTS", 200), env("REQUESTS", 10));
    let dir = std::env::temp_dir().join(format!("dataink-serve-load-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    std::fs::write(dir.join("d.csv"), CSV).expect("data");
    let server = Server::new(dir.clone(), Limits::default()).expect("server");
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let rt = tokio::runtime::Builder::new_multi_thread().enable_all().build().expect("runtime");
        let _ = rt.block_on(run("127.0.0.1:0".parse().unwrap(), server, |addr| tx.send(addr).expect("send")));
    });
    let addr = rx.recv_timeout(Duration::from_secs(30)).expect("the server binds");
    // The clients on their own runtime (one thread: the load generator must not starve the
    // server of both cores).
    let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().expect("runtime");
    println!("dataink serve on {addr}: {clients} concurrent clients × {requests} requests, keep-alive");
    for (round, distinct) in [("the same chart (cached)", false), ("a different chart each request", true)] {
        let started = Instant::now();
        let results: Vec<Option<Duration>> = rt.block_on(async {
            let tasks: Vec<_> = (0..clients).map(|id| tokio::spawn(client(addr, id, requests, distinct))).collect();
            let mut all = Vec::new();
            for task in tasks {
                all.extend(task.await.unwrap_or_else(|_| vec![None; requests]));
            }
            all
        });
        let elapsed = started.elapsed();
        let mut ok: Vec<Duration> = results.iter().flatten().copied().collect();
        ok.sort();
        let errors = results.len() - ok.len();
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        println!(
            "{round}: {} requests in {:.2} s = {:.0} requests/s; p50 {:.1} ms, p90 {:.1} ms, p99 {:.1} ms, max {:.1} ms; {errors} errors",
            results.len(),
            elapsed.as_secs_f64(),
            ok.len() as f64 / elapsed.as_secs_f64(),
            ms(percentile(&ok, 50.0)),
            ms(percentile(&ok, 90.0)),
            ms(percentile(&ok, 99.0)),
            ms(ok.last().copied().unwrap_or_default()),
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
