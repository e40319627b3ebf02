// Every model bin against a brute-force quadrature of the model's own f.
//
// A model's bin value is the bin average (1/Omega) * integral over the bin of f(l, v) cos(theta_v) dv, Omega the
// bin's projected solid angle (docs/MODELS.md, "Bin integration"). For every model that can represent the stack,
// on every shipped stack (stacks/*.toml), every hard stack (stacks/hard/*.toml) and the coat over copper of an
// independent check (family "coat-over-copper": alpha 0.05, IOR 1.5, tau (0.05, 0.2, 0.4) over alpha 0.1, n (0.27, 0.68, 1.22),
// k (3.6, 2.6, 2.3)), at theta_i = 0, 30, 60, 80 and
// 89 degrees, reflection side and (for models with a transmitted lobe) transmission side, on the reference's
// default grid (1 degree in theta x 2 degrees in phi, bins centred on phi = 0), each device bin
// (ModelEvaluator::evaluate) must lie within 1% of the brute-force bin value plus 1e-4 of the slice's peak
// (per channel; the peak of the slice's continuous part, see below), plus kZero (1e-6 sr^-1, float noise).
//
// The brute force does not use the device's integration (shaders/models.comp, host/models/model_plan.cpp plan()): it
// evaluates f through the CPU twin of the model code (ModelCpu, the same function as model_value_cpu) and
// integrates f cos(theta) sin(theta) over the bin's (theta, phi) rectangle by adaptive cubature:
//   * the bin is first cut at the lobes' peak coordinates (every lobe of these models is centred on the mirror
//     direction, or on the straight-through direction for a transmitted lobe) when they fall inside it, so that a
//     lobe narrower than the nodes sits at a cell corner, where the rules below see its power-law flanks;
//   * each cell carries a 4 x 4 Gauss-Legendre value and the same rule on its two halves across theta and on its
//     two halves across phi; the two differences are the cell's error estimates by direction (of the coarse value:
//     the kept value, corrected by both, is far better);
//   * the cell with the largest estimate is split in two across the direction that changed it more, until the
//     estimates sum to
//     at most 1e-4 of the bin's value (or 1e-6 of the slice's peak times Omega: the device's peak, which sets
//     only where to stop), i.e. until two levels agree. A bin that has not converged after 100 000 evaluations
//     fails the test unless its estimate is 10x below the test's tolerance (float noise in f can keep it moving).
// Delta lobes (roughness 0: a smooth interface, or a lobe whose roughness the model computes below
// kModelDeltaAlpha, host/models/model_plan.h) are distributions: the models evaluate them as GGX at roughness 1e-4
// (MODEL_MIN_ALPHA) and their bin value is, by definition (docs/MODELS.md), the lobe's whole mass in the bin
// containing the mirror (or straight-through) direction. The test takes those terms out of the cubature, computes
// their mass by a half-vector quadrature of the same 1e-4 lobe (tan(theta_m) = a (e^(L u) - 1), fine at the
// peak), and puts it in that bin; a direction on a bin edge (theta_i = 30 degrees lies on one) may go to either
// neighbour, and at the pole (theta_i = 0) to any bin of the first ring; the test takes the candidate where the
// device put more. A term mixing delta and rough lobes is not handled (none of these stacks has one: asserted).
//
// Which bins (the cubature needs 80 evaluations where f is smooth and a few thousand next to a 1e-4 lobe, and
// Belcour's adding loop runs per evaluation in the CPU twin): every bin above 1% of the slice's peak on the device,
// within 3 bins of the peak's bin, in the first two and last two rows (pole, horizon), or differing from one of
// its four neighbours by more than 5% (and 1e-4 of the peak), plus a fixed quarter of the others, which shifts
// from slice to slice: 56% of the 11 million bins in all. Runtime: 1.3 to 1.8 minutes on the 2 shared cores.
#include "model_twin_on_stack.h"
#include "gpu_fixture.h"
#include "model_plan.h"
#include "model_quadrature.h"
#include "models.h"
#include "text_format.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <map>
#include <queue>
#include <stdexcept>
#include <string>
#include <thread>

using namespace gonio;
using namespace gonio_test;

