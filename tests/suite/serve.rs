//! `dataink serve`: every endpoint through the router in-process (answers equal the pipeline's
//! own output), every limit, paths kept under the root, uploads, the cache, the headers every
//! response carries, and one request over a real socket on loopback.

use std::time::Duration;

use axum::body::Body;
use axum::http::{Request, Response, StatusCode, header};
use dataink::serve::{Limits, Server, router};
use serde_json::Value;
use tower::ServiceExt;

use crate::common::Fixture;

const CSV: &str = "a,b,kind\n1,2,x\n2,4,y\n3,5,x\n4,3,y\n";

fn spec(title: &str) -> String {
    format!(
        "[data.d]\npath = \"d.csv\"\n\n[[chart]]\nname = \"pts\"\nkind = \"scatter\"\ndata = \"d\"\ntitle = \"{title}\"\n\
         x = \"a\"\ny = \"b\"\n\n[[chart]]\nname = \"bars\"\nkind = \"bar\"\ndata = \"d\"\nx = \"kind\"\ny = \"b\"\n"
    )
}

/// A root folder holding `d.csv`, and the fixture (the same spec and data) the pipeline reads.
fn root(limits: Limits) -> (tempfile::TempDir, axum::Router) {
    let dir = tempfile::tempdir().expect("dir");
    std::fs::write(dir.path().join("d.csv"), CSV).expect("write");
    let server = Server::new(dir.path().to_path_buf(), limits).expect("server");
    (dir, router(server))
}

fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_current_thread().enable_all().build().expect("runtime")
}

/// Send `request` through `app`; the status, headers and body.
fn send(app: &axum::Router, request: Request<Body>) -> (StatusCode, axum::http::HeaderMap, Vec<u8>) {
    runtime().block_on(async {
        let response: Response<Body> = app.clone().oneshot(request).await.expect("infallible");
        let (parts, body) = response.into_parts();
        let bytes = axum::body::to_bytes(body, usize::MAX).await.expect("body");
        (parts.status, parts.headers, bytes.to_vec())
    })
}

fn post(uri: &str, body: impl Into<Body>) -> Request<Body> {
    Request::post(uri).header(header::CONTENT_TYPE, "application/toml").body(body.into()).expect("request")
}

fn json(bytes: &[u8]) -> Value {
    serde_json::from_slice(bytes).unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(bytes)))
}

/// A multipart form with a `spec` field and `files` (name, bytes).
fn form(spec: &str, files: &[(&str, &[u8])]) -> Request<Body> {
    let boundary = "dataink-test-boundary";
    let mut body = Vec::new();
    body.extend(format!("--{boundary}\r\nContent-Disposition: form-data; name=\"spec\"\r\n\r\n{spec}\r\n").as_bytes());
    for (name, bytes) in files {
        body.extend(
            format!(
                "--{boundary}\r\nContent-Disposition: form-data; name=\"file\"; filename=\"{name}\"\r\n\
                 Content-Type: application/octet-stream\r\n\r\n"
            )
            .as_bytes(),
        );
        body.extend(*bytes);
        body.extend(b"\r\n");
    }
    body.extend(format!("--{boundary}--\r\n").as_bytes());
    Request::post("/api/render?format=svg")
        .header(header::CONTENT_TYPE, format!("multipart/form-data; boundary={boundary}"))
        .body(Body::from(body))
        .expect("request")
}

