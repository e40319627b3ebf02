// heitz_microsurface: drive the authors' random walk on ONE rough interface (Heitz, Hanika, d'Eon, Dachsbacher 2016,
// "Multiple-Scattering Microfacet BSDFs with the Smith Model", supplemental MicrosurfaceScattering.{h,cpp}) the
// way gonio's reference walk is driven, and bin the exits into gonio's grid. Our own code (gonio project); it is
// compiled against a checkout of the authors' two files (README.md, CMakeLists.txt) and is no part of gonio's build.
//
// What is measured
// ----------------
// For one incident direction wi = (sin theta_i, 0, cos theta_i) (directions point away from the surface, z the
// macro-normal: gonio's light direction l) we call Microsurface{Conductor,Dielectric}::sample(wi, order) N times.
// sample() traces one particle through the microsurface (a volumetric random walk over heights: sampleHeight, then
// the microfacet phase function: sampleD_wi, then reflect / refract with probability F) and returns its exit
// direction and the number of scattering events, `order`. Every exit carries weight 1: the walk is analog (the
// phase functions are sampled exactly, no roulette, no weights), so the fraction of paths leaving into a bin B,
// divided by the bin's projected solid angle, estimates the bin average of the BSDF (times nothing: f excludes the
// cosine, as gonio's f) - gonio's bin value F = S1 / (N Omega_proj), se = sqrt((S2/N - (S1/N)^2)/(N-1)) / Omega_proj
// (host/reference/histogram.cpp make_slice), here with S1 = S2 = the count. A path that is not binned (its order
// excluded by --max-order / --only-order) contributes 0: the estimate of that part of the BSDF alone.
//
// Sides, as gonio books them (shaders/lib/bins.glsl): reflection R for wo.z > 0, transmission T (dielectric) for
// wo.z < 0; theta from the exit side's normal (+z for R, -z for T), phi = atan2(y, x) of the exit direction.
// The grid is gonio's default: theta bins [t, t+1) degrees, t = 0..89; phi bins 2 degrees wide, centred on
// multiples of 2 degrees (bin 0 is [-1, 1)).
//
// Order 1 and gonio's single-scattering walk (--only-order 1). The first event of the authors' walk samples the
// height of the first intersection (C1(h) = V^(1 / (1 + Lambda_i))), a visible normal from D_wi, reflects or refracts
// with probability F, and leaves with probability G1(wo, h) (reflection: C1(h)^Lambda_o) or, going down, with
// (1 - C1(h))^Lambda_o. Averaged over h: reflection (1 + Lambda_i) / (1 + Lambda_i + Lambda_o) = G2 / G1(wi), the
// height-correlated Smith G2 that gonio uses; transmission (1 + Lambda_i) B(1 + Lambda_i, 1 + Lambda_o), i.e. G2_T =
// B(1 + Lambda_i, 1 + Lambda_o) (Beta function; the authors' evalSingleScattering uses exactly this), whereas gonio
// (shaders/lib/ggx.glsl ggx_G2, "as pbrt-v4 does") uses 1 / (1 + Lambda_i + Lambda_o) for transmission too. The two
// agree where Lambda_i Lambda_o is small (normal incidence: equal) and differ by about -pi^2/6 Lambda_i Lambda_o
// relative where both are small, more where they are not. With --only-order 1 the driver therefore also bins the
// transmitted order-1 exits a second time with the weight r = [1 / (1 + L_i + L_o)] / B(1 + L_i, 1 + L_o) (our own
// Lambda, same formulas as the authors', in double): the authors' order-1 density of wo times r is exactly the
// single-scattering BTDF with gonio's G2 (the escape factor depends on wo only through Lambda_o), columns f_rw,
// se_rw of the CSV and transmitted_rw in the JSON. R rows of f_rw are f.
//
// The authors' random numbers: one static std::mt19937 (internal linkage, seeded from std::random_device in their
// file) for everything; heitz_unit.cpp reseeds it with --seed. Not thread-safe: this driver is single-threaded (run
// several processes with different seeds for more throughput).
#include "MicrosurfaceScattering.h"   // the authors' header (glm, `using namespace glm`)

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

void heitz_seed(uint32_t seed);   // heitz_unit.cpp

