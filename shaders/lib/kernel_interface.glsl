// kernel_interface.glsl: everything the host and the compute kernels both know, compiled as GLSL by the kernels
// and as C++ (through compat.glsl and GLM) by the host: push-constant structs, workgroup sizes, fixed-point scales,
// table sizes, node rules. A value the two sides share is written here once, never mirrored by hand.
// A kernel declares its push constants as a block holding one of these structs:
//     layout(push_constant) uniform PushBlock { WalkPush pc; };
// and the host fills the same struct (static_assert on its size beside the struct).
#ifndef GONIO_KERNEL_INTERFACE_GLSL
#define GONIO_KERNEL_INTERFACE_GLSL
#include "compat.glsl"

// ---- the walk kernels (simulate.comp, simulate_batch.comp, fold.comp) ----
#include "stack_params.glsl"   // BatchStack's StackGpu

// The workgroup shapes the kernels declare and the hosts dispatch by (host/reference/walk_runner.h,
// host/gpu/fold_kernel.cpp).
const uint WALK_LOCAL_SIZE = 64u;       // invocations per workgroup of simulate.comp and simulate_batch.comp
const uint FOLD_LOCAL_SIZE = 64u;       // of fold.comp
const uint FOLD_PER_INVOCATION = 16u;   // staging elements each fold.comp invocation adds

// The descriptor bindings of set 0, which the kernels declare (layout(binding = ...)) and the hosts fill (a
// ComputeKernel's descriptor types and buffers are indexed by binding).
const uint WALK_BINDING_STACK = 0u;     // simulate.comp: uniform StackBlock; simulate_batch.comp: storage Stacks
const uint WALK_BINDING_STAGING = 1u;   // the staging histogram (simulate_path.glsl)
const uint WALK_BINDING_ENERGY = 2u;    // the energy book
const uint WALK_BINDING_ANGLES = 3u;    // simulate.comp: storage Angles, the incident angles of a dispatch (WalkAngle)
const uint WALK_BINDINGS = 4u;
const uint FOLD_BINDING_STAGING = 0u;   // fold.comp: the staging histogram it empties
const uint FOLD_BINDING_TOTALS = 1u;    // and the 64-bit totals it adds to
const uint FOLD_BINDINGS = 2u;

// The walk kernels' specialisation constant ids (simulate_head.glsl, stack_constants.glsl), which build_walk_kernel
// (host/gpu/compute_kernel.h) sets.
const uint SPEC_SPECIALISED = 0u;
const uint SPEC_LAYER_COUNT = 1u;
const uint SPEC_BASE_KIND = 2u;
const uint SPEC_ROUGH_MASK = 3u;
const uint SPEC_ABSORB_MASK = 4u;
const uint SPEC_ORDERS = 5u;
const uint SPEC_PATHS_PER_INVOCATION = 6u;
const uint SPEC_SERIES = 7u;
const uint SPEC_BAKED_STACK = 8u;              // simulate.comp: the baked stack
const uint SPEC_BAKED_SIDES = 9u;
const uint SPEC_BAKED_LAYERS = 10u;            // layers[0], layers[1]: p0.xyzw, tau.xyz, c0.xyz, c1.xyz each
const uint BAKED_LAYER_FLOATS = 13u;
const uint SPEC_BAKED_SERIES = 36u;            // series: gain.xyzw, lost.xyz, emit.xyzw
const uint BAKED_SERIES_FLOATS = 11u;
const uint SPEC_INVALID_PATH_FOR_TESTS = 47u;
const uint SPEC_SCATTER_MASK = 48u;
const uint SPEC_EXIT_ESTIMATES = 49u;
const uint MAX_EXIT_ESTIMATES = 6u;            // the most fresh exit estimates trace_book.glsl holds per path
const uint SPEC_ENTRY_BRANCH = 50u;
// For the negative controls of the tests only (tests/test_reference.cpp): a fault the booking estimators' checks must
// catch; the default, none, folds away.
const uint SPEC_FAULT_FOR_TESTS = 51u;
const uint FAULT_NONE = 0u;
const uint FAULT_ENTRY_BRANCH_HEAVY = 1u;   // the entry's reflected branch booked 2% heavy (a bias)
const uint FAULT_BOOKINGS_SQUARED_APART = 2u;   // a path's bookings in one bin squared apart (a dishonest se)
// simulate.comp, simulate_batch.comp: whether the run has an incident azimuth other than 0 (SimOptions::phi_i_deg).
// Without one the kernels build the plane's direction (bins.glsl incident_travel_in_plane), whose y the compiler sees
// is 0, and which it compiles to the code, and the bits, of a walk that has no azimuth at all
const uint SPEC_INCIDENT_AZIMUTH = 52u;
// The interfaces' microsurfaces (WalkSpec::microsurface_mask; walk.glsl walk_microsurface): 0 on every stack that
// keeps GGX with height-correlated Smith, whose walk then carries no other microsurface's code
const uint SPEC_MICROSURFACE_MASK = 53u;
// The interfaces where light walks on the microsurface (WalkSpec::multiple_mask; walk.glsl walk_multiple): 0 on every
// stack whose microfacets scatter once, whose walk then carries none of its code
const uint SPEC_MULTIPLE_MASK = 54u;
// The media of microflakes (WalkSpec::microflake_mask; walk.glsl walk_microflakes_any): 0 on every stack whose media
// are Henyey-Greenstein's, whose walk then carries none of the SGGX code
const uint SPEC_MICROFLAKE_MASK = 55u;

