//! The scenes: their geometry (spheres, possibly moving, and axis-aligned rectangles), their
//! materials and lights, the thin-lens camera, ray intersection, and the scenes `cornell`,
//! `spheres`, `cornell-direct`, `studio` and `studio-direct`.

use glam::{Vec2, Vec3};
use strata::pixel::warp;

/// Which scene.
#[derive(Clone, Copy, Debug, PartialEq, clap::ValueEnum)]
pub enum SceneKind {
    /// a Cornell box, up to 8 bounces, two lights, a discrete light and lobe choice, Russian
    /// roulette, thin lens
    Cornell,
    /// direct lighting, seven dimensions
    Spheres,
    /// the Cornell box in direct lighting: the first diffuse hit's next-event estimate (and the
    /// lights seen directly or in a mirror), no further bounce
    CornellDirect,
    /// not a box: a checkered floor with glossy tiles, a striped wall, a plastic, a metal and a
    /// textured sphere under one small light; up to 8 bounces, the next direction from a lobe
    /// chosen by weight
    Studio,
    /// studio in direct lighting: the first hit's next-event estimate (through its diffuse
    /// and glossy lobes), and the light seen directly
    StudioDirect,
}

impl SceneKind {
    /// The scene's name on the command line and in section names.
    pub fn name(self) -> &'static str {
        match self {
            SceneKind::Cornell => "cornell",
            SceneKind::Spheres => "spheres",
            SceneKind::CornellDirect => "cornell-direct",
            SceneKind::Studio => "studio",
            SceneKind::StudioDirect => "studio-direct",
        }
    }
}

/// The scene of `kind`.
pub fn build(kind: SceneKind) -> Scene {
    match kind {
        SceneKind::Cornell => cornell(),
        SceneKind::Spheres => spheres(),
        SceneKind::CornellDirect => Scene {
            direct: true,
            ..cornell()
        },
        SceneKind::Studio => studio(),
        SceneKind::StudioDirect => Scene {
            direct: true,
            kind: SceneKind::StudioDirect,
            ..studio()
        },
    }
}

/// A sphere, possibly moving over the shutter interval (motion blur).
struct Sphere {
    centre: Vec3,
    radius: f32,
    motion: Vec3,
    material: Material,
}

/// An axis-aligned rectangle: `axis` is the normal axis (0, 1, 2) at `offset`, spanning
/// `[lo, hi]` on the other two axes; `facing` is the sign of the side it faces.
pub struct Rect {
    axis: usize,
    offset: f32,
    lo: [f32; 2],
    hi: [f32; 2],
    facing: f32,
    pub material: Material,
}

/// What a surface does with light.
#[derive(Clone, Copy, Debug)]
pub enum Material {
    /// Lambertian with an albedo; `mirror` is the probability weight of a perfect mirror lobe.
    Surface { albedo: Vec3, mirror: f32 },
    /// An area light, emitting `radiance` on its facing side (black behind).
    Light { radiance: Vec3 },
    /// A textured diffuse lobe and a glossy (normalized Phong) lobe of colour `specular` and
    /// exponent `exponent` about the mirror direction: the BRDF is `(1 - gloss) albedo / pi +
    /// gloss specular (n + 2) / (2 pi) cos^n`. Next-event estimation sees both lobes; the next
    /// direction comes from one, chosen with its weight.
    Glossy {
        texture: Texture,
        gloss: f32,
        specular: Vec3,
        exponent: f32,
    },
}

/// A procedural albedo.
#[derive(Clone, Copy, Debug)]
pub enum Texture {
    /// Squares of side `1 / scale` on the x-z plane, alternating `a` and `b`.
    Checker {
        a: Vec3,
        b: Vec3,
        scale: f32,
    },
    /// Stripes of width `1 / scale` along x, alternating `a` and `b`.
    Stripes {
        a: Vec3,
        b: Vec3,
        scale: f32,
    },
    /// Cubes of side `1 / scale` in space, alternating `a` and `b` (a solid texture).
    Solid {
        a: Vec3,
        b: Vec3,
        scale: f32,
    },
    Flat(Vec3),
}

impl Texture {
    /// The albedo at `p`.
    pub fn at(&self, p: Vec3) -> Vec3 {
        let cell = |v: f32, scale: f32| (v * scale).floor() as i64;
        let pick = |even: bool, a: Vec3, b: Vec3| if even { a } else { b };
        match *self {
            Texture::Checker { a, b, scale } => pick(
                (cell(p.x, scale) + cell(p.z, scale)).rem_euclid(2) == 0,
                a,
                b,
            ),
            Texture::Stripes { a, b, scale } => pick(cell(p.x, scale).rem_euclid(2) == 0, a, b),
            Texture::Solid { a, b, scale } => pick(
                (cell(p.x, scale) + cell(p.y, scale) + cell(p.z, scale)).rem_euclid(2) == 0,
                a,
                b,
            ),
            Texture::Flat(a) => a,
        }
    }
}

