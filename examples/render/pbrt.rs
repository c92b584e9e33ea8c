//! Two reference samplers from pbrt-v4, written here (not in the library) so that `render` can
//! set the crate's sequences beside them: `PaddedSobolSampler` (its default `FastOwen`
//! randomization) and `ZSobolSampler`.
//!
//! Written from the description of pbrt-v4's code (Matt Pharr, Wenzel Jakob and Greg
//! Humphreys, `mmp/pbrt-v4` at commit `5f7a606806a4ac7b939131ded9d7a30ebd02416e`, Apache-2.0:
//! `src/pbrt/samplers.h` l.144-366, `src/pbrt/util/lowdiscrepancy.h`, `src/pbrt/util/hash.h`,
//! `src/pbrt/util/math.h`), and checked bit for bit against test vectors made from pbrt's own
//! function bodies (`tests/lab/render_pbrt.rs`, `tests/lab/pbrt_vectors.txt`). The hash is
//! Austin Appleby's MurmurHash64A (public domain), the index permutation Kensler's
//! ("Correlated Multi-Jittered Sampling", 2013), the `FastOwen` scramble Laine and Karras's
//! with Burley's and Vegdahl's constants, the Z order Ahmed and Wonka's (2020).
//!
//! Only Sobol' dimensions 0 (the identity) and 1 (the Pascal matrix) are used by these two
//! samplers; their columns are computed here.
//!
//! Dimensions: pbrt's samplers count dimensions themselves (`Get1D` takes one, `Get2D` two).
//! `render` sets the dimension of each draw from its own layout (the camera's draws at 0, 2, 4,
//! bounce `k`'s at `8 + 8 k` plus a fixed offset); the references take that dimension as
//! pbrt's dimension counter, so a draw's hash, index permutation and scramble are those pbrt
//! would use for a draw at that dimension, and two draws of one sample never share one.

// Each item is used by `render` or by the test that includes this file alone
// (`tests/lab/render_pbrt.rs`); neither uses all of them.
#![allow(dead_code)]

/// How a Sobol' sample's 32 bits are randomized (pbrt's `RandomizeStrategy`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Randomize {
    None,
    PermuteDigits,
    /// pbrt-v4's default.
    FastOwen,
    Owen,
}

impl Randomize {
    /// The randomized bits `v` under `seed`.
    #[inline]
    pub fn apply(self, v: u32, seed: u32) -> u32 {
        match self {
            Randomize::None => v,
            Randomize::PermuteDigits => v ^ seed,
            Randomize::FastOwen => fast_owen(v, seed),
            Randomize::Owen => owen(v, seed),
        }
    }
}

/// pbrt's `Hash(args...)` for at most four `int` arguments (a `Point2i` is its `x`, `y`):
/// MurmurHash64A (seed 0) of their little-endian bytes, packed.
#[inline]
pub fn hash_i32(words: &[i32]) -> u64 {
    let mut bytes = [0u8; 16];
    for (chunk, w) in bytes.chunks_exact_mut(4).zip(words) {
        chunk.copy_from_slice(&w.to_le_bytes());
    }
    murmur_hash64a(&bytes[..4 * words.len().min(4)], 0)
}

/// Austin Appleby's MurmurHash64A of `bytes` (pbrt's `MurmurHash64A`, `hash.h`).
pub fn murmur_hash64a(bytes: &[u8], seed: u64) -> u64 {
    const M: u64 = 0xc6a4_a793_5bd1_e995;
    const R: u32 = 47;
    let mut h = seed ^ (bytes.len() as u64).wrapping_mul(M);
    let mut blocks = bytes.chunks_exact(8);
    for b in &mut blocks {
        let mut k = u64::from_le_bytes(b.try_into().expect("eight bytes"));
        k = k.wrapping_mul(M);
        k ^= k >> R;
        k = k.wrapping_mul(M);
        h ^= k;
        h = h.wrapping_mul(M);
    }
    let tail = blocks.remainder();
    if !tail.is_empty() {
        for (i, &b) in tail.iter().enumerate().rev() {
            h ^= (b as u64) << (8 * i);
        }
        h = h.wrapping_mul(M);
    }
    h ^= h >> R;
    h = h.wrapping_mul(M);
    h ^ (h >> R)
}