namespace {

class ModelBins : public GpuTest {};

constexpr double kDeg = M_PI / 180;
// Values below this (1/sr) are zero: float rounding of terms that vanish (an index-matched interface's Fresnel
// factor, 0, evaluates to up to 1e-8 near grazing, and its lobe to 1e-6 sr^-1).
constexpr double kZero = 1e-6;

std::vector<std::string> stack_files() {
    std::vector<std::string> files;
    for (const char* dir : {"stacks", "stacks/hard"})
        for (auto& e : std::filesystem::directory_iterator(dir))
            if (e.path().extension() == ".toml") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    return files;
}

// 4-point Gauss-Legendre on [-1, 1]
const double kGx[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
const double kGw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};

struct Rect {
    double t0, t1, p0, p1;
};

// Integral of f(l, v(theta, phi)) cos(theta) sin(theta) over a (theta, phi) rectangle, 4 x 4 Gauss-Legendre.
template <class F>
glm::dvec3 gl16(const F& f, const Rect& r, uint64_t& evals) {
    glm::dvec3 acc(0.0);
    const double ht = 0.5 * (r.t1 - r.t0), hp = 0.5 * (r.p1 - r.p0), ct = 0.5 * (r.t1 + r.t0), cp = 0.5 * (r.p1 + r.p0);
    for (int a = 0; a < 4; ++a) {
        const double th = ct + ht * kGx[a], st = std::sin(th), co = std::cos(th);
        for (int b = 0; b < 4; ++b) {
            const double ph = cp + hp * kGx[b];
            acc += f(st, co, ph) * (kGw[a] * kGw[b] * co * st);
        }
    }
    evals += 16;
    return acc * (ht * hp);
}

// The two halves of a rectangle across theta (dim 0) or phi (dim 1).
std::array<Rect, 2> halves(const Rect& r, int dim) {
    if (dim == 0) {
        const double tm = 0.5 * (r.t0 + r.t1);
        return {Rect{r.t0, tm, r.p0, r.p1}, Rect{tm, r.t1, r.p0, r.p1}};
    }
    const double pm = 0.5 * (r.p0 + r.p1);
    return {Rect{r.t0, r.t1, r.p0, pm}, Rect{r.t0, r.t1, pm, r.p1}};
}

struct Cell {
    Rect r;
    glm::dvec3 coarse;   // 4 x 4 Gauss-Legendre on the cell
    std::array<glm::dvec3, 2> h[2];   // the same rule on its halves across theta and across phi
    glm::dvec3 value;   // coarse + both halvings' corrections (a product rule's errors add by direction)
    double err_dim[2], err;
};

double maxabs(glm::dvec3 v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }

// Adaptive cubature of one bin (see the header); returns the integral (not yet divided by Omega). A cell is split
// across the direction whose halving changes it more (a lobe squeezed into a sliver at grazing incidence is
// refined across the sliver only).
template <class F>
glm::dvec3 adaptive_bin(const F& f, const std::vector<Rect>& start, double floor_abs, double enough_abs,
                        bool& converged, uint64_t& evals) {
    auto make = [&](const Rect& r, glm::dvec3 coarse) {
        Cell c{r, coarse, {}, glm::dvec3(0.0), {0.0, 0.0}, 0.0};
        c.value = coarse;
        for (int d = 0; d < 2; ++d) {
            auto hs = halves(r, d);
            for (int i = 0; i < 2; ++i) c.h[d][i] = gl16(f, hs[i], evals);
            c.err_dim[d] = maxabs(c.h[d][0] + c.h[d][1] - coarse);
            c.value += c.h[d][0] + c.h[d][1] - coarse;
        }
        c.err = c.err_dim[0] + c.err_dim[1];
        return c;
    };
    auto cmp = [](const Cell& a, const Cell& b) { return a.err < b.err; };
    std::priority_queue<Cell, std::vector<Cell>, decltype(cmp)> heap(cmp);
    glm::dvec3 total(0.0);
    double err = 0.0;
    for (const Rect& r : start) {
        Cell c = make(r, gl16(f, r, evals));
        total += c.value;
        err += c.err;
        heap.push(c);
    }
    const uint64_t cap = evals + 100000;
    converged = true;
    while (err > std::max(1e-4 * maxabs(total), floor_abs)) {
        if (evals > cap) {   // float noise in f (kZero) can keep it from settling: enough if 10x below the tolerance
            converged = err <= 0.1 * (0.01 * maxabs(total) + enough_abs);
            break;
        }
        Cell c = heap.top();
        heap.pop();
        total -= c.value;
        err -= c.err;
        const int d = c.err_dim[0] >= c.err_dim[1] ? 0 : 1;
        auto hs = halves(c.r, d);
        for (int i = 0; i < 2; ++i) {
            Cell k = make(hs[i], c.h[d][i]);
            total += k.value;
            err += k.err;
            heap.push(k);
        }
        err = std::max(err, 0.0);
    }
    return total;
}

// The delta terms of a model on a stack at l (the test's own reading of the models, see the header): a bit mask
// of kModelTermTop / kModelTermBase. `mixed` is set where one term holds both delta and rough lobes.
uint32_t delta_terms(size_t m, const Stack& s, double ti, int side, const std::vector<float>* tables, bool& mixed) {
    // a convention variant (id base+g2, +tir) is its base model with other conventions (ModelInfo::convention)
    const std::string& full_id = model_registry()[m].id;
    const std::string id = full_id.substr(0, full_id.find('+'));
    const uint32_t conv = model_registry()[m].convention;
    mixed = false;
    // a model without a plan is integrated as a function, whatever its top interface: its terms are its own (the sheen
    // models' lobe is the fibres', under a smooth index-matched top)
    if (plan_kind_of(id) == PlanKind::BlackBox) return 0u;
    const bool belcour = id.rfind("belcour18", 0) == 0, tm = id == "tm21";
    uint32_t d = 0;
    if (belcour || tm) {
        const double mu = std::cos(ti);
        BelcourLobesHost b = tables ? (tm ? model_lobes_cpu("tm21", s, mu, *tables, conv)
                                          : model_lobes_cpu("belcour18-forward", s, mu, *tables, conv))
                                    : (tm ? model_lobes_cpu("tm21", s, mu, false, conv)
                                          : model_lobes_cpu("belcour18-forward", s, mu, false, conv));
        if (side == 1) return b.alpha_t < kModelDeltaAlpha ? kModelTermBase : 0u;
        if (s.layers[0].roughness == 0.0f) d |= kModelTermTop;
        int smooth = 0, rough = 0;
        for (size_t k = 1; k < b.e.size(); ++k) {
            if (!(b.e[k].x + b.e[k].y + b.e[k].z > 0.0)) continue;
            (b.alpha[k] < kModelDeltaAlpha ? smooth : rough)++;
        }
        if (smooth && rough) mixed = true;
        if (smooth && !rough) d |= kModelTermBase;
        return d;
    }
    const double a0 = s.layers[0].roughness, a1 = s.layers[1].roughness;
    if (a0 == 0.0) d |= kModelTermTop;
    // a conductor base, or a dielectric base's interface (three layers; its diffuse, TERM_DIFFUSE, is never a delta)
    if (s.layers[1].kind == InterfaceKind::Conductor ||
        (s.layers.size() == 3 && s.layers[1].kind == InterfaceKind::Dielectric)) {
        const bool unrefracted = id == "ww09" || id == "albedo-scaling" || id.rfind("gltf-clearcoat", 0) == 0 ||
                                 id == "standard-surface" || id == "standard-surface+osl" ||
                                 id == "materialx-layer";   // base at (l, v), its own roughness
        // the others: the base at refracted directions with max(alpha0, alpha1), or (openpbr) at (l, v) roughened by
        // the coat to sqrt(alpha1^2 + 2 alpha0^2): a delta only when both interfaces are smooth
        if ((unrefracted ? a1 : std::max(a0, a1)) == 0.0) d |= kModelTermBase;
    }
    return d;
}

// Mass of the delta terms at l: the integral of f cos over the hemisphere of the side, in half-vector space
// (v = reflect(l, m), flipped through the surface for the transmission side), steps fine at the 1e-4 peak.
glm::dvec3 delta_mass(const ModelCpu& mc, uint32_t terms, glm::dvec3 l, int side) {
    return half_vector_quadrature(
        [&](glm::vec3 vf) {
            if (side == 1) vf.z = -vf.z;
            return mc.value(glm::vec3(l), vf, terms);
        },
        l, 1e-4, 800, 128);
}

struct Tally {
    int slices = 0, bins = 0, off = 0;
    double worst = 0.0;   // largest |device - brute| / (1% of brute + 1e-4 of the peak)
    std::string worst_where;
};

// What the whole test adds up over its slices.
struct Totals {
    std::map<std::string, Tally> tally;   // per stack family, angle and side
    std::map<std::string, double> seconds;   // brute force, per model
    uint64_t est_bins = 0, est_below = 0;   // bins with an error estimate (f_err), and those whose error is within it
    std::vector<std::string> failures;
    uint64_t evals = 0;
    int off = 0, slices = 0;
};

// One slice: a model at one incident angle and side, its device bins and what the test compares them with.
struct SliceCase {
    const Stack& s;
    size_t index;   // the model's in the registry
    const ModelSlices& ms;
    const ModelCpu& mc;
    const ModelGrid& g;
    size_t a;   // the incident angle's index
    int side;
    const std::vector<glm::dvec3>& dev;   // the device's bins
    const std::vector<std::vector<glm::dvec3>>& errs;   // the device's error estimates (empty: none)
    double ti() const { return g.theta_i_deg[a] * kDeg; }
    glm::dvec3 l() const { return glm::dvec3(std::sin(ti()), 0.0, std::cos(ti())); }
    size_t bins() const { return size_t(g.n_theta) * g.n_phi; }
    double omega(uint32_t t) const {
        const double lo = t * g.dtheta_deg * kDeg, hi = (t + 1) * g.dtheta_deg * kDeg;
        return 0.5 * (std::pow(std::sin(hi), 2) - std::pow(std::sin(lo), 2)) * g.dphi_deg * kDeg;
    }
    std::string where() const {
        return s.name + " " + ms.id + " theta_i " + format_g9(g.theta_i_deg[a]) + (side ? " T" : " R");
    }
};

// GONIO_MODEL_BINS_ANGLES=a,b,...: other incident angles than 0, 30, 60, 80, 89 (for working on one case)
ModelGrid model_bins_grid() {
    ModelGrid g{90, 180, 1.0, 2.0, {0, 30, 60, 80, 89}};
    if (const char* angles = std::getenv("GONIO_MODEL_BINS_ANGLES"); angles && *angles) {
        g.theta_i_deg.clear();
        for (const char* p = angles; *p;) {
            char* end = nullptr;
            g.theta_i_deg.push_back(std::strtod(p, &end));
            p = *end == ',' ? end + 1 : end;
            if (end == p && *p) break;
        }
    }
    return g;
}

// The shipped and hard stacks, the independent check's case (a rough absorbing coat over copper), and an absorbing coat
// index-matched to the exterior over a Lambertian, where the view-dependent absorption exp(-tau / mu) of the
// albedo-scaling models (openpbr's T^(1/mu^t), mu^t = mu) falls to 0 at the horizon; and a dielectric base with smooth
// interfaces, its lobe a delta beside its diffuse (three layers). GONIO_MODEL_BINS_ONLY=word: only the stacks whose
// file name contains it (for working on one case); GONIO_MODEL_BINS_SHARD=i/n: every n-th stack from the i-th (ctest
// runs the list in two entries). Each with its family (shipped, hard, or its own name).
std::vector<std::pair<std::string, Stack>> model_bins_stacks() {
    const char* only = std::getenv("GONIO_MODEL_BINS_ONLY");
    unsigned shard = 0, shards = 1;
    if (const char* sh = std::getenv("GONIO_MODEL_BINS_SHARD"); sh && *sh) {
        if (std::sscanf(sh, "%u/%u", &shard, &shards) != 2 || shards == 0 || shard >= shards)
            throw std::invalid_argument(std::string("GONIO_MODEL_BINS_SHARD=") + sh + ": expected i/n with i < n");
    }
    std::vector<std::string> files = stack_files();
    files.push_back("coat-over-copper");
    files.push_back("absorbing-index-matched");
    files.push_back("smooth-dielectric-base");
    std::vector<std::pair<std::string, Stack>> out;
    for (size_t i = 0; i < files.size(); ++i) {
        const std::string& file = files[i];
        if (i % shards != shard) continue;
        if (only && *only && file.find(only) == std::string::npos) continue;
        const Stack s =
            file == "coat-over-copper"
                ? make_stack("coat-over-copper",
                             {dielectric(1.5f, 0.05f, glm::vec3(0.05f, 0.2f, 0.4f)),
                              conductor(glm::vec3(0.27f, 0.68f, 1.22f), glm::vec3(3.6f, 2.6f, 2.3f), 0.1f)})
            : file == "absorbing-index-matched"
                ? make_stack("absorbing-index-matched",
                             {dielectric(1.0f, 0.3f, glm::vec3(0.2f, 0.5f, 1.0f)), lambertian(glm::vec3(0.8f))})
            : file == "smooth-dielectric-base"
                ? make_stack("smooth-dielectric-base",
                             {dielectric(1.5f, 0.0f, glm::vec3(0.1f, 0.2f, 0.4f)), dielectric(1.8f, 0.0f),
                              lambertian(glm::vec3(0.6f, 0.4f, 0.2f))})
                : parse_stack_file(file);
        const std::string family = file.find("/hard/") != std::string::npos ? "hard"
                                   : file.find('/') == std::string::npos    ? file
                                                                            : "shipped";
        out.emplace_back(family, s);
    }
    return out;
}

double peak_of(const std::vector<glm::dvec3>& f) {
    double peak = 0.0;
    for (const glm::dvec3& v : f) peak = std::max(peak, maxabs(v));
    return peak;
}

// The bins the brute force checks: every bin above 1% of the device's peak, or within 3 bins of the peak's, or in
// the first or last two rows, or differing from a neighbour by more than 5% (and 1e-4 of the peak), plus every 4th of
// the others (a fixed pattern that shifts with the slice, `slice`); the unchecked bins are left out of the comparison.
std::vector<char> bins_to_check(const SliceCase& c, int slice) {
    const ModelGrid& g = c.g;
    const double dev_peak = peak_of(c.dev);
    const uint32_t pt = uint32_t(g.theta_i_deg[c.a] / g.dtheta_deg);
    std::vector<char> check(c.bins(), 0);
    for (size_t b = 0; b < c.bins(); ++b) {
        const uint32_t t = uint32_t(b / g.n_phi), p = uint32_t(b % g.n_phi);
        const double v = maxabs(c.dev[b]);
        bool k = v >= 1e-2 * dev_peak || t < 2 || t + 2 >= g.n_theta ||
                 (std::abs(int(t) - int(pt)) <= 3 && std::abs(int(p) - int(g.n_phi / 2)) <= 3) ||
                 (b * 2654435761u + size_t(slice) * 40503u) % 4 == 0;
        const size_t nbrs[4] = {t > 0 ? b - g.n_phi : b, t + 1 < g.n_theta ? b + g.n_phi : b,
                                p > 0 ? b - 1 : b + g.n_phi - 1, p + 1 < g.n_phi ? b + 1 : b + 1 - g.n_phi};
        for (size_t n : nbrs) {
            const double w = maxabs(c.dev[n]);
            k |= std::fabs(w - v) > 0.05 * std::max(w, v) && std::fabs(w - v) > 1e-4 * dev_peak;
        }
        check[b] = k;
    }
    return check;
}

// The brute force of the continuous terms `cterms` over the checked bins, on all cores.
struct Brute {
    std::vector<glm::dvec3> f;
    std::vector<char> converged;
    uint64_t evals = 0;
    double seconds = 0;
};
Brute brute_force(const SliceCase& c, uint32_t cterms, const std::vector<char>& check) {
    const ModelGrid& g = c.g;
    const size_t nb = c.bins();
    const double dev_peak = peak_of(c.dev), ti = c.ti();
    const glm::dvec3 l = c.l();
    Brute out{std::vector<glm::dvec3>(nb, glm::dvec3(0.0)), std::vector<char>(nb, 1)};
    std::atomic<size_t> next{0};
    std::atomic<uint64_t> evals{0};
    const float zsign = c.side == 0 ? 1.0f : -1.0f;
    auto f = [&](double st, double co, double ph) {
        glm::vec3 v(float(st * std::cos(ph)), float(st * std::sin(ph)), zsign * float(co));
        return c.mc.value(glm::vec3(l), v, cterms);
    };
    auto work = [&] {
        uint64_t my = 0;
        for (size_t b; cterms && (b = next++) < nb;) {
            if (!check[b]) continue;
            const uint32_t t = uint32_t(b / g.n_phi), p = uint32_t(b % g.n_phi);
            Rect r{t * g.dtheta_deg * kDeg, (t + 1) * g.dtheta_deg * kDeg, (p - 0.5) * g.dphi_deg * kDeg,
                   (p + 0.5) * g.dphi_deg * kDeg};
            // cut at the peak's coordinates (theta_i, phi = 180 degrees) where they are inside the bin
            std::vector<double> ts{r.t0}, ps{r.p0};
            if (ti > r.t0 + 1e-12 && ti < r.t1 - 1e-12) ts.push_back(ti);
            if (M_PI > r.p0 + 1e-12 && M_PI < r.p1 - 1e-12) ps.push_back(M_PI);
            ts.push_back(r.t1);
            ps.push_back(r.p1);
            std::vector<Rect> start;
            for (size_t i = 0; i + 1 < ts.size(); ++i)
                for (size_t j = 0; j + 1 < ps.size(); ++j) start.push_back({ts[i], ts[i + 1], ps[j], ps[j + 1]});
            bool ok = true;
            const double w = c.omega(t);
            out.f[b] = adaptive_bin(f, start, std::max(1e-6 * dev_peak, 0.01 * kZero) * w,
                                    (1e-4 * dev_peak + kZero) * w, ok, my) /
                       w;
            out.converged[b] = ok;
        }
        evals += my;
    };
    const auto clock0 = std::chrono::steady_clock::now();
    std::vector<std::thread> pool;
    for (unsigned i = 1; i < std::max(1u, std::thread::hardware_concurrency()); ++i) pool.emplace_back(work);
    work();
    for (auto& th : pool) th.join();
    out.evals = evals;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
    return out;
}

// The delta terms' mass, put in the bin of the mirror (or straight-through) direction: on a bin edge either
// neighbour, at the pole any bin of the first ring; the candidate where the device put more. Returns that bin.
size_t add_delta_mass(const SliceCase& c, uint32_t dterms, std::vector<glm::dvec3>& want) {
    const ModelGrid& g = c.g;
    const glm::dvec3 mass = delta_mass(c.mc, dterms, c.l(), c.side);
    std::vector<size_t> cand;
    if (g.theta_i_deg[c.a] == 0.0) {
        for (uint32_t p = 0; p < g.n_phi; ++p) cand.push_back(p);
    } else {
        const double x = g.theta_i_deg[c.a] / g.dtheta_deg;
        const uint32_t p = g.n_phi / 2;   // phi = 180 degrees
        const double k = std::round(x);
        if (std::fabs(x - k) < 1e-6) {
            if (k >= 1) cand.push_back(size_t(k - 1) * g.n_phi + p);
            if (k < g.n_theta) cand.push_back(size_t(k) * g.n_phi + p);
        } else {
            cand.push_back(size_t(std::floor(x)) * g.n_phi + p);
        }
    }
    size_t best = cand[0];
    for (size_t k : cand)
        if (maxabs(c.dev[k]) > maxabs(c.dev[best])) best = k;
    want[best] += mass / c.omega(uint32_t(best / g.n_phi));
    if (std::getenv("GONIO_MODEL_BINS_VERBOSE")) {
        glm::dvec3 sum(0.0);
        for (size_t b = 0; b < c.bins(); ++b) sum += c.dev[b] * c.omega(uint32_t(b / g.n_phi));
        std::printf("  %s: delta mass %.6g in bin %zu; device sum %.6g; candidates", c.where().c_str(), mass.x, best,
                    sum.x);
        for (size_t k : cand) std::printf(" %zu: %.6g", k, c.dev[k].x * c.omega(uint32_t(k / g.n_phi)));
        std::printf("\n");
    }
    return best;
}

// GONIO_MODEL_BINS_VERBOSE=1: per slice, both bin sums and the six largest differences
void print_verbose(const SliceCase& c, const std::vector<glm::dvec3>& want) {
    if (!std::getenv("GONIO_MODEL_BINS_VERBOSE")) return;
    const uint32_t n_phi = c.g.n_phi;
    glm::dvec3 sd(0.0), sw(0.0);
    std::vector<std::pair<double, size_t>> diffs;
    for (size_t b = 0; b < c.bins(); ++b) {
        const double w = c.omega(uint32_t(b / n_phi));
        sd += c.dev[b] * w;
        sw += want[b] * w;
        diffs.push_back({-std::fabs(c.dev[b].x - want[b].x) * w, b});
    }
    std::printf("  %s: bin sums device %.6f, brute force %.6f\n", c.where().c_str(), sd.x, sw.x);
    std::sort(diffs.begin(), diffs.end());
    for (int k = 0; k < 6; ++k) {
        const size_t b = diffs[k].second;
        std::printf("    bin (%zu,%zu): device %.6g brute %.6g (x Omega: %.3g)\n", b / n_phi, b % n_phi, c.dev[b].x,
                    want[b].x, -diffs[k].first);
    }
}

// Each checked bin of the slice against `want` (the brute force, with the delta terms' mass), into the tally: off
// where |device - want| > 1% of want + 1e-4 of the peak + kZero in a channel. Returns how many bins are off.
int compare_slice(const SliceCase& c, const Brute& brute, const std::vector<glm::dvec3>& want, glm::dvec3 peak,
                  bool deltas, const std::vector<char>& check, Tally& ty, Totals& totals) {
    int off = 0;
    for (size_t b = 0; b < c.bins(); ++b) {
        if (!check[b]) continue;
        const uint32_t t = uint32_t(b / c.g.n_phi), p = uint32_t(b % c.g.n_phi);
        if (!brute.converged[b] && totals.failures.size() < 200)
            totals.failures.push_back(c.where() + " bin " + std::to_string(b) + ": brute force did not converge");
        double e = 0.0;
        for (int k = 0; k < 3; ++k)
            e = std::max(e,
                         std::fabs(c.dev[b][k] - want[b][k]) / (0.01 * std::fabs(want[b][k]) + 1e-4 * peak[k] + kZero));
        ty.bins++;
        if (!c.errs.empty() && !(deltas && maxabs(want[b] - brute.f[b]) > 0.0)) {
            // the estimate against the actual error, beyond float rounding (1e-6 of the peak)
            totals.est_bins++;
            bool within = true;
            for (int k = 0; k < 3; ++k)
                within &= std::fabs(c.dev[b][k] - want[b][k]) <= c.errs[c.a][b][k] + 1e-6 * peak[k] + kZero;
            totals.est_below += within;
        }
        if (e > ty.worst) {
            ty.worst = e;
            char buf[256];
            std::snprintf(buf, sizeof buf, "%s %s bin (%u,%u) %.4g vs %.4g", c.s.name.c_str(), c.ms.id.c_str(), t, p,
                          c.dev[b].x, want[b].x);
            ty.worst_where = buf;
        }
        if (e <= 1.0) continue;
        ++off;
        if (totals.failures.size() < 200) {
            char buf[400];
            std::snprintf(buf, sizeof buf,
                          " bin (theta %u, phi %u): device (%.5g %.5g %.5g), brute force (%.5g %.5g %.5g), peak %.4g",
                          t, p * 2, c.dev[b].x, c.dev[b].y, c.dev[b].z, want[b].x, want[b].y, want[b].z,
                          std::max({peak.x, peak.y, peak.z}));
            totals.failures.push_back(c.where() + buf);
        }
    }
    return off;
}

// One slice: the brute force of its continuous terms, its delta terms' mass, and the comparison with the device.
void check_slice(const SliceCase& c, const std::string& family, const std::vector<float>* tables, Totals& totals) {
    ASSERT_TRUE(c.errs.empty() ||
                (c.errs.size() == (c.side == 0 ? c.ms.f.size() : c.ms.t.size()) && c.errs[c.a].size() == c.bins()))
        << "f_err / t_err must have the shape of f / t";
    ASSERT_EQ(c.dev.size(), c.bins());
    bool mixed = false;
    const uint32_t dterms = delta_terms(c.index, c.s, c.ti(), c.side, tables, mixed);
    ASSERT_FALSE(mixed) << c.s.name << " " << c.ms.id << ": a term mixes delta and rough lobes (not handled)";
    const std::vector<char> check = bins_to_check(c, totals.slices);
    const Brute brute = brute_force(c, kModelTermAll & ~dterms, check);
    totals.evals += brute.evals;
    totals.seconds[c.ms.id] += brute.seconds;
    if (brute.seconds > 2.0)
        std::printf("  (%s: brute force %.1f s, %.3g evaluations)\n", c.where().c_str(), brute.seconds,
                    double(brute.evals));
    glm::dvec3 peak(0.0);   // of the continuous part
    for (const glm::dvec3& v : brute.f) peak = glm::max(peak, v);
    std::vector<glm::dvec3> want = brute.f;
    if (dterms) peak = glm::max(peak, glm::dvec3(1e-7 * maxabs(want[add_delta_mass(c, dterms, want)])));
    print_verbose(c, want);
    Tally& ty = totals.tally[family + " " + (c.side ? "T" : "R") + " " + std::to_string(int(c.g.theta_i_deg[c.a]))];
    ty.slices++;
    totals.slices++;
    const int off = compare_slice(c, brute, want, peak, dterms != 0, check, ty, totals);
    ty.off += off;
    totals.off += off;
    if (off) std::printf("  %-60s: %d bins off\n", c.where().c_str(), off);
}

void print_totals(const Totals& t) {
    std::printf("%-18s %7s %8s %6s %10s  worst bin\n", "family side angle", "slices", "bins", "off", "worst");
    for (auto& [k, ty] : t.tally)
        std::printf("%-18s %7d %8d %6d %10.3g  %s\n", k.c_str(), ty.slices, ty.bins, ty.off, ty.worst,
                    ty.worst_where.c_str());
    std::printf("%d slices, %llu brute-force evaluations, %d bins off\n", t.slices, (unsigned long long)t.evals, t.off);
    for (auto& [id, sec] : t.seconds) std::printf("  brute force %-20s %6.1f s\n", id.c_str(), sec);
    if (t.est_bins)
        std::printf(
            "error estimates (f_err, t_err): the actual error is within the estimate (+1e-6 of the peak) in "
            "%.4f%% of %llu bins\n",
            100.0 * double(t.est_below) / double(t.est_bins), (unsigned long long)t.est_bins);
}

}   // namespace