// The push constants of simulate.comp and simulate_batch.comp: the histogram's grid, the event cap, and for
// simulate_batch.comp one dispatch's paths and incident direction (simulate.comp reads those per angle, WalkAngle).
struct WalkPush {
    uint path_base_lo;      // first path index of this dispatch (64-bit)
    uint path_base_hi;
    uint path_count;        // paths in this dispatch (per configuration)
    uint seed_mix0;         // simulate.comp: rng_seed_mix(seed, stream), computed once by the host
    uint seed_mix1;
    uint stream;            // incident-angle index (simulate_batch.comp mixes it with each configuration's seed)
    uint max_events;
    uint n_theta;
    uint n_phi;
    float sin_ti;
    float cos_ti;
    float sin_pi;           // the incident azimuth phi_i (bins.glsl incident_travel)
    float cos_pi;
    float inv_dtheta;       // 1 / bin width in radians
    float inv_dphi;
    uint staging_stride;    // staging values per configuration (simulate_batch.comp) or angle slot (simulate.comp)
};

// One incident angle of a simulate.comp dispatch (std430, the storage buffer Angles): workgroup row y traces entry y,
// so one dispatch covers many angles of a stack, each with its own paths, random streams and histograms
// (host/reference/reference_gpu.cpp). The same fields as WalkPush's for one angle, so the same paths and bits.
struct WalkAngle {
    uint path_base_lo;      // first path index of this angle in the dispatch (64-bit)
    uint path_base_hi;
    uint path_count;        // this angle's paths in the dispatch
    uint slot;              // its histograms: staging from slot x staging_stride, energy book from slot x ENERGY_ENTRIES
    uint seed_mix0;         // rng_seed_mix(seed, angle index)
    uint seed_mix1;
    float sin_ti;
    float cos_ti;
    float sin_pi;
    float cos_pi;
};

// One configuration of simulate_batch.comp (std430, the storage buffer Stacks): its stack as the walk reads it and
// its own seed and state.
struct BatchStack {
    StackGpu stack;                 // stack_params.glsl; series.gain.w the same for every stack of a batch
    uvec4 extra;                    // x: the configuration's seed; y: 1 while it still takes paths (--rse)
};

// fold.comp's push constants. count: staging elements (bins x 3 channels). shift: the staging holds weights times
// 2^-shift (a walk whose weights exceed 1, the Lambertian series): the totals stay in units of 2^-12.
struct FoldPush {
    uint count;
    uint shift;
};