/// pbrt's `MixBits`.
#[inline]
pub fn mix_bits(mut v: u64) -> u64 {
    v ^= v >> 31;
    v = v.wrapping_mul(0x7fb5_d329_728e_a185);
    v ^= v >> 27;
    v = v.wrapping_mul(0x81da_def4_bc2d_d44d);
    v ^ (v >> 33)
}

/// pbrt's `PermutationElement(i, l, p)`: element `i` of a permutation of `0..l` keyed by `p`
/// (Kensler's hash, cycle-walking until below `l`).
pub fn permutation_element(mut i: u32, l: u32, p: u32) -> u32 {
    let mut w = l.wrapping_sub(1);
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    loop {
        i ^= p;
        i = i.wrapping_mul(0xe170_893d);
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i = i.wrapping_mul(0x0929_eb3f);
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | (p >> 27));
        i = i.wrapping_mul(0x6935_fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dc_b303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e50_1cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860_a3df);
        i &= w;
        i ^= i >> 5;
        if i < l {
            break;
        }
    }
    i.wrapping_add(p) % l
}

/// pbrt's `FastOwenScrambler`.
#[inline]
pub fn fast_owen(v: u32, seed: u32) -> u32 {
    let mut v = v.reverse_bits();
    v ^= v.wrapping_mul(0x3d20_adea);
    v = v.wrapping_add(seed);
    v = v.wrapping_mul((seed >> 16) | 1);
    v ^= v.wrapping_mul(0x0552_6c56);
    v ^= v.wrapping_mul(0x53a2_2864);
    v.reverse_bits()
}

/// pbrt's `OwenScrambler` (one hash per digit).
pub fn owen(mut v: u32, seed: u32) -> u32 {
    if seed & 1 != 0 {
        v ^= 1 << 31;
    }
    for b in 1..32 {
        let mask = u32::MAX << (32 - b);
        if (mix_bits(((v & mask) ^ seed) as u64) as u32) & (1 << b) != 0 {
            v ^= 1 << (31 - b);
        }
    }
    v
}

/// Columns per Sobol' dimension (pbrt's `SobolMatrixSize`).
const COLUMNS: usize = 52;

/// The generator columns of Sobol' dimensions 0 (identity) and 1 (Pascal), MSB first: pbrt's
/// `SobolMatrices32` for those dimensions.
const fn sobol01() -> [[u32; COLUMNS]; 2] {
    let mut m = [[0u32; COLUMNS]; 2];
    let mut v = 0x8000_0000u32;
    let mut i = 0;
    while i < COLUMNS {
        if i < 32 {
            m[0][i] = 1 << (31 - i);
        }
        m[1][i] = v;
        v ^= v >> 1;
        i += 1;
    }
    m
}

const SOBOL01: [[u32; COLUMNS]; 2] = sobol01();

/// pbrt's `SobolSample(a, dimension, randomizer)` for dimension 0 or 1, as `f32`.
#[inline]
pub fn sobol_sample(mut a: u64, dimension: usize, r: Randomize, seed: u32) -> f32 {
    let mut v = 0u32;
    let mut i = 0;
    while a != 0 && i < COLUMNS {
        if a & 1 != 0 {
            v ^= SOBOL01[dimension][i];
        }
        a >>= 1;
        i += 1;
    }
    let v = r.apply(v, seed);
    // `v * 0x1p-32f`: `v` rounded to `f32` (nearest, ties to even), then an exact product;
    // at most `FloatOneMinusEpsilon`
    ((v as f32) * f32::from_bits(0x2f80_0000)).min(f32::from_bits(0x3f7f_ffff))
}