#[test]
fn every_format_equals_what_the_pipeline_writes() {
    let (_dir, app) = root(Limits::default());
    let text = spec("Points");
    let fixture = Fixture::new(&text, &[("d.csv", CSV.as_bytes())]);
    let outputs = fixture.draw().expect("draw");

    let (status, headers, svg) = send(&app, post("/api/render?chart=pts", text.clone()));
    assert_eq!(status, StatusCode::OK, "{}", String::from_utf8_lossy(&svg));
    assert_eq!(headers[header::CONTENT_TYPE], "image/svg+xml");
    assert_eq!(String::from_utf8(svg).expect("utf-8"), dataink::render::svg::to_svg(&outputs[0].scene));

    let (status, headers, png) = send(&app, post("/api/render?chart=bars&format=png&scale=2", text.clone()));
    assert_eq!((status, &headers[header::CONTENT_TYPE]), (StatusCode::OK, &"image/png".parse().unwrap()));
    assert_eq!(png, dataink::render::png::to_png(&outputs[1].scene, 2.0).expect("png"));

    let (_, _, csv) = send(&app, post("/api/render?chart=bars&format=csv", text.clone()));
    let loaded = fixture.load().expect("load");
    let table = &loaded.tables["d"];
    assert_eq!(String::from_utf8(csv).expect("utf-8"), outputs[1].derived.to_csv(table));

    // Lint: every chart unless one is named; the bar chart has no title (LB001).
    let (status, _, lint) = send(&app, post("/api/render?format=lint", text.clone()));
    assert_eq!(status, StatusCode::OK);
    let lint = json(&lint);
    let charts = lint["charts"].as_array().expect("charts");
    assert_eq!(charts.len(), 2);
    let codes: Vec<&str> =
        charts[1]["findings"].as_array().unwrap().iter().filter_map(|f| f["code"].as_str()).collect();
    assert!(codes.contains(&"LB001"), "{codes:?}");
    let (_, headers, sarif) = send(&app, post("/api/render?format=sarif&chart=bars", text.clone()));
    assert_eq!(headers[header::CONTENT_TYPE], "application/sarif+json");
    let sarif = json(&sarif);
    assert_eq!(sarif["version"], "2.1.0");
    assert!(sarif["runs"][0]["results"].as_array().unwrap().iter().any(|r| r["ruleId"] == "LB001"));

    let (status, headers, page) = send(&app, post("/api/render?format=report", text.clone()));
    assert_eq!((status, headers[header::CONTENT_TYPE].to_str().unwrap()), (StatusCode::OK, "text/html; charset=utf-8"));
    let page = String::from_utf8(page).expect("utf-8");
    assert!(page.contains("<svg") && page.contains("Points"));

    // No chart named: the first.
    let (_, _, first) = send(&app, post("/api/render", text.clone()));
    assert_eq!(String::from_utf8(first).unwrap(), dataink::render::svg::to_svg(&outputs[0].scene));
}

#[test]
fn diagnostics_come_back_at_their_line_and_column() {
    let (_dir, app) = root(Limits::default());
    // Line 7: a misspelt key.
    let text = spec("Points").replacen("x = \"a\"", "xx = \"a\"", 1);
    assert_eq!(text.lines().position(|l| l.starts_with("xx")), Some(8));
    let (status, _, body) = send(&app, post("/api/check", text));
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    let body = json(&body);
    let found = body["diagnostics"].as_array().expect("diagnostics");
    let typo = found.iter().find(|d| d["message"].as_str().unwrap_or("").contains("xx")).expect("the typo is named");
    assert_eq!(
        (typo["line"].as_u64(), typo["column"].as_u64(), typo["severity"].as_str()),
        (Some(9), Some(1), Some("error"))
    );
    assert!(typo["hint"].as_str().is_some_and(|h| h.contains('x')), "{typo}");

    // A valid spec: 200, its charts by name and no errors.
    let (status, _, body) = send(&app, post("/api/check", spec("Points")));
    assert_eq!(status, StatusCode::OK);
    let body = json(&body);
    assert_eq!(body["charts"], serde_json::json!(["pts", "bars"]));
    assert!(body["diagnostics"].as_array().unwrap().iter().all(|d| d["severity"] != "error"));

    // An unknown chart, an unknown format, a bad scale, an unknown key.
    let (status, _, body) = send(&app, post("/api/render?chart=nope", spec("Points")));
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert!(json(&body)["error"].as_str().unwrap().contains("no chart named `nope`"));
    for (query, says) in [
        ("format=gif", "unknown format `gif`"),
        ("scale=100", "`scale` must be a number from 0.25 to 8"),
        ("colour=red", "unknown query key `colour`"),
    ] {
        let (status, _, body) = send(&app, post(&format!("/api/render?{query}"), spec("Points")));
        assert_eq!(status, StatusCode::BAD_REQUEST, "{query}");
        assert!(json(&body)["error"].as_str().unwrap().contains(says), "{query}");
    }
    let (status, _, body) = send(&app, post("/api/render", vec![0xff, 0xfe]));
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(json(&body)["error"].as_str().unwrap().contains("not UTF-8"));
    let (status, _, body) = send(&app, Request::get("/nowhere").body(Body::empty()).unwrap());
    assert_eq!(status, StatusCode::NOT_FOUND);
    assert!(json(&body)["error"].as_str().unwrap().contains("openapi"));
}

