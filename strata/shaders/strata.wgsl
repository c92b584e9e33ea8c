// strata.wgsl: the draw kernel of the `strata` crate's path-tracer adapter, as WGSL.
//
// A line-by-line port of `src/pixel/kernel.rs` (32-bit wrapping integer arithmetic only): for
// the sequences random (0), sobol (1), pmj02 (2), lattice (3), zsobol (4) and zpmj02 (5), the
// same bits as `PixelSampler::sample_2d_u32` on the CPU, which the crate's GPU test checks over
// 2^22 draws per sequence on the Vulkan adapter present. zjoint (6) is strata_zjoint.wgsl,
// included after this file. jittered and halton are CPU-only.
//
// Use: include this file in your shader module, fill a `StrataParameters` from
// `PixelSampler::gpu_parameters()` (eight u32 words, `GpuParameters::words()`), then
//
//     let u = strata_get_2d(params, pixel, sample_index, dimension);   // vec2<f32> in [0, 1)
//
// Dimensions are taken in pairs as on the CPU: a 2D draw at `dim` reads dimensions dim and
// dim + 1; a 1D draw at `dim` is the `.x` of the 2D draw at `dim`.
//
// Domain: sample indices below 2^32 (a u32). The CPU continues past 2^32 with a fresh key per
// block of 2^32 samples (`Key::epoch`); a renderer that goes that far uploads that key instead.
// Pixels and dimensions: any u32. Every value is below 1.0.

struct StrataParameters {
    key: vec4<u32>,
    resolution: vec2<u32>,
    sequence: u32,
    // bits 0-7: log2 of the samples per pixel rounded up to a power of two (the Z-ordered
    // sequences' block of each pixel); bit 8: the shell padding (`Padding::Shells`)
    z_bits: u32,
}

// lowbias32 (Wellons) of x ^ key: a bijective 32-bit hash.
fn strata_hash32(x: u32, key: u32) -> u32 {
    var v = x ^ key;
    v ^= v >> 16u;
    v *= 0x7feb352du;
    v ^= v >> 15u;
    v *= 0x846ca68bu;
    return v ^ (v >> 16u);
}

// The Owen scramble of a 32-bit fixed-point value in the bit-reversed domain (Burley 2020,
// Vegdahl's constants).
fn strata_owen_rev(n_in: u32, seed: u32) -> u32 {
    var n = n_in;
    n ^= n * 0x3d20adeau;
    n += seed;
    n *= (seed >> 16u) | 1u;
    n ^= n * 0x05526c56u;
    return n ^ (n * 0x53a22864u);
}

// The Owen scramble of two values.
fn strata_owen_rev2(n_in: vec2<u32>, seed: vec2<u32>) -> vec2<u32> {
    var n = n_in;
    n ^= n * 0x3d20adeau;
    n += seed;
    n *= (seed >> vec2<u32>(16u)) | vec2<u32>(1u);
    n ^= n * 0x05526c56u;
    return n ^ (n * 0x53a22864u);
}

// The nested uniform shuffle of a bit-reversed index: a seeded XOR-multiply, then one round.
fn strata_shuffle_rev(index_rev: u32, even: u32, key: u32) -> u32 {
    return strata_owen_rev(index_rev ^ (index_rev * even), key);
}

// The base-4 nested scramble (Vegdahl 2022), bit-reversed domain.
fn strata_owen_base4_rev(n_in: u32, seed: u32) -> u32 {
    var n = n_in;
    n ^= n * 0x3d20adeau;
    n ^= (n >> 1u) & (n << 1u) & 0x55555555u;
    n += seed;
    n *= (seed >> 16u) | 1u;
    n ^= (n >> 1u) & (n << 1u) & 0x55555555u;
    n ^= n * 0x05526c56u;
    return n ^ (n * 0x53a22864u);
}

// The Morton code of a pixel (16 bits of each coordinate).
fn strata_spread(v_in: u32) -> u32 {
    var v = v_in & 0xffffu;
    v = (v | (v << 8u)) & 0x00ff00ffu;
    v = (v | (v << 4u)) & 0x0f0f0f0fu;
    v = (v | (v << 2u)) & 0x33333333u;
    return (v | (v << 1u)) & 0x55555555u;
}

fn strata_morton(pixel: vec2<u32>) -> u32 {
    return strata_spread(pixel.x) | (strata_spread(pixel.y) << 1u);
}

// The four keys of a pixel: word j is lowbias(x ^ lowbias(y ^ k_j)).
fn strata_pixel_keys(key: vec4<u32>, pixel: vec2<u32>) -> vec4<u32> {
    return vec4<u32>(
        strata_hash32(pixel.x, strata_hash32(pixel.y, key.x)),
        strata_hash32(pixel.x, strata_hash32(pixel.y, key.y)),
        strata_hash32(pixel.x, strata_hash32(pixel.y, key.z)),
        strata_hash32(pixel.x, strata_hash32(pixel.y, key.w)),
    );
}

