//! The path tracer: camera samples through the path-tracer adapter, bounces with next-event
//! estimation, a lobe choice and Russian roulette, and the image of one sequence at one count.

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use strata::pixel::frames::SeedPermutation;
use strata::pixel::{Padding, PixelSampler, warp};

use crate::method::{Method, PixelDraws, Visit, with_sampler};
use crate::scene::{Hit, Material, Scene, SceneKind, checker};

/// The most bounces of a path.
pub const MAX_BOUNCES: u32 = 8;

// The dimensions of a bounce, at fixed offsets from `start_bounce`, so that every draw keeps
// its dimension whatever the path did before (a mirror bounce skips the light draws).
pub const LOBE: u32 = 0;
pub const LIGHT_CHOICE: u32 = 1;
pub const LIGHT_POINT: u32 = 2; // 2-3
const DIRECTION: u32 = 4; // 4-5
const ROULETTE: u32 = 6;

/// Where the draws of a path go (`--layout`).
///
/// * `bounce` (the default): the camera's block holds the film position (0-1), the lens
///   (2-3) and the time (4); each bounce's block its lobe choice (0), light choice (1), light
///   point (2-3), direction (4-5) and Russian roulette (6).
/// * `interacting`: the draws that meet in one integrand share an aligned group of
///   dimensions, so that a joint sequence (`zquad`, `zjoint`, `sobol12`, `zsobol12`)
///   stratifies them together: the film position with the first hit's light point and light
///   choice (camera 0-1, 2-3 and 4; the time at 5, the lens at 6-7), and each bounce's
///   direction (its block's 0-1) with the next hit's light point (2-3) and light choice (4);
///   the lobe choice at 5, Russian roulette at 6. Bounce `k`'s light draws are then in bounce
///   `k - 1`'s block (the camera's for the first). Groups of 4 hold a position and the light
///   point it meets, groups of 8 the light choice too.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Layout {
    /// the camera's and each bounce's own block
    Bounce,
    /// the film position with the first light point and each direction with the next light
    /// point in one aligned group of four dimensions, for zquad and sobol12-4/zsobol12-4
    Interacting,
}

impl Layout {
    /// The offsets in a bounce's block of its lobe choice and its direction, and of the
    /// roulette.
    fn offsets(self) -> (u32, u32, u32) {
        match self {
            Layout::Bounce => (LOBE, DIRECTION, ROULETTE),
            Layout::Interacting => (5, 0, 6),
        }
    }

    /// The dimensions of bounce `k`'s light choice and light point, its block starting at
    /// `base` (the default [`strata::pixel::DimensionLayout`]: eight dimensions for the camera
    /// and per bounce).
    fn light(self, k: u32, base: u32) -> (u32, u32) {
        match self {
            Layout::Bounce => (base + LIGHT_CHOICE, base + LIGHT_POINT),
            Layout::Interacting => {
                let from = if k == 0 { 0 } else { base - 8 };
                (from + 4, from + 2)
            }
        }
    }

    /// The first dimensions of the draws of a direct-lighting path (the camera's and the first
    /// bounce's), which the interaction split takes one at a time: the film position, the
    /// lens, the time (`spheres` only), the lobe choice, the light choice and the light point.
    pub fn split_draws(self, time: bool) -> Vec<u32> {
        let b0 = strata::pixel::DimensionLayout::default().bounce_start(0);
        let (lens, t) = self.camera();
        let (lobe, _, _) = self.offsets();
        let (choice, point) = self.light(0, b0);
        let mut draws = vec![0, lens];
        if time {
            draws.push(t);
        }
        draws.extend([b0 + lobe, choice, point]);
        draws
    }

    /// The camera's dimensions of the lens and the time.
    fn camera(self) -> (u32, u32) {
        match self {
            Layout::Bounce => (2, 4),
            Layout::Interacting => (6, 5),
        }
    }
}

