#include "output.h"
#include "exr_parts.h"
#include "text_format.h"
#include "json.h"
#include "histogram.h"
#include "models.h"
#include "lambertian_series.h"
#include "stack_gpu.h"
#include "stack_vocabulary.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace {

std::ofstream open_out(const std::string& path) {
    std::ofstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error("cannot write " + path);
    return f;
}

}   // namespace

std::string safe_file_name(const std::string& name) {
    std::string out;
    for (char c : name) {
        const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                          c == '_' || (c == '.' && !out.empty());
        out += keep ? c : '_';
    }
    return out.empty() ? "_" : out.substr(0, 200);
}

void write_slices_csv(const std::string& path, const SimResult& r, const std::vector<ModelSlices>* models) {
    auto f = open_out(path);
    write_slices_csv(f, r, models);
    if (!f) throw std::runtime_error("error writing " + path);
}

std::string slices_csv_text(const SimResult& r, const std::vector<ModelSlices>* models) {
    std::ostringstream f;
    write_slices_csv(f, r, models);
    return f.str();
}

void write_slices_csv(std::ostream& f, const SimResult& r, const std::vector<ModelSlices>* models) {
    // a run at an incident azimuth other than 0 has a phi_i column after theta_i (the reference's rows and the
    // models'), a run in the plane of incidence none
    const bool azimuth = r.options.phi_i_deg != 0.0;
    f << (azimuth ? "source,theta_i,phi_i,side," : "source,theta_i,side,")
      << "theta_lo,theta_hi,phi_lo,phi_hi,r,g,b,se_r,se_g,se_b\n";
    BinGrid g(r);
    const bool transmissive = r.stack.transmissive();
    for (int cls = -1; cls < (r.options.orders ? 3 : 0); ++cls) {
        std::string source = cls < 0 ? "reference" : "reference:order" + std::to_string(cls);
        for (size_t a = 0; a < r.angles.size(); ++a) {
            for (int side = 0; side < (transmissive ? 2 : 1); ++side) {
                Slice s = make_slice(r, a, Side(side), cls);
                for (uint32_t t = 0; t < g.n_theta; ++t)
                    for (uint32_t p = 0; p < g.n_phi; ++p) {
                        size_t b = size_t(t) * g.n_phi + p;
                        f << source << ',' << format_g9(r.angles[a].theta_i_deg) << ','
                          << (azimuth ? format_g9(r.angles[a].phi_i_deg) + "," : "") << (side ? 'T' : 'R') << ','
                          << format_g9(g.theta_lo(t)) << ',' << format_g9(g.theta_hi(t)) << ','
                          << format_g9(g.phi_lo(p)) << ',' << format_g9(g.phi_hi(p));
                        for (int c = 0; c < kChannels; ++c) f << ',' << format_g9(s.f[b][c]);
                        for (int c = 0; c < kChannels; ++c) f << ',' << format_g9(s.se[b][c]);
                        f << '\n';
                    }
            }
        }
    }
    if (models) {
        for (const ModelSlices& m : *models) {
            if (!model_has_bins(m)) continue;   // invalid values are reported in summary.json, never written
            for (size_t a = 0; a < m.f.size(); ++a)
                for (int side = 0; side < (m.t.empty() ? 1 : 2); ++side)
                    for (uint32_t t = 0; t < g.n_theta; ++t)
                        for (uint32_t p = 0; p < g.n_phi; ++p) {
                            const glm::dvec3& v = (side ? m.t : m.f)[a][size_t(t) * g.n_phi + p];
                            f << m.id << ',' << format_g9(r.angles[a].theta_i_deg) << ','
                              << (azimuth ? format_g9(r.angles[a].phi_i_deg) + "," : "") << (side ? 'T' : 'R') << ','
                              << format_g9(g.theta_lo(t)) << ',' << format_g9(g.theta_hi(t)) << ','
                              << format_g9(g.phi_lo(p)) << ',' << format_g9(g.phi_hi(p)) << ',' << format_g9(v.x) << ','
                              << format_g9(v.y) << ',' << format_g9(v.z) << ",0,0,0\n";
                        }
        }
    }
}

void write_summary_json(const std::string& path, const SimResult& r, const Json* extra) {
    write_json_file(path, summary_json(r, extra));
}

namespace {

// The walk's layers that are not today's defaults, in summary.json's "walk": the rough interfaces whose microsurface is
// not GGX with height-correlated Smith and single scattering ("microsurfaces"), and the media of microflakes
// ("microflake_media"); each absent where none is.
void walk_layers_json(const Stack& s, Json& walk) {
    Json micro = Json::array(), flakes = Json::array();
    for (size_t i = 0; i < s.layers.size(); ++i) {
        const Layer& y = s.layers[i];
        Json m = {{"layer", i + 1}}, f = {{"layer", i + 1}};
        for (const ChoiceKey& c : choice_keys())
            if (c.of_kind(y.kind)) (c.medium ? f : m)[c.name] = c.words[size_t(c.get(y))];
        if (layer_microsurface_code(y) != 0u) micro.push_back(m);
        if (s.medium_scatters(i) && y.phase != MediumPhase::Hg) {
            f["fibre_roughness"] = json_number(y.fibre_roughness);
            flakes.push_back(f);
        }
    }
    if (!micro.empty()) walk["microsurfaces"] = micro;
    if (!flakes.empty()) walk["microflake_media"] = flakes;
}

}   // namespace

