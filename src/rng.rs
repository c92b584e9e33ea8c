//! The lab's random numbers: the streams each construction draws from a block key, named once
//! (`stream_seed(stream, key)`: distinct streams of one key are independent, and a
//! construction's values change if its stream does, so the numbers are pinned by the golden
//! digests), PCG32 seeded from two of them, and the two draws the constructions share.

use rand::Rng;
use rand_pcg::Pcg32;
use strata::float::unit_f64_from_u64;
use strata::hash::stream_seed;

/// A construction's streams of a block key. Two constructions may use the same numbers (their
/// keys differ); one construction never uses a stream for two purposes.
pub(crate) mod streams {
    /// Dart throwing's generator (state, increment).
    pub(crate) const DART_THROWING: [u64; 2] = [1, 2];
    /// Bridson's generator.
    pub(crate) const BRIDSON: [u64; 2] = [3, 4];
    /// Lloyd's random start.
    pub(crate) const LLOYD_START: u64 = 5;
    /// CCVT's generator.
    pub(crate) const CCVT: [u64; 2] = [7, 8];
    /// Best candidate's generator.
    pub(crate) const BEST_CANDIDATE: [u64; 2] = [9, 10];
    /// BNOT's generator.
    pub(crate) const BNOT: [u64; 2] = [11, 12];
    /// The PMJ construction's generator.
    pub(crate) const PMJ: [u64; 2] = [1, 2];
    /// The PMJ construction's candidate keys.
    pub(crate) const PMJ_CANDIDATES: u64 = 3;
    /// The blue-noise PMJ construction's two keys.
    pub(crate) const PMJBN: [u64; 2] = [0x0b10, 0x0b11];
    /// The blue-noise PMJ construction's keys of its deep levels.
    pub(crate) const PMJBN_DEEP: [u64; 2] = [0x0b12, 0x0b13];
    /// The blue-noise (0,m,2)-net's seed.
    pub(crate) const NET02BN: u64 = 0x0602;
    /// The blue-noise (0,m,2)-net's sweeps: sweep `s` draws stream `NET02BN_SWEEPS + s`.
    pub(crate) const NET02BN_SWEEPS: u64 = 0x0603;
    /// The blue-noise table optimiser's generator.
    pub(crate) const BNTABLE: [u64; 2] = [0x0b70, 0x0b71];
    /// The test integrands of a table's figures.
    pub(crate) const BNTABLE_TESTS: [u64; 2] = [0x0b72, 0x0b73];
    /// The random entries a table's figures compare it with.
    pub(crate) const BNTABLE_RANDOM: [u64; 2] = [0x0b74, 0x0b75];
}

/// PCG32 seeded from two streams of `key` (state and increment).
pub(crate) fn pcg(key: u64, streams: [u64; 2]) -> Pcg32 {
    Pcg32::new(stream_seed(streams[0], key), stream_seed(streams[1], key))
}

/// A uniform `f64` in `[0, 1)` from the generator.
pub(crate) fn uniform(rng: &mut Pcg32) -> f64 {
    unit_f64_from_u64(rng.next_u64())
}

/// A uniform index in `[0, len)`.
pub(crate) fn below(rng: &mut Pcg32, len: usize) -> usize {
    ((rng.next_u32() as u64 * len as u64) >> 32) as usize
}
