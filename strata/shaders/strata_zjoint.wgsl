// strata_zjoint.wgsl: the draws of the joint sequences of the `strata` crate's path-tracer
// adapter, as WGSL: sequence 6 (`zjoint`, `zquad`, `zsobol12`: Z-ordered) and sequence 7
// (`sobol12`: each pixel its own copy), which differ only in their table and in the keys and
// index strata.wgsl's `strata_sample` gives them. A port of `kernel::joint` and of the adapter's
// keying of a draw by its group's first dimension, the same bits as
// `PixelSampler::sample_2d_u32`, which the crate's GPU test checks over 2^22 draws for each of
// these sequences and for groups of 2, 8 and 512.
//
// Use: include strata.wgsl, then this file, and declare the table this file reads at a
// binding of your choice, filled with the words of `Sequence::gpu_joint_table()` (word 0 the
// group size G, then 32 generator columns per Sobol' dimension 0..=G):
//
//     @group(0) @binding(3) var<storage, read> strata_joint: array<u32>;
//
// then `strata_joint_get_2d(params, pixel, sample_index, dimension)` (vec2<f32> in [0, 1)) or
// `strata_joint_draw` (32-bit fixed point), with `params` from `PixelSampler::gpu_parameters()`
// as for strata.wgsl. Domain: as strata.wgsl (indices below 2^32; pixels and dimensions any
// u32).

// Sobol' dimension `d` (of the table) at a bit-reversed index, bit-reversed: the XOR of the
// columns of the index's set bits.
fn strata_joint_point_rev(d: u32, index_rev: u32) -> u32 {
    var x = index_rev;
    var v = 0u;
    let base = 1u + 32u * d;
    while (x != 0u) {
        v ^= strata_joint[base + firstTrailingBit(x)];
        x &= x - 1u;
    }
    return v;
}

// The 2D draw at `dim` of sample `index` of `pixel`, as 32-bit fixed point: every draw of a
// group of G dimensions reads the index of the group's first dimension `g` (its pixel place and
// index shuffle keyed by `g`), at Sobol' dimensions dim - g and dim - g + 1, each
// Owen-scrambled under the draw's own keys.
fn strata_joint_draw(params: StrataParameters, pixel: vec2<u32>, index: u32, dim: u32) -> vec2<u32> {
    let g = dim & ~(strata_joint[0] - 1u);
    let at = strata_sample(params, pixel, index, g);
    let kg = strata_draw_keys(at.keys, g);
    let k = strata_draw_keys(at.keys, dim);
    let r = strata_shuffle_rev(reverseBits(at.index), kg.e, kg.h);
    let o = dim - g;
    let p = vec2<u32>(strata_joint_point_rev(o, r), strata_joint_point_rev(o + 1u, r));
    return reverseBits(strata_owen_rev2(p, k.v));
}

// Whether a sequence number is one of this file's (6 or 7), not strata.wgsl's `strata_draw`.
fn strata_is_joint(sequence: u32) -> bool {
    return sequence == 6u || sequence == 7u;
}

// The joint draw as floats in [0, 1): the top 24 bits of each value.
fn strata_joint_get_2d(
    params: StrataParameters,
    pixel: vec2<u32>,
    index: u32,
    dim: u32,
) -> vec2<f32> {
    let v = strata_joint_draw(params, pixel, index, dim);
    return vec2<f32>(v >> vec2<u32>(8u)) * (1.0 / 16777216.0);
}