/// pbrt-v4's `PaddedSobolSampler`: every draw permutes the pixel's sample index by its own
/// random permutation of `0..spp` (keyed by the hash of pixel, dimension and seed) and takes
/// Sobol' dimension 0 (1D) or 0 and 1 (2D) at the permuted index, scrambled under that hash.
#[derive(Clone, Debug)]
pub struct PaddedSobol {
    spp: u32,
    seed: i32,
    randomize: Randomize,
    pixel: [i32; 2],
    index: u32,
    dim: u32,
}

impl PaddedSobol {
    /// `spp` samples per pixel (any count: the permutation cycle-walks), `seed` (pbrt's
    /// `int` seed, here a `u32` taken as its bit pattern).
    pub fn new(spp: u32, seed: u32, randomize: Randomize) -> Self {
        PaddedSobol {
            spp,
            seed: seed as i32,
            randomize,
            pixel: [0, 0],
            index: 0,
            dim: 0,
        }
    }

    pub fn start_pixel_sample(&mut self, pixel: [u32; 2], index: u32, dim: u32) {
        self.pixel = [pixel[0] as i32, pixel[1] as i32];
        self.index = index;
        self.dim = dim;
    }

    pub fn dimension(&self) -> u32 {
        self.dim
    }

    pub fn set_dimension(&mut self, dim: u32) {
        self.dim = dim;
    }

    /// The draw's hash and the permuted index.
    #[inline]
    fn draw(&self) -> (u64, u64) {
        let hash = hash_i32(&[self.pixel[0], self.pixel[1], self.dim as i32, self.seed]);
        let index = permutation_element(self.index, self.spp, hash as u32);
        (hash, index as u64)
    }

    pub fn get_1d(&mut self) -> f32 {
        let (hash, index) = self.draw();
        self.dim = self.dim.wrapping_add(1);
        sobol_sample(index, 0, self.randomize, (hash >> 32) as u32)
    }

    pub fn get_2d(&mut self) -> [f32; 2] {
        let (hash, index) = self.draw();
        self.dim = self.dim.wrapping_add(2);
        [
            sobol_sample(index, 0, self.randomize, hash as u32),
            sobol_sample(index, 1, self.randomize, (hash >> 32) as u32),
        ]
    }

    pub fn get_pixel_2d(&mut self) -> [f32; 2] {
        self.get_2d()
    }
}

/// The 24 permutations of four digits, in pbrt's order (`ZSobolSampler::GetSampleIndex`).
const PERMUTATIONS: [[u8; 4]; 24] = [
    [0, 1, 2, 3],
    [0, 1, 3, 2],
    [0, 2, 1, 3],
    [0, 2, 3, 1],
    [0, 3, 2, 1],
    [0, 3, 1, 2],
    [1, 0, 2, 3],
    [1, 0, 3, 2],
    [1, 2, 0, 3],
    [1, 2, 3, 0],
    [1, 3, 2, 0],
    [1, 3, 0, 2],
    [2, 1, 0, 3],
    [2, 1, 3, 0],
    [2, 0, 1, 3],
    [2, 0, 3, 1],
    [2, 3, 0, 1],
    [2, 3, 1, 0],
    [3, 1, 2, 0],
    [3, 1, 0, 2],
    [3, 2, 1, 0],
    [3, 2, 0, 1],
    [3, 0, 2, 1],
    [3, 0, 1, 2],
];

