//! The position of a progressive sampler in its endless stream.
//!
//! A progressive sequence has a finite length (`2^32` points for the digital and PMJ
//! sequences, whose indices are 32-bit; less for best candidate, whose cost grows with its
//! length). [`Sampler::next_sample`](crate::Sampler::next_sample) never ends, so when a sequence
//! is exhausted the sampler starts a new epoch: a fresh, independent sequence keyed by
//! `stream_seed(epoch, seed)`. Every progressive sampler counts its samples with an [`Epochs`].

use crate::hash::stream_seed;
use crate::sampler::Seed;

/// The most samples a progressive sequence holds before it starts over with a new seed:
/// `2^32` (its indices are 32-bit).
pub const MAX_SEQUENCE_LEN: u64 = 1 << 32;

/// Sample `next` of epoch `epoch` of a progressive sampler whose sequences hold `len` points.
#[derive(Clone, Debug)]
pub struct Epochs {
    seed: u64,
    len: u64,
    epoch: u64,
    next: u64,
}

impl Epochs {
    /// The start of the stream of sequences of `len` points each (at least 1: a `len` of 0
    /// is taken as 1, since a sequence of no points has no next sample).
    pub fn new(len: u64, seed: Seed) -> Self {
        Epochs {
            seed: seed.0,
            len: len.max(1),
            epoch: 0,
            next: 0,
        }
    }

    /// The key of epoch `epoch`.
    pub fn key(&self, epoch: u64) -> u64 {
        stream_seed(epoch, self.seed)
    }

    /// The index (inside its sequence) of the next sample, and the key of the new epoch when
    /// that sample starts one (never for the first epoch: the sampler set it up itself).
    #[inline]
    pub fn advance(&mut self) -> (u64, Option<u64>) {
        let (start, _, key) = self.take(1);
        (start, key)
    }

    /// Moves `n` samples on, as `n` calls of [`advance`](Epochs::advance) would. Returns the
    /// epoch it ends in when that differs from the one it started in (the sampler must then
    /// re-key: epoch 0 with its initial key, a later one with [`key`](Epochs::key)).
    pub(crate) fn skip(&mut self, n: u64) -> Option<u64> {
        // absolute position, in samples taken; a full epoch stays "exhausted" (next == len)
        // so that the next take starts the following epoch with its key, as advance does
        let p = (self.epoch as u128) * (self.len as u128) + self.next as u128 + n as u128;
        let len = self.len as u128;
        let (mut e, mut next) = (p / len, p % len);
        if next == 0 && e > 0 {
            e -= 1;
            next = len;
        }
        let e = u64::try_from(e).unwrap_or(u64::MAX);
        let changed = e != self.epoch;
        self.epoch = e;
        self.next = next as u64;
        changed.then_some(e)
    }

    /// Up to `max` (>= 1) next samples inside one sequence: the first index, how many, and the
    /// key of the new epoch when they start one.
    #[inline]
    pub(crate) fn take(&mut self, max: u64) -> (u64, u64, Option<u64>) {
        let mut key = None;
        if self.next == self.len {
            self.epoch += 1;
            self.next = 0;
            key = Some(self.key(self.epoch));
        }
        let start = self.next;
        let count = max.min(self.len - start);
        self.next += count;
        (start, count, key)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn epochs_restart_with_fresh_keys() {
        let mut e = Epochs::new(3, Seed(5));
        let got: Vec<_> = (0..7).map(|_| e.advance()).collect();
        assert_eq!(got[..3], [(0, None), (1, None), (2, None)]);
        assert_eq!(got[3], (0, Some(stream_seed(1, 5))));
        assert_eq!(got[6], (0, Some(stream_seed(2, 5))));
        // skipping equals taking, across epochs
        for n in 0..25u64 {
            let (mut a, mut b) = (Epochs::new(3, Seed(5)), Epochs::new(3, Seed(5)));
            let mut last = 0;
            for _ in 0..n {
                if let (_, Some(_)) = a.advance() {
                    last += 1;
                }
            }
            let moved = b.skip(n);
            assert_eq!(moved.unwrap_or(0), last, "n = {n}");
            assert_eq!(a.advance(), {
                let (i, key) = b.advance();
                (i, key)
            });
        }
        let mut e = Epochs::new(10, Seed(5));
        assert_eq!(e.take(4), (0, 4, None));
        assert_eq!(e.take(100), (4, 6, None));
        assert_eq!(e.take(100), (0, 10, Some(stream_seed(1, 5))));
    }

    #[test]
    fn a_sequence_of_no_points_is_taken_as_one() {
        // (was: index 0 of an empty sequence and a new epoch at the first call, and a division
        // by zero in skip)
        let mut e = Epochs::new(0, Seed(5));
        assert_eq!(e.advance(), (0, None));
        assert_eq!(e.advance(), (0, Some(stream_seed(1, 5))));
        assert_eq!(e.skip(3), Some(4));
    }
}
