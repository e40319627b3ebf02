// pbrt_layered: drive pbrt-v4's LayeredBxDF (CoatedDiffuseBxDF / CoatedConductorBxDF) the way gonio's
// reference walk is driven, and bin the samples into gonio's grid. Our own code (gonio project); it is
// compiled against a pbrt-v4 checkout (see README.md / CMakeLists.txt) and is no part of gonio's build.
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
// Spectra: pbrt carries NSpectrumSamples (4) wavelength samples per path. All spectra here are constant
// (every lane the same value), so one lane (lane 0) is the result; the other lanes are computed anyway, as
// pbrt always does. gonio likewise carries 3 channels per path.
#include <pbrt/bxdfs.h>
#include <pbrt/options.h>
#include <pbrt/util/rng.h>
#include <pbrt/util/spectrum.h>
#include <pbrt/util/vecmath.h>

#include <algorithm>
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
    std::string base = "diffuse";   // diffuse | conductor
    double coat_ior = 1.5, coat_alpha = 0.05;
    double thickness = 0.05;   // = gonio's optical_depth tau (pbrt's medium has sigma_t = 1 per unit thickness)
    double medium_albedo = 0;  // = gonio's scattering_albedo
    double g = 0;              // = gonio's phase_g
    double base_albedo = 0.6;  // Lambertian base
    double cond_eta = 0.2, cond_k = 3.0, cond_alpha = 0.2;   // absolute; divided by coat_ior for pbrt
    double theta_i = 30;
    double paths = 1e6;
    int max_depth = 256, n_samples = 1, threads = 2;
    uint64_t seed = 1;
    bool importance = true;
    std::string csv;   // optional per-bin output
};

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

struct Tally {
    std::vector<double> s1, s2;   // per reflection bin: sum of w, sum of w^2
    uint64_t returned = 0, none = 0, transmitted = 0;
    double s1_trans = 0, s2_refl = 0;   // transmitted sum; sum of w^2 over all reflected paths
    Tally() : s1(kNBins, 0.0), s2(kNBins, 0.0) {}
};

template <typename BxDF>
void walk(const BxDF &bxdf, Vector3f wo, TransportMode mode, uint64_t n, uint64_t seed, int thread,
          Tally &t) {
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
        double w = double(bs->f[0]) * AbsCosTheta(bs->wi) / double(bs->pdf);
        if (!(w > 0) || !std::isfinite(w)) {
            ++t.none;
            continue;
        }
        if (bs->wi.z <= 0) {   // transmission (none for the opaque stacks here)
            ++t.transmitted;
            t.s1_trans += w;
            continue;
        }
        double theta = std::acos(std::clamp(double(bs->wi.z), -1.0, 1.0)) * 180.0 / M_PI;
        double phi = std::atan2(double(bs->wi.y), double(bs->wi.x)) * 180.0 / M_PI;
        int b = theta_bin(theta) * kNPhi + phi_bin(phi);
        t.s1[b] += w;
        t.s2[b] += w * w;
        t.s2_refl += w * w;
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
                 "usage: pbrt_layered [--base diffuse|conductor] [--coat-ior 1.5] [--coat-alpha 0.05]\n"
                 "  [--tau 0.05] [--medium-albedo 0] [--g 0] [--base-albedo 0.6]\n"
                 "  [--cond-eta N --cond-k K --cond-alpha A]   (absolute IOR, as gonio's TOML)\n"
                 "  [--theta-i 30] [--paths 1e6] [--max-depth 256] [--threads 2] [--seed 1]\n"
                 "  [--mode importance|radiance] [--csv FILE]\n"
                 "prints one JSON object on stdout\n");
    std::exit(2);
}

}  // namespace

