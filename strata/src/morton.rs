//! Morton (Z-order) codes: the bits of two coordinates interleaved, so that nearby cells get
//! nearby codes. Used by the Z-ordered adapter sequences (pixels along a Z curve) and by the
//! constructive PMJ generators (cells visited along one).

/// The Morton (Z-order) code of a cell: the bits of `x` (below 2^16) in the even positions, of
/// `y` in the odd ones.
#[inline]
pub fn morton(x: u32, y: u32) -> u32 {
    let spread = |v: u32| {
        let mut v = v & 0xffff;
        v = (v | (v << 8)) & 0x00ff_00ff;
        v = (v | (v << 4)) & 0x0f0f_0f0f;
        v = (v | (v << 2)) & 0x3333_3333;
        (v | (v << 1)) & 0x5555_5555
    };
    spread(x) | (spread(y) << 1)
}

/// The cell of a Morton code: the inverse of [`morton`].
#[inline]
pub fn unmorton(z: u32) -> [u32; 2] {
    let compact = |v: u32| {
        let mut v = v & 0x5555_5555;
        v = (v | (v >> 1)) & 0x3333_3333;
        v = (v | (v >> 2)) & 0x0f0f_0f0f;
        v = (v | (v >> 4)) & 0x00ff_00ff;
        (v | (v >> 8)) & 0x0000_ffff
    };
    [compact(z), compact(z >> 1)]
}

#[cfg(test)]
mod morton_tests {
    use super::*;

    #[test]
    fn morton_codes_round_trip() {
        for (x, y) in [
            (0, 0),
            (1, 0),
            (0, 1),
            (5, 9),
            (65535, 65535),
            (12345, 54321),
        ] {
            assert_eq!(unmorton(morton(x, y)), [x, y]);
        }
        assert_eq!(morton(1, 0), 1);
        assert_eq!(morton(0, 1), 2);
        assert_eq!(morton(3, 3), 15);
    }
}
