//! The draw kernel: one 2D draw of the adapter as 32-bit integer arithmetic.
//!
//! Everything a draw of `random`, `sobol`, `pmj02`, `lattice`, `zsobol` or `zpmj02` computes
//! between the image's [`Key`] and the draw's two 32-bit fixed-point values is here, written
//! with 32-bit wrapping integer operations only (no `u64`, no `u128`): the arithmetic every GPU
//! runs. The WGSL shader ([`super::WGSL`]) is a line-by-line port of this file, and the GPU test
//! crate (`gpu/` in the repository) checks, on the Vulkan adapter present, that it computes the
//! same bits over `2^22` tuples per sequence. What stays on the CPU, outside the kernel: the
//! seed's expansion into the [`Key`] (once per image) and the fresh key of each block of `2^32`
//! samples ([`Key::epoch`]).
//!
//! # One draw
//!
//! 1. **Pixel keys**: four words from the key and the pixel, each its own chain of two
//!    `lowbias32` hashes (`pixel_keys`), so that two pixels share all four only with
//!    probability about `2^-128`. For the Z-ordered sequences, inside the pixel's block of the
//!    global sequence, the keys of its *tile* (`2^32` consecutive global indices) instead.
//! 2. **Draw keys** from the pixel keys and the dimension (`DrawKeys::new`): the shuffle key
//!    `h` (one multiply-xorshift of `dim ^ p0`, a bijection of the dimension, so that two draws
//!    of one pixel never share it), the shuffle's even multiplier `e` (from `dim ^ p1`), and the
//!    value keys `h ^ p2`, `h ^ p3`.
//! 3. **The sequence**: the index's nested shuffle ([`crate::scramble::shuffle_rev`]) and the
//!    digital point at the shuffled index, both Owen-scrambled ([`crate::scramble`]) for
//!    `sobol`, `pmj02`, `zsobol`, `zpmj02`; the lattice point at the shuffled index plus a
//!    toroidal shift for `lattice`; two hashes of an affine map of the index for `random`.

use crate::digital::{ByteTables, PairTables, lookup};
use crate::hash::{GOLDEN_GAMMA_32, LOWBIAS32, hash32, mix64, stream_seed};
use crate::morton::morton;
use crate::sampler::Seed;
use crate::samplers::lattice;
use crate::scramble::{
    Lanes, Pair, X2, X4, join, owen_scramble_base4_rev, owen_scramble_lanes, shuffle_lanes,
};

/// The four 32-bit words every draw of an image is keyed by, expanded from the [`Seed`] once
/// (on the CPU: [`Key::new`]); a shader receives them as a uniform
/// ([`PixelSampler::gpu_parameters`](super::PixelSampler::gpu_parameters)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct Key([u32; 4]);

/// The stream of the seed from which the [`Key`] is expanded.
const KEY_STREAM: u64 = 0x6b65_7934;

impl Key {
    /// The key of `seed`.
    pub(crate) fn new(seed: Seed) -> Key {
        let (a, b) = (
            stream_seed(KEY_STREAM, seed.0),
            stream_seed(KEY_STREAM + 1, seed.0),
        );
        Key([a as u32, (a >> 32) as u32, b as u32, (b >> 32) as u32])
    }

    /// The key's four words.
    pub(crate) fn words(&self) -> [u32; 4] {
        self.0
    }

    /// The key of the samples `e 2^32 ..< (e + 1) 2^32` (`e >= 1`): a fresh, independent copy
    /// of every sequence for each block of `2^32` samples. Epoch 0 is the key itself.
    pub(crate) fn epoch(&self, e: u32) -> Key {
        if e == 0 {
            return *self;
        }
        let k = self.0;
        let (a, b) = (
            stream_seed(e as u64, k[0] as u64 | (k[1] as u64) << 32),
            stream_seed(e as u64, k[2] as u64 | (k[3] as u64) << 32),
        );
        Key([a as u32, (a >> 32) as u32, b as u32, (b >> 32) as u32])
    }
}

