#version 450
// hemisphere.vert: a rectangle (two triangles) from the push constants; uv in [-1, 1]^2, +y up.
layout(push_constant) uniform Push {
    vec4 rect;          // x0, y0, x1, y1 in normalised device coordinates (y down)
    vec4 params;        // see hemisphere.frag
    uvec4 offsets;
    uvec4 unused;
} pc;

layout(location = 0) out vec2 uv;

void main() {
    const vec2 corners[6] = vec2[6](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
    vec2 c = corners[gl_VertexIndex];
    gl_Position = vec4(mix(pc.rect.xy, pc.rect.zw, c), 0.0, 1.0);
    uv = vec2(2.0 * c.x - 1.0, 1.0 - 2.0 * c.y);
}
