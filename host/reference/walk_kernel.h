// walk_kernel.h: the walk kernels' specialisation (simulate.comp, simulate_batch.comp): a stack's WalkSpec, and where
// it is baked, its parameters, as the pipeline's specialisation constants.
#pragma once
#include "compute_kernel.h"
#include "kernel_interface.glsl"
#include "stack_gpu.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace gonio {

// The specialisation constants of the walk kernels (simulate.comp, simulate_batch.comp; ids SPEC_* in
// kernel_interface.glsl), from the stack's WalkSpec: builds `k`'s pipeline. baked (simulate.comp only): the baked
// stack, the stack's parameters compiled into the pipeline as well (stack_constants.glsl; can_bake_stack says where
// they apply). incident_azimuth: the run's phi_i is not 0 (SPEC_INCIDENT_AZIMUTH). invalid_path_for_tests: a path
// whose weight is made NaN, for the tests; fault_for_tests: a FAULT_* of the tests' negative controls.
inline void build_walk_kernel(ComputeKernel& k, vk::raii::Device& dev, const WalkSpec& ws, bool orders,
                              uint32_t paths_per_invocation, bool incident_azimuth, const StackGpu* baked = nullptr,
                              uint32_t invalid_path_for_tests = 0xffffffffu, uint32_t fault_for_tests = 0) {
    struct SpecData {
        VkBool32 specialised;
        uint32_t layer_count, base_kind, rough_mask, absorb_mask, scatter_mask, microsurface_mask, multiple_mask,
            microflake_mask;
        VkBool32 orders;
        uint32_t paths_per_invocation;
        VkBool32 series;
        uint32_t exit_estimates;
        VkBool32 entry_branch;
        VkBool32 baked_stack;
        uint32_t baked_sides;
        float layer[2][BAKED_LAYER_FLOATS];   // p0.xyzw, tau.xyz, c0.xyz, c1.xyz
        float series_values[BAKED_SERIES_FLOATS];   // gain.xyzw, lost.xyz, emit.xyzw
        uint32_t invalid_path;
        uint32_t fault;
        VkBool32 incident_azimuth;
    } sd{};
    sd.specialised = ws.specialised ? VK_TRUE : VK_FALSE;
    sd.layer_count = ws.layer_count;
    sd.base_kind = ws.base_kind;
    sd.rough_mask = ws.rough_mask;
    sd.absorb_mask = ws.absorb_mask;
    sd.scatter_mask = ws.scatter_mask;
    sd.microsurface_mask = ws.microsurface_mask;
    sd.multiple_mask = ws.multiple_mask;
    sd.microflake_mask = ws.microflake_mask;
    sd.orders = orders ? VK_TRUE : VK_FALSE;
    sd.paths_per_invocation = paths_per_invocation;
    sd.series = ws.series ? VK_TRUE : VK_FALSE;
    sd.exit_estimates = ws.exit_estimates;
    sd.entry_branch = ws.entry_branch ? VK_TRUE : VK_FALSE;
    std::vector<vk::SpecializationMapEntry> entries{
        {SPEC_SPECIALISED, offsetof(SpecData, specialised), sizeof(VkBool32)},
        {SPEC_LAYER_COUNT, offsetof(SpecData, layer_count), 4},
        {SPEC_BASE_KIND, offsetof(SpecData, base_kind), 4},
        {SPEC_ROUGH_MASK, offsetof(SpecData, rough_mask), 4},
        {SPEC_ABSORB_MASK, offsetof(SpecData, absorb_mask), 4},
        {SPEC_SCATTER_MASK, offsetof(SpecData, scatter_mask), 4},
        {SPEC_MICROSURFACE_MASK, offsetof(SpecData, microsurface_mask), 4},
        {SPEC_MULTIPLE_MASK, offsetof(SpecData, multiple_mask), 4},
        {SPEC_MICROFLAKE_MASK, offsetof(SpecData, microflake_mask), 4},
        {SPEC_ORDERS, offsetof(SpecData, orders), sizeof(VkBool32)},
        {SPEC_PATHS_PER_INVOCATION, offsetof(SpecData, paths_per_invocation), 4},
        {SPEC_SERIES, offsetof(SpecData, series), sizeof(VkBool32)},
        {SPEC_EXIT_ESTIMATES, offsetof(SpecData, exit_estimates), 4},
        {SPEC_ENTRY_BRANCH, offsetof(SpecData, entry_branch), sizeof(VkBool32)}};
    if (baked) {
        sd.baked_stack = VK_TRUE;
        sd.baked_sides = uint32_t(baked->info.y);
        for (int l = 0; l < 2; ++l) {
            const LayerGpu& L = baked->layers[l];
            const float v[BAKED_LAYER_FLOATS] = {L.p0.x, L.p0.y, L.p0.z, L.p0.w, L.tau.x, L.tau.y, L.tau.z,
                                                 L.c0.x, L.c0.y, L.c0.z, L.c1.x, L.c1.y,  L.c1.z};
            std::copy(v, v + BAKED_LAYER_FLOATS, sd.layer[l]);
        }
        const SeriesGpu& S = baked->series;
        const float v[BAKED_SERIES_FLOATS] = {S.gain.x, S.gain.y, S.gain.z, S.gain.w, S.lost.x, S.lost.y,
                                              S.lost.z, S.emit.x, S.emit.y, S.emit.z, S.emit.w};
        std::copy(v, v + BAKED_SERIES_FLOATS, sd.series_values);
        entries.push_back({SPEC_BAKED_STACK, offsetof(SpecData, baked_stack), sizeof(VkBool32)});
        entries.push_back({SPEC_BAKED_SIDES, offsetof(SpecData, baked_sides), 4});
        for (uint32_t i = 0; i < 2 * BAKED_LAYER_FLOATS; ++i)
            entries.push_back({SPEC_BAKED_LAYERS + i, uint32_t(offsetof(SpecData, layer) + 4 * i), 4});
        for (uint32_t i = 0; i < BAKED_SERIES_FLOATS; ++i)
            entries.push_back({SPEC_BAKED_SERIES + i, uint32_t(offsetof(SpecData, series_values) + 4 * i), 4});
    }
    if (invalid_path_for_tests != 0xffffffffu) {
        sd.invalid_path = invalid_path_for_tests;
        entries.push_back({SPEC_INVALID_PATH_FOR_TESTS, offsetof(SpecData, invalid_path), 4});
    }
    if (incident_azimuth) {
        sd.incident_azimuth = VK_TRUE;
        entries.push_back({SPEC_INCIDENT_AZIMUTH, offsetof(SpecData, incident_azimuth), sizeof(VkBool32)});
    }
    if (fault_for_tests != 0) {
        sd.fault = fault_for_tests;
        entries.push_back({SPEC_FAULT_FOR_TESTS, offsetof(SpecData, fault), 4});
    }
    k.build(dev, entries, &sd, sizeof(sd));
}

}   // namespace gonio
