#include "models.h"
#include "compute_kernel.h"
#include "stack_gpu.h"

// What the models read from their environment (shaders/models.comp provides the same from its buffers):
// the albedo-scaling model its coat's directional albedo E_coat(mu) (coat_albedo_table below), Belcour's the
// whole stack and the FGD / TIR tables. Here through these per-thread pointers.
static thread_local const float* g_coat_albedo = nullptr;
static thread_local const gonio::StackGpu* g_stack = nullptr;
static thread_local const float* g_tables = nullptr;
static thread_local bool g_use_tables = true;
static thread_local uint32_t g_convention = 0;
inline float model_coat_albedo(float mu) {
    float x = std::clamp(mu, 0.0f, 1.0f) * 64.0f;
    unsigned i = std::min(unsigned(x), 63u);
    return g_coat_albedo[i] + (g_coat_albedo[i + 1] - g_coat_albedo[i]) * (x - float(i));
}
inline uint model_layer_count() { return uint(g_stack->info.x); }
inline LayerGpu model_layer(uint i) { return g_stack->layers[i]; }
inline bool model_use_tables() { return g_use_tables; }
inline float model_table(uint i) { return g_tables ? g_tables[i] : 0.0f; }
inline uint model_convention() { return g_convention; }

#include "models/all.glsl"
static_assert(gonio::MODEL_CONVENTION_G2 == CONVENTION_G2 && gonio::MODEL_CONVENTION_TIR_BELOW_MEDIA == CONVENTION_TIR_BELOW_MEDIA);
#include "models_0_spv.h"
#include "models_1_spv.h"
#include "models_2_spv.h"
#include "models_3_spv.h"
#include "models_4_spv.h"
#include "models_5_spv.h"
#include "models_6_spv.h"
#include "models_7_spv.h"
#include "tables_spv.h"

#include <cstdlib>
#include <filesystem>
#include <atomic>
#include <future>
#include <set>
#include <fstream>
#include <map>
#include <memory>
#include <unistd.h>
#include <mutex>
#include <thread>

#include <algorithm>
#include <span>

#include <chrono>
#include <cmath>
#include <cstring>

namespace gonio {

namespace {

struct Push {
    uint32_t model, terms, n_theta, n_phi;
    float dtheta, dphi, sin_ti, cos_ti;
    uint32_t grid;
    float alpha_grid;
    uint32_t delta;
    float alpha_partner;
    uint32_t side, use_tables;
    uint32_t partner_nodes;  // nodes of the partner grid
    float grid_eta;      // > 0: the lobe grid is drawn inside a coat of this relative IOR and refracted out
    uint32_t grid_rows;  // lobe-grid rows (grid: its columns, the azimuth about l)
    // the graded quadrature (models.comp, KERNEL 0)
    float w_theta;       // the narrowest lobe's width in theta at the peak, 2 alpha (0: no lobe)
    float a_phi;         // its roughness, for its width across the plane of incidence (0: none)
    float w_horizon;     // width of the masking's fall at the horizon, alpha (0: none)
    float theta_break;   // a critical angle of v (0: none)
    uint32_t max_rects;  // piece pairs per bin at most (lavapipe's loop limiter)
    float cos_kink;      // > 0: l.h below which the top interface totally reflects (a denser exterior)
    float mu_jump;       // > 0: Belcour's lobes jump at this incident cosine (mu_jump_of)
    float refine;        // >= 1: pieces next to the peak this many times shorter than the lobe (float resolution)
};
static_assert(sizeof(Push) <= 128, "push constants");

// models.comp, one SPIR-V module per model (CMakeLists.txt: GONIO_MODEL_ONLY), in registry order
struct ModelSpv { const uint32_t* code; size_t bytes; };
const ModelSpv kModelSpv[] = {{models_0_spv, sizeof(models_0_spv)}, {models_1_spv, sizeof(models_1_spv)},
                              {models_2_spv, sizeof(models_2_spv)}, {models_3_spv, sizeof(models_3_spv)},
                              {models_4_spv, sizeof(models_4_spv)}, {models_5_spv, sizeof(models_5_spv)},
                              {models_6_spv, sizeof(models_6_spv)}, {models_7_spv, sizeof(models_7_spv)}};

// Lobe-grid nodes per side: 2^16 per grid; 2^18 when the mirror direction is within 5 degrees of the normal,
// where the bins are small wedges (1 degree x 2 degrees of phi at the pole) and a narrow lobe spreads over all
// of them (256 there doubled the RMSE of ww-corrected at normal incidence on metallic-paint, measured).
uint32_t lobe_grid_nodes(double theta_i_deg) { return theta_i_deg < 5.0 ? 512u : 256u; }
// The lobe grids of a narrow term: the lobe's own (columns x rows) and the wide partner's. The columns are the
// azimuth of the sampled normal about l (sample_ggx_visible_normal: phi = 2 pi u1). At normal incidence that is
// the azimuth of v, and the bins of the first rings are 2-degree wedges that a narrow lobe covers all of: 512
// columns gave each wedge 2 or 3 of them (256: 1 or 2), a 20-40% ripple from bin to bin; 2 n_phi' columns
// (n_phi' = n_phi * ceil(180 / n_phi), two per phi bin, half a column from its edges) give every wedge the same
// share with fewer nodes (360 x 256 and 360 x 128 instead of 512^2 and 256^2 at 1 x 2 degree bins).
struct GridShape { uint32_t cols, rows, wide_cols, wide_rows; };
GridShape lobe_grids(double theta_i_deg, uint32_t n_phi) {
    if (theta_i_deg == 0.0) {
        uint32_t cols = 2 * n_phi * uint32_t(std::ceil(180.0 / n_phi));
        return {cols, 256u, cols, 128u};
    }
    uint32_t g = lobe_grid_nodes(theta_i_deg);
    return {g, g, g / 2, g / 2};
}
constexpr double kWideGrid = 0.5;             // roughness of the wide partner grid (tails)
// A GGX lobe about the mirror direction of l is 2 alpha cos(theta_i) wide in the components of v that the models'
// half vector l + v resolves, and v.x near +-1 is a float with steps of 6e-8: below 2e-5 (333 steps; at 89 degrees
// alpha < 5.7e-4, at 89.9 degrees alpha < 5.7e-3) f, evaluated at float directions, is a staircase at the lobe's own
// scale, which a quadrature in v cannot integrate (at 89.9 degrees a 1e-4 lobe's bins summed 1% off). Such a lobe
// is integrated on visible-normal grids, which draw the half vector itself: f at v = reflect(l, m) weighed by the
// density of m, the lobe grid of the delta lobes plus a wide partner grid for the tails (balance heuristic).
constexpr double kFloatUnresolved = 2e-5;
constexpr double kLobeScale = 576460752303423488.0;   // 2^59, LOBE_SCALE in models.comp

// How each term of a model is integrated over the bins for this stack: a delta lobe (roughness 0) on a lobe grid
// of roughness alpha_grid (MODEL_MIN_ALPHA) whose whole mass goes to the bin of the mirror direction; every other
// term by the graded quadrature (alpha_grid = 0), refined towards the mirror direction at the lobe's roughness
// alpha_eff (0: no lobe, a Lambertian term).
struct TermPlan { uint32_t term; double alpha_grid; bool delta; double alpha_eff; double grid_eta = 0.0; };

// The graded quadrature's lavapipe loop budget: 65535 loop trips per invocation in all (docs/ARCHITECTURE.md);
// a piece pair costs 40 trips of the kernel's own loops (the 4 x 4 and 3 x 3 rules, the walks) plus its 25
// evaluations times the model's loop trips.
uint32_t quadrature_max_rects(size_t model, const Stack& s) {
    const bool lobes = model >= MODEL_BELCOUR18_FORWARD;   // Belcour's and tm21 loop over the stack's lobes
    const uint32_t trips = lobes ? uint32_t(s.layers.size()) + 1 : 1;
    return 60000u / (40u + 25u * trips);
}

// ---- the on-disk cache of Belcour tables -------------------------------------------------------------------
// $GONIO_CACHE_DIR, else $XDG_CACHE_HOME/gonio, else $HOME/.cache/gonio; GONIO_NO_CACHE=1 turns it off (the
// tests do). A file holds one stack's tables, named by a hash of what they depend on: the interfaces' (kind,
// eta, k) and the SPIR-V of the shader that computes them, so any change to the table code misses the cache.
// The file repeats the key, which is checked on reading; a file that does not match is ignored and replaced.
std::string table_cache_dir() {
    const char* off = std::getenv("GONIO_NO_CACHE");
    if (off && *off && std::string(off) != "0") return "";
    if (const char* d = std::getenv("GONIO_CACHE_DIR"); d && *d) return d;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/gonio";
    if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/gonio";
    return "";
}
uint64_t fnv1a(const void* data, size_t n, uint64_t h = 1469598103934665603ull) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}
std::string table_cache_file(const std::string& key) {
    std::string dir = table_cache_dir();
    if (dir.empty()) return "";
    uint64_t h = fnv1a(tables_spv, sizeof(tables_spv));
    h = fnv1a(key.data(), key.size(), h);
    char name[64];
    std::snprintf(name, sizeof name, "/belcour-tables-%016llx.bin", (unsigned long long)h);
    return dir + name;
}
const char kTableMagic[8] = {'G', 'O', 'N', 'I', 'O', 'T', 'B', '1'};
bool load_cached_tables(const std::string& key, std::vector<float>& out) {
    std::string path = table_cache_file(key);
    if (path.empty()) return false;
    std::ifstream f(path, std::ios::binary);
    if (!f) return false;
    char magic[8];
    uint64_t klen = 0, spv = 0;
    if (!f.read(magic, 8) || std::memcmp(magic, kTableMagic, 8) != 0) return false;
    if (!f.read(reinterpret_cast<char*>(&spv), 8) || spv != fnv1a(tables_spv, sizeof(tables_spv))) return false;
    if (!f.read(reinterpret_cast<char*>(&klen), 8) || klen != key.size()) return false;
    std::string k(klen, '\0');
    if (!f.read(k.data(), std::streamsize(klen)) || k != key) return false;
    out.assign(TABLE_FLOATS, 0.0f);
    if (!f.read(reinterpret_cast<char*>(out.data()), std::streamsize(TABLE_FLOATS * 4))) return false;
    for (float v : out)
        if (!std::isfinite(v)) return false;
    return true;
}
void store_cached_tables(const std::string& key, const std::vector<float>& t) {
    std::string path = table_cache_file(key);
    if (path.empty()) return;
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
    std::string tmp = path + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream f(tmp, std::ios::binary);
        uint64_t spv = fnv1a(tables_spv, sizeof(tables_spv)), klen = key.size();
        f.write(kTableMagic, 8);
        f.write(reinterpret_cast<const char*>(&spv), 8);
        f.write(reinterpret_cast<const char*>(&klen), 8);
        f.write(key.data(), std::streamsize(klen));
        f.write(reinterpret_cast<const char*>(t.data()), std::streamsize(t.size() * 4));
        if (!f) {
            static bool warned = false;
            if (!warned) std::fprintf(stderr, "gonio: warning: cannot write the table cache %s (computing tables each run)\n", path.c_str());
            warned = true;
            std::filesystem::remove(tmp, ec);
            return;
        }
    }
    std::filesystem::rename(tmp, path, ec);   // atomic: readers see the old file or the whole new one
    if (ec) std::filesystem::remove(tmp, ec);
}