/// An orthonormal basis around `n` (Duff et al. 2017).
fn basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// Direct light at a point from one light chosen by `choice`, a point on it by `on`, through
/// the BRDF `brdf` (times pi: the albedo of a diffuse surface) towards the light's direction.
fn next_event(
    scene: &Scene,
    p: Vec3,
    n: Vec3,
    time: f32,
    (choice, on): (f32, Vec2),
    brdf: impl Fn(Vec3) -> Vec3,
) -> Vec3 {
    let mut c = 0.0;
    let (mut index, mut prob) = scene.lights[scene.lights.len() - 1];
    for &(i, pr) in &scene.lights {
        c += pr;
        if choice < c {
            (index, prob) = (i, pr);
            break;
        }
    }
    let light = &scene.rects[index];
    let Material::Light { radiance } = light.material else {
        return Vec3::ZERO;
    };
    let q = light.point(on);
    let to = q - p;
    let d2 = to.length_squared();
    let l = to / d2.sqrt();
    let (cos_s, cos_l) = (n.dot(l), -light.normal().dot(l));
    if cos_s <= 0.0 || cos_l <= 0.0 || !scene.visible(p + n * 1e-4, q, time) {
        return Vec3::ZERO;
    }
    brdf(l) * (radiance * (cos_s * cos_l / d2 * light.area() / prob / std::f32::consts::PI))
}

/// What the path tracer asks of its sampler: the adapter's draw calls ([`PixelSampler`], or
/// [`Mixed`](crate::split::Mixed) for the interaction split).
pub trait Draws {
    fn get_pixel_2d(&mut self) -> Vec2;
    fn get_2d(&mut self) -> Vec2;
    fn get_1d(&mut self) -> f32;
    fn start_bounce(&mut self, k: u32);
    fn dimension(&self) -> u32;
    fn set_dimension(&mut self, dim: u32);
}

impl Draws for PixelSampler {
    fn get_pixel_2d(&mut self) -> Vec2 {
        PixelSampler::get_pixel_2d(self).into()
    }
    fn get_2d(&mut self) -> Vec2 {
        PixelSampler::get_2d(self).into()
    }
    fn get_1d(&mut self) -> f32 {
        PixelSampler::get_1d(self)
    }
    fn start_bounce(&mut self, k: u32) {
        PixelSampler::start_bounce(self, k)
    }
    fn dimension(&self) -> u32 {
        PixelSampler::dimension(self)
    }
    fn set_dimension(&mut self, dim: u32) {
        PixelSampler::set_dimension(self, dim)
    }
}

/// The state of a path being traced: the ray, its throughput, the radiance gathered so far,
/// and whether the next light hit counts (not after next-event estimation counted the lights).
struct Path {
    origin: Vec3,
    dir: Vec3,
    throughput: Vec3,
    sum: Vec3,
    count_emission: bool,
    /// A diffuse bounce is behind: next-event estimation leaves the glossy lobes out (their
    /// light after a diffuse bounce is a glossy caustic, left out as the mirror's are).
    diffused: bool,
}

/// What a surface hit does: its (textured) diffuse albedo, the probability weights of its
/// mirror and glossy lobes, and the glossy lobe's colour and exponent.
#[derive(Clone, Copy)]
struct Surface {
    albedo: Vec3,
    mirror: f32,
    gloss: f32,
    specular: Vec3,
    exponent: f32,
}

/// Radiance along one camera sample.
pub fn radiance<S: Draws>(px: u32, py: u32, size: (u32, u32), s: &mut S, scene: &Scene) -> Vec3 {
    let film = s.get_pixel_2d();
    let (lens_dim, time_dim) = scene.layout.camera();
    s.set_dimension(lens_dim);
    let lens = s.get_2d();
    let time = if scene.kind == SceneKind::Spheres {
        s.set_dimension(time_dim);
        s.get_1d()
    } else {
        0.0
    };
    let (origin, dir) = scene.camera.ray(px, py, size, film, lens);
    let mut path = Path {
        origin,
        dir,
        throughput: Vec3::ONE,
        sum: Vec3::ZERO,
        count_emission: true,
        diffused: false,
    };
    for bounce in 0..MAX_BOUNCES {
        if !path.bounce(bounce, s, scene, time) {
            break;
        }
    }
    path.sum
}

