//! Which replies may be computed now, and how much memory replies not yet sent may hold.
//!
//! Two rules, both enforced before any work:
//! - **Heavy replies take turns.** A whole layer, a layer's statistics and a pixel's ray trees
//!   can take most of a second each (a 1080p metric's statistics, a million-sphere scene's
//!   hierarchy); at most `HEAVY_AT_ONCE` of them run at a time, always one fewer than the
//!   worker threads, so that the cheap routes (the version the page polls, a probe, a tile)
//!   find a free worker however many heavy ones are asked for. The rest wait as tasks,
//!   holding no thread.
//! - **Unsent replies share a budget.** A reply is charged its size (known from the request
//!   before it is computed) against `REPLY_BUDGET`, and gives it back only when its last byte
//!   has left (`HeldBody` holds the charge): clients that ask for large layers and never read
//!   them stop being answered, rather than pinning the machine's memory until their
//!   connections time out. A reply larger than the whole budget is charged the whole budget,
//!   so that it can still be sent, alone. Replies of at most `FREE` bytes (the version, a
//!   probe, a tile of an RGBA layer) are not charged: `MAX_CONNECTIONS` of them hold little,
//!   and they must never queue behind a large layer waiting for the budget (the budget's
//!   queue is first come, first served).

use std::sync::Arc;
use std::time::Duration;

use tokio::sync::{OwnedSemaphorePermit, Semaphore};

/// The server's blocking worker threads, on which every reply is computed: the admission rules
/// are written in terms of them, so the count lives here and the server reads it.
pub const WORKERS: usize = 4;
/// Heavy replies computed at once: one fewer than the worker threads.
pub const HEAVY_AT_ONCE: usize = WORKERS - 1;
/// What replies computed but not yet sent may hold at once.
pub const REPLY_BUDGET: u64 = 256 << 20;
/// The budget's unit: replies are charged in whole units.
const UNIT: u64 = 64 << 10;
/// Replies up to this size are not charged (a 256 x 256 tile of four channels).
pub const FREE: u64 = 1 << 20;
/// How long a reply waits for its share of the budget before the client is told to come back.
pub const BUDGET_WAIT: Duration = Duration::from_secs(30);

/// The server's two gates.
pub struct Admission {
    heavy: Arc<Semaphore>,
    budget: Arc<Semaphore>,
    /// The budget in units (`REPLY_BUDGET` or less when this process may use less memory).
    units: u32,
    /// How long a reply waits for its charge (`BUDGET_WAIT`).
    wait: Duration,
}

impl Admission {
    pub fn new() -> Admission {
        let bytes = match whitted_core::memory::available_bytes() {
            Some(available) => REPLY_BUDGET.min(available / 4),
            None => REPLY_BUDGET,
        };
        Admission::with_budget(bytes, BUDGET_WAIT)
    }

    fn with_budget(bytes: u64, wait: Duration) -> Admission {
        let units = u32::try_from((bytes / UNIT).max(1)).unwrap_or(u32::MAX);
        Admission {
            heavy: Arc::new(Semaphore::new(HEAVY_AT_ONCE)),
            budget: Arc::new(Semaphore::new(units as usize)),
            units,
            wait,
        }
    }

    /// A turn for a heavy reply (waits while `HEAVY_AT_ONCE` others compute).
    pub async fn heavy_turn(&self) -> Option<OwnedSemaphorePermit> {
        self.heavy.clone().acquire_owned().await.ok()
    }

    /// The charge for a reply of `bytes` (nothing for a small one), or Err when it could not
    /// be had within `BUDGET_WAIT` (the unsent replies of other clients hold the budget).
    pub async fn charge(&self, bytes: u64) -> Result<Option<OwnedSemaphorePermit>, Busy> {
        if bytes <= FREE {
            return Ok(None);
        }
        let units = u32::try_from(bytes.div_ceil(UNIT))
            .unwrap_or(u32::MAX)
            .clamp(1, self.units);
        let wanted = self.budget.clone().acquire_many_owned(units);
        match tokio::time::timeout(self.wait, wanted).await {
            Ok(Ok(permit)) => Ok(Some(permit)),
            _ => Err(Busy),
        }
    }
}

/// The budget of unsent replies stayed full for `BUDGET_WAIT`.
#[derive(Debug)]
pub struct Busy;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn charges_wait_for_sent_replies_and_a_huge_reply_still_goes_alone() {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_time()
            .build()
            .expect("runtime");
        runtime.block_on(async {
            let admission = Admission::with_budget(64 << 20, Duration::from_millis(10));
            let whole = u64::from(admission.units) * UNIT;
            let first = admission.charge(whole / 2 + 1).await.expect("room");
            assert!(first.is_some());
            // The second half does not fit until the first reply is sent.
            assert!(admission.charge(whole / 2 + 1).await.is_err());
            drop(first);
            let huge = admission.charge(whole * 10).await.expect("alone");
            assert!(admission.charge(FREE + 1).await.is_err());
            // Small replies are never held up.
            assert!(matches!(admission.charge(FREE).await, Ok(None)));
            drop(huge);
            assert!(admission.charge(FREE + 1).await.expect("room").is_some());
        });
    }
}
