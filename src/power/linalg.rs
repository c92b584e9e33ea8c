//! A sparse symmetric matrix and a Jacobi-preconditioned conjugate gradient.

/// A square sparse matrix: its diagonal, and the off-diagonal entries by rows (a row may list
/// the same column more than once; the entries add up).
#[derive(Clone, Debug, Default)]
pub(crate) struct SparseSym {
    pub diag: Vec<f64>,
    start: Vec<u32>,
    col: Vec<u32>,
    val: Vec<f64>,
    // Assembly scratch.
    triplets: Vec<(u32, u32, f64)>,
}

impl SparseSym {
    /// Starts assembling an `n x n` matrix.
    pub fn begin(&mut self, n: usize) {
        self.diag.clear();
        self.diag.resize(n, 0.0);
        self.triplets.clear();
    }

    /// Adds `-h` at `(i, j)` and `(j, i)` and `h` on both diagonals: one edge of a weighted graph
    /// Laplacian.
    pub fn add_edge(&mut self, i: usize, j: usize, h: f64) {
        self.diag[i] += h;
        self.diag[j] += h;
        self.triplets.push((i as u32, j as u32, -h));
        self.triplets.push((j as u32, i as u32, -h));
    }

    /// Finishes assembly (rows in order).
    pub fn finish(&mut self) {
        let n = self.diag.len();
        self.start.clear();
        self.start.resize(n + 1, 0);
        for &(i, _, _) in &self.triplets {
            self.start[i as usize + 1] += 1;
        }
        for i in 0..n {
            self.start[i + 1] += self.start[i];
        }
        let m = self.triplets.len();
        self.col.clear();
        self.col.resize(m, 0);
        self.val.clear();
        self.val.resize(m, 0.0);
        let mut fill: Vec<u32> = self.start[..n].to_vec();
        for &(i, j, v) in &self.triplets {
            let k = fill[i as usize] as usize;
            self.col[k] = j;
            self.val[k] = v;
            fill[i as usize] += 1;
        }
    }

    /// `y = A x`.
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        for i in 0..self.diag.len() {
            let mut s = self.diag[i] * x[i];
            for k in self.start[i] as usize..self.start[i + 1] as usize {
                s += self.val[k] * x[self.col[k] as usize];
            }
            y[i] = s;
        }
    }
}

/// How a conjugate-gradient solve ended.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct CgOutcome {
    pub iterations: u32,
    /// `|b - A x| / |b|` at the end.
    pub relative_residual: f64,
}

#[derive(Clone, Debug, Default)]
pub(crate) struct CgWork {
    r: Vec<f64>,
    z: Vec<f64>,
    p: Vec<f64>,
    q: Vec<f64>,
}

fn precondition(r: &[f64], inv: &[f64], z: &mut [f64]) {
    for ((z, r), d) in z.iter_mut().zip(r).zip(inv) {
        *z = r * d;
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Solves `A x = b` for a symmetric positive semi-definite `A` (a connected graph Laplacian) and
/// a right-hand side with zero sum, starting from `x = 0`, with the Jacobi preconditioner, until
/// `|r| <= rtol |b|` or `max_iter` iterations. The result is projected to zero mean (the
/// Laplacian's null space is the constants).
pub(crate) fn pcg(
    a: &SparseSym,
    b: &[f64],
    x: &mut [f64],
    rtol: f64,
    max_iter: u32,
    w: &mut CgWork,
) -> CgOutcome {
    let n = b.len();
    for v in [&mut w.r, &mut w.z, &mut w.p, &mut w.q] {
        v.clear();
        v.resize(n, 0.0);
    }
    x.iter_mut().for_each(|v| *v = 0.0);
    let mean = b.iter().sum::<f64>() / n as f64;
    for (r, b) in w.r.iter_mut().zip(b) {
        *r = b - mean;
    }
    let bnorm = dot(&w.r, &w.r).sqrt();
    if bnorm == 0.0 {
        return CgOutcome::default();
    }
    let inv: Vec<f64> = a
        .diag
        .iter()
        .map(|&d| if d > 0.0 { 1.0 / d } else { 0.0 })
        .collect();
    precondition(&w.r, &inv, &mut w.z);
    w.p.copy_from_slice(&w.z);
    let mut rz = dot(&w.r, &w.z);
    let mut it = 0;
    let mut rnorm = bnorm;
    while it < max_iter && rnorm > rtol * bnorm {
        a.mul(&w.p, &mut w.q);
        let pq = dot(&w.p, &w.q);
        // A direction of zero (or non-finite) curvature: nothing more to gain.
        if pq.is_nan() || pq <= 0.0 {
            break;
        }
        let alpha = rz / pq;
        for ((xi, ri), (pi, qi)) in x.iter_mut().zip(&mut w.r).zip(w.p.iter().zip(&w.q)) {
            *xi += alpha * pi;
            *ri -= alpha * qi;
        }
        rnorm = dot(&w.r, &w.r).sqrt();
        precondition(&w.r, &inv, &mut w.z);
        let rz_new = dot(&w.r, &w.z);
        let beta = rz_new / rz;
        rz = rz_new;
        for (pi, zi) in w.p.iter_mut().zip(&w.z) {
            *pi = zi + beta * *pi;
        }
        it += 1;
    }
    let mx = x.iter().sum::<f64>() / n as f64;
    x.iter_mut().for_each(|v| *v -= mx);
    CgOutcome {
        iterations: it,
        relative_residual: rnorm / bnorm,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_ring_laplacian() {
        let n = 50;
        let mut a = SparseSym::default();
        a.begin(n);
        for i in 0..n {
            a.add_edge(i, (i + 1) % n, 1.0 + (i % 3) as f64);
        }
        a.finish();
        let mut b: Vec<f64> = (0..n).map(|i| ((i * 7) % 11) as f64).collect();
        let m = b.iter().sum::<f64>() / n as f64;
        b.iter_mut().for_each(|v| *v -= m);
        let mut x = vec![0.0; n];
        let out = pcg(&a, &b, &mut x, 1e-12, 1000, &mut CgWork::default());
        assert!(out.relative_residual <= 1e-12, "{out:?}");
        let mut y = vec![0.0; n];
        a.mul(&x, &mut y);
        for i in 0..n {
            assert!((y[i] - b[i]).abs() < 1e-9);
        }
    }
}