/// Dimension `k` of the bounce whose dimensions start at `base`, as a 1D draw.
fn draw_1d<S: Draws>(s: &mut S, base: u32, k: u32) -> f32 {
    s.set_dimension(base + k);
    s.get_1d()
}

/// Dimensions `k` and `k + 1` of the bounce whose dimensions start at `base`, as a 2D draw.
fn draw_2d<S: Draws>(s: &mut S, base: u32, k: u32) -> Vec2 {
    s.set_dimension(base + k);
    s.get_2d()
}

impl Path {
    /// One bounce: the next hit, its emission, a scattered ray and Russian roulette from the
    /// third bounce; false when the path ends.
    fn bounce<S: Draws>(&mut self, bounce: u32, s: &mut S, scene: &Scene, time: f32) -> bool {
        let Some(hit) = scene.intersect(self.origin, self.dir, time) else {
            self.sum += self.throughput * scene.sky;
            return false;
        };
        let Some(surface) = self.surface(&hit, scene) else {
            return false;
        };
        s.start_bounce(bounce);
        let base = s.dimension();
        if !self.scatter(s, (bounce, base), scene, &hit, surface, time) {
            return false;
        }
        if bounce >= 2 {
            let q = self.throughput.max_element().clamp(0.05, 0.95);
            if draw_1d(s, base, scene.layout.offsets().2) >= q {
                return false;
            }
            self.throughput /= q;
        }
        true
    }

    /// The surface hit: its albedo (with the `spheres` ground's checkerboard, or the
    /// material's texture) and lobes; `None` at a light, whose emission is added when it counts.
    fn surface(&mut self, hit: &Hit, scene: &Scene) -> Option<Surface> {
        let plain = |albedo, mirror| Surface {
            albedo,
            mirror,
            gloss: 0.0,
            specular: Vec3::ZERO,
            exponent: 1.0,
        };
        match hit.material {
            Material::Light { radiance } => {
                if self.count_emission && hit.normal.dot(self.dir) < 0.0 {
                    self.sum += self.throughput * radiance;
                }
                None
            }
            Material::Surface { albedo, mirror } => {
                let albedo = if scene.kind == SceneKind::Spheres && hit.normal == Vec3::Y {
                    albedo * checker(hit.point)
                } else {
                    albedo
                };
                Some(plain(albedo, mirror))
            }
            Material::Glossy {
                texture,
                gloss,
                specular,
                exponent,
            } => Some(Surface {
                albedo: texture.at(hit.point),
                mirror: 0.0,
                gloss,
                specular,
                exponent,
            }),
        }
    }

    /// The next ray from `hit`, whose surface is `surface`: the mirror lobe, chosen with its
    /// weight, or next-event estimation (through the diffuse and the glossy lobe) and a
    /// direction sampled from the glossy lobe or the cosine, chosen by the lobes' weights;
    /// false when the path ends there (direct lighting only in `spheres`, `cornell-direct` and
    /// `studio-direct`).
    fn scatter<S: Draws>(
        &mut self,
        s: &mut S,
        (bounce, base): (u32, u32),
        scene: &Scene,
        hit: &Hit,
        surface: Surface,
        time: f32,
    ) -> bool {
        let Surface {
            albedo,
            mirror,
            gloss,
            ..
        } = surface;
        // face the normal towards the incoming ray
        let n = if hit.normal.dot(self.dir) < 0.0 {
            hit.normal
        } else {
            -hit.normal
        };
        let (lobe, direction, _) = scene.layout.offsets();
        let (choice, point) = scene.layout.light(bounce, base);
        if mirror > 0.0 && draw_1d(s, base, lobe) < mirror {
            // the mirror lobe, chosen with its own weight: the weights cancel
            self.throughput *= albedo;
            self.dir -= 2.0 * self.dir.dot(n) * n;
            self.origin = hit.point + n * 1e-4;
            // `count_emission` stays as it was: lights seen in the mirror count on the camera's
            // specular chain only; caustics (diffuse, mirror, light) are left out, in the
            // reference too, as their variance would drown every sampler's difference
        } else {
            let light = (draw_1d(s, choice, 0), draw_2d(s, point, 0));
            let reflected = self.dir - 2.0 * self.dir.dot(n) * n;
            let direct = if gloss > 0.0 && !self.diffused {
                // both lobes towards the light (times pi)
                let lobe = (surface.exponent + 2.0) / 2.0;
                let brdf = |l: Vec3| {
                    (1.0 - gloss) * albedo
                        + gloss
                            * surface.specular
                            * (lobe * reflected.dot(l).max(0.0).powf(surface.exponent))
                };
                next_event(scene, hit.point, n, time, light, brdf)
            } else {
                next_event(scene, hit.point, n, time, light, |_| albedo)
            };
            self.sum += self.throughput * direct;
            if scene.direct {
                return false; // direct lighting only
            }
            let u = draw_2d(s, base, direction);
            if gloss > 0.0 && draw_1d(s, base, lobe) < gloss {
                // the glossy lobe, chosen with its own weight: the weights cancel
                let Some((dir, weight)) = phong(reflected, n, surface.exponent, u) else {
                    return false;
                };
                self.throughput *= surface.specular * weight;
                self.dir = dir;
            } else {
                let local = Vec3::from(warp::cosine_hemisphere(u.into()));
                let (t, b) = basis(n);
                self.dir = (t * local.x + b * local.y + n * local.z).normalize();
                self.throughput *= albedo; // cosine sampling: f cos / pdf = albedo
                self.diffused = true;
            }
            self.origin = hit.point + n * 1e-4;
            self.count_emission = false; // next-event estimation counted the lights
        }
        true
    }
}

