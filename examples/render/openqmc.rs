//! A reference sampler from OpenQMC, written here (not in the library) so that `render` can set
//! the crate's blue-noise sequence beside it: `oqmc::SobolBnSampler`, the blue-noise Owen-
//! scrambled Sobol' of OpenQMC (Framestore; `AcademySoftwareFoundation/openqmc` at commit
//! `294d65627f667b668373250a751862232cf21d65`, Apache-2.0, `LICENSE-openqmc` beside this file:
//! `include/oqmc/{sobolbn.h, bntables.h, state.h, pcg.h, owen.h, permute.h, encode.h,
//! float.h}`), with its key and rank tables (`include/oqmc/data/sobol/{keys,ranks}.txt`, as
//! little-endian `u32` in `openqmc/sobol_{keys,ranks}.bin`: see `openqmc/PROVENANCE.md`).
//! Checked bit for bit against vectors printed by OpenQMC's own headers compiled with
//! `g++ -std=c++17` (`tests/lab/render_openqmc.rs`, `tests/lab/openqmc_vectors.txt`).
//!
//! The draw (`SobolBnImpl::drawSample`): the state is a pattern id (an LCG state: the frame plus
//! the index's bits above 16, then one LCG step per `newDomain(key)` of `key` added), the
//! sample id (the index's low 16 bits) and the pixel id (`x mod 256`, `y mod 256`). The pattern
//! id's PCG output gives a toroidal shift of the 256 x 256 table; the entry there gives a key
//! and a rank (below 128); the sample is Sobol' dimensions 0-3 at `sample ^ rank`, the index
//! Owen-shuffled and each dimension Owen-scrambled under the key (rotated by a byte per
//! dimension), 16 Sobol' digits and 16 hashed ones.
//!
//! How `render`'s draws map to OpenQMC's domains, after OpenQMC's own path tracer
//! (`src/tools/lib/trace.cpp`: a camera domain `root.newDomain(0)` with the film position at
//! its key 0 and the lens at key 1, a chain of bounce domains from `root.newDomain(1)`, a draw
//! per key of a bounce): the camera block's draw at dimension `d` reads `camera.newDomain(d)`
//! (the film position at key 0, the lens at 2, the time at 4; `trace.cpp` puts the time in the
//! lens's domain, as its third dimension), bounce `k`'s draw at offset `o` reads
//! `trace_k.newDomain(o)`, with `trace_0 = root.newDomain(1)` and `trace_(k+1) =
//! trace_k.newDomain(per_bounce)` (the per-bounce keys 0 to 7 and the chain's step apart, as
//! `trace.cpp`'s 0-3 and 4). A 2D draw takes components 0 and 1 of its domain, a 1D draw
//! component 0. The seed is OpenQMC's `frame`, as `seed * 65536` (wrapping): the frame is added
//! to the pattern id, so that consecutive frames would share domains (frame `f + 1`'s domain
//! `k - 1` is frame `f`'s domain `k`); frames 65536 apart share none below 65536 samples.

// Each item is used by `render` or by the test that includes this file alone
// (`tests/lab/render_openqmc.rs`); neither uses all of them.
#![allow(dead_code)]

/// `bntables::sobol::keyTable`, 65536 little-endian `u32`.
static KEYS: &[u8] = include_bytes!("openqmc/sobol_keys.bin");
/// `bntables::sobol::rankTable`, 65536 little-endian `u32`.
static RANKS: &[u8] = include_bytes!("openqmc/sobol_ranks.bin");

const _: () = assert!(KEYS.len() == 4 << 16 && RANKS.len() == 4 << 16);

/// Element `i` of a table.
#[inline]
fn table(bytes: &[u8], i: usize) -> u32 {
    u32::from_le_bytes([
        bytes[4 * i],
        bytes[4 * i + 1],
        bytes[4 * i + 2],
        bytes[4 * i + 3],
    ])
}

