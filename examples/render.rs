//! `render`: the samplers inside a small path tracer, against a converged reference, over a
//! sweep of sample counts.
//!
//! ```text
//! cargo run --release --example render -- [--samplers a,b,..|all] [--spp N[,N,..]]
//!         [--size WxH] [--scene cornell|spheres] [--reference-spp N] [--out DIR]
//! ```
//!
//! Two scenes, both through the path-tracer adapter (`strata::pixel::PixelSampler`):
//!
//! * `cornell` (default): a Cornell box lit by two area lights, with a white diffuse sphere and
//!   a sphere that is half mirror, half diffuse. Up to eight bounces of diffuse
//!   interreflection, next-event estimation with a discrete choice of light (by power), a
//!   discrete choice of lobe, Russian roulette from the third bounce, and a thin-lens camera
//!   (caustics, diffuse-mirror-light paths, are left out, as in many production renderers):
//!   about 60 sample dimensions per path, each bounce at a fixed dimension budget
//!   (`start_bounce`), as a real path tracer takes them.
//! * `spheres`: direct lighting only (seven dimensions: pixel, lens, time, light).
//!
//! The reference is scrambled Sobol' at `--reference-spp` (default 16 times the largest count,
//! at least 1024) with another seed.

mod common;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use common::{CliError, cli_error, parse_int, string_value};
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use strata::analysis::study;
use strata::io::{self, Canvas, LinePlot, Marker, Rgb, Series};
use strata::pixel::{DimensionLayout, Padding, PixelSampler, Sequence, warp};
use strata::spectrum::{self, ErrorImage};

const USAGE: &str = "render [--samplers a,b,..|all] [--spp N[,N,..]] [--size WxH] \
[--scene cornell|spheres] [--reference-spp N] [--seed S] [--seeds K] [--out DIR] [--markdown FILE]";

const HELP: &str = "\
render: a small path tracer rendered with each sampler at one or more sample counts and
compared with a converged reference.

Usage:
  cargo run --release --example render -- [options]

Options:
  --samplers a,b,..|all  samplers with a path-tracer adapter: random, jittered, pmj02, sobol,
                         halton, lattice, zsobol, zpmj02, zjoint, and zjoint-G (groups of G
                         dimensions) (default all; the Z-ordered ones for the image size)
  --spp N[,N,..]         samples per pixel, one to eight counts (default 4,16,64,256; each 1
                         to 65536; jittered needs squares)
  --size WxH             image size (default 128x128; each side 8 to 1024: every sequence and
                         count keeps its image until the pictures are drawn, about 1.2 GB at
                         1024x1024 with four counts)
  --scene NAME           cornell (default: a Cornell box, up to 8 bounces, two lights, a
                         discrete light and lobe choice, Russian roulette, thin lens), spheres
                         (direct lighting, seven dimensions) or cornell-direct (the Cornell box
                         in direct lighting: the first diffuse hit's next-event estimate)
  --padding nested|uniform  how two draws' samples meet (strata::Padding; default nested:
                         every power-of-two prefix a net; uniform: each block of spp samples
                         reordered per draw by a sharply 2-transitive map)
  --reference-spp N      samples per pixel of the reference (default 16 x the largest count,
                         at least 1024, at most 65536; never below the largest count)
  --seed S               seed of the samplers (u64, default 1; the reference has its own)
  --seeds K              renders per sampler and count, seeds S to S+K-1 (default 4, 1 to
                         64): rmse and rel_rmse are over all of them (the root of the mean
                         squared error), ms is the mean time; the pictures show seed S
  --out DIR              output directory (default out/render)
  --interactions         at the smallest count, also split the error (emitters masked) into
                         its one-draw part (each draw's main effect, the other draws
                         integrated out by 64 Sobol' points) and the interaction part (the
                         rest), and print their RMSE, blurred RMSE and low-band share
                         (direct-lighting scenes only: spheres, cornell-direct)
  --markdown FILE        also write the tables into FILE, as its section
                         'render-SCENE-COUNTS' (e.g. render-cornell-4,16,64,256)
  -h, --help             this text

Writes, into DIR: render.csv (sampler,spp,rmse,rel_rmse,ms,blur1_rmse,blur2_rmse,lowband,
masked_rmse,masked_blur1_rmse,masked_blur2_rmse,masked_lowband: one row per sampler and count;
rmse over all pixels and channels of linear radiance, rel_rmse of |I - R| / (R + 0.02) on
luminance, ms the render time on all cores; blur1_rmse, blur2_rmse and lowband describe the
signed luminance error image: its RMSE after a Gaussian blur of sigma 1 and 2 pixels, and the
share of its power (mean error excluded) below 1/8 cycle per pixel, about 0.05 for white
error; the masked_ columns are rmse and those three without the pixels that see an emitter,
directly or in a mirror, whose error is the emitter's edge), emitter-mask.png (the reference with
those pixels in magenta), NAME.png and NAME-error.png (the largest count; the error map is the per-pixel
relative error, colour-mapped from 0 to 0.5), NAME-SPP.png and NAME-SPP-error-spectrum.png
(the signed error image beside its periodogram) for each count, reference.png, compare.png
(one row per sampler), blue-noise.png (every sampler's error image and periodogram at the
smallest count) and blue-noise-masked.png (the same without the pixels that see an emitter), convergence.png (RMSE against spp with the fitted slope per sampler) and
pareto.png (RMSE against render time, the sequences on the Pareto front bold); prints the
tables, the slopes and the renderer's trade: per sequence the render time to reach the RMSE
that the median sequence reaches at each count but the smallest (power laws of RMSE and
time against spp fitted over the counts; '*' where extrapolated).";

/// Which scene.
#[derive(Clone, Copy, Debug, PartialEq)]
enum SceneKind {
    Cornell,
    Spheres,
    /// The Cornell box in direct lighting: the first diffuse hit's next-event estimate (and the
    /// lights seen directly or in a mirror), no further bounce.
    CornellDirect,
}

impl SceneKind {
    /// The scene's name on the command line and in section names.
    fn name(self) -> &'static str {
        match self {
            SceneKind::Cornell => "cornell",
            SceneKind::Spheres => "spheres",
            SceneKind::CornellDirect => "cornell-direct",
        }
    }
}

struct Args {
    samplers: Vec<String>,
    spp: Vec<u32>,
    size: (u32, u32),
    scene: SceneKind,
    padding: Padding,
    reference_spp: Option<u32>,
    seed: u64,
    seeds: u32,
    out: PathBuf,
    markdown: Option<PathBuf>,
    /// Split the error at the smallest count into one-draw and interaction parts.
    interactions: bool,
}

