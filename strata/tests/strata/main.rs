//! The renderer crate's integration tests, in one test binary: the path-tracer adapter's
//! guarantees, the golden digests of its samplers and sequences, and that nothing allocates
//! after construction. One module per subject, in `tests/strata/`.

mod common;
mod golden;
mod no_alloc;
mod pixel;
mod public_api;
mod surface;