/// A direction sampled from the normalized Phong lobe of exponent `exponent` around
/// `reflected`, by `u`, above the surface of normal `n`, with its weight `f cos / pdf`
/// (without the lobe's colour): `(n + 2) / (n + 1) cos`. `None` below the surface.
fn phong(reflected: Vec3, n: Vec3, exponent: f32, u: Vec2) -> Option<(Vec3, f32)> {
    let cos_a = u.x.powf(1.0 / (exponent + 1.0));
    let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * u.y;
    let (t, b) = basis(reflected);
    let dir = (t * (sin_a * phi.cos()) + b * (sin_a * phi.sin()) + reflected * cos_a).normalize();
    let cos = dir.dot(n);
    (cos > 0.0).then_some((dir, (exponent + 2.0) / (exponent + 1.0) * cos))
}

/// Renders the image (linear radiance, row-major) with `spp` samples of `method` (the crate's
/// sequences with `padding`).
pub fn render(
    scene: &Scene,
    method: &Method,
    spp: u32,
    size: (u32, u32),
    seed: u64,
    progress: Option<&str>,
    padding: Padding,
) -> Result<Vec<Vec3>, strata_lab::Error> {
    render_counts(
        scene,
        method,
        Counts::Fixed(spp),
        size,
        seed,
        progress,
        padding,
        None,
    )
}

/// How many samples each pixel takes: `Fixed(spp)`, or `Adaptive { max, key }`: pixel `(x, y)`
/// takes [`Counts::at`] samples, from 1 to `max`, varying smoothly across the image as an
/// adaptive sampler's counts follow the image's variance.
#[derive(Clone, Copy, Debug)]
pub enum Counts {
    Fixed(u32),
    Adaptive { max: u32, key: u64 },
}

/// The cell of the adaptive counts' random field, pixels.
pub const COUNT_CELL: u32 = 16;

impl Counts {
    /// The samples of pixel `(x, y)`: for `Adaptive`, `1 + floor(max u)`, `u` the bilinear
    /// interpolation of values uniform in `[0, 1)` hashed at the corners of `COUNT_CELL`-pixel
    /// cells.
    #[inline]
    pub fn at(&self, x: u32, y: u32) -> u32 {
        match *self {
            Counts::Fixed(spp) => spp,
            Counts::Adaptive { max, key } => {
                let corner = |cx: u32, cy: u32| {
                    let h = strata::hash::hash_u64((cy as u64) << 32 | cx as u64, key);
                    (h >> 11) as f64 / (1u64 << 53) as f64
                };
                let (cx, cy) = (x / COUNT_CELL, y / COUNT_CELL);
                let c = COUNT_CELL as f64;
                let (fx, fy) = ((x % COUNT_CELL) as f64 / c, (y % COUNT_CELL) as f64 / c);
                let top = corner(cx, cy) * (1.0 - fx) + corner(cx + 1, cy) * fx;
                let bottom = corner(cx, cy + 1) * (1.0 - fx) + corner(cx + 1, cy + 1) * fx;
                let u = top * (1.0 - fy) + bottom * fy;
                (1 + (u * max as f64) as u32).min(max)
            }
        }
    }
}

