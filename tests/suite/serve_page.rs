//! The page `dataink serve` sends, in a real headless Chromium driven over WebDriver: it draws
//! its first chart, draws a typed spec, and marks a typo at its line.

use std::time::Duration;

use dataink::serve::{Limits, Server};

use crate::webdriver::{Browser, available};

/// The server on a free loopback port, on its own thread for the rest of the test run.
fn serve(root: &std::path::Path) -> std::net::SocketAddr {
    let server = Server::new(root.to_path_buf(), Limits::default()).expect("server");
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let rt = tokio::runtime::Builder::new_multi_thread().worker_threads(2).enable_all().build().expect("rt");
        let _ = rt.block_on(dataink::serve::run("127.0.0.1:0".parse().unwrap(), server, |a| tx.send(a).expect("send")));
    });
    rx.recv_timeout(Duration::from_secs(30)).expect("the server binds")
}

const TYPED: &str = "[data.d]\nvalues = [{ a = 1, b = 3 }, { a = 2, b = 1 }, { a = 3, b = 2 }]\n\n\
                     [[chart]]\nname = \"typed\"\nkind = \"scatter\"\ndata = \"d\"\nsize = [500, 300]\n\
                     x = \"a\"\ny = \"b\"";

#[test]
fn a_browser_draws_what_is_typed_and_marks_a_typo_at_its_line() {
    if !available() {
        return;
    }
    let root = tempfile::tempdir().expect("root");
    let addr = serve(root.path());
    let browser = Browser::start();
    browser.open(&format!("http://{addr}/"));

    // The example spec is drawn on load.
    let status = browser.wait_for(
        "const s = document.getElementById('status').textContent; return s.startsWith('Drawn') ? s : null;",
        60,
        "the first chart",
    );
    assert_eq!(status, "Drawn decay; 0 lint findings");
    assert!(browser.run("return document.getElementById('chart-image').naturalWidth;").as_u64().unwrap_or(0) > 100);

    // Type a spec: its chart is drawn.
    let editor = browser.element("#spec");
    browser.clear(&editor);
    browser.type_text(&editor, TYPED);
    browser.wait_for(
        "return document.getElementById('chart').value === 'typed' && !document.getElementById('chart-image').classList.contains('stale');",
        60,
        "the typed chart",
    );
    // The image is the typed chart: its size is the one typed (the page shows the server's SVG
    // in an <img>, where no script of it could run).
    let size =
        browser.run("const i = document.getElementById('chart-image'); return [i.naturalWidth, i.naturalHeight];");
    assert_eq!(size, serde_json::json!([500, 300]));
    let findings = browser.run("return [...document.querySelectorAll('#findings li')].map(li => li.textContent);");
    assert!(findings.to_string().contains("LB001 missing-title"), "the untitled chart's finding is listed: {findings}");

    // A typo on a new last line: the diagnostic names it at that line, and the gutter marks it.
    let typo_line = TYPED.lines().count() + 1;
    browser.type_text(&editor, "\nkidn = \"line\"");
    let marked = browser.wait_for(
        "const li = document.querySelector('#diagnostics li[data-line]'); return li ? [li.dataset.line, li.textContent] : null;",
        60,
        "the typo's diagnostic",
    );
    assert_eq!(marked[0], typo_line.to_string(), "{marked}");
    assert!(marked[1].as_str().unwrap_or("").contains("unknown key `kidn`"), "{marked}");
    let gutter =
        browser.run(&format!("return document.querySelector('#gutter div:nth-child({typo_line})').className;"));
    assert_eq!(gutter, "error");
    let status = browser.run("return document.getElementById('status').className;");
    assert_eq!(status, "error");
}
