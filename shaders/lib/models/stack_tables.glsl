// models/stack_tables.glsl: how the models read their per-stack tables (kernel_interface.glsl STACK_TABLE_*; the
// sets' layout generated from the model files' `// table:` lines, each set filled by its file's GONIO_MODEL_TABLES
// hook through host/models/stack_tables.cpp): the includer provides float model_stack_table(uint i), element i of
// the buffer (models.comp and render.comp from their StackTables binding, the CPU twin from host/models/model_cpu.cpp).
#ifndef GONIO_MODELS_STACK_TABLES_GLSL
#define GONIO_MODELS_STACK_TABLES_GLSL

// A set of `nodes` values at mu = i / (nodes - 1) from `offset`, at mu by linear interpolation between its nodes
// (mu clamped to [0, 1])
GONIO_INLINE float model_stack_table_at(uint offset, uint nodes, float mu) {
    const float x = clamp(mu, 0.0f, 1.0f) * float(nodes - 1u);
    const uint i = min(uint(x), nodes - 2u);
    const float a = model_stack_table(offset + i), b = model_stack_table(offset + i + 1u);
    return a + (b - a) * (x - float(i));
}

// The model's own parameter i (its file's i-th `parameter:` line; a file reads it as param_NAME): the includer
// provides uint model_parameter_slot(), the model's slot (kernel_interface.glsl STACK_TABLE_PARAMETERS)
GONIO_INLINE float model_parameter(uint i) {
    return model_stack_table(STACK_TABLE_PARAMETERS + model_parameter_slot() * MODEL_MAX_PARAMETERS + i);
}

// The albedo sets (coat-albedo, openpbr-base-albedo, standard-surface-base-albedo, openpbr-separable): an
// interface's directional albedo at COAT_ALBEDO_NODES nodes mu = i / (COAT_ALBEDO_NODES - 1)
const uint COAT_ALBEDO_NODES = 65u;
GONIO_INLINE float coat_albedo_node_mu(uint i) { return float(i) / float(COAT_ALBEDO_NODES - 1u); }

// The two nodes of a tabulated axis an exact index falls between and the weight of the upper one, as the authors'
// lookups take them (Adobe's, Cycles'): clamped to [0, nodes - 1], the upper node min(lower + 1, nodes - 1)
struct TableAxisCell {
    uint lo;
    uint hi;
    float t;
};
GONIO_INLINE TableAxisCell table_axis_cell(float exact_index, uint nodes) {
    const float x = clamp(exact_index, 0.0f, float(nodes - 1u));
    TableAxisCell c;
    c.lo = uint(floor(x));
    c.hi = min(c.lo + 1u, nodes - 1u);
    c.t = x - float(c.lo);
    return c;
}
#endif
