//! Runs the WGSL draw kernel of `strata` ([`strata::pixel::WGSL`]) on the GPU: a compute
//! shader that evaluates `strata_draw` for a batch of `(pixel, index, dim)` tuples, with the
//! parameters and the tables of [`strata::PixelSampler::gpu_parameters`], and the same tuples
//! on the CPU ([`strata::PixelSampler::sample_2d_u32`]). The tests in `tests/` compare the two.

use strata::pixel::GpuParameters;

/// The compute shader around the kernel: tuple `k` is [`tuple()`]`(k)`, computed the same way on
/// both sides; its two 32-bit values land at `out[2k]`, `out[2k + 1]`.
pub fn compute_shader() -> String {
    format!(
        "{}\n{}",
        strata::pixel::WGSL,
        r#"
@group(0) @binding(0) var<uniform> params: StrataParameters;
@group(0) @binding(1) var<storage, read_write> out: array<u32>;
@group(0) @binding(2) var<uniform> batch: vec4<u32>;
@group(0) @binding(3) var<storage, read> strata_tables: array<u32>;

fn test_hash(k: u32, salt: u32) -> u32 {
    return strata_hash32(k, strata_hash32(salt, 0x51ed270bu));
}

// The tuple of invocation k: the first half a grid of pixels, indices and dimensions as a
// renderer asks for them; the second half hashed over the whole u32 range of each.
fn test_tuple(k: u32) -> vec4<u32> {
    if (k < batch.y) {
        return vec4<u32>(k & 63u, (k >> 6u) & 63u, (k >> 12u) & 255u, ((k >> 20u) & 15u) * 2u);
    }
    return vec4<u32>(test_hash(k, 1u), test_hash(k, 2u), test_hash(k, 3u), test_hash(k, 4u));
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let k = gid.x + gid.y * batch.z;
    if (k >= batch.x) {
        return;
    }
    let t = test_tuple(k);
    let v = strata_draw(params, t.xy, t.z, t.w);
    out[2u * k] = v.x;
    out[2u * k + 1u] = v.y;
}
"#
    )
}

/// `lowbias32(x ^ key)`, as `strata_hash32` in the shader.
fn hash32(x: u32, key: u32) -> u32 {
    strata::hash::hash32(x, key)
}

/// Tuple `k` of a batch whose first `grid` tuples are the grid (see the shader).
pub fn tuple(k: u32, grid: u32) -> ([u32; 2], u32, u32) {
    if k < grid {
        return (
            [k & 63, (k >> 6) & 63],
            (k >> 12) & 255,
            ((k >> 20) & 15) * 2,
        );
    }
    let h = |salt: u32| hash32(k, hash32(salt, 0x51ed_270b));
    ([h(1), h(2)], h(3), h(4))
}

/// A GPU, or why there is none.
pub struct Gpu {
    device: wgpu::Device,
    queue: wgpu::Queue,
    /// The adapter's name and backend.
    pub name: String,
    pipeline: wgpu::ComputePipeline,
}

/// What to install when no adapter is found.
pub const DRIVER_HINT: &str = "no Vulkan adapter: install a Vulkan driver (on Debian: `apt-get \
     install mesa-vulkan-drivers libvulkan1`, Mesa's lavapipe, a Vulkan device on the CPU)";

impl Gpu {
    /// The first adapter wgpu finds, with the test shader compiled.
    pub fn new() -> Result<Gpu, String> {
        let instance = wgpu::Instance::default();
        let adapter =
            pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default()))
                .map_err(|e| format!("{DRIVER_HINT} ({e})"))?;
        let info = adapter.get_info();
        let (device, queue) =
            pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor::default()))
                .map_err(|e| format!("request_device: {e}"))?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("strata test"),
            source: wgpu::ShaderSource::Wgsl(compute_shader().into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("strata test"),
            layout: None,
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        Ok(Gpu {
            device,
            queue,
            name: format!("{} ({:?}, {:?})", info.name, info.backend, info.device_type),
            pipeline,
        })
    }

    /// The kernel's values of tuples `0..count` (the first `grid` a grid) for `params` (its
    /// uniform's words and its tables).
    pub fn draw(&self, params: &GpuParameters, count: u32, grid: u32) -> Result<Vec<u32>, String> {
        use wgpu::util::DeviceExt;
        const GROUPS_X: u32 = 32768;
        let words = params.words();
        let bytes = |w: &[u32]| w.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>();
        let params_buf = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents: &bytes(&words),
                usage: wgpu::BufferUsages::UNIFORM,
            });
        let batch_buf = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents: &bytes(&[count, grid, GROUPS_X * 64, 0]),
                usage: wgpu::BufferUsages::UNIFORM,
            });
        let tables_buf = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents: &bytes(&params.tables()),
                usage: wgpu::BufferUsages::STORAGE,
            });
        let size = count as u64 * 8;
        let out = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let read = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = self.pipeline.get_bind_group_layout(0);
        let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: params_buf.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: out.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: batch_buf.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: tables_buf.as_entire_binding(),
                },
            ],
        });
        let mut encoder = self.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &group, &[]);
            let groups = count.div_ceil(64);
            pass.dispatch_workgroups(groups.min(GROUPS_X), groups.div_ceil(GROUPS_X), 1);
        }
        encoder.copy_buffer_to_buffer(&out, 0, &read, 0, size);
        self.queue.submit([encoder.finish()]);
        let slice = read.slice(..);
        slice.map_async(wgpu::MapMode::Read, |r| {
            r.expect("map the read-back buffer")
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| format!("poll: {e}"))?;
        let view = slice
            .get_mapped_range()
            .map_err(|e| format!("mapped range: {e}"))?;
        Ok(view
            .chunks_exact(4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect())
    }
}
