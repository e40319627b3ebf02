// colour_error.cpp: see colour_error.h.
#include "colour_error.h"
#include "histogram.h"
#include "json.h"
#include "statistics.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <stdexcept>

namespace gonio {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kNoiseDraws = 15;

Colour3 c3(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
glm::dvec3 v3(const Colour3& c) { return {c[0], c[1], c[2]}; }

double quantile(const std::vector<double>& v, double q) { return nearest_rank_quantile(v, q); }

}   // namespace

SpectralReference spectral_reference(const SpectralResult& spectral, size_t a, int side) {
    const SimResult& first = spectral.groups.front();
    const std::vector<std::array<double, 3>> w = xyz_weights(spectral.bands);
    SpectralReference ref;
    ref.angle = a;
    ref.side = side;
    ref.theta_i_deg = first.angles[a].theta_i_deg;
    ref.n_phi = first.n_phi;
    ref.slice = spectral_slice(spectral, a, side);
    ref.group_se.resize(spectral.groups.size());
    for (size_t g = 0; g < spectral.groups.size(); ++g) {
        const Slice gs = make_slice(spectral.groups[g], a, Side(side));
        ref.group_se[g].assign(gs.se.size(), glm::dvec3(0));
        for (size_t c = 0; c < 3 && 3 * g + c < spectral.bands.count(); ++c) {
            const glm::dvec3 wb(w[3 * g + c][0], w[3 * g + c][1], w[3 * g + c][2]);
            for (size_t i = 0; i < gs.se.size(); ++i) ref.group_se[g][i] += wb * gs.se[i][int(c)];
        }
    }
    for (size_t b = 0; b < spectral.bands.count(); ++b) {
        const EnergyBook book = energy_book(spectral.groups[b / 3], a);
        const double v = (side == 0 ? book.reflected : book.transmitted)[int(b % 3)];
        ref.albedo += glm::dvec3(w[b][0], w[b][1], w[b][2]) * v;
    }
    return ref;
}

ColourErrorSlice colour_error_slice(const SpectralReference& ref, const OtherColours& other) {
    const SpectralSlice& s = ref.slice;
    const size_t a = ref.angle;
    const int side = ref.side;
    ColourErrorSlice e;
    e.theta_i_deg = ref.theta_i_deg;
    e.side = side;
    if (other.f_xyz.size() != s.xyz.size() || other.se_xyz.size() != s.xyz.size())
        throw std::logic_error("colour_error: the colours compared differ in bins");
    const std::vector<std::vector<glm::dvec3>>& group_se = ref.group_se;
    e.albedo_spectral = ref.albedo;
    e.albedo_other = other.albedo_xyz;
    e.albedo_de = colour_difference(c3(e.albedo_spectral), c3(e.albedo_other));
    std::vector<double> de2000, itp, noise;
    double worst = -1;
    e.bins.resize(s.xyz.size());
    for (size_t i = 0; i < s.xyz.size(); ++i) {
        ColourErrorBin& bin = e.bins[i];
        bin.theta = uint32_t(i / ref.n_phi);
        bin.phi = uint32_t(i % ref.n_phi);
        bin.xyz_spectral = kPi * s.xyz[i];
        bin.xyz_other = kPi * other.f_xyz[i];
        bin.de = colour_difference(c3(bin.xyz_spectral), c3(bin.xyz_other));
        // the noise: the median CIEDE2000 between two draws of the spectral colour, one perturbed by the spectral
        // run's errors (a normal deviate per pass, its three bands fully correlated: the same paths), the other by
        // the other colours' (one deviate for their three channels; none for a model), kNoiseDraws draws
        const glm::dvec3 other_se = kPi * other.se_xyz[i];
        std::mt19937 rng(uint32_t(a * 7919u + size_t(side) * 104729u + i));
        std::normal_distribution<double> normal;
        double draws[kNoiseDraws];
        for (double& d : draws) {
            glm::dvec3 ds(0);
            for (const std::vector<glm::dvec3>& g : group_se) ds += normal(rng) * g[i];
            const glm::dvec3 dr = normal(rng) * other_se;
            d = delta_e_2000(xyz_to_lab(c3(bin.xyz_spectral + kPi * ds)), xyz_to_lab(c3(bin.xyz_spectral + dr)));
        }
        std::nth_element(draws, draws + kNoiseDraws / 2, draws + kNoiseDraws);
        bin.de2000_noise = draws[kNoiseDraws / 2];
        bin.lit = bin.xyz_spectral.y >= kLitReflectanceFactor;
        if (!bin.lit) continue;
        de2000.push_back(bin.de.de2000);
        itp.push_back(bin.de.de_itp);
        noise.push_back(bin.de2000_noise);
        if (bin.de.de2000 > worst) {
            worst = bin.de.de2000;
            e.max_bin = i;
        }
    }
    // X's, Y's and Z's median relative errors over the bins above 1% of the peak Y, each
    double peak = 0;
    for (const glm::dvec3& x : s.xyz) peak = std::max(peak, x.y);
    for (int c = 0; c < 3; ++c) {
        std::vector<double> rse_s, rse_o;
        for (size_t i = 0; i < s.xyz.size(); ++i) {
            if (!(s.xyz[i].y > 0.01 * peak)) continue;
            if (s.xyz[i][c] > 0) rse_s.push_back(s.xyz_se[i][c] / s.xyz[i][c]);
            if (other.f_xyz[i][c] > 0) rse_o.push_back(other.se_xyz[i][c] / other.f_xyz[i][c]);
        }
        e.xyz_median_rse_spectral[c] = quantile(rse_s, 0.5);
        e.xyz_median_rse_other[c] = quantile(rse_o, 0.5);
    }
    e.lit = de2000.size();
    e.median_de2000 = quantile(de2000, 0.5);
    e.p95_de2000 = quantile(de2000, 0.95);
    e.max_de2000 = quantile(de2000, 1);
    e.median_de_itp = quantile(itp, 0.5);
    e.p95_de_itp = quantile(itp, 0.95);
    e.max_de_itp = quantile(itp, 1);
    e.median_de2000_noise = quantile(noise, 0.5);
    return e;
}

std::vector<ColourErrorSlice> colour_error(const SpectralResult& spectral, const SimResult& rgb) {
    const SimResult& first = spectral.groups.front();
    if (rgb.angles.size() != first.angles.size() || rgb.n_theta != first.n_theta || rgb.n_phi != first.n_phi ||
        rgb.n_sides != first.n_sides)
        throw std::logic_error("colour_error: the RGB and spectral runs differ in angles or bins");
    std::vector<ColourErrorSlice> out;
    for (size_t a = 0; a < first.angles.size(); ++a)
        for (int side = 0; side < int(first.n_sides); ++side) {
            const Slice r = make_slice(rgb, a, Side(side));
            OtherColours o;   // the RGB run's linear sRGB in XYZ (the matrix is positive: se maps as an upper bound)
            for (size_t i = 0; i < r.f.size(); ++i) {
                o.f_xyz.push_back(v3(linear_srgb_to_xyz(c3(r.f[i]))));
                o.se_xyz.push_back(v3(linear_srgb_to_xyz(c3(r.se[i]))));
            }
            const EnergyBook rb = energy_book(rgb, a);
            o.albedo_xyz = v3(linear_srgb_to_xyz(c3(side == 0 ? rb.reflected : rb.transmitted)));
            out.push_back(colour_error_slice(spectral_reference(spectral, a, side), o));
        }
    return out;
}

double spectral_cost_at_equal_error(const std::vector<ColourErrorSlice>& e, const std::array<double, 2>& seconds) {
    double worst = 0;
    for (int c = 0; c < 3; ++c) {
        double sum = 0;
        size_t n = 0;
        for (const ColourErrorSlice& s : e) {
            if (!(s.xyz_median_rse_other[c] > 0)) continue;
            const double q = s.xyz_median_rse_spectral[c] / s.xyz_median_rse_other[c];
            sum += q * q;
            ++n;
        }
        if (n) worst = std::max(worst, seconds[0] / seconds[1] * sum / double(n));
    }
    return worst;
}

Json colour_error_json(const ColourErrorSlice& s, const BinGrid& grid, const std::string& other) {
    const ColourErrorBin& worst = s.bins[s.max_bin];
    return {{"theta_i", s.theta_i_deg},
            {"side", s.side == 0 ? "reflection" : "transmission"},
            {"albedo",
             {{"xyz_spectral", json_rgb(s.albedo_spectral)},
              {"xyz_" + other, json_rgb(s.albedo_other)},
              {"de2000", json_number(s.albedo_de.de2000)},
              {"de_itp", json_number(s.albedo_de.de_itp)}}},
            {"lit_bins", s.lit},
            {"de2000", {{"median", s.median_de2000}, {"p95", s.p95_de2000}, {"max", s.max_de2000}}},
            {"de_itp", {{"median", s.median_de_itp}, {"p95", s.p95_de_itp}, {"max", s.max_de_itp}}},
            {"median_de2000_noise", s.median_de2000_noise},
            {"xyz_median_rse",
             {{"spectral", json_rgb(s.xyz_median_rse_spectral)}, {other, json_rgb(s.xyz_median_rse_other)}}},
            {"max_bin",
             {{"theta", 0.5 * (grid.theta_lo(worst.theta) + grid.theta_hi(worst.theta))},
              {"phi", 0.5 * (grid.phi_lo(worst.phi) + grid.phi_hi(worst.phi))}}}};
}

void write_colour_error(const std::string& dir, const std::vector<ColourErrorSlice>& e, const SpectralResult& spectral,
                        const std::string& reduction, const std::string& reduction_notes,
                        const std::array<double, 2>& seconds) {
    const BinGrid grid(spectral.groups.front());
    Json j;
    j["stack"] = spectral.stack.name;
    j["reduction"] = reduction;
    j["reduction_clipped"] = reduction_notes;
    j["bands"] = {{"first_nm", spectral.bands.first_nm},
                  {"last_nm", spectral.bands.last_nm},
                  {"width_nm", spectral.bands.width_nm}};
    j["colour"] =
        "bins as reflectance factors pi f in CIE 1931 XYZ under D65 (a white diffuser: Y = 1); CIELAB "
        "against D65 at Y_n = 1; ICtCp (PQ) with Y = 1 at 100 cd/m^2";
    j["lit_reflectance_factor"] = kLitReflectanceFactor;
    j["seconds"] = {{"spectral", seconds[0]}, {"rgb", seconds[1]}};
    j["spectral_cost_at_equal_xyz_error"] = spectral_cost_at_equal_error(e, seconds);
    Json angles = Json::array();
    for (const ColourErrorSlice& s : e) angles.push_back(colour_error_json(s, grid, "rgb"));
    j["angles"] = angles;
    write_json_file(dir + "/rgb-vs-spectral.json", j);
    std::ofstream csv(dir + "/rgb-vs-spectral.csv");
    csv << "theta_i,side,theta_lo,theta_hi,phi_lo,phi_hi,X_spectral,Y_spectral,Z_spectral,X_rgb,Y_rgb,Z_rgb,de2000,"
           "de_itp,de2000_noise,lit\n";
    char line[512];
    for (const ColourErrorSlice& s : e)
        for (const ColourErrorBin& b : s.bins) {
            if (b.xyz_spectral == glm::dvec3(0) && b.xyz_other == glm::dvec3(0)) continue;   // nothing left there
            std::snprintf(line, sizeof line, "%g,%s,%g,%g,%g,%g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.5g,%.5g,%.5g,%d\n",
                          s.theta_i_deg, s.side == 0 ? "R" : "T", grid.theta_lo(b.theta), grid.theta_hi(b.theta),
                          grid.phi_lo(b.phi), grid.phi_hi(b.phi), b.xyz_spectral.x, b.xyz_spectral.y, b.xyz_spectral.z,
                          b.xyz_other.x, b.xyz_other.y, b.xyz_other.z, b.de.de2000, b.de.de_itp, b.de2000_noise,
                          b.lit ? 1 : 0);
            csv << line;
        }
    if (!csv) throw std::runtime_error("cannot write " + dir + "/rgb-vs-spectral.csv");
}

}   // namespace gonio
