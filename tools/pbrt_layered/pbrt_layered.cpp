// pbrt_layered: drive pbrt-v4's LayeredBxDF (CoatedDiffuseBxDF / CoatedConductorBxDF, or a dielectric slab:
// LayeredBxDF<DielectricBxDF, DielectricBxDF, false>, see BottomDielectricBxDF) the way gonio's reference
// walk is driven, and bin the samples into gonio's grid. Our own code (gonio project); it is compiled against
// a pbrt-v4 checkout (see README.md / CMakeLists.txt) and is no part of gonio's build.
//
// What is measured
// ----------------
// For one incident direction we call bxdf.Sample_f(wo, uc, u, mode) N times with fresh uniform numbers
// (uc, u) from a pbrt RNG (one PCG32 stream per thread) and bin each returned sample's direction wi with
// the weight  w = bs->f * AbsCosTheta(bs->wi) / bs->pdf.
//
// What LayeredBxDF::Sample_f estimates (pbrt-v4 src/pbrt/bxdfs.h): it samples the entrance interface
// (top.Sample_f(wo)); a reflection there is returned as is. Otherwise it runs a random walk inside the
// layers: exponential free flights in a medium of sigma_t = 1 per unit thickness (when albedo != 0:
// scattering events multiply f by albedo * p_HG and pdf by p_HG; when albedo == 0, f is multiplied by the
// transmittance Tr(thickness, w) = exp(-thickness / |w.z|) per crossing), and at each interface it samples
// that interface's BxDF, multiplying f by bs->f and pdf by bs->pdf (and f by |cos| between events), with
// Russian roulette after depth 3 when f/pdf < 0.25 (pdf is divided by the survival probability). It
// returns when the walk transmits out through an interface, or nothing when the walk is absorbed by
// roulette or exceeds maxDepth (maxDepth counts interface/medium events). The returned f and pdf are the
// path's product of BxDF values and of sampling densities (pdfIsProportional = true: pdf is NOT the
// marginal density of wi), and the final |cos(wi)| is not in f. Hence
//     w = f * |cos wi| / pdf
// is the walk's throughput, and E[ w * 1{wi in B} ] = integral over B of f_layered(wo, wi) |cos wi| dwi:
// exactly what a bin of gonio's histogram estimates (gonio: F = S1 / (N * Omega_proj), the bin average of
// f). Unbiased up to maxDepth truncation; nSamples only matters for f() and PDF(), not Sample_f.
//
// Direction mapping. gonio: the light arrives from l = (sin theta_i, 0, cos theta_i) (directions point
// away from the surface, z is the normal) and it bins the exit directions v of light paths. pbrt's
// Sample_f(wo, ...) samples wi given wo; with TransportMode::Importance it traces a particle coming from
// wo (pbrt's light-tracing convention), so wo = l, wi = v and mode = Importance is the literal "light
// path" reading. With TransportMode::Radiance the only difference in a dielectric is the 1/eta^2 radiance
// scaling on refraction, which cancels on a path that enters and leaves through the same exterior medium
// (air, eta 1, here): the reflected histogram is the same per path either way (--mode radiance to check).
// And for a reciprocal BRDF f(l, v) = f(v, l), so binning wi for wo = l gives gonio's histogram also in the
// "camera path" reading.
//
// Transparent slab (--base dielectric): LayeredBxDF<DielectricBxDF, DielectricBxDF, false>, the top interface
// the coat's DielectricBxDF, the bottom a second DielectricBxDF between the slab and the medium below. The
// bottom's eta convention, from pbrt-v4 (5f7a6068) src/pbrt/bxdfs.h and bxdfs.cpp:
//  * LayeredBxDF::Sample_f (bxdfs.h:744-753) picks the bottom at z == 0 and samples it as
//    interface.Sample_f(-w, ...) in the SAME local frame as the top (no flip): a walk reaching the bottom
//    travels down (w.z < 0), so the bottom sees wo = -w with wo.z > 0, i.e. from the slab's side.
//  * DielectricBxDF (class at bxdfs.h:167) takes eta = (IOR on the -z side) / (IOR on the +z side): its
//    Sample_f refracts with Refract(wo, n = +z, eta) (bxdfs.cpp:103, 149), which uses eta for wo.z > 0 and
//    1 / eta for wo.z < 0 (util/scattering.h:22-30); f/PDF likewise etap = cosTheta_o > 0 ? eta : 1 / eta
//    (bxdfs.cpp:179-181). The "outside" is +z. For the top, +z is the exterior (air) and -z the slab:
//    eta = coat IOR (as pbrt's CoatedDiffuseMaterial / DielectricMaterial pass it).
//  * So for the bottom, +z (outside) is the slab and -z the medium below: eta = n_below / n_slab, here
//    1.0 / 1.5 = 0.667: gonio's relative eta of the bottom interface (n_below / n_above) exactly.
//  --bottom-ior is absolute (the medium below, as gonio's TOML `ior` of the last layer) and is divided by
//  --coat-ior here. twoSided = false (the template's third argument): light arrives from above (wo.z > 0,
//  enteredTop, bxdfs.h:668), and a walk leaving through the bottom is returned with wi.z < 0 (transmission).
// Transmitted samples (wi.z < 0) are binned in a second histogram, the T side, as gonio books them: theta
// measured from -z (the exit side's normal), phi = atan2(y, x) of the exit direction, the same grid. In
// importance mode pbrt applies no 1/eta^2 on refraction; in radiance mode the slab's two refractions scale by
// 1/1.5^2 and 1.5^2 (bxdfs.cpp:111, 165), which cancel: the T histogram is the same in both modes too.
// The median rse (gonio's relative_ses, host/reference/histogram.cpp): per side, the bins above 1% of that
// side's peak; the nearest-rank median over the pooled list of both sides (an opaque stack: R only).
//
// Spectra: pbrt carries NSpectrumSamples (4) wavelength samples per path. All spectra here are constant
// (every lane the same value), so one lane (lane 0) is the result; the other lanes are computed anyway, as
// pbrt always does. gonio likewise carries 3 channels per path.
//
// Spectral mode (--cond-nk FILE --lambda L1[,L2,L3,L4]): the conductor's n(lambda), k(lambda) are read from
// a table (gonio's data/spectra/*.csv format: '#' comment lines, a header line, then rows nm,n,k) into two
// pbrt PiecewiseLinearSpectrum objects (pbrt's own class: linear between the rows, as gonio reads the table).
// The lanes of a pbrt SampledWavelengths are set to the given wavelengths (the last one repeated to fill
// the 4 lanes), pbrt evaluates both spectra there (PiecewiseLinearSpectrum::Sample), divides them by the
// coat's IOR (relative to the medium above, as CoatedConductorMaterial does) and the ConductorBxDF gets
// those SampledSpectrum values, so each lane of every walk carries its own wavelength. Each given
// wavelength's lane is binned into its own histogram: a walk's direction does not depend on the lane
// (nothing here disperses: the coat's IOR is one value), only its weight f[lane] does, so every lane is an
// unbiased estimate of the BRDF at its wavelength (pbrt's Russian roulette uses the largest lane's f/pdf,
// which changes the variance, not the expectation). Lanes of one run share their paths (correlated with
// each other, independent of every other run).
#include <pbrt/bxdfs.h>
#include <pbrt/options.h>
#include <pbrt/util/rng.h>
#include <pbrt/util/spectrum.h>
#include <pbrt/util/vecmath.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <sstream>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