int main(int argc, char **argv) {
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
        else if (a == "--theta-i") c.theta_i = std::atof(next());
        else if (a == "--paths") c.paths = std::atof(next());
        else if (a == "--max-depth") c.max_depth = std::atoi(next());
        else if (a == "--threads") c.threads = std::atoi(next());
        else if (a == "--seed") c.seed = std::strtoull(next(), nullptr, 10);
        else if (a == "--mode") c.importance = std::string(next()) != "radiance";
        else if (a == "--csv") c.csv = next();
        else usage();
    }
    if (c.threads < 1 || c.paths < 2 || (c.base != "diffuse" && c.base != "conductor")) usage();

    // pbrt's global options: LayeredBxDF seeds its internal RNG with Hash(GetOptions().seed, wo).
    Options = new PBRTOptions;
    Options->seed = int(c.seed);

    const double ti = c.theta_i * M_PI / 180.0;
    const Vector3f wo(std::sin(ti), 0, std::cos(ti));   // gonio's light direction l
    const TransportMode mode = c.importance ? TransportMode::Importance : TransportMode::Radiance;
    // pbrt's TrowbridgeReitzDistribution takes alpha directly (the roughness remap is in materials.cpp only);
    // gonio's roughness is GGX alpha.
    DielectricBxDF top(Float(c.coat_ior), TrowbridgeReitzDistribution(Float(c.coat_alpha), Float(c.coat_alpha)));
    const SampledSpectrum medium_albedo(Float(c.medium_albedo));

    const uint64_t total = uint64_t(c.paths);
    std::vector<Tally> tallies(c.threads);
    auto t0 = std::chrono::steady_clock::now();
    auto run_all = [&](auto &bxdf) {
        std::vector<std::thread> pool;
        for (int t = 0; t < c.threads; ++t) {
            uint64_t n = total / c.threads + (uint64_t(t) < total % c.threads ? 1 : 0);
            pool.emplace_back([&, t, n] { walk(bxdf, wo, mode, n, c.seed, t, tallies[t]); });
        }
        for (auto &th : pool) th.join();
    };
    if (c.base == "diffuse") {
        CoatedDiffuseBxDF bxdf(top, DiffuseBxDF(SampledSpectrum(Float(c.base_albedo))), Float(c.thickness),
                               medium_albedo, Float(c.g), c.max_depth, c.n_samples);
        run_all(bxdf);
    } else {
        // pbrt's ConductorBxDF wants eta, k relative to the medium above it (CoatedConductorMaterial divides
        // by the interface IOR the same way); gonio's TOML gives them absolute.
        ConductorBxDF bottom(TrowbridgeReitzDistribution(Float(c.cond_alpha), Float(c.cond_alpha)),
                             SampledSpectrum(Float(c.cond_eta / c.coat_ior)),
                             SampledSpectrum(Float(c.cond_k / c.coat_ior)));
        CoatedConductorBxDF bxdf(top, bottom, Float(c.thickness), medium_albedo, Float(c.g), c.max_depth,
                                 c.n_samples);
        run_all(bxdf);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    Tally sum;
    for (auto &t : tallies) {
        for (int b = 0; b < kNBins; ++b) {
            sum.s1[b] += t.s1[b];
            sum.s2[b] += t.s2[b];
        }
        sum.returned += t.returned;
        sum.none += t.none;
        sum.transmitted += t.transmitted;
        sum.s1_trans += t.s1_trans;
        sum.s2_refl += t.s2_refl;
    }

    // gonio's make_slice / relative_ses: F = mean / Omega, se = sqrt((S2/N - mean^2) / (N - 1)) / Omega; the
    // bins with F > 1% of the slice's peak F; nearest-rank quantiles of se / F.
    const double N = double(total);
    std::vector<double> F(kNBins), SE(kNBins);
    double peak = 0, albedo = 0;
    for (int t = 0; t < kNTheta; ++t) {
        double omega = projected_solid_angle(t);
        for (int p = 0; p < kNPhi; ++p) {
            int b = t * kNPhi + p;
            double mean = sum.s1[b] / N;
            double var = std::max(0.0, sum.s2[b] / N - mean * mean) / (N - 1);
            F[b] = mean / omega;
            SE[b] = std::sqrt(var) / omega;
            peak = std::max(peak, F[b]);
            albedo += mean;
        }
    }
    std::vector<double> rel;
    for (int b = 0; b < kNBins; ++b)
        if (F[b] > 0.01 * peak) rel.push_back(SE[b] / F[b]);
    const double median = nearest_rank(rel, 0.5), p90 = nearest_rank(rel, 0.9), worst = nearest_rank(rel, 1.0);
    const double albedo_se = std::sqrt(std::max(0.0, sum.s2_refl / N - albedo * albedo) / (N - 1));
    const double pps = N / seconds;
    const double n_1pct = N * (median / 0.01) * (median / 0.01);

    if (!c.csv.empty()) {
        FILE *f = std::fopen(c.csv.c_str(), "w");
        if (!f) { std::perror(c.csv.c_str()); return 1; }
        std::fprintf(f, "theta_lo,theta_hi,phi_lo,phi_hi,f,se\n");
        for (int t = 0; t < kNTheta; ++t)
            for (int p = 0; p < kNPhi; ++p) {
                int b = t * kNPhi + p;
                std::fprintf(f, "%g,%g,%g,%g,%.9g,%.9g\n", t * kDTheta, (t + 1) * kDTheta, (p - 0.5) * kDPhi,
                             (p + 0.5) * kDPhi, F[b], SE[b]);
            }
        std::fclose(f);
    }

    std::printf(
        "{\"tool\": \"pbrt_layered\", \"base\": \"%s\", \"coat_ior\": %g, \"coat_alpha\": %g, \"tau\": %g, "
        "\"medium_albedo\": %g, \"g\": %g, \"base_albedo\": %g, \"cond_eta\": %g, \"cond_k\": %g, "
        "\"cond_alpha\": %g, \"theta_i\": %g, \"mode\": \"%s\", \"max_depth\": %d, \"threads\": %d, "
        "\"seed\": %llu, \"paths\": %llu, \"seconds\": %.6f, \"paths_per_second\": %.6g, "
        "\"reflected\": %.8g, \"reflected_se\": %.3g, \"transmitted\": %.8g, \"no_sample_fraction\": %.6g, "
        "\"rse_bins\": %zu, \"peak_f\": %.8g, \"median_rse\": %.6g, \"p90_rse\": %.6g, \"worst_rse\": %.6g, "
        "\"paths_to_1pct_median_rse\": %.6g, \"seconds_to_1pct_median_rse\": %.6g}\n",
        c.base.c_str(), c.coat_ior, c.coat_alpha, c.thickness, c.medium_albedo, c.g, c.base_albedo, c.cond_eta,
        c.cond_k, c.cond_alpha, c.theta_i, c.importance ? "importance" : "radiance", c.max_depth, c.threads,
        (unsigned long long)c.seed, (unsigned long long)total, seconds, pps, albedo, albedo_se, sum.s1_trans / N,
        double(sum.none) / N, rel.size(), peak, median, p90, worst, n_1pct, n_1pct / pps);
    return 0;
}
