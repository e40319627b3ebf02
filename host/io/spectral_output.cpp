// spectral_output.cpp: see spectral_output.h.
#include "spectral_output.h"
#include "exr_parts.h"
#include "histogram.h"
#include "json.h"
#include "stack_spectral.h"

#include <cmath>
#include <cstdio>

namespace gonio {

namespace {

std::string band_name(const SpectralBands& bands, size_t b) {
    char s[32];
    std::snprintf(s, sizeof s, "%g", bands.centre_nm(b));
    return s;
}

// The keys given per RGB channel that the run uplifted (stack_uplifts): per key, the method and its coefficients.
Json uplifted_keys(const Stack& s) {
    Json out = Json::array();
    auto arr = [](const std::array<double, 3>& v) {
        return Json::array({json_number(v[0]), json_number(v[1]), json_number(v[2])});
    };
    for (const KeyUplift& u : stack_uplifts(s)) {
        const RgbUplift& r = u.uplift;
        out.push_back({{"layer", u.layer + 1},
                       {"key", u.key},
                       {"rgb", json_rgb(glm::dvec3(u.given))},
                       {"uplifted", u.through_transmittance
                                        ? "its transmittance exp(-optical_depth) per channel, as a colour; the optical "
                                          "depth at a wavelength is -ln s"
                                        : "the value per channel, as a colour"},
                       {"colour", arr(r.rgb)},
                       {"method", kUpliftMethod},
                       {"coefficients_per_nm", arr(r.spectrum.per_nm())},
                       {"coefficients_normalised", arr(r.spectrum.c)},
                       {"normalised_wavelength", "u = (nm - 360) / (830 - 360): s = S(c0 u^2 + c1 u + c2)"},
                       {"colour_reached", arr(r.rgb_reached)},
                       {"delta_e76", json_number(r.delta_e76)}});
    }
    return out;
}

glm::dvec3 to_srgb(const glm::dvec3& xyz) {
    const std::array<double, 3> c = xyz_to_linear_srgb({xyz.x, xyz.y, xyz.z});
    return {c[0], c[1], c[2]};
}

}   // namespace

SpectralSlice spectral_slice(const SpectralResult& r, size_t angle, int side) {
    const size_t n_bands = r.bands.count();
    const std::vector<std::array<double, 3>> w = xyz_weights(r.bands);
    SpectralSlice out;
    out.f.resize(n_bands);
    out.se.resize(n_bands);
    std::vector<glm::dvec3> se_sum;   // per group, sum over its bands of w se (fully correlated within a group)
    for (size_t g = 0; g < r.groups.size(); ++g) {
        const Slice s = make_slice(r.groups[g], angle, Side(side));
        if (out.xyz.empty()) {
            out.xyz.assign(s.f.size(), glm::dvec3(0));
            out.xyz_se.assign(s.f.size(), glm::dvec3(0));
        }
        se_sum.assign(s.f.size(), glm::dvec3(0));
        for (size_t c = 0; c < 3 && 3 * g + c < n_bands; ++c) {
            const size_t b = 3 * g + c;
            out.f[b].resize(s.f.size());
            out.se[b].resize(s.f.size());
            for (size_t i = 0; i < s.f.size(); ++i) {
                out.f[b][i] = s.f[i][int(c)];
                out.se[b][i] = s.se[i][int(c)];
                const glm::dvec3 wb(w[b][0], w[b][1], w[b][2]);
                out.xyz[i] += wb * out.f[b][i];
                se_sum[i] += wb * out.se[b][i];
            }
        }
        for (size_t i = 0; i < se_sum.size(); ++i) out.xyz_se[i] += se_sum[i] * se_sum[i];
    }
    out.srgb.resize(out.xyz.size());
    for (size_t i = 0; i < out.xyz.size(); ++i) {
        out.xyz_se[i] = glm::sqrt(out.xyz_se[i]);
        out.srgb[i] = to_srgb(out.xyz[i]);
    }
    return out;
}

void write_spectral_exr(const std::string& path, const SpectralResult& r) {
    const SimResult& first = r.groups.front();
    write_exr_parts(path, int(first.n_phi), int(first.n_theta), spectral_exr_parts(r));
}

std::vector<ExrPart> spectral_exr_parts(const SpectralResult& r) {
    const SimResult& first = r.groups.front();
    const BinGrid grid(first);
    const size_t n = size_t(grid.n_theta) * grid.n_phi;
    std::vector<ExrPart> parts;
    for (size_t a = 0; a < first.angles.size(); ++a)
        for (int side = 0; side < int(first.n_sides); ++side) {
            const SpectralSlice s = spectral_slice(r, a, side);
            ExrPart p;
            char name[64];
            std::snprintf(name, sizeof name, "theta_i=%g %s", first.angles[a].theta_i_deg, side ? "T" : "R");
            p.name = name;
            p.attribute("gonio_version", std::string(GONIO_VERSION));
            p.attribute("gonio_stack", r.stack.source_text);
            p.attribute("gonio_theta_i_deg", first.angles[a].theta_i_deg);
            p.attribute("gonio_seed", int(first.options.seed));
            p.attribute("gonio_dtheta_deg", grid.dtheta_deg);
            p.attribute("gonio_dphi_deg", grid.dphi_deg);
            p.attribute("gonio_layout", std::string("row t = theta bin [t*dtheta, (t+1)*dtheta); column p = phi bin "
                                                    "centred on p*dphi; band.NNN: the bin average of f (1/sr) at the "
                                                    "band centred on NNN nm; X, Y, Z: under D65, Y = 1 for a perfect "
                                                    "white reflector's albedo; R, G, B: linear sRGB"));
            const char* xyz = "XYZ";
            const char* rgb = "RGB";
            for (int c = 0; c < 3; ++c) {
                p.plane(std::string(1, xyz[c]), n, [&](size_t i) { return s.xyz[i][c]; });
                p.plane("se." + std::string(1, xyz[c]), n, [&](size_t i) { return s.xyz_se[i][c]; });
                p.plane(std::string(1, rgb[c]), n, [&](size_t i) { return s.srgb[i][c]; });
            }
            for (size_t b = 0; b < r.bands.count(); ++b) {
                p.plane("band." + band_name(r.bands, b), n, [&](size_t i) { return s.f[b][i]; });
                p.plane("se.band." + band_name(r.bands, b), n, [&](size_t i) { return s.se[b][i]; });
            }
            parts.push_back(std::move(p));
        }
    return parts;
}

namespace {

std::string pass_paths_text(SpectralBands::PassPaths p) {
    switch (p) {
        case SpectralBands::PassPaths::Even:
            return "--paths in every pass";
        case SpectralBands::PassPaths::Weight:
            return "by the pass's weight in X + Y + Z, at least a quarter of the mean, the mean --paths";
        case SpectralBands::PassPaths::Measured:
            return "measured: a pilot of --paths / 8 in every pass, then each pass's share of passes x --paths (at "
                   "least its pilot's) by the minimax of X's, Y's and Z's relative variances the pilot measured";
    }
    return "";
}

}   // namespace

void write_spectral_summary(const std::string& path, const SpectralResult& r) {
    write_json_file(path, spectral_summary_json(r));
}

Json spectral_summary_json(const SpectralResult& r) {
    const SimResult& first = r.groups.front();
    const std::vector<std::array<double, 3>> w = xyz_weights(r.bands);
    Json j;
    j["gonio_version"] = GONIO_VERSION;
    j["stack"] = r.stack.name;
    j["stack_file"] = r.stack.source_path;
    j["device"] = first.device;
    j["driver"] = first.driver;
    j["seed"] = first.options.seed;
    Json pass_paths = Json::array();
    for (const SimResult& g : r.groups) pass_paths.push_back(g.options.paths);
    j["paths_per_angle"] = pass_paths;   // per pass (pass_shares)
    j["bins"] = {{"dtheta_deg", first.options.dtheta_deg},
                 {"dphi_deg", first.options.dphi_deg},
                 {"n_theta", first.n_theta},
                 {"n_phi", first.n_phi}};
    j["spectral"] = {{"bands", r.bands.count()},
                     {"band_width_nm", r.bands.width_nm},
                     {"first_nm", r.bands.first_nm},
                     {"last_nm", r.bands.last_nm},
                     {"points_per_band", r.bands.points},
                     {"evaluated_at", r.bands.points == 1 ? "each band's centre wavelength"
                                                          : "the midpoints of each band's equal parts (points_per_band "
                                                            "of them), their mean: the midpoint rule"},
                     {"passes", r.groups.size()},
                     {"pass_seeds",
                      "band b traced as channel b % 3 of pass b / 3, its point j with seed + b / 3 + "
                      "passes j"},
                     {"pass_paths", pass_paths_text(r.bands.pass_paths)},
                     {"colour",
                      "CIE 1931 2-degree observer, D65, Y = 1 for a perfect white reflector; linear sRGB (IEC "
                      "61966-2-1)"}};
    j["uplifted"] = uplifted_keys(r.stack);   // [] where the stack gives no key per RGB channel
    j["seconds"] = json_number(r.seconds);
    Json angles = Json::array();
    for (size_t a = 0; a < first.angles.size(); ++a) {
        Json ja;
        ja["theta_i"] = first.angles[a].theta_i_deg;
        Json angle_paths = Json::array();
        for (const SimResult& g : r.groups) angle_paths.push_back(g.angles[a].paths);
        ja["paths"] = angle_paths;   // per pass
        std::vector<double> nm, refl, trans, absorbed;
        glm::dvec3 xyz_r(0), xyz_t(0);
        for (size_t b = 0; b < r.bands.count(); ++b) {
            const EnergyBook e = energy_book(r.groups[b / 3], a);
            const int c = int(b % 3);
            nm.push_back(r.bands.centre_nm(b));
            refl.push_back(e.reflected[c]);
            trans.push_back(e.transmitted[c]);
            absorbed.push_back(e.absorbed[c] + e.microfacet_loss[c] + e.truncated[c] + e.invalid[c]);
            const glm::dvec3 wb(w[b][0], w[b][1], w[b][2]);
            xyz_r += wb * e.reflected[c];
            xyz_t += wb * e.transmitted[c];
        }
        auto arr = [](const std::vector<double>& v) {
            Json out = Json::array();
            for (double x : v) out.push_back(json_number(x));
            return out;
        };
        ja["spectral"] = {{"wavelength_nm", arr(nm)},
                          {"band_width_nm", r.bands.width_nm},
                          {"reflected", arr(refl)},
                          {"transmitted", arr(trans)},
                          {"absorbed_or_lost", arr(absorbed)}};
        ja["xyz"] = {{"reflected", json_rgb(xyz_r)}, {"transmitted", json_rgb(xyz_t)}};
        ja["srgb"] = {{"reflected", json_rgb(to_srgb(xyz_r))}, {"transmitted", json_rgb(to_srgb(xyz_t))}};
        angles.push_back(ja);
    }
    j["angles"] = angles;
    return j;
}

}   // namespace gonio
