//! What `render` draws from: one of the crate's path-tracer sequences, a reference sampler
//! written in this program (pbrt-v4's padded Sobol' and ZSobol, [`crate::pbrt`]; OpenQMC's
//! blue-noise Sobol', [`crate::openqmc`]), or an
//! experiment on the crate's padding (a crate sequence whose draws are paired anew).

use glam::Vec2;
use strata::pixel::{Padding, PixelSampler, Sequence};

use crate::common::{CliError, cli_error};
use crate::openqmc::OpenQmcBn;
use crate::pbrt::{self, PaddedSobol, Randomize, ZSobol};
use crate::trace::Draws;

/// The reference samplers' names (`--samplers`; not in `all`).
pub const REFERENCES: [&str; 4] = [
    "pbrt-padded",
    "pbrt-zsobol",
    "pbrt-zsobol-seeded",
    "openqmc-sobolbn",
];

/// A sampler of `--samplers`.
#[derive(Clone, Debug, PartialEq)]
pub enum Method {
    /// A crate sequence, through [`PixelSampler`] with `--padding`.
    Crate(Sequence),
    /// pbrt-v4's `PaddedSobolSampler` (FastOwen).
    PbrtPadded,
    /// pbrt-v4's `ZSobolSampler` (FastOwen); `seeded`: with the seed in the hash of its pixel
    /// order (pbrt's depends on the dimension only, so that every seed orders the pixels alike).
    PbrtZSobol { seeded: bool },
    /// OpenQMC's `SobolBnSampler` (progressive blue noise from a 256 x 256 table).
    OpenQmcBn,
    /// An experiment: a crate sequence (with `--padding`) whose draw at dimension `d` reads the
    /// sample `perm_d(i)` instead of sample `i`.
    Repaired(Sequence, Repair),
}

/// How [`Method::Repaired`] permutes a pixel's sample index per draw (keyed by the pixel, the
/// draw's dimension and the seed: pbrt's hash and `PermutationElement`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Repair {
    /// pbrt's pairing: a random permutation of the whole pixel's `0..spp` (every power-of-two
    /// prefix below `spp` loses its net).
    Permute,
    /// (Not `Padding::Shells`, whose affine maps are another algorithm.) A random permutation
    /// inside each dyadic shell `[2^j, 2^(j+1))` of the index (0 and 1
    /// stay): every power-of-two prefix keeps its set of samples, so it stays the net it was,
    /// while two draws' samples meet at random inside each shell. Needs no sample count.
    ShellPermutations,
}

impl Method {
    /// The sampler named `name` for an image of `size`.
    pub fn by_name(name: &str, size: (u32, u32)) -> Result<Method, CliError> {
        match name {
            "pbrt-padded" => return Ok(Method::PbrtPadded),
            "pbrt-zsobol" => return Ok(Method::PbrtZSobol { seeded: false }),
            "pbrt-zsobol-seeded" => return Ok(Method::PbrtZSobol { seeded: true }),
            "openqmc-sobolbn" => return Ok(Method::OpenQmcBn),
            _ => {}
        }
        let resolution = [size.0, size.1];
        if let Some((seq, repair)) = name.split_once('+') {
            let repair = match repair {
                "permute" => Repair::Permute,
                "shells" => Repair::ShellPermutations,
                other => {
                    return Err(cli_error(format!(
                        "--samplers {name:?}: '+{other}' is not an experiment; allowed: \
                         SEQUENCE+permute, SEQUENCE+shells"
                    )));
                }
            };
            let seq = Sequence::by_name(seq, resolution)?;
            return Ok(Method::Repaired(seq, repair));
        }
        Sequence::by_name(name, resolution)
            .map(Method::Crate)
            .map_err(|e| {
                cli_error(format!(
                    "{e}; also the references {} and the experiments SEQUENCE+permute, \
                 SEQUENCE+shells",
                    REFERENCES.join(", ")
                ))
            })
    }

