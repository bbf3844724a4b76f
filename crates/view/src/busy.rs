//! The answer to a connection past the limit of connections at once: `503 Service
//! Unavailable` with `Retry-After`, not a closed socket. A class of 300 polling one service
//! met "connection reset by peer" when connections were simply dropped; a browser shows a
//! reset as a broken site, while a 503 is retried by the pages' poller and says what is
//! happening to anyone who reads it.
//!
//! The turned-away connections are themselves bounded (`TURNED_AWAY` at once, each for at
//! most `TURN_AWAY_TIME`): past that, a flood is dropped as before, so answering it never
//! costs more than a fixed number of descriptors and tasks.

use std::sync::Arc;
use std::time::Duration;

use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use tokio::sync::Semaphore;

/// Turned-away connections being answered at once, past which they are dropped.
pub const TURNED_AWAY: usize = 256;
/// How long one turned-away connection is given, all in all.
const TURN_AWAY_TIME: Duration = Duration::from_secs(2);
/// How much of a turned-away request is read (and discarded) before answering, so that the
/// answer is not lost to a reset of unread input when the socket closes.
const READ_AT_MOST: usize = 64 * 1024;

const ANSWER: &[u8] = b"HTTP/1.1 503 Service Unavailable\r\n\
Retry-After: 2\r\n\
Content-Type: text/plain; charset=utf-8\r\n\
Content-Length: 60\r\n\
Cache-Control: no-store\r\n\
Connection: close\r\n\r\n\
busy: too many connections at once; try again in a moment.\r\n";

/// Answers `stream` with 503 in the background if a turn-away slot is free; drops it if not.
pub fn turn_away(stream: TcpStream, slots: &Arc<Semaphore>) {
    let Ok(slot) = slots.clone().try_acquire_owned() else {
        return;
    };
    tokio::spawn(async move {
        let _slot = slot;
        let _ = tokio::time::timeout(TURN_AWAY_TIME, answer(stream)).await;
    });
}

async fn answer(mut stream: TcpStream) -> std::io::Result<()> {
    let mut head = Vec::new();
    let mut buffer = [0u8; 4096];
    // Up to the end of the request head (or what arrives first), so the client has sent its
    // request before it reads the answer.
    while head.len() < READ_AT_MOST && !head.windows(4).any(|w| w == b"\r\n\r\n") {
        match stream.read(&mut buffer).await? {
            0 => break,
            n => head.extend_from_slice(&buffer[..n]),
        }
    }
    stream.write_all(ANSWER).await?;
    stream.shutdown().await?;
    // A body still coming is read away until the client closes (or time runs out), so
    // closing with unread input does not reset the connection before the answer is read.
    let mut left = READ_AT_MOST;
    while left > 0 {
        match stream.read(&mut buffer).await? {
            0 => break,
            n => left = left.saturating_sub(n),
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_answer_declares_its_body_length() {
        let text = std::str::from_utf8(ANSWER).expect("ascii");
        let (head, body) = text.split_once("\r\n\r\n").expect("head and body");
        assert!(
            head.contains(&format!("Content-Length: {}", body.len())),
            "{text}"
        );
        assert!(head.starts_with("HTTP/1.1 503 "));
    }
}