/// pcg.h `stateTransition`: one LCG step.
#[inline]
pub const fn lcg(state: u32) -> u32 {
    state.wrapping_mul(747_796_405).wrapping_add(2_891_336_453)
}

/// pcg.h `output`: the PCG RXS-M-XS output permutation.
#[inline]
pub const fn pcg_output(mut state: u32) -> u32 {
    state ^= state >> (4 + (state >> 28));
    state = state.wrapping_mul(277_803_737);
    state ^ (state >> 22)
}

/// permute.h `laineKarrasPermutation` (Vegdahl's constants).
#[inline]
pub const fn laine_karras(mut value: u32, seed: u32) -> u32 {
    value ^= value.wrapping_mul(0x3d20_adea);
    value = value.wrapping_add(seed);
    value = value.wrapping_mul((seed >> 16) | 1);
    value ^= value.wrapping_mul(0x0552_6c56);
    value ^ value.wrapping_mul(0x53a2_2864)
}

/// owen.h `sobolReversedIndex` (the scalar path): Sobol' dimension `dimension` (0 to 3) at a
/// bit-reversed 16-bit index, bit-reversed.
#[inline]
pub fn sobol_reversed_index(index: u16, dimension: u32) -> u16 {
    let mut index = index.reverse_bits();
    match dimension {
        1 => {
            index ^= (index & 0xff00) >> 8;
            index ^= (index & 0xf0f0) >> 4;
            index ^= (index & 0xcccc) >> 2;
            index ^= (index & 0xaaaa) >> 1;
        }
        2 => {
            index ^= (index & 0xc000) >> 14;
            index ^= (index & 0x2000) >> 13;
            index ^= (index & 0xf000) >> 12;
            index ^= (index & 0xcc00) >> 10;
            index ^= (index & 0xaa00) >> 9;
            index ^= (index & 0x0c00) >> 8;
            index ^= (index & 0xc0c0) >> 6;
            index ^= (index & 0xa0a0) >> 5;
            index ^= (index & 0xcf30) >> 4;
            index ^= (index & 0x8888) >> 3;
            index ^= (index & 0xf0f0) >> 2;
            index ^= (index & 0x6666) >> 1;
        }
        3 => {
            index ^= (index & 0xf000) >> 12;
            index ^= (index & 0x0c00) >> 10;
            index ^= (index & 0x0a00) >> 9;
            index ^= (index & 0xfe00) >> 8;
            index ^= (index & 0x0fc0) >> 6;
            index ^= (index & 0x0820) >> 5;
            index ^= (index & 0x07e0) >> 4;
            index ^= (index & 0x8e38) >> 3;
            index ^= (index & 0x8e38) >> 2;
            index ^= (index & 0x2492) >> 1;
        }
        _ => {}
    }
    index
}

/// owen.h `shuffledScrambledSobol<N>`: the index Owen-shuffled under `seed` (its top 16 bits a
/// reversed 16-bit index), Sobol' dimensions `0..N` there, dimension `i` Owen-scrambled under
/// `seed` rotated right by `8 i` bits.
#[inline]
pub fn shuffled_scrambled_sobol<const N: usize>(index: u32, seed: u32) -> [u32; N] {
    let index = laine_karras(index.reverse_bits(), seed);
    core::array::from_fn(|i| {
        let v = sobol_reversed_index((index >> 16) as u16, i as u32) as u32;
        laine_karras(v, seed.rotate_right(8 * i as u32)).reverse_bits()
    })
}

/// float.h `uintToFloat`: the guard bit cleared so that the conversion rounds down, times
/// `2^-32` (in `[0, 1)`).
#[inline]
pub fn uint_to_float(value: u32) -> f32 {
    (value & !(value >> 24)) as f32 * (1.0 / 4_294_967_296.0)
}

/// `oqmc::SobolBnSampler`'s state (state.h `State64Bit`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SobolBn {
    pub pattern_id: u32,
    pub sample_id: u16,
    pub pixel_id: u16,
}

