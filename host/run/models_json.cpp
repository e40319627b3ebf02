// models_json.cpp: see models_json.h.
#include "models_json.h"

#include <algorithm>

namespace gonio {

Json agreement_json(const Agreement& a) {
    return {{"chi2_per_dof", json_number(a.chi2_per_dof)},
            {"mean_z", json_number(a.mean_z)},
            {"chi2_p_value", json_number(a.chi2_p_value)},
            {"bias_p_value", json_number(a.bias_p_value)},
            {"bins_tested", a.cells},
            {"bins_pooled", a.pooled_bins},
            {"bins_without_paths", a.bins_without_paths},
            {"pooled_cells_tested", a.pooled_cells},
            {"smallest_detectable_relative_bias", json_number(a.smallest_detectable_relative_bias)},
            {"integration_error_over_noise",
             a.integration_error_over_noise < 0 ? Json(nullptr) : json_number(a.integration_error_over_noise)},
            {"within_reference_noise", a.within_noise},
            {"verdict", a.within_noise ? "cannot be told apart from the reference at these paths" : a.reason}};
}

Json best_models_json(const SimResult& ref, const Comparison& c) {
    Json o = Json::array();
    for (int side = 0; side < int(ref.n_sides); ++side)
        for (size_t a = 0; a < ref.angles.size(); ++a) {
            const BestModel& b = c.best_of(a, Side(side));
            if (b.best.empty()) continue;
            o.push_back({{"theta_i", json_number(ref.angles[a].theta_i_deg)},
                         {"side", side ? "T" : "R"},
                         {"best", b.best},
                         {"runner_up", b.runner_up.empty() ? Json(nullptr) : Json(b.runner_up)},
                         {"separation_z", json_number(b.separation_z)},
                         {"tie", b.tie}});
        }
    return o;
}

namespace {

// bins listed by incident angle, side and their place (the first 100)
Json bins_json(const SimResult& ref, const std::vector<ModelSlices::BinRef>& bins) {
    Json list = Json::array();
    const BinGrid g(ref);
    for (size_t k = 0; k < bins.size() && k < 100; ++k) {
        const auto& b = bins[k];
        const uint32_t t = b.bin / ref.n_phi, p = b.bin % ref.n_phi;
        list.push_back({{"theta_i", json_number(ref.angles.at(b.angle).theta_i_deg)},
                        {"side", b.side ? "T" : "R"},
                        {"theta_lo", json_number(g.theta_lo(t))},
                        {"theta_hi", json_number(g.theta_hi(t))},
                        {"phi", json_number(p * g.dphi_deg)}});
    }
    return list;
}

// the incident angles and sides listed
Json angles_json(const SimResult& ref, const std::vector<ModelSlices::BinRef>& v) {
    Json list = Json::array();
    for (const auto& b : v)
        list.push_back({{"theta_i", json_number(ref.angles.at(b.angle).theta_i_deg)}, {"side", b.side ? "T" : "R"}});
    return list;
}

// A model that was not scored: where its values could not be used (model_evaluator.h)
void not_scored_json(Json& e, const SimResult& ref, const ModelSlices& ms) {
    e["applicable"] = true;
    e["scored"] = false;
    e["reason"] = ms.invalid;
    e["invalid_values"] = {{"nodes", ms.invalid_nodes},
                           {"bins", ms.invalid_bins.size()},
                           {"first_bins", bins_json(ref, ms.invalid_bins)},
                           {"cut_short_bins", ms.cut_short_bins.size()},
                           {"first_cut_short_bins", bins_json(ref, ms.cut_short_bins)}};
    // a black box's: the incident angles and sides where its hints were unusable, or its narrowest lobe is
    // narrower than float resolves
    if (!ms.invalid_hints.empty()) e["invalid_values"]["unusable_lobe_hints"] = angles_json(ref, ms.invalid_hints);
    if (!ms.float_unresolved.empty())
        e["invalid_values"]["lobes_below_float_resolution"] = angles_json(ref, ms.float_unresolved);
}

// One incident angle of a scored model on one side: metrics, verdict and, on the reflection side, the white-furnace
// bound.
Json angle_json(const SimResult& ref, const ModelScores& scores, size_t a, Side side) {
    const ModelMetrics& m = scores.side(side)[a];
    Json j;
    j["theta_i"] = json_number(ref.angles[a].theta_i_deg);
    j["rmse_remapped"] = json_number(m.rmse_remapped);
    j["mean_abs_error_remapped"] = json_number(m.mean_abs_remapped);
    j["rmse_linear"] = json_number(m.rmse_linear);
    j["mean_relative_error_linear"] = json_number(m.mean_rel_linear);
    j["albedo_model"] = json_rgb(m.albedo_model);
    j["albedo_reference"] = json_rgb(m.albedo_reference);
    j["albedo_error"] = json_rgb(m.albedo_model - m.albedo_reference);
    j["max_error_remapped"] = {{"value", json_number(m.max_abs_remapped)},
                               {"theta", json_number(m.max_theta_deg)},
                               {"phi", json_number(m.max_phi_deg)},
                               {"channel", std::string(1, "RGB"[m.max_channel])}};
    j["reference_noise_remapped"] = json_number(m.reference_noise_remapped);
    const Json verdict = agreement_json(m.agreement);
    for (auto& [key, value] : verdict.items()) j[key] = value;
    // the white-furnace bound, on the reflection entry: reflected + transmitted <= 1 (+1e-3 for the bin
    // integration); a model that breaks it says so here, it is not clamped
    if (side == kReflection) {
        const glm::dvec3 total = scores.total_albedo[a];
        j["albedo_model_total"] = json_rgb(total);
        j["reflects_more_than_it_receives"] =
            std::max(total.x, std::max(total.y, total.z)) > 1.0 + kWhiteFurnaceTolerance;
    }
    return j;
}

Json side_json(const SimResult& ref, const ModelScores& scores, Side side) {
    Json list = Json::array();
    for (size_t a = 0; a < scores.side(side).size(); ++a) list.push_back(angle_json(ref, scores, a, side));
    return list;
}

// A scored model: how it was integrated, what it cost, and its metrics per incident angle and side
void scored_json(Json& e, const SimResult& ref, const ModelSlices& ms, const ModelScores& scores, const ModelCost& c) {
    e["applicable"] = true;
    e["scored"] = true;
    e["integration"] = ms.integration;
    if (ms.integration != "planned") {
        e["refined_bins"] = ms.refined_bins;
        e["unrefined_bins"] = ms.unrefined_bins;
    }
    if (!ms.file.empty()) e["compile_seconds"] = json_number(c.compile_seconds);
    e["seconds"] = json_number(c.wall_seconds);
    e["device_seconds"] = json_number(c.device_seconds);
    e["evaluations"] = c.evaluations;
    e["ns_per_evaluation"] = json_number(c.evaluations ? c.device_seconds * 1e9 / double(c.evaluations) : 0.0);
    e["angles"] = side_json(ref, scores, kReflection);
    if (!ms.t.empty()) e["transmission_angles"] = side_json(ref, scores, kTransmission);
}

// What the model claims (its header: true, false, or null where a user's file does not say) beside what gonio
// measured: its largest albedo on this stack, and a GLSL user's model's reciprocity (model_reciprocity.h)
Json claims_json(const ModelSlices& ms, const ModelScores& scores) {
    auto claim = [](int c) { return c < 0 ? Json(nullptr) : Json(c == 1); };
    Json j;
    j["claims"] = {{"reciprocal", claim(ms.claims_reciprocal)},
                   {"energy_conserving", claim(ms.claims_energy_conserving)}};
    if (!ms.energy_note.empty()) j["claims"]["energy_note"] = ms.energy_note;
    const LargestAlbedo& la = scores.largest;
    j["measured"]["largest_albedo"] = {{"value", json_number(la.value)},
                                       {"theta_i", json_number(la.theta_i)},
                                       {"channel", std::string(1, "RGB"[la.channel])},
                                       {"above_one", la.value > 1.0 + kWhiteFurnaceTolerance}};
    const ModelAsymmetry& a = ms.reciprocity;
    if (a.pairs)
        j["measured"]["reciprocity"] = {
            {"pairs", a.pairs},
            {"non_finite_pairs", a.non_finite},
            {"channels_compared", a.compared},
            {"largest_relative_asymmetry", json_number(a.worst)},
            {"where",
             {{"theta_l", json_number(a.theta_l)}, {"theta_v", json_number(a.theta_v)}, {"phi", json_number(a.phi)}}},
            {"reciprocal", a.compared ? Json(a.reciprocal()) : Json(nullptr)},
            {"tolerance", json_number(kReciprocityTolerance)}};
    return j;
}

// The family a model is grouped with in reports: a built-in's header's (its variants share it), else "your models"
std::string family_of(const ModelSlices& ms) {
    for (const ModelInfo& m : model_registry())
        if (m.id == ms.id) return m.header.family;
    return "your models";
}

}   // namespace

Json models_json(const SimResult& ref, const std::vector<ModelSlices>& models, const Comparison& c,
                 const std::vector<ModelCost>& costs, const ModelStageCost* stage) {
    Json o;
    if (stage)
        o["model_stage"] = {{"wall_seconds", json_number(stage->wall_seconds)},
                            {"device_seconds", json_number(stage->device_seconds)},
                            {"setup_seconds", json_number(stage->setup_seconds)},
                            {"pipeline_seconds", json_number(stage->pipeline_seconds)},
                            {"pipelines_created", stage->pipelines_created},
                            {"user_compile_seconds", json_number(stage->user_compile_seconds)}};
    o["best_model"] = best_models_json(ref, c);
    Json entries = Json::array();
    for (size_t i = 0; i < models.size(); ++i) {
        const ModelSlices& ms = models[i];
        Json e;
        e["id"] = ms.id;
        e["family"] = family_of(ms);
        if (!ms.file.empty()) e["file"] = ms.file;
        if (!ms.not_applicable.empty()) {
            e["applicable"] = false;
            e["reason"] = ms.not_applicable;
        } else if (!ms.invalid.empty()) {
            not_scored_json(e, ref, ms);
        } else {
            scored_json(e, ref, ms, c.models[i], i < costs.size() ? costs[i] : ModelCost{});
            const Json claims = claims_json(ms, c.models[i]);
            for (auto& [key, value] : claims.items()) e[key] = value;
        }
        entries.push_back(e);
    }
    o["models"] = entries;
    return o;
}

}   // namespace gonio
