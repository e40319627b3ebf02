// stack_params.glsl: the layer stack as the walk reads it. One layout for the device (std140 uniform
// block) and the CPU twin (the same struct in C++; vec4 members only, so the layouts agree).
#ifndef GONIO_STACK_PARAMS_GLSL
#define GONIO_STACK_PARAMS_GLSL
#include "compat.glsl"

#define MAX_LAYERS 16
// The channels every spectral quantity of a stack, a weight, a bin and an energy entry carries: RGB (vec3). A
// wavelength-band dimension would change this count and what a channel means (docs/ARCHITECTURE.md, "New
// dimensions").
const uint CHANNELS = 3u;
const uint KIND_DIELECTRIC = 0u;
const uint KIND_CONDUCTOR = 1u;
const uint KIND_LAMBERTIAN = 2u;

struct LayerGpu {
    vec4 p0;    // x: kind, y: GGX alpha (0 = smooth), z: dielectric eta = n_below / n_above, w: 1 / eta
    vec4 tau;   // xyz: extinction optical depth of the medium under this interface (0 for the base / substrate)
    vec4 c0;    // conductor: relative eta (n / n_above) per channel; lambertian: albedo; dielectric: the medium's
                // single-scattering albedo (xyz) and Henyey-Greenstein g (w)
    vec4 c1;    // conductor: relative k (k / n_above) per channel (xyz); dielectric: the medium's phase function (x,
                // medium.glsl MEDIUM_PHASE_*; 0: Henyey-Greenstein) and a microflake medium's alpha (y); w: the
                // interface's microsurface (microsurface.glsl MICROSURFACE_*; 0: GGX, height-correlated Smith)
};

// Read a layer through these, never through p0.y and the like: one place says which field holds what.
GONIO_INLINE uint layer_kind(LayerGpu L) { return uint(L.p0.x); }
GONIO_INLINE float layer_alpha(LayerGpu L) { return L.p0.y; }           // GGX alpha of the interface (0 = smooth)
GONIO_INLINE float layer_eta(LayerGpu L) { return L.p0.z; }             // dielectric: n_below / n_above
GONIO_INLINE float layer_inv_eta(LayerGpu L) { return L.p0.w; }         // dielectric: n_above / n_below
GONIO_INLINE vec3 layer_optical_depth(LayerGpu L) { return vec3(L.tau); }   // of the medium under the interface
GONIO_INLINE vec3 layer_conductor_eta(LayerGpu L) { return vec3(L.c0); }    // conductor: n / n_above per channel
GONIO_INLINE vec3 layer_conductor_k(LayerGpu L) { return vec3(L.c1); }      // conductor: k / n_above per channel
GONIO_INLINE uint layer_microsurface(LayerGpu L) { return uint(L.c1.w); }   // rough interface: MICROSURFACE_*
GONIO_INLINE vec3 layer_albedo(LayerGpu L) { return vec3(L.c0); }           // Lambertian base
GONIO_INLINE vec3 layer_scattering_albedo(LayerGpu L) { return vec3(L.c0); }   // dielectric: of the medium under it
GONIO_INLINE float layer_phase_g(LayerGpu L) { return L.c0.w; }               // dielectric: of the medium under it
GONIO_INLINE uint layer_medium_phase(LayerGpu L) { return uint(L.c1.x); }    // dielectric: MEDIUM_PHASE_* (medium.glsl)
GONIO_INLINE float layer_microflake_alpha(LayerGpu L) { return L.c1.y; }     // dielectric: SGGX media's alpha
// Whether a path in the medium under L takes free flights (walk.glsl walk_medium_event): some channel with optical
// depth and single-scattering albedo above 0, or a microflake medium with optical depth above 0 (its extinction
// depends on the direction, which Beer-Lambert's tau / |cos| does not know). The rule of Stack::medium_scatters, which
// decides what pack_stack writes and sets SCATTER_MASK.
GONIO_INLINE bool layer_medium_scatters(LayerGpu L) {
    vec3 t = layer_optical_depth(L), a = layer_scattering_albedo(L);
    bool microflakes = layer_medium_phase(L) != 0u && (t.x > 0.0f || t.y > 0.0f || t.z > 0.0f);
    return layer_kind(L) == KIND_DIELECTRIC &&
           ((t.x > 0.0f && a.x > 0.0f) || (t.y > 0.0f && a.y > 0.0f) || (t.z > 0.0f && a.z > 0.0f) || microflakes);
}

// The Lambertian series (docs/PHYSICS.md, "The Lambertian series"): for a dielectric coat over a Lambertian base,
// what the walk needs to sum every trip between the base and the coat after the first one exactly. Zero gain and
// lost, emit = (1, 0, 1, 1), weight_scale 1 for every other stack (and where the series is off).
struct SeriesGpu {
    vec4 gain;   // xyz: S = 1 / (1 - albedo r), r the energy one trip returns to the base; w: weight_scale, 2^-k: the
                 // staging histogram holds w * weight_scale (weights up to 2^k, bins.glsl)
    vec4 lost;   // xyz: microfacet loss of all trips, per unit of energy leaving the base (l1 S)
    vec4 emit;   // x: sin^2 of the emission cone's half-angle; y: probability of sampling within the cone;
                 // z: weight cos/(pi pdf) of a direction inside the cone, w: outside it
};

// The stack as the walk reads it: simulate.comp's uniform block (std140), a member of simulate_batch.comp's
// BatchStack (std430), the CPU twin's u_stack; vec4 members only, so the layouts agree. The host fills it
// (host/core/stack_gpu.cpp).
struct StackGpu {
    LayerGpu layers[MAX_LAYERS];
    vec4 info;          // read through stack_layer_count, stack_sides, stack_exterior_ior
    SeriesGpu series;   // the Lambertian series (walk_stack fills it)
};
// What StackGpu.info holds: the layer count, the histogram sides (2, or 1 for an opaque stack), and for the model
// kernels the exterior's absolute IOR (the walk reads relative IORs only, not it)
GONIO_INLINE uint stack_layer_count(vec4 info) { return uint(info.x); }
GONIO_INLINE uint stack_sides(vec4 info) { return uint(info.y); }
GONIO_INLINE float stack_exterior_ior(vec4 info) { return info.z; }
#ifdef __cplusplus
static_assert(sizeof(LayerGpu) == 64 && sizeof(SeriesGpu) == 48 && sizeof(StackGpu) == 64 * MAX_LAYERS + 64,
              "std140 and std430 layout");
#endif

// Path outcomes.
const uint OUTCOME_REFLECTED = 0u;
const uint OUTCOME_TRANSMITTED = 1u;
const uint OUTCOME_ENDED = 2u;        // absorbed, lost to a microfacet, or ended by Russian roulette
const uint OUTCOME_TRUNCATED = 3u;    // reached the event cap; its weight is counted as truncated

// Russian roulette starts when the largest channel of the throughput falls below this. 0.3 rather than 0.1:
// paths to a 1% median relative standard error +0.3% to +1.3% on the shipped stacks, CPU per path -10 to -20%
// (docs/PERFORMANCE.md); 0.5 costs 5% more paths on plastic for no net gain, 1.0 85% more.
const float RR_THRESHOLD = 0.3f;
#endif