Json summary_json(const SimResult& r, const Json* extra) {
    double total_s = 0;
    uint64_t total_paths = 0;
    for (auto& a : r.angles) {
        total_s += a.seconds;
        total_paths += a.paths;
    }
    Json j;
    j["gonio_version"] = GONIO_VERSION;
    j["stack"] = r.stack.name;
    j["stack_file"] = r.stack.source_path;
    j["device"] = r.device;
    j["driver"] = r.driver;
    j["seed"] = r.options.seed;
    j["paths_per_angle"] = r.options.paths;
    j["bins"] = {{"dtheta_deg", json_number(r.options.dtheta_deg)},
                 {"dphi_deg", json_number(r.options.dphi_deg)},
                 {"n_theta", r.n_theta},
                 {"n_phi", r.n_phi},
                 {"phi_bins_centred_on_multiples_of_dphi", true}};
    j["max_events"] = r.options.max_events;
    j["orders"] = r.options.orders;
    j["rse_target"] = json_number(r.options.rse_target);
    j["rse_quantile"] = json_number(r.options.rse_quantile);
    j["stack_description"] = describe_stack(r.stack);
    {   // which walk ran, as the host that ran it recorded it: specialised or general, baked (the stack's parameters
        // compiled into the shader, stack_constants.glsl), and the Lambertian series (docs/PHYSICS.md)
        const LambertianSeries ls = walk_stack(r.stack, r.options.specialised).series;
        Json series;
        if (r.walk.series) {
            series = {{"applied", true},
                      {"trip_escaped", json_rgb(ls.trip.escaped)},
                      {"trip_returned", json_rgb(ls.trip.returned)},
                      {"trip_lost", json_rgb(ls.trip.lost)},
                      {"gain", json_rgb(ls.gain)},
                      {"quadrature_error", json_number(ls.quadrature_error)},
                      {"relative_error_bound", json_number(ls.relative_error)}};
        } else {
            std::string why = !ls.applies              ? ls.reason
                              : !r.options.specialised ? "--general-walk"
                              : !r.options.series      ? "--no-series"
                              : r.options.orders       ? "--orders: the path classes need every trip"
                                                       : "--max-events below 3";
            series = {{"applied", false}, {"reason", why}};
        }
        j["walk"] = {{"specialised", r.walk.specialised},
                     {"baked_stack", r.walk.baked_stack},
                     {"lambertian_series", series},
                     {"entry_branch", r.walk.entry_branch},
                     {"exit_estimates", r.walk.exit_estimates}};
        walk_layers_json(r.stack, j["walk"]);
    }
    j["seconds"] = json_number(total_s);
    j["paths_per_second"] = json_number(total_s > 0 ? double(total_paths) / total_s : 0.0);
    Json angles = Json::array();
    const char* ch[3] = {"R", "G", "B"};
    for (size_t a = 0; a < r.angles.size(); ++a) {
        const AngleResult& ar = r.angles[a];
        EnergyBook e = energy_book(r, a);
        Json angle;
        angle["theta_i"] = json_number(ar.theta_i_deg);
        if (ar.phi_i_deg != 0.0) angle["phi_i"] = json_number(ar.phi_i_deg);   // else 0, the plane of incidence
        angle["paths"] = ar.paths;
        angle["seconds"] = json_number(ar.seconds);
        angle["device_seconds"] = json_number(ar.device_seconds);
        angle["paths_per_second"] = json_number(ar.seconds > 0 ? double(ar.paths) / ar.seconds : 0.0);
        angle["stopped_by"] = ar.stopped_by;
        angle["worst_relative_se"] = json_number(ar.worst_rse);
        angle["relative_se"] = {{"median", json_number(ar.median_rse)},
                                {"p90", json_number(ar.p90_rse)},
                                {"worst", json_number(ar.worst_rse)},
                                {"over", "bins above 1% of their slice's peak, per side and channel"}};
        Json energy;
        for (int c = 0; c < kChannels; ++c)
            energy[ch[c]] = {{"reflected", json_number(e.reflected[c])},
                             {"transmitted", json_number(e.transmitted[c])},
                             {"absorbed", json_number(e.absorbed[c])},
                             {"microfacet_loss", json_number(e.microfacet_loss[c])},
                             {"truncated", json_number(e.truncated[c])},
                             {"invalid", json_number(e.invalid[c])},
                             {"sum", json_number(e.sum()[c])}};
        angle["energy"] = energy;
        angles.push_back(angle);
    }
    j["angles"] = angles;
    if (extra)
        for (auto& [key, value] : extra->items()) j[key] = value;
    return j;
}