/// Where a ray meets the scene: its distance, the point, the surface normal and material.
pub struct Hit {
    pub t: f32,
    pub point: Vec3,
    pub normal: Vec3,
    pub material: Material,
}

/// The two axes other than `axis`, in increasing order.
fn other_axes(axis: usize) -> (usize, usize) {
    match axis {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

impl Rect {
    /// The unit normal on the side the rectangle faces.
    pub fn normal(&self) -> Vec3 {
        let mut n = Vec3::ZERO;
        n[self.axis] = self.facing;
        n
    }

    /// The rectangle's area.
    pub fn area(&self) -> f32 {
        (self.hi[0] - self.lo[0]) * (self.hi[1] - self.lo[1])
    }

    /// The point at `u` on the rectangle.
    pub fn point(&self, u: Vec2) -> Vec3 {
        let (a, b) = other_axes(self.axis);
        let mut p = Vec3::ZERO;
        p[self.axis] = self.offset;
        p[a] = self.lo[0] + u.x * (self.hi[0] - self.lo[0]);
        p[b] = self.lo[1] + u.y * (self.hi[1] - self.lo[1]);
        p
    }

    /// The distance along the ray at which it meets the rectangle, if nearer than `best`.
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

/// A scene: the spheres and rectangles, the lights among the rectangles, and the camera.
pub struct Scene {
    spheres: Vec<Sphere>,
    pub rects: Vec<Rect>,
    /// Indices into `rects` of the lights, with the probability of choosing each (by power).
    pub lights: Vec<(usize, f32)>,
    pub camera: Camera,
    pub kind: SceneKind,
    /// The radiance of a ray that leaves the scene.
    pub sky: Vec3,
    /// Direct lighting only: the path ends after the first diffuse hit's next-event estimate.
    pub direct: bool,
    /// Where the draws of a path go (`--layout`).
    pub layout: crate::trace::Layout,
}

/// A thin-lens camera looking along `forward`, focused at distance `focus`.
pub struct Camera {
    eye: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    tan_half: f32,
    focus: f32,
    aperture: f32,
}

impl Camera {
    /// A camera at `eye` looking at `target` with a vertical field of view of `fov_deg`.
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
    pub fn ray(&self, px: u32, py: u32, size: (u32, u32), film: Vec2, lens: Vec2) -> (Vec3, Vec3) {
        let (w, h) = (size.0 as f32, size.1 as f32);
        let ndc = Vec2::new(
            (px as f32 + film.x) / w * 2.0 - 1.0,
            1.0 - (py as f32 + film.y) / h * 2.0,
        );
        let dir = (self.forward
            + self.right * ndc.x * self.tan_half * w / h
            + self.up * ndc.y * self.tan_half)
            .normalize();
        let disk = Vec2::from(warp::concentric_disk(lens.into())) * self.aperture;
        let offset = self.right * disk.x + self.up * disk.y;
        let focal_point = self.eye + dir * (self.focus / dir.dot(self.forward));
        let origin = self.eye + offset;
        (origin, (focal_point - origin).normalize())
    }
}

impl Scene {
    /// The nearest hit of the ray at shutter time `time`, if any.
    pub fn intersect(&self, origin: Vec3, dir: Vec3, time: f32) -> Option<Hit> {
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
    pub fn visible(&self, p: Vec3, q: Vec3, time: f32) -> bool {
        let d = q - p;
        let len = d.length();
        self.intersect(p, d / len, time)
            .is_none_or(|h| h.t >= len * (1.0 - 1e-4))
    }
}

/// A diffuse surface of `albedo` with no mirror lobe.
fn surface(albedo: Vec3) -> Material {
    Material::Surface {
        albedo,
        mirror: 0.0,
    }
}

/// A rectangle of material `m` (see [`Rect`]).
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
    let rects = cornell_rects();
    let lights = lights_by_power(&rects);
    Scene {
        spheres: cornell_spheres(),
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
        sky: Vec3::ZERO,
        direct: false,
        layout: crate::trace::Layout::Bounce,
    }
}

/// The Cornell box's walls (white, red on the left as the camera sees it, green on the right)
/// and its two lights, a warm one on the ceiling and a cool one on the back wall.
fn cornell_rects() -> Vec<Rect> {
    let white = surface(Vec3::splat(0.73));
    let red = surface(Vec3::new(0.65, 0.05, 0.05));
    let green = surface(Vec3::new(0.12, 0.45, 0.15));
    let ceiling_light = Material::Light {
        radiance: Vec3::new(17.0, 12.0, 4.0),
    };
    let wall_light = Material::Light {
        radiance: Vec3::new(2.0, 3.0, 6.0),
    };
    vec![
        rect(1, 0.0, [0.0, 0.0], [1.0, 1.0], 1.0, white), // floor
        rect(1, 1.0, [0.0, 0.0], [1.0, 1.0], -1.0, white), // ceiling
        rect(2, 1.0, [0.0, 0.0], [1.0, 1.0], -1.0, white), // back
        rect(0, 1.0, [0.0, 0.0], [1.0, 1.0], -1.0, red),  // left as the camera sees it
        rect(0, 0.0, [0.0, 0.0], [1.0, 1.0], 1.0, green), // right
        rect(1, 0.999, [0.37, 0.42], [0.63, 0.68], -1.0, ceiling_light),
        rect(2, 0.999, [0.08, 0.55], [0.3, 0.8], -1.0, wall_light),
    ]
}

/// The lights among `rects` (their indices), each with the probability of choosing it: its
/// share of the total power (area times the sum of the radiance's channels).
fn lights_by_power(rects: &[Rect]) -> Vec<(usize, f32)> {
    let power = |r: &Rect| match r.material {
        Material::Light { radiance } => r.area() * (radiance.x + radiance.y + radiance.z),
        Material::Surface { .. } | Material::Glossy { .. } => 0.0,
    };
    let total: f32 = rects.iter().map(power).sum();
    rects
        .iter()
        .enumerate()
        .filter(|(_, r)| power(r) > 0.0)
        .map(|(i, r)| (i, power(r) / total))
        .collect()
}

/// The Cornell box's spheres: a white diffuse one, and one half mirror, half diffuse.
fn cornell_spheres() -> Vec<Sphere> {
    vec![
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
    ]
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
        sky: Vec3::new(0.05, 0.07, 0.1),
        direct: true,
        layout: crate::trace::Layout::Bounce,
    }
}

/// The ground's checkerboard in the `spheres` scene.
pub fn checker(p: Vec3) -> f32 {
    let even = ((p.x * 1.5).floor() as i64 + (p.z * 1.5).floor() as i64).rem_euclid(2) == 0;
    if even { 0.75 } else { 0.2 }
}

/// Not a Cornell box: a floor of diffuse checkers, the dark ones polished (a glossy lobe), a
/// striped back wall, a red plastic sphere (diffuse and a broad glossy lobe), a metal sphere
/// (a sharp glossy lobe) and a sphere with a solid checker texture, lit by one small square
/// light (0.4 x 0.4, seen in the top of the image) and nothing else (no sky).
fn studio() -> Scene {
    let floor = Material::Glossy {
        texture: Texture::Checker {
            a: Vec3::new(0.75, 0.72, 0.65),
            b: Vec3::new(0.08, 0.08, 0.1),
            scale: 1.25,
        },
        gloss: 0.25,
        specular: Vec3::splat(0.9),
        exponent: 30.0,
    };
    let wall = Material::Glossy {
        texture: Texture::Stripes {
            a: Vec3::new(0.7, 0.7, 0.72),
            b: Vec3::new(0.25, 0.35, 0.6),
            scale: 2.5,
        },
        gloss: 0.0,
        specular: Vec3::ZERO,
        exponent: 1.0,
    };
    let light = Material::Light {
        radiance: Vec3::new(150.0, 135.0, 110.0),
    };
    let rects = vec![
        rect(1, 0.0, [-4.0, -3.0], [4.0, 4.0], 1.0, floor),
        rect(2, 4.0, [-4.0, 0.0], [4.0, 4.0], -1.0, wall),
        rect(1, 2.2, [-0.2, 1.4], [0.2, 1.8], -1.0, light),
    ];
    let lights = lights_by_power(&rects);
    Scene {
        spheres: vec![
            Sphere {
                centre: Vec3::new(-1.15, 0.6, 1.9),
                radius: 0.6,
                motion: Vec3::ZERO,
                material: Material::Glossy {
                    texture: Texture::Flat(Vec3::new(0.7, 0.12, 0.1)),
                    gloss: 0.3,
                    specular: Vec3::splat(0.8),
                    exponent: 25.0,
                },
            },
            Sphere {
                centre: Vec3::new(0.55, 0.5, 2.5),
                radius: 0.5,
                motion: Vec3::ZERO,
                material: Material::Glossy {
                    texture: Texture::Flat(Vec3::new(0.1, 0.1, 0.1)),
                    gloss: 0.85,
                    specular: Vec3::new(0.95, 0.8, 0.55),
                    exponent: 120.0,
                },
            },
            Sphere {
                centre: Vec3::new(1.45, 0.4, 1.0),
                radius: 0.4,
                motion: Vec3::ZERO,
                material: Material::Glossy {
                    texture: Texture::Solid {
                        a: Vec3::new(0.2, 0.55, 0.25),
                        b: Vec3::new(0.85, 0.85, 0.8),
                        scale: 6.0,
                    },
                    gloss: 0.0,
                    specular: Vec3::ZERO,
                    exponent: 1.0,
                },
            },
        ],
        rects,
        lights,
        camera: Camera::new(
            Vec3::new(0.0, 1.4, -3.0),
            Vec3::new(0.0, 0.7, 2.0),
            40.0,
            5.0,
            0.03,
        ),
        kind: SceneKind::Studio,
        sky: Vec3::ZERO,
        direct: false,
        layout: crate::trace::Layout::Bounce,
    }
}