// The keys of a tile (2^32 global indices) of the Z-ordered sequences' global sequence.
fn strata_tile_keys(key: vec4<u32>, tile: u32) -> vec4<u32> {
    let salt = 0x7a027a02u;
    return vec4<u32>(
        strata_hash32(tile, strata_hash32(salt, key.x)),
        strata_hash32(tile, strata_hash32(salt, key.y)),
        strata_hash32(tile, strata_hash32(salt, key.z)),
        strata_hash32(tile, strata_hash32(salt, key.w)),
    );
}

struct StrataDrawKeys {
    h: u32,
    e: u32,
    v: vec2<u32>,
}

// The keys of the draw at `dim`.
fn strata_draw_keys(p: vec4<u32>, dim: u32) -> StrataDrawKeys {
    let x = (dim ^ p.x) * 0x7feb352du;
    let h = x ^ (x >> 15u);
    let e = ((dim ^ p.y) * 0x9e3779b9u) & 0xfffffffeu;
    return StrataDrawKeys(h, e, vec2<u32>(h ^ p.z, h ^ p.w));
}

// Sobol' dimensions 0-1 at a plain index, bit-reversed.
fn strata_sobol01_rev(index: u32) -> vec2<u32> {
    var y = index;
    y ^= (y >> 1u) & 0x55555555u;
    y ^= (y >> 2u) & 0x33333333u;
    y ^= (y >> 4u) & 0x0f0f0f0fu;
    y ^= (y >> 8u) & 0x00ff00ffu;
    y ^= (y >> 16u) & 0x0000ffffu;
    return vec2<u32>(index, y);
}

// W(t + t^2) over GF(2), W's coefficients at the even bits.
fn strata_substitute(w_in: u32) -> u32 {
    var w = w_in;
    w ^= (w & 0xccccccccu) >> 1u;
    w ^= (w & 0xf0f0f0f0u) >> 2u;
    w ^= (w & 0xff00ff00u) >> 4u;
    w ^= (w & 0xffff0000u) >> 8u;
    return w;
}

// pmj02's digital dimensions at a plain index, bit-reversed.
fn strata_pmj02_rev(index: u32) -> vec2<u32> {
    let u = strata_substitute(index & 0x55555555u);
    let v = strata_substitute((index >> 1u) & 0x55555555u);
    let x = u ^ (v << 1u);
    return vec2<u32>(x, x ^ v);
}

// random: two lowbias32 hashes of an affine map of the index (odd multiplier, offset).
fn strata_random(k: StrataDrawKeys, index: u32) -> vec2<u32> {
    let m = vec2<u32>(k.e | 1u, ((k.e << 16u) | (k.e >> 16u)) | 1u);
    var x = vec2<u32>(index) * m + k.v;
    x = (x ^ (x >> vec2<u32>(16u))) * 0x7feb352du;
    x = (x ^ (x >> vec2<u32>(15u))) * 0x846ca68bu;
    return x ^ (x >> vec2<u32>(16u));
}

// sobol, pmj02, zsobol, zpmj02: the digital point at the shuffled index, Owen-scrambled.
fn strata_digital(pmj02: bool, k: StrataDrawKeys, index: u32) -> vec2<u32> {
    let r = strata_shuffle_rev(reverseBits(index), k.e, k.h);
    var p: vec2<u32>;
    if (pmj02) {
        p = strata_pmj02_rev(reverseBits(r));
    } else {
        p = strata_sobol01_rev(reverseBits(r));
    }
    return reverseBits(strata_owen_rev2(p, k.v));
}

// lattice: the rank-1 lattice point at the shuffled index, shifted.
fn strata_lattice(k: StrataDrawKeys, index: u32) -> vec2<u32> {
    let r = strata_shuffle_rev(reverseBits(index), k.e, k.h);
    return vec2<u32>(r, r * 182667u) + k.v;
}

// A random affine map of every base-4 digit (an aligned bit pair over GF(2)^2), one per digit
// position: three transvections, then a translation (every permutation of a digit's values).
fn strata_digit_affine_rev(n_in: u32, key: u32) -> u32 {
    let lo = 0x55555555u;
    let k = strata_hash32(key, 0x7a037a03u);
    var n = n_in;
    n ^= (n >> 1u) & k & lo;
    n ^= (n & (k >> 1u) & lo) << 1u;
    n ^= (n >> 1u) & ((k << 16u) | (k >> 16u)) & lo;
    return n ^ (k * 0x2c1b3c6du);
}

// The mask of the base-4 digits of the Morton codes of an image (its ceil(log2(max side))
// lowest digits).
fn strata_z_mask(resolution: vec2<u32>) -> u32 {
    let side = max(max(resolution.x, resolution.y), 1u);
    let levels = 32u - countLeadingZeros(side - 1u);
    if (levels >= 16u) {
        return 0xffffffffu;
    }
    return (1u << (2u * levels)) - 1u;
}