#ifdef __cplusplus
static_assert(SPEC_BAKED_LAYERS + 2u * BAKED_LAYER_FLOATS == SPEC_BAKED_SERIES &&
              SPEC_BAKED_SERIES + BAKED_SERIES_FLOATS <= SPEC_INVALID_PATH_FOR_TESTS, "specialisation constant ids");
static_assert(sizeof(WalkPush) == 64 && sizeof(FoldPush) == 8, "push-constant layout (std430, scalars only)");
static_assert(sizeof(WalkAngle) == 40, "std430 layout (scalars only)");
static_assert(sizeof(BatchStack) == 64 * MAX_LAYERS + 80, "std430 layout (vec4 members only)");
#endif

// ---- the model kernels (models.comp, belcour_tables.comp, ...) ----
// models.comp (host/models/model_evaluator.cpp) and tables.comp (host/models/belcour_tables_host.cpp).

// The descriptor bindings of models.comp and tables.comp (set 0).
const uint MODEL_BINDING_STACK = 0u;            // uniform StackBlock (both kernels)
const uint MODEL_BINDING_QUADRATURE = 1u;       // models.comp: the quadrature's outputs per bin
const uint MODEL_BINDING_LOBE_SUMS = 2u;        // the lobe grids' 64-bit sums
const uint MODEL_BINDING_STACK_TABLES = 3u;     // the models' per-stack tables (STACK_TABLE_*)
const uint MODEL_BINDING_BELCOUR_TABLES = 4u;   // FGD and TIR tables
const uint MODEL_BINDING_BELCOUR_LOBES = 5u;    // KERNEL 2's output
const uint MODEL_BINDINGS = 6u;
const uint TABLES_BINDING_STACK = 0u;           // tables.comp: uniform StackBlock
const uint TABLES_BINDING_OUT = 1u;             // the tables it writes
const uint TABLES_BINDINGS = 2u;

// models.comp's specialisation constants: which kernel, which model's code, which conventions (CONVENTION_* bits)
const uint MODEL_SPEC_KERNEL = 0u;
const uint MODEL_SPEC_MODEL = 1u;
const uint MODEL_SPEC_CONVENTION = 2u;
// Whether the bins are those of an incident azimuth other than 0 (ModelGrid::phi_i_deg; ModelPush sin_pi ... phi_rest).
// Without one the kernels integrate in the plane's frame only, the code and the bits they have always had
const uint MODEL_SPEC_INCIDENT_AZIMUTH = 3u;

// models.comp's kernels (specialisation constant KERNEL, id MODEL_SPEC_KERNEL).
const uint MODEL_KERNEL_QUADRATURE = 0u;   // graded quadrature, one invocation per bin
const uint MODEL_KERNEL_LOBE_GRID = 1u;    // visible-normal lobe grids
const uint MODEL_KERNEL_LOBES = 2u;        // Belcour's and tm21's lobes, once per dispatch
const uint MODEL_KERNEL_POINTS = 3u;       // a user's model at given direction pairs (its reciprocity)
// Invocations per workgroup of models.comp and tables.comp.
const uint MODEL_GROUP_SIZE = 64u;
// models.comp's graded quadrature, its outputs per bin (std430, the storage buffer Quadrature; float members only, so
// that host and kernel agree on the layout)
struct QuadBin {
    float f[CHANNELS];     // the bin average of f per channel (1/sr)
    float nodes;       // the nodes evaluated; -1: lavapipe's loop limiter cut the quadrature short
    float err[CHANNELS];   // its error estimate: |4 x 4 rule - 3 x 3 rule| over the pieces
    float bad;         // nodes where the model returned NaN, an infinity or a negative value
    float hint_flags;  // a user's model_lobes: QUAD_HINTS_UNUSABLE (an unusable lobe), QUAD_HINTS_UNRESOLVED (a lobe
                       // narrower than MODEL_FLOAT_UNRESOLVED), added
};
const uint QUAD_HINTS_UNUSABLE = 1u;
const uint QUAD_HINTS_UNRESOLVED = 2u;
// A GGX lobe is 2 alpha cos(theta) wide in the components of v about its peak at theta, and v.x near +-1 is a float
// with steps of 6e-8: below this width f at float directions is a staircase at the lobe's own scale, which a
// quadrature in v cannot integrate (host/models/model_plan.h kFloatUnresolved, the same value)
const float MODEL_FLOAT_UNRESOLVED = 2e-5f;
// The most lobes a user's model_lobes gives (models/user_model.glsl GONIO_MAX_LOBES)
const uint GONIO_MAX_HINTS = 8u;
const uint LOBE_SUMS_PER_BIN = CHANNELS;
// models.comp KERNEL 1: lobe-grid nodes per invocation.
const uint LOBE_GRID_NODES_PER_INVOCATION = 16u;
// The lobe grid's 64-bit fixed point: a node adds round(w * LOBE_SCALE) to its bin, 2^59. The lobe grid only carries
// delta lobes, whose bin integrals are at most a model's albedo (< 2, measured 1.9 for elek10), so sums stay below
// 2^63 while a delta of 1e-10 of the light keeps 4e-4 relative resolution over 65536 nodes (at 2^-40 such masses
// rounded to 0).
const float LOBE_SCALE = 576460752303423488.0f;