/// The four keys of a pixel (or of a tile of a Z-ordered global sequence).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PixelKeys(pub(crate) [u32; 4]);

/// The keys of `pixel`: word `j` is `lowbias(x ^ lowbias(y ^ k_j))`, the four chains in four
/// lanes.
#[inline]
pub(crate) fn pixel_keys(key: &Key, pixel: [u32; 2]) -> PixelKeys {
    pixel_keys_in_row(&row_keys(key, pixel[1]), pixel[0])
}

/// The part of [`pixel_keys`] that depends on the row `y` only: `lowbias(y ^ k_j)`.
#[inline]
pub(crate) fn row_keys(key: &Key, y: u32) -> [u32; 4] {
    lowbias_lanes(X4::new(key.0).xor(X4::splat(y))).to_array()
}

/// [`pixel_keys`] of the pixel in column `x` of the row whose [`row_keys`] are `row`.
#[inline]
pub(crate) fn pixel_keys_in_row(row: &[u32; 4], x: u32) -> PixelKeys {
    PixelKeys(lowbias_lanes(X4::new(*row).xor(X4::splat(x))).to_array())
}

/// Wellons' `lowbias32` in every lane (as [`crate::hash::hash32`] with a zero key).
#[inline(always)]
fn lowbias_lanes<L: Lanes>(x: L) -> L {
    let x = x.xor(x.shr::<16>()).mul(L::splat(LOWBIAS32[0]));
    let x = x.xor(x.shr::<15>()).mul(L::splat(LOWBIAS32[1]));
    x.xor(x.shr::<16>())
}

/// Salt of the Z-ordered sequences' pixel scramble key.
const Z_PIXELS: u32 = 0x7a01_7a01;
/// Salt of the Z-ordered sequences' global-sequence keys.
const Z_DRAWS: u32 = 0x7a02_7a02;

/// The keys of tile `tile` (global indices `tile 2^32 ..< (tile + 1) 2^32`) of the global
/// sequence of the Z-ordered sequences.
#[inline]
pub(crate) fn tile_keys(key: &Key, tile: u32) -> PixelKeys {
    PixelKeys(key.0.map(|k| hash32(tile, hash32(Z_DRAWS, k))))
}

/// What the Z-ordered sequences need of a pixel to place it along their global sequence, draw
/// by draw: its Morton code (bit-reversed), the mask of the image's base-4 digits and the
/// image's pixel-order key.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ZPixel {
    morton_rev: u32,
    mask: u32,
    key: u32,
}

/// The mask of the base-4 digits of the Morton codes of an image of `resolution` (the
/// `ceil(log2(max side))` lowest digits): the pixel order permutes these and keeps the rest 0.
#[inline]
pub(crate) fn z_mask(resolution: [u32; 2]) -> u32 {
    let side = resolution[0].max(resolution[1]).max(1);
    let levels = 32 - (side - 1).leading_zeros(); // ceil(log2 side)
    if levels >= 16 {
        u32::MAX
    } else {
        (1u32 << (2 * levels)) - 1
    }
}

/// The Z-ordered sequences' view of `pixel`; `None` outside the `resolution`.
#[inline]
pub(crate) fn z_pixel(key: &Key, resolution: [u32; 2], pixel: [u32; 2]) -> Option<ZPixel> {
    if pixel[0] >= resolution[0] || pixel[1] >= resolution[1] {
        return None;
    }
    Some(ZPixel {
        morton_rev: morton(pixel[0], pixel[1]).reverse_bits(),
        mask: z_mask(resolution),
        key: hash32(key.0[0] ^ key.0[1], Z_PIXELS),
    })
}

