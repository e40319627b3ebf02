// stack_tables.h: the models' per-stack tables (kernel_interface.glsl STACK_TABLE_*), which the host computes for
// the stack at hand and models.comp, render.comp and the CPU twin read (model_stack_table): the coat's directional
// albedo E_coat(mu) of the albedo-scaling models, and the energy tables production models read (adobe/openpbr-bsdf's,
// Cycles'), recomputed by gonio's quadrature at the nodes their authors tabulate them at.
#pragma once
#include "kernel_interface.glsl"
#include "stack.h"
#include "stack_gpu.h"

#include <cstdint>
#include <vector>

namespace gonio {

// STACK_TABLE_FLOATS floats: the sets named in `sets` (STACK_TABLES_* bits) computed for the stack where it is two
// layers and opaque (the models that read them take no other stack), zeros elsewhere.
std::vector<float> stack_tables(const StackGpu& sg, uint32_t sets);

// The directional albedo E(mu) of the stack's top interface (its reflection alone), at the nodes
// coat_albedo_node_mu(i), i = 0 .. COAT_ALBEDO_NODES - 1: the coat-albedo set alone.
std::vector<float> coat_albedo_table(const StackGpu& sg);

// The production models' tables at their authors' nodes, by gonio's quadrature (models/fgd_quadrature.glsl), for the
// tests to hold against the published values: adobe/openpbr-bsdf's (impl/data/*.h; IOR node i, roughness node j,
// cosine node k of models/builtin/14-openpbr-adobe.glsl) and Cycles' (src/scene/shader.tables; roughness i, mu j,
// z k of models/builtin/13-cycles-principled.glsl).
float adobe_opaque_dielectric_complement(uint32_t i, uint32_t j, uint32_t k);   // OD[i][j][k]
float adobe_opaque_dielectric_average_complement(uint32_t i, uint32_t j);   // ODA[i][j]
float adobe_ideal_metal_complement(uint32_t j, uint32_t k);   // IM[j][k]
float adobe_ideal_metal_average_complement(uint32_t j);   // IMA[j]
float cycles_ggx_e(uint32_t i, uint32_t j);   // ggx_E at roughness node i, mu node j
float cycles_ggx_e_avg(uint32_t i);   // ggx_Eavg
float cycles_schlick_ior_s(uint32_t i, uint32_t j, uint32_t k);   // ggx_gen_schlick_ior_s at (roughness i, mu j, z k)

// interfaced-lambertian's (models/builtin/15-interfaced-lambertian.glsl): the flat interface's internal hemispherical
// reflectance r_i = 1 - (1 - r_e) / eta^2, and its body's mean over visible normals B at the table's node (i, j, k)
// on n_az (midpoint, azimuth) x n_cap (Gauss-Legendre, the cap's height) nodes
float interfaced_internal_reflectance(float eta);
float interfaced_body_node(float eta, float alpha, uint32_t i, uint32_t j, uint32_t k, uint32_t n_az, uint32_t n_cap);

}   // namespace gonio
