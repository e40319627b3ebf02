// spectral_compare.cpp: see spectral_compare.h.
#include "spectral_compare.h"
#include "artist_parameters.h"
#include "colour_error.h"
#include "histogram.h"
#include "json.h"
#include "model_evaluator.h"
#include "output.h"
#include "spectral_simulate.h"
#include "stack_spectral.h"

#include <cstdio>
#include <string>

namespace gonio {

namespace {

// A model's bins over the passes, in XYZ, on one angle and side; false where the model has none there.
bool model_xyz(const std::vector<std::vector<ModelSlices>>& passes, size_t m, size_t a, int side,
               const std::vector<std::array<double, 3>>& w, const BinGrid& grid, OtherColours& o) {
    const size_t n_bands = w.size();
    for (size_t b = 0; b < n_bands; ++b) {
        const ModelSlices& ms = passes[b / 3][m];
        const std::vector<std::vector<glm::dvec3>>& v = side == 0 ? ms.f : ms.t;
        if (v.empty()) return false;
        if (o.f_xyz.empty()) o.f_xyz.assign(v[a].size(), glm::dvec3(0));
        const glm::dvec3 wb(w[b][0], w[b][1], w[b][2]);
        for (size_t i = 0; i < v[a].size(); ++i) o.f_xyz[i] += wb * v[a][i][int(b % 3)];
    }
    o.se_xyz.assign(o.f_xyz.size(), glm::dvec3(0));
    o.albedo_xyz = glm::dvec3(0);
    for (size_t i = 0; i < o.f_xyz.size(); ++i)
        o.albedo_xyz += o.f_xyz[i] * grid.projected_solid_angle(uint32_t(i / grid.n_phi));
    return true;
}

// A model evaluated in RGB (its inputs an artist's colours), its linear sRGB bins in XYZ; false where it has none there.
bool model_xyz_from_rgb(const ModelSlices& ms, size_t a, int side, const BinGrid& grid, OtherColours& o) {
    const std::vector<std::vector<glm::dvec3>>& v = side == 0 ? ms.f : ms.t;
    if (v.empty()) return false;
    for (const glm::dvec3& f : v[a]) {
        const Colour3 x = linear_srgb_to_xyz({f.x, f.y, f.z});
        o.f_xyz.emplace_back(x[0], x[1], x[2]);
    }
    o.se_xyz.assign(o.f_xyz.size(), glm::dvec3(0));
    for (size_t i = 0; i < o.f_xyz.size(); ++i)
        o.albedo_xyz += o.f_xyz[i] * grid.projected_solid_angle(uint32_t(i / grid.n_phi));
    return true;
}

// Adds weight times the evaluation's channels (only: that channel alone, -1: all three) into the pass's models; the
// first evaluation of a pass gives its shape and every reason a model has no bins.
void add_models(std::vector<ModelSlices>& pass, const std::vector<ModelSlices>& e, int only, double weight) {
    if (pass.empty()) {   // the shape and the reasons of the first evaluation, its values not yet counted
        pass = e;
        for (ModelSlices& p : pass)
            for (auto* side : {&p.f, &p.t})
                for (auto& angle : *side)
                    for (glm::dvec3& v : angle) v = glm::dvec3(0);
    }
    for (size_t m = 0; m < e.size(); ++m) {
        ModelSlices& p = pass[m];
        if (p.not_applicable.empty() && !e[m].not_applicable.empty()) p.not_applicable = e[m].not_applicable;
        if (p.invalid.empty() && !e[m].invalid.empty()) p.invalid = e[m].invalid;
        for (auto [dst, src] : {std::pair{&p.f, &e[m].f}, std::pair{&p.t, &e[m].t}})
            for (size_t a = 0; a < src->size() && a < dst->size(); ++a)
                for (size_t i = 0; i < (*src)[a].size(); ++i)
                    for (int c = 0; c < 3; ++c)
                        if (only < 0 || c == only) (*dst)[a][i][c] += weight * (*src)[a][i][c];
    }
}

// Why a model has no bins at some band ("" where it has them at every band).
std::string why_no_bins(const std::vector<std::vector<ModelSlices>>& passes, size_t m, const SpectralBands& bands) {
    for (size_t g = 0; g < passes.size(); ++g) {
        const ModelSlices& ms = passes[g][m];
        if (!ms.not_applicable.empty()) return ms.not_applicable;
        if (!ms.invalid.empty())
            return ms.invalid + " (at " + std::to_string(int(bands.centre_nm(3 * g))) + " to " +
                   std::to_string(int(bands.centre_nm(std::min(3 * g + 2, bands.count() - 1)))) + " nm)";
    }
    return "";
}

}   // namespace

std::vector<SpectralModelColours> spectral_model_colours(const SpectralResult& spectral, const Stack& stack,
                                                         const ModelOptions& models, RgbReduction reduction,
                                                         ModelEvaluator& evaluator, bool progress,
                                                         std::string& clipped) {
    const SimResult& first = spectral.groups.front();
    const SpectralBands& bands = spectral.bands;
    const ModelGrid grid_m = model_grid(first);
    const BinGrid grid(first);
    const size_t n_bands = bands.count();
    // per pass, the models at the reference's wavelengths: the mean over the band's points, and where the stack
    // disperses one wavelength per evaluation (channel c of evaluation c)
    const bool disperses = stack_disperses(stack);
    std::vector<std::vector<ModelSlices>> passes;
    for (size_t g = 0; g < spectral.groups.size(); ++g) {
        std::vector<ModelSlices> pass;
        for (unsigned j = 0; j < bands.points; ++j) {
            std::array<double, 3> nm{};
            for (size_t c = 0; c < 3; ++c) nm[c] = bands.point_nm(std::min(3 * g + c, n_bands - 1), j);
            for (int only = disperses ? 0 : -1; only < (disperses ? 3 : 0); ++only) {
                const std::array<double, 3> at =
                    only < 0 ? nm : std::array<double, 3>{nm[size_t(only)], nm[size_t(only)], nm[size_t(only)]};
                if (progress) std::fprintf(stderr, "gonio: the models at %g, %g, %g nm\n", at[0], at[1], at[2]);
                add_models(pass, evaluator.evaluate(stack_at_wavelengths(stack, at), grid_m, nullptr, models), only,
                           1.0 / double(bands.points));
            }
        }
        passes.push_back(std::move(pass));
    }
    // the models whose inputs are an artist's colours, once more on the stack reduced to RGB, as they are defined
    const Stack rgb_stack = stack_reduced_to_rgb(stack, reduction, clipped);
    if (progress) std::fprintf(stderr, "gonio: the production models in RGB (reduction %s)\n", to_string(reduction));
    const std::vector<ModelSlices> in_rgb = evaluator.evaluate(rgb_stack, grid_m, nullptr, models);
    const std::vector<std::array<double, 3>> w = xyz_weights(bands);
    std::vector<SpectralReference> refs;   // per angle and side, once for every model
    for (size_t a = 0; a < first.angles.size(); ++a)
        for (int side = 0; side < int(first.n_sides); ++side) refs.push_back(spectral_reference(spectral, a, side));
    std::vector<SpectralModelColours> out;
    for (size_t m = 0; m < passes.front().size(); ++m) {
        const ModelSlices& m0 = passes.front()[m];
        if (m0.not_selected) continue;
        SpectralModelColours one;
        one.id = m0.id;
        one.in_rgb = model_takes_artist_colours(m0.id);
        one.why = one.in_rgb ? (!in_rgb[m].not_applicable.empty() ? in_rgb[m].not_applicable : in_rgb[m].invalid)
                             : why_no_bins(passes, m, bands);
        if (one.why.empty())
            for (size_t a = 0; a < first.angles.size(); ++a)
                for (int side = 0; side < int(first.n_sides); ++side) {
                    OtherColours o;
                    if (one.in_rgb ? !model_xyz_from_rgb(in_rgb[m], a, side, grid, o)
                                   : !model_xyz(passes, m, a, side, w, grid, o))
                        continue;
                    one.slices.push_back(colour_error_slice(refs[a * first.n_sides + size_t(side)], o));
                }
        out.push_back(std::move(one));
    }
    return out;
}

std::string spectral_model_evaluation(const SpectralModelColours& m, RgbReduction reduction) {
    return m.in_rgb ? std::string("in RGB, as defined (its inputs are an artist's colours), the stack reduced by ") +
                          to_string(reduction)
                    : std::string("band by band");
}

int run_spectral_compare(const Case& run, const SpectralBands& bands, const ModelOptions& models,
                         RgbReduction reduction, VkContext& ctx) {
    int rc = 0;
    const SpectralResult spectral = trace_spectral(run, bands, &ctx, 1, rc);
    const BinGrid grid(spectral.groups.front());
    ModelEvaluator evaluator(ctx);
    std::string clipped;
    const std::vector<SpectralModelColours> colours =
        spectral_model_colours(spectral, run.stack, models, reduction, evaluator, run.sim.progress, clipped);
    if (!clipped.empty())
        std::fprintf(stderr, "gonio: warning: the %s reduction: %s\n", to_string(reduction), clipped.c_str());
    Json jm = Json::array();
    std::printf("%-32s %-28s %-28s %s\n", "model", "albedo dE2000 per angle", "lit bins' median dE2000", "noise");
    for (const SpectralModelColours& m : colours) {
        Json one;
        one["id"] = m.id;
        one["evaluated"] = spectral_model_evaluation(m, reduction);
        if (!m.why.empty()) {
            one["not_evaluated"] = m.why;
            jm.push_back(one);
            std::printf("%-32s not evaluated: %s\n", m.id.c_str(), m.why.c_str());
            continue;
        }
        Json angles = Json::array();
        std::string albedo, median, noise;
        for (const ColourErrorSlice& e : m.slices) {
            angles.push_back(colour_error_json(e, grid, "model"));
            if (e.side != 0) continue;
            char t[32];
            std::snprintf(t, sizeof t, "%s%.2f", albedo.empty() ? "" : "/", e.albedo_de.de2000);
            albedo += t;
            std::snprintf(t, sizeof t, "%s%.2f", median.empty() ? "" : "/", e.median_de2000);
            median += t;
            std::snprintf(t, sizeof t, "%s%.2f", noise.empty() ? "" : "/", e.median_de2000_noise);
            noise += t;
        }
        one["angles"] = angles;
        jm.push_back(one);
        std::printf("%-32s %-28s %-28s %s\n", (m.id + (m.in_rgb ? " (RGB)" : "")).c_str(), albedo.c_str(),
                    median.c_str(), noise.c_str());
    }
    write_spectral_exr(run.out + "/" + safe_file_name(run.stack.name) + ".exr", spectral);
    write_spectral_summary(run.out + "/summary.json", spectral);
    Json j;
    j["stack"] = run.stack.name;
    j["bands"] = {{"first_nm", bands.first_nm}, {"last_nm", bands.last_nm}, {"width_nm", bands.width_nm}};
    j["evaluated"] =
        "each model band by band: the stack at each pass's three wavelengths (its measured materials' "
        "and spectra's values there), on the reference's bins; colours in XYZ under D65";
    j["colour"] =
        "bins as reflectance factors pi f in CIE 1931 XYZ under D65 (a white diffuser: Y = 1); CIELAB "
        "against D65 at Y_n = 1; ICtCp (PQ) with Y = 1 at 100 cd/m^2";
    j["lit_reflectance_factor"] = kLitReflectanceFactor;
    j["models"] = jm;
    write_json_file(run.out + "/models-spectral.json", j);
    std::printf("wrote %s/{summary.json,models-spectral.json} and the spectral reference's EXR (%zu bands)\n",
                run.out.c_str(), bands.count());
    return rc;
}

}   // namespace gonio
