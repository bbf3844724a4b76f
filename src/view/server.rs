//! The thin adapter between hyper and the viewer's pure request -> reply functions. hyper 1
//! (HTTP/1 only) on a single-threaded tokio runtime: each connection is a task, so a client
//! that stalls costs one task, not the server. The limits:
//! - request line and headers: at most `MAX_HEAD` bytes (hyper answers 431 past them), read
//!   within `HEAD_TIMEOUT`;
//! - no body is read or buffered, ever: a request that announces one gets 413 (hyper then
//!   closes the connection rather than read what was announced);
//! - a connection lives at most `CONNECTION_TIME`, whatever it does (a client that never
//!   reads a layer is cut off then);
//! - at most `MAX_CONNECTIONS` at once; others are closed at once, and a failed accept (out
//!   of descriptors) is waited out, never a panic;
//! - each reply is computed on one of `WORKERS` blocking threads, so that a slow one (a 4K
//!   layer's statistics) does not hold up the others, nor the accept loop;
//! - while the first load runs, a request that needs its content (any but the page and the
//!   version) waits for it as a task, holding no worker, for at most `OPEN_TIMEOUT` (then
//!   503; a failed first load stops the server sooner), so that a client asking at once gets
//!   the answer it would have got later.

use std::convert::Infallible;
use std::sync::Arc;
use std::time::Duration;

use http_body_util::Full;
use hyper::body::{Bytes, Incoming as Body};
use hyper::header::{HeaderValue, CONTENT_LENGTH, HOST, TRANSFER_ENCODING};
use hyper::{Request, Response};
use hyper_util::rt::{TokioIo, TokioTimer};

use super::request::{parse, ApiRequest, Incoming};
use super::{api, text, Reply, Served, State};
use crate::error::{Error, Result};
use crate::interrupt;

const MAX_HEAD: usize = 16 * 1024;
const HEAD_TIMEOUT: Duration = Duration::from_secs(10);
const CONNECTION_TIME: Duration = Duration::from_secs(120);
const MAX_CONNECTIONS: usize = 64;
const WORKERS: usize = 4;
const OPEN_TIMEOUT: Duration = Duration::from_secs(60);
/// How often the accept loop looks for Ctrl-C.
const POLL: Duration = Duration::from_millis(100);

/// Serves `served` on `listener` until a signal stops the process, or the first load fails.
pub fn run(listener: std::net::TcpListener, served: Arc<Served>) -> Result<()> {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_io()
        .enable_time()
        .max_blocking_threads(WORKERS)
        .build()
        .map_err(|e| Error::io("127.0.0.1", "cannot start the viewer's runtime", e))?;
    runtime.block_on(async move {
        listener
            .set_nonblocking(true)
            .map_err(|e| Error::io("127.0.0.1", "cannot listen", e))?;
        let listener = tokio::net::TcpListener::from_std(listener)
            .map_err(|e| Error::io("127.0.0.1", "cannot listen", e))?;
        let permits = Arc::new(tokio::sync::Semaphore::new(MAX_CONNECTIONS));
        loop {
            interrupt::check()?;
            if let Some(failure) = served.take_failure() {
                return Err(failure);
            }
            let accepted = match tokio::time::timeout(POLL, listener.accept()).await {
                Err(_) => continue,
                Ok(accepted) => accepted,
            };
            let Ok((stream, _)) = accepted else {
                // Out of descriptors, or a connection reset before it was taken: wait and go
                // on serving the others.
                tokio::time::sleep(POLL).await;
                continue;
            };
            let Ok(permit) = permits.clone().try_acquire_owned() else {
                drop(stream);
                continue;
            };
            let served = served.clone();
            tokio::spawn(async move {
                let _permit = permit;
                let service = hyper::service::service_fn(move |request: Request<Body>| {
                    let served = served.clone();
                    async move {
                        let head = request.method() == hyper::Method::HEAD;
                        let parsed = checked(&served, &request);
                        if parsed.as_ref().is_ok_and(ApiRequest::needs_content) {
                            let mut changes = served.changes();
                            let open = changes.wait_for(|s| matches!(s, State::Open(_)));
                            let _ = tokio::time::timeout(OPEN_TIMEOUT, open).await;
                        }
                        let reply = tokio::task::spawn_blocking(move || match parsed {
                            Ok(api_request) => api::respond(&served.now(), &api_request),
                            Err(refusal) => refusal,
                        })
                        .await
                        .unwrap_or_else(|_| text(500, "internal error"));
                        Ok::<_, Infallible>(response(reply, head))
                    }
                });
                let connection = hyper::server::conn::http1::Builder::new()
                    .timer(TokioTimer::new())
                    .header_read_timeout(HEAD_TIMEOUT)
                    .max_buf_size(MAX_HEAD)
                    .serve_connection(TokioIo::new(stream), service);
                // A client that misbehaves or goes away ends its own connection only.
                let _ = tokio::time::timeout(CONNECTION_TIME, connection).await;
            });
        }
    })
}

/// The request parsed and checked (token, Host, no body), or the refusal.
fn checked(served: &Served, request: &Request<Body>) -> std::result::Result<ApiRequest, Reply> {
    let headers = request.headers();
    let announced = headers
        .get(CONTENT_LENGTH)
        .is_some_and(|v| v.as_bytes() != b"0")
        || headers.contains_key(TRANSFER_ENCODING);
    let incoming = Incoming {
        method: request.method().as_str(),
        path: request.uri().path(),
        query: request.uri().query().unwrap_or(""),
        hosts: headers
            .get_all(HOST)
            .iter()
            .map(HeaderValue::as_bytes)
            .collect(),
        authority: request.uri().authority().map(|a| a.as_str()),
        has_body: announced,
    };
    parse(&incoming, &served.token, served.port)
}

/// A reply as hyper wants it (without its body for a HEAD request).
fn response((status, kind, body): Reply, head: bool) -> Response<Full<Bytes>> {
    let body = if head { Vec::new() } else { body };
    let mut response = Response::new(Full::new(Bytes::from(body)));
    *response.status_mut() =
        hyper::StatusCode::from_u16(status).unwrap_or(hyper::StatusCode::INTERNAL_SERVER_ERROR);
    let headers = response.headers_mut();
    for (name, value) in [
        (hyper::header::CONTENT_TYPE, kind),
        (hyper::header::CACHE_CONTROL, "no-store"),
        (hyper::header::X_CONTENT_TYPE_OPTIONS, "nosniff"),
    ] {
        headers.insert(name, HeaderValue::from_static(value));
    }
    response
}