namespace {

constexpr int kNTheta = 90, kNPhi = 180;   // gonio's default grid: dtheta 1 deg, dphi 2 deg
constexpr double kDTheta = 1.0, kDPhi = 2.0;
constexpr int kNBins = kNTheta * kNPhi;
constexpr int kOrders = 8;   // per-order fractions 1..8, then "more than 8"

struct Config {
    std::string interface = "conductor";   // conductor | dielectric
    std::string distribution = "ggx";      // ggx | beckmann
    std::string height = "uniform";        // uniform | gaussian (the authors' two height distributions)
    double alpha = 0.3, eta = 1.5, theta_i = 0;
    double paths = 1e6;
    uint32_t seed = 1;
    int max_order = 0;    // bin only paths of order <= K (0: all)
    int only_order = 0;   // bin only paths of order == K (0: off)
    std::string csv;
};

[[noreturn]] void usage() {
    std::fprintf(stderr,
                 "usage: heitz_microsurface [--interface conductor|dielectric] [--distribution ggx|beckmann]\n"
                 "  [--alpha 0.3] [--eta 1.5] [--theta-i 0] [--paths 1e6] [--seed 1] [--height uniform|gaussian]\n"
                 "  [--max-order K | --only-order K] [--csv FILE]\n"
                 "  --eta: the dielectric's relative IOR, inside over outside (light arrives from outside, +z):\n"
                 "         1.5 from air into glass, 1/1.5 from glass into air\n"
                 "prints one JSON object on stdout\n");
    std::exit(2);
}

Config parse_config(int argc, char **argv) {
    Config c;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto next = [&]() -> const char * {
            if (i + 1 >= argc) usage();
            return argv[++i];
        };
        if (a == "--interface") c.interface = next();
        else if (a == "--distribution") c.distribution = next();
        else if (a == "--height") c.height = next();
        else if (a == "--alpha") c.alpha = std::atof(next());
        else if (a == "--eta") c.eta = std::atof(next());
        else if (a == "--theta-i") c.theta_i = std::atof(next());
        else if (a == "--paths") c.paths = std::atof(next());
        else if (a == "--seed") c.seed = uint32_t(std::strtoul(next(), nullptr, 10));
        else if (a == "--max-order") c.max_order = std::atoi(next());
        else if (a == "--only-order") c.only_order = std::atoi(next());
        else if (a == "--csv") c.csv = next();
        else usage();
    }
    const bool ok = (c.interface == "conductor" || c.interface == "dielectric") &&
                    (c.distribution == "ggx" || c.distribution == "beckmann") &&
                    (c.height == "uniform" || c.height == "gaussian") && c.alpha > 0 && c.eta > 0 &&
                    c.theta_i >= 0 && c.theta_i < 90 && c.paths >= 2 && c.max_order >= 0 && c.only_order >= 0 &&
                    !(c.max_order > 0 && c.only_order > 0);
    if (!ok) usage();
    return c;
}

// gonio's binning (shaders/lib/bins.glsl bin_index; host/reference/histogram.cpp BinGrid), in double.
int bin_of(double x, double y, double z) {
    const double theta = std::atan2(std::sqrt(x * x + y * y), std::fabs(z)) * 180.0 / M_PI;
    const int t = std::min(int(std::max(0.0, theta / kDTheta)), kNTheta - 1);
    const double phi = (x == 0.0 && y == 0.0) ? 0.0 : std::atan2(y, x) * 180.0 / M_PI;
    long p = std::lround(std::floor(phi / kDPhi + 0.5)) % long(kNPhi);
    if (p < 0) p += kNPhi;
    return t * kNPhi + int(p);
}

double projected_solid_angle(int t) {
    const double s_lo = std::sin(t * kDTheta * M_PI / 180.0), s_hi = std::sin((t + 1) * kDTheta * M_PI / 180.0);
    return 0.5 * (s_hi * s_hi - s_lo * s_lo) * kDPhi * M_PI / 180.0;
}

// Smith Lambda of an isotropic GGX or Beckmann surface for a direction on either side (|z|), in double: the
// authors' formulas (MicrosurfaceSlope{GGX,Beckmann}::Lambda), with std::erfc for their erf approximation.
double smith_lambda(double x, double y, double z, double alpha, bool beckmann) {
    const double s = std::sqrt(x * x + y * y), c = std::fabs(z);
    if (s == 0.0) return 0.0;
    if (!beckmann) return 0.5 * (std::sqrt(1.0 + alpha * alpha * s * s / (c * c)) - 1.0);
    const double a = c / (alpha * s);
    return 0.5 * (std::exp(-a * a) / (a * std::sqrt(M_PI)) - std::erfc(a));
}

// r = [1 / (1 + L_i + L_o)] / B(1 + L_i, 1 + L_o): turns the authors' order-1 transmission (Beta-function G2) into
// gonio's (1 / (1 + L_i + L_o)); see the header comment.
double transmission_g2_ratio(double li, double lo) {
    const double log_beta = std::lgamma(1.0 + li) + std::lgamma(1.0 + lo) - std::lgamma(2.0 + li + lo);
    return std::exp(-std::log1p(li + lo) - log_beta);
}