// The key of a stack's Belcour tables: what they depend on (each interface's kind, eta, k).
std::string table_key(const StackGpu& g) {
    std::string k;
    for (uint32_t i = 0; i < uint32_t(g.info.x); ++i) {
        const LayerGpu& L = g.layers[i];
        const glm::vec3 n = layer_conductor_eta(L), kk = layer_conductor_k(L);
        float v[8] = {float(layer_kind(L)), layer_eta(L), n.x, n.y, n.z, kk.x, kk.y, kk.z};
        k.append(reinterpret_cast<const char*>(v), sizeof v);
    }
    return k;
}

// The code (MODEL_*) of registry entry `index`: a variant runs its base model's code.
uint32_t shader_model_of(size_t index) { return model_registry().at(index).shader_model; }
bool is_belcour(size_t index) {
    const uint32_t m = shader_model_of(index);
    return m >= MODEL_BELCOUR18_FORWARD && m <= MODEL_BELCOUR18_TOPLOBE;
}
// Models that read the FGD/TIR tables and whose lobes the device computes once per dispatch.
bool uses_tables(size_t index) { return is_belcour(index) || shader_model_of(index) == MODEL_TM21; }

// The incident cosine below which Belcour's mean direction is totally reflected inside the stack (0: never): Snell
// carries sin(theta) through the interfaces as sin(theta_0) / (n_1 n_2 ... n_i) (belcour_layer), so interface i
// reflects it totally once sin(theta_0) exceeds the product P_i of the relative indices down to it; the first
// jump from mu = 1 down is at the smallest P_i < 1.
double mu_jump_of(const Stack& s) {
    StackGpu sg = pack_stack(s);
    double P = 1.0, pmin = 1.0;
    for (uint32_t i = 0; i < uint32_t(sg.info.x); ++i) {
        const LayerGpu& L = sg.layers[i];
        if (layer_kind(L) != KIND_DIELECTRIC) break;
        P *= layer_eta(L);
        pmin = std::min(pmin, P);
    }
    return pmin < 1.0 ? std::sqrt(1.0 - pmin * pmin) : 0.0;
}