#[test]
fn every_response_carries_the_security_headers_and_the_api_is_described() {
    let (_dir, app) = root(Limits::default());
    let requests = [
        Request::get("/api/openapi.json").body(Body::empty()).unwrap(),
        Request::get("/").body(Body::empty()).unwrap(),
        Request::get("/missing").body(Body::empty()).unwrap(),
        post("/api/render", spec("Points")),
        post("/api/render", "not toml ["),
    ];
    for request in requests {
        let uri = request.uri().to_string();
        let (_, headers, _) = send(&app, request);
        let csp = headers[header::CONTENT_SECURITY_POLICY].to_str().unwrap();
        assert!(csp.contains("default-src 'none'") && csp.contains("frame-ancestors 'none'"), "{uri}");
        assert_eq!(headers[header::X_CONTENT_TYPE_OPTIONS], "nosniff", "{uri}");
    }
    let (_, _, doc) = send(&app, Request::get("/api/openapi.json").body(Body::empty()).unwrap());
    let doc = json(&doc);
    assert_eq!(doc["openapi"], "3.1.0");
    for path in ["/api/render", "/api/check"] {
        assert!(doc["paths"][path]["post"]["responses"]["422"].is_object(), "{path}");
    }
}

#[test]
fn the_page_is_in_the_binary_and_asks_nothing_of_other_servers() {
    let (_dir, app) = root(Limits::default());
    let get = |path: &str| send(&app, Request::get(path).body(Body::empty()).unwrap());
    let (status, headers, html) = get("/");
    assert_eq!((status, headers[header::CONTENT_TYPE].to_str().unwrap()), (StatusCode::OK, "text/html; charset=utf-8"));
    let html = String::from_utf8(html).unwrap();
    // The script is a file of its own (the policy allows no inline script) and every asset is local.
    assert!(html.contains("<script src=\"/app.js\"></script>"));
    assert_eq!(html.matches("<script").count(), 1, "no inline script");
    let (_, js_headers, js) = get("/app.js");
    let (_, css_headers, css) = get("/app.css");
    assert_eq!(js_headers[header::CONTENT_TYPE], "text/javascript; charset=utf-8");
    assert_eq!(css_headers[header::CONTENT_TYPE], "text/css; charset=utf-8");
    let js = String::from_utf8(js).unwrap();
    for text in [&html, &js, &String::from_utf8(css).unwrap()] {
        assert!(
            !text.contains("http://") && !text.contains("https://") && !text.contains("//cdn"),
            "an external address"
        );
    }
    // What the server sends goes into the page as text, never as markup.
    assert!(!js.contains("innerHTML") && !js.contains("outerHTML") && !js.contains("insertAdjacentHTML"));
    assert!(!js.contains("eval(") && !js.contains("new Function"));
    // The endpoints the script calls exist.
    for endpoint in ["/api/check", "/api/render?format=svg", "/api/render?format=lint"] {
        assert!(js.contains(endpoint), "{endpoint}");
    }
}

