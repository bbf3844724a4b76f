//! whitted-view: the viewer. A local HTTP server (token, Host check, admission limits) and the
//! page it serves, which shows an EXR's layers, traces a pixel with whitted-check's `explain`
//! and reloads when the file changes (`docs/view.md`).
//!
//! # What it may depend on
//! whitted-core, whitted-io, whitted-check, hyper and tokio. Never clap or zip.
//!
//! `whitted view` (and `whitted check --view`): a local web viewer for AOV renders. It binds 127.0.0.1 only, prints its URL
//! (with a per-run random token) as the first line on stdout, refuses any request whose Host
//! header is not the loopback address it listens on (DNS rebinding) or that lacks the token,
//! and serves nothing but its page and what it loaded (`view/content.rs`): the images' layers,
//! their error metrics and statistics, a pixel's ray trees, the check's report. The page
//! (`view/page/`, plain files compiled into the binary: no build chain, no CDN) does the tone
//! mapping, zoom, false colour, relighting and A/B comparison in the browser. With `--watch`,
//! a thread reloads the files when they change (`view/watch.rs`) and the page follows. A
//! first load that takes longer than `OPEN_WAIT` (a 4K EXR of 53 layers: 10 s) does not keep
//! the URL back: the page opens and says what is being read until it is there.
//!
//! The server is hyper behind a thin adapter (`view/server.rs`, which says why and with which
//! limits); every request is parsed into a closed set first (`view/request.rs`) and answered
//! by a pure function (`view/api.rs`).

mod admission;
mod api;
mod busy;
mod connections;
mod content;
pub mod held_body;
mod metric;
mod planes;
mod request;
mod server;
mod stats;
pub mod token;
mod watch;

use std::io::Write;
use std::sync::mpsc::RecvTimeoutError;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use whitted_core::error::{Error, Result};

pub use api::{Snapshot, State};
pub use connections::{
    serve_connections, Limits, CONNECTION_TIME, HEAD_TIMEOUT, MAX_CONNECTIONS, MAX_HEAD,
};
pub use content::{Content, Source};
/// The connection limits and the Host check, which `whitted serve` shares.
pub use request::check_host;

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

/// How long the first load may run before the URL is printed anyway. A load that ends within
/// it behaves as if it had not been waited for (a file refused is refused before any URL); a
/// longer one gets a page at once that says what it is reading, not a silent terminal.
const OPEN_WAIT: Duration = Duration::from_secs(1);

/// What the viewer serves: the latest load, and the token and port every request is checked
/// against.
pub struct Served {
    /// The token every request must carry.
    pub token: String,
    /// The port it listens on, for the Host check.
    pub port: u16,
    /// Whether the files are watched (`--watch`): the page polls for reloads only then.
    watching: bool,
    /// What is served, watched: requests that need the content wait for it to be open.
    current: tokio::sync::watch::Sender<State>,
    /// The first load's failure, which the server stops with.
    failure: Mutex<Option<Error>>,
}

impl Served {
    /// Serving `content`, loaded before the server started.
    pub fn open(content: Content, token: String, port: u16, watching: bool) -> Served {
        let first = State::Open(Snapshot::first(content, watching));
        Served::holding(first, token, port, watching)
    }

    /// Serving the page while `what` is read, since `started` (then `opened` gives what it
    /// held).
    pub fn opening(
        what: String,
        started: Instant,
        token: String,
        port: u16,
        watching: bool,
    ) -> Served {
        Served::holding(State::Opening { what, started }, token, port, watching)
    }

    fn holding(state: State, token: String, port: u16, watching: bool) -> Served {
        Served {
            token,
            port,
            watching,
            current: tokio::sync::watch::Sender::new(state),
            failure: Mutex::new(None),
        }
    }

    /// The latest load, for one request (a reload meanwhile does not change it under it).
    pub fn now(&self) -> State {
        self.current.borrow().clone()
    }

    /// What is served, as a receiver to wait on.
    pub fn changes(&self) -> tokio::sync::watch::Receiver<State> {
        self.current.subscribe()
    }

    /// The first load's outcome: the content to serve, or the failure to stop with.
    pub fn opened(&self, outcome: Result<Content>) {
        match outcome {
            Ok(content) => {
                self.current
                    .send_replace(State::Open(Snapshot::first(content, self.watching)));
            }
            Err(e) => self.fail(e),
        }
    }

    fn fail(&self, e: Error) {
        *self.failure.lock().unwrap_or_else(|e| e.into_inner()) = Some(e);
    }

    /// The failure the server must stop with, if there is one (given once).
    pub fn take_failure(&self) -> Option<Error> {
        self.failure
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take()
    }

    /// A reload's outcome: the new content, or why there is none (the old one stays).
    fn reloaded(&self, outcome: Result<Content>) {
        self.current.send_modify(|state| {
            let State::Open(current) = state else {
                return; // reloads start only once the first load has ended
            };
            match outcome {
                Ok(content) => {
                    current.content = Arc::new(content);
                    current.version += 1;
                    current.problem = None;
                }
                Err(e) => current.problem = Some(e.to_string()),
            }
        });
    }
}

