//! The samplers that need `std`, one family per file: the constructed PMJ sequences (pmj,
//! pmjbn, pmj02, pmj02bn), blue noise (Poisson disk, best candidate, Lloyd, CCVT, BNOT, the
//! blue-noise (0,m,2)-nets), orthogonal arrays, and the blue-noise dither masks of the frame
//! permutation ([`mask`]). The renderer crate's samplers
//! (`strata::samplers`: the classic ones, Sobol', Halton, the lattices, stochastic pmj02) are
//! the other half; [`crate::registry`] lists both.
//!
//! Which sampler is where: the table of the crate docs ([Samplers](crate#samplers)), generated
//! from the registry ([`crate::registry::table`]), where each lab sampler's file declares its
//! name, kind, promises, rates and paper.
//!
//! Fixed-count samplers run on the renderer crate's [`Blocks`](strata::samplers::Blocks)
//! machinery; those that build a whole set at once implement [`SetGenerator`] and run inside
//! [`Sets`].
//!
//! Lloyd relaxation runs on `spade`'s Delaunay triangulation (its dual, the Voronoi diagram, on
//! the torus by copying the points across the borders), as the design card asks; BNOT and CCVT
//! need power diagrams (weighted Voronoi cells), which [`crate::power`] computes exactly. A
//! Voronoi diagram is the power diagram with zero weights, so Lloyd could run on either; it
//! stays on `spade`, the established library, and a test checks that the two agree on the
//! cells of the same points.

pub mod best_candidate;
pub mod bnot;
pub mod bntable;
pub mod ccvt;
pub mod lloyd;
pub mod mask;
pub mod net02bn;
pub mod oa;
pub mod pmj;
pub mod poisson;
mod sets;

pub use best_candidate::BestCandidate;
pub use bnot::{Bnot, BnotSets};
pub use ccvt::{Ccvt, CcvtSets};
pub use lloyd::{Lloyd, LloydSets};
pub use net02bn::{Net02Bn, Net02BnSets};
pub use oa::{Bose, Bush};
pub use pmj::{Pmj, Pmj02Bn};
pub use poisson::{Bridson, BridsonDisk, DartThrowing, PoissonDisk};
pub use sets::{SetGenerator, Sets};

use crate::{Error, Result};

/// Validates a point count of a sampler that makes 1 to `max` points.
pub(crate) fn check_count(sampler: &'static str, count: u64, max: u64) -> Result<()> {
    if count == 0 || count > max {
        return Err(Error::count(
            sampler,
            count,
            format!("the count must be between 1 and {max}"),
        ));
    }
    Ok(())
}