struct Tally {
    std::vector<double> s1r = std::vector<double>(kNBins), s1t = std::vector<double>(kNBins);   // counts (w = 1)
    std::vector<double> s1rw = std::vector<double>(kNBins), s2rw = std::vector<double>(kNBins);  // T, weight r
    uint64_t order_r[kOrders + 1] = {}, order_t[kOrders + 1] = {};   // all paths by side and order (1..8, >8)
    uint64_t binned_r = 0, binned_t = 0, all_r = 0, all_t = 0;
    uint64_t order_sum = 0, max_order = 0;
    uint64_t fallback = 0;   // returns of exactly (0, 0, 1): the authors' "if NaN" fallback (or, unlikely, a true exit)
    uint64_t horizon = 0;    // wo.z == 0 or not finite: not binned
};

void walk(const Microsurface &surface, const Config &c, Tally &t) {
    const double ti = c.theta_i * M_PI / 180.0;
    const vec3 wi(float(std::sin(ti)), 0.0f, float(std::cos(ti)));
    const bool beckmann = c.distribution == "beckmann";
    const double li = smith_lambda(wi.x, wi.y, wi.z, c.alpha, beckmann);
    const uint64_t n = uint64_t(c.paths);
    for (uint64_t i = 0; i < n; ++i) {
        int order = 0;
        const vec3 wo = surface.sample(wi, order);   // virtual: MicrosurfaceDielectric overrides it
        if (wo.x == 0.0f && wo.y == 0.0f && wo.z == 1.0f) ++t.fallback;
        if (!(wo.z != 0.0f) || !std::isfinite(wo.x) || !std::isfinite(wo.y) || !std::isfinite(wo.z)) {
            ++t.horizon;
            continue;
        }
        const bool trans = wo.z < 0.0f;
        const int ob = std::min(std::max(order, 1), kOrders + 1) - 1;   // order 0 cannot happen (wi.z > 0)
        ++(trans ? t.order_t : t.order_r)[ob];
        ++(trans ? t.all_t : t.all_r);
        t.order_sum += uint64_t(order);
        t.max_order = std::max<uint64_t>(t.max_order, uint64_t(order));
        if (c.only_order > 0 && order != c.only_order) continue;
        if (c.max_order > 0 && order > c.max_order) continue;
        const int b = bin_of(wo.x, wo.y, wo.z);
        if (!trans) {
            t.s1r[b] += 1.0;
            ++t.binned_r;
            continue;
        }
        t.s1t[b] += 1.0;
        ++t.binned_t;
        if (c.only_order == 1) {
            const double r = transmission_g2_ratio(li, smith_lambda(wo.x, wo.y, wo.z, c.alpha, beckmann));
            t.s1rw[b] += r;
            t.s2rw[b] += r * r;
        }
    }
}

// Per bin F = S1 / (N Omega), se = sqrt((S2/N - (S1/N)^2) / (N - 1)) / Omega (gonio's make_slice).
void bin_values(const std::vector<double> &s1, const std::vector<double> *s2, double N, std::vector<double> &F,
                std::vector<double> &SE) {
    F.assign(kNBins, 0.0);
    SE.assign(kNBins, 0.0);
    for (int t = 0; t < kNTheta; ++t) {
        const double omega = projected_solid_angle(t);
        for (int p = 0; p < kNPhi; ++p) {
            const int b = t * kNPhi + p;
            const double mean = s1[b] / N, m2 = (s2 ? (*s2)[b] : s1[b]) / N;
            F[b] = mean / omega;
            SE[b] = std::sqrt(std::max(0.0, m2 - mean * mean) / (N - 1)) / omega;
        }
    }
}

// The fraction p of N paths and its standard error (weights 0 or 1).
double binomial_se(double p, double N) { return std::sqrt(std::max(0.0, p * (1.0 - p)) / (N - 1)); }

// The weighted total of a histogram (sum S1 / N, sum S2 / N) and its standard error (one bin per path).
void weighted_total(const std::vector<double> &s1, const std::vector<double> &s2, double N, double &tot, double &se) {
    double a = 0, b = 0;
    for (int i = 0; i < kNBins; ++i) {
        a += s1[i];
        b += s2[i];
    }
    tot = a / N;
    se = std::sqrt(std::max(0.0, b / N - tot * tot) / (N - 1));
}

