//! `whitted view`: a local web viewer for AOV renders. It binds 127.0.0.1 only, prints its URL
//! (with a per-run random token) as the first line on stdout, refuses any request whose Host
//! header is not the loopback address it listens on (DNS rebinding) or that lacks the token,
//! and serves nothing but its page and the given images' layers. The page (`view/page/`,
//! plain files compiled into the binary: no build chain, no CDN) does the tone mapping,
//! probing, relighting and A/B comparison in the browser.
//!
//! The server is hyper behind a thin adapter (`view/server.rs`, which says why and with which
//! limits); every request is parsed into a closed set first (`view/request.rs`) and answered
//! by a pure function (`view/api.rs`).

mod api;
mod request;
mod server;
mod token;

use std::io::Write;

use crate::error::{Error, Result};
use crate::input::Image;

pub use api::respond;
pub use request::{parse, ApiRequest, Incoming, Which};

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

/// The images the viewer serves: the render and, optionally, a reference for A/B.
pub struct Served {
    pub main: Image,
    pub reference: Option<Image>,
    /// The token every request must carry.
    pub token: String,
    /// The port it listens on, for the Host check.
    pub port: u16,
}

/// Listens on 127.0.0.1:`port` (0 for any free port), prints the URL, opens a browser unless
/// `no_browser`, and serves until a signal stops it.
pub fn serve(main: Image, reference: Option<Image>, port: u16, no_browser: bool) -> Result<()> {
    let listener = std::net::TcpListener::bind(("127.0.0.1", port))
        .map_err(|e| Error::Environment(format!("cannot listen on 127.0.0.1:{port}: {e}")))?;
    let port = listener
        .local_addr()
        .map_err(|e| Error::io("127.0.0.1", "cannot listen", e))?
        .port();
    let served = Served {
        main,
        reference,
        token: token::new(),
        port,
    };
    let url = format!("http://127.0.0.1:{port}/?token={}", served.token);
    crate::output::stdout::print_line(&url)?;
    let _ = std::io::stdout().flush();
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