    /// Refuses a count the sampler cannot take: the crate's own checks; pbrt-zsobol (which
    /// rounds a count down to a power of two) and the `permute` experiment need powers of two.
    pub fn check_spp(&self, spp: u32) -> Result<(), CliError> {
        match self {
            Method::Crate(seq) | Method::Repaired(seq, _) => {
                PixelSampler::new(seq.clone(), spp, strata::Seed(0))?;
            }
            Method::PbrtPadded | Method::OpenQmcBn => {}
            Method::PbrtZSobol { .. } => {}
        }
        let why = match self {
            Method::PbrtZSobol { .. } => {
                "pbrt-zsobol and pbrt-zsobol-seeded take powers of two only (pbrt's ZSobol \
                 rounds the count down)"
            }
            Method::Repaired(_, Repair::Permute) => {
                "the +permute experiments take powers of two only (a permutation of a pixel's \
                 samples keeps the sequence's net only when they are a whole power of two)"
            }
            _ => return Ok(()),
        };
        if !spp.is_power_of_two() {
            return Err(cli_error(format!("--spp {spp}: {why}")));
        }
        Ok(())
    }
}

/// A sampler the path tracer renders a pixel with: [`Draws`] and where each sample starts.
pub trait PixelDraws: Draws + Clone + Send + Sync {
    fn start(&mut self, pixel: [u32; 2], index: u32);
}

impl PixelDraws for PixelSampler {
    #[inline]
    fn start(&mut self, pixel: [u32; 2], index: u32) {
        self.start_pixel_sample(pixel, index as u64, 0);
    }
}

/// The seed of a pbrt sampler for `render`'s seed: its low 32 bits (pbrt's seed is an `int`).
pub fn pbrt_seed(seed: u64) -> u32 {
    seed as u32
}

macro_rules! pbrt_draws {
    ($t:ty) => {
        impl Draws for $t {
            #[inline]
            fn get_pixel_2d(&mut self) -> Vec2 {
                <$t>::get_pixel_2d(self).into()
            }
            #[inline]
            fn get_2d(&mut self) -> Vec2 {
                <$t>::get_2d(self).into()
            }
            #[inline]
            fn get_1d(&mut self) -> f32 {
                <$t>::get_1d(self)
            }
            #[inline]
            fn start_bounce(&mut self, k: u32) {
                self.set_dimension(strata::pixel::DimensionLayout::default().bounce_start(k));
            }
            #[inline]
            fn dimension(&self) -> u32 {
                <$t>::dimension(self)
            }
            #[inline]
            fn set_dimension(&mut self, dim: u32) {
                <$t>::set_dimension(self, dim)
            }
        }

        impl PixelDraws for $t {
            #[inline]
            fn start(&mut self, pixel: [u32; 2], index: u32) {
                self.start_pixel_sample(pixel, index, 0);
            }
        }
    };
}

pbrt_draws!(PaddedSobol);
pbrt_draws!(ZSobol);
pbrt_draws!(OpenQmcBn);

/// [`Method::Repaired`]: the crate's sampler, each draw at the permuted sample index.
#[derive(Clone, Debug)]
pub struct Repaired {
    inner: PixelSampler,
    repair: Repair,
    spp: u32,
    seed: i32,
    pixel: [u32; 2],
    index: u32,
    dim: u32,
}

impl Repaired {
    pub fn new(inner: PixelSampler, repair: Repair, spp: u32, seed: u64) -> Self {
        Repaired {
            inner,
            repair,
            spp,
            // a seed of its own beside the crate's (the permutations' keys)
            seed: (pbrt_seed(seed) ^ 0x5ea1_5ea1) as i32,
            pixel: [0, 0],
            index: 0,
            dim: 0,
        }
    }

    /// The sample index the draw at `dim` reads.
    #[inline]
    fn index_at(&self, dim: u32) -> u64 {
        let [x, y] = self.pixel;
        let hash = pbrt::hash_i32(&[x as i32, y as i32, dim as i32, self.seed]);
        let i = self.index;
        match self.repair {
            Repair::Permute => pbrt::permutation_element(i, self.spp, hash as u32) as u64,
            Repair::ShellPermutations => {
                if i < 2 {
                    return i as u64;
                }
                let j = i.ilog2();
                // each shell its own permutation: the hash's high word mixed with the shell
                let key = (hash >> 32) as u32 ^ (j.wrapping_mul(0x9e37_79b9));
                let shell = 1u32 << j;
                (shell + pbrt::permutation_element(i - shell, shell, key)) as u64
            }
        }
    }
}