impl SobolBn {
    /// `SobolBnSampler(x, y, frame, index, cache)`.
    pub fn new(x: i32, y: i32, frame: i32, index: i32) -> Self {
        SobolBn {
            pattern_id: lcg(0).wrapping_add(frame.wrapping_add(index >> 16) as u32),
            sample_id: (index & 0xffff) as u16,
            pixel_id: ((x & 255) | (y & 255) << 8) as u16,
        }
    }

    /// `newDomain(key)`.
    pub fn new_domain(&self, key: i32) -> Self {
        SobolBn {
            pattern_id: lcg(self.pattern_id.wrapping_add(key as u32)),
            ..*self
        }
    }

    /// `drawSample<N>(uint32_t*)`: the table's entry at the pixel shifted by the pattern's
    /// output (toroidally on 256 x 256), then the Sobol' sample at `sample ^ rank` under its key.
    pub fn draw_sample<const N: usize>(&self) -> [u32; N] {
        let shift = pcg_output(self.pattern_id);
        let x = (self.pixel_id as u32 + shift) & 255;
        let y = ((self.pixel_id as u32 >> 8) + (shift >> 8)) & 255;
        let cell = (x | y << 8) as usize;
        shuffled_scrambled_sobol::<N>(
            self.sample_id as u32 ^ table(RANKS, cell),
            table(KEYS, cell),
        )
    }

    /// `drawSample<N>(float*)`.
    pub fn draw_sample_f32<const N: usize>(&self) -> [f32; N] {
        self.draw_sample::<N>().map(uint_to_float)
    }
}

/// `render`'s draws from [`SobolBn`], by dimension (see the module docs for the mapping).
#[derive(Clone, Debug)]
pub struct OpenQmcBn {
    frame: i32,
    camera: u32,
    per_bounce: u32,
    root: SobolBn,
    dim: u32,
}

impl OpenQmcBn {
    /// The sampler of `render`'s `seed` (OpenQMC's frame `seed * 65536`).
    pub fn new(seed: u64) -> Self {
        let layout = strata::pixel::DimensionLayout::default();
        OpenQmcBn {
            frame: (seed as i32).wrapping_mul(1 << 16),
            camera: layout.camera,
            per_bounce: layout.per_bounce,
            root: SobolBn::new(0, 0, 0, 0),
            dim: 0,
        }
    }

    /// Starts sample `index` of `pixel`, at dimension `dim`.
    pub fn start_pixel_sample(&mut self, pixel: [u32; 2], index: u32, dim: u32) {
        self.root = SobolBn::new(pixel[0] as i32, pixel[1] as i32, self.frame, index as i32);
        self.dim = dim;
    }

    pub fn dimension(&self) -> u32 {
        self.dim
    }

    pub fn set_dimension(&mut self, dim: u32) {
        self.dim = dim;
    }

    /// The domain of the draw at dimension `d`.
    fn domain(&self, d: u32) -> SobolBn {
        if d < self.camera {
            return self.root.new_domain(0).new_domain(d as i32);
        }
        let (k, o) = (
            (d - self.camera) / self.per_bounce,
            (d - self.camera) % self.per_bounce,
        );
        let mut trace = self.root.new_domain(1);
        for _ in 0..k {
            trace = trace.new_domain(self.per_bounce as i32);
        }
        trace.new_domain(o as i32)
    }

    pub fn get_1d(&mut self) -> f32 {
        let d = self.dim;
        self.dim = d.wrapping_add(1);
        self.domain(d).draw_sample_f32::<1>()[0]
    }

    pub fn get_2d(&mut self) -> [f32; 2] {
        let d = self.dim;
        self.dim = d.wrapping_add(2);
        self.domain(d).draw_sample_f32::<2>()
    }

    pub fn get_pixel_2d(&mut self) -> [f32; 2] {
        self.get_2d()
    }
}
