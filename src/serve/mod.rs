//! `dataink serve`: the pipeline over HTTP. A client posts a spec (TOML text, or a multipart form
//! with the spec and its data files) and gets a chart back as SVG, PNG or derived CSV, the lint
//! findings as JSON or SARIF, the report page, or the spec's diagnostics as JSON with line and
//! column. Data comes only from the request's uploads or from under the server's root folder.
//!
//! One module per job: [`limits`] (what a request may ask for), [`submitted`] (reading a
//! request's spec and files), [`job`] (loading, drawing and writing one answer, on a blocking
//! thread), [`cache`] (answers by the hash of what was asked), [`reply`] (JSON bodies and the
//! headers every response carries), [`openapi`] (the API's description) and [`page`] (the
//! browser page).

pub mod cache;
pub mod hosts;
pub mod job;
pub mod limits;
pub mod openapi;
pub mod page;
pub mod reply;
pub mod submitted;

use std::collections::HashMap;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;

use axum::Router;
use axum::extract::{DefaultBodyLimit, Query, Request, State};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use tokio::sync::Semaphore;

pub use limits::Limits;

use job::{Answer, Asked};
use reply::{Problem, error_json};

/// What the server holds between requests.
pub struct Server {
    /// Data named by a spec's relative paths resolves here (symlinks must stay inside).
    root: PathBuf,
    limits: Limits,
    /// Which `Host` names are answered (loopback names only, for a loopback address).
    hosts: hosts::HostCheck,
    cache: cache::Cache,
    /// Requests for the same answer made at once take turns, so it is made once.
    gates: cache::Gates,
    /// One permit per render running; a render past its time keeps its permit until its thread
    /// ends, so abandoned work cannot pile up.
    slots: Arc<Semaphore>,
    /// One permit per request past its query check, held until it is answered: bounds the
    /// request bodies held at once (each up to the upload limit).
    readers: Semaphore,
}

impl Server {
    /// A server over `root` (made absolute and resolved) with `limits`.
    pub fn new(root: PathBuf, limits: Limits) -> std::io::Result<Server> {
        let root = root.canonicalize()?;
        if !root.is_dir() {
            return Err(std::io::Error::other(format!("`{}` is not a folder", root.display())));
        }
        let slots = Arc::new(Semaphore::new(limits.concurrent_renders.max(1)));
        let cache = cache::Cache::new(limits.cache_bytes);
        let readers = Semaphore::new(limits.concurrent_renders.max(1) * 4);
        Ok(Server {
            root,
            limits,
            hosts: hosts::HostCheck::Loopback,
            cache,
            gates: cache::Gates::default(),
            slots,
            readers,
        })
    }
}

impl Server {
    /// Answer requests to any host name (for a server bound to an address others reach it by);
    /// by default only loopback names are answered.
    pub fn answering_any_host(mut self) -> Server {
        self.hosts = hosts::HostCheck::Any;
        self
    }
}

/// The HTTP API over `server`: every route, the body limit, the host check, and the headers every
/// response carries.
pub fn router(server: Server) -> Router {
    let body_limit = server.limits.upload_bytes;
    let host_check = server.hosts;
    Router::new()
        .route("/", get(page::index))
        .route("/app.js", get(page::script))
        .route("/app.css", get(page::style))
        .route("/api", get(index))
        .route("/api/openapi.json", get(openapi_json))
        .route("/api/check", post(check))
        .route("/api/render", post(render))
        .with_state(Arc::new(server))
        .fallback(not_found)
        .layer(DefaultBodyLimit::max(body_limit))
        .layer(axum::middleware::from_fn_with_state(host_check, hosts::check))
        .layer(axum::middleware::map_response(reply::secure))
}