std::vector<TermPlan> plan(size_t model, const Stack& s, double theta_deg, int side, const std::vector<float>* tables,
                           uint32_t convention) {
    std::vector<TermPlan> out;
    const double ti = theta_deg * M_PI / 180;
    // a GGX lobe of roughness alpha about the mirror direction of l (grid_eta = 0), or about the mirror direction
    // of l refracted into a coat of relative IOR grid_eta: a delta on a lobe grid (drawn in the coat's directions
    // for a refracted one), else the graded quadrature
    auto lobe_term = [&](uint32_t term, double alpha, bool delta, double grid_eta = 0.0) {
        if (delta) {
            out.push_back({term, double(MODEL_MIN_ALPHA), true, 0.0, grid_eta});
            return;
        }
        const double a = std::max(alpha, double(MODEL_MIN_ALPHA));
        // the polar angle of the direction the lobe mirrors: l, or l refracted into the coat
        double theta_eff = ti;
        if (grid_eta > 0.0) {
            double st = std::sin(ti) / grid_eta;
            theta_eff = st < 1.0 ? std::asin(st) : M_PI / 2;
        }
        if (2.0 * a * std::cos(theta_eff) < kFloatUnresolved) {
            // too narrow for v's floats (kFloatUnresolved): visible-normal grids, drawn in the half vector
            out.push_back({term, a, false, 0.0, grid_eta});
            return;
        }
        // a lobe at Snell-refracted directions inside a coat of relative IOR eta is, seen from outside, eta times
        // wider than its roughness when eta > 1, narrower when eta < 1 (grading finer than needed costs nodes only)
        out.push_back({term, 0.0, false, a * (grid_eta > 0.0 ? std::min(1.0, grid_eta) : 1.0), 0.0});
    };
    if (uses_tables(model)) {
        // the forward lobes at this incident angle (the symmetric variant's are close to them near the peak), with
        // the tables the device uses: which lobes exist and which are deltas is decided on the model's own lobes
        auto lobes = [&](double mu) {
            if (model == MODEL_TM21)
                return tables ? tm21_lobes_cpu(s, mu, *tables, convention) : tm21_lobes_cpu(s, mu, false, convention);
            return tables ? belcour_lobes_cpu(s, mu, *tables, convention) : belcour_lobes_cpu(s, mu, false, convention);
        };
        BelcourLobesHost b = lobes(std::cos(ti));
        if (side == 1) {
            if (b.e_t.x + b.e_t.y + b.e_t.z > 0.0) lobe_term(TERM_BASE, b.alpha_t, b.alpha_t < kModelDeltaAlpha);
            return out;
        }
        lobe_term(TERM_TOP, s.layers[0].roughness, s.layers[0].roughness == 0.0f);
        double lo = 1.0, hi = 0.0;
        auto take = [&](const BelcourLobesHost& lb) {
            for (size_t k = 1; k < lb.e.size(); ++k) {
                if (!(lb.e[k].x + lb.e[k].y + lb.e[k].z > 0.0)) continue;
                lo = std::min(lo, lb.alpha[k]);
                hi = std::max(hi, lb.alpha[k]);
            }
        };
        take(b);
        // the symmetric variant's lobes follow mu = |h.l|, not cos(theta_i) (which they equal at the mirror
        // direction, h = n): lobes below can exist for some v even when the forward lobes at l have none (light from
        // a dense medium beyond the critical angle: h.l > cos of it only for v towards l); then its base term is
        // planned from the lobes over the whole range of mu
        if (model == MODEL_BELCOUR18_SYMMETRIC && hi < lo)
            for (int i = 1; i <= 8; ++i) take(lobes(i / 8.0));
        if (hi >= lo) lobe_term(TERM_BASE, lo, hi < kModelDeltaAlpha);   // a delta only if every lobe below is one
        return out;
    }
    const double a0 = s.layers[0].roughness, a1 = s.layers[1].roughness;
    const double eta = s.layers[0].ior.x / s.exterior_ior;
    lobe_term(TERM_TOP, a0, a0 == 0.0);
    if (s.layers[1].kind == InterfaceKind::Lambertian) {
        out.push_back({TERM_BASE, 0.0, false, 0.0, 0.0});
        return out;
    }
    const bool unrefracted = model == MODEL_WW09 || model == MODEL_ALBEDO_SCALING;   // base at (l, v), own roughness
    if (unrefracted) {
        lobe_term(TERM_BASE, a1, a1 == 0.0);
    } else {
        // the base lobe at Snell-refracted (l1, v1): its grid is drawn about the mirror direction of l1 inside the
        // coat and refracted out (models.comp), where a lobe of the base's roughness is a GGX lobe; seen from
        // outside it is ~eta times wider (quadrature nodes)
        const double base_alpha = std::max(a0, a1);
        if (eta > std::sin(ti)) lobe_term(TERM_BASE, base_alpha, base_alpha == 0.0, eta);
        // else: l is totally reflected at the coat, no base term
    }
    return out;
}

}  // namespace

