#version 450
// tables.comp: Belcour 2018's FGD and TIR tables for the interfaces of one stack (shaders/lib/models/
// belcour_tables.glsl): one invocation per (table set, interface, alpha node, mu node); set 0 with separable Smith G,
// set 1 with height-correlated G2, both computed once per stack.
#extension GL_GOOGLE_include_directive : require

#include "compat.glsl"
#include "kernel_interface.glsl"
#include "stack_params.glsl"

layout(local_size_x = MODEL_GROUP_SIZE) in;

layout(std140, set = 0, binding = TABLES_BINDING_STACK) uniform StackBlock { StackGpu u_stack; };   // stack_params.glsl
layout(std430, set = 0, binding = TABLES_BINDING_OUT) writeonly buffer Tables { float tables[]; };

float model_table(uint i) { return 0.0f; }   // not read here
uint model_convention() { return 0u; }        // not read here
#include "models/belcour_tables.glsl"

void main() {
    uint per_layer = TABLE_NMU * TABLE_NALPHA;
    uint per_set = stack_layer_count(u_stack.info) * per_layer;
    uint set = gl_GlobalInvocationID.x / per_set;
    if (set >= TABLE_SETS) return;
    uint id = gl_GlobalInvocationID.x - set * per_set;
    uint layer = id / per_layer;
    uint r = id - layer * per_layer;
    uint a = r / TABLE_NMU, c = r - a * TABLE_NMU;
    vec4 e = belcour_table_entry(u_stack.layers[layer], table_node_mu(c), table_node_alpha(a), set == 1u);
    uint f = set * TABLE_SET_FLOATS + layer * TABLE_FGD_STRIDE + r * 3u;
    tables[f] = e.x;
    tables[f + 1u] = e.y;
    tables[f + 2u] = e.z;
    tables[set * TABLE_SET_FLOATS + TABLE_TIR_OFFSET + layer * per_layer + r] = e.w;
}
