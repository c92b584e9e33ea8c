//! Strata occupancy tracking: which 1D strata and which base-2 elementary intervals a point set
//! already occupies, and where a new point may still go.
//!
//! Points are 32-bit fixed point (`x / 2^32`). At level `m` (a set on its way to `2^m` points):
//!
//! * [`Strata1D`] tracks the `2^m` strata of width `2^-m` in x and in y and picks a free one
//!   inside a range (PMJ's N-rooks condition), by counting free bits a word at a time.
//! * [`ElementaryIntervals`] tracks every elementary interval shape `2^a x 2^(m-a)` (`a` x bits,
//!   `m - a` y bits, `a = 0..=m`): one bitset of `2^m` cells per shape. For a target cell with
//!   `h = ceil(m/2)` bits per axis it enumerates the x strata and y strata (width `2^-m`) where a
//!   new point keeps every shape unoccupied, without rejection sampling (Pharr, "Efficient
//!   Generation of Points that Satisfy Two-Dimensional Elementary Intervals", JCGT 2019): shapes
//!   with `a >= h` only constrain x (their y bits are fixed by the target cell) and shapes with
//!   `a <= m - h` only constrain y, so the two sets are independent and are found by two
//!   recursions over x bits and y bits that prune at the first occupied interval; `O(sqrt N)`
//!   per point.
//!
//! Memory: `(m + 1) 2^m` bits for the intervals, `2^(m+1)` for the 1D strata, about 2-4 bytes
//! per point at the sizes that matter.

/// A fixed-size bitset.
#[derive(Clone, Debug, Default)]
pub struct Bitset {
    words: Vec<u64>,
}

impl Bitset {
    /// `len` bits, all clear.
    #[cfg(test)]
    pub fn new(len: usize) -> Self {
        Bitset {
            words: vec![0; len.div_ceil(64)],
        }
    }

    /// Clears every bit and resizes to `len` bits (reusing the allocation).
    pub fn reset(&mut self, len: usize) {
        self.words.clear();
        self.words.resize(len.div_ceil(64), 0);
    }

    /// Sets bit `i`.
    #[inline]
    pub fn set(&mut self, i: usize) {
        self.words[i >> 6] |= 1 << (i & 63);
    }

    /// The number of clear bits in `[lo, hi)`.
    pub fn count_clear(&self, lo: usize, hi: usize) -> usize {
        (hi - lo) - self.count_set(lo, hi)
    }

    /// The number of set bits in `[lo, hi)`.
    pub fn count_set(&self, lo: usize, hi: usize) -> usize {
        segments(lo, hi)
            .map(|(w, mask)| (self.words[w] & mask).count_ones() as usize)
            .sum()
    }

    /// The index of the `k`-th clear bit in `[lo, hi)` (`k` counted from 0), if there is one.
    pub fn nth_clear(&self, lo: usize, hi: usize, mut k: usize) -> Option<usize> {
        for (w, mask) in segments(lo, hi) {
            let mut free = !self.words[w] & mask;
            let c = free.count_ones() as usize;
            if k < c {
                for _ in 0..k {
                    free &= free - 1;
                }
                return Some((w << 6) + free.trailing_zeros() as usize);
            }
            k -= c;
        }
        None
    }

    /// Appends the index of every clear bit in `[lo, hi)` to `out`, in increasing order.
    pub fn clear_bits(&self, lo: usize, hi: usize, out: &mut Vec<u32>) {
        for (w, mask) in segments(lo, hi) {
            let mut free = !self.words[w] & mask;
            while free != 0 {
                out.push(((w << 6) + free.trailing_zeros() as usize) as u32);
                free &= free - 1;
            }
        }
    }
}

/// The words covering bits `[lo, hi)`, each with the mask of the bits inside the range.
fn segments(lo: usize, hi: usize) -> impl Iterator<Item = (usize, u64)> {
    let mut i = lo;
    std::iter::from_fn(move || {
        if i >= hi {
            return None;
        }
        let w = i >> 6;
        let start = i & 63;
        let end = (hi - (w << 6)).min(64);
        let mask = if end - start == 64 {
            u64::MAX
        } else {
            ((1u64 << (end - start)) - 1) << start
        };
        i = (w << 6) + end;
        Some((w, mask))
    })
}

/// The top `bits` bits of a 32-bit fixed-point coordinate (0 for `bits = 0`).
#[inline]
pub fn top_bits(v: u32, bits: u32) -> u32 {
    if bits == 0 { 0 } else { v >> (32 - bits) }
}

/// Occupancy of the `2^m` strata of width `2^-m` in x and in y.
#[derive(Clone, Debug, Default)]
pub struct Strata1D {
    level: u32,
    x: Bitset,
    y: Bitset,
}