impl Draws for Repaired {
    fn get_pixel_2d(&mut self) -> Vec2 {
        self.get_2d()
    }
    fn get_2d(&mut self) -> Vec2 {
        let d = self.dim;
        self.dim = d.wrapping_add(2);
        self.inner.sample_2d(self.pixel, self.index_at(d), d).into()
    }
    fn get_1d(&mut self) -> f32 {
        let d = self.dim;
        self.dim = d.wrapping_add(1);
        self.inner.sample_1d(self.pixel, self.index_at(d), d)
    }
    fn start_bounce(&mut self, k: u32) {
        self.dim = self.inner.layout().bounce_start(k);
    }
    fn dimension(&self) -> u32 {
        self.dim
    }
    fn set_dimension(&mut self, dim: u32) {
        self.dim = dim;
    }
}

impl PixelDraws for Repaired {
    fn start(&mut self, pixel: [u32; 2], index: u32) {
        self.pixel = pixel;
        self.index = index;
        self.dim = 0;
    }
}

/// A sampler's values as stateless functions of (pixel, index, dimension), for the
/// interaction split ([`crate::split::Mixed`]).
pub trait Stateless: Sync {
    fn sample_1d(&self, pixel: [u32; 2], index: u64, dim: u32) -> f32;
    fn sample_2d(&self, pixel: [u32; 2], index: u64, dim: u32) -> Vec2;
}

impl Stateless for PixelSampler {
    fn sample_1d(&self, pixel: [u32; 2], index: u64, dim: u32) -> f32 {
        PixelSampler::sample_1d(self, pixel, index, dim)
    }
    fn sample_2d(&self, pixel: [u32; 2], index: u64, dim: u32) -> Vec2 {
        PixelSampler::sample_2d(self, pixel, index, dim).into()
    }
}

/// Any [`PixelDraws`] as a stateless one: a copy started at the sample, moved to the dimension.
pub struct ByCopy<S>(pub S);

impl<S: PixelDraws> Stateless for ByCopy<S> {
    fn sample_1d(&self, pixel: [u32; 2], index: u64, dim: u32) -> f32 {
        let mut s = self.0.clone();
        s.start(pixel, index as u32);
        s.set_dimension(dim);
        s.get_1d()
    }
    fn sample_2d(&self, pixel: [u32; 2], index: u64, dim: u32) -> Vec2 {
        let mut s = self.0.clone();
        s.start(pixel, index as u32);
        s.set_dimension(dim);
        s.get_2d()
    }
}

/// Runs `f` with the sampler of `method` at `spp` for `seed` (an image of `size`, the crate's
/// sequences with `padding`), as whichever concrete type it is.
pub fn with_sampler<R>(
    method: &Method,
    spp: u32,
    size: (u32, u32),
    seed: u64,
    padding: Padding,
    f: impl Visit<R>,
) -> Result<R, strata_lab::Error> {
    Ok(match method {
        Method::Crate(seq) => {
            f.visit(PixelSampler::new(seq.clone(), spp, strata::Seed(seed))?.with_padding(padding))
        }
        Method::PbrtPadded => f.visit(PaddedSobol::new(spp, pbrt_seed(seed), Randomize::FastOwen)),
        Method::OpenQmcBn => f.visit(OpenQmcBn::new(seed)),
        Method::PbrtZSobol { seeded } => {
            let s = ZSobol::new(spp, [size.0, size.1], pbrt_seed(seed), Randomize::FastOwen);
            f.visit(if *seeded { s.with_seeded_order() } else { s })
        }
        Method::Repaired(seq, repair) => {
            let inner =
                PixelSampler::new(seq.clone(), spp, strata::Seed(seed))?.with_padding(padding);
            f.visit(Repaired::new(inner, *repair, spp, seed))
        }
    })
}

/// What [`with_sampler`] runs: generic over the sampler's type.
pub trait Visit<R> {
    fn visit<S: PixelDraws + 'static>(self, s: S) -> R;
}