TEST_F(ModelBins, EveryBinMatchesABruteForceQuadrature) {
    const ModelGrid g = model_bins_grid();
    const ModelOptions opt;
    ModelEvaluator ev(context());
    Totals totals;
    for (const auto& [family, s] : model_bins_stacks()) {
        const std::vector<ModelSlices> all = ev.evaluate(s, g, nullptr, opt);
        for (size_t m = 0; m < all.size(); ++m) {
            if (!all[m].not_applicable.empty()) continue;
            // the model's f as the device evaluates it: with the device's Belcour tables
            const bool tabled = all[m].id.rfind("belcour18", 0) == 0 || all[m].id.rfind("tm21", 0) == 0;
            const StackGpu sg = pack_stack(s);
            const ModelCpu mc(m, sg, opt, tabled ? &ev.belcour_tables(sg) : nullptr);
            const std::vector<float>* tables = tabled && opt.belcour_tables ? &ev.belcour_tables(sg) : nullptr;
            for (size_t a = 0; a < g.theta_i_deg.size(); ++a)
                for (int side = 0; side < (all[m].t.empty() ? 1 : 2); ++side)
                    check_slice(SliceCase{s, m, all[m], mc, g, a, side, side == 0 ? all[m].f[a] : all[m].t[a],
                                          side == 0 ? all[m].f_err : all[m].t_err},
                                family, tables, totals);
        }
    }
    print_totals(totals);
    for (size_t i = 0; i < std::min<size_t>(totals.failures.size(), 40); ++i) ADD_FAILURE() << totals.failures[i];
    EXPECT_EQ(totals.off, 0);
    EXPECT_GE(totals.slices, 200);
}
