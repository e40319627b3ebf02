#include "compare.h"
#include "text_format.h"
#include "histogram.h"
#include "output.h"

#include <cmath>
#include <cstdio>

namespace gonio {

namespace {
double remap(double f) { return std::log1p(std::sqrt(std::max(f, 0.0))); }
std::string num(double v) { return format_g9(v); }
std::string rgb(glm::dvec3 v) { return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]"; }
}  // namespace

ModelMetrics compare_model(const SimResult& ref, size_t angle, const std::vector<glm::dvec3>& model, Side side) {
    ModelMetrics m;
    BinGrid g(ref);
    Slice s = make_slice(ref, angle, side);
    double n = 0, nrel = 0, se2 = 0;
    for (uint32_t t = 0; t < g.n_theta; ++t) {
        double omega = g.projected_solid_angle(t);
        for (uint32_t p = 0; p < g.n_phi; ++p) {
            size_t b = size_t(t) * g.n_phi + p;
            for (int c = 0; c < 3; ++c) {
                double fr = s.f[b][c], fm = model[b][c];
                double d = remap(fm) - remap(fr);
                m.rmse_remapped += d * d;
                m.mean_abs_remapped += std::fabs(d);
                m.rmse_linear += (fm - fr) * (fm - fr);
                if (fr > 0) { m.mean_rel_linear += std::fabs(fm - fr) / fr; nrel++; }
                // g'(f) = 1 / (2 sqrt f (1 + sqrt f)); at f = 0 use the noise of a one-path bin instead
                double sq = std::sqrt(std::max(fr, s.se[b][c]));
                double noise = sq > 0 ? s.se[b][c] / (2 * sq * (1 + sq)) : 0.0;
                se2 += noise * noise;
                n++;
                if (std::fabs(d) > m.max_abs_remapped) {
                    m.max_abs_remapped = std::fabs(d);
                    m.max_theta_deg = 0.5 * (g.theta_lo(t) + g.theta_hi(t));
                    m.max_phi_deg = p * g.dphi_deg;
                    m.max_channel = c;
                }
            }
            m.albedo_model += model[b] * omega;
            m.albedo_reference += s.f[b] * omega;
        }
    }
    m.rmse_remapped = std::sqrt(m.rmse_remapped / n);
    m.mean_abs_remapped /= n;
    m.rmse_linear = std::sqrt(m.rmse_linear / n);
    m.mean_rel_linear = nrel > 0 ? m.mean_rel_linear / nrel : 0.0;
    m.reference_noise_remapped = std::sqrt(se2 / n);
    m.within_noise = m.rmse_remapped < 2 * m.reference_noise_remapped;
    return m;
}

void warn_energy_gains(const SimResult& ref, const std::vector<ModelSlices>& models) {
    const auto& reg = model_registry();
    for (const ModelSlices& ms : models) {
        if (!ms.not_applicable.empty()) continue;
        for (size_t a = 0; a < ms.f.size(); ++a) {
            glm::dvec3 total = compare_model(ref, a, ms.f[a], kReflection).albedo_model;
            if (a < ms.t.size()) total += compare_model(ref, a, ms.t[a], kTransmission).albedo_model;
            double mx = std::max(total.x, std::max(total.y, total.z));
            if (mx <= 1.0 + kWhiteFurnaceTolerance) continue;
            std::string why;
            for (const ModelInfo& m : reg)
                if (m.id == ms.id) why = m.energy_conserving ? "it claims energy conservation: a bug, please report it" : m.energy_note;
            std::fprintf(stderr, "gonio: %s reflects %.4f of the light it receives at theta_i %g (not clamped; %s)\n",
                         ms.id.c_str(), mx, ref.angles[a].theta_i_deg, why.c_str());
        }
    }
}

std::string models_json(const SimResult& ref, const std::vector<ModelSlices>& models, const std::vector<ModelCost>& costs,
                        const ModelStageCost* stage) {
    std::string o;
    if (stage)
        o += "  \"model_stage\": {\"wall_seconds\": " + num(stage->wall_seconds) + ", \"device_seconds\": " + num(stage->device_seconds) +
             ", \"setup_seconds\": " + num(stage->setup_seconds) + ", \"pipeline_seconds\": " + num(stage->pipeline_seconds) +
             ", \"pipelines_created\": " + std::to_string(stage->pipelines_created) + "},\n";
    o += "  \"models\": [\n";
    for (size_t i = 0; i < models.size(); ++i) {
        const ModelSlices& ms = models[i];
        o += "    {\"id\": \"" + json_escape(ms.id) + "\"";
        if (!ms.not_applicable.empty()) {
            o += ", \"applicable\": false, \"reason\": \"" + json_escape(ms.not_applicable) + "\"}";
        } else {
            ModelCost c = i < costs.size() ? costs[i] : ModelCost{};
            o += ", \"applicable\": true, \"seconds\": " + num(c.wall_seconds) + ", \"device_seconds\": " + num(c.device_seconds) +
                 ", \"evaluations\": " + std::to_string(c.evaluations) + ", \"ns_per_evaluation\": " +
                 num(c.evaluations ? c.device_seconds * 1e9 / double(c.evaluations) : 0.0) + ", \"angles\": [\n";
            auto side_json = [&](const std::vector<std::vector<glm::dvec3>>& f, Side side) {
                std::string j;
                for (size_t a = 0; a < f.size(); ++a) {
                    ModelMetrics m = compare_model(ref, a, f[a], side);
                    // the white-furnace bound, on the reflection entry: reflected + transmitted <= 1 (+1e-3 for
                    // the bin integration); a model that breaks it says so here, it is not clamped
                    std::string energy;
                    if (side == kReflection) {
                        glm::dvec3 total = m.albedo_model;
                        if (a < ms.t.size()) total += compare_model(ref, a, ms.t[a], kTransmission).albedo_model;
                        bool over = std::max(total.x, std::max(total.y, total.z)) > 1.0 + kWhiteFurnaceTolerance;
                        energy = ", \"albedo_model_total\": " + rgb(total) + ", \"reflects_more_than_it_receives\": " +
                                 (over ? "true" : "false");
                    }
                    j += "      {\"theta_i\": " + num(ref.angles[a].theta_i_deg) +
                         ", \"rmse_remapped\": " + num(m.rmse_remapped) + ", \"mean_abs_error_remapped\": " + num(m.mean_abs_remapped) +
                         ", \"rmse_linear\": " + num(m.rmse_linear) + ", \"mean_relative_error_linear\": " + num(m.mean_rel_linear) +
                         ", \"albedo_model\": " + rgb(m.albedo_model) + ", \"albedo_reference\": " + rgb(m.albedo_reference) +
                         ", \"albedo_error\": " + rgb(m.albedo_model - m.albedo_reference) +
                         ", \"max_error_remapped\": {\"value\": " + num(m.max_abs_remapped) + ", \"theta\": " + num(m.max_theta_deg) +
                         ", \"phi\": " + num(m.max_phi_deg) + ", \"channel\": \"" + "RGB"[m.max_channel] + "\"}" +
                         ", \"reference_noise_remapped\": " + num(m.reference_noise_remapped) +
                         ", \"within_reference_noise\": " + (m.within_noise ? "true" : "false") + energy + "}" +
                         (a + 1 < f.size() ? ",\n" : "\n");
                }
                return j;
            };
            o += side_json(ms.f, kReflection);
            if (!ms.t.empty()) o += "    ], \"transmission_angles\": [\n" + side_json(ms.t, kTransmission);
            o += "    ]}";
        }
        o += i + 1 < models.size() ? ",\n" : "\n";
    }
    o += "  ]";
    return o;
}

}  // namespace gonio
