//! The thin adapter between hyper and the viewer's pure request -> reply functions, on the
//! accept loop and limits every whitted server shares (`connections.rs`: the request head's
//! size and time, connections at once, a connection's lifetime). Besides:
//! - no body is read or buffered, ever: a request that announces one gets 413 (hyper then
//!   closes the connection rather than read what was announced);
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

use std::sync::Arc;
use std::time::Duration;

use hyper::body::Incoming as Body;
use hyper::header::{HeaderValue, CONTENT_LENGTH, HOST, TRANSFER_ENCODING};
use hyper::{Request, Response};

use super::admission::{Admission, WORKERS};
use super::connections::{serve_connections, Limits};
use super::held_body::HeldBody;
use super::request::{parse, ApiRequest, Incoming};
use super::{api, text, Reply, Served, State};
use whitted_core::error::Result;

const OPEN_TIMEOUT: Duration = Duration::from_secs(60);

/// Serves `served` on `listener` until a signal stops the process, or the first load fails.
pub fn run(listener: std::net::TcpListener, served: Arc<Served>) -> Result<()> {
    let admission = Arc::new(Admission::new());
    let watched = served.clone();
    let stop = move || match watched.take_failure() {
        Some(failure) => Err(failure),
        None => Ok(()),
    };
    let service = move |request: Request<Body>, _peer| {
        let served = served.clone();
        let admission = admission.clone();
        async move {
            let head = request.method() == hyper::Method::HEAD;
            let response = match checked(&served, &request) {
                Ok(api_request) => answer(served, &admission, api_request).await,
                Err(refusal) => (refusal, None, None),
            };
            self::response(response, head)
        }
    };
    serve_connections(listener, Limits::with_threads(WORKERS), stop, service)
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
