// strata.wgsl: the draw kernel of the `strata` crate's path-tracer adapter, as WGSL.
//
// A port of the crate's 32-bit draw path (`src/pixel/kernel.rs`, `padding.rs` and the sampler's
// placing of a draw): for every sequence `PixelSampler::gpu_parameters()` accepts (all but
// jittered and halton), the same bits as `PixelSampler::sample_2d_u32` on the CPU, which the
// crate's GPU test checks over 2^22 draws per sequence and padding on the Vulkan adapter
// present.
//
// Use: include this file in your shader module, declare the storage buffer it reads at a
// binding of your choice,
//
//     @group(0) @binding(1) var<storage, read> strata_tables: array<u32>;
//
// fill a `StrataParameters` uniform with `GpuParameters::words()` and `strata_tables` with
// `GpuParameters::tables()` (both from `PixelSampler::gpu_parameters()`), then
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
    // what the draws read: 0 hashed values, 1 Sobol', 2 pmj02, 3 the lattice, 4 a joint
    // sequence's matrices, 5 Sobol' through a blue-noise table (both in `strata_tables`)
    kernel: u32,
    // bits 0-7: log2 of the samples per pixel rounded up to a power of two (the Z-ordered
    // sequences' block of each pixel); bit 8: the shell padding (`Padding::Shells`; else the
    // nested one); bit 9: Z-ordered
    flags: u32,
}

// Words of `strata_tables` before a joint sequence's group size and matrices (or a blue-noise
// table's side and entries): the shell padding's table, two 16-bit entries per word.
const STRATA_JOINT_AT = 32768u;

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