// The keys and the index that a draw reads: the pixel's own keys and the sample index, or
// for the Z-ordered sequences (4, 5, 6) inside the image and the pixel's block the keys of
// the global sequence's tile and the pixel's place along it for the draw keyed by `dim`.
struct StrataSample {
    keys: vec4<u32>,
    index: u32,
}

// Irreducible polynomials of GF(2^m) for m = 0..16, without their x^m term.
const STRATA_GF_POLY = array<u32, 17>(
    0u, 0x1u, 0x3u, 0x3u, 0x3u, 0x5u, 0x3u, 0x3u, 0x1du, 0x11u, 0x9u, 0x5u, 0x53u, 0x1bu, 0x443u,
    0x3u, 0x100bu,
);

// a b in GF(2^m) (m <= 16, a, b < 2^m).
fn strata_gf_mul(a_in: u32, b: u32, m: u32) -> u32 {
    let reduce = (1u << m) | STRATA_GF_POLY[min(m, 16u)];
    var a = a_in;
    var r = 0u;
    for (var i = 0u; i < m; i++) {
        r ^= a & (0u - ((b >> i) & 1u));
        a <<= 1u;
        a ^= reduce & (0u - ((a >> m) & 1u));
    }
    return r;
}

// The position of `index` inside its aligned block of 2^bits mapped by x -> alpha x + beta over
// GF(2^bits), keyed by `key`, the draw's dimension and the block (bits 1 to 16; others keep).
fn strata_uniform_block(index: u32, bits: u32, key: u32, dim: u32) -> u32 {
    if (bits == 0u || bits > 16u) {
        return index;
    }
    let mask = (1u << bits) - 1u;
    let h = strata_hash32(index >> bits, strata_hash32(dim, key ^ 0x70616431u));
    var alpha = 1u + h % max(mask, 1u);
    if (bits == 1u) {
        alpha = 1u;
    }
    let beta = strata_hash32(h, 0x70616431u) & mask;
    return (index & ~mask) | (strata_gf_mul(alpha, index & mask, bits) ^ beta);
}

// The shell padding: the index's position inside its dyadic shell [2^j, 2^(j+1)) mapped so
// (indices 0 and 1 stay), keyed by the pixel's first key word.
fn strata_shell_block(index: u32, key: u32, dim: u32) -> u32 {
    if (index < 2u) {
        return index;
    }
    return strata_uniform_block(index, 31u - countLeadingZeros(index), key, dim);
}

fn strata_sample(
    params: StrataParameters,
    pixel: vec2<u32>,
    index: u32,
    dim: u32,
) -> StrataSample {
    var keys = strata_pixel_keys(params.key, pixel);
    var i = index;
    if ((params.z_bits & 0x100u) != 0u) {
        i = strata_shell_block(index, keys.x, dim);
    }
    let seq = params.sequence;
    if (seq == 4u || seq == 5u || seq == 6u) {
        // the pixel's block of the global sequence, along a scrambled Z curve
        let inside = pixel.x < params.resolution.x && pixel.y < params.resolution.y;
        let bits = params.z_bits & 0xffu;
        if (inside && bits < 32u && (index >> bits) == 0u) {
            // the pixel's place for this draw: its Morton code under a nested base-4 scramble
            // of the image's digits, keyed by the image and the draw
            let zk = strata_hash32(dim, strata_hash32(params.key.x ^ params.key.y, 0x7a017a01u));
            let r = strata_owen_base4_rev(reverseBits(strata_morton(pixel)), zk);
            let z = reverseBits(strata_digit_affine_rev(r, zk)) & strata_z_mask(params.resolution);
            var tile = 0u;
            if (bits > 0u) {
                tile = z >> (32u - bits);
            }
            keys = strata_tile_keys(params.key, tile);
            i = (z << bits) | i;
        }
    }
    return StrataSample(keys, i);
}

// The 2D draw at `dim` of sample `index` of `pixel`, as 32-bit fixed point (value / 2^32), for
// sequences 0-5 (the joint sequences 6 and 7 are `strata_joint_draw` in strata_zjoint.wgsl;
// here they give 0).
fn strata_draw(params: StrataParameters, pixel: vec2<u32>, index: u32, dim: u32) -> vec2<u32> {
    let seq = params.sequence;
    let at = strata_sample(params, pixel, index, dim);
    let keys = at.keys;
    let i = at.index;
    let k = strata_draw_keys(keys, dim);
    switch seq {
        case 0u: {
            return strata_random(k, i);
        }
        case 1u, 4u: {
            return strata_digital(false, k, i);
        }
        case 2u, 5u: {
            return strata_digital(true, k, i);
        }
        case 3u: {
            return strata_lattice(k, i);
        }
        default: {
            return vec2<u32>(0u);
        }
    }
}

// The 2D draw as floats in [0, 1): the top 24 bits of each value.
fn strata_get_2d(params: StrataParameters, pixel: vec2<u32>, index: u32, dim: u32) -> vec2<f32> {
    let v = strata_draw(params, pixel, index, dim);
    return vec2<f32>(v >> vec2<u32>(8u)) * (1.0 / 16777216.0);
}