/// The place of a pixel along the global sequence for the draw at `dim`: its Morton code under
/// a nested base-4 scramble of the image's digits keyed by the image and the draw (Vegdahl's
/// hash, then a random affine map per digit position: every one of the 24 permutations of a
/// digit is reached), so that each draw orders
/// the pixels anew, as pbrt-v4's `ZSobolSampler` does per dimension, while every aligned
/// `2^k x 2^k` tile of pixels still takes consecutive blocks. A bijection of the image's
/// Morton codes `[0, 4^L)` for every draw.
#[inline]
pub(crate) fn z_place(z: &ZPixel, dim: u32) -> u32 {
    let k = hash32(dim, z.key);
    digit_affine_rev(owen_scramble_base4_rev(z.morton_rev, k), k).reverse_bits() & z.mask
}

/// Salt of the key of [`digit_affine_rev`].
const Z_AFFINE: u32 = 0x7a03_7a03;

/// A random affine map of every base-4 digit (an aligned bit pair, read as a vector over
/// GF(2)^2), one map per digit position keyed by `key`: three transvections chosen per digit
/// (`lo ^= hi`, `hi ^= lo`, `lo ^= hi`), then a translation. The affine group of GF(2)^2 is
/// the whole symmetric group of the four digit values, so composed after Vegdahl's nested hash,
/// which reaches only 16 of the 24 permutations of a digit, every permutation is reached; the
/// map depends on the digit's position only, so the composition stays a nested scramble.
#[inline(always)]
fn digit_affine_rev(mut n: u32, key: u32) -> u32 {
    const LO: u32 = 0x5555_5555;
    let k = hash32(key, Z_AFFINE);
    n ^= (n >> 1) & k & LO;
    n ^= (n & (k >> 1) & LO) << 1;
    n ^= (n >> 1) & k.rotate_left(16) & LO;
    n ^ k.wrapping_mul(0x2c1b_3c6d)
}

/// The keys of one draw: what randomizes the draw at a dimension of a pixel (public for tests
/// that study the randomization itself, such as the lab's pair test of index shuffles).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DrawKeys {
    /// The index shuffle's key (also the base of the value keys).
    pub h: u32,
    /// The index shuffle's even multiplier.
    pub e: u32,
    /// The keys of the two values' scrambles (or shifts).
    pub v: [u32; 2],
}

impl DrawKeys {
    /// The keys of the draw at `dim` of `pixel` for `seed`, in the first `2^32` samples: the
    /// keys [`PixelSampler`](super::PixelSampler) gives the draws of the sequences that are
    /// not Z-ordered.
    pub fn of(pixel: [u32; 2], dim: u32, seed: Seed) -> Self {
        DrawKeys::new(&pixel_keys(&Key::new(seed), pixel), dim)
    }

    /// The keys of the draw at `dim` of a pixel (or tile) with keys `p`.
    #[inline(always)]
    pub(crate) fn new(p: &PixelKeys, dim: u32) -> Self {
        let p = p.0;
        let x = (dim ^ p[0]).wrapping_mul(LOWBIAS32[0]);
        let h = x ^ (x >> 15);
        let e = (dim ^ p[1]).wrapping_mul(GOLDEN_GAMMA_32) & !1;
        DrawKeys {
            h,
            e,
            v: [h ^ p[2], h ^ p[3]],
        }
    }

    /// The value keys alone of the draw at `dim` (`DrawKeys::new(p, dim).v`).
    #[inline(always)]
    pub(crate) fn values(p: &PixelKeys, dim: u32) -> [u32; 2] {
        let h = Self::hash(p, dim);
        [h ^ p.0[2], h ^ p.0[3]]
    }

    /// The shuffle key `h` alone of the draw at `dim` (`DrawKeys::new(p, dim).h`): one
    /// multiply-xorshift of `dim ^ p0`, a bijection of the dimension.
    #[inline(always)]
    pub(crate) fn hash(p: &PixelKeys, dim: u32) -> u32 {
        let x = (dim ^ p.0[0]).wrapping_mul(LOWBIAS32[0]);
        x ^ (x >> 15)
    }

    /// A well-mixed 64-bit stream of the draw, for the sequences that are not part of the
    /// kernel (`jittered`, `halton`).
    #[inline]
    pub(crate) fn stream(&self) -> u64 {
        mix64((self.v[0] as u64) << 32 | self.h as u64)
    }
}

