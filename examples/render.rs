//! `render`: the samplers inside a small path tracer, against a converged reference.
//!
//! ```text
//! cargo run --release --example render -- [--samplers a,b,..|all] [--spp N] [--size WxH] [--out DIR]
//! ```
//!
//! The scene needs seven sample dimensions per camera sample: the position in the pixel (0-1),
//! the thin lens (2-3, depth of field), the shutter time (4, a moving sphere), and a point on a
//! square area light (5-6, soft shadows; direct lighting with one shadow ray). Each sampler
//! renders it at `--spp` samples per pixel through the path-tracer adapter
//! (`strata::pixel::PixelSampler`); the reference is scrambled Sobol' at 64 times as many.

mod common;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use common::{CliError, cli_error, parse_int, string_value};
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use strata::io::{self, Canvas, Rgb};
use strata::pixel::{PixelSampler, PixelSequence, Sequence};

const USAGE: &str = "render [--samplers a,b,..|all] [--spp N] [--size WxH] [--out DIR]";

const HELP: &str = "\
render: a small path tracer (depth of field, motion blur, an area light) rendered with each
sampler at N samples per pixel and compared with a converged reference.

Usage:
  cargo run --release --example render -- [options]

Options:
  --samplers a,b,..|all  samplers with a path-tracer adapter: random, jittered, pmj02, sobol,
                         halton (default all)
  --spp N                samples per pixel (default 16; 1 to 65536; jittered needs a square)
  --size WxH             image size (default 192x128; each side 8 to 4096)
  --reference-spp N      samples per pixel of the reference (default 64 x spp, at most 16384)
  --out DIR              output directory (default out/render)
  -h, --help             this text

Writes DIR/NAME.png, DIR/NAME-error.png (per-pixel relative error |I - R| / (R + 0.02),
colour-mapped from 0 to 0.5 with a scale), DIR/reference.png, DIR/compare.png (side by side)
and DIR/render.csv (sampler,spp,rmse,rel_rmse,ms); prints the table.";

struct Args {
    samplers: Vec<String>,
    spp: u32,
    size: (u32, u32),
    reference_spp: Option<u32>,
    out: PathBuf,
}

fn parse() -> Result<Option<Args>, CliError> {
    use lexopt::prelude::*;
    let mut a = Args {
        samplers: Sequence::NAMES.iter().map(|s| s.to_string()).collect(),
        spp: 16,
        size: (192, 128),
        reference_spp: None,
        out: PathBuf::from("out/render"),
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
                a.spp = parse_int("--spp", &string_value("--spp", p.value()?)?, 1, 65536)? as u32
            }
            Long("reference-spp") => {
                let v = string_value("--reference-spp", p.value()?)?;
                a.reference_spp = Some(parse_int("--reference-spp", &v, 1, 16384)? as u32);
            }
            Long("size") => {
                let v = string_value("--size", p.value()?)?;
                let bad = || {
                    cli_error(format!(
                        "--size {v:?} is not WxH; allowed: two whole numbers 8 to 4096, e.g. 192x128"
                    ))
                };
                let (w, h) = v.split_once(['x', 'X']).ok_or_else(bad)?;
                a.size = (
                    parse_int("--size", w, 8, 4096)? as u32,
                    parse_int("--size", h, 8, 4096)? as u32,
                );
            }
            Long("out") => a.out = p.value()?.into(),
            Short('h') | Long("help") => {
                println!("{HELP}");
                return Ok(None);
            }
            other => return Err(common::unexpected(other, USAGE)),
        }
    }
    Ok(Some(a))
}

// ---------------------------------------------------------------------------------------------
// The scene

struct Sphere {
    centre: Vec3,
    radius: f32,
    albedo: Vec3,
    /// Displacement over the shutter interval (motion blur).
    motion: Vec3,
}

struct Hit {
    t: f32,
    point: Vec3,
    normal: Vec3,
    albedo: Vec3,
    emissive: bool,
}

/// A square light in the plane y = LIGHT_Y, centred at (LIGHT_X, LIGHT_Z), facing down.
const LIGHT_Y: f32 = 4.0;
const LIGHT_X: f32 = -1.0;
const LIGHT_Z: f32 = 1.5;
const LIGHT_SIZE: f32 = 1.6;
const LIGHT_RADIANCE: f32 = 12.0;

fn spheres() -> [Sphere; 3] {
    [
        Sphere {
            centre: Vec3::new(-1.2, 0.8, 1.0),
            radius: 0.8,
            albedo: Vec3::new(0.8, 0.3, 0.25),
            motion: Vec3::ZERO,
        },
        Sphere {
            centre: Vec3::new(0.6, 0.6, 2.4),
            radius: 0.6,
            albedo: Vec3::new(0.25, 0.5, 0.8),
            motion: Vec3::new(0.5, 0.0, 0.0),
        },
        Sphere {
            centre: Vec3::new(1.8, 0.5, -0.5),
            radius: 0.5,
            albedo: Vec3::new(0.85, 0.8, 0.3),
            motion: Vec3::ZERO,
        },
    ]
}