impl Strata1D {
    /// Clears and moves to level `m`, marking `points`.
    pub fn reset(&mut self, level: u32, points: &[[u32; 2]]) {
        self.level = level;
        self.x.reset(1 << level);
        self.y.reset(1 << level);
        for p in points {
            self.mark(*p);
        }
    }

    /// Marks the strata of a point.
    pub fn mark(&mut self, p: [u32; 2]) {
        self.x.set(top_bits(p[0], self.level) as usize);
        self.y.set(top_bits(p[1], self.level) as usize);
    }

    /// The free x strata (or y strata, `axis = 1`) in `[lo, hi)`: count, and the `k`-th.
    pub fn free_count(&self, axis: usize, lo: u32, hi: u32) -> usize {
        let b = if axis == 0 { &self.x } else { &self.y };
        b.count_clear(lo as usize, hi as usize)
    }

    /// Appends every free stratum of `axis` in `[lo, hi)` to `out`, in increasing order.
    pub fn free_strata(&self, axis: usize, lo: u32, hi: u32, out: &mut Vec<u32>) {
        let b = if axis == 0 { &self.x } else { &self.y };
        b.clear_bits(lo as usize, hi as usize, out);
    }

    /// The `k`-th free stratum of `axis` in `[lo, hi)`.
    pub fn nth_free(&self, axis: usize, lo: u32, hi: u32, k: usize) -> Option<u32> {
        let b = if axis == 0 { &self.x } else { &self.y };
        b.nth_clear(lo as usize, hi as usize, k).map(|i| i as u32)
    }
}

/// Occupancy of every base-2 elementary interval shape at one level.
///
/// Shape `a` has `2^m` cells: `2^a` columns (x prefixes) by `2^(m-a)` rows (y prefixes). Shapes
/// with `a >= h = ceil(m/2)` are stored row-major (`(y << a) | x`), the others column-major
/// (`(x << (m - a)) | y`). The search for valid x strata only reads shapes `a >= h`, where the
/// candidate x prefixes of a target cell form one contiguous run of bits of a row; the search
/// for y only reads shapes `a <= m - h`, where the candidates form a run of a column. Each
/// level of a search is then "double every surviving prefix, clear the occupied ones" over
/// `2^(a - h) / 64` words, and every point is marked once per shape.
#[derive(Clone, Debug, Default)]
pub struct ElementaryIntervals {
    level: u32,
    /// Words per shape: `2^m / 64`, at least 1.
    stride: usize,
    words: Vec<u64>,
    /// Scratch of the search: the live words of the current and the next step.
    alive: Vec<(usize, u64)>,
    next: Vec<(usize, u64)>,
}

/// The bit of shape `a` (of `m + 1`, each `max(2^m, 64)` bits, `h = ceil(m/2)`) holding the
/// point's cell: row-major `(y << a) | x` for `a >= h`, column-major `(x << (m - a)) | y`
/// below, with the top `a` bits of x and `m - a` of y.
#[inline(always)]
fn cell_in_shape(m: u32, h: u32, a: u32, p: &[u32; 2]) -> usize {
    let bits = 1usize << m.max(6);
    // the coordinate in the top half of a u64, so that the top b bits are v >> (64 - b) for
    // 1 <= b <= 32, and b = 0 gives 0 through the double shift
    let (x, y) = ((p[0] as u64) << 32, (p[1] as u64) << 32);
    let top = |v: u64, b: u32| (v >> 1) >> (63 - b);
    let i = if a >= h {
        (top(y, m - a) << a) | top(x, a)
    } else {
        (top(x, a) << (m - a)) | top(y, m - a)
    };
    a as usize * bits + i as usize
}

/// Each of the 8 bits of a byte twice: bit `i` to bits `2i` and `2i + 1`.
const DOUBLED_BYTE: [u16; 256] = {
    let mut t = [0u16; 256];
    let mut b = 0;
    while b < 256 {
        let mut v = 0u16;
        let mut i = 0;
        while i < 8 {
            if (b >> i) & 1 == 1 {
                v |= 3 << (2 * i);
            }
            i += 1;
        }
        t[b] = v;
        b += 1;
    }
    t
};

/// Each of the 32 bits of `x` twice, in order: bit `i` goes to bits `2i` and `2i + 1`.
#[inline]
fn double_bits(x: u32) -> u64 {
    let t = |s: u32| DOUBLED_BYTE[((x >> s) & 0xff) as usize] as u64;
    t(0) | t(8) << 16 | t(16) << 32 | t(24) << 48
}

