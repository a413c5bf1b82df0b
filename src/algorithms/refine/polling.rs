//! Cancel and progress polling of a refinement run: the caller's `cancel` and `progress`
//! hooks, asked now and then (the driver makes it, the loop polls it).

use super::Quality;
use crate::data::{Phase, Progress, ProgressFn};

/// Cancel and progress polling: the caller's `cancel` every 64 steps (once it says so, for
/// good), `progress` every 1024.
pub(super) struct Polling<'q> {
    cancel: Option<&'q (dyn Fn() -> bool + Sync + 'q)>,
    progress: Option<&'q ProgressFn<'q>>,
    polls: u32,
    cancelled: bool,
}

impl<'q> Polling<'q> {
    pub(super) fn new(quality: &Quality<'q>) -> Self {
        Polling {
            cancel: quality.cancel,
            progress: quality.progress,
            polls: 0,
            cancelled: false,
        }
    }

    /// Whether the caller has cancelled.
    pub(super) fn cancelled(&self) -> bool {
        self.cancelled
    }

    /// One step of refinement, with `done` Steiner points made and `waiting()` splits queued:
    /// tells the caller of the progress now and then, asks whether to cancel now and then, and
    /// returns whether the caller has cancelled.
    pub(super) fn poll(&mut self, done: u64, waiting: impl FnOnce() -> usize) -> bool {
        if self.cancelled {
            return true;
        }
        self.polls = self.polls.wrapping_add(1);
        if self.polls % 1024 == 0 {
            if let Some(progress) = self.progress {
                progress(Progress {
                    phase: Phase::Refinement,
                    done,
                    estimate: done + waiting() as u64,
                });
            }
        }
        if self.polls % 64 == 0 && self.cancel.is_some_and(|cancelled| cancelled()) {
            self.cancelled = true;
        }
        self.cancelled
    }
}
