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
//!   layer's statistics) does not hold up the accept loop; heavy replies take turns and
//!   unsent replies share a memory budget (`admission.rs`), so that the cheap routes never
//!   queue behind heavy ones and clients that never read cannot pin the machine's memory;
//! - every reply computed from the files says which load it came from (`X-Whitted-Version`),
//!   so that the page never mixes the tiles of two versions;
//! - while the first load runs, a request that needs its content (any but the page and the
//!   version) waits for it as a task, holding no worker, for at most `OPEN_TIMEOUT` (then
//!   503; a failed first load stops the server sooner), so that a client asking at once gets
//!   the answer it would have got later.

use std::convert::Infallible;
use std::sync::Arc;
use std::time::Duration;

use hyper::body::Incoming as Body;
use hyper::header::{HeaderValue, CONTENT_LENGTH, HOST, TRANSFER_ENCODING};
use hyper::{Request, Response};
use hyper_util::rt::{TokioIo, TokioTimer};

use super::admission::{Admission, WORKERS};
use super::held_body::HeldBody;
use super::request::{parse, ApiRequest, Incoming};
use super::{api, text, Reply, Served, State};
use whitted_core::error::{Error, Result};
use whitted_core::interrupt;

/// The request line and headers' bytes at most.
pub const MAX_HEAD: usize = 16 * 1024;
/// How long the request line and headers may take to arrive.
pub const HEAD_TIMEOUT: Duration = Duration::from_secs(10);
/// How long a connection may live, whatever it does.
pub const CONNECTION_TIME: Duration = Duration::from_secs(120);
/// Connections served at once.
pub const MAX_CONNECTIONS: usize = 64;
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
        let admission = Arc::new(Admission::new());
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
            let admission = admission.clone();
            tokio::spawn(async move {
                let _permit = permit;
                let service = hyper::service::service_fn(move |request: Request<Body>| {
                    let served = served.clone();
                    let admission = admission.clone();
                    async move {
                        let head = request.method() == hyper::Method::HEAD;
                        let response = match checked(&served, &request) {
                            Ok(api_request) => answer(served, &admission, api_request).await,
                            Err(refusal) => (refusal, None, None),
                        };
                        Ok::<_, Infallible>(self::response(response, head))
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

/// The reply to a checked request, the version of the files it was computed from, and its
/// charge against the budget of unsent replies.
async fn answer(
    served: Arc<Served>,
    admission: &Admission,
    request: ApiRequest,
) -> (
    Reply,
    Option<u64>,
    Option<tokio::sync::OwnedSemaphorePermit>,
) {
    if request.needs_content() {
        let mut changes = served.changes();
        let open = changes.wait_for(|s| matches!(s, State::Open(_)));
        let _ = tokio::time::timeout(OPEN_TIMEOUT, open).await;
    }
    let turn = match request.is_heavy() {
        true => admission.heavy_turn().await,
        false => None,
    };
    // One snapshot for the whole reply: a reload meanwhile does not change it under it.
    let state = served.now();
    let Ok(charge) = admission.charge(api::reply_bytes(&state, &request)).await else {
        return (
            text(
                503,
                "service unavailable: replies other clients have not read yet hold the viewer's \
                 memory; ask again shortly",
            ),
            None,
            None,
        );
    };
    let version = match &state {
        State::Open(now) => Some(now.version),
        State::Opening { .. } => None,
    };
    let reply = tokio::task::spawn_blocking(move || api::respond(&state, &request))
        .await
        .unwrap_or_else(|_| text(500, "internal error"));
    drop(turn);
    (reply, version, charge)
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
fn response(
    ((status, kind, body), version, charge): (
        Reply,
        Option<u64>,
        Option<tokio::sync::OwnedSemaphorePermit>,
    ),
    head: bool,
) -> Response<HeldBody> {
    let body = if head { Vec::new() } else { body };
    let mut response = Response::new(HeldBody::new(body, charge));
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
    if let Some(version) = version {
        headers.insert("x-whitted-version", HeaderValue::from(version));
    }
    response
}
