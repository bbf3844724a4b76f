//! `whitted view`: a local web viewer for AOV renders. It binds 127.0.0.1 only, prints its URL
//! (with a per-run random token) as the first line on stdout, refuses any request whose Host
//! header is not the loopback address it listens on (DNS rebinding) or that lacks the token,
//! and serves nothing but its page and the given images' layers. The page (`view/page/`,
//! plain files compiled into the binary: no build chain, no CDN) does the tone mapping,
//! probing, relighting and A/B comparison in the browser.
//!
//! tiny_http is the server: small, synchronous and maintained, and a viewer for one person on
//! one machine needs no async runtime.

mod api;
mod token;

use std::io::Write;
use std::time::Duration;

use crate::error::{Error, Result};
use crate::input::Image;
use crate::interrupt;

pub use api::respond;

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
    let server = tiny_http::Server::http(("127.0.0.1", port))
        .map_err(|e| Error::Usage(format!("cannot listen on 127.0.0.1:{port}: {e}")))?;
    let port = server
        .server_addr()
        .to_ip()
        .map(|a| a.port())
        .ok_or_else(|| Error::Usage("the server has no IP address".into()))?;
    let served = Served {
        main,
        reference,
        token: token::new(),
        port,
    };
    let url = format!("http://127.0.0.1:{port}/?token={}", served.token);
    crate::output::stdout::print_line(&url)?;
    let _ = std::io::stdout().flush();
    if !no_browser {
        // Best effort: a desktop opens it; elsewhere the URL above is the way in.
        let _ = std::process::Command::new("xdg-open")
            .arg(&url)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn();
    }
    loop {
        interrupt::check()?;
        match server.recv_timeout(Duration::from_millis(100)) {
            Ok(Some(request)) => respond(&served, request),
            Ok(None) => {}
            Err(e) => return Err(Error::io("127.0.0.1", "cannot accept a request", e)),
        }
    }
}
