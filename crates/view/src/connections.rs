//! The accept loop every whitted server shares (`whitted view`, `whitted serve`): hyper 1
//! (HTTP/1 only) on a single-threaded tokio runtime, each connection a task, so that a client
//! that stalls costs one task, not the server. The limits:
//! - request line and headers: at most `max_head` bytes (hyper answers 431 past them), read
//!   within `head_timeout`;
//! - a connection lives at most `connection_time`, whatever it does (a client that never
//!   reads is cut off then);
//! - at most `max_connections` at once; others are answered 503 with Retry-After (busy.rs,
//!   itself bounded), and a failed accept (out of descriptors) is waited out, never a panic;
//! - replies are computed on at most `blocking_threads` blocking threads.
//!
//! What a request gets is the caller's service; what is in a body, and whether one is read at
//! all, is its business too.

use std::convert::Infallible;
use std::future::Future;
use std::net::IpAddr;
use std::sync::Arc;
use std::time::Duration;

use hyper::body::Incoming as Body;
use hyper::{Request, Response};
use hyper_util::rt::{TokioIo, TokioTimer};

use super::busy;
use super::held_body::HeldBody;
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
/// How often the accept loop looks for a signal and for the caller's reason to stop.
const POLL: Duration = Duration::from_millis(100);

/// A server's limits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    pub max_head: usize,
    pub head_timeout: Duration,
    pub connection_time: Duration,
    pub max_connections: usize,
    /// Threads that compute replies (`spawn_blocking`).
    pub blocking_threads: usize,
}

impl Limits {
    /// The viewer's, with `blocking_threads` threads for the replies.
    pub const fn with_threads(blocking_threads: usize) -> Limits {
        Limits {
            max_head: MAX_HEAD,
            head_timeout: HEAD_TIMEOUT,
            connection_time: CONNECTION_TIME,
            max_connections: MAX_CONNECTIONS,
            blocking_threads,
        }
    }
}

/// Serves `listener` within `limits`, each request answered by `service` (given the peer's
/// address), until a signal stops the process or `stop` gives a reason (an Err).
pub fn serve_connections<S, F>(
    listener: std::net::TcpListener,
    limits: Limits,
    mut stop: impl FnMut() -> Result<()>,
    service: S,
) -> Result<()>
where
    S: Fn(Request<Body>, IpAddr) -> F + Clone + Send + Sync + 'static,
    F: Future<Output = Response<HeldBody>> + Send + 'static,
{
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_io()
        .enable_time()
        .max_blocking_threads(limits.blocking_threads.max(1))
        .build()
        .map_err(|e| Error::Environment(format!("cannot start the server's runtime: {e}")))?;
    runtime.block_on(async move {
        listener
            .set_nonblocking(true)
            .map_err(|e| Error::Environment(format!("cannot listen: {e}")))?;
        let listener = tokio::net::TcpListener::from_std(listener)
            .map_err(|e| Error::Environment(format!("cannot listen: {e}")))?;
        let permits = Arc::new(tokio::sync::Semaphore::new(limits.max_connections));
        let turn_away_slots = Arc::new(tokio::sync::Semaphore::new(busy::TURNED_AWAY));
        loop {
            interrupt::check()?;
            stop()?;
            let accepted = match tokio::time::timeout(POLL, listener.accept()).await {
                Err(_) => continue,
                Ok(accepted) => accepted,
            };
            let Ok((stream, peer)) = accepted else {
                // Out of descriptors, or a connection reset before it was taken: wait and go
                // on serving the others.
                tokio::time::sleep(POLL).await;
                continue;
            };
            let Ok(permit) = permits.clone().try_acquire_owned() else {
                busy::turn_away(stream, &turn_away_slots);
                continue;
            };
            let service = service.clone();
            tokio::spawn(async move {
                let _permit = permit;
                let answer = hyper::service::service_fn(move |request: Request<Body>| {
                    let reply = service(request, peer.ip());
                    async move { Ok::<_, Infallible>(reply.await) }
                });
                let connection = hyper::server::conn::http1::Builder::new()
                    .timer(TokioTimer::new())
                    .header_read_timeout(limits.head_timeout)
                    .max_buf_size(limits.max_head)
                    .serve_connection(TokioIo::new(stream), answer);
                // A client that misbehaves or goes away ends its own connection only.
                let _ = tokio::time::timeout(limits.connection_time, connection).await;
            });
        }
    })
}
