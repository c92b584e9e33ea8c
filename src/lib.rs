//! # strata: sample patterns for Monte Carlo rendering
//!
//! Where the samples go decides the error of a Monte Carlo estimate. `strata` provides sample
//! patterns (progressive sequences a renderer can stop at any count, and fixed-count sets), and
//! the tools to see and measure how good they are.
//!
//! ## The idea in brief
//!
//! A Monte Carlo estimate `(1/N) sum f(x_k)` is the integral of `f` against the sampling pattern
//! `S(x) = (1/N) sum delta(x - x_k)`. In the Fourier domain that is the DC term of the
//! convolution of `f^` with `S^` (Durand 2011). For patterns whose expected spectrum vanishes
//! away from DC the estimate is unbiased, and its variance is
//!
//! ```text
//! Var = sum_{w != 0} |f^(w)|^2 E[|S^(w)|^2]          (Subr and Kautz 2013; Pilleboue et al. 2015)
//! ```
//!
//! the integrand's power spectrum times the pattern's **expected power spectrum**. Natural
//! integrands keep their energy at low frequencies, so a good pattern has little power near DC:
//! jittered sampling pushes it out (variance `N^-1.5` to `N^-2` in 2D instead of random's
//! `N^-1`), blue noise empties a whole disc around DC, and low-discrepancy nets do both at every
//! power of two.
//!
//! ## Samplers
//!
//! | name | kind | guarantees | paper |
//! |---|---|---|---|
//! | `random` | progressive | i.i.d. uniform | - |
//! | `regular` | fixed `s^2` | cell centres (aliasing, zero variance, biased) | - |
//! | `jittered` | fixed `s^2` | one point per cell of `s x s` | Cook 1986 |
//! | `nrooks` | fixed, any `N` | one point per row and column (Latin hypercube) | Shirley 1991 |
//! | `multijittered` | fixed `n^2` | jittered on `n x n` and N-rooks | Chiu, Shirley, Wang 1994 |
//! | `cmj` | fixed, any `N` | multi-jittered on `m x n`, correlated shuffles | Kensler 2013 |
//! | `pmj` | progressive | 1D strata and squarest grid at every `2^m` prefix | Christensen, Kensler, Kilpatrick 2018 |
//! | `pmjbn` | progressive | `pmj` + best-candidate blue noise | same; Mitchell 1991 |
//! | `pmj02` | progressive | (0,m,2)-net at every `2^m` prefix and aligned block | same; Pharr 2019 |
//! | `pmj02bn` | progressive | `pmj02` + best candidate in the valid strata | same |
//! | `pmj02-stochastic` | progressive | as `pmj02`, O(1) per sample, stratified classes | Helmer, Christensen, Kensler 2021 |
//! | `poisson` | fixed, any `N` | exactly `N` points at least `rho r_max(N)` apart | Cook 1986; Ebeida et al. 2011 |
//! | `bridson` | fixed, any `N` | Poisson disk by Bridson's algorithm, exactly `N` | Bridson 2007 |
//! | `best-candidate` | progressive | farthest of `k n` candidates | Mitchell 1991 |
//! | `lloyd` | fixed, any `N` | Lloyd relaxation to a centroidal Voronoi tessellation | Lloyd 1982 |
//! | `ccvt` | fixed, any `N` | capacity-constrained Voronoi tessellation | Balzer, Schlömer, Deussen 2009 |
//! | `sobol` | progressive | (0,m,2)-nets in dims 0-1, Owen-scrambled; up to 1000 dims | Sobol' 1967; Joe, Kuo 2008; Burley 2020 |
//! | `halton` | progressive | prime-base radical inverses, Owen-scrambled digits; 1000 dims | Halton 1960 |
//! | `latin` | fixed, any `N` | D-dim Latin hypercube: every 1D projection stratified | McKay et al. 1979 |
//! | `uncorrelated` | fixed `s^2` | jittered 2D pairs combined in random orders | Cook 1986 |
//! | `oa-bose` | fixed `q^2` | every 2D projection on `q x q`, every 1D into `N` | Jarosz et al. 2019 |
//! | `oa-bush` | fixed `q^t` | every t-D projection on `q^t`, every 1D into `N` | Jarosz et al. 2019 |
//!
//! [`pixel`] is the path-tracer adapter: values by (pixel, sample index, dimension), padded and
//! decorrelated per pixel and dimension, allocation-free.
//!
//! Every sampler implements [`Sampler`]; [`registry`] builds them by name.
//!
//! ## Contract
//!
//! * Points lie in `[0,1)^2`; `f32` coordinates never equal 1.0 ([`sampler`] explains how).
//! * Everything is seeded (`u64`): same seed, same bits, on every platform.
//! * Constructors validate their parameters and return [`Result`]; the [`Error`] says what was
//!   wrong and what is allowed. Nothing panics on user input.
//!
//! ```
//! use strata::{Sampler, registry::{self, Params}};
//! let mut s = registry::build("jittered", &Params::new(64).seed(3))?;
//! let mut points = vec![glam::Vec2::ZERO; 64];
//! s.fill(&mut points);
//! let mean_x: f32 = points.iter().map(|p| p.x).sum::<f32>() / 64.0;
//! assert!((mean_x - 0.5).abs() < 0.05);
//! # Ok::<(), strata::Error>(())
//! ```
//!
//! ## Features
//!
//! * `spectrum` (default): power spectra and point-set measures ([`spectrum`]).
//! * `io` (default): PNG, EXR and CSV output and plots ([`io`]).
//! * `lloyd` (default): Lloyd relaxation on the periodic Voronoi diagram (`spade`).
//! * `joe-kuo` (default): Joe and Kuo's Sobol' direction numbers for 1000 dimensions.
//!
//! With `default-features = false` the crate depends only on `rand`, `rand_pcg` and `glam`.

#![warn(missing_docs)]

pub mod analysis;
pub mod conformance;
pub mod error;
pub mod grid;
pub mod hash;
#[cfg(feature = "io")]
pub mod io;
pub mod occupancy;
pub mod pixel;
pub mod registry;
pub mod sampler;
pub mod samplers;
#[cfg(feature = "spectrum")]
pub mod spectrum;
mod stats;

pub use error::{Error, Result};

/// The README's code examples, compiled and run by `cargo test`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
pub use sampler::{Point2, Progression, Sampler, SamplerNd, StrataGrid};