#[test]
fn data_comes_only_from_under_the_root_or_the_uploads() {
    let (dir, app) = root(Limits::default());
    let outside = tempfile::tempdir().expect("dir");
    std::fs::write(outside.path().join("secret.csv"), CSV).expect("write");
    std::os::unix::fs::symlink(outside.path().join("secret.csv"), dir.path().join("link.csv")).expect("symlink");
    for path in ["../secret.csv", "/etc/passwd", "link.csv"] {
        let (status, _, body) = send(&app, post("/api/render", spec("P").replace("d.csv", path)));
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{path}");
        assert!(
            json(&body)["diagnostics"][0]["line"].as_u64() == Some(2),
            "{path}: {}",
            String::from_utf8_lossy(&body)
        );
    }

    // A source on a query engine would have the server connect anywhere: refused at its key.
    let engine = spec("P").replace("path = \"d.csv\"\n", "path = \"d.parquet\"\nengine = \"sc://10.0.0.1:15002\"\n");
    let (status, _, body) = send(&app, post("/api/render", engine));
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    let body = json(&body);
    assert!(body["error"].as_str().unwrap().contains("reads files only"), "{body}");
    assert_eq!(body["diagnostics"][0]["line"], 3);

    // Uploaded files: the spec's paths name them, and only them.
    let other = "a,b,kind\n10,20,z\n";
    let (status, _, svg) = send(&app, form(&spec("Uploaded"), &[("d.csv", other.as_bytes())]));
    assert_eq!(status, StatusCode::OK, "{}", String::from_utf8_lossy(&svg));
    let uploaded = Fixture::new(&spec("Uploaded"), &[("d.csv", other.as_bytes())]).draw().expect("draw");
    assert_eq!(String::from_utf8(svg).unwrap(), dataink::render::svg::to_svg(&uploaded[0].scene));
    for (files, says) in [
        (vec![("../d.csv", other.as_bytes())], "not a relative path of plain names"),
        (vec![("/etc/d.csv", other.as_bytes())], "not a relative path of plain names"),
        (vec![("a/.hidden", other.as_bytes())], "not a relative path of plain names"),
        (vec![("d.csv", other.as_bytes()), ("d.csv", other.as_bytes())], "sent twice"),
        (vec![("d", other.as_bytes()), ("d/e.csv", other.as_bytes())], "one would be a folder holding the other"),
    ] {
        let (status, _, body) = send(&app, form(&spec("U"), &files));
        assert_eq!(status, StatusCode::BAD_REQUEST, "{says}");
        assert!(json(&body)["error"].as_str().unwrap().contains(says), "{says}");
    }
    // A file in a folder, as the spec names it.
    let (status, _, _) =
        send(&app, form(&spec("U").replace("d.csv", "data/d.csv"), &[("data/d.csv", other.as_bytes())]));
    assert_eq!(status, StatusCode::OK);
    // Uploads do not reach the root's files: `e.csv` is neither uploaded nor looked for there.
    std::fs::write(dir.path().join("e.csv"), CSV).expect("write");
    let (status, _, _) = send(&app, form(&spec("U").replace("d.csv", "e.csv"), &[("d.csv", other.as_bytes())]));
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
}

#[test]
fn sql_cannot_read_files_and_other_host_names_are_refused() {
    let (_dir, app) = root(Limits::default());
    // polars' SQL table functions would read any file past the path policy.
    let reads = spec("P").replace(
        "path = \"d.csv\"\n",
        "path = \"d.csv\"\ntransform = [{ sql = \"SELECT * FROM read_csv('/etc/passwd')\" }]\n",
    );
    let (status, _, body) = send(&app, post("/api/render?format=csv", reads));
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    let body = json(&body);
    assert!(body["error"].as_str().unwrap().contains("reads `read_csv(...)`"), "{body}");
    assert!(!body.to_string().contains("root:"), "nothing of the file comes back");

    // A page on another domain resolving to 127.0.0.1 sends its own name as Host: refused.
    let with_host = |host: &str| {
        Request::post("/api/render")
            .header(header::HOST, host)
            .header(header::CONTENT_TYPE, "application/toml")
            .body(Body::from(spec("P")))
            .unwrap()
    };
    let (status, headers, body) = send(&app, with_host("rebound.example:8700"));
    assert_eq!(status, StatusCode::FORBIDDEN);
    assert!(json(&body)["error"].as_str().unwrap().contains("only requests to localhost"));
    assert!(headers.contains_key(header::CONTENT_SECURITY_POLICY));
    for host in ["127.0.0.1:8700", "localhost:8700", "[::1]:8700"] {
        assert_eq!(send(&app, with_host(host)).0, StatusCode::OK, "{host}");
    }
    // A server bound where others reach it answers any name.
    let dir = tempfile::tempdir().expect("dir");
    std::fs::write(dir.path().join("d.csv"), CSV).expect("write");
    let open = router(Server::new(dir.path().to_path_buf(), Limits::default()).expect("server").answering_any_host());
    assert_eq!(send(&open, with_host("charts.example")).0, StatusCode::OK);
}