impl ElementaryIntervals {
    /// Empty intervals at level `m` (`m <= 32`).
    #[cfg(test)]
    pub fn new(level: u32) -> Self {
        let mut e = ElementaryIntervals::default();
        e.reset(level, &[]);
        e
    }

    /// Clears and moves to level `m`, marking `points` (reuses the allocation).
    pub fn reset(&mut self, level: u32, points: &[[u32; 2]]) {
        self.level = level;
        self.stride = (1usize << level).div_ceil(64);
        self.words.clear();
        self.words.resize(self.stride * (level as usize + 1), 0);
        // shape by shape: each pass writes into one shape's bitset (2^m bits, cache-sized
        // where all shapes together are not) while reading the points in order
        let (m, h) = (level, level.div_ceil(2));
        let bits = self.stride * 64;
        for a in 0..=m {
            let shape = &mut self.words[a as usize * self.stride..(a as usize + 1) * self.stride];
            for p in points {
                let i = cell_in_shape(m, h, a, p) - a as usize * bits;
                shape[i >> 6] |= 1 << (i & 63);
            }
        }
    }

    /// The bit index of cell (x prefix `xi`, y prefix `yi`) of shape `a`, in that shape's layout.
    #[inline]
    fn cell(&self, a: u32, xi: u32, yi: u32) -> usize {
        let (m, h) = (self.level, self.level.div_ceil(2));
        let i = if a >= h {
            ((yi as usize) << a) | xi as usize
        } else {
            ((xi as usize) << (m - a)) | yi as usize
        };
        a as usize * self.stride * 64 + i
    }

    /// Marks every interval containing the point.
    pub fn mark(&mut self, p: [u32; 2]) {
        let (m, h) = (self.level, self.level.div_ceil(2));
        for a in 0..=m {
            let i = cell_in_shape(m, h, a, &p);
            self.words[i >> 6] |= 1 << (i & 63);
        }
    }

    /// True when some interval containing the point is already occupied.
    #[cfg(test)]
    pub fn collides(&self, p: [u32; 2]) -> bool {
        let m = self.level;
        (0..=m).any(|a| self.occupied_cell(a, top_bits(p[0], a), top_bits(p[1], m - a)))
    }

    /// Appends to `xs` and `ys` the x strata and y strata (indices at resolution `2^m`) inside
    /// the target cell `(cx, cy)` of `h = ceil(m/2)` bits per axis where a new point occupies no
    /// occupied interval: any pair `(xs[i], ys[j])` is valid.
    pub fn valid_strata(&mut self, cx: u32, cy: u32, xs: &mut Vec<u32>, ys: &mut Vec<u32>) {
        let m = self.level;
        let h = m.div_ceil(2);
        let drop = 2 * h - m; // 0 for even m, 1 for odd
        // The target cell itself, at the shape where both searches start (a = h for x; for y,
        // a = m - h, which is h for even m and h - 1 for odd m).
        if self.occupied_cell(h, cx, cy >> drop) || self.occupied_cell(m - h, cx >> drop, cy) {
            return;
        }
        self.search(true, cx, cy >> drop, xs);
        self.search(false, cy, cx >> drop, ys);
    }

    #[inline]
    fn occupied_cell(&self, a: u32, xi: u32, yi: u32) -> bool {
        let i = self.cell(a, xi, yi);
        self.words[i >> 6] >> (i & 63) & 1 != 0
    }