std::vector<float> coat_albedo_table(const Stack& s) {
    // E(mu) = integral of f_r0(l, v) cos(theta_v) dv, by quadrature in half-vector space (v = reflect(l, m),
    // dv = 4 (l.m) dm) with tan(theta_m) = a (e^(L u) - 1) to resolve narrow lobes; 65 nodes mu = i / 64.
    StackGpu sg = pack_stack(s);
    CoatParams p = coat_params(sg.layers[0], sg.layers[1]);
    const double a = p.alpha0, L = std::log(1e4 / a + 1);
    const int NU = 600, NP = 96;
    std::vector<float> table(65);
    // l lies in the xz-plane, so the phi nodes j and NP - 1 - j give the same value: half of them, twice; the 65
    // nodes of mu on all cores (this runs on the host before every model evaluation: it was 0.1 s)
    std::atomic<int> next{0};
    auto work = [&] {
        for (int i; (i = next++) <= 64;) {
            double mu = std::max(i / 64.0, 1e-3);
            glm::dvec3 l(std::sqrt(1 - mu * mu), 0, mu);
            double acc = 0;
            for (int k = 0; k < NU; ++k) {
                double u = (k + 0.5) / NU, tan_m = a * (std::exp(L * u) - 1), tm = std::atan(tan_m);
                double dtm = a * L * std::exp(L * u) / (1 + tan_m * tan_m);
                for (int j = 0; j < NP / 2; ++j) {
                    double pm = (j + 0.5) / NP * 2 * M_PI;
                    glm::dvec3 m(std::sin(tm) * std::cos(pm), std::sin(tm) * std::sin(pm), std::cos(tm));
                    double lm = glm::dot(l, m);
                    if (lm <= 0) continue;
                    glm::dvec3 v = 2 * lm * m - l;
                    if (v.z <= 0) continue;
                    acc += 2 * top_reflection(glm::vec3(l), glm::vec3(glm::normalize(v)), p.alpha0, p.eta) * v.z * 4 * lm * std::sin(tm) * dtm;
                }
            }
            table[i] = float(std::min(1.0, acc / NU * 2 * M_PI / NP));
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < std::max(1u, std::thread::hardware_concurrency()); ++t) pool.emplace_back(work);
    work();
    for (auto& th : pool) th.join();
    return table;
}

const std::vector<ModelInfo>& model_registry() {
    static const std::vector<ModelInfo> r = [] {
    std::vector<ModelInfo> r = {
        {"ww09", "Weidlich & Wilkie 2009 (SIGGRAPH Asia course), variant of Weidlich & Wilkie 2007; Bati et al. 2019 eq. 2",
         "T01/T10 from the top microfacet normal, base at unrefracted directions, TIR term t = (1 - G) + T10 G",
         "one dielectric coat over a Lambertian or conductor base",
         true,    // h0-based T01 = T10 (l.h0 = v.h0), t and the base at (l, v) are symmetric
         false, "the base is added to the full top reflection without the energy the top reflects; t = (1 - G) + T10 G can exceed T10"},
        {"elek10", "Elek 2010 (CESCG), as described by Bati et al. 2019 section 2.1",
         "as ww09 but the base at Snell-refracted directions, alpha1 <- max(alpha0, alpha1)",
         "one dielectric coat over a Lambertian or conductor base",
         true,    // as ww09, and Snell refraction of l and v is the same map
         false, "as ww09"},
        {"ww-corrected", "Bati, Pacanowski & Barla 2019, eq. 4",
         "geometric normal for T01, T10 and refraction, 1/eta^2 solid-angle factor, Elek's roughness rule",
         "one dielectric coat over a Lambertian or conductor base",
         true,    // T01(l) T10(v) / eta^2 with the geometric normal
         true, ""},
        {"albedo-scaling", "OpenPBR Surface v1.1 layering (Andersson et al. 2024), as used by Autodesk Standard Surface (Georgiev et al. 2019)",
         "f_coat + T_coat (1 - E_coat(v)) f_base(l, v): albedo scaling with view-dependent coat absorption",
         "one dielectric coat over a Lambertian or conductor base", false,   // E_coat of v only
         false, "the base is scaled by 1 - E_coat(v), the coat's albedo seen from v, not from l"},
        {"belcour18-forward", "Belcour 2018, ACM TOG 37(4) 73, sections 4-6 (atomic operators, adding)",
         "sum of GGX lobes (separable Smith G, as the official code) from energy/variance statistics of the incident "
         "direction, FGD and TIR tables (separable G); no TIR term below an absorbing medium (as the official code)",
         "any number of dielectric interfaces over a conductor base, or a slab (dielectric stack in one medium); "
         "not a Lambertian base", false,
         true, ""},   // lobe energies sum to at most 1 (adding equations), each GGX lobe (F = 1) reflects at most its energy
        {"belcour18-symmetric", "Belcour 2018, section 7.2 (symmetric model)",
         "as belcour18-forward with statistics from |h.l|, h = normalize(l + v): reciprocal",
         "dielectric interfaces over a conductor base (reflection only)", true,
         false, "each direction v has its own lobe energies (from |h.l|): their sum over v is not bounded by 1 (1.215 measured at 89.9 degrees on stacks/hard/ior-3-metal)"},
        {"belcour18-toplobe", "Bati, Pacanowski & Barla 2019 section 4.2, on Belcour 2018",
         "exact top-interface BRDF f_r0 for lobe 0, belcour18-forward for the lobes below",
         "as belcour18-forward", false,
         false, "the exact lobe 0 reflects the exact top albedo while the lobes below get 1 - FGD from the table; near grazing the two differ (not bounded by construction; no excess found on the hard cases with the separable tables: largest 1.000)"},
        {"tm21", "Randrianandrasana, Callet & Lucas 2021, ACM TOG 40(4) (two-flux transfer matrices, the authors' tm2)",
         "lobe energies from 2x2 transfer matrices of FGD/TIR albedos, roughness from Henyey-Greenstein asymmetry "
         "through the same matrices, exact top lobe; separable Smith G in the lobes below and the tables (as the authors' code)",
         "dielectric interfaces (absorbing media: gonio's extension) over a conductor base", false,
         false, "as belcour18-toplobe: the exact lobe 0 and the table's FGD differ near grazing (not bounded by construction; no excess found on the hard cases: largest 0.996)"},
    };
    for (size_t i = 0; i < r.size(); ++i) r[i].shader_model = uint32_t(i);   // registry order = MODEL_* (all.glsl)
    // gonio's alternatives to the official codes' conventions (docs/MODELS.md, "Conventions"), as variants of the
    // same code: +g2, the reference's height-correlated G2 in the GGX lobes and in the FGD/TIR tables instead of
    // the separable G1(l) G1(v); +tir (Belcour's adding loop only), the TIR term of an interface kept when an
    // absorbing medium lies under it; +g2+tir, both (gonio's models before they followed the official codes)
    struct Variant { const char* suffix; uint32_t convention; const char* what; };
    const Variant belcour_variants[] = {
        {"+g2", CONVENTION_G2, "with height-correlated Smith G2 in its GGX lobes and FGD/TIR tables (gonio's alternative to the separable G of the official code)"},
        {"+tir", CONVENTION_TIR_BELOW_MEDIA, "with the TIR term kept for an interface over an absorbing medium (the official code loses it there)"},
        {"+g2+tir", CONVENTION_G2 | CONVENTION_TIR_BELOW_MEDIA, "with both: height-correlated G2 and the TIR term kept below absorbing media"},
    };
    const Variant tm_variants[] = {
        {"+g2", CONVENTION_G2, "with height-correlated Smith G2 in its lobes below lobe 0 and in the FGD/TIR tables (gonio's alternative to the separable G of the authors' code)"},
    };
    const size_t bases = r.size();
    for (size_t i = 0; i < bases; ++i) {
        const bool belcour = i >= MODEL_BELCOUR18_FORWARD && i <= MODEL_BELCOUR18_TOPLOBE;
        if (!belcour && i != MODEL_TM21) continue;
        for (const Variant& v : belcour ? std::span<const Variant>(belcour_variants) : std::span<const Variant>(tm_variants)) {
            ModelInfo m = r[i];
            m.id += v.suffix;
            m.citation = "gonio's variant of " + r[i].id + " (" + r[i].citation + ")";
            m.summary = "as " + r[i].id + ", " + v.what;
            m.convention = v.convention;
            // the energy excess measured for this variant on the hard cases (tests/test_hard_cases.cpp)
            const struct { const char* id; const char* note; } measured[] = {
                {"belcour18-symmetric+g2", "as belcour18-symmetric (1.318 measured at 89.9 degrees on stacks/hard/ior-3-metal)"},
                {"belcour18-symmetric+tir", "as belcour18-symmetric (1.040 measured at 89.9 degrees on stacks/hard/ior-3-metal)"},
                {"belcour18-symmetric+g2+tir", "as belcour18-symmetric (1.069 measured at 89.9 degrees on stacks/hard/ior-3-metal)"},
                {"belcour18-toplobe+g2", "as belcour18-toplobe (1.003 measured at 89.9 degrees on stacks/hard/tir-trap-slab)"},
                {"belcour18-toplobe+tir", "as belcour18-toplobe (not bounded by construction; no excess found on the hard cases: largest 1.000)"},
                {"belcour18-toplobe+g2+tir", "as belcour18-toplobe (1.003 measured at 89.9 degrees on stacks/hard/tir-trap-slab)"},
                {"tm21+g2", "as tm21 (not bounded by construction; no excess found on the hard cases: largest 0.996)"},
            };
            for (const auto& e : measured)
                if (m.id == e.id) m.energy_note = e.note;
            r.push_back(m);
        }
    }
    return r;
    }();
    return r;
}

std::string model_cannot_represent(size_t index, const Stack& s) {
    const std::string& id = model_registry().at(index).id;
    const uint32_t model = shader_model_of(index);   // a variant represents what its base model does
    if (model == MODEL_TM21) {
        for (const Layer& L : s.layers)
            if (L.kind == InterfaceKind::Lambertian)
                return id + " (two-flux, tm2) takes dielectric interfaces over a conductor; a Lambertian base needs the "
                            "authors' six-flux variant, not implemented";
        if (s.transmissive())
            return id + ": the transmissive variant (the authors' tm2_dielectric) is not implemented";
        return "";
    }
    if (is_belcour(index)) {
        for (const Layer& L : s.layers)
            if (L.kind == InterfaceKind::Lambertian)
                return id + " is limited to forward propagation: light entering a Lambertian base never leaves it on "
                            "reflection (Bati et al. 2019 section 2.2)";
        if (s.transmissive()) {
            if (model == MODEL_BELCOUR18_SYMMETRIC)
                return id + " is defined for reflection (its statistics use the reflection half-vector); this stack "
                            "is transmissive";
            if (s.base().ior.x != s.exterior_ior)
                return id + ": a transmitted lobe into a substrate of another IOR than the exterior's is not "
                            "implemented (only slabs: substrate IOR " + std::to_string(s.base().ior.x) +
                            " differs from the exterior's " + std::to_string(s.exterior_ior) + ")";
        }
        // the TIR convention differs only below an absorbing medium: elsewhere the variant is its base model, and is
        // not computed twice
        if (model_registry().at(index).convention & MODEL_CONVENTION_TIR_BELOW_MEDIA) {
            bool absorbing = false;
            for (size_t i = 0; i + 1 < s.layers.size(); ++i) absorbing |= s.layers[i].optical_depth != glm::vec3(0.0f);
            if (!absorbing)
                return id + " equals " + id.substr(0, id.size() - 4) + " on this stack: no absorbing medium lies below an "
                            "interface, where keeping the TIR term differs";
        }
        return "";
    }
    if (s.transmissive())
        return id + " models reflection only (a BRDF); this stack is transmissive (its last layer is a dielectric)";
    if (s.base().kind != InterfaceKind::Lambertian && s.base().kind != InterfaceKind::Conductor)
        return id + " takes a Lambertian or conductor base (models/common.glsl base_brdf), not a " + to_string(s.base().kind);
    if (s.layers.size() != 2)
        return id + " is implemented for one dielectric coat over an opaque base; this stack has " +
               std::to_string(s.layers.size()) + " layers";
    return "";
}

ModelGrid model_grid(const SimResult& r) {
    return {r.n_theta, r.n_phi, r.options.dtheta_deg, r.options.dphi_deg, r.options.theta_i_deg};
}

struct ModelEvaluator::Impl {
    VkContext& ctx;
    Buffer ubo, albedo, tables, lobes;
    Buffer quad, lobe, host;
    size_t nb = 0;   // bins the grid buffers hold
    std::map<std::pair<uint32_t, uint32_t>, std::unique_ptr<ComputeKernel>> kernels;   // (kernel, model), built when first used
    std::unique_ptr<ComputeKernel> table_kernel;
    vk::raii::QueryPool queries = nullptr;
    std::map<std::string, std::vector<float>> table_cache;
    std::string tables_loaded;   // key of the tables now in the device buffer
    double table_seconds = 0.0;

    explicit Impl(VkContext& c) : ctx(c) {
        ubo = ctx.make_buffer(sizeof(StackGpu), vk::BufferUsageFlagBits::eUniformBuffer, true);
        albedo = ctx.make_buffer(65 * 4, vk::BufferUsageFlagBits::eStorageBuffer, true);
        tables = ctx.make_buffer(TABLE_FLOATS * 4, vk::BufferUsageFlagBits::eStorageBuffer, true);
        std::memset(tables.mapped, 0, TABLE_FLOATS * 4);
        lobes = ctx.make_device_buffer(BELCOUR_MU_NODES * BELCOUR_LOBE_STRIDE * 16, vk::BufferUsageFlagBits::eStorageBuffer);
        queries = vk::raii::QueryPool(ctx.device(), vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = 2});
    }

    void ensure_grid(size_t bins) {
        if (bins <= nb) return;
        auto& dev = ctx.device();
        nb = bins;
        quad = ctx.make_device_buffer(nb * 8 * 4, vk::BufferUsageFlagBits::eStorageBuffer);
        lobe = ctx.make_device_buffer(nb * 3 * 8, vk::BufferUsageFlagBits::eStorageBuffer);
        host = ctx.make_buffer(nb * (32 + 24), vk::BufferUsageFlagBits::eTransferDst, false);
        for (auto& [key, k] : kernels) k->bind(dev, {&ubo, &quad, &lobe, &albedo, &tables, &lobes});
    }

    // `model`: a registry index; its pipeline is its base model's module specialised with its conventions
    std::unique_ptr<ComputeKernel> make_kernel(uint32_t which, uint32_t model) {
        const uint32_t code = shader_model_of(model), convention = model_registry().at(model).convention;
        if (code >= std::size(kModelSpv)) throw std::runtime_error("models.comp: no SPIR-V module for model " + std::to_string(code));
        auto& dev = ctx.device();
        auto k = std::make_unique<ComputeKernel>(dev, kModelSpv[code].code, kModelSpv[code].bytes, std::vector<vk::DescriptorType>{vk::DescriptorType::eUniformBuffer,
                                                 vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eStorageBuffer,
                                                 vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eStorageBuffer}, uint32_t(sizeof(Push)));
        uint32_t spec[3] = {which, code, convention};
        k->build(dev, {{0, 0, 4}, {1, 4, 4}, {2, 8, 4}}, spec, sizeof spec);
        k->bind(dev, {&ubo, &quad, &lobe, &albedo, &tables, &lobes});
        return k;
    }

    ComputeKernel& kernel(uint32_t which, uint32_t model) {
        auto& k = kernels[{which, model}];
        if (!k) k = make_kernel(which, model);
        return *k;
    }

    // Creates the pipelines in `need` that do not exist yet, concurrently (vkCreateComputePipelines is where
    // lavapipe translates and optimises the shader, on the calling thread; each pipeline has its own module,
    // layout and descriptor pool, so no object is shared between the threads). Returns how many it made.
    uint32_t prepare(const std::set<std::pair<uint32_t, uint32_t>>& need) {
        std::vector<std::pair<uint32_t, uint32_t>> todo;
        for (auto& key : need)
            if (!kernels.count(key) || !kernels[key]) todo.push_back(key);
        std::vector<std::unique_ptr<ComputeKernel>> made(todo.size());
        std::atomic<size_t> next{0};
        auto work = [&] {
            for (size_t i; (i = next++) < todo.size();) made[i] = make_kernel(todo[i].first, todo[i].second);
        };
        const unsigned threads = std::min<unsigned>(std::max(1u, std::thread::hardware_concurrency()), unsigned(todo.size()));
        std::vector<std::future<void>> pool;
        for (unsigned t = 1; t < threads; ++t) pool.push_back(std::async(std::launch::async, work));
        work();
        for (auto& f : pool) f.get();   // rethrows a worker's exception
        for (size_t i = 0; i < todo.size(); ++i) kernels[todo[i]] = std::move(made[i]);
        return uint32_t(todo.size());
    }

    const std::vector<float>& compute_tables(const Stack& s) {
        StackGpu sg = pack_stack(s);
        std::string key = table_key(sg);
        auto it = table_cache.find(key);
        if (it != table_cache.end()) return it->second;
        std::vector<float> cached;
        if (load_cached_tables(key, cached)) return table_cache.emplace(key, std::move(cached)).first->second;
        auto& dev = ctx.device();
        if (!table_kernel) {
            table_kernel = std::make_unique<ComputeKernel>(dev, tables_spv, sizeof(tables_spv),
                std::vector<vk::DescriptorType>{vk::DescriptorType::eUniformBuffer, vk::DescriptorType::eStorageBuffer}, 4u);
            table_kernel->build(dev, {}, nullptr, 0);
        }
        Buffer u = ctx.make_buffer(sizeof(StackGpu), vk::BufferUsageFlagBits::eUniformBuffer, true);
        std::memcpy(u.mapped, &sg, sizeof sg);
        Buffer out = ctx.make_buffer(TABLE_FLOATS * 4, vk::BufferUsageFlagBits::eStorageBuffer, false);
        std::memset(out.mapped, 0, TABLE_FLOATS * 4);
        table_kernel->bind(dev, {&u, &out});
        uint32_t invocations = 2u * uint32_t(s.layers.size()) * TABLE_NMU * TABLE_NALPHA;   // both sets (tables.comp)
        ctx.run_now([&](vk::CommandBuffer c) {
            c.resetQueryPool(*queries, 0, 2);
            c.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries, 0);
            c.bindPipeline(vk::PipelineBindPoint::eCompute, *table_kernel->pipeline);
            c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *table_kernel->layout, 0, {*table_kernel->set}, nullptr);
            c.dispatch((invocations + 63) / 64, 1, 1);
            c.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries, 1);
            vk::MemoryBarrier read{.srcAccessMask = vk::AccessFlagBits::eShaderWrite, .dstAccessMask = vk::AccessFlagBits::eHostRead};
            c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eHost, {}, read, nullptr, nullptr);
        });
        auto [qr, ts] = queries.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                                                     vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
        table_seconds += double(ts[1] - ts[0]) * ctx.timestamp_period_ns() * 1e-9;
        const float* p = static_cast<const float*>(out.mapped);
        const std::vector<float>& t = table_cache.emplace(key, std::vector<float>(p, p + TABLE_FLOATS)).first->second;
        store_cached_tables(key, t);
        return t;
    }

    std::vector<ModelSlices> evaluate(const Stack& s, const ModelGrid& grid, std::vector<ModelCost>* costs, const ModelOptions& options,
                                      ModelStageCost* stage);
};

