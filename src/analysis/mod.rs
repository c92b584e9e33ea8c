//! Measuring the trade between speed and accuracy: test integrands with exact values,
//! convergence studies over seeds and counts, slopes, generation time, discrepancy, and the
//! variance predicted from spectra.
//!
//! The study ([`study::run`]): for each sampler, integrand and allowed count `N` between two
//! bounds, the estimate `(1/N) sum f(x_k)` over `K` seeds (seed `s` uses exactly the points that
//! `points --sampler NAME -n N --seed s` prints), their mean, variance and RMSE against the exact
//! value, the least-squares slope of `log variance` against `log N`, and the generation time
//! per sample. Seeds run in parallel with rayon; results are reduced in seed order, so every
//! number but the timings is bit-identical for any thread count.

pub mod discrepancy;
mod fit;
pub mod fourier;
mod integrands;
pub mod study;

pub use integrands::Integrand;