/// `random`: two `lowbias32` hashes of an affine map of the index, `index m + v` with an odd
/// multiplier `m` and an offset `v` per draw and coordinate. (An index XOR-ed or added to a key
/// would not do: two draws whose keys differ by less than the sample count would read the same
/// hash inputs in another order, a permutation of each other's values, which the pair test
/// catches.)
#[inline(always)]
pub(crate) fn random<P: Pair>(k: &DrawKeys, index: u32) -> P {
    let m = P::new([k.e | 1, k.e.rotate_left(16) | 1]);
    lowbias_lanes(P::splat(index).mul(m).add(P::new(k.v)))
}

/// [`Padding::Nested`](super::Padding::Nested): the nested shuffle of a bit-reversed index
/// under the draw's keys (aligned blocks of `2^m` indices go to aligned blocks, in an order of
/// their own), bit-reversed.
#[inline(always)]
pub(crate) fn shuffled(k: &DrawKeys, index_rev: u32) -> u32 {
    shuffle_lanes(index_rev, k.e, k.h)
}

/// `sobol`, `pmj02`, `zsobol`, `zpmj02`: the digital (0,2)-sequence of `table` at the draw's
/// (padded, bit-reversed) index, each coordinate Owen-scrambled under its value key `v`;
/// values in natural bit order.
#[inline(always)]
pub(crate) fn digital<P: Pair>(table: &PairTables, v: [u32; 2], index_rev: u32) -> P {
    let p = P::new(table.point_rev(index_rev));
    owen_scramble_lanes(p, P::new(v)).reverse_bits()
}

/// Two draws at once: the points `a` and `b` (bit-reversed, as the tables give them), each
/// coordinate Owen-scrambled under its draw's value keys `va`, `vb`, as four values in
/// `[0, 1)` (the same bits as [`digital`] on each). Two lanes at a time: on the SSE2 baseline
/// a two-lane multiply is one `pmuludq`, a four-lane one two of them and four shuffles, and
/// with SSE4.1 enabled (its one-instruction `pmulld`) four lanes measured no faster.
#[inline(always)]
pub(crate) fn scrambled_pair(a: [u32; 2], va: [u32; 2], b: [u32; 2], vb: [u32; 2]) -> [f32; 4] {
    let (a, b) = (
        owen_scramble_lanes(X2::new(a), X2::new(va)),
        owen_scramble_lanes(X2::new(b), X2::new(vb)),
    );
    join(a, b).reverse_bits().unit_f32()
}

/// The joint sequences: dimensions `o` and `o + 1` (`o` the draw's offset in its group) of the
/// multi-dimensional digital sequence of `tables` at the group's (padded, bit-reversed) index,
/// each coordinate Owen-scrambled under the draw's own value keys `v`; values in natural bit
/// order. At `o = 0` over Sobol' this is [`digital`] over Sobol' dimensions 0 and 1.
#[inline(always)]
pub(crate) fn joint<P: Pair>(tables: &[ByteTables], v: [u32; 2], o: u32, index_rev: u32) -> P {
    let o = o as usize;
    let p = P::new([
        lookup(&tables[o], index_rev),
        lookup(&tables[o + 1], index_rev),
    ]);
    owen_scramble_lanes(p, P::new(v)).reverse_bits()
}