/// pbrt's `EncodeMorton2(x, y)`: `x`'s bits at the even positions, `y`'s at the odd ones.
pub fn encode_morton2(x: u32, y: u32) -> u64 {
    fn spread(v: u32) -> u64 {
        let mut x = v as u64;
        x = (x ^ (x << 16)) & 0x0000_ffff_0000_ffff;
        x = (x ^ (x << 8)) & 0x00ff_00ff_00ff_00ff;
        x = (x ^ (x << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
        x = (x ^ (x << 2)) & 0x3333_3333_3333_3333;
        (x ^ (x << 1)) & 0x5555_5555_5555_5555
    }
    (spread(y) << 1) | spread(x)
}

/// pbrt-v4's `ZSobolSampler` (Ahmed and Wonka's Z-ordered Sobol'): the pixel's samples are a
/// block of one global Sobol' sequence (dimensions 0 and 1) along the Morton curve, whose base-4
/// digits each draw permutes by a hash of the digits above them and the dimension; the
/// scrambles depend on the dimension and seed only.
#[derive(Clone, Debug)]
pub struct ZSobol {
    log2_spp: u32,
    base4_digits: u32,
    seed: i32,
    randomize: Randomize,
    /// XOR-ed into the hash of every digit's permutation: 0 in pbrt (the pixel order depends
    /// on the dimension alone), a hash of the seed in [`ZSobol::with_seeded_order`].
    order_key: u64,
    morton: u64,
    dim: u32,
}

impl ZSobol {
    /// `spp` samples per pixel (rounded down to a power of two, as pbrt does), an image of
    /// `resolution`.
    pub fn new(spp: u32, resolution: [u32; 2], seed: u32, randomize: Randomize) -> Self {
        let log2_spp = spp.max(1).ilog2();
        let res = resolution[0].max(resolution[1]).max(1).next_power_of_two();
        let log4_spp = log2_spp.div_ceil(2);
        ZSobol {
            log2_spp,
            base4_digits: res.ilog2() + log4_spp,
            seed: seed as i32,
            randomize,
            order_key: 0,
            morton: 0,
            dim: 0,
        }
    }

    /// Not pbrt: the same sampler with the seed in the hash of the pixel order, so that each
    /// seed orders the pixels anew (pbrt's order is one per dimension for every seed: a study
    /// over seeds then measures one order's luck).
    pub fn with_seeded_order(mut self) -> Self {
        self.order_key = mix_bits(self.seed as u32 as u64 | 1 << 32);
        self
    }

    /// The samples per pixel pbrt takes (a power of two).
    pub fn samples_per_pixel(&self) -> u32 {
        1 << self.log2_spp
    }

    pub fn start_pixel_sample(&mut self, pixel: [u32; 2], index: u32, dim: u32) {
        self.dim = dim;
        self.morton = (encode_morton2(pixel[0], pixel[1]) << self.log2_spp) | index as u64;
    }

    pub fn dimension(&self) -> u32 {
        self.dim
    }

    pub fn set_dimension(&mut self, dim: u32) {
        self.dim = dim;
    }

    /// pbrt's `GetSampleIndex` at the current dimension.
    pub fn sample_index(&self) -> u64 {
        let odd = self.log2_spp & 1 == 1;
        let last = if odd { 1 } else { 0 };
        let mult = 0x5555_5555u32.wrapping_mul(self.dim) as u64;
        let mut index = 0u64;
        for i in (last..self.base4_digits).rev() {
            let shift = 2 * i - odd as u32;
            let digit = (self.morton >> shift) & 3;
            let higher = self.morton >> (shift + 2);
            let p = (mix_bits(higher ^ mult ^ self.order_key) >> 24) % 24;
            index |= (PERMUTATIONS[p as usize][digit as usize] as u64) << shift;
        }
        if odd {
            let digit = self.morton & 1;
            index |= digit ^ (mix_bits((self.morton >> 1) ^ mult ^ self.order_key) & 1);
        }
        index
    }

    pub fn get_1d(&mut self) -> f32 {
        let index = self.sample_index();
        self.dim = self.dim.wrapping_add(1);
        let hash = hash_i32(&[self.dim as i32, self.seed]) as u32;
        sobol_sample(index, 0, self.randomize, hash)
    }

    pub fn get_2d(&mut self) -> [f32; 2] {
        let index = self.sample_index();
        self.dim = self.dim.wrapping_add(2);
        let bits = hash_i32(&[self.dim as i32, self.seed]);
        [
            sobol_sample(index, 0, self.randomize, bits as u32),
            sobol_sample(index, 1, self.randomize, (bits >> 32) as u32),
        ]
    }

    pub fn get_pixel_2d(&mut self) -> [f32; 2] {
        self.get_2d()
    }
}