fn intersect(origin: Vec3, dir: Vec3, time: f32, spheres: &[Sphere; 3]) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for s in spheres {
        let c = s.centre + s.motion * time;
        let oc = origin - c;
        let b = oc.dot(dir);
        let disc = b * b - (oc.length_squared() - s.radius * s.radius);
        if disc < 0.0 {
            continue;
        }
        let t = -b - disc.sqrt();
        if t > 1e-3 && best.as_ref().is_none_or(|h| t < h.t) {
            let point = origin + dir * t;
            best = Some(Hit {
                t,
                point,
                normal: (point - c) / s.radius,
                albedo: s.albedo,
                emissive: false,
            });
        }
    }
    // ground plane y = 0 with a checkerboard
    if dir.y < 0.0 {
        let t = -origin.y / dir.y;
        if t > 1e-3 && best.as_ref().is_none_or(|h| t < h.t) {
            let point = origin + dir * t;
            let check = ((point.x * 1.5).floor() as i64 + (point.z * 1.5).floor() as i64)
                .rem_euclid(2)
                == 0;
            let albedo = if check {
                Vec3::splat(0.75)
            } else {
                Vec3::splat(0.2)
            };
            best = Some(Hit {
                t,
                point,
                normal: Vec3::Y,
                albedo,
                emissive: false,
            });
        }
    }
    // the light itself (seen from below)
    if dir.y > 0.0 {
        let t = (LIGHT_Y - origin.y) / dir.y;
        let p = origin + dir * t;
        if t > 1e-3
            && (p.x - LIGHT_X).abs() < LIGHT_SIZE / 2.0
            && (p.z - LIGHT_Z).abs() < LIGHT_SIZE / 2.0
            && best.as_ref().is_none_or(|h| t < h.t)
        {
            best = Some(Hit {
                t,
                point: p,
                normal: -Vec3::Y,
                albedo: Vec3::ZERO,
                emissive: true,
            });
        }
    }
    best
}

