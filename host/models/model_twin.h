// model_twin.h: the analytic models' shader code (shaders/lib/models/*.glsl) compiled as C++ through GLM, with
// the constants the kernels share with the host (kernel_interface.glsl). For the files of host/models only.
#pragma once
#include "stack_gpu.h"
#include "kernel_interface.glsl"

// What the models read from their environment: shaders/models.comp provides them from its buffers, the CPU twin
// (model_cpu.cpp) from per-thread pointers set around each evaluation.
float model_stack_table(uint i);   // the per-stack tables (kernel_interface.glsl STACK_TABLE_*)
uint model_layer_count();
LayerGpu model_layer(uint i);
bool model_use_tables();
float model_table(uint i);   // Belcour's FGD / TIR tables (models/belcour_tables.glsl layout)
uint model_convention();   // CONVENTION_* bits
uint model_parameter_slot();   // the model's slot of parameters (kernel_interface.glsl STACK_TABLE_PARAMETERS)

// What a file's GONIO_MODEL_TABLES hook (models/all.glsl: the per-stack table sets it declares) builds its sets with,
// on the host only: host/models/stack_tables.cpp provides them around gonio's one quadrature of an interface's albedo
// (models/fgd_quadrature.glsl)
#include "models/fgd_quadrature.glsl"
void model_stack_table_store(uint i, float value);   // element i of the buffer being filled
// The shapes the sets are computed for (the models that read them take no other): two layers with an opaque base;
// three, a dielectric coat over a dielectric interface over a Lambertian
constexpr uint TABLE_SHAPE_OTHER = 0u, TABLE_SHAPE_TWO_LAYER_OPAQUE = 1u, TABLE_SHAPE_THREE_LAYER_DIELECTRIC_BASE = 2u;
uint table_stack_shape(const StackGpu& s);
// The quadrature's sums (fgd_quadrature.glsl FgdSums) for a dielectric interface of relative IOR eta and GGX alpha at
// mu, masking and Fresnel g_mode (FGD_*); below the quadrature's smallest roughness (MODEL_MIN_ALPHA) the smooth
// interface's: its Fresnel at mu, the whole lobe
FgdSums table_interface_sums(float eta, float alpha, float mu, uint g_mode);
// 2 int_0^1 e(mu) mu dmu, the cosine-weighted average of a directional albedo e (24-point Gauss-Legendre in mu), of
// e = the smooth interface's Fresnel F(mu, eta), or table_interface_sums' fgd or lobe
constexpr uint TABLE_MEAN_FRESNEL = 0u, TABLE_MEAN_FGD = 1u, TABLE_MEAN_LOBE = 2u;
double table_cosine_average(uint e, float eta, float alpha, uint g_mode);
// A dielectric interface's directional albedo (its reflection alone, table_interface_sums' fgd at alpha, at least
// MODEL_MIN_ALPHA) at the albedo sets' COAT_ALBEDO_NODES nodes, into elements offset.., clamped to 1 (1 - E weighs
// what lies below)
void table_store_interface_albedo(uint offset, float eta, float alpha, uint g_mode);
// A GGX lobe's directional albedo with F = 1 (table_interface_sums' lobe at alpha, at least MODEL_MIN_ALPHA; 1 below
// it), at the same nodes, into elements offset..: the E_ss of an energy compensation 1 + F_avg (1 - E_ss) / E_ss
void table_store_lobe_albedo(uint offset, float alpha, uint g_mode);
// Node j of the n-point Gauss-Legendre rule on [0, 1], and its weight
double table_gauss_legendre_node(uint n, uint j);
double table_gauss_legendre_weight(uint n, uint j);

#include "models/all.glsl"

namespace gonio {
// A production or sheen model's artist parameters (its file's GONIO_MODEL_ARTIST_PARAMETERS hook, eval_model_artist_
// parameters) with the stack `sg` as model_layer() reads it (the sheen models read their fibres' alpha and colour
// there): model_cpu.cpp sets the twin's environment around the hook. False if the file defines no hook
bool eval_model_artist_parameters_on(uint32_t code, const StackGpu& sg, CoatParams p, vec3 diffuse, ArtistValues& a);
}   // namespace gonio