/// `lattice`: the rank-1 lattice point at the draw's (padded, bit-reversed) index (a reversed
/// index is its radical inverse, the lattice's `phi_2`), shifted on the torus by `v`.
#[inline(always)]
pub(crate) fn lattice<P: Pair>(v: [u32; 2], index_rev: u32) -> P {
    lattice::point_lanes(index_rev, P::new(v))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::digital::{PMJ02, SOBOL01, pmj02_rev, sobol01_rev};
    use crate::scramble::X2;

    #[test]
    fn the_simd_pair_computes_the_reference_bits() {
        let key = Key::new(Seed(3));
        for (px, py) in [(0u32, 0u32), (7, 1), (u32::MAX, 12)] {
            let p = pixel_keys(&key, [px, py]);
            for dim in [0u32, 2, 9, 1000, u32::MAX] {
                let k = DrawKeys::new(&p, dim);
                for i in [0u32, 1, 2, 3, 77, 65535, 65536, u32::MAX] {
                    let r = shuffled(&k, i.reverse_bits());
                    for table in [&SOBOL01, &PMJ02] {
                        let want: [u32; 2] = digital(table, k.v, r);
                        assert_eq!(digital::<X2>(table, k.v, r).to_array(), want);
                        assert_eq!(
                            digital::<X2>(table, k.v, r).unit_f32().map(f32::to_bits),
                            want.unit_f32().map(f32::to_bits)
                        );
                    }
                    let want: [u32; 2] = random(&k, i);
                    assert_eq!(random::<X2>(&k, i).to_array(), want);
                    let want: [u32; 2] = lattice(k.v, r);
                    assert_eq!(lattice::<X2>(k.v, r).to_array(), want);
                }
            }
        }
    }

    #[test]
    fn the_tables_equal_the_shader_s_table_free_forms() {
        // the shader computes the digital points from the plain index; the CPU reads tables
        let mut h = 1u64;
        for _ in 0..100_000 {
            h = mix64(h);
            let r = h as u32;
            assert_eq!(SOBOL01.point_rev(r), sobol01_rev(r.reverse_bits()));
            assert_eq!(PMJ02.point_rev(r), pmj02_rev(r.reverse_bits()));
        }
    }

    #[test]
    fn z_places_are_a_bijection_and_global_indices_stay_in_their_tile() {
        let key = Key::new(Seed(9));
        for (res, dim) in [([64, 64], 0), ([64, 64], 7), ([48, 40], 2), ([1, 1], 0)] {
            let codes = z_mask(res) as u64 + 1;
            let mut seen = std::collections::HashSet::new();
            let place = |x, y| z_place(&z_pixel(&key, res, [x, y]).unwrap(), dim);
            for y in 0..res[1] {
                for x in 0..res[0] {
                    let z = place(x, y);
                    assert!(seen.insert(z) && (z as u64) < codes, "{res:?} {x},{y}: {z}");
                    // aligned 2^k x 2^k tiles of pixels keep consecutive places
                    for k in 1..6 {
                        let corner = place(x >> k << k, y >> k << k);
                        assert_eq!(z >> (2 * k), corner >> (2 * k), "tile {k} of {x},{y}");
                    }
                }
            }
        }
        assert_eq!(z_mask([64, 64]), (1 << 12) - 1);
        assert_eq!(z_mask([65, 2]), (1 << 14) - 1);
        assert_eq!(z_mask([65536, 1]), u32::MAX);
        assert_eq!(z_pixel(&key, [64, 64], [64, 0]), None);
    }

    #[test]
    fn each_draw_orders_the_pixels_anew_with_every_digit_permutation() {
        // each draw permutes the base-4 digit of every 2x2 block, and over draws every one of
        // the 24 permutations appears, for the finest digit and for a coarser one
        let key = Key::new(Seed(3));
        let res = [64, 64];
        for (level, origin) in [(0u32, [10u32, 6u32]), (2, [16, 32])] {
            let mut perms = std::collections::HashSet::new();
            for dim in 0..2000 {
                let digit = |x: u32, y: u32| {
                    let s = 1 << level;
                    let z = z_place(
                        &z_pixel(&key, res, [origin[0] + x * s, origin[1] + y * s]).unwrap(),
                        dim,
                    );
                    (z >> (2 * level)) & 3
                };
                perms.insert([digit(0, 0), digit(1, 0), digit(0, 1), digit(1, 1)]);
            }
            assert_eq!(
                perms.len(),
                24,
                "level {level}: {} permutations",
                perms.len()
            );
        }
    }
}
