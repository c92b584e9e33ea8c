//! The smallest complete use of the path-tracer adapter: the soft shadow of a sphere under a
//! square area light, one `PixelSampler` per thread, written as `DIR/path_tracer.pgm`.
//! `cargo run --release --example path_tracer [-- --out DIR]` (default `out`)
mod common;

use std::path::PathBuf;
use std::process::ExitCode;

use glam::{Vec2, Vec3};
use strata::{PixelSampler, Seed, Sequence};

const SIZE: u32 = 256;
const SPP: u32 = 64;

/// Radiance at the floor point under pixel (x, y): the light seen past the sphere.
fn shade(s: &mut PixelSampler, x: u32, y: u32) -> f32 {
    let film = Vec2::from(s.get_pixel_2d()); // dimensions 0-1: where in the pixel
    let p = Vec3::new(x as f32 + film.x, 0.0, y as f32 + film.y) / SIZE as f32 * 4.0 - 2.0;
    let on_light = Vec2::from(s.get_2d()); // dimensions 2-3: a point on the 1 x 1 light at height 3
    let q = Vec3::new(on_light.x - 0.5, 3.0, on_light.y - 0.5);
    let (d, c, r) = ((q - p).normalize(), Vec3::new(0.0, 1.0, 0.0), 0.6);
    let b = (p - c).dot(d);
    let blocked = b * b - (p - c).length_squared() + r * r > 0.0 && b < 0.0;
    if blocked {
        0.0
    } else {
        9.0 * d.y.powi(2) / (q - p).length_squared()
    }
}

/// The one option, declared once (clap makes `--help`, the usage and the errors from it).
#[derive(clap::Parser)]
#[command(
    name = "path_tracer",
    about = "path_tracer: the smallest complete use of strata's path-tracer adapter; writes \
             DIR/path_tracer.pgm (256 x 256, 64 spp of pmj02)"
)]
struct Args {
    /// where to write
    #[arg(long, value_name = "DIR", default_value = "out")]
    out: PathBuf,
}

fn main() -> ExitCode {
    use clap::{CommandFactory, FromArgMatches};
    let matches = match common::clap_matches(Args::command()) {
        Ok(Some(m)) => m,
        Ok(None) => return ExitCode::SUCCESS, // --help
        Err(common::CliError::Message(m)) => return fail(&m),
        Err(common::CliError::BrokenPipe) => return ExitCode::from(141),
    };
    let args = match Args::from_arg_matches(&matches) {
        Ok(a) => a,
        Err(e) => return fail(&e.to_string()),
    };
    match render(&args.out) {
        Ok(msg) => say(&msg),
        Err(e) => fail(&e.to_string()),
    }
}

/// Prints a line: a closed pipe ends the program quietly (status 141), another failure says so.
fn say(text: &str) -> ExitCode {
    use std::io::Write;
    match writeln!(std::io::stdout(), "{text}") {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::from(141),
        Err(e) => fail(&format!("writing to standard output: {e}")),
    }
}

fn fail(msg: &str) -> ExitCode {
    eprintln!("path_tracer: error: {msg}");
    ExitCode::from(2)
}

fn render(out: &std::path::Path) -> Result<String, strata_lab::Error> {
    let sampler = PixelSampler::new(Sequence::pmj02(), SPP, Seed(1))?;
    let mut image = vec![0.0f32; (SIZE * SIZE) as usize];
    std::thread::scope(|scope| {
        for (t, rows) in image.chunks_mut((SIZE * SIZE / 2) as usize).enumerate() {
            let mut s = sampler.clone(); // one sampler per thread: cheap, allocation-free
            scope.spawn(move || {
                for (i, v) in rows.iter_mut().enumerate() {
                    let (x, y) = (i as u32 % SIZE, i as u32 / SIZE + t as u32 * SIZE / 2);
                    for index in 0..SPP as u64 {
                        s.start_pixel_sample([x, y], index, 0);
                        *v += shade(&mut s, x, y) / SPP as f32;
                    }
                }
            });
        }
    });
    let bytes: Vec<u8> = image
        .iter()
        .map(|v| (v.min(1.0).powf(1.0 / 2.2) * 255.0) as u8)
        .collect();
    let path = out.join("path_tracer.pgm");
    // never half written; a failure names the file and the reason
    strata_lab::io::write_file(
        &path,
        &[format!("P5 {SIZE} {SIZE} 255\n").as_bytes(), &bytes].concat(),
    )?;
    Ok(format!(
        "wrote {} ({SIZE}x{SIZE}, {SPP} spp); mean {:.4}",
        path.display(),
        image.iter().sum::<f32>() / image.len() as f32
    ))
}