// --csv: pbrt_layered's format (side,theta_lo,theta_hi,phi_lo,phi_hi,f,se), R rows, then T rows for a dielectric;
// with --only-order 1 on a dielectric also f_rw,se_rw (T reweighted to gonio's transmission G2; R rows: f, se).
bool write_csv(const Config &c, const Tally &t, double N) {
    FILE *f = std::fopen(c.csv.c_str(), "w");
    if (!f) {
        std::perror(c.csv.c_str());
        return false;
    }
    const bool dielectric = c.interface == "dielectric", rw = dielectric && c.only_order == 1;
    std::vector<double> FR, SR, FT, ST, FW, SW;
    bin_values(t.s1r, nullptr, N, FR, SR);
    bin_values(t.s1t, nullptr, N, FT, ST);
    bin_values(t.s1rw, &t.s2rw, N, FW, SW);
    std::fprintf(f, "side,theta_lo,theta_hi,phi_lo,phi_hi,f,se%s\n", rw ? ",f_rw,se_rw" : "");
    for (int side = 0; side < (dielectric ? 2 : 1); ++side)
        for (int th = 0; th < kNTheta; ++th)
            for (int p = 0; p < kNPhi; ++p) {
                const int b = th * kNPhi + p;
                const double fv = side ? FT[b] : FR[b], sv = side ? ST[b] : SR[b];
                std::fprintf(f, "%c,%g,%g,%g,%g,%.9g,%.9g", side ? 'T' : 'R', th * kDTheta, (th + 1) * kDTheta,
                             (p - 0.5) * kDPhi, (p + 0.5) * kDPhi, fv, sv);
                if (rw) std::fprintf(f, ",%.9g,%.9g", side ? FW[b] : fv, side ? SW[b] : sv);
                std::fprintf(f, "\n");
            }
    std::fclose(f);
    return true;
}

void print_fractions(const char *key, const uint64_t *counts, double N) {
    std::printf(", \"%s\": [", key);
    for (int k = 0; k < kOrders; ++k) std::printf("%s%.6g", k ? ", " : "", double(counts[k]) / N);
    std::printf("], \"%s_over_%d\": %.6g", key, kOrders, double(counts[kOrders]) / N);
}

}  // namespace

int main(int argc, char **argv) {
    const Config c = parse_config(argc, argv);
    heitz_seed(c.seed);
    const bool uniform = c.height == "uniform", beckmann = c.distribution == "beckmann";
    const float a = float(c.alpha);
    Tally t;
    const auto t0 = std::chrono::steady_clock::now();
    if (c.interface == "conductor") {
        MicrosurfaceConductor surface(uniform, beckmann, a, a);   // F = 1 on every facet (no Fresnel)
        walk(surface, c, t);
    } else {
        MicrosurfaceDielectric surface(uniform, beckmann, a, a, float(c.eta));
        walk(surface, c, t);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double N = double(uint64_t(c.paths));
    if (!c.csv.empty() && !write_csv(c, t, N)) return 1;

    const double R = double(t.binned_r) / N, T = double(t.binned_t) / N;
    double Trw = 0, Trw_se = 0;
    weighted_total(t.s1rw, t.s2rw, N, Trw, Trw_se);
    uint64_t all[kOrders + 1];
    for (int k = 0; k <= kOrders; ++k) all[k] = t.order_r[k] + t.order_t[k];
    std::printf("{\"tool\": \"heitz_microsurface\", \"interface\": \"%s\", \"distribution\": \"%s\", \"height\": \"%s\", "
                "\"alpha\": %g, \"eta\": %.9g, \"theta_i\": %g, \"seed\": %u, \"paths\": %llu, \"max_order\": %d, "
                "\"only_order\": %d, \"seconds\": %.4f, \"paths_per_second\": %.6g, "
                "\"reflected\": %.8g, \"reflected_se\": %.3g, \"transmitted\": %.8g, \"transmitted_se\": %.3g",
                c.interface.c_str(), c.distribution.c_str(), c.height.c_str(), c.alpha, c.eta, c.theta_i, c.seed,
                (unsigned long long)uint64_t(N), c.max_order, c.only_order, seconds, N / seconds, R,
                binomial_se(R, N), T, binomial_se(T, N));
    if (c.interface == "dielectric" && c.only_order == 1)
        std::printf(", \"transmitted_rw\": %.8g, \"transmitted_rw_se\": %.3g", Trw, Trw_se);
    std::printf(", \"reflected_all\": %.8g, \"transmitted_all\": %.8g, \"mean_order\": %.6g, \"max_order_seen\": %llu, "
                "\"fallback_001\": %llu, \"horizon_or_nonfinite\": %llu",
                double(t.all_r) / N, double(t.all_t) / N, double(t.order_sum) / N, (unsigned long long)t.max_order,
                (unsigned long long)t.fallback, (unsigned long long)t.horizon);
    print_fractions("order_fraction", all, N);
    print_fractions("order_fraction_R", t.order_r, N);
    print_fractions("order_fraction_T", t.order_t, N);
    std::printf("}\n");
    return 0;
}