#[test]
fn every_limit_answers_with_its_status_and_number() {
    let small =
        Limits { upload_bytes: 2_000, spec_bytes: 600, files: 1, rows: 3, pixels: 300_000, ..Limits::default() };
    let (_dir, app) = root(small);
    let cases: Vec<(Request<Body>, StatusCode, &str)> = vec![
        (post("/api/render", "#".repeat(3_000)), StatusCode::PAYLOAD_TOO_LARGE, "limit of 2000 bytes"),
        (
            post("/api/render", format!("{}\n{}", spec("P"), "#".repeat(700))),
            StatusCode::PAYLOAD_TOO_LARGE,
            "at most 600",
        ),
        (
            form(&spec("P"), &[("d.csv", CSV.as_bytes()), ("e.csv", CSV.as_bytes())]),
            StatusCode::PAYLOAD_TOO_LARGE,
            "more than 1 files",
        ),
        (post("/api/render", spec("P")), StatusCode::UNPROCESSABLE_ENTITY, "has 4 rows; this server draws at most 3"),
        // A form over the body limit: its file is not read past the limit.
        (
            form(&spec("P"), &[("d.csv", "a\n1\n".repeat(1_500).as_bytes())]),
            StatusCode::PAYLOAD_TOO_LARGE,
            "limit of 2000 bytes",
        ),
    ];
    for (request, status, says) in cases {
        let (got, _, body) = send(&app, request);
        assert_eq!(got, status, "{says}: {}", String::from_utf8_lossy(&body));
        assert!(json(&body)["error"].as_str().unwrap().contains(says), "{says}: {}", String::from_utf8_lossy(&body));
    }
    let (_dir, app) = root(Limits { pixels: 300_000, ..Limits::default() });
    let (status, _, body) = send(&app, post("/api/render?format=png&scale=2", spec("P")));
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    let body = json(&body);
    assert!(body["error"].as_str().unwrap().contains("this server draws at most 300000"));
    assert!(body["diagnostics"][0]["line"].is_u64(), "placed in the spec, as `dataink render` places it: {body}");
    let (status, _, _) = send(&app, post("/api/render?format=png&scale=1", spec("P")));
    assert_eq!(status, StatusCode::OK, "the same chart at scale 1 fits");

    // A render past its time is answered with 503 and the limit.
    let (_dir, app) = root(Limits { render_time: Duration::from_nanos(1), ..Limits::default() });
    let (status, _, body) = send(&app, post("/api/render", spec("P")));
    assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE);
    // Past the deadline while rendering or (on a loaded machine) already while waiting for a
    // slot: 503 either way, naming the limit.
    let error = json(&body)["error"].as_str().unwrap().to_string();
    assert!(error.contains("0.000000001 s") && (error.contains("longer than") || error.contains("busy")), "{error}");
}

#[test]
fn answers_are_cached_until_the_spec_or_its_data_changes() {
    let (dir, app) = root(Limits::default());
    let (_, first, a) = send(&app, post("/api/render", spec("P")));
    let (_, second, b) = send(&app, post("/api/render", spec("P")));
    assert_eq!(
        (&first["x-dataink-cache"], &second["x-dataink-cache"]),
        (&"miss".parse().unwrap(), &"hit".parse().unwrap())
    );
    assert_eq!(a, b);
    let (_, other, _) = send(&app, post("/api/render", spec("Q")));
    assert_eq!(other["x-dataink-cache"], "miss", "another spec");
    std::fs::write(dir.path().join("d.csv"), format!("{CSV}5,9,x\n")).expect("write");
    let (_, changed, c) = send(&app, post("/api/render", spec("P")));
    assert_eq!(changed["x-dataink-cache"], "miss", "the data file changed");
    assert_ne!(a, c);
}