ModelEvaluator::ModelEvaluator(VkContext& ctx) : impl_(new Impl(ctx)) {}
ModelEvaluator::~ModelEvaluator() { delete impl_; }
const std::vector<float>& ModelEvaluator::belcour_tables(const Stack& s) { return impl_->compute_tables(s); }
double ModelEvaluator::table_seconds() const { return impl_->table_seconds; }
std::vector<ModelSlices> ModelEvaluator::evaluate(const Stack& s, const ModelGrid& grid, std::vector<ModelCost>* costs,
                                                  const ModelOptions& options, ModelStageCost* stage) {
    return impl_->evaluate(s, grid, costs, options, stage);
}

std::vector<ModelSlices> evaluate_models(VkContext& ctx, const Stack& s, const ModelGrid& grid,
                                         std::vector<ModelCost>* costs, const ModelOptions& options, ModelStageCost* stage) {
    ModelEvaluator e(ctx);
    return e.evaluate(s, grid, costs, options, stage);
}

std::vector<ModelSlices> ModelEvaluator::Impl::evaluate(const Stack& s, const ModelGrid& grid, std::vector<ModelCost>* costs,
                                                        const ModelOptions& options, ModelStageCost* stage) {
    using clock = std::chrono::steady_clock;
    const auto stage0 = clock::now();
    auto since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
    ModelStageCost sc;
    const size_t nb = size_t(grid.n_theta) * grid.n_phi;
    ensure_grid(nb);
    StackGpu sg = pack_stack(s);
    std::memcpy(ubo.mapped, &sg, sizeof(sg));
    std::vector<float> table(65, 0.0f);
    if (s.layers.size() == 2 && !s.transmissive()) table = coat_albedo_table(s);
    std::memcpy(albedo.mapped, table.data(), 65 * 4);
    std::vector<ModelSlices> out;
    if (costs) costs->clear();
    bool need_tables = false;
    for (size_t m = 0; m < model_registry().size(); ++m)
        need_tables |= uses_tables(m) && options.belcour_tables && model_cannot_represent(m, s).empty();
    double table_before = table_seconds;
    std::vector<float> tables_now;   // what the device reads (planning looks at the lobes they give)
    if (need_tables) {
        auto t0 = std::chrono::steady_clock::now();
        const std::vector<float>& t = compute_tables(s);
        std::memcpy(tables.mapped, t.data(), TABLE_FLOATS * 4);
        tables_now = t;
        double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        (void)wall;
    }
    const double table_cost = table_seconds - table_before;   // shared by Belcour's models: charged to the first
    bool table_charged = false;
    sc.setup_seconds = since(stage0);
    // every model's plan at every angle and side, then the pipelines they need (only those), made concurrently
    const int sides = s.transmissive() ? 2 : 1;
    std::vector<std::vector<std::vector<TermPlan>>> plans(model_registry().size());
    std::set<std::pair<uint32_t, uint32_t>> need;
    for (size_t m = 0; m < model_registry().size(); ++m) {
        if (!model_cannot_represent(m, s).empty()) continue;
        if (uses_tables(m)) need.insert({2u, uint32_t(m)});
        for (double theta : grid.theta_i_deg)
            for (int side = 0; side < sides; ++side) {
                plans[m].push_back(plan(shader_model_of(m), s, theta, side,
                                        uses_tables(m) && options.belcour_tables ? &tables_now : nullptr,
                                        model_registry()[m].convention));
                for (auto& t : plans[m].back()) need.insert({t.alpha_grid == 0 ? 0u : 1u, uint32_t(m)});
            }
    }
    const auto pipes0 = clock::now();
    sc.pipelines_created = prepare(need);
    sc.pipeline_seconds = since(pipes0);
    for (size_t m = 0; m < model_registry().size(); ++m) {
        ModelSlices ms;
        ms.id = model_registry()[m].id;
        ms.not_applicable = model_cannot_represent(m, s);
        ModelCost cost;
        auto t0 = std::chrono::steady_clock::now();
        if (ms.not_applicable.empty()) {
            if (uses_tables(m) && options.belcour_tables && !table_charged) {
                cost.device_seconds += table_cost;
                table_charged = true;
            }
            size_t plan_index = 0;
            for (double theta : grid.theta_i_deg) {
                double ti = theta * M_PI / 180;
                for (int side = 0; side < sides; ++side) {
                    const std::vector<TermPlan>& terms = plans[m][plan_index++];
                    uint32_t quad_terms = 0;
                    double narrowest = 0.0;   // the narrowest lobe among the quadrature's terms (0: none)
                    for (auto& t : terms)
                        if (t.alpha_grid == 0) {
                            quad_terms |= t.term;
                            if (t.alpha_eff > 0.0) narrowest = narrowest > 0.0 ? std::min(narrowest, t.alpha_eff) : t.alpha_eff;
                        }
                    const double eta = s.layers[0].ior.x / s.exterior_ior;
                    // v beyond the critical angle of a coat of lower index (a denser exterior) cannot enter it: the
                    // base terms of the two-layer models stop there
                    const bool coat_model = !uses_tables(m);
                    Push pc{uint32_t(m), quad_terms, grid.n_theta, grid.n_phi, float(grid.dtheta_deg * M_PI / 180),
                            float(grid.dphi_deg * M_PI / 180), float(std::sin(ti)), float(std::cos(ti)), lobe_grid_nodes(theta),
                            0.0f, 0u, 0.0f, uint32_t(side), options.belcour_tables ? 1u : 0u, 0u, 0.0f, lobe_grid_nodes(theta),
                            float(2.0 * narrowest), std::sin(ti) > 1e-6 ? float(narrowest) : 0.0f, float(narrowest),
                            coat_model && eta < 1.0 ? float(std::asin(eta)) : 0.0f, quadrature_max_rects(shader_model_of(m), s),
                            s.layers[0].kind == InterfaceKind::Dielectric && eta < 1.0 ? float(std::sqrt(1.0 - eta * eta)) : 0.0f,
                            float(mu_jump_of(s)),
                            // the lobe's width in the components of v, 2 alpha cos(theta_i), against 1e-4 (1700 float
                            // steps of 6e-8): narrower lobes get up to 8x finer pieces at their peak (models.comp)
                            narrowest > 0.0 ? float(std::clamp(1e-4 / (2.0 * narrowest * std::max(std::cos(ti), 1e-3)), 1.0, 8.0)) : 1.0f};
                    bool any_grid = false;
                    for (auto& t : terms) any_grid |= t.alpha_grid != 0;
                    ComputeKernel* kq = quad_terms ? &kernel(0, uint32_t(m)) : nullptr;
                    ComputeKernel* kl = any_grid ? &kernel(1, uint32_t(m)) : nullptr;
                    const bool prepass = uses_tables(m);
                    ComputeKernel* kp = prepass ? &kernel(2, uint32_t(m)) : nullptr;
                    ctx.run_now([&](vk::CommandBuffer c) {
                        c.resetQueryPool(*queries, 0, 2);
                        c.fillBuffer(*quad.buffer, 0, VK_WHOLE_SIZE, 0);
                        c.fillBuffer(*lobe.buffer, 0, VK_WHOLE_SIZE, 0);
                        vk::MemoryBarrier fill{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                               .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
                        c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, fill, nullptr, nullptr);
                        c.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries, 0);
                        if (kp) {   // Belcour's lobes for this angle, once (models.comp KERNEL 2)
                            c.bindPipeline(vk::PipelineBindPoint::eCompute, *kp->pipeline);
                            c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *kp->layout, 0, {*kp->set}, nullptr);
                            c.pushConstants<Push>(*kp->layout, vk::ShaderStageFlagBits::eCompute, 0, pc);
                            c.dispatch(shader_model_of(m) == MODEL_BELCOUR18_SYMMETRIC ? (BELCOUR_MU_NODES + 63) / 64 : 1, 1, 1);
                            vk::MemoryBarrier lobes_done{.srcAccessMask = vk::AccessFlagBits::eShaderWrite, .dstAccessMask = vk::AccessFlagBits::eShaderRead};
                            c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {}, lobes_done, nullptr, nullptr);
                        }
                        if (quad_terms) {
                            c.bindPipeline(vk::PipelineBindPoint::eCompute, *kq->pipeline);
                            c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *kq->layout, 0, {*kq->set}, nullptr);
                            c.pushConstants<Push>(*kq->layout, vk::ShaderStageFlagBits::eCompute, 0, pc);
                            c.dispatch(uint32_t((nb + 63) / 64), 1, 1);
                        }
                        for (auto& t : terms) {
                            if (t.alpha_grid == 0) continue;
                            // the lobe's own grid and a wide one, combined by the balance heuristic (a delta: its own only)
                            for (int pass = 0; pass < (t.delta ? 1 : 2); ++pass) {
                                Push lp = pc;
                                lp.terms = t.term;
                                lp.alpha_grid = float(pass == 0 ? t.alpha_grid : kWideGrid);
                                lp.alpha_partner = t.delta ? 0.0f : float(pass == 0 ? kWideGrid : t.alpha_grid);
                                lp.delta = t.delta ? 1u : 0u;
                                lp.grid_eta = float(t.grid_eta);
                                // the wide grid carries the tails only: half the nodes per side of the lobe's own
                                const GridShape gs = lobe_grids(theta, grid.n_phi);
                                lp.grid = pass == 0 ? gs.cols : gs.wide_cols;
                                lp.grid_rows = pass == 0 ? gs.rows : gs.wide_rows;
                                lp.partner_nodes = pass == 0 ? gs.wide_cols * gs.wide_rows : gs.cols * gs.rows;
                                c.bindPipeline(vk::PipelineBindPoint::eCompute, *kl->pipeline);
                                c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *kl->layout, 0, {*kl->set}, nullptr);
                                c.pushConstants<Push>(*kl->layout, vk::ShaderStageFlagBits::eCompute, 0, lp);
                                c.dispatch((lp.grid * lp.grid_rows + 16 * 64 - 1) / (16 * 64), 1, 1);
                                vk::MemoryBarrier acc{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                                      .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
                                c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {}, acc, nullptr, nullptr);
                            }
                        }
                        c.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries, 1);
                        vk::MemoryBarrier done{.srcAccessMask = vk::AccessFlagBits::eShaderWrite, .dstAccessMask = vk::AccessFlagBits::eTransferRead};
                        c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eTransfer, {}, done, nullptr, nullptr);
                        c.copyBuffer(*quad.buffer, *host.buffer, vk::BufferCopy{0, 0, nb * 32});
                        c.copyBuffer(*lobe.buffer, *host.buffer, vk::BufferCopy{0, nb * 32, nb * 24});
                        vk::MemoryBarrier read{.srcAccessMask = vk::AccessFlagBits::eTransferWrite, .dstAccessMask = vk::AccessFlagBits::eHostRead};
                        c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eHost, {}, read, nullptr, nullptr);
                    });
                    auto [qr, ts] = queries.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                                                                 vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
                    cost.device_seconds += double(ts[1] - ts[0]) * ctx.timestamp_period_ns() * 1e-9;
                    for (auto& t : terms)
                        if (t.alpha_grid != 0) {
                            const GridShape gs = lobe_grids(theta, grid.n_phi);
                            cost.evaluations += uint64_t(gs.cols) * gs.rows + (t.delta ? 0 : uint64_t(gs.wide_cols) * gs.wide_rows);
                        }
                    // per bin: the quadrature's RGB bin average, its node count, its error estimate (models.comp)
                    const float* q = static_cast<const float*>(host.mapped);
                    const int64_t* lb = reinterpret_cast<const int64_t*>(static_cast<const char*>(host.mapped) + nb * 32);
                    std::vector<glm::dvec3> f(nb), fe(nb);
                    for (size_t b = 0; b < nb; ++b) {
                        uint32_t t = uint32_t(b / grid.n_phi);
                        double lo = t * grid.dtheta_deg * M_PI / 180, hi = (t + 1) * grid.dtheta_deg * M_PI / 180;
                        double omega = 0.5 * (std::pow(std::sin(hi), 2) - std::pow(std::sin(lo), 2)) * grid.dphi_deg * M_PI / 180;
                        for (int c = 0; c < 3; ++c) {
                            f[b][c] = double(q[b * 8 + c]) + double(lb[b * 3 + c]) / kLobeScale / omega;
                            fe[b][c] = double(q[b * 8 + 4 + c]);
                        }
                        if (quad_terms) cost.evaluations += uint64_t(q[b * 8 + 3]);
                    }
                    (side == 0 ? ms.f_err : ms.t_err).push_back(std::move(fe));
                    (side == 0 ? ms.f : ms.t).push_back(std::move(f));
                }
            }
        }
        cost.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        sc.device_seconds += cost.device_seconds;
        if (costs) costs->push_back(cost);
        out.push_back(std::move(ms));
    }
    sc.wall_seconds = since(stage0);
    if (stage) *stage = sc;
    return out;
}

