// fit_json.cpp: see fit_json.h.
#include "fit_json.h"

#include <cmath>
#include <cstdio>

namespace gonio {

namespace {

Json metrics_json(const ModelMetrics& m) {
    Json j;
    j["rmse_remapped"] = json_rounded(m.rmse_remapped, 6);
    j["chi2_per_dof"] = json_rounded(m.agreement.chi2_per_dof, 5);
    j["mean_z"] = json_rounded(m.agreement.mean_z, 5);
    j["within_reference_noise"] = m.within_noise;
    j["verdict"] = m.within_noise ? "within the reference's noise" : m.agreement.reason;
    return j;
}

}   // namespace

Json fit_json(const FitSpec& spec, const std::string& stack, const SimResult& r, const FitResult& f,
              const Comparison& c) {
    Json j;
    j["model"] = spec.model;
    if (!spec.bias_corrections) j["bias_corrections"] = false;   // the negative control's fit (model_fit.h)
    j["stack"] = stack;
    j["loss"] = {
        {"name", to_string(spec.loss)}, {"start", json_number(f.loss_start)}, {"best", json_number(f.loss_best)}};
    Json params = Json::object();
    const std::string starts = f.starts > 1 ? ", the best of " + std::to_string(f.starts) + " starts" : "";
    std::printf(
        "fit of %s (loss %s: %.6g at the start, %.6g at the fit%s; %d iterations, %d model evaluations; "
        "stopped: %s)\n",
        spec.model.c_str(), to_string(spec.loss), f.loss_start, f.loss_best, starts.c_str(), f.iterations,
        f.evaluations, f.stopped.c_str());
    for (const FitParameter& p : f.parameters) {
        Json q;
        q["value"] = json_number(p.value);
        q["se"] = p.constrained ? json_number(p.se) : Json(nullptr);
        q["start"] = json_number(p.start);
        q["constrained"] = p.constrained;
        q["at_limit"] = p.at_limit;
        if (!p.channels.empty()) q["channels"] = p.channels;
        params[p.name] = q;
        const std::string in = p.channels == "rgb" ? " (one value in every channel)" : "";
        if (p.constrained)
            std::printf("  %s = %.6g +- %.2g (from %.6g)%s%s\n", p.name.c_str(), p.value, p.se, p.start,
                        p.at_limit ? ", at the end of its range" : "", in.c_str());
        else
            std::printf("  %s = %.6g: unconstrained (the loss does not change with it; from %.6g)%s\n", p.name.c_str(),
                        p.value, p.start, in.c_str());
    }
    j["parameters"] = params;
    j["correlation"] = f.correlation;
    Json angles = Json::array();
    for (size_t i = 0; i < r.angles.size(); ++i) {
        Json aj;
        aj["theta_i"] = r.options.theta_i_deg[i];
        if (r.options.phi_i_deg != 0.0) aj["phi_i"] = json_number(r.options.phi_i_deg);   // 0: the plane of incidence
        const std::vector<ModelMetrics>&start = c.models[0].r, &fit = c.models[1].r;
        if (i < start.size()) aj["start"] = metrics_json(start[i]);
        if (i < fit.size()) {
            const ModelMetrics& m = fit[i];
            aj["fit"] = metrics_json(m);
            std::printf("  theta_i %5g: RMSE %.4f -> %.4f, chi2/dof %.3g, %s\n", r.options.theta_i_deg[i],
                        i < start.size() ? start[i].rmse_remapped : NAN, m.rmse_remapped, m.agreement.chi2_per_dof,
                        m.within_noise ? "within the reference's noise" : "told apart");
        }
        angles.push_back(aj);
    }
    j["angles"] = angles;
    j["iterations"] = f.iterations;
    j["evaluations"] = f.evaluations;
    j["starts"] = f.starts;   // starting points descended from; the parameters' start is the kept one's
    j["stopped"] = f.stopped;
    j["fitted_model_id"] = spec.model + "@fit";
    return j;
}

}   // namespace gonio
