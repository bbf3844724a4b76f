//! `whitted view` (and `whitted check --view`): a local web viewer for AOV renders. It binds 127.0.0.1 only, prints its URL
//! (with a per-run random token) as the first line on stdout, refuses any request whose Host
//! header is not the loopback address it listens on (DNS rebinding) or that lacks the token,
//! and serves nothing but its page and what it loaded (`view/content.rs`): the images' layers,
//! their error metrics and statistics, a pixel's ray trees, the check's report. The page
//! (`view/page/`, plain files compiled into the binary: no build chain, no CDN) does the tone
//! mapping, zoom, false colour, relighting and A/B comparison in the browser. With `--watch`,
//! a thread reloads the files when they change (`view/watch.rs`) and the page follows.
//!
//! The server is hyper behind a thin adapter (`view/server.rs`, which says why and with which
//! limits); every request is parsed into a closed set first (`view/request.rs`) and answered
//! by a pure function (`view/api.rs`).

mod api;
mod content;
mod metric;
mod planes;
mod request;
mod server;
mod stats;
mod token;
mod watch;

use std::io::Write;
use std::sync::{Arc, Mutex};

use crate::error::{Error, Result};

pub use api::{respond, Snapshot};
pub use content::{Content, Source};
pub use request::{parse, ApiRequest, Incoming};

/// A reply: status, content type, body.
pub type Reply = (u16, &'static str, Vec<u8>);

/// A plain-text reply.
fn text(status: u16, message: &str) -> Reply {
    (
        status,
        "text/plain; charset=utf-8",
        message.as_bytes().to_vec(),
    )
}

/// What the viewer serves: the latest load, and the token and port every request is checked
/// against.
pub struct Served {
    /// The token every request must carry.
    pub token: String,
    /// The port it listens on, for the Host check.
    pub port: u16,
    current: Mutex<Snapshot>,
}

impl Served {
    pub fn new(content: Content, token: String, port: u16) -> Served {
        Served {
            token,
            port,
            current: Mutex::new(Snapshot {
                content: Arc::new(content),
                version: 1,
                problem: None,
            }),
        }
    }

    /// The latest load, for one request (a reload meanwhile does not change it under it).
    pub fn now(&self) -> Snapshot {
        // A poisoned lock still holds a whole snapshot: they are only ever replaced whole.
        self.current
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .clone()
    }

    /// A reload's outcome: the new content, or why there is none (the old one stays).
    fn reloaded(&self, outcome: Result<Content>) {
        let mut current = self.current.lock().unwrap_or_else(|e| e.into_inner());
        match outcome {
            Ok(content) => {
                current.content = Arc::new(content);
                current.version += 1;
                current.problem = None;
            }
            Err(e) => current.problem = Some(e.to_string()),
        }
    }
}

/// Loads `source`, listens on 127.0.0.1:`port` (0 for any free port), prints the URL, opens a
/// browser unless `no_browser`, and serves until a signal stops it; with `watch`, reloading
/// the source whenever one of its files changes.
pub fn serve(source: Source, port: u16, no_browser: bool, watch: bool) -> Result<()> {
    let content = source.load()?;
    let listener = std::net::TcpListener::bind(("127.0.0.1", port))
        .map_err(|e| Error::Environment(format!("cannot listen on 127.0.0.1:{port}: {e}")))?;
    let port = listener
        .local_addr()
        .map_err(|e| Error::io("127.0.0.1", "cannot listen", e))?
        .port();
    let served = Arc::new(Served::new(content, token::new(), port));
    let url = format!("http://127.0.0.1:{port}/?token={}", served.token);
    crate::output::stdout::print_line(&url)?;
    let _ = std::io::stdout().flush();
    if watch {
        watch::start(source, served.clone())?;
    }
    // Kept until the server stops, so the browser can still read it.
    let _opener = if no_browser { None } else { open_browser(&url) };
    server::run(listener, served)
}

/// Best effort: opens the URL in a desktop browser through a file only this user can read,
/// which redirects to it (as Jupyter does), so that the token never stands in a browser's
/// command line, where every local user can read it in /proc. Elsewhere the URL printed is
/// the way in.
fn open_browser(url: &str) -> Option<tempfile::TempPath> {
    let mut file = tempfile::Builder::new()
        .prefix("whitted-view-")
        .suffix(".html")
        .tempfile()
        .ok()?;
    let page = format!(
        "<!doctype html><meta charset=utf-8><meta http-equiv=refresh content=\"0;url={url}\">\
         <title>whitted view</title><a href=\"{url}\">whitted view</a>\n"
    );
    file.write_all(page.as_bytes()).ok()?;
    let path = file.into_temp_path();
    let _ = std::process::Command::new("xdg-open")
        .arg(&path)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn();
    Some(path)
}