// The models' per-stack tables (host/models/stack_tables.cpp): one buffer of STACK_TABLE_FLOATS floats, computed by
// the host for the stack at hand, which models.comp and render.comp bind and the CPU twin reads alike
// (model_stack_table(i)). First the models' own parameters (a model file's `parameter:` lines, docs/MODELS.md "A
// model's own parameters"): MODEL_MAX_PARAMETERS values per slot, in the header's order; a built-in model's slot is
// its code, the k-th model file's (--model, a sweep's models = [...]) MODEL_USER_PARAMETER_SLOT0 + k; the kernels'
// MODEL specialisation constant is the slot (models/stack_tables.glsl model_parameter).
const uint MODEL_MAX_PARAMETERS = 8u;
const uint MODEL_USER_PARAMETER_SLOT0 = 32u;
const uint MODEL_PARAMETER_SLOTS = 64u;
const uint STACK_TABLE_PARAMETERS = 0u;
// Then, from STACK_TABLE_SETS, the table sets the built-in model files declare (a file's `// table: NAME FLOATS`
// line; the layout, STACK_TABLES_NAME bits and STACK_TABLE_NAME offsets, is generated into builtin_models.glsl by
// cmake/builtin_models.cmake, and the file's GONIO_MODEL_TABLES hook fills its sets on the host). A built-in model's
// `tables:` header line names the sets it reads; a set is computed where a model that reads it runs, zeros elsewhere.
// STACK_TABLE_FLOATS is the buffer's capacity (the generated layout asserts that its sets fit).
const uint STACK_TABLE_SETS = STACK_TABLE_PARAMETERS + MODEL_PARAMETER_SLOTS * MODEL_MAX_PARAMETERS;
const uint STACK_TABLE_FLOATS = 24576u;

// Belcour's FGD and TIR tables (models/belcour_tables.glsl): TABLE_NMU nodes mu = (c / (N - 1))^2 (finer towards
// grazing, where FGD is steep) and TABLE_NALPHA nodes alpha = (a / (N - 1))^2 (finer at low roughness).
const uint TABLE_NMU = 32u;
const uint TABLE_NALPHA = 32u;
GONIO_INLINE float table_node_mu(uint c) {
    float x = float(c) / float(TABLE_NMU - 1u);
    return x * x;
}
GONIO_INLINE float table_node_alpha(uint a) {
    float x = float(a) / float(TABLE_NALPHA - 1u);
    return x * x;
}
// Belcour's and tm21's lobes, computed by models.comp KERNEL 2 (models/belcour18.glsl): at one node (mu = cos
// theta_i), or for the symmetric variant at BELCOUR_MU_NODES nodes mu = (i / (N - 1))^2 of mu = |h.l|.
const uint BELCOUR_MU_NODES = 256u;
GONIO_INLINE float belcour_mu_node(uint i) {
    float x = float(i) / float(BELCOUR_MU_NODES - 1u);
    return x * x;
}