// lattice: the rank-1 lattice point at a bit-reversed index, shifted.
fn strata_lattice(v: vec2<u32>, r: u32) -> vec2<u32> {
    return vec2<u32>(r, r * 182667u) + v;
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

// Entry i of the shell padding's table: the powers of the primitive element of GF(2^j), each
// element's j bits reversed at the top of 16 bits, entry 2^j - 1 + e being g^e.
fn strata_exp(i: u32) -> u32 {
    return (strata_tables[i >> 1u] >> ((i & 1u) * 16u)) & 0xffffu;
}

// floor(t m / 2^32) for m < 2^16, from 16-bit halves.
fn strata_below(t: u32, m: u32) -> u32 {
    return ((t >> 16u) * m + (((t & 0xffffu) * m) >> 16u)) >> 16u;
}

// The shell padding of sample `index` for the draw whose group starts at `g`, bit-reversed: its
// position in its shell [2^j, 2^(j+1)) mapped by x -> g^((x + r) mod (2^j - 1)) + b over
// GF(2^j) (the last position standing for zero), keyed by the pixel's third key word, the draw
// and the shell, then (when `mixed`) one round of the Owen hash keyed by `mix`, kept to the
// positions. From 2^16 on, a nested scramble of the shell.
fn strata_shell_rev(index: u32, key: u32, g: u32, mix: u32, mixed: bool) -> u32 {
    if (index < 2u) {
        return reverseBits(index);
    }
    let j = 31u - countLeadingZeros(index);
    let m = (1u << j) - 1u;
    let x = index & m;
    let top = ~(0xffffffffu >> j);
    let marker = 0x80000000u >> j;
    let t = strata_hash32(g, key ^ (j * 0x9e3779b9u));
    if (j > 15u) {
        return (strata_owen_rev(marker | reverseBits(x), t) & top) | marker;
    }
    var e = x + strata_below((t << 16u) | (t >> 16u), m);
    if (e >= m) {
        e -= m;
    }
    var live = top;
    if (x == m) {
        live = 0u;
    }
    let v = ((strata_exp((m + e) & 0xffffu) << 16u) & live) ^ (t & top);
    if (!mixed) {
        return marker | v;
    }
    return marker | (strata_owen_rev(v, mix) & top);
}

// Point `index_rev` (bit-reversed) of dimension `d` of a joint sequence's table, bit-reversed:
// the XOR of the columns of the index's set bits.
fn strata_joint_point_rev(d: u32, index_rev: u32) -> u32 {
    var x = index_rev;
    var v = 0u;
    let base = STRATA_JOINT_AT + 1u + 32u * d;
    while (x != 0u) {
        v ^= strata_tables[base + firstTrailingBit(x)];
        x &= x - 1u;
    }
    return v;
}

// `sobolbn`'s draw at `dim` of `pixel` whose padded index is `r` (bit-reversed): the entry of the
// blue-noise table at the pixel shifted toroidally by the draw (from the image's keys), its
// rank XOR-ed onto the index, the Sobol' point there Owen-scrambled under its key and a second
// key hashed from it, then a digital shift per seed, dimension and coordinate.
fn strata_blue_noise(params: StrataParameters, pixel: vec2<u32>, dim: u32, r: u32) -> vec2<u32> {
    let image_keys = strata_tile_keys(params.key, 0u);
    let image = strata_draw_keys(image_keys, dim);
    let side_bits = strata_tables[STRATA_JOINT_AT];
    let m = (1u << side_bits) - 1u;
    let x = (pixel.x + (image.e >> 22u)) & m;
    let y = (pixel.y + (image.e >> 12u)) & m;
    let at = STRATA_JOINT_AT + 1u + 2u * ((y << side_bits) | x);
    let key = strata_tables[at];
    let p = strata_sobol01_rev(reverseBits(r ^ strata_tables[at + 1u]));
    let k2 = key * 0x9e3779b9u;
    let v = strata_owen_rev2(p, vec2<u32>(key, k2 ^ (k2 >> 16u)));
    return reverseBits(v ^ vec2<u32>(image.v.x, strata_hash32(dim, image_keys.w)));
}

// The 2D draw at `dim` of sample `index` of `pixel`, as 32-bit fixed point (value / 2^32).
fn strata_draw(params: StrataParameters, pixel: vec2<u32>, index: u32, dim: u32) -> vec2<u32> {
    let kernel = params.kernel;
    let own = strata_pixel_keys(params.key, pixel);
    if (kernel == 0u) {
        return strata_random(strata_draw_keys(own, dim), index);
    }
    // the draws of a joint sequence's group read the index of its first dimension
    var g = dim;
    if (kernel == 4u) {
        g = dim & ~(strata_tables[STRATA_JOINT_AT] - 1u);
    }
    let shells = (params.flags & 0x100u) != 0u;
    // the Z-ordered sequences: the pixel's block of the global sequence, along a scrambled Z
    // curve, inside the image and the block; the keys of its tile
    var keys = own;
    var base = 0u;
    let bits = params.flags & 0xffu;
    let inside = pixel.x < params.resolution.x && pixel.y < params.resolution.y;
    let in_z = (params.flags & 0x200u) != 0u && inside && bits < 32u && (index >> bits) == 0u;
    if (in_z) {
        // the pixel's place for this draw: its Morton code under a nested base-4 scramble of
        // the image's digits, keyed by the image and the draw
        let zk = strata_hash32(g, strata_hash32(params.key.x ^ params.key.y, 0x7a017a01u));
        let s = strata_owen_base4_rev(reverseBits(strata_morton(pixel)), zk);
        let z = reverseBits(strata_digit_affine_rev(s, zk)) & strata_z_mask(params.resolution);
        var tile = 0u;
        if (bits > 0u) {
            tile = z >> (32u - bits);
        }
        keys = strata_tile_keys(params.key, tile);
        base = reverseBits(z) >> bits;
    }
    var r = reverseBits(index);
    if (shells) {
        // inside a Z block the affine map alone: the global shuffle below brings the rest
        r = strata_shell_rev(index, own.z, g, strata_draw_keys(keys, g).h, !in_z);
    }
    r = base | r;
    if (!shells || in_z) {
        let kg = strata_draw_keys(keys, g);
        r = strata_shuffle_rev(r, kg.e, kg.h);
    }
    if (kernel == 5u) {
        if (!shells) {
            // the nested shuffle moves the first 2^m samples to an aligned block: back to the
            // first, XOR-ing the shuffle of index 0
            let k0 = strata_draw_keys(own, dim);
            r ^= strata_shuffle_rev(0u, k0.e, k0.h);
        }
        return strata_blue_noise(params, pixel, dim, r);
    }
    let v = strata_draw_keys(keys, dim).v;
    var p: vec2<u32>;
    switch kernel {
        case 1u: {
            p = strata_sobol01_rev(reverseBits(r));
        }
        case 2u: {
            p = strata_pmj02_rev(reverseBits(r));
        }
        case 3u: {
            return strata_lattice(v, r);
        }
        default: {
            let o = dim - g;
            p = vec2<u32>(strata_joint_point_rev(o, r), strata_joint_point_rev(o + 1u, r));
        }
    }
    return reverseBits(strata_owen_rev2(p, v));
}

// The 2D draw as floats in [0, 1): the top 24 bits of each value.
fn strata_get_2d(params: StrataParameters, pixel: vec2<u32>, index: u32, dim: u32) -> vec2<f32> {
    let v = strata_draw(params, pixel, index, dim);
    return vec2<f32>(v >> vec2<u32>(8u)) * (1.0 / 16777216.0);
}
