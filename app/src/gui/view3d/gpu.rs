//! The 3D view's wgpu side: one pipeline drawing instanced screen-space
//! segments (`lines.wgsl`), built once for eframe's target format and kept in
//! egui-wgpu's callback resources; each frame a [`DrawLines`] paint callback
//! uploads the segments and the camera, then draws into egui's render pass.

use std::sync::Arc;

use eframe::egui;
use eframe::egui_wgpu::{self, CallbackResources, CallbackTrait, ScreenDescriptor};
use eframe::wgpu;
use eframe::wgpu::util::DeviceExt as _;

use super::scene::Segment;

/// The uniforms of `lines.wgsl`.
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct Uniforms {
    /// World (scene) to clip space, column-major.
    pub view_proj: [[f32; 4]; 4],
    /// The viewport in physical pixels.
    pub viewport: [f32; 2],
    /// Padding to 16 bytes.
    pub pad: [f32; 2],
}

/// The pipeline and buffers, stored in the renderer's callback resources.
struct LineRenderer {
    pipeline: wgpu::RenderPipeline,
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    instances: wgpu::Buffer,
    capacity: usize,
    count: u32,
}

const SEGMENT_SIZE: u64 = size_of::<Segment>() as u64;

fn instance_buffer(device: &wgpu::Device, capacity: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("dmpscope 3d segments"),
        size: capacity as u64 * SEGMENT_SIZE,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// Builds the pipeline for `render_state`'s target format and stores it
/// for [`DrawLines`] callbacks. Call once, when the app is created.
pub fn install(render_state: &egui_wgpu::RenderState) {
    let device = &render_state.device;
    let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("dmpscope 3d lines"),
        source: wgpu::ShaderSource::Wgsl(include_str!("lines.wgsl").into()),
    });
    let layout = uniforms_layout(device);
    let pipeline = line_pipeline(device, &shader, &layout, render_state.target_format);
    let (uniforms, bind_group) = uniforms_and_bind_group(device, &layout);
    let capacity = 4096;
    let renderer = LineRenderer {
        pipeline,
        uniforms,
        bind_group,
        instances: instance_buffer(device, capacity),
        capacity,
        count: 0,
    };
    render_state
        .renderer
        .write()
        .callback_resources
        .insert(renderer);
}

/// The layout of the shader's one binding: the uniforms, read by the vertex stage.
fn uniforms_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("dmpscope 3d uniforms"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }],
    })
}

/// The pipeline drawing one instance per segment into `format`, blended as
/// premultiplied alpha.
fn line_pipeline(
    device: &wgpu::Device,
    shader: &wgpu::ShaderModule,
    layout: &wgpu::BindGroupLayout,
    format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("dmpscope 3d"),
        bind_group_layouts: &[Some(layout)],
        immediate_size: 0,
    });
    let attributes = wgpu::vertex_attr_array![
        0 => Float32x3, 1 => Float32x3, 2 => Float32x4, 3 => Float32x4
    ];
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("dmpscope 3d lines"),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: shader,
            entry_point: Some("vs_main"),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: SEGMENT_SIZE,
                step_mode: wgpu::VertexStepMode::Instance,
                attributes: &attributes,
            })],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: shader,
            entry_point: Some("fs_main"),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format,
                blend: Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// The uniforms' buffer (zeroed) and the bind group that binds it.
fn uniforms_and_bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
) -> (wgpu::Buffer, wgpu::BindGroup) {
    let uniforms = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("dmpscope 3d uniforms"),
        contents: bytemuck::bytes_of(&Uniforms::default()),
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("dmpscope 3d uniforms"),
        layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: uniforms.as_entire_binding(),
        }],
    });
    (uniforms, bind_group)
}

/// One frame's draw of the 3D view.
pub struct DrawLines {
    /// Camera and viewport.
    pub uniforms: Uniforms,
    /// The segments in painter's order.
    pub segments: Arc<Vec<Segment>>,
}

impl CallbackTrait for DrawLines {
    fn prepare(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        _screen: &ScreenDescriptor,
        _encoder: &mut wgpu::CommandEncoder,
        resources: &mut CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        let Some(r) = resources.get_mut::<LineRenderer>() else {
            return Vec::new();
        };
        if self.segments.len() > r.capacity {
            r.capacity = self.segments.len().next_power_of_two();
            r.instances = instance_buffer(device, r.capacity);
        }
        queue.write_buffer(&r.uniforms, 0, bytemuck::bytes_of(&self.uniforms));
        queue.write_buffer(&r.instances, 0, bytemuck::cast_slice(&self.segments));
        r.count = u32::try_from(self.segments.len()).unwrap_or(u32::MAX);
        Vec::new()
    }

    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        resources: &CallbackResources,
    ) {
        let Some(r) = resources.get::<LineRenderer>() else {
            return;
        };
        if r.count == 0 {
            return;
        }
        pass.set_pipeline(&r.pipeline);
        pass.set_bind_group(0, &r.bind_group, &[]);
        pass.set_vertex_buffer(0, r.instances.slice(..));
        pass.draw(0..6, 0..r.count);
    }
}