fn parse() -> Result<Option<Args>, CliError> {
    use lexopt::prelude::*;
    let mut a = Args {
        samplers: Sequence::NAMES.iter().map(|s| s.to_string()).collect(),
        spp: vec![4, 16, 64, 256],
        size: (128, 128),
        scene: SceneKind::Cornell,
        padding: Padding::Nested,
        reference_spp: None,
        seed: 1,
        seeds: 4,
        out: PathBuf::from("out/render"),
        markdown: None,
        interactions: false,
    };
    let mut p = lexopt::Parser::from_env();
    while let Some(arg) = p.next()? {
        match arg {
            Long("samplers") => {
                let v = string_value("--samplers", p.value()?)?;
                if v != "all" {
                    a.samplers = v
                        .split(',')
                        .map(|s| s.trim().to_string())
                        .filter(|s| !s.is_empty())
                        .collect();
                    if a.samplers.is_empty() {
                        return Err(cli_error("--samplers needs at least one name (or all)"));
                    }
                }
            }
            Long("spp") => {
                let v = string_value("--spp", p.value()?)?;
                a.spp = v
                    .split(',')
                    .map(|s| parse_int("--spp", s, 1, 65536).map(|n| n as u32))
                    .collect::<Result<_, _>>()?;
                a.spp.sort_unstable();
                a.spp.dedup();
                if a.spp.len() > MAX_COUNTS {
                    return Err(cli_error(format!(
                        "--spp lists {} counts; allowed: at most {MAX_COUNTS}",
                        a.spp.len()
                    )));
                }
            }
            Long("reference-spp") => {
                let v = string_value("--reference-spp", p.value()?)?;
                a.reference_spp = Some(parse_int("--reference-spp", &v, 1, 65536)? as u32);
            }
            Long("scene") => {
                a.scene = match string_value("--scene", p.value()?)?.as_str() {
                    "cornell" => SceneKind::Cornell,
                    "spheres" => SceneKind::Spheres,
                    "cornell-direct" => SceneKind::CornellDirect,
                    other => {
                        return Err(cli_error(format!(
                            "--scene {other:?} is not a scene; allowed: cornell, spheres, cornell-direct"
                        )));
                    }
                }
            }
            Long("padding") => {
                a.padding = match string_value("--padding", p.value()?)?.as_str() {
                    "nested" => Padding::Nested,
                    "uniform" => Padding::Uniform,
                    other => {
                        return Err(cli_error(format!(
                            "--padding {other:?} is not a padding; allowed: nested, uniform"
                        )));
                    }
                }
            }
            Long("size") => {
                let v = string_value("--size", p.value()?)?;
                let bad = || {
                    cli_error(format!(
                        "--size {v:?} is not WxH; allowed: two whole numbers 8 to {MAX_SIDE}, e.g. 128x128"
                    ))
                };
                let (w, h) = v.split_once(['x', 'X']).ok_or_else(bad)?;
                a.size = (
                    parse_int("--size", w, 8, MAX_SIDE)? as u32,
                    parse_int("--size", h, 8, MAX_SIDE)? as u32,
                );
            }
            Long("seeds") => {
                let v = string_value("--seeds", p.value()?)?;
                a.seeds = parse_int("--seeds", &v, 1, 64)? as u32;
            }
            Long("seed") => {
                let v = string_value("--seed", p.value()?)?;
                a.seed = parse_int("--seed", &v, 0, u64::MAX)?;
            }
            Long("out") => a.out = p.value()?.into(),
            Long("markdown") => a.markdown = Some(p.value()?.into()),
            Long("interactions") => a.interactions = true,
            Short('h') | Long("help") => {
                outln!("{HELP}")?;
                return Ok(None);
            }
            other => return Err(common::unexpected(other, USAGE)),
        }
    }
    let largest = *a.spp.last().expect("at least one count");
    if let Some(r) = a.reference_spp
        && r < largest
    {
        return Err(cli_error(format!(
            "--reference-spp {r} is below the largest --spp {largest}: the error would be \
                 measured against a noisier image; allowed: {largest} to 65536"
        )));
    }
    if a.interactions && a.scene == SceneKind::Cornell {
        return Err(cli_error(
            "--interactions splits the error of a direct-lighting render; allowed with --scene \
             spheres or cornell-direct (every bounce has too many draws to integrate each out)",
        ));
    }
    common::check_output_dir(&a.out)?;
    if let Some(m) = &a.markdown {
        common::check_markdown(m, &markdown_section(&a))?;
    }
    Ok(Some(a))
}

/// The name of the `--markdown` section a run writes: `render-SCENE-COUNTS`.
fn markdown_section(args: &Args) -> String {
    let scene = args.scene.name();
    let counts: Vec<String> = args.spp.iter().map(|n| n.to_string()).collect();
    format!("render-{scene}-{}", counts.join(","))
}

/// The largest image side: every sequence at eight counts keeps its images and error images
/// until the pictures are drawn, about 37 bytes per pixel per (sequence, count): at 1024 x 1024
/// about 1.2 GB with the default four counts, 2.4 GB at eight.
const MAX_SIDE: u64 = 1024;

/// The most sample counts in `--spp`.
const MAX_COUNTS: usize = 8;

// ---------------------------------------------------------------------------------------------
// Geometry shared by the scenes

/// A sphere, possibly moving over the shutter interval (motion blur).
struct Sphere {
    centre: Vec3,
    radius: f32,
    motion: Vec3,
    material: Material,
}

/// An axis-aligned rectangle: `axis` is the normal axis (0, 1, 2) at `offset`, spanning
/// `[lo, hi]` on the other two axes; `facing` is the sign of the side it faces.
struct Rect {
    axis: usize,
    offset: f32,
    lo: [f32; 2],
    hi: [f32; 2],
    facing: f32,
    material: Material,
}

#[derive(Clone, Copy, Debug)]
enum Material {
    /// Lambertian with an albedo; `mirror` is the probability weight of a perfect mirror lobe.
    Surface { albedo: Vec3, mirror: f32 },
    /// An area light, emitting `radiance` on its facing side (black behind).
    Light { radiance: Vec3 },
}

struct Hit {
    t: f32,
    point: Vec3,
    normal: Vec3,
    material: Material,
}