/// [`render`] with each pixel stopping at its own count, `Counts::Adaptive { max, key }`; the
/// sampler is made for `max` samples per pixel.
pub fn render_adaptive(
    scene: &Scene,
    method: &Method,
    counts: Counts,
    size: (u32, u32),
    seed: u64,
    padding: Padding,
) -> Result<Vec<Vec3>, strata_lab::Error> {
    render_counts(scene, method, counts, size, seed, None, padding, None)
}

/// [`render`] with each pixel taking the draws of the pixel `seeds` gives it (`--frames`).
pub fn render_remapped(
    scene: &Scene,
    method: &Method,
    spp: u32,
    size: (u32, u32),
    seed: u64,
    padding: Padding,
    seeds: Option<&SeedPermutation>,
) -> Result<Vec<Vec3>, strata_lab::Error> {
    render_counts(
        scene,
        method,
        Counts::Fixed(spp),
        size,
        seed,
        None,
        padding,
        seeds,
    )
}

#[allow(clippy::too_many_arguments)]
fn render_counts(
    scene: &Scene,
    method: &Method,
    counts: Counts,
    size: (u32, u32),
    seed: u64,
    progress: Option<&str>,
    padding: Padding,
    seeds: Option<&SeedPermutation>,
) -> Result<Vec<Vec3>, strata_lab::Error> {
    /// [`render_with`] for whichever sampler `method` is.
    struct Go<'a> {
        scene: &'a Scene,
        counts: Counts,
        size: (u32, u32),
        progress: Option<&'a str>,
        seeds: Option<&'a SeedPermutation>,
    }
    impl Visit<Vec<Vec3>> for Go<'_> {
        fn visit<S: PixelDraws + 'static>(self, s: S) -> Vec<Vec3> {
            render_with(
                self.scene,
                s,
                self.counts,
                self.size,
                self.progress,
                self.seeds,
            )
        }
    }
    let spp = match counts {
        Counts::Fixed(spp) => spp,
        Counts::Adaptive { max, .. } => max,
    };
    let go = Go {
        scene,
        counts,
        size,
        progress,
        seeds,
    };
    with_sampler(method, spp, size, seed, padding, go)
}

/// Renders the image with `counts` samples per pixel of `sampler` (cloned per row), each
/// pixel taking the draws of the pixel `seeds` gives it (its own without).
fn render_with<S: PixelDraws>(
    scene: &Scene,
    sampler: S,
    counts: Counts,
    size: (u32, u32),
    progress: Option<&str>,
    seeds: Option<&SeedPermutation>,
) -> Vec<Vec3> {
    let rows_done = std::sync::atomic::AtomicU32::new(0);
    let rows: Vec<Vec<Vec3>> = (0..size.1)
        .into_par_iter()
        .map(|y| {
            let mut s = sampler.clone();
            let row = (0..size.0)
                .map(|x| {
                    let mut sum = Vec3::ZERO;
                    let from = seeds.map_or([x, y], |p| p.source([x, y]));
                    let spp = counts.at(x, y);
                    for i in 0..spp {
                        s.start(from, i);
                        sum += radiance(x, y, size, &mut s, scene);
                    }
                    sum / spp as f32
                })
                .collect();
            if let Some(label) = progress {
                // a line at every tenth of the rows, so a long reference shows how far it got
                let done = rows_done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                let tenth = |k: u32| (k as u64 * 10 / size.1 as u64) as u32;
                if tenth(done) > tenth(done - 1) {
                    eprintln!("{label}: {}0% of the rows", tenth(done));
                }
            }
            row
        })
        .collect();
    rows.concat()
}
