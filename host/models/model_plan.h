// model_plan.h: how a model's terms are integrated over the bins at one incident angle (the graded quadrature, or
// visible-normal lobe grids for delta lobes and lobes float cannot resolve; docs/MODELS.md "Bin integration"), and
// the lobe grids' shapes: what the evaluator (model_evaluator.cpp) dispatches models.comp with.
#pragma once
#include "kernel_interface.glsl"   // MODEL_FLOAT_UNRESOLVED
#include "model_file.h"   // PlanKind
#include "stack.h"
#include "stack_gpu.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

// A lobe whose roughness a model computes below this is a delta: the models evaluate every lobe below
// MODEL_MIN_ALPHA (1e-4) as GGX at MODEL_MIN_ALPHA, the stand-in of a smooth interface, and a roughness this far
// below it is 0 up to float rounding (e.g. a transmitted lobe's variance through index-matched interfaces, with
// tables whose Fresnel 0 is 1e-7). Its whole mass belongs in the bin of the mirror (or straight-through) direction.
constexpr double kModelDeltaAlpha = 5e-5;

// Lobe-grid nodes per side: 2^16 per grid; 2^18 when the mirror direction is within 5 degrees of the normal,
// where the bins are small wedges (1 degree x 2 degrees of phi at the pole) and a narrow lobe spreads over all
// of them (256 there doubled the RMSE of ww-corrected at normal incidence on metallic-paint, measured).
inline uint32_t lobe_grid_nodes(double theta_i_deg) { return theta_i_deg < 5.0 ? 512u : 256u; }
// The lobe grids of a narrow term: the lobe's own (columns x rows) and the wide partner's. The columns are the
// azimuth of the sampled normal about l (sample_ggx_visible_normal: phi = 2 pi u1). At normal incidence that is
// the azimuth of v, and the bins of the first rings are 2-degree wedges that a narrow lobe covers all of: 512
// columns gave each wedge 2 or 3 of them (256: 1 or 2), a 20-40% ripple from bin to bin; 2 n_phi' columns
// (n_phi' = n_phi * ceil(180 / n_phi), two per phi bin, half a column from its edges) give every wedge the same
// share with fewer nodes (360 x 256 and 360 x 128 instead of 512^2 and 256^2 at 1 x 2 degree bins).
struct GridShape {
    uint32_t cols, rows, wide_cols, wide_rows;
};
GridShape lobe_grids(double theta_i_deg, uint32_t n_phi);
constexpr double kWideGrid = 0.5;   // roughness of the wide partner grid (tails)
// A GGX lobe about the mirror direction of l is 2 alpha cos(theta_i) wide in the components of v that the models'
// half vector l + v resolves, and v.x near +-1 is a float with steps of 6e-8: below 2e-5 (333 steps; at 89 degrees
// alpha < 5.7e-4, at 89.9 degrees alpha < 5.7e-3) f, evaluated at float directions, is a staircase at the lobe's own
// scale, which a quadrature in v cannot integrate (at 89.9 degrees a 1e-4 lobe's bins summed 1% off). Such a lobe
// is integrated on visible-normal grids, which draw the half vector itself: f at v = reflect(l, m) weighed by the
// density of m, the lobe grid of the delta lobes plus a wide partner grid for the tails (balance heuristic).
inline const double kFloatUnresolved = MODEL_FLOAT_UNRESOLVED;   // 2e-5, shared with the kernels

// How each term of a model is integrated over the bins for this stack: a delta lobe (roughness 0) on a lobe grid
// of roughness alpha_grid (MODEL_MIN_ALPHA) whose whole mass goes to the bin of the mirror direction; every other
// term by the graded quadrature (alpha_grid = 0), refined towards the mirror direction at the lobe's roughness
// alpha_eff (0: no lobe, a Lambertian term).
struct TermPlan {
    uint32_t term;
    double alpha_grid;
    bool delta;
    double alpha_eff;
    double grid_eta = 0.0;
};

// How a built-in model's terms are planned: its file's `plan:` (model_file.h PlanKind), by code or by id.
PlanKind plan_kind(uint32_t code);
PlanKind plan_kind_of(const std::string& id);   // the same by the base model's id

// The terms of code `model` (ModelInfo::shader_model; a model with a plan) on the stack (as the models read it) at
// theta_deg, side 0 (reflection) or 1 (transmission), with the Belcour tables the device uses (tables: ms.tables,
// else none) and the model's CONVENTION_* bits.
struct ModelStack;
std::vector<TermPlan> plan(size_t model, const ModelStack& ms, double theta_deg, int side, bool tables,
                           uint32_t convention);

// The graded quadrature's lavapipe loop budget: 65535 loop trips per invocation in all (docs/ARCHITECTURE.md);
// a piece pair costs 40 trips of the kernel's own loops (the 4 x 4 and 3 x 3 rules, the walks) plus its 25
// evaluations times the model's loop trips.
// `model`: a code.
uint32_t quadrature_max_rects(size_t model, const Stack& s);
// A model integrated as a black box (a user's, or a built-in with no plan): it may loop over the layers in each
// evaluation, as Belcour's models do, and is budgeted as they are.
uint32_t quadrature_max_rects_black_box(const Stack& s);

// The incident cosine below which Belcour's mean direction is totally reflected inside the stack (0: never): Snell
// carries sin(theta) through the interfaces as sin(theta_0) / (n_1 n_2 ... n_i) (belcour_layer), so interface i
// reflects it totally once sin(theta_0) exceeds the product P_i of the relative indices down to it; the first
// jump from mu = 1 down is at the smallest P_i < 1.
double mu_jump_of(const StackGpu& sg);

}   // namespace gonio
