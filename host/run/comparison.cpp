// comparison.cpp: see comparison.h.
#include "comparison.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace gonio {

namespace {

ModelScores scores_of(const SimResult& ref, const ModelSlices& ms) {
    ModelScores s;
    if (!model_has_bins(ms)) return s;
    for (size_t a = 0; a < ms.f.size(); ++a)
        s.r.push_back(compare_model(ref, a, ms.f[a], kReflection, a < ms.f_err.size() ? &ms.f_err[a] : nullptr));
    for (size_t a = 0; a < ms.t.size(); ++a)
        s.t.push_back(compare_model(ref, a, ms.t[a], kTransmission, a < ms.t_err.size() ? &ms.t_err[a] : nullptr));
    for (size_t a = 0; a < s.r.size(); ++a) {
        glm::dvec3 total = s.r[a].albedo_model;
        if (a < s.t.size()) total += s.t[a].albedo_model;
        s.total_albedo.push_back(total);
        for (int c = 0; c < kChannels; ++c)
            if (total[c] > s.largest.value) s.largest = {total[c], ref.angles[a].theta_i_deg, c};
    }
    return s;
}

// The best model on one slice by rmse_remapped, and whether the reference's noise tells the runner-up from it
BestModel best_on_slice(const SimResult& ref, size_t angle, Side side, const std::vector<ModelSlices>& models,
                        const std::vector<ModelScores>& scores) {
    std::vector<std::pair<double, size_t>> ranked;
    for (size_t i = 0; i < models.size(); ++i) {
        const std::vector<ModelMetrics>& m = scores[i].side(side);
        if (angle < m.size()) ranked.push_back({m[angle].rmse_remapped, i});
    }
    if (ranked.empty()) return {};
    std::sort(ranked.begin(), ranked.end());
    if (ranked.size() < 2) return BestModel{models[ranked[0].second].id, ""};
    return separate_models(ref, angle, side, models[ranked[0].second], models[ranked[1].second]);
}

}   // namespace

const BestModel& Comparison::best_of(size_t angle, Side side) const {
    static const BestModel none;
    const std::vector<BestModel>& b = best[side == kReflection ? 0 : 1];
    return angle < b.size() ? b[angle] : none;
}

Comparison compare_models(const SimResult& ref, const std::vector<ModelSlices>& models) {
    Comparison c;
    for (const ModelSlices& ms : models) c.models.push_back(scores_of(ref, ms));
    for (int side = 0; side < int(ref.n_sides); ++side)
        for (size_t a = 0; a < ref.angles.size(); ++a)
            c.best[side].push_back(best_on_slice(ref, a, Side(side), models, c.models));
    return c;
}

void warn_energy_gains(const SimResult& ref, const std::vector<ModelSlices>& models, const Comparison& c) {
    for (size_t i = 0; i < models.size(); ++i) {
        const ModelSlices& ms = models[i];
        const std::vector<glm::dvec3>& totals = c.models[i].total_albedo;
        for (size_t a = 0; a < totals.size(); ++a) {
            const glm::dvec3 total = totals[a];
            double mx = std::max(total.x, std::max(total.y, total.z));
            if (mx <= 1.0 + kWhiteFurnaceTolerance) continue;
            const std::string whose = ms.file.empty() ? "it claims" : "its header claims";
            const std::string why =
                ms.claims_energy_conserving == 1
                    ? whose + " energy conservation: a bug" + (ms.file.empty() ? ", please report it" : "")
                : ms.claims_energy_conserving == 0
                    ? (ms.energy_note.empty() ? "not energy-conserving by its header" : ms.energy_note)
                    : "its header does not say whether it conserves energy";
            std::fprintf(stderr, "gonio: %s reflects %.4f of the light it receives at theta_i %g (not clamped; %s)\n",
                         ms.id.c_str(), mx, ref.angles[a].theta_i_deg, why.c_str());
        }
    }
}

}   // namespace gonio