// models.comp's push constants (kernel: layout(push_constant) uniform PushBlock { ModelPush pc; }).
struct ModelPush {
    uint terms;          // which terms this dispatch integrates (TERM_TOP, TERM_BASE)
    uint n_theta;
    uint n_phi;
    float dtheta;        // radians
    float dphi;
    float sin_ti;
    float cos_ti;
    uint grid;           // lobe-grid columns (u1: the azimuth of the normal about l)
    float alpha_grid;    // roughness of the visible-normal grid
    uint delta;          // 1: the lobe is a delta (roughness 0): its mass all goes to the mirror direction's bin
    float alpha_partner; // the other grid of the pair (balance heuristic), 0: none
    uint side;           // 0: reflection (v.z > 0), 1: transmission (v.z < 0; lobes are mirrored through z = 0)
    uint use_tables;     // Belcour's models: 1: FGD and TIR tables, 0: Fresnel at the mean cosine, no TIR
    uint partner_nodes;  // nodes of the partner grid (balance heuristic with sample counts)
    float grid_eta;      // > 0: a lobe at Snell-refracted directions: the grid is drawn about the mirror direction of
                         // l refracted into a coat of this relative IOR, and its directions are refracted out
    uint grid_rows;      // lobe-grid rows (u2: the polar angle)
    // KERNEL 0's graded quadrature (quad_piece_step): the narrowest lobe's width in theta at the peak (2 alpha, 0:
    // no peak), its roughness for the width across the plane of incidence (0: none, e.g. at normal incidence),
    // the width of the masking's fall at the horizon (0: none), a critical angle (0: none), and the most piece
    // pairs per bin (the loop limiter: 16 nodes each, times the model's own loop trips per evaluation)
    float w_theta;
    float a_phi;
    float w_horizon;
    float theta_break;
    uint max_rects;
    float cos_kink;      // > 0: l.h below which the top interface totally reflects (a denser exterior)
    float mu_jump;       // > 0: Belcour's lobes jump at this incident cosine (the mean direction is totally
                         // reflected in the stack below it)
    // >= 1: pieces next to an attractor are this many times shorter than its width. A lobe about the mirror direction
    // is 2 alpha cos(theta_i) wide in the components of v that the models' half vector l + v resolves, and v.x near
    // +-1 is a float with steps of 6e-8: at 89 degrees a 1e-4 lobe spans 58 of them, so each node's direction is off
    // by up to 1.7% of the lobe's width, an error that averages out over the nodes (0.4% in a bin with 16 nodes on
    // the peak)
    float refine;
    // >= 1: pieces at most 1/split of the bin's side (a black-box model refined where its nodes disagreed)
    uint split;
    uint bin_first;   // KERNEL 0: invocation i integrates bin bin_first + i (a refinement's blocks of bins)
    // The incident azimuth phi_i (MODEL_SPEC_INCIDENT_AZIMUTH): the kernels integrate in the incident frame, where l
    // is in the plane xz, and turn l and v by phi_i before the model sees them. phi_i = phi_shift dphi + phi_rest,
    // phi_rest in [-dphi / 2, dphi / 2): bin j of the surface's frame is bin j - phi_shift of the incident frame
    // moved by -phi_rest (at a multiple of dphi, the plane's bin exactly)
    float sin_pi;
    float cos_pi;
    uint phi_shift;
    float phi_rest;   // radians
};
#ifdef __cplusplus
static_assert(sizeof(QuadBin) == 9 * 4, "QuadBin: std430 floats");
static_assert(sizeof(ModelPush) == 30 * 4 && sizeof(ModelPush) <= 128, "ModelPush: std430 scalars, within 128 bytes");
#endif

#endif