using namespace pbrt;

namespace {

struct Config {
    std::string base = "diffuse";   // diffuse | conductor | dielectric (a transparent slab)
    double coat_ior = 1.5, coat_alpha = 0.05;
    double thickness = 0.05;   // = gonio's optical_depth tau (pbrt's medium has sigma_t = 1 per unit thickness)
    double medium_albedo = 0;  // = gonio's scattering_albedo
    double g = 0;              // = gonio's phase_g
    double base_albedo = 0.6;  // Lambertian base
    double cond_eta = 0.2, cond_k = 3.0, cond_alpha = 0.2;   // absolute; divided by coat_ior for pbrt
    double bottom_ior = 1.0, bottom_alpha = 0.2;   // --base dielectric: absolute IOR below; divided by coat_ior
    double theta_i = 30;
    double paths = 1e6;
    int max_depth = 256, n_samples = 1, threads = 2;
    uint64_t seed = 1;
    bool importance = true;
    std::string csv;   // optional per-bin output
    std::string nk_file;          // spectral mode: the conductor's n, k table (nm,n,k rows)
    std::vector<double> lambdas;  // spectral mode: wavelengths (nm), one per lane, at most NSpectrumSamples
};

// The slab's bottom face. pbrt-v4's TopOrBottomBxDF<TopBxDF, BottomBxDF> (bxdfs.h:384-400), which
// LayeredBxDF::Sample_f uses to hold "the interface at z", overloads operator= for const TopBxDF * and
// const BottomBxDF *; with both DielectricBxDF the two overloads collide and LayeredBxDF<DielectricBxDF,
// DielectricBxDF, false> does not compile. So the bottom is this subclass: a distinct type that is the same
// DielectricBxDF (constructor and every member inherited, nothing overridden).
struct BottomDielectricBxDF : DielectricBxDF {
    using DielectricBxDF::DielectricBxDF;
};
using SlabBxDF = LayeredBxDF<DielectricBxDF, BottomDielectricBxDF, false>;

constexpr int kNTheta = 90, kNPhi = 180;   // gonio's default grid: dtheta 1 deg, dphi 2 deg
constexpr double kDTheta = 1.0, kDPhi = 2.0;
constexpr int kNBins = kNTheta * kNPhi;

// gonio's BinGrid (host/reference/histogram.cpp): theta bins [t, t+1) deg, phi bins centred on multiples of dphi.
inline int theta_bin(double theta_deg) {
    return std::min(int(std::max(0.0, theta_deg / kDTheta)), kNTheta - 1);
}
inline int phi_bin(double phi_deg) {
    long j = std::lround(std::floor(phi_deg / kDPhi + 0.5));
    j %= long(kNPhi);
    if (j < 0) j += kNPhi;
    return int(j);
}
inline double projected_solid_angle(int t) {
    double lo = t * kDTheta * M_PI / 180.0, hi = (t + 1) * kDTheta * M_PI / 180.0;
    double s_lo = std::sin(lo), s_hi = std::sin(hi);
    return 0.5 * (s_hi * s_hi - s_lo * s_lo) * kDPhi * M_PI / 180.0;
}

// One histogram per binned lane (1 without --lambda; one per given wavelength with it).
struct Tally {
    int nl = 1;
    std::vector<double> s1, s2;   // per lane and reflection bin (lane-major): sum of w, sum of w^2
    std::vector<double> s1t, s2t; // the same for the transmission bins (the T side)
    uint64_t returned = 0, none = 0, transmitted = 0;
    // returned samples whose f (any binned lane) or pdf is not finite (float overflow of LayeredBxDF's running
    // products: f and pdf are carried separately in 32-bit Float); such a sample's weight is lost (counted in none)
    uint64_t nonfinite = 0, inf_pdf = 0;   // inf_pdf: of those, the ones whose pdf is +inf
    std::vector<double> s1_trans, s2_refl;   // per lane: transmitted sum; sum of w^2 over all reflected paths
    std::vector<double> s2_trans;            // per lane: sum of w^2 over all transmitted paths
    // per lane: sum of w over the samples whose pdf or f exceeds the largest 32-bit float (in a float64 build:
    // the weight that a float32 build would have lost at the end of the walk, at least)
    std::vector<double> s1_over_float;
    explicit Tally(int nl = 1)
        : nl(nl), s1(size_t(nl) * kNBins, 0.0), s2(size_t(nl) * kNBins, 0.0), s1t(size_t(nl) * kNBins, 0.0),
          s2t(size_t(nl) * kNBins, 0.0), s1_trans(nl, 0.0), s2_refl(nl, 0.0), s2_trans(nl, 0.0),
          s1_over_float(nl, 0.0) {}
};

// Reads a gonio data/spectra table: '#' comment lines and blank lines skipped, one header line (the first
// line whose first field is not a number), then rows wavelength_nm,n,k in increasing wavelength.
void read_nk_table(const std::string &path, std::vector<Float> &nm, std::vector<Float> &n,
                   std::vector<Float> &k) {
    std::ifstream in(path);
    if (!in) {
        std::perror(path.c_str());
        std::exit(1);
    }
    std::string line;
    int lineno = 0;
    while (std::getline(in, line)) {
        ++lineno;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        size_t first = line.find_first_not_of(" \t");
        if (first == std::string::npos || line[first] == '#') continue;
        std::stringstream ss(line);
        std::string f0, f1, f2;
        std::getline(ss, f0, ',');
        std::getline(ss, f1, ',');
        std::getline(ss, f2, ',');
        char *end = nullptr;
        double l = std::strtod(f0.c_str(), &end);
        if (end == f0.c_str()) {   // the header line
            if (!nm.empty()) {
                std::fprintf(stderr, "%s:%d: not a number: '%s'\n", path.c_str(), lineno, f0.c_str());
                std::exit(1);
            }
            continue;
        }
        if (f1.empty() || f2.empty() || (!nm.empty() && !(l > nm.back()))) {
            std::fprintf(stderr, "%s:%d: expected nm,n,k in increasing wavelength\n", path.c_str(), lineno);
            std::exit(1);
        }
        nm.push_back(Float(l));
        n.push_back(Float(std::atof(f1.c_str())));
        k.push_back(Float(std::atof(f2.c_str())));
    }
    if (nm.size() < 2) {
        std::fprintf(stderr, "%s: fewer than 2 rows\n", path.c_str());
        std::exit(1);
    }
}

template <typename BxDF>
void walk(const BxDF &bxdf, Vector3f wo, TransportMode mode, uint64_t n, uint64_t seed, int thread,
          Tally &t, const std::vector<int> &lanes) {
    RNG rng(uint64_t(thread) + 1, MixBits(seed));
    for (uint64_t i = 0; i < n; ++i) {
        Float uc = rng.Uniform<Float>();
        Point2f u(rng.Uniform<Float>(), rng.Uniform<Float>());
        pstd::optional<BSDFSample> bs = bxdf.Sample_f(wo, uc, u, mode);
        if (!bs || bs->pdf == 0) {
            ++t.none;
            continue;
        }
        ++t.returned;
        bool finite = std::isfinite(bs->pdf);
        for (int l : lanes) finite &= std::isfinite(bs->f[l]);
        if (!finite) ++t.nonfinite;
        if (std::isinf(bs->pdf)) ++t.inf_pdf;
        const double g = AbsCosTheta(bs->wi) / double(bs->pdf);
        // A lane's weight may be 0 where another's is not (the direction is shared): skip the sample only
        // when no lane has a positive finite weight, otherwise add each lane's (possibly 0) weight.
        bool any = false, bad = false;
        for (int l : lanes) {
            double w = double(bs->f[l]) * g;
            any |= w > 0;
            bad |= !std::isfinite(w) || w < 0;
        }
        if (!any || bad) {
            ++t.none;
            continue;
        }
        bool over = double(bs->pdf) > double(std::numeric_limits<float>::max());
        for (int l : lanes) over |= double(bs->f[l]) > double(std::numeric_limits<float>::max());
        if (over)
            for (size_t j = 0; j < lanes.size(); ++j) t.s1_over_float[j] += double(bs->f[lanes[j]]) * g;
        // The side: R (wi.z > 0) or T (wi.z < 0; none for the opaque stacks). gonio's bins (shaders/lib/bins.glsl):
        // theta from the exit side's normal (+z for R, -z for T), phi = atan2(y, x) of the exit direction.
        const bool trans = bs->wi.z <= 0;
        if (trans) ++t.transmitted;
        double theta = std::acos(std::clamp(std::abs(double(bs->wi.z)), 0.0, 1.0)) * 180.0 / M_PI;
        double phi = std::atan2(double(bs->wi.y), double(bs->wi.x)) * 180.0 / M_PI;
        int b = theta_bin(theta) * kNPhi + phi_bin(phi);
        std::vector<double> &s1 = trans ? t.s1t : t.s1, &s2 = trans ? t.s2t : t.s2;
        for (size_t j = 0; j < lanes.size(); ++j) {
            double w = double(bs->f[lanes[j]]) * g;
            size_t bj = j * kNBins + b;
            s1[bj] += w;
            s2[bj] += w * w;
            if (trans) {
                t.s1_trans[j] += w;
                t.s2_trans[j] += w * w;
            } else {
                t.s2_refl[j] += w * w;
            }
        }
    }
}

double nearest_rank(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    size_t k = size_t(std::ceil(std::clamp(q, 0.0, 1.0) * double(v.size())));
    return v[std::min(v.size(), std::max<size_t>(k, 1)) - 1];
}

void usage() {
    std::fprintf(stderr,
                 "usage: pbrt_layered [--base diffuse|conductor|dielectric] [--coat-ior 1.5] [--coat-alpha 0.05]\n"
                 "  [--tau 0.05] [--medium-albedo 0] [--g 0] [--base-albedo 0.6]\n"
                 "  [--cond-eta N --cond-k K --cond-alpha A]   (absolute IOR, as gonio's TOML)\n"
                 "  [--bottom-ior 1.0 --bottom-alpha 0.2]   --base dielectric: a slab; the ABSOLUTE IOR of the medium\n"
                 "      below it (gonio's TOML), divided by --coat-ior for pbrt; T side binned too\n"
                 "  [--theta-i 30] [--paths 1e6] [--max-depth 256] [--threads 2] [--seed 1]\n"
                 "  [--mode importance|radiance] [--csv FILE]\n"
                 "  [--cond-nk TABLE.csv --lambda L1[,L2,L3,L4]]   spectral: the conductor's n, k from a table\n"
                 "      (nm,n,k rows, gonio's data/spectra format) at up to 4 wavelengths (nm), one per lane\n"
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
        if (a == "--base") c.base = next();
        else if (a == "--coat-ior") c.coat_ior = std::atof(next());
        else if (a == "--coat-alpha") c.coat_alpha = std::atof(next());
        else if (a == "--tau") c.thickness = std::atof(next());
        else if (a == "--medium-albedo") c.medium_albedo = std::atof(next());
        else if (a == "--g") c.g = std::atof(next());
        else if (a == "--base-albedo") c.base_albedo = std::atof(next());
        else if (a == "--cond-eta") c.cond_eta = std::atof(next());
        else if (a == "--cond-k") c.cond_k = std::atof(next());
        else if (a == "--cond-alpha") c.cond_alpha = std::atof(next());
        else if (a == "--bottom-ior") c.bottom_ior = std::atof(next());
        else if (a == "--bottom-alpha") c.bottom_alpha = std::atof(next());
        else if (a == "--theta-i") c.theta_i = std::atof(next());
        else if (a == "--paths") c.paths = std::atof(next());
        else if (a == "--max-depth") c.max_depth = std::atoi(next());
        else if (a == "--threads") c.threads = std::atoi(next());
        else if (a == "--seed") c.seed = std::strtoull(next(), nullptr, 10);
        else if (a == "--mode") c.importance = std::string(next()) != "radiance";
        else if (a == "--csv") c.csv = next();
        else if (a == "--cond-nk") c.nk_file = next();
        else if (a == "--lambda") {
            std::stringstream ss(next());
            std::string tok;
            while (std::getline(ss, tok, ',')) c.lambdas.push_back(std::atof(tok.c_str()));
        } else usage();
    }
    if (c.nk_file.empty() != c.lambdas.empty() || c.lambdas.size() > size_t(NSpectrumSamples)) usage();
    if (!c.nk_file.empty() && c.base != "conductor") usage();
    if (c.threads < 1 || c.paths < 2 || (c.base != "diffuse" && c.base != "conductor" && c.base != "dielectric"))
        usage();
    if (c.base == "dielectric" && !(c.bottom_ior > 0 && c.bottom_ior != c.coat_ior)) usage();
    return c;
}

// The conductor's absolute n and k per lane: the constants of --cond-eta, --cond-k, or (spectral mode) pbrt's
// PiecewiseLinearSpectrum of the table's n and k at the lanes of swl, set to the given wavelengths (the last
// repeated to fill NSpectrumSamples). Exits 2 for a wavelength outside the table (pbrt would return 0 there).
void conductor_spectra(const Config &c, SampledWavelengths &swl, SampledSpectrum &eta, SampledSpectrum &k) {
    eta = SampledSpectrum(Float(c.cond_eta));
    k = SampledSpectrum(Float(c.cond_k));
    if (c.lambdas.empty()) return;
    std::vector<Float> nm, n, kk;
    read_nk_table(c.nk_file, nm, n, kk);
    for (double l : c.lambdas)
        if (!(l >= nm.front() && l <= nm.back())) {
            std::fprintf(stderr, "--lambda %g outside %s's %g-%g nm\n", l, c.nk_file.c_str(), double(nm.front()),
                         double(nm.back()));
            std::exit(2);
        }
    PiecewiseLinearSpectrum eta_s{pstd::span<const Float>(nm), pstd::span<const Float>(n)};
    PiecewiseLinearSpectrum k_s{pstd::span<const Float>(nm), pstd::span<const Float>(kk)};
    const int nl = int(c.lambdas.size());
    for (int i = 0; i < NSpectrumSamples; ++i) swl[i] = Float(c.lambdas[std::min(i, nl - 1)]);
    eta = eta_s.Sample(swl);
    k = k_s.Sample(swl);
}

// The Sample_f loop on c.threads threads over the stack's layered BxDF; the threads' tallies summed. Returns seconds.
double run_walks(const Config &c, const SampledSpectrum &cond_eta, const SampledSpectrum &cond_k,
                 const std::vector<int> &lanes, Tally &sum) {
    // pbrt's global options: LayeredBxDF seeds its internal RNG with Hash(GetOptions().seed, wo).
    Options = new PBRTOptions;
    Options->seed = int(c.seed);
    const double ti = c.theta_i * M_PI / 180.0;
    const Vector3f wo(std::sin(ti), 0, std::cos(ti));   // gonio's light direction l
    const TransportMode mode = c.importance ? TransportMode::Importance : TransportMode::Radiance;
    // pbrt's TrowbridgeReitzDistribution takes alpha directly (the roughness remap is in materials.cpp only);
    // gonio's roughness is GGX alpha. NB: EffectivelySmooth() is max(alpha) < 1e-3f (util/scattering.h:137): alpha
    // 0.001 is rough in the float build (== 1e-3f, as gonio's 32-bit roughness) but a perfect mirror in a
    // PBRT_FLOAT_AS_DOUBLE build; there pass --coat-alpha 0.0010000000474974513 (the float value) instead.
    DielectricBxDF top(Float(c.coat_ior), TrowbridgeReitzDistribution(Float(c.coat_alpha), Float(c.coat_alpha)));
    const SampledSpectrum medium_albedo(Float(c.medium_albedo));
    const uint64_t total = uint64_t(c.paths);
    const int nl = int(lanes.size());
    std::vector<Tally> tallies(c.threads, Tally(nl));
    auto t0 = std::chrono::steady_clock::now();
    auto run_all = [&](auto &bxdf) {
        std::vector<std::thread> pool;
        for (int t = 0; t < c.threads; ++t) {
            uint64_t n = total / c.threads + (uint64_t(t) < total % c.threads ? 1 : 0);
            pool.emplace_back([&, t, n] { walk(bxdf, wo, mode, n, c.seed, t, tallies[t], lanes); });
        }
        for (auto &th : pool) th.join();
    };
    if (c.base == "diffuse") {
        CoatedDiffuseBxDF bxdf(top, DiffuseBxDF(SampledSpectrum(Float(c.base_albedo))), Float(c.thickness),
                               medium_albedo, Float(c.g), c.max_depth, c.n_samples);
        run_all(bxdf);
    } else if (c.base == "dielectric") {
        // The slab's bottom face: eta = n_below / n_slab (pbrt's DielectricBxDF: IOR of the -z side over the +z
        // side; the bottom is sampled with wo on the slab's side, +z; see the comment at the top of this file).
        BottomDielectricBxDF bottom(Float(c.bottom_ior / c.coat_ior),
                                    TrowbridgeReitzDistribution(Float(c.bottom_alpha), Float(c.bottom_alpha)));
        SlabBxDF bxdf(top, bottom, Float(c.thickness), medium_albedo, Float(c.g), c.max_depth, c.n_samples);
        run_all(bxdf);
    } else {
        // pbrt's ConductorBxDF wants eta, k relative to the medium above it (CoatedConductorMaterial divides
        // by the interface IOR the same way); gonio's TOML gives them absolute.
        ConductorBxDF bottom(TrowbridgeReitzDistribution(Float(c.cond_alpha), Float(c.cond_alpha)),
                             cond_eta / Float(c.coat_ior), cond_k / Float(c.coat_ior));
        CoatedConductorBxDF bxdf(top, bottom, Float(c.thickness), medium_albedo, Float(c.g), c.max_depth,
                                 c.n_samples);
        run_all(bxdf);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (auto &t : tallies) {
        for (size_t b = 0; b < sum.s1.size(); ++b) {
            sum.s1[b] += t.s1[b];
            sum.s2[b] += t.s2[b];
            sum.s1t[b] += t.s1t[b];
            sum.s2t[b] += t.s2t[b];
        }
        sum.returned += t.returned;
        sum.none += t.none;
        sum.transmitted += t.transmitted;
        sum.nonfinite += t.nonfinite;
        sum.inf_pdf += t.inf_pdf;
        for (int j = 0; j < nl; ++j) {
            sum.s1_trans[j] += t.s1_trans[j];
            sum.s2_refl[j] += t.s2_refl[j];
            sum.s2_trans[j] += t.s2_trans[j];
            sum.s1_over_float[j] += t.s1_over_float[j];
        }
    }
    return seconds;
}

// Per lane and side, the bins as gonio's make_slice / relative_ses compute them: F = mean / Omega, se =
// sqrt((S2/N - mean^2) / (N - 1)) / Omega; per side, the bins with F > 1% of that side's peak F; the nearest-rank
// quantiles of se / F over the pooled list of both sides (gonio's relative_ses: per side and channel, pooled).
// A side with no weight (T of an opaque stack) contributes no bins, as gonio's opaque stacks have no T side.
struct Stats {
    std::vector<double> F, SE, FT, SET;   // R side, T side: per lane and bin (lane-major)
    std::vector<double> peak, peak_t, albedo, albedo_se, trans, trans_se, median, p90, worst, median_r, median_t;
    std::vector<size_t> nrel, nrel_t;   // pooled bins; of those, the T side's
};
Stats summarise(const Tally &sum, double N, int nl) {
    Stats st;
    for (auto *v : {&st.F, &st.SE, &st.FT, &st.SET}) v->assign(sum.s1.size(), 0.0);
    for (auto *v : {&st.peak, &st.peak_t, &st.albedo, &st.albedo_se, &st.trans, &st.trans_se, &st.median, &st.p90,
                    &st.worst, &st.median_r, &st.median_t})
        v->assign(nl, 0.0);
    st.nrel.assign(nl, 0);
    st.nrel_t.assign(nl, 0);
    for (int j = 0; j < nl; ++j) {
        std::vector<double> rel_all;
        for (int side = 0; side < 2; ++side) {
            const std::vector<double> &s1 = side ? sum.s1t : sum.s1, &s2 = side ? sum.s2t : sum.s2;
            std::vector<double> &F = side ? st.FT : st.F, &SE = side ? st.SET : st.SE;
            double &peak = side ? st.peak_t[j] : st.peak[j];
            double &tot = side ? st.trans[j] : st.albedo[j];
            for (int t = 0; t < kNTheta; ++t) {
                double omega = projected_solid_angle(t);
                for (int p = 0; p < kNPhi; ++p) {
                    size_t b = size_t(j) * kNBins + t * kNPhi + p;
                    double mean = s1[b] / N;
                    double var = std::max(0.0, s2[b] / N - mean * mean) / (N - 1);
                    F[b] = mean / omega;
                    SE[b] = std::sqrt(var) / omega;
                    peak = std::max(peak, F[b]);
                    tot += mean;
                }
            }
            std::vector<double> rel;
            if (peak > 0)
                for (int b = 0; b < kNBins; ++b) {
                    size_t bj = size_t(j) * kNBins + b;
                    if (F[bj] > 0.01 * peak) rel.push_back(SE[bj] / F[bj]);
                }
            (side ? st.median_t[j] : st.median_r[j]) = nearest_rank(rel, 0.5);
            if (side) st.nrel_t[j] = rel.size();
            rel_all.insert(rel_all.end(), rel.begin(), rel.end());
        }
        st.nrel[j] = rel_all.size();
        st.median[j] = nearest_rank(rel_all, 0.5);
        st.p90[j] = nearest_rank(rel_all, 0.9);
        st.worst[j] = nearest_rank(rel_all, 1.0);
        st.albedo_se[j] = std::sqrt(std::max(0.0, sum.s2_refl[j] / N - st.albedo[j] * st.albedo[j]) / (N - 1));
        st.trans_se[j] = std::sqrt(std::max(0.0, sum.s2_trans[j] / N - st.trans[j] * st.trans[j]) / (N - 1));
    }
    return st;
}

// --csv: per bin its side (R; and T for a transmissive stack, --base dielectric), edges and, per lane, f and se
// (without --lambda: f, se; with it: f.L, se.L per wavelength L). T rows: theta from -z, phi of the exit direction.
bool write_csv(const Config &c, const Stats &st, int nl) {
    FILE *f = std::fopen(c.csv.c_str(), "w");
    if (!f) {
        std::perror(c.csv.c_str());
        return false;
    }
    std::fprintf(f, "side,theta_lo,theta_hi,phi_lo,phi_hi");
    for (int j = 0; j < nl; ++j) {
        if (!c.lambdas.empty()) std::fprintf(f, ",f.%g,se.%g", c.lambdas[j], c.lambdas[j]);
        else std::fprintf(f, ",f,se");
    }
    std::fprintf(f, "\n");
    const int n_sides = c.base == "dielectric" ? 2 : 1;
    for (int side = 0; side < n_sides; ++side) {
        const std::vector<double> &F = side ? st.FT : st.F, &SE = side ? st.SET : st.SE;
        for (int t = 0; t < kNTheta; ++t)
            for (int p = 0; p < kNPhi; ++p) {
                int b = t * kNPhi + p;
                std::fprintf(f, "%c,%g,%g,%g,%g", side ? 'T' : 'R', t * kDTheta, (t + 1) * kDTheta,
                             (p - 0.5) * kDPhi, (p + 0.5) * kDPhi);
                for (int j = 0; j < nl; ++j)
                    std::fprintf(f, ",%.9g,%.9g", F[size_t(j) * kNBins + b], SE[size_t(j) * kNBins + b]);
                std::fprintf(f, "\n");
            }
    }
    std::fclose(f);
    return true;
}

}  // namespace

int main(int argc, char **argv) {
    const Config c = parse_config(argc, argv);
    const bool spectral = !c.lambdas.empty();
    const int nl = spectral ? int(c.lambdas.size()) : 1;
    std::vector<int> lanes(nl);
    for (int j = 0; j < nl; ++j) lanes[j] = j;
    SampledWavelengths swl = SampledWavelengths::SampleUniform(0.5f);
    SampledSpectrum cond_eta, cond_k;   // absolute
    conductor_spectra(c, swl, cond_eta, cond_k);
    const uint64_t total = uint64_t(c.paths);
    Tally sum(nl);
    const double seconds = run_walks(c, cond_eta, cond_k, lanes, sum);
    const double N = double(total);
    const Stats st = summarise(sum, N, nl);
    const double pps = N / seconds;
    const double n_1pct = N * (st.median[0] / 0.01) * (st.median[0] / 0.01);
    if (!c.csv.empty() && !write_csv(c, st, nl)) return 1;
    std::printf(
        "{\"tool\": \"pbrt_layered\", \"base\": \"%s\", \"coat_ior\": %g, \"coat_alpha\": %g, \"tau\": %g, "
        "\"medium_albedo\": %g, \"g\": %g, \"base_albedo\": %g, \"cond_eta\": %g, \"cond_k\": %g, "
        "\"cond_alpha\": %g, \"bottom_ior\": %g, \"bottom_eta_rel\": %g, \"bottom_alpha\": %g, \"theta_i\": %g, \"mode\": \"%s\", \"max_depth\": %d, \"threads\": %d, "
        "\"seed\": %llu, \"paths\": %llu, \"seconds\": %.6f, \"paths_per_second\": %.6g, "
        "\"reflected\": %.8g, \"reflected_se\": %.3g, \"transmitted\": %.8g, \"transmitted_se\": %.3g, \"no_sample_fraction\": %.6g, \"nonfinite_fraction\": %.6g, \"inf_pdf_fraction\": %.6g, "
        "\"rse_bins\": %zu, \"rse_bins_T\": %zu, \"peak_f\": %.8g, \"peak_f_T\": %.8g, \"median_rse_R\": %.6g, "
        "\"median_rse_T\": %.6g, \"median_rse\": %.6g, \"p90_rse\": %.6g, \"worst_rse\": %.6g, "
        "\"paths_to_1pct_median_rse\": %.6g, \"seconds_to_1pct_median_rse\": %.6g, \"weight_over_float_max\": %.6g",
        c.base.c_str(), c.coat_ior, c.coat_alpha, c.thickness, c.medium_albedo, c.g, c.base_albedo,
        double(cond_eta[0]), double(cond_k[0]), c.cond_alpha, c.bottom_ior, c.bottom_ior / c.coat_ior,
        c.bottom_alpha, c.theta_i, c.importance ? "importance" : "radiance",
        c.max_depth, c.threads, (unsigned long long)c.seed, (unsigned long long)total, seconds, pps, st.albedo[0],
        st.albedo_se[0], st.trans[0], st.trans_se[0], double(sum.none) / N, double(sum.nonfinite) / N,
        double(sum.inf_pdf) / N, st.nrel[0], st.nrel_t[0], st.peak[0], st.peak_t[0], st.median_r[0], st.median_t[0],
        st.median[0], st.p90[0], st.worst[0],
        n_1pct, n_1pct / pps, sum.s1_over_float[0] / N);
    if (spectral) {
        // Per given wavelength (lane): pbrt's n, k there (absolute, from the table) and the lane's results.
        std::printf(", \"cond_nk\": \"%s\", \"lanes\": [", c.nk_file.c_str());
        for (int j = 0; j < nl; ++j)
            std::printf("%s{\"lambda_nm\": %.9g, \"n\": %.9g, \"k\": %.9g, \"eta_rel\": %.9g, \"k_rel\": %.9g, "
                        "\"reflected\": %.8g, \"reflected_se\": %.3g, \"transmitted\": %.8g, "
                        "\"transmitted_se\": %.3g, \"peak_f\": %.8g, "
                        "\"median_rse\": %.6g, \"weight_over_float_max\": %.6g}",
                        j ? ", " : "", double(swl[j]), double(cond_eta[j]), double(cond_k[j]),
                        double(cond_eta[j] / Float(c.coat_ior)), double(cond_k[j] / Float(c.coat_ior)),
                        st.albedo[j], st.albedo_se[j], st.trans[j], st.trans_se[j], st.peak[j], st.median[j],
                        sum.s1_over_float[j] / N);
        std::printf("]");
    }
    std::printf("}\n");
    return 0;
}