namespace {
// One set of the stack's tables on the CPU twin, as tables.comp computes it (set 0: separable G, set 1:
// height-correlated G2), into t (TABLE_FLOATS floats).
void fill_table_set(const StackGpu& sg, uint32_t layers, uint32_t set, std::vector<float>& t) {
    const uint32_t per_layer = TABLE_NMU * TABLE_NALPHA, total = layers * per_layer;
    std::atomic<uint32_t> next{0};
    auto work = [&] {
        for (uint32_t id; (id = next++) < total;) {
            uint32_t layer = id / per_layer, r = id - layer * per_layer, a = r / TABLE_NMU, c = r - a * TABLE_NMU;
            vec4 e = belcour_table_entry(sg.layers[layer], table_node_mu(c), table_node_alpha(a), set == 1);
            uint32_t f = set * TABLE_SET_FLOATS + layer * TABLE_FGD_STRIDE + r * 3;
            t[f] = e.x; t[f + 1] = e.y; t[f + 2] = e.z;
            t[set * TABLE_SET_FLOATS + TABLE_TIR_OFFSET + layer * per_layer + r] = e.w;
        }
    };
    std::vector<std::thread> pool;
    for (unsigned i = 0; i < std::max(1u, std::thread::hardware_concurrency()); ++i) pool.emplace_back(work);
    for (auto& th : pool) th.join();
}

// The CPU twin's tables for the last stack seen, per thread; each set computed when a model first reads it
// (convention: the reader's CONVENTION_* bits).
const std::vector<float>& cpu_tables_for(const StackGpu& sg, const Stack& s, uint32_t convention) {
    static thread_local std::string key;
    static thread_local std::vector<float> tables;
    static thread_local bool have[2] = {false, false};
    std::string k = table_key(sg);
    if (k != key || tables.empty()) {
        tables.assign(TABLE_FLOATS, 0.0f);
        have[0] = have[1] = false;
        key = k;
    }
    const uint32_t set = (convention & CONVENTION_G2) != 0 ? 1 : 0;
    if (!have[set]) {
        fill_table_set(sg, uint32_t(s.layers.size()), set, tables);
        have[set] = true;
    }
    return tables;
}
}  // namespace

