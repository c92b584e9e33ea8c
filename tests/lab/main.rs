//! The lab's integration tests, in one test binary (one link instead of one per file): every
//! sampler through the registry, spectra, point-set files, the programs' command lines, the
//! conformance suite, the golden digests. One module per subject, in `tests/lab/`.

mod adapter;
mod blue_noise;
mod bnot;
mod cli;
mod common;
mod conformance;
mod contract;
mod docs;
mod extremes;
mod golden;
mod high_dim;
mod hostile;
mod pmj;
mod pointsets;
mod properties;
mod public_api;
mod render_openqmc;
mod render_pbrt;
mod spectrum;
mod stratification;
mod tradeoff;