#[test]
fn the_same_answer_asked_at_once_is_made_once() {
    let (_dir, app) = root(Limits::default());
    let rt = tokio::runtime::Builder::new_multi_thread().worker_threads(2).enable_all().build().expect("rt");
    let marks: Vec<String> = rt.block_on(async {
        let tasks: Vec<_> = (0..8)
            .map(|_| {
                let app = app.clone();
                tokio::spawn(async move {
                    let response = app.oneshot(post("/api/render?format=png", spec("Together"))).await.expect("answer");
                    assert_eq!(response.status(), StatusCode::OK);
                    response.headers()["x-dataink-cache"].to_str().unwrap().to_string()
                })
            })
            .collect();
        let mut marks = Vec::new();
        for task in tasks {
            marks.push(task.await.expect("task"));
        }
        marks
    });
    assert_eq!(marks.iter().filter(|m| *m == "miss").count(), 1, "{marks:?}");
}

#[test]
fn hostile_text_never_becomes_markup() {
    let (_dir, app) = root(Limits::default());
    let title = "<script>alert(1)</script> & \\\"quoted\\\"";
    let (status, _, svg) = send(&app, post("/api/render", spec(title)));
    assert_eq!(status, StatusCode::OK);
    let svg = String::from_utf8(svg).unwrap();
    assert!(!svg.contains("<script") && svg.contains("&lt;script&gt;"), "{svg}");
    let (status, _, page) = send(&app, post("/api/render?format=report", spec(title)));
    assert_eq!(status, StatusCode::OK);
    let page = String::from_utf8(page).unwrap();
    assert!(!page.contains("<script>alert"), "the report escapes the title");
    // A hostile category, uploaded: its bar label and the derived CSV carry it as text.
    let hostile = "a,b,kind\n1,2,<img src=x onerror=alert(1)>\n2,4,y\n";
    let mut bars = form(&spec("P"), &[("d.csv", hostile.as_bytes())]);
    *bars.uri_mut() = "/api/render?format=svg&chart=bars".parse().unwrap();
    let (status, _, svg) = send(&app, bars);
    assert_eq!(status, StatusCode::OK);
    let svg = String::from_utf8(svg).unwrap();
    assert!(!svg.contains("<img") && svg.contains("&lt;img src=x onerror=alert(1)&gt;"), "{svg:.400}");
    let (status, _, body) = send(&app, form(&spec("P"), &[("d\u{7}.csv", CSV.as_bytes())]));
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(!String::from_utf8_lossy(&body).contains('\u{7}'));
}

#[test]
fn a_real_socket_on_loopback_answers() {
    let dir = tempfile::tempdir().expect("dir");
    std::fs::write(dir.path().join("d.csv"), CSV).expect("write");
    let server = Server::new(dir.path().to_path_buf(), Limits::default()).expect("server");
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let rt = tokio::runtime::Builder::new_multi_thread().worker_threads(2).enable_all().build().expect("rt");
        let addr = "127.0.0.1:0".parse().unwrap();
        let _ = rt.block_on(dataink::serve::run(addr, server, |bound| tx.send(bound).expect("send")));
    });
    let addr = rx.recv_timeout(Duration::from_secs(30)).expect("the server binds");
    assert!(addr.ip().is_loopback());
    use std::io::{Read, Write};
    let mut stream = std::net::TcpStream::connect(addr).expect("connect");
    let body = spec("Over the wire");
    write!(
        stream,
        "POST /api/render?format=svg HTTP/1.1\r\nHost: {addr}\r\nContent-Type: application/toml\r\n\
         Content-Length: {}\r\nConnection: close\r\n\r\n{body}",
        body.len()
    )
    .expect("send");
    let mut answer = String::new();
    stream.read_to_string(&mut answer).expect("read");
    assert!(answer.starts_with("HTTP/1.1 200 OK"), "{answer}");
    assert!(answer.contains("content-security-policy:") && answer.contains("Over the wire"));
}