std::vector<float> belcour_tables_cpu(const Stack& s) {
    StackGpu sg = pack_stack(s);
    std::vector<float> t(TABLE_FLOATS, 0.0f);
    for (uint32_t set = 0; set < 2; ++set) fill_table_set(sg, uint32_t(s.layers.size()), set, t);
    return t;
}

namespace {
BelcourLobesHost lobes_host(const Stack& s, double mu, const float* tables, bool tm21, uint32_t convention) {
    StackGpu sg = pack_stack(s);
    g_stack = &sg;
    g_use_tables = tables != nullptr;
    g_convention = convention;
    g_tables = tables;
    BelcourLobes b = tm21 ? tm21_lobes(float(mu), tables != nullptr) : belcour_lobes(float(mu), tables != nullptr);
    BelcourLobesHost h;
    for (uint32_t k = 0; k < b.count; ++k) {
        h.e.push_back(glm::dvec3(b.e[k]));
        h.alpha.push_back(b.alpha[k]);
    }
    if (!tm21) {
        h.e_t = glm::dvec3(b.e_t);
        h.alpha_t = b.alpha_t;
    }
    g_stack = nullptr;
    return h;
}
}  // namespace

BelcourLobesHost tm21_lobes_cpu(const Stack& s, double mu, bool tables, uint32_t convention) {
    return lobes_host(s, mu, tables ? cpu_tables_for(pack_stack(s), s, convention).data() : nullptr, true, convention);
}
BelcourLobesHost tm21_lobes_cpu(const Stack& s, double mu, const std::vector<float>& tables, uint32_t convention) {
    return lobes_host(s, mu, tables.data(), true, convention);
}