namespace {

constexpr const char* kSideNames[2] = {"R (reflection, theta from +z)", "T (transmission, theta from -z)"};

// A part's name: "theta_i=30 R", "theta_i=30 phi_i=45 R" where the azimuth is not 0, and " model=ID" for a model's
std::string part_name(const AngleResult& ar, int side, const std::string& model = "") {
    char name[64];
    if (ar.phi_i_deg != 0.0)
        std::snprintf(name, sizeof name, "theta_i=%g phi_i=%g %s", ar.theta_i_deg, ar.phi_i_deg, side ? "T" : "R");
    else
        std::snprintf(name, sizeof name, "theta_i=%g %s", ar.theta_i_deg, side ? "T" : "R");
    return std::string(name) + (model.empty() ? "" : " model=" + model);
}

// The reference's part of angle a and side: f and se per channel, and per path class with --orders.
ExrPart reference_part(const SimResult& r, size_t a, int side, const BinGrid& g) {
    ExrPart p;
    p.name = part_name(r.angles[a], side);
    p.attribute("gonio_version", std::string(GONIO_VERSION));
    p.attribute("gonio_stack", r.stack.source_text);
    p.attribute("gonio_stack_name", r.stack.name);
    p.attribute("gonio_theta_i_deg", r.angles[a].theta_i_deg);
    if (r.angles[a].phi_i_deg != 0.0) p.attribute("gonio_phi_i_deg", r.angles[a].phi_i_deg);
    p.attribute("gonio_side", std::string(kSideNames[side]));
    p.attribute("gonio_paths", std::to_string(r.angles[a].paths));
    p.attribute("gonio_seed", int(r.options.seed));
    p.attribute("gonio_device", r.device + " (" + r.driver + ")");
    p.attribute("gonio_layout", std::string("row t = theta bin [t*dtheta, (t+1)*dtheta); column p = phi bin centred "
                                            "on p*dphi; values = bin average of f (1/sr)"));
    p.attribute("gonio_dtheta_deg", g.dtheta_deg);
    p.attribute("gonio_dphi_deg", g.dphi_deg);
    const char* ch[3] = {"R", "G", "B"};
    const size_t n = size_t(g.n_theta) * g.n_phi;
    for (int cls = -1; cls < (r.options.orders ? 3 : 0); ++cls) {
        const Slice s = make_slice(r, a, Side(side), cls);
        const std::string prefix = cls < 0 ? "" : "order" + std::to_string(cls) + ".";
        for (int c = 0; c < kChannels; ++c) {
            p.plane(prefix + ch[c], n, [&](size_t b) { return s.f[b][c]; });
            p.plane(prefix + "se." + ch[c], n, [&](size_t b) { return s.se[b][c]; });
        }
    }
    return p;
}

// A model's part of angle a and side: its f per channel.
ExrPart model_part(const SimResult& r, const ModelSlices& m, size_t a, int side, const BinGrid& g) {
    ExrPart p;
    p.name = part_name(r.angles[a], side, m.id);
    p.attribute("gonio_version", std::string(GONIO_VERSION));
    p.attribute("gonio_model", m.id);
    p.attribute("gonio_side", std::string(kSideNames[side]));
    p.attribute("gonio_stack_name", r.stack.name);
    p.attribute("gonio_theta_i_deg", r.angles[a].theta_i_deg);
    if (r.angles[a].phi_i_deg != 0.0) p.attribute("gonio_phi_i_deg", r.angles[a].phi_i_deg);
    p.attribute("gonio_layout", std::string("row t = theta bin [t*dtheta, (t+1)*dtheta); column p = phi bin centred "
                                            "on p*dphi; values = bin average of the model's f (1/sr)"));
    const auto& mf = side ? m.t : m.f;
    const char* ch[3] = {"R", "G", "B"};
    for (int c = 0; c < kChannels; ++c)
        p.plane(ch[c], size_t(g.n_theta) * g.n_phi, [&](size_t b) { return mf[a][b][c]; });
    return p;
}

}   // namespace

void write_exr(const std::string& path, const SimResult& r, const std::vector<ModelSlices>* models) {
    const BinGrid g(r);
    std::vector<ExrPart> parts;
    for (size_t a = 0; a < r.angles.size(); ++a)
        for (int side = 0; side < (r.stack.transmissive() ? 2 : 1); ++side)
            parts.push_back(reference_part(r, a, side, g));
    if (models)
        for (const ModelSlices& m : *models)
            for (size_t a = 0; model_has_bins(m) && a < m.f.size(); ++a)
                for (int side = 0; side < (m.t.empty() ? 1 : 2); ++side) parts.push_back(model_part(r, m, a, side, g));
    write_exr_parts(path, int(g.n_phi), int(g.n_theta), parts);
}

}   // namespace gonio