    /// Word-parallel search for the valid prefixes on one axis: `c` is the cell's prefix on
    /// that axis (`h` bits), `other` the other axis' prefix at the first shape. Step `s` looks at
    /// shape `h + s` (x) or `m - h - s` (y), where the candidates are `2^s` contiguous bits.
    fn search(&mut self, along_x: bool, c: u32, other: u32, out: &mut Vec<u32>) {
        let m = self.level;
        let h = m.div_ceil(2);
        let steps = m - h;
        let bits = self.stride * 64;
        let (c, other) = (c as usize, other as usize);
        // First bit of the candidates' run at step s: row `fixed` of a row-major shape (x), or
        // column `fixed` of a column-major one (y), then the candidates' offset inside it.
        let start = |step: u32| -> usize {
            let a = if along_x { h + step } else { m - h - step };
            let fixed = other >> step;
            let line = if along_x {
                fixed << a
            } else {
                fixed << (m - a)
            };
            a as usize * bits + line + (c << step)
        };
        // Steps with at most 64 candidates run in one register.
        let small = steps.min(6);
        let mut w = 1u64; // step 0: the cell itself, checked by the caller
        let mut step = 1;
        while step <= small {
            let b = start(step);
            let o = self.words[b >> 6] >> (b & 63);
            let len = 1u32 << step;
            let mask = if len < 64 {
                (1u64 << len) - 1
            } else {
                u64::MAX
            };
            w = double_bits(w as u32) & mask & !o;
            step += 1;
        }
        // Larger steps: the surviving words only, as (word offset, bits) pairs. A zero word's
        // children are zero, so the work per step is the number of live words: a handful once
        // the occupied intervals have pruned the run (the usual case), at most the run's words.
        let mut alive = std::mem::take(&mut self.alive);
        let mut next = std::mem::take(&mut self.next);
        alive.clear();
        // One live word (almost always, once a level has a few points): in registers.
        let (mut i, mut v) = (0usize, w);
        while v != 0 && step <= steps {
            let b = start(step) >> 6;
            let lo = double_bits(v as u32) & !self.words[b + 2 * i];
            let hi = double_bits((v >> 32) as u32) & !self.words[b + 2 * i + 1];
            step += 1;
            match (lo != 0, hi != 0) {
                (true, false) => (i, v) = (2 * i, lo),
                (false, true) => (i, v) = (2 * i + 1, hi),
                (false, false) => v = 0,
                (true, true) => {
                    alive.push((2 * i, lo));
                    alive.push((2 * i + 1, hi));
                    v = 0;
                }
            }
        }
        if v != 0 {
            alive.push((i, v));
        }
        while !alive.is_empty() && step <= steps {
            let b = start(step) >> 6;
            next.clear();
            for &(i, v) in &alive {
                let lo = double_bits(v as u32) & !self.words[b + 2 * i];
                let hi = double_bits((v >> 32) as u32) & !self.words[b + 2 * i + 1];
                if lo != 0 {
                    next.push((2 * i, lo));
                }
                if hi != 0 {
                    next.push((2 * i + 1, hi));
                }
            }
            std::mem::swap(&mut alive, &mut next);
            step += 1;
        }
        let base = c << steps;
        for &(wi, mut v) in &alive {
            while v != 0 {
                out.push((base + wi * 64 + v.trailing_zeros() as usize) as u32);
                v &= v - 1;
            }
        }
        self.alive = alive;
        self.next = next;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bitset_counts_and_selects_clear_bits() {
        let mut b = Bitset::new(200);
        for i in [0, 3, 64, 65, 130, 199] {
            b.set(i);
        }
        assert_eq!(b.count_set(0, 200), 6);
        assert_eq!(b.count_clear(60, 70), 8);
        assert_eq!(b.nth_clear(0, 200, 0), Some(1));
        assert_eq!(b.nth_clear(60, 70, 4), Some(66));
        assert_eq!(b.nth_clear(195, 200, 4), None);
        assert_eq!(b.nth_clear(128, 192, 1), Some(129));
        let mut v = Vec::new();
        b.clear_bits(60, 70, &mut v);
        assert_eq!(v, vec![60, 61, 62, 63, 66, 67, 68, 69]);
    }

    #[test]
    fn valid_strata_match_brute_force() {
        // Random partial nets: whatever the occupancy, the enumeration must return exactly the
        // strata pairs whose points collide with nothing.
        let mut h = 0x9e37u64;
        let mut rnd = || {
            h = strata::hash::mix64(h);
            h as u32
        };
        // m past 12 runs the sparse steps (more than 64 candidates per axis)
        for (m, reps) in (1..=8u32)
            .map(|m| (m, 20))
            .chain([(12, 4), (14, 4), (16, 2), (18, 1)])
        {
            for _ in 0..reps {
                let mut e = ElementaryIntervals::new(m);
                for _ in 0..(1u32 << m) / 3 {
                    let p = [rnd(), rnd()];
                    if !e.collides(p) {
                        e.mark(p);
                    }
                }
                let hb = m.div_ceil(2);
                let (cx, cy) = (rnd() >> (32 - hb), rnd() >> (32 - hb));
                let (mut xs, mut ys) = (Vec::new(), Vec::new());
                e.valid_strata(cx, cy, &mut xs, &mut ys);
                // brute force over all strata pairs inside the cell
                let per = 1u32 << (m - hb);
                let mut want = Vec::new();
                for sx in cx * per..(cx + 1) * per {
                    for sy in cy * per..(cy + 1) * per {
                        let p = [sx << (32 - m), sy << (32 - m)];
                        if !e.collides(p) {
                            want.push((sx, sy));
                        }
                    }
                }
                let mut got: Vec<(u32, u32)> = xs
                    .iter()
                    .flat_map(|&x| ys.iter().map(move |&y| (x, y)))
                    .collect();
                got.sort();
                assert_eq!(got, want, "m={m}");
            }
        }
    }
}