/// Radiance along one camera sample, from the 7 sample dimensions.
fn radiance(
    px: u32,
    py: u32,
    size: (u32, u32),
    s: &mut PixelSampler<Sequence>,
    spheres: &[Sphere; 3],
) -> Vec3 {
    let film = s.get_pixel_2d();
    let lens = s.get_2d();
    let time = s.get_1d();
    let light = s.get_2d();
    // a thin-lens camera looking at the scene, focused on the blue sphere's distance
    let (w, h) = (size.0 as f32, size.1 as f32);
    let eye = Vec3::new(0.0, 1.6, 7.0);
    let target = Vec3::new(0.0, 0.6, 0.8);
    let forward = (target - eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let tan_half = (0.5f32 * 42f32.to_radians()).tan();
    let ndc = Vec2::new(
        (px as f32 + film.x) / w * 2.0 - 1.0,
        1.0 - (py as f32 + film.y) / h * 2.0,
    );
    let dir = (forward + right * ndc.x * tan_half * w / h + up * ndc.y * tan_half).normalize();
    let focus = 5.2;
    let aperture = 0.12;
    // uniform point on the lens disk (concentric-free polar map)
    let (r, phi) = (aperture * lens.x.sqrt(), std::f32::consts::TAU * lens.y);
    let offset = right * (r * phi.cos()) + up * (r * phi.sin());
    let focal_point = eye + dir * (focus / dir.dot(forward));
    let origin = eye + offset;
    let dir = (focal_point - origin).normalize();

    let Some(hit) = intersect(origin, dir, time, spheres) else {
        return Vec3::new(0.05, 0.07, 0.1); // sky
    };
    if hit.emissive {
        return Vec3::splat(LIGHT_RADIANCE);
    }
    // direct lighting: one point on the light
    let lp = Vec3::new(
        LIGHT_X + (light.x - 0.5) * LIGHT_SIZE,
        LIGHT_Y,
        LIGHT_Z + (light.y - 0.5) * LIGHT_SIZE,
    );
    let to_light = lp - hit.point;
    let d2 = to_light.length_squared();
    let l = to_light / d2.sqrt();
    let cos_s = hit.normal.dot(l);
    let cos_l = l.y; // the light faces down
    if cos_s <= 0.0 || cos_l <= 0.0 {
        return Vec3::ZERO;
    }
    let occluded = intersect(hit.point + hit.normal * 1e-3, l, time, spheres)
        .is_some_and(|h| !h.emissive && h.t * h.t < d2);
    if occluded {
        return Vec3::ZERO;
    }
    let area = LIGHT_SIZE * LIGHT_SIZE;
    hit.albedo / std::f32::consts::PI * LIGHT_RADIANCE * cos_s * cos_l / d2 * area
}

/// Renders the image (linear radiance, row-major) with `spp` samples of `sequence`.
fn render(
    sequence: Sequence,
    spp: u32,
    size: (u32, u32),
    seed: u64,
) -> Result<Vec<Vec3>, strata::Error> {
    let sampler = PixelSampler::new(sequence, spp, seed)?;
    let scene = spheres();
    let image = (0..size.1)
        .into_par_iter()
        .flat_map_iter(|y| {
            let mut s = sampler.clone();
            let scene = &scene;
            (0..size.0).map(move |x| {
                let mut sum = Vec3::ZERO;
                for i in 0..spp {
                    s.start_pixel_sample([x, y], i as u64, 0);
                    sum += radiance(x, y, size, &mut s, scene);
                }
                sum / spp as f32
            })
        })
        .collect();
    Ok(image)
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
    image: Vec<Vec3>,
    rmse: f64,
    rel_rmse: f64,
    ms: f64,
}

fn main() -> ExitCode {
    common::run("render", || {
        let Some(args) = parse()? else { return Ok(()) };
        let sequences: Vec<(String, Sequence)> = args
            .samplers
            .iter()
            .map(|n| Ok((n.clone(), Sequence::by_name(n)?)))
            .collect::<Result<_, strata::Error>>()?;
        for (_, seq) in &sequences {
            seq.check_spp(args.spp)?;
        }
        let size = args.size;
        let ref_spp = args.reference_spp.unwrap_or((args.spp * 64).min(16384));
        eprintln!(
            "reference: sobol at {ref_spp} spp, {}x{} ...",
            size.0, size.1
        );
        let reference = render(Sequence::sobol(), ref_spp, size, 0x5eed_0000_0001)?;
        io::write_png(args.out.join("reference.png"), &to_canvas(&reference, size))?;

        let mut rows = Vec::new();
        for (name, seq) in sequences {
            let start = Instant::now();
            let image = render(seq, args.spp, size, 1)?;
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let n = image.len() as f64;
            let mse: f64 = image
                .iter()
                .zip(&reference)
                .map(|(a, r)| (*a - *r).length_squared() as f64 / 3.0)
                .sum::<f64>()
                / n;
            let rel: f64 = image
                .iter()
                .zip(&reference)
                .map(|(a, r)| (relative_error(*a, *r) as f64).powi(2))
                .sum::<f64>()
                / n;
            io::write_png(
                args.out.join(format!("{name}.png")),
                &to_canvas(&image, size),
            )?;
            io::write_png(
                args.out.join(format!("{name}-error.png")),
                &error_canvas(&image, &reference, size),
            )?;
            rows.push(Row {
                name,
                image,
                rmse: mse.sqrt(),
                rel_rmse: rel.sqrt(),
                ms,
            });
        }

        // compare.png: the reference, then per sampler the image over its error map
        let label_h = 22u32;
        let col_w = size.0 + 56 + 8;
        let width = col_w * (rows.len() as u32 + 1) + 8;
        let height = label_h + size.1 + 8 + size.1 + 8;
        let mut compare = Canvas::new(width, height, Rgb::WHITE);
        compare.paste(&to_canvas(&reference, size), 8, label_h as i64);
        io::label(
            &mut compare,
            &format!("reference ({ref_spp} spp)"),
            8,
            4,
            14,
        );
        for (k, r) in rows.iter().enumerate() {
            let x = 8 + col_w as i64 * (k as i64 + 1);
            io::label(
                &mut compare,
                &format!("{} ({} spp), rel. RMSE {:.3}", r.name, args.spp, r.rel_rmse),
                x as i32,
                4,
                14,
            );
            compare.paste(&to_canvas(&r.image, size), x, label_h as i64);
            compare.paste(
                &error_canvas(&r.image, &reference, size),
                x,
                (label_h + size.1 + 8) as i64,
            );
        }
        io::write_png(args.out.join("compare.png"), &compare)?;

        let mut csv = String::from("sampler,spp,rmse,rel_rmse,ms\n");
        println!("| sampler | spp | rmse | rel_rmse | ms |");
        println!("|---|---|---|---|---|");
        for r in &rows {
            csv.push_str(&format!(
                "{},{},{},{},{}\n",
                r.name, args.spp, r.rmse, r.rel_rmse, r.ms
            ));
            println!(
                "| {} | {} | {:.5} | {:.4} | {:.1} |",
                r.name, args.spp, r.rmse, r.rel_rmse, r.ms
            );
        }
        io::write_text(args.out.join("render.csv"), &csv)?;
        eprintln!("wrote {} into {}", rows.len(), args.out.display());
        Ok(())
    })
}