fn other_axes(axis: usize) -> (usize, usize) {
    match axis {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

impl Rect {
    fn normal(&self) -> Vec3 {
        let mut n = Vec3::ZERO;
        n[self.axis] = self.facing;
        n
    }

    fn area(&self) -> f32 {
        (self.hi[0] - self.lo[0]) * (self.hi[1] - self.lo[1])
    }

    /// The point at `u` on the rectangle.
    fn point(&self, u: Vec2) -> Vec3 {
        let (a, b) = other_axes(self.axis);
        let mut p = Vec3::ZERO;
        p[self.axis] = self.offset;
        p[a] = self.lo[0] + u.x * (self.hi[0] - self.lo[0]);
        p[b] = self.lo[1] + u.y * (self.hi[1] - self.lo[1]);
        p
    }

    fn intersect(&self, origin: Vec3, dir: Vec3, best: f32) -> Option<f32> {
        let d = dir[self.axis];
        if d.abs() < 1e-9 {
            return None;
        }
        let t = (self.offset - origin[self.axis]) / d;
        if !(t > 1e-4 && t < best) {
            return None;
        }
        let p = origin + dir * t;
        let (a, b) = other_axes(self.axis);
        (p[a] >= self.lo[0] && p[a] <= self.hi[0] && p[b] >= self.lo[1] && p[b] <= self.hi[1])
            .then_some(t)
    }
}

struct Scene {
    spheres: Vec<Sphere>,
    rects: Vec<Rect>,
    /// Indices into `rects` of the lights, with the probability of choosing each (by power).
    lights: Vec<(usize, f32)>,
    camera: Camera,
    kind: SceneKind,
    /// Direct lighting only: the path ends after the first diffuse hit's next-event estimate.
    direct: bool,
}

struct Camera {
    eye: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    tan_half: f32,
    focus: f32,
    aperture: f32,
}

impl Camera {
    fn new(eye: Vec3, target: Vec3, fov_deg: f32, focus: f32, aperture: f32) -> Self {
        let forward = (target - eye).normalize();
        let right = forward.cross(Vec3::Y).normalize();
        let up = right.cross(forward);
        Camera {
            eye,
            forward,
            right,
            up,
            tan_half: (0.5 * fov_deg.to_radians()).tan(),
            focus,
            aperture,
        }
    }

    /// The camera ray through `film` (position in pixel `(px, py)`) and `lens` (a 2D draw).
    fn ray(&self, px: u32, py: u32, size: (u32, u32), film: Vec2, lens: Vec2) -> (Vec3, Vec3) {
        let (w, h) = (size.0 as f32, size.1 as f32);
        let ndc = Vec2::new(
            (px as f32 + film.x) / w * 2.0 - 1.0,
            1.0 - (py as f32 + film.y) / h * 2.0,
        );
        let dir = (self.forward
            + self.right * ndc.x * self.tan_half * w / h
            + self.up * ndc.y * self.tan_half)
            .normalize();
        let disk = warp::concentric_disk(lens) * self.aperture;
        let offset = self.right * disk.x + self.up * disk.y;
        let focal_point = self.eye + dir * (self.focus / dir.dot(self.forward));
        let origin = self.eye + offset;
        (origin, (focal_point - origin).normalize())
    }
}

impl Scene {
    fn intersect(&self, origin: Vec3, dir: Vec3, time: f32) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let far = |b: &Option<Hit>| b.as_ref().map_or(f32::INFINITY, |h| h.t);
        for s in &self.spheres {
            let c = s.centre + s.motion * time;
            let oc = origin - c;
            let b = oc.dot(dir);
            let disc = b * b - (oc.length_squared() - s.radius * s.radius);
            if disc < 0.0 {
                continue;
            }
            let t = -b - disc.sqrt();
            if t > 1e-4 && t < far(&best) {
                let point = origin + dir * t;
                best = Some(Hit {
                    t,
                    point,
                    normal: (point - c) / s.radius,
                    material: s.material,
                });
            }
        }
        for r in &self.rects {
            if let Some(t) = r.intersect(origin, dir, far(&best)) {
                best = Some(Hit {
                    t,
                    point: origin + dir * t,
                    normal: r.normal(),
                    material: r.material,
                });
            }
        }
        best
    }

    /// Whether the segment from `p` to `q` is unobstructed.
    fn visible(&self, p: Vec3, q: Vec3, time: f32) -> bool {
        let d = q - p;
        let len = d.length();
        self.intersect(p, d / len, time)
            .is_none_or(|h| h.t >= len * (1.0 - 1e-4))
    }
}

fn surface(albedo: Vec3) -> Material {
    Material::Surface {
        albedo,
        mirror: 0.0,
    }
}

fn rect(axis: usize, offset: f32, lo: [f32; 2], hi: [f32; 2], facing: f32, m: Material) -> Rect {
    Rect {
        axis,
        offset,
        lo,
        hi,
        facing,
        material: m,
    }
}

/// The Cornell box `[0,1]^3`, open at `z = 0` where the camera looks in.
fn cornell() -> Scene {
    let white = surface(Vec3::splat(0.73));
    let red = surface(Vec3::new(0.65, 0.05, 0.05));
    let green = surface(Vec3::new(0.12, 0.45, 0.15));
    let ceiling_light = Material::Light {
        radiance: Vec3::new(17.0, 12.0, 4.0),
    };
    let wall_light = Material::Light {
        radiance: Vec3::new(2.0, 3.0, 6.0),
    };
    let rects = vec![
        rect(1, 0.0, [0.0, 0.0], [1.0, 1.0], 1.0, white), // floor
        rect(1, 1.0, [0.0, 0.0], [1.0, 1.0], -1.0, white), // ceiling
        rect(2, 1.0, [0.0, 0.0], [1.0, 1.0], -1.0, white), // back
        rect(0, 1.0, [0.0, 0.0], [1.0, 1.0], -1.0, red),  // left as the camera sees it
        rect(0, 0.0, [0.0, 0.0], [1.0, 1.0], 1.0, green), // right
        rect(1, 0.999, [0.37, 0.42], [0.63, 0.68], -1.0, ceiling_light),
        rect(2, 0.999, [0.08, 0.55], [0.3, 0.8], -1.0, wall_light),
    ];
    let power = |r: &Rect| match r.material {
        Material::Light { radiance } => r.area() * (radiance.x + radiance.y + radiance.z),
        Material::Surface { .. } => 0.0,
    };
    let total: f32 = rects.iter().map(power).sum();
    let lights = rects
        .iter()
        .enumerate()
        .filter(|(_, r)| power(r) > 0.0)
        .map(|(i, r)| (i, power(r) / total))
        .collect();
    Scene {
        spheres: vec![
            Sphere {
                centre: Vec3::new(0.3, 0.2, 0.62),
                radius: 0.2,
                motion: Vec3::ZERO,
                material: surface(Vec3::splat(0.8)),
            },
            Sphere {
                centre: Vec3::new(0.72, 0.17, 0.38),
                radius: 0.17,
                motion: Vec3::ZERO,
                material: Material::Surface {
                    albedo: Vec3::new(0.9, 0.85, 0.7),
                    mirror: 0.5,
                },
            },
        ],
        rects,
        lights,
        camera: Camera::new(
            Vec3::new(0.5, 0.5, -1.35),
            Vec3::new(0.5, 0.5, 0.5),
            40.0,
            1.85,
            0.02,
        ),
        kind: SceneKind::Cornell,
        direct: false,
    }
}

/// Spheres on a checkerboard under one square light; direct lighting only.
fn spheres() -> Scene {
    let light = rect(
        1,
        4.0,
        [-1.8, 0.7],
        [-0.2, 2.3],
        -1.0,
        Material::Light {
            radiance: Vec3::splat(12.0),
        },
    );
    Scene {
        spheres: vec![
            Sphere {
                centre: Vec3::new(-1.2, 0.8, 1.0),
                radius: 0.8,
                motion: Vec3::ZERO,
                material: surface(Vec3::new(0.8, 0.3, 0.25)),
            },
            Sphere {
                centre: Vec3::new(0.6, 0.6, 2.4),
                radius: 0.6,
                motion: Vec3::new(0.5, 0.0, 0.0),
                material: surface(Vec3::new(0.25, 0.5, 0.8)),
            },
            Sphere {
                centre: Vec3::new(1.8, 0.5, -0.5),
                radius: 0.5,
                motion: Vec3::ZERO,
                material: surface(Vec3::new(0.85, 0.8, 0.3)),
            },
        ],
        rects: vec![
            // the ground (its checkerboard is applied at the hit), then the light
            rect(
                1,
                0.0,
                [-50.0, -50.0],
                [50.0, 50.0],
                1.0,
                surface(Vec3::ONE),
            ),
            light,
        ],
        lights: vec![(1, 1.0)],
        camera: Camera::new(
            Vec3::new(0.0, 1.6, 7.0),
            Vec3::new(0.0, 0.6, 0.8),
            42.0,
            5.2,
            0.12,
        ),
        kind: SceneKind::Spheres,
        direct: true,
    }
}

/// The ground's checkerboard in the `spheres` scene.
fn checker(p: Vec3) -> f32 {
    let even = ((p.x * 1.5).floor() as i64 + (p.z * 1.5).floor() as i64).rem_euclid(2) == 0;
    if even { 0.75 } else { 0.2 }
}

const SKY: Vec3 = Vec3::new(0.05, 0.07, 0.1);
const MAX_BOUNCES: u32 = 8;

// The dimensions of a bounce, at fixed offsets from `start_bounce`, so that every draw keeps
// its dimension whatever the path did before (a mirror bounce skips the light draws).
const LOBE: u32 = 0;
const LIGHT_CHOICE: u32 = 1;
const LIGHT_POINT: u32 = 2; // 2-3
const DIRECTION: u32 = 4; // 4-5
const ROULETTE: u32 = 6;

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

/// Direct light at a diffuse point from one light chosen by `choice`, a point on it by `on`.
fn next_event(scene: &Scene, p: Vec3, n: Vec3, time: f32, choice: f32, on: Vec2) -> Vec3 {
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
    radiance * (cos_s * cos_l / d2 * light.area() / prob / std::f32::consts::PI)
}

/// Radiance along one camera sample.
/// What the path tracer asks of its sampler: the adapter's draw calls ([`PixelSampler`], or
/// [`Mixed`] for the interaction split).
trait Draws {
    fn get_pixel_2d(&mut self) -> Vec2;
    fn get_2d(&mut self) -> Vec2;
    fn get_1d(&mut self) -> f32;
    fn start_bounce(&mut self, k: u32);
    fn dimension(&self) -> u32;
    fn set_dimension(&mut self, dim: u32);
}

impl Draws for PixelSampler {
    fn get_pixel_2d(&mut self) -> Vec2 {
        PixelSampler::get_pixel_2d(self)
    }
    fn get_2d(&mut self) -> Vec2 {
        PixelSampler::get_2d(self)
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

/// A path's draws with one draw (the one starting at dimension `keep`) from the sampler under
/// test, at sample `index`, and every other draw from an independent Owen-scrambled Sobol'
/// sampler at sample `inner`: averaged over a block of `inner` samples, the path's radiance
/// with that draw fixed and the others integrated out (the draw's main effect).
struct Mixed<'a> {
    tested: &'a PixelSampler,
    others: &'a PixelSampler,
    pixel: [u32; 2],
    index: u64,
    inner: u64,
    keep: u32,
    dim: u32,
}

impl Draws for Mixed<'_> {
    fn get_pixel_2d(&mut self) -> Vec2 {
        self.get_2d()
    }
    fn get_2d(&mut self) -> Vec2 {
        let d = self.dim;
        self.dim += 2;
        if d == self.keep {
            self.tested.sample_2d(self.pixel, self.index, d)
        } else {
            self.others.sample_2d(self.pixel, self.inner, d)
        }
    }
    fn get_1d(&mut self) -> f32 {
        let d = self.dim;
        self.dim += 1;
        if d == self.keep {
            self.tested.sample_1d(self.pixel, self.index, d)
        } else {
            self.others.sample_1d(self.pixel, self.inner, d)
        }
    }
    fn start_bounce(&mut self, k: u32) {
        self.dim = DimensionLayout::default().bounce_start(k);
    }
    fn dimension(&self) -> u32 {
        self.dim
    }
    fn set_dimension(&mut self, dim: u32) {
        self.dim = dim;
    }
}

/// The inner samples per draw and pixel sample of the interaction split (a power of two: each
/// block a net of the inner Sobol' sampler).
const INNER: u64 = 64;

/// The one-draw part of a render's luminance error (row-major): per pixel, the mean over its
/// samples of the sum over the draws of the camera and the first bounce (`draws`: their first
/// dimensions) of each draw's main effect, `E[L | that draw] - I`, with the expectation over the
/// other draws estimated by [`INNER`] Sobol' points and `I` the reference. The rest of the
/// error (the render's minus this) is the draws' interactions (and, for pixels whose camera ray
/// meets the mirror, the later bounces' draws).
fn one_draw_errors(
    scene: &Scene,
    tested: &PixelSampler,
    spp: u32,
    size: (u32, u32),
    reference: &[Vec3],
    draws: &[u32],
) -> Vec<f64> {
    let others = PixelSampler::new(Sequence::sobol(), 1, strata::Seed(0x1a7e_5eed))
        .expect("sobol takes any count");
    (0..size.0 * size.1)
        .into_par_iter()
        .map(|p| {
            let pixel = [p % size.0, p / size.0];
            let truth = luminance(reference[p as usize]) as f64;
            let mut sum = 0.0;
            for i in 0..spp as u64 {
                for &keep in draws {
                    let mut mean = 0.0;
                    for m in 0..INNER {
                        let mut s = Mixed {
                            tested,
                            others: &others,
                            pixel,
                            index: i,
                            inner: i * INNER + m,
                            keep,
                            dim: 0,
                        };
                        mean += luminance(radiance(pixel[0], pixel[1], size, &mut s, scene)) as f64;
                    }
                    sum += mean / INNER as f64 - truth;
                }
            }
            sum / spp as f64
        })
        .collect()
}

fn radiance<S: Draws>(px: u32, py: u32, size: (u32, u32), s: &mut S, scene: &Scene) -> Vec3 {
    let film = s.get_pixel_2d();
    let lens = s.get_2d();
    let time = if scene.kind == SceneKind::Spheres {
        s.get_1d()
    } else {
        0.0
    };
    let (mut origin, mut dir) = scene.camera.ray(px, py, size, film, lens);
    let (mut throughput, mut sum, mut count_emission) = (Vec3::ONE, Vec3::ZERO, true);
    for bounce in 0..MAX_BOUNCES {
        let Some(hit) = scene.intersect(origin, dir, time) else {
            if scene.kind == SceneKind::Spheres {
                sum += throughput * SKY;
            }
            break;
        };
        let (albedo, mirror) = match hit.material {
            Material::Light { radiance } => {
                if count_emission && hit.normal.dot(dir) < 0.0 {
                    sum += throughput * radiance;
                }
                break;
            }
            Material::Surface { albedo, mirror } => (albedo, mirror),
        };
        let albedo = if scene.kind == SceneKind::Spheres && hit.normal == Vec3::Y {
            albedo * checker(hit.point)
        } else {
            albedo
        };
        // face the normal towards the incoming ray
        let n = if hit.normal.dot(dir) < 0.0 {
            hit.normal
        } else {
            -hit.normal
        };
        s.start_bounce(bounce);
        let base = s.dimension();
        let draw_1d = |s: &mut S, k: u32| {
            s.set_dimension(base + k);
            s.get_1d()
        };
        let draw_2d = |s: &mut S, k: u32| {
            s.set_dimension(base + k);
            s.get_2d()
        };
        if mirror > 0.0 && draw_1d(s, LOBE) < mirror {
            // the mirror lobe, chosen with its own weight: the weights cancel
            throughput *= albedo;
            dir -= 2.0 * dir.dot(n) * n;
            origin = hit.point + n * 1e-4;
            // `count_emission` stays as it was: lights seen in the mirror count on the camera's
            // specular chain only; caustics (diffuse, mirror, light) are left out, in the
            // reference too, as their variance would drown every sampler's difference
        } else {
            let choice = draw_1d(s, LIGHT_CHOICE);
            let on = draw_2d(s, LIGHT_POINT);
            sum += throughput * albedo * next_event(scene, hit.point, n, time, choice, on);
            if scene.direct {
                break; // direct lighting only
            }
            let local = warp::cosine_hemisphere(draw_2d(s, DIRECTION));
            let (t, b) = basis(n);
            dir = (t * local.x + b * local.y + n * local.z).normalize();
            origin = hit.point + n * 1e-4;
            throughput *= albedo; // cosine sampling: f cos / pdf = albedo
            count_emission = false; // next-event estimation counted the lights
        }
        if bounce >= 2 {
            let q = throughput.max_element().clamp(0.05, 0.95);
            if draw_1d(s, ROULETTE) >= q {
                break;
            }
            throughput /= q;
        }
    }
    sum
}

/// Renders the image (linear radiance, row-major) with `spp` samples of `sequence`.
fn render(
    scene: &Scene,
    sequence: Sequence,
    spp: u32,
    size: (u32, u32),
    seed: u64,
    progress: Option<&str>,
    padding: Padding,
) -> Result<Vec<Vec3>, strata::Error> {
    let sampler = PixelSampler::new(sequence, spp, strata::Seed(seed))?.with_padding(padding);
    let rows_done = std::sync::atomic::AtomicU32::new(0);
    let rows: Vec<Vec<Vec3>> = (0..size.1)
        .into_par_iter()
        .map(|y| {
            let mut s = sampler.clone();
            let row = (0..size.0)
                .map(|x| {
                    let mut sum = Vec3::ZERO;
                    for i in 0..spp {
                        s.start_pixel_sample([x, y], i as u64, 0);
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
    Ok(rows.concat())
}

/// Which pixels do not see an emitter (`true`: kept in the masked figures). A pixel sees one
/// when any of 144 camera rays through it (4 x 4 film positions, 3 x 3 lens positions, three
/// times of the shutter) meets a light's emitting side, directly or along a chain of mirror
/// lobes: its error is then the emitter's edge and the light-or-mirror choice, not the
/// sampler's distribution of the lighting integral.
fn emitter_mask(scene: &Scene, size: (u32, u32)) -> Vec<bool> {
    let sees_emitter = |px: u32, py: u32| {
        (0..144u32).any(|k| {
            let film = Vec2::new((k % 4) as f32 + 0.5, (k / 4 % 4) as f32 + 0.5) / 4.0;
            let lens = Vec2::new((k / 16 % 3) as f32 + 0.5, (k / 48) as f32 + 0.5) / 3.0;
            let time = if scene.kind == SceneKind::Spheres {
                ((k % 3) as f32 + 0.5) / 3.0
            } else {
                0.0
            };
            let (mut origin, mut dir) = scene.camera.ray(px, py, size, film, lens);
            for _ in 0..MAX_BOUNCES {
                let Some(hit) = scene.intersect(origin, dir, time) else {
                    return false;
                };
                match hit.material {
                    Material::Light { .. } => return hit.normal.dot(dir) < 0.0,
                    Material::Surface { mirror, .. } if mirror > 0.0 => {
                        let n = if hit.normal.dot(dir) < 0.0 {
                            hit.normal
                        } else {
                            -hit.normal
                        };
                        dir -= 2.0 * dir.dot(n) * n;
                        origin = hit.point + n * 1e-4;
                    }
                    Material::Surface { .. } => return false,
                }
            }
            false
        })
    };
    (0..size.0 * size.1)
        .into_par_iter()
        .map(|i| !sees_emitter(i % size.0, i / size.0))
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Pictures and numbers

fn tone(v: f32) -> u8 {
    let v = v.max(0.0);
    let mapped = (v / (1.0 + v)).powf(1.0 / 2.2); // Reinhard, then display gamma
    (mapped * 255.0).round().clamp(0.0, 255.0) as u8
}

fn to_canvas(img: &[Vec3], size: (u32, u32)) -> Canvas {
    let mut c = Canvas::new(size.0, size.1, Rgb::BLACK);
    for (i, v) in img.iter().enumerate() {
        c.set(
            (i as u32 % size.0) as i64,
            (i as u32 / size.0) as i64,
            Rgb::new(tone(v.x), tone(v.y), tone(v.z)),
        );
    }
    c
}

fn luminance(v: Vec3) -> f32 {
    0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z
}

/// Relative error of a pixel: |I - R| / (R + 0.02) on luminance.
fn relative_error(a: Vec3, r: Vec3) -> f32 {
    (luminance(a) - luminance(r)).abs() / (luminance(r) + 0.02)
}

/// A perceptual colour map (black - purple - orange - yellow), `t` in [0, 1].
fn colormap(t: f32) -> Rgb {
    const STOPS: [(f32, [u8; 3]); 5] = [
        (0.0, [0, 0, 4]),
        (0.25, [87, 16, 110]),
        (0.5, [188, 55, 84]),
        (0.75, [249, 142, 9]),
        (1.0, [252, 255, 164]),
    ];
    let t = t.clamp(0.0, 1.0);
    for w in STOPS.windows(2) {
        let ((t0, c0), (t1, c1)) = (w[0], w[1]);
        if t <= t1 {
            let u = (t - t0) / (t1 - t0);
            let mix = |a: u8, b: u8| (a as f32 + (b as f32 - a as f32) * u).round() as u8;
            return Rgb::new(mix(c0[0], c1[0]), mix(c0[1], c1[1]), mix(c0[2], c1[2]));
        }
    }
    Rgb::new(252, 255, 164)
}

const ERROR_SCALE: f32 = 0.5;

fn error_canvas(img: &[Vec3], reference: &[Vec3], size: (u32, u32)) -> Canvas {
    let bar = 56;
    let mut c = Canvas::new(size.0 + bar, size.1, Rgb::WHITE);
    for (i, (a, r)) in img.iter().zip(reference).enumerate() {
        let e = relative_error(*a, *r) / ERROR_SCALE;
        c.set(
            (i as u32 % size.0) as i64,
            (i as u32 / size.0) as i64,
            colormap(e),
        );
    }
    // the scale: a vertical bar from 0 (bottom) to ERROR_SCALE (top), with labels
    let (x0, top, bottom) = (size.0 as i64 + 6, 14i64, size.1 as i64 - 14);
    for y in top..=bottom {
        let t = (bottom - y) as f32 / (bottom - top) as f32;
        for x in x0..x0 + 12 {
            c.set(x, y, colormap(t));
        }
    }
    io::label(
        &mut c,
        &format!("{ERROR_SCALE}"),
        (x0 + 14) as i32,
        (top - 6) as i32,
        11,
    );
    io::label(&mut c, "0", (x0 + 14) as i32, (bottom - 6) as i32, 11);
    io::label(
        &mut c,
        "rel.",
        (x0 + 14) as i32,
        (size.1 as i64 / 2 - 6) as i32,
        11,
    );
    c
}

struct Row {
    name: String,
    spp: u32,
    image: Vec<Vec3>,
    rmse: f64,
    rel_rmse: f64,
    ms: f64,
    blur1: f64,
    blur2: f64,
    lowband: f64,
    /// The same figures without the pixels that see an emitter ([`emitter_mask`]).
    masked: Masked,
    /// The error image's measures for the first seed (for the pictures), and its pixels.
    errors: ErrorImage,
    error_pixels: Vec<f64>,
    /// The same without the pixels that see an emitter (their errors at zero), when any pixel
    /// is kept.
    masked_errors: Option<(ErrorImage, Vec<f64>)>,
    /// With `--interactions`, at the smallest count: the one-draw and the interaction parts of
    /// the error, without the pixels that see an emitter, over the seeds.
    split: Option<[Masked; 2]>,
}

/// A row's figures over the pixels that do not see an emitter: the RMSE of linear radiance,
/// the blurred RMSEs and the low-band share of the luminance error image
/// ([`spectrum::error_image_masked`]), over the seeds as the unmasked ones.
#[derive(Default)]
struct Masked {
    rmse: f64,
    blur1: f64,
    blur2: f64,
    lowband: f64,
}

/// The signed luminance error of every pixel.
fn luminance_errors(image: &[Vec3], reference: &[Vec3]) -> Vec<f64> {
    image
        .iter()
        .zip(reference)
        .map(|(a, r)| luminance(*a) as f64 - luminance(*r) as f64)
        .collect()
}

/// A diverging colour map for signed values in [-1, 1]: blue, white, red.
fn diverging(t: f32) -> Rgb {
    let t = t.clamp(-1.0, 1.0);
    let mix = |a: f32, b: f32, u: f32| (a + (b - a) * u).round() as u8;
    if t < 0.0 {
        let u = -t;
        Rgb::new(
            mix(255.0, 33.0, u),
            mix(255.0, 102.0, u),
            mix(255.0, 172.0, u),
        )
    } else {
        Rgb::new(
            mix(255.0, 178.0, t),
            mix(255.0, 24.0, t),
            mix(255.0, 43.0, t),
        )
    }
}

/// The signed error image (scaled to `scale`) beside its periodogram (log scale, DC centred).
fn error_image_canvas(e: &ErrorImage, errors: &[f64], scale: f64) -> Canvas {
    let (w, h) = (e.width, e.height);
    let mut c = Canvas::new(2 * w + 8, h, Rgb::WHITE);
    for (i, v) in errors.iter().enumerate() {
        c.set(
            (i as u32 % w) as i64,
            (i as u32 / w) as i64,
            diverging((v / scale) as f32),
        );
    }
    // the periodogram over 3 decades below its largest value
    let top = e.spectrum.iter().cloned().fold(f64::MIN_POSITIVE, f64::max);
    for (i, p) in e.spectrum.iter().enumerate() {
        let t = ((p / top).max(1e-3).log10() + 3.0) / 3.0;
        let g = (t.clamp(0.0, 1.0) * 255.0) as u8;
        c.set(
            (w + 8 + i as u32 % w) as i64,
            (i as u32 / w) as i64,
            Rgb::new(g, g, g),
        );
    }
    c
}

/// A label's width in pixels at `size` (the bundled font averages about 0.55 em per glyph).
fn label_width(text: &str, size: u32) -> u32 {
    (text.chars().count() as f32 * size as f32 * 0.56).ceil() as u32
}

fn main() -> ExitCode {
    common::run("render", || {
        let Some(args) = parse()? else { return Ok(()) };
        let sequences: Vec<(String, Sequence)> = args
            .samplers
            .iter()
            .map(|n| {
                Ok((
                    n.clone(),
                    Sequence::by_name_at(n, [args.size.0, args.size.1])?,
                ))
            })
            .collect::<Result<_, strata::Error>>()?;
        for (_, seq) in &sequences {
            for &spp in &args.spp {
                seq.check_spp(spp)?;
            }
        }
        let scene = match args.scene {
            SceneKind::Cornell => cornell(),
            SceneKind::Spheres => spheres(),
            SceneKind::CornellDirect => Scene {
                direct: true,
                ..cornell()
            },
        };
        let size = args.size;
        let largest = *args.spp.last().expect("at least one count");
        let ref_spp = args
            .reference_spp
            .unwrap_or((largest * 16).clamp(1024, 65536));
        eprintln!(
            "reference: sobol at {ref_spp} spp, {}x{} ...",
            size.0, size.1
        );
        let start = Instant::now();
        let reference = render(
            &scene,
            Sequence::sobol(),
            ref_spp,
            size,
            0x5eed_0000_0001,
            Some("reference"),
            Padding::Nested,
        )?;
        eprintln!("reference: {:.1} s", start.elapsed().as_secs_f64());
        io::write_png(args.out.join("reference.png"), &to_canvas(&reference, size))?;
        let keep = emitter_mask(&scene, size);
        let kept = keep.iter().filter(|&&k| k).count();
        let mut mask_canvas = to_canvas(&reference, size);
        for (i, _) in keep.iter().enumerate().filter(|(_, k)| !**k) {
            let (x, y) = ((i as u32 % size.0) as i64, (i as u32 / size.0) as i64);
            mask_canvas.set(x, y, Rgb::new(255, 0, 255));
        }
        io::write_png(args.out.join("emitter-mask.png"), &mask_canvas)?;
        // the draws the interaction split integrates out one by one: the film, the lens (and
        // the shutter time of the spheres), the first bounce's lobe, light choice and light point
        let b0 = DimensionLayout::default().bounce_start(0);
        let mut draws = vec![0, 2];
        if args.scene == SceneKind::Spheres {
            draws.push(4);
        }
        draws.extend([b0 + LOBE, b0 + LIGHT_CHOICE, b0 + LIGHT_POINT]);
        eprintln!(
            "{} of {} pixels see an emitter (left out of the masked figures)",
            keep.len() - kept,
            keep.len()
        );

        let mut rows = Vec::new();
        for (name, seq) in &sequences {
            for &spp in &args.spp {
                let (mut mse, mut rel, mut ms, mut first) = (0.0f64, 0.0f64, 0.0f64, None);
                let (mut blur1, mut blur2, mut lowband, mut errors) = (0.0, 0.0, 0.0, None);
                let (mut masked, mut masked_errors) = (Masked::default(), None);
                let mut split = (args.interactions && spp == args.spp[0] && kept > 0)
                    .then(<[Masked; 2]>::default);
                for k in 0..args.seeds as u64 {
                    let start = Instant::now();
                    let image = render(
                        &scene,
                        seq.clone(),
                        spp,
                        size,
                        args.seed.wrapping_add(k),
                        None,
                        args.padding,
                    )?;
                    ms += start.elapsed().as_secs_f64() * 1e3 / args.seeds as f64;
                    let n = image.len() as f64 * args.seeds as f64;
                    mse += image
                        .iter()
                        .zip(&reference)
                        .map(|(a, r)| (*a - *r).length_squared() as f64 / 3.0)
                        .sum::<f64>()
                        / n;
                    rel += image
                        .iter()
                        .zip(&reference)
                        .map(|(a, r)| (relative_error(*a, *r) as f64).powi(2))
                        .sum::<f64>()
                        / n;
                    let lum = luminance_errors(&image, &reference);
                    let e = spectrum::error_image(&lum, size.0, size.1)?;
                    let seeds = args.seeds as f64;
                    blur1 += e.blur1_rmse.powi(2) / seeds;
                    blur2 += e.blur2_rmse.powi(2) / seeds;
                    lowband += e.lowband / seeds;
                    if kept > 0 {
                        let m = spectrum::error_image_masked(&lum, &keep, size.0, size.1)?;
                        masked.rmse += image
                            .iter()
                            .zip(&reference)
                            .zip(&keep)
                            .filter(|(_, k)| **k)
                            .map(|((a, r), _)| (*a - *r).length_squared() as f64 / 3.0)
                            .sum::<f64>()
                            / (kept as f64 * seeds);
                        masked.blur1 += m.blur1_rmse.powi(2) / seeds;
                        masked.blur2 += m.blur2_rmse.powi(2) / seeds;
                        masked.lowband += m.lowband / seeds;
                        if let Some(parts) = &mut split {
                            let tested = PixelSampler::new(
                                seq.clone(),
                                spp,
                                strata::Seed(args.seed.wrapping_add(k)),
                            )?
                            .with_padding(args.padding);
                            let one =
                                one_draw_errors(&scene, &tested, spp, size, &reference, &draws);
                            let rest: Vec<f64> = lum.iter().zip(&one).map(|(e, o)| e - o).collect();
                            for (part, errors) in parts.iter_mut().zip([&one, &rest]) {
                                let m =
                                    spectrum::error_image_masked(errors, &keep, size.0, size.1)?;
                                part.rmse += m.rmse.powi(2) / seeds;
                                part.blur2 += m.blur2_rmse.powi(2) / seeds;
                                part.lowband += m.lowband / seeds;
                            }
                        }
                        if masked_errors.is_none() {
                            let dropped = lum
                                .iter()
                                .zip(&keep)
                                .map(|(e, k)| if *k { *e } else { 0.0 })
                                .collect();
                            masked_errors = Some((m, dropped));
                        }
                    }
                    errors.get_or_insert(e);
                    first.get_or_insert(image);
                }
                let image = first.expect("at least one seed");
                eprintln!("{name} at {spp} spp: {ms:.0} ms");
                io::write_png(
                    args.out.join(format!("{name}-{spp}.png")),
                    &to_canvas(&image, size),
                )?;
                if spp == largest {
                    io::write_png(
                        args.out.join(format!("{name}.png")),
                        &to_canvas(&image, size),
                    )?;
                    io::write_png(
                        args.out.join(format!("{name}-error.png")),
                        &error_canvas(&image, &reference, size),
                    )?;
                }
                let errors = errors.expect("at least one seed");
                let e = luminance_errors(&image, &reference);
                let scale = 4.0 * errors.rmse.max(1e-9);
                io::write_png(
                    args.out.join(format!("{name}-{spp}-error-spectrum.png")),
                    &error_image_canvas(&errors, &e, scale),
                )?;
                rows.push(Row {
                    name: name.clone(),
                    spp,
                    image,
                    rmse: mse.sqrt(),
                    rel_rmse: rel.sqrt(),
                    ms,
                    blur1: blur1.sqrt(),
                    blur2: blur2.sqrt(),
                    lowband,
                    masked: Masked {
                        rmse: masked.rmse.sqrt(),
                        blur1: masked.blur1.sqrt(),
                        blur2: masked.blur2.sqrt(),
                        lowband: masked.lowband,
                    },
                    errors,
                    error_pixels: e,
                    masked_errors,
                    split: split.map(|parts| {
                        parts.map(|p| Masked {
                            rmse: p.rmse.sqrt(),
                            blur1: 0.0,
                            blur2: p.blur2.sqrt(),
                            lowband: p.lowband,
                        })
                    }),
                });
            }
        }

        write_compare(&args, &rows, &reference, ref_spp)?;

        let mut csv = String::from(
            "sampler,spp,rmse,rel_rmse,ms,blur1_rmse,blur2_rmse,lowband,masked_rmse,\
             masked_blur1_rmse,masked_blur2_rmse,masked_lowband\n",
        );
        let mut full = String::from(
            "| sampler | spp | rmse | rel_rmse | ms | blur1_rmse | blur2_rmse | lowband | masked: rmse | blur1_rmse | blur2_rmse | lowband |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
        );
        for r in &rows {
            let m = &r.masked;
            csv.push_str(&format!(
                "{},{},{},{},{},{},{},{},{},{},{},{}\n",
                r.name,
                r.spp,
                r.rmse,
                r.rel_rmse,
                r.ms,
                r.blur1,
                r.blur2,
                r.lowband,
                m.rmse,
                m.blur1,
                m.blur2,
                m.lowband
            ));
            full.push_str(&format!(
                "| {} | {} | {:.5} | {:.4} | {:.1} | {:.5} | {:.5} | {:.4} | {:.5} | {:.5} | {:.5} | {:.4} |\n",
                r.name, r.spp, r.rmse, r.rel_rmse, r.ms, r.blur1, r.blur2, r.lowband, m.rmse,
                m.blur1, m.blur2, m.lowband
            ));
        }
        common::out(&full)?;
        io::write_text(args.out.join("render.csv"), &csv)?;
        write_blue_noise(&args, &rows, false)?;
        write_blue_noise(&args, &rows, true)?;
        let split_table = interaction_table(&rows);
        if let Some(t) = &split_table {
            outln!("\n{t}")?;
        }

        // RMSE against spp, with the fitted slope per sampler
        let mut plot = LinePlot::new(
            format!(
                "RMSE against samples per pixel ({} scene)",
                args.scene.name()
            ),
            "samples per pixel",
            "RMSE against the reference",
        );
        plot.log_x = true;
        plot.log_y = true;
        // RMSE per sampler (rows) and count (columns), with the fitted slope
        let mut table = format!(
            "| sampler | {} | slope |\n|---|{}---|\n",
            args.spp
                .iter()
                .map(|n| format!("{n} spp"))
                .collect::<Vec<_>>()
                .join(" | "),
            "---|".repeat(args.spp.len())
        );
        for (k, (name, _)) in sequences.iter().enumerate() {
            let mine: Vec<&Row> = rows.iter().filter(|r| &r.name == name).collect();
            let pts: Vec<(f64, f64)> = mine.iter().map(|r| (r.spp as f64, r.rmse)).collect();
            let fitted = study::fit_slope(&pts);
            table.push_str(&format!(
                "| {name} | {} | {} |\n",
                mine.iter()
                    .map(|r| format!("{:.4}", r.rmse))
                    .collect::<Vec<_>>()
                    .join(" | "),
                fitted.map_or("-".to_string(), |s| format!("{s:.2}"))
            ));
            let label = match fitted {
                Some(s) => format!("{name} (slope {s:.2})"),
                None => name.clone(),
            };
            plot.series
                .push(Series::new(label, pts, io::PALETTE[k % io::PALETTE.len()]));
        }
        outln!("\n{table}")?;
        let trade = write_trade(&args, &sequences, &rows)?;
        outln!("{trade}")?;
        if let Some(path) = &args.markdown {
            common::write_markdown_section(
                path,
                &markdown_section(&args),
                &format!(
                    "RMSE of linear radiance against the reference ({} scene, {}x{}, reference: \
                     Sobol' at {ref_spp} spp), root of the mean over pixels, channels and {} \
                     seeds; slope of log RMSE against log spp.\n\n{table}\nThe error image \
                     (signed luminance error): its RMSE after a Gaussian blur of sigma 1 and 2 \
                     pixels, and the share of its power below 1/8 cycle per pixel (white \
                     error: about 0.05); 'masked': the same without the {} pixels that see \
                     an emitter, directly or in a mirror.\n\n{full}\n{trade}{}",
                    args.scene.name(),
                    size.0,
                    size.1,
                    args.seeds,
                    keep.len() - kept,
                    split_table.map_or(String::new(), |t| format!("\n{t}"))
                ),
            )?;
        }
        io::write_png(args.out.join("convergence.png"), &plot.render(720, 480))?;
        eprintln!("wrote {} renders into {}", rows.len(), args.out.display());
        Ok(())
    })
}

/// With `--interactions`: the one-draw and the interaction parts of the error at the smallest
/// count, emitters masked (Markdown), or `None`.
fn interaction_table(rows: &[Row]) -> Option<String> {
    let mut t = String::from(
        "The error split at the smallest count, without the pixels that see an emitter: the \
         one-draw part (per pixel, the sum over the camera's and the first bounce's draws of \
         each draw's main effect, the other draws integrated out by 64 Owen-scrambled Sobol' \
         points) and the interaction part (the rest); RMSE, RMSE after a blur of sigma 2, \
         low-band share.\n\n| sampler | spp | one-draw rmse | blur2_rmse | lowband | \
         interaction rmse | blur2_rmse | lowband |\n|---|---|---|---|---|---|---|---|\n",
    );
    let mut any = false;
    for r in rows {
        if let Some([one, rest]) = &r.split {
            any = true;
            t.push_str(&format!(
                "| {} | {} | {:.5} | {:.5} | {:.4} | {:.5} | {:.5} | {:.4} |\n",
                r.name,
                r.spp,
                one.rmse,
                one.blur2,
                one.lowband,
                rest.rmse,
                rest.blur2,
                rest.lowband
            ));
        }
    }
    any.then_some(t)
}

/// The renderer's trade: per sequence, the render time and the time to reach each target RMSE
/// (power laws of RMSE and time against spp, fitted over the measured counts; `*`: outside
/// them). The targets are the median RMSE over the sequences at each count but the smallest
/// (the error a typical sequence reaches there). Writes `pareto.png` (RMSE against render
/// time, sequences on the Pareto front bold) and returns the Markdown table.
fn write_trade(
    args: &Args,
    sequences: &[(String, Sequence)],
    rows: &[Row],
) -> Result<String, CliError> {
    let mut targets: Vec<f64> = args
        .spp
        .iter()
        .skip(1)
        .map(|&spp| {
            let mut v: Vec<f64> = rows
                .iter()
                .filter(|r| r.spp == spp)
                .map(|r| r.rmse)
                .collect();
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        })
        .collect();
    if targets.is_empty() {
        targets = rows.iter().map(|r| r.rmse).take(1).collect();
    }
    let points: Vec<(f64, f64)> = rows.iter().map(|r| (r.ms, r.rmse)).collect();
    let front = study::pareto_front(&points);
    let on_front = |name: &str| front.iter().any(|&i| rows[i].name == name);
    struct Line {
        name: String,
        ms_per_spp: f64,
        cells: Vec<Option<(f64, f64, bool)>>,
    }
    let mut lines: Vec<Line> = sequences
        .iter()
        .map(|(name, _)| {
            let mine: Vec<&Row> = rows.iter().filter(|r| &r.name == name).collect();
            let err: Vec<(f64, f64)> = mine.iter().map(|r| (r.spp as f64, r.rmse)).collect();
            let time: Vec<(f64, f64)> = mine.iter().map(|r| (r.spp as f64, r.ms)).collect();
            let (lo, hi) = (
                args.spp[0] as f64,
                *args.spp.last().expect("a count") as f64,
            );
            let cells = targets
                .iter()
                .map(|&t| {
                    let spp = study::count_to_reach(&err, t)?.ceil();
                    let ms = study::power_law_at(&time, spp)?;
                    Some((spp, ms, spp < lo || spp > hi))
                })
                .collect();
            let last = mine.last().expect("a count");
            Line {
                name: name.clone(),
                ms_per_spp: last.ms / f64::from(last.spp),
                cells,
            }
        })
        .collect();
    let key = |l: &Line| {
        l.cells
            .last()
            .copied()
            .flatten()
            .map_or(f64::INFINITY, |c| c.1)
    };
    lines.sort_by(|a, b| key(a).total_cmp(&key(b)));
    let mut table = format!(
        "The renderer's trade: render time (all cores, one image) to reach each RMSE, cheapest \
         first at the smallest RMSE; the targets are the median RMSE over the sequences at \
         {} spp; `*`: extrapolated beyond the measured counts; bold: on the Pareto front of \
         (time, RMSE) over all renders.\n\n| sequence | ms per spp | {} |\n|---|---|{}\n",
        args.spp
            .iter()
            .skip(1)
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        targets
            .iter()
            .map(|t| format!("RMSE {t:.4}"))
            .collect::<Vec<_>>()
            .join(" | "),
        "---|".repeat(targets.len())
    );
    for l in &lines {
        let name = if on_front(&l.name) {
            format!("**{}**", l.name)
        } else {
            l.name.clone()
        };
        let cells: Vec<String> = l
            .cells
            .iter()
            .map(|c| match c {
                Some((spp, ms, x)) => {
                    format!("{ms:.0} ms ({spp} spp{})", if *x { "*" } else { "" })
                }
                None => "-".into(),
            })
            .collect();
        table.push_str(&format!(
            "| {name} | {:.2} | {} |\n",
            l.ms_per_spp,
            cells.join(" | ")
        ));
    }
    let mut plot = LinePlot::new(
        "render: RMSE against render time (bold: Pareto front)",
        "render time (ms, all cores)",
        "RMSE against the reference",
    );
    plot.log_x = true;
    plot.log_y = true;
    plot.legend_outside = true;
    let mut line = Series::reference(
        "Pareto front",
        front.iter().map(|&i| points[i]).collect(),
        Rgb::grey(60),
    );
    line.width = 1;
    plot.series.push(line);
    for (k, (name, _)) in sequences.iter().enumerate() {
        let pts: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| &r.name == name)
            .map(|r| (r.ms, r.rmse))
            .collect();
        let bold = on_front(name);
        let mut s = Series::new(
            if bold {
                format!("{name} *")
            } else {
                name.clone()
            },
            pts,
            io::PALETTE[k % io::PALETTE.len()],
        );
        s.marker = Marker::ALL[k % Marker::ALL.len()];
        s.width = if bold { 3 } else { 1 };
        s.faint = !bold;
        plot.series.push(s);
    }
    io::write_png(args.out.join("pareto.png"), &plot.render(820, 500))?;
    Ok(table)
}

/// blue-noise.png (or, `masked`, blue-noise-masked.png, without the pixels that see an emitter):
/// per sampler (side by side), at the smallest count, the signed error image (one colour scale
/// for all) above its periodogram: white error against blue.
fn write_blue_noise(args: &Args, rows: &[Row], masked: bool) -> Result<(), CliError> {
    let smallest = args.spp[0];
    // each row's error image and pixels: all of them, or without the emitters' pixels
    let mine: Vec<(&Row, &ErrorImage, &[f64])> = rows
        .iter()
        .filter(|r| r.spp == smallest)
        .filter_map(|r| match (masked, &r.masked_errors) {
            (false, _) => Some((r, &r.errors, r.error_pixels.as_slice())),
            (true, Some((e, p))) => Some((r, e, p.as_slice())),
            (true, None) => None,
        })
        .collect();
    let Some(first) = mine.first() else {
        return Ok(());
    };
    let (w, h) = (first.1.width, first.1.height);
    let label_h = 34u32;
    let cell_w = w.max(150) + 12;
    let scale = 4.0 * mine.iter().map(|r| r.1.rmse).fold(1e-9, f64::max);
    let mut c = Canvas::new(
        8 + cell_w * mine.len() as u32,
        label_h + 2 * h + 16,
        Rgb::WHITE,
    );
    for (k, (r, errors, pixels)) in mine.iter().enumerate() {
        let x = 8 + cell_w * k as u32;
        io::label(
            &mut c,
            &format!("{} at {} spp", r.name, r.spp),
            x as i32,
            2,
            12,
        );
        io::label(
            &mut c,
            &format!(
                "low band {:.3}, blur2 {:.4}",
                errors.lowband, errors.blur2_rmse
            ),
            x as i32,
            17,
            11,
        );
        let both = error_image_canvas(errors, pixels, scale);
        // the canvas holds the image and the spectrum side by side: stack them
        let mut image = Canvas::new(w, h, Rgb::WHITE);
        image.paste(&both, 0, 0);
        let mut spectrum = Canvas::new(w, h, Rgb::WHITE);
        spectrum.paste(&both, -((w + 8) as i64), 0);
        c.paste(&image, x as i64, label_h as i64);
        c.paste(&spectrum, x as i64, (label_h + h + 8) as i64);
    }
    let name = if masked {
        "blue-noise-masked.png"
    } else {
        "blue-noise.png"
    };
    io::write_png(args.out.join(name), &c)?;
    Ok(())
}

/// compare.png: the reference, then one row per sampler: its image at each count, and the
/// error map at the largest count. Titles are clipped to their cell, so that they stay
/// legible (and apart) at any image size.
fn write_compare(
    args: &Args,
    rows: &[Row],
    reference: &[Vec3],
    ref_spp: u32,
) -> Result<(), CliError> {
    let size = args.size;
    let gap = 8u32;
    let label_h = 18u32;
    let names: Vec<&str> = {
        let mut v: Vec<&str> = rows.iter().map(|r| r.name.as_str()).collect();
        v.dedup();
        v
    };
    let cols = args.spp.len() as u32 + 1;
    let cell_w = size.0.max(72) + 56 + gap;
    let cell_h = label_h + size.1 + gap;
    let width = gap + cell_w * cols;
    let height = gap + cell_h * (names.len() as u32 + 1);
    let mut c = Canvas::new(width, height, Rgb::WHITE);
    // a label, shortened until it fits `room` pixels
    let put = |c: &mut Canvas, text: String, x: u32, y: u32, room: u32| {
        let mut t = text;
        let size = if room < 120 { 10 } else { 12 };
        while t.chars().count() > 3 && label_width(&t, size) > room {
            t.pop();
        }
        io::label(c, &t, x as i32, y as i32, size);
    };
    put(
        &mut c,
        format!("reference ({ref_spp} spp)"),
        gap,
        gap / 2,
        cell_w * 2,
    );
    c.paste(
        &to_canvas(reference, size),
        gap as i64,
        (gap / 2 + label_h) as i64,
    );
    for (k, name) in names.iter().enumerate() {
        let y = gap / 2 + cell_h * (k as u32 + 1);
        for (j, r) in rows.iter().filter(|r| &r.name == name).enumerate() {
            let x = gap + cell_w * j as u32;
            put(
                &mut c,
                format!("{} {} spp: {:.4}", r.name, r.spp, r.rmse),
                x,
                y,
                cell_w - gap,
            );
            c.paste(&to_canvas(&r.image, size), x as i64, (y + label_h) as i64);
        }
        if let Some(last) = rows.iter().rfind(|r| &r.name == name) {
            let x = gap + cell_w * (cols - 1);
            put(
                &mut c,
                format!("{} error at {} spp", last.name, last.spp),
                x,
                y,
                cell_w - gap,
            );
            c.paste(
                &error_canvas(&last.image, reference, size),
                x as i64,
                (y + label_h) as i64,
            );
        }
    }
    io::write_png(args.out.join("compare.png"), &c)?;
    Ok(())
}