/// Serve `router` on `addr` until Ctrl-C; `ready` is told the bound address.
pub async fn run(addr: SocketAddr, server: Server, ready: impl FnOnce(SocketAddr)) -> std::io::Result<()> {
    let listener = tokio::net::TcpListener::bind(addr).await?;
    let server = if addr.ip().is_loopback() { server } else { server.answering_any_host() };
    ready(listener.local_addr()?);
    axum::serve(listener, router(server))
        .with_graceful_shutdown(async {
            let _ = tokio::signal::ctrl_c().await;
        })
        .await
}

async fn index() -> Response {
    let body = serde_json::json!({
        "name": "dataink",
        "version": env!("CARGO_PKG_VERSION"),
        "api": "/api/openapi.json",
        "endpoints": ["POST /api/check", "POST /api/render?format=svg|png|csv|lint|sarif|report&chart=NAME&scale=S"],
    });
    reply::json(StatusCode::OK, &body)
}

async fn openapi_json() -> Response {
    reply::json(StatusCode::OK, &openapi::document())
}

async fn not_found() -> Response {
    error_json(StatusCode::NOT_FOUND, "no such endpoint; GET /api/openapi.json lists them")
}

/// `POST /api/check`: the spec's diagnostics (errors and warnings), after loading its data.
async fn check(State(server): State<Arc<Server>>, request: Request) -> Response {
    answer(server, request, HashMap::new(), true).await
}

/// `POST /api/render`: one chart (or the lint findings, or the report) in the asked format.
async fn render(
    State(server): State<Arc<Server>>,
    Query(query): Query<HashMap<String, String>>,
    request: Request,
) -> Response {
    answer(server, request, query, false).await
}

async fn answer(server: Arc<Server>, request: Request, query: HashMap<String, String>, check_only: bool) -> Response {
    let asked = match Asked::from_query(&query, check_only) {
        Ok(asked) => asked,
        Err(problem) => return problem.into_response(),
    };
    let Ok(Ok(_reading)) = tokio::time::timeout(server.limits.render_time, server.readers.acquire()).await else {
        return Problem::busy(&server.limits).into_response();
    };
    let submitted = match submitted::read(request, &server.limits).await {
        Ok(s) => s,
        Err(problem) => return problem.into_response(),
    };
    let key = cache::key(&asked, &submitted);
    if let Some(hit) = server.cache.get(&key) {
        return hit.into_response_marked(true);
    }
    // One deadline for waiting (for the same answer, or for a render slot) and rendering.
    let deadline = tokio::time::Instant::now() + server.limits.render_time;
    let entered = server.gates.enter(&key);
    match tokio::time::timeout_at(deadline, entered.turn()).await {
        Ok(_turn) => match server.cache.get(&key) {
            Some(hit) => hit.into_response_marked(true),
            None => make(&server, key, asked, submitted, deadline).await,
        },
        Err(_) => Problem::busy(&server.limits).into_response(),
    }
}

/// Make the answer on a blocking thread within `deadline`, and keep it when it is a success.
async fn make(
    server: &Arc<Server>,
    key: cache::Key,
    asked: Asked,
    submitted: submitted::Submitted,
    deadline: tokio::time::Instant,
) -> Response {
    let Ok(Ok(permit)) = tokio::time::timeout_at(deadline, Arc::clone(&server.slots).acquire_owned()).await else {
        return Problem::busy(&server.limits).into_response();
    };
    let (root, limits) = (server.root.clone(), server.limits.clone());
    let work = tokio::task::spawn_blocking(move || {
        let answer = job::run(&root, &limits, &asked, submitted);
        drop(permit);
        answer
    });
    match tokio::time::timeout_at(deadline, work).await {
        Ok(Ok(Ok(Answer { reply, inputs, cacheable }))) => {
            if cacheable && reply.status == StatusCode::OK {
                server.cache.put(key, reply.clone(), inputs);
            }
            reply.into_response_marked(false)
        }
        Ok(Ok(Err(problem))) => problem.into_response(),
        Ok(Err(_)) => error_json(StatusCode::INTERNAL_SERVER_ERROR, "the render failed unexpectedly"),
        Err(_) => Problem::too_slow(&server.limits).into_response(),
    }
}
