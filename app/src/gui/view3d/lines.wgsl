// Screen-space lines for the 3D view. Each instance is one segment between
// two world points; the vertex shader expands it into a quad a fixed number
// of pixels wide (plus a one-pixel margin for anti-aliasing) with round
// caps, so polylines join smoothly and a zero-length segment is a disc.
// Written for WebGL2 as well as Vulkan/Metal/WebGPU: no storage buffers,
// no depth buffer (draw order is the painter's order).

struct Uniforms {
    view_proj: mat4x4<f32>,
    // The callback's viewport in physical pixels.
    viewport: vec2<f32>,
    _pad: vec2<f32>,
};

@group(0) @binding(0) var<uniform> u: Uniforms;

struct Segment {
    @location(0) p0: vec3<f32>,
    @location(1) p1: vec3<f32>,
    // Premultiplication happens here; the colour is sRGB-encoded like egui's.
    @location(2) colour: vec4<f32>,
    // x: width in pixels, y: dash period in world units (0 = solid),
    // z, w: arc length at p0 and p1.
    @location(3) style: vec4<f32>,
};

struct VsOut {
    @builtin(position) pos: vec4<f32>,
    @location(0) colour: vec4<f32>,
    // x: along the segment from p0 (px), y: across (px),
    // z: segment length (px), w: half width (px).
    @location(1) frame: vec4<f32>,
    // x: arc length, y: dash period.
    @location(2) dash: vec2<f32>,
};

@vertex
fn vs_main(@builtin(vertex_index) vi: u32, seg: Segment) -> VsOut {
    var out: VsOut;
    let c0 = u.view_proj * vec4<f32>(seg.p0, 1.0);
    let c1 = u.view_proj * vec4<f32>(seg.p1, 1.0);
    // Segments with an end behind the eye are not drawn.
    if (c0.w <= 1e-6 || c1.w <= 1e-6) {
        out.pos = vec4<f32>(2.0, 2.0, 2.0, 1.0);
        out.colour = vec4<f32>(0.0);
        out.frame = vec4<f32>(0.0);
        out.dash = vec2<f32>(0.0);
        return out;
    }
    let half_vp = 0.5 * u.viewport;
    let s0 = c0.xy / c0.w * half_vp;
    let s1 = c1.xy / c1.w * half_vp;
    let delta = s1 - s0;
    let len = length(delta);
    var dir = vec2<f32>(1.0, 0.0);
    if (len > 1e-4) {
        dir = delta / len;
    }
    let nrm = vec2<f32>(-dir.y, dir.x);
    let half_w = 0.5 * seg.style.x;
    let r = half_w + 1.0;

    var corners = array<vec2<f32>, 6>(
        vec2<f32>(0.0, -1.0), vec2<f32>(1.0, -1.0), vec2<f32>(1.0, 1.0),
        vec2<f32>(0.0, -1.0), vec2<f32>(1.0, 1.0), vec2<f32>(0.0, 1.0),
    );
    let corner = corners[vi % 6u];
    let at_end = corner.x > 0.5;
    var base = s0;
    var ext = -r;
    if (at_end) {
        base = s1;
        ext = r;
    }
    let px = base + dir * ext + nrm * (corner.y * r);

    let z0 = clamp(c0.z / c0.w, 0.0, 1.0);
    let z1 = clamp(c1.z / c1.w, 0.0, 1.0);
    out.pos = vec4<f32>(px / half_vp, mix(z0, z1, corner.x), 1.0);
    out.colour = seg.colour;
    out.frame = vec4<f32>(dot(px - s0, dir), corner.y * r, len, half_w);
    var s = seg.style.z;
    if (at_end) {
        s = seg.style.w;
    }
    out.dash = vec2<f32>(s, seg.style.y);
    return out;
}

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    let along = in.frame.x;
    let across = in.frame.y;
    let len = in.frame.z;
    var dist = abs(across);
    if (along < 0.0) {
        dist = length(vec2<f32>(along, across));
    } else if (along > len) {
        dist = length(vec2<f32>(along - len, across));
    }
    let coverage = clamp(in.frame.w + 0.5 - dist, 0.0, 1.0);
    if (coverage <= 0.0) {
        discard;
    }
    if (in.dash.y > 0.0 && fract(in.dash.x / in.dash.y) > 0.6) {
        discard;
    }
    let a = in.colour.a * coverage;
    return vec4<f32>(in.colour.rgb * a, a);
}
