// stack_constants.glsl: the baked stack, the stack's parameters as specialisation constants (GLSL only;
// simulate.comp). Where the walk is specialised and has at most two layers, every parameter it reads is fixed for the
// whole run, so the host bakes them into the pipeline (BAKED_STACK, build_walk_kernel): the compiler folds them into
// the code (alpha^2, eta^2 - k^2, ... computed once), and no uniform load remains in the walk. On lavapipe a uniform
// load is a gather of 8 lanes with a bounds check (Mesa 22.3): 12% less CPU per path on the metal stacks
// (docs/PERFORMANCE.md). Elsewhere (BAKED_STACK false) the walk reads the uniform block u_stack.
// The values are those of walk_stack (StackGpu); ids SPEC_BAKED_* (kernel_interface.glsl).
#ifndef GONIO_STACK_CONSTANTS_GLSL
#define GONIO_STACK_CONSTANTS_GLSL
#define GONIO_BAKED_STACK   // walk.glsl: BAKED_STACK, baked_layer, baked_series, baked_sides

layout(constant_id = SPEC_BAKED_STACK) const bool BAKED_STACK = false;
layout(constant_id = SPEC_BAKED_SIDES) const uint BAKED_SIDES = 2u;          // info.y: histogram sides
// layers[0] and layers[1]: p0 (kind, alpha, eta, 1/eta), tau.xyz, c0.xyz, c1.xyz
layout(constant_id = SPEC_BAKED_LAYERS + 0u) const float L0_P0X = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 1u) const float L0_P0Y = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 2u) const float L0_P0Z = 1.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 3u) const float L0_P0W = 1.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 4u) const float L0_TAUX = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 5u) const float L0_TAUY = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 6u) const float L0_TAUZ = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 7u) const float L0_C0X = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 8u) const float L0_C0Y = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 9u) const float L0_C0Z = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 10u) const float L0_C1X = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 11u) const float L0_C1Y = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 12u) const float L0_C1Z = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 13u) const float L1_P0X = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 14u) const float L1_P0Y = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 15u) const float L1_P0Z = 1.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 16u) const float L1_P0W = 1.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 17u) const float L1_TAUX = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 18u) const float L1_TAUY = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 19u) const float L1_TAUZ = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 20u) const float L1_C0X = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 21u) const float L1_C0Y = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 22u) const float L1_C0Z = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 23u) const float L1_C1X = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 24u) const float L1_C1Y = 0.0f;
layout(constant_id = SPEC_BAKED_LAYERS + 25u) const float L1_C1Z = 0.0f;
// series: gain.xyzw, lost.xyz, emit.xyzw
layout(constant_id = SPEC_BAKED_SERIES + 0u) const float S_GAINX = 0.0f;
layout(constant_id = SPEC_BAKED_SERIES + 1u) const float S_GAINY = 0.0f;
layout(constant_id = SPEC_BAKED_SERIES + 2u) const float S_GAINZ = 0.0f;
layout(constant_id = SPEC_BAKED_SERIES + 3u) const float S_GAINW = 1.0f;
layout(constant_id = SPEC_BAKED_SERIES + 4u) const float S_LOSTX = 0.0f;
layout(constant_id = SPEC_BAKED_SERIES + 5u) const float S_LOSTY = 0.0f;
layout(constant_id = SPEC_BAKED_SERIES + 6u) const float S_LOSTZ = 0.0f;
layout(constant_id = SPEC_BAKED_SERIES + 7u) const float S_EMITX = 1.0f;
layout(constant_id = SPEC_BAKED_SERIES + 8u) const float S_EMITY = 0.0f;
layout(constant_id = SPEC_BAKED_SERIES + 9u) const float S_EMITZ = 1.0f;
layout(constant_id = SPEC_BAKED_SERIES + 10u) const float S_EMITW = 1.0f;

LayerGpu baked_layer(uint k) {
    LayerGpu L;
    if (k == 0u) {
        L.p0 = vec4(L0_P0X, L0_P0Y, L0_P0Z, L0_P0W);
        L.tau = vec4(L0_TAUX, L0_TAUY, L0_TAUZ, 0.0f);
        L.c0 = vec4(L0_C0X, L0_C0Y, L0_C0Z, 0.0f);
        L.c1 = vec4(L0_C1X, L0_C1Y, L0_C1Z, 0.0f);
    } else {
        L.p0 = vec4(L1_P0X, L1_P0Y, L1_P0Z, L1_P0W);
        L.tau = vec4(L1_TAUX, L1_TAUY, L1_TAUZ, 0.0f);
        L.c0 = vec4(L1_C0X, L1_C0Y, L1_C0Z, 0.0f);
        L.c1 = vec4(L1_C1X, L1_C1Y, L1_C1Z, 0.0f);
    }
    return L;
}

SeriesGpu baked_series() {
    SeriesGpu s;
    s.gain = vec4(S_GAINX, S_GAINY, S_GAINZ, S_GAINW);
    s.lost = vec4(S_LOSTX, S_LOSTY, S_LOSTZ, 0.0f);
    s.emit = vec4(S_EMITX, S_EMITY, S_EMITZ, S_EMITW);
    return s;
}
uint baked_sides() { return BAKED_SIDES; }
#endif
