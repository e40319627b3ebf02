#version 450
// tables.comp: Belcour 2018's FGD and TIR tables for the interfaces of one stack (shaders/lib/models/
// belcour_tables.glsl): one invocation per (interface, alpha node, mu node).
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

#include "compat.glsl"
#include "stack_params.glsl"

layout(std140, set = 0, binding = 0) uniform StackBlock {
    LayerGpu layers[MAX_LAYERS];
    vec4 info;
} u_stack;
layout(std430, set = 0, binding = 1) writeonly buffer Tables { float tables[]; };

float model_table(uint i) { return 0.0f; }   // not read here
#include "models/belcour_tables.glsl"

void main() {
    uint id = gl_GlobalInvocationID.x;
    uint per_layer = TABLE_NMU * TABLE_NALPHA;
    uint layer = id / per_layer;
    if (layer >= uint(u_stack.info.x)) return;
    uint r = id - layer * per_layer;
    uint a = r / TABLE_NMU, c = r - a * TABLE_NMU;
    vec4 e = belcour_table_entry(u_stack.layers[layer], table_node_mu(c), table_node_alpha(a));
    uint f = layer * TABLE_FGD_STRIDE + r * 3u;
    tables[f] = e.x;
    tables[f + 1u] = e.y;
    tables[f + 2u] = e.z;
    tables[TABLE_TIR_OFFSET + layer * per_layer + r] = e.w;
}
