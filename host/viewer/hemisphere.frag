#version 450
// hemisphere.frag: the top view of a hemisphere of bins (orthographic: radius sin(theta), x along phi = 0,
// the light's side). The colours are computed per bin on the host (ui.cpp), so a pixel costs one load: lavapipe
// shades fragments on the CPU, and the window must keep its frame rate.
layout(push_constant) uniform Push {
    vec4 rect;
    vec4 params;        // x: sin(theta_i) for the light's marker (< 0: none), y: bin width in theta (rad), z: in phi
                        // (rad), w: the light's azimuth phi_i (rad)
    uvec4 offsets;      // x: first colour of this panel in the buffer, y: n_theta, z: n_phi
    uvec4 unused;
} pc;

layout(std430, set = 0, binding = 0) readonly buffer Colours { uint rgba8[]; };

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 colour;

void main() {
    float r = length(uv);
    if (r > 1.0) {
        if (r > 1.02) discard;
        colour = vec4(0.55, 0.55, 0.55, 1.0);    // the horizon
        return;
    }
    float theta = asin(r);
    float phi = atan(uv.y, uv.x);
    if (phi < 0.0) phi += 6.28318530718;
    uint n_theta = pc.offsets.y, n_phi = pc.offsets.z;
    uint t = min(uint(theta / pc.params.y), n_theta - 1u);
    uint q = uint(floor(phi / pc.params.z + 0.5)) % n_phi;    // phi bins are centred on multiples of dphi
    colour = unpackUnorm4x8(rgba8[pc.offsets.x + t * n_phi + q]);
    vec2 light = pc.params.x * vec2(cos(pc.params.w), sin(pc.params.w));
    if (pc.params.x >= 0.0 && distance(uv, light) < 0.035) colour = vec4(1.0, 0.8, 0.1, 1.0);   // the light
}