double belcour_variance_of(double alpha) { return belcour_roughness_to_variance(float(alpha)); }
double belcour_roughness_of(double sigma) { return belcour_variance_to_roughness(float(sigma)); }
BelcourTableGeometry belcour_table_geometry() { return {TABLE_NMU, TABLE_NALPHA}; }
double belcour_table_mu(uint32_t c) { return table_node_mu(c); }
double belcour_table_alpha(uint32_t a) { return table_node_alpha(a); }
glm::dvec3 belcour_table_fgd(const std::vector<float>& t, uint32_t layer, uint32_t a, uint32_t c, bool g2) {
    size_t i = (g2 ? TABLE_SET_FLOATS : 0) + layer * TABLE_FGD_STRIDE + (a * TABLE_NMU + c) * 3;
    return {t.at(i), t.at(i + 1), t.at(i + 2)};
}
double belcour_table_tir(const std::vector<float>& t, uint32_t layer, uint32_t a, uint32_t c, bool g2) {
    return t.at((g2 ? TABLE_SET_FLOATS : 0) + TABLE_TIR_OFFSET + layer * TABLE_NMU * TABLE_NALPHA + a * TABLE_NMU + c);
}

BelcourLobesHost belcour_lobes_cpu(const Stack& s, double mu, bool tables, uint32_t convention) {
    return lobes_host(s, mu, tables ? cpu_tables_for(pack_stack(s), s, convention).data() : nullptr, false, convention);
}
BelcourLobesHost belcour_lobes_cpu(const Stack& s, double mu, const std::vector<float>& tables, uint32_t convention) {
    return lobes_host(s, mu, tables.data(), false, convention);
}

glm::dvec3 model_value_cpu(size_t index, const Stack& s, glm::vec3 l, glm::vec3 v, const ModelOptions& options) {
    // the coat-albedo table depends on the coat's roughness and IOR only: keep the last one per thread
    static thread_local float last_alpha = -1.0f, last_eta = -1.0f;
    static thread_local std::vector<float> table;
    if (s.layers.size() == 2 && !s.transmissive() &&
        (s.layers[0].roughness != last_alpha || s.layers[0].ior.x / s.exterior_ior != last_eta)) {
        table = coat_albedo_table(s);
        last_alpha = s.layers[0].roughness;
        last_eta = s.layers[0].ior.x / s.exterior_ior;
    }
    g_coat_albedo = table.data();
    StackGpu sg = pack_stack(s);
    g_stack = &sg;
    g_use_tables = options.belcour_tables;
    g_convention = model_registry().at(index).convention;
    g_tables = uses_tables(index) && options.belcour_tables ? cpu_tables_for(sg, s, g_convention).data() : nullptr;
    CoatParams p = coat_params(sg.layers[0], sg.layers[1]);
    glm::dvec3 f(eval_model(shader_model_of(index), p, TERM_TOP | TERM_BASE, l, v));
    g_stack = nullptr;
    return f;
}

ModelCpu::ModelCpu(size_t index, const Stack& s, const ModelOptions& options, const std::vector<float>* tables)
    : index_(index), use_tables_(options.belcour_tables) {
    // what model_value_cpu sets up per call: E_coat for two-layer opaque stacks, the packed stack, the tables
    coat_albedo_.assign(65, 0.0f);
    if (s.layers.size() == 2 && !s.transmissive()) coat_albedo_ = coat_albedo_table(s);
    StackGpu sg = pack_stack(s);
    stack_.resize(sizeof(StackGpu));
    std::memcpy(stack_.data(), &sg, sizeof sg);
    if (uses_tables(index) && options.belcour_tables)
        tables_ = tables ? *tables : cpu_tables_for(sg, s, model_registry().at(index).convention);
}

glm::dvec3 ModelCpu::value(glm::vec3 l, glm::vec3 v, uint32_t terms) const {
    const StackGpu* sg = reinterpret_cast<const StackGpu*>(stack_.data());
    g_coat_albedo = coat_albedo_.data();
    g_stack = sg;
    g_use_tables = use_tables_;
    g_convention = model_registry().at(index_).convention;
    g_tables = tables_.empty() ? nullptr : tables_.data();
    CoatParams p = coat_params(sg->layers[0], sg->layers[1]);
    glm::dvec3 f(eval_model(shader_model_of(index_), p, terms, l, v));
    g_stack = nullptr;
    return f;
}

}  // namespace gonio