/// Loads `source` (waiting at most `OPEN_WAIT` for it before serving the page meanwhile),
/// listens on 127.0.0.1:`port` (0 for any free port), prints the URL, opens a browser unless
/// `no_browser`, and serves until a signal or the first load's failure stops it; with
/// `watch`, reloading the source whenever one of its files changes.
pub fn serve(source: Source, port: u16, no_browser: bool, watch: bool) -> Result<()> {
    let (done, first_load) = std::sync::mpsc::channel();
    // Before the first load, so that a change made while it runs is seen.
    let baseline = watch.then(|| watch::Baseline::of(&source));
    let (reading, started) = (source.clone(), Instant::now());
    std::thread::Builder::new()
        .name("load".into())
        .spawn(move || {
            let _ = done.send(reading.load());
        })
        .map_err(|e| Error::Environment(format!("cannot start the loading thread: {e}")))?;
    let loaded = match first_load.recv_timeout(OPEN_WAIT) {
        Ok(outcome) => Some(outcome?),
        Err(RecvTimeoutError::Timeout) => None,
        Err(RecvTimeoutError::Disconnected) => return Err(load_stopped()),
    };
    whitted_core::interrupt::check()?;
    let listener = std::net::TcpListener::bind(("127.0.0.1", port))
        .map_err(|e| Error::Environment(format!("cannot listen on 127.0.0.1:{port}: {e}")))?;
    let port = listener
        .local_addr()
        .map_err(|e| Error::io("127.0.0.1", "cannot listen", e))?
        .port();
    let (served, pending) = match loaded {
        Some(content) => (Served::open(content, token::new(), port, watch), None),
        None => (
            Served::opening(source.describe(), started, token::new(), port, watch),
            Some(first_load),
        ),
    };
    let served = Arc::new(served);
    let url = format!("http://127.0.0.1:{port}/?token={}", served.token);
    whitted_io::output::stdout::print_line(&url)?;
    let _ = std::io::stdout().flush();
    match (pending, baseline) {
        (Some(first_load), baseline) => {
            finish_opening(first_load, source, served.clone(), baseline)?
        }
        (None, Some(baseline)) => watch::start(source, served.clone(), baseline)?,
        (None, None) => {}
    }
    // Kept until the server stops, so the browser can still read it.
    let _opener = if no_browser { None } else { open_browser(&url) };
    server::run(listener, served)
}

/// Hands the first load's outcome to `served` when it comes (the server stops with a
/// failure), and starts watching from `baseline` after it.
fn finish_opening(
    first_load: std::sync::mpsc::Receiver<Result<Content>>,
    source: Source,
    served: Arc<Served>,
    baseline: Option<watch::Baseline>,
) -> Result<()> {
    std::thread::Builder::new()
        .name("open".into())
        .spawn(move || {
            let outcome = first_load.recv().unwrap_or_else(|_| Err(load_stopped()));
            let ok = outcome.is_ok();
            served.opened(outcome);
            if let Some(baseline) = baseline.filter(|_| ok) {
                if let Err(e) = watch::start(source, served.clone(), baseline) {
                    served.fail(e);
                }
            }
        })
        .map(drop)
        .map_err(|e| Error::Environment(format!("cannot start the loading thread: {e}")))
}

/// The loading thread ended without an outcome (it panicked: a bug, reported as one line).
fn load_stopped() -> Error {
    Error::Environment("reading the files stopped unexpectedly".into())
}

/// Best effort: opens the URL in a desktop browser through a file only this user can read,
/// which redirects to it (as Jupyter does), so that the token never stands in a browser's
/// command line, where every local user can read it in /proc. Elsewhere the URL printed is
/// the way in.
/// The browser's redirect page, a temporary file holding the token: deleted when dropped, and
/// registered so that a forced exit (which runs no destructor) deletes it too.
struct RedirectPage(tempfile::TempPath);

impl Drop for RedirectPage {
    fn drop(&mut self) {
        whitted_core::interrupt::unregister_temp(&self.0);
    }
}

fn open_browser(url: &str) -> Option<RedirectPage> {
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
    whitted_core::interrupt::register_temp(&path);
    let _ = std::process::Command::new("xdg-open")
        .arg(&path)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn();
    Some(RedirectPage(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn content() -> Content {
        Content {
            main: whitted_io::input::raster::rgb8(2, 2, &[0; 12]),
            reference: None,
            tracer: None,
            check: None,
            labels: ["a.png".into(), String::new()],
        }
    }

    #[test]
    fn a_first_load_opens_the_content_or_stops_the_server_once() {
        let served = Served::opening("a.png".into(), Instant::now(), "t".into(), 1, false);
        assert!(matches!(served.now(), State::Opening { .. }));
        let changes = served.changes();
        // A reload before the first load ends is not taken.
        served.reloaded(Ok(content()));
        assert!(matches!(served.now(), State::Opening { .. }));
        served.opened(Ok(content()));
        assert!(
            matches!(*changes.borrow(), State::Open(_)),
            "waiters see it open"
        );
        let State::Open(snapshot) = served.now() else {
            panic!("not open");
        };
        assert_eq!(
            (snapshot.version, served.take_failure().is_none()),
            (1, true)
        );
        served.reloaded(Err(Error::Usage("truncated".into())));
        let State::Open(snapshot) = served.now() else {
            panic!("not open");
        };
        assert_eq!(snapshot.problem.as_deref(), Some("truncated"));

        let failed = Served::opening("b.exr".into(), Instant::now(), "t".into(), 1, false);
        failed.opened(Err(Error::Usage("b.exr: not an image".into())));
        assert!(matches!(failed.now(), State::Opening { .. }));
        assert_eq!(
            failed.take_failure().map(|e| e.to_string()).as_deref(),
            Some("b.exr: not an image")
        );
        assert!(failed.take_failure().is_none(), "given once");
    }
}
