// case.cpp: see case.h.
#include "case.h"
#include "histogram.h"
#include "model_table.h"
#include "models_json.h"
#include "output.h"
#include "state.h"
#include "validation.h"
#include "vk_context.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace gonio {

ModelsOnCase models_on_case(const SimResult& ref, std::vector<ModelSlices> slices, std::vector<ModelCost> costs,
                            std::optional<ModelStageCost> stage) {
    ModelsOnCase m{std::move(slices), std::move(costs), stage, {}};
    m.comparison = compare_models(ref, m.slices);
    return m;
}

CaseResult run_case(VkContext& ctx, const Case& c, const ModelOptions* models) {
    CaseResult r;
    r.reference = simulate_gpu(ctx, c.stack, c.sim, c.resumed());
    if (!models) return r;
    std::vector<ModelCost> costs;
    ModelStageCost stage;
    std::vector<ModelSlices> slices = evaluate_models(ctx, c.stack, model_grid(r.reference), &costs, *models, &stage);
    r.models = models_on_case(r.reference, std::move(slices), std::move(costs), stage);
    warn_energy_gains(r.reference, r.models->slices, r.models->comparison);
    return r;
}

int run_and_write_case(VkContext& ctx, const Case& c, const ModelOptions* models) {
    return write_case(c, run_case(ctx, c, models));
}

namespace {

Json models_summary(const SimResult& ref, const ModelsOnCase& m) {
    return models_json(ref, m.slices, m.comparison, m.costs, m.stage ? &*m.stage : nullptr);
}

}   // namespace

Json case_summary_json(const CaseResult& cr) {
    if (!cr.models) return summary_json(cr.reference);
    const Json models = models_summary(cr.reference, *cr.models);
    return summary_json(cr.reference, &models);
}

std::string case_slices_csv(const CaseResult& cr) {
    return slices_csv_text(cr.reference, cr.models ? &cr.models->slices : nullptr);
}

void write_case_files(const std::string& out, const CaseResult& cr) {
    const SimResult& r = cr.reference;
    const std::vector<ModelSlices>* models = cr.models ? &cr.models->slices : nullptr;
    write_exr(out + "/" + safe_file_name(r.stack.name) + ".exr", r, models);
    write_slices_csv(out + "/slices.csv", r, models);
    const std::optional<Json> summary = cr.models ? std::optional<Json>(models_summary(r, *cr.models)) : std::nullopt;
    write_summary_json(out + "/summary.json", r, summary ? &*summary : nullptr);
    save_state(out + "/state.gonio", r);
}

void write_models_beside(const std::string& out, const SimResult& ref, const ModelsOnCase& m) {
    std::filesystem::create_directories(out);
    const Json summary = models_summary(ref, m);
    write_exr(out + "/" + safe_file_name(ref.stack.name) + ".exr", ref, &m.slices);
    write_slices_csv(out + "/slices.csv", ref, &m.slices);
    write_summary_json(out + "/summary.json", ref, &summary);
}

int write_case(const Case& c, const CaseResult& cr) {
    const SimResult& r = cr.reference;
    const std::string& out = c.out;
    const std::string name = safe_file_name(c.stack.name);
    int rc = 0;
    write_case_files(out, cr);
    for (size_t i = 0; i < r.angles.size(); ++i) {
        EnergyBook e = energy_book(r, i);
        if (e.invalid.x > 0) {   // walk.glsl path_is_finite: booked apart, never as absorbed or leaving
            std::fprintf(stderr,
                         "gonio: theta_i %g: %.0f paths booked a number that is not finite (summary.json: energy "
                         "invalid %.3g): a bug, please report it with the stack file and the command\n",
                         r.angles[i].theta_i_deg, e.invalid.x * double(r.angles[i].paths), e.invalid.x);
            rc = 1;
        }
        std::printf("theta_i %5g: R %.5f %.5f %.5f, T %.5f %.5f %.5f, %llu paths (%s), median rse %.4f, worst %.3f\n",
                    r.angles[i].theta_i_deg, e.reflected.x, e.reflected.y, e.reflected.z, e.transmitted.x,
                    e.transmitted.y, e.transmitted.z, (unsigned long long)r.angles[i].paths,
                    r.angles[i].stopped_by.c_str(), r.angles[i].median_rse, r.angles[i].worst_rse);
    }
    if (cr.models) {
        print_model_metrics(r, cr.models->slices, cr.models->comparison);
        for (const ModelSlices& m : cr.models->slices)
            if (!m.invalid.empty()) {   // never scored: summary.json says where
                std::fprintf(stderr, "gonio: %s: its bins cannot be used: %s\n", m.id.c_str(), m.invalid.c_str());
                rc = 1;
            }
    }
    std::printf("wrote %s/{%s.exr,slices.csv,summary.json,state.gonio}\n", out.c_str(), name.c_str());
    return std::max(rc, check_finite_json());
}

}   // namespace gonio
