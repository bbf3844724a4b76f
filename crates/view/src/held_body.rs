//! A reply body that hands hyper its bytes a chunk at a time and holds the reply's charge
//! against the budget (`admission.rs`) until the last chunk is taken. hyper asks for the next
//! chunk only when its write buffer has room, so the bytes a client has not read stay here,
//! counted, instead of in hyper's queue, uncounted. Each chunk is a copy, not a slice of the
//! reply: a slice would keep the whole reply alive in hyper's queue after the charge is given
//! back; a copy leaves at most hyper's queue (a few chunks) uncounted.

use std::convert::Infallible;
use std::pin::Pin;
use std::task::{Context, Poll};

use hyper::body::{Body, Bytes, Frame, SizeHint};
use tokio::sync::OwnedSemaphorePermit;

/// What hyper is handed at a time.
const CHUNK: usize = 64 << 10;

pub struct HeldBody {
    bytes: Vec<u8>,
    /// How much of `bytes` hyper has taken.
    sent: usize,
    charge: Option<OwnedSemaphorePermit>,
}

impl HeldBody {
    pub fn new(bytes: Vec<u8>, charge: Option<OwnedSemaphorePermit>) -> HeldBody {
        HeldBody {
            bytes,
            sent: 0,
            charge,
        }
    }
}

impl Body for HeldBody {
    type Data = Bytes;
    type Error = Infallible;

    fn poll_frame(
        mut self: Pin<&mut Self>,
        _: &mut Context<'_>,
    ) -> Poll<Option<Result<Frame<Bytes>, Infallible>>> {
        let body = &mut *self;
        if body.sent == body.bytes.len() {
            return Poll::Ready(None);
        }
        let end = body.bytes.len().min(body.sent + CHUNK);
        let chunk = Bytes::copy_from_slice(&body.bytes[body.sent..end]);
        body.sent = end;
        if body.sent == body.bytes.len() {
            // Every byte is in hyper's hands now: the reply's memory and charge go back.
            body.bytes = Vec::new();
            body.sent = 0;
            body.charge = None;
        }
        Poll::Ready(Some(Ok(Frame::data(chunk))))
    }

    fn is_end_stream(&self) -> bool {
        self.sent == self.bytes.len()
    }

    fn size_hint(&self) -> SizeHint {
        SizeHint::with_exact((self.bytes.len() - self.sent) as u64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;
    use tokio::sync::Semaphore;

    #[test]
    fn hands_out_every_byte_in_chunks_and_gives_the_charge_back_at_the_end() {
        let budget = Arc::new(Semaphore::new(4));
        let charge = budget
            .clone()
            .try_acquire_many_owned(4)
            .expect("the budget");
        let bytes: Vec<u8> = (0..CHUNK * 2 + 7).map(|i| i as u8).collect();
        let mut body = HeldBody::new(bytes.clone(), Some(charge));
        assert_eq!(body.size_hint().exact(), Some(bytes.len() as u64));
        let mut context = Context::from_waker(std::task::Waker::noop());
        let mut seen = Vec::new();
        while let Poll::Ready(Some(Ok(frame))) = Pin::new(&mut body).poll_frame(&mut context) {
            let data = frame.into_data().expect("data");
            assert!(data.len() <= CHUNK);
            // Held while any byte is still to be taken.
            if seen.len() + data.len() < bytes.len() {
                assert_eq!(budget.available_permits(), 0);
            }
            seen.extend_from_slice(&data);
        }
        assert_eq!(seen, bytes);
        assert!(body.is_end_stream());
        assert_eq!(budget.available_permits(), 4);
    }
}
