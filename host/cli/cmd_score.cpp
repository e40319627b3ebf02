// cmd_score.cpp: `gonio score`: a model in any language, through files: the values of f the user's code wrote at the
// nodes of gonio nodes (cmd_nodes.cpp), put on a reference run's bins and written as compare writes a model.
#include "cmd_score.h"
#include "input_file.h"

#include "bin_nodes.h"
#include "case.h"
#include "json.h"
#include "model_table.h"
#include "node_files.h"
#include "output.h"
#include "python_tool.h"
#include "stack.h"
#include "text_format.h"
#include "state.h"
#include "validation.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace gonio {

namespace {

constexpr const char* kScoreUsage = "NODES_DIR --values FILE --id ID --reference SIMULATE_DIR --out DIR [--no-report]";

struct ScoreSettings {
    std::string values, id, reference, out;
    bool no_report = false;
};

OptionTable score_options(ScoreSettings& a) {
    return {
        {"--values", "FILE",
         "the values of f at the nodes: one row r,g,b per node, in nodes.csv's order (an optional header r,g,b), or "
         "a .npy of shape (nodes, 3); 1/sr, cosine excluded (required)",
         [&a](const std::string& v) { a.values = v; }},
        {"--id", "ID",
         "the model's name in the outputs: not 'reference', no comma, quote or control character (required)",
         [&a](const std::string& v) { a.id = v; }},
        {"--reference", "SIMULATE_DIR", "a simulate run of the same stack, angles and bins (required)",
         [&a](const std::string& v) { a.reference = v; }},
        {"--out", "DIR", "where slices.csv, summary.json, the EXR and report.html go (required)",
         [&a](const std::string& v) { a.out = v; }},
        {"--no-report", nullptr, "no figures, no report.html", [&a](const std::string&) { a.no_report = true; }},
    };
}

int run_score(ScoreSettings& a, const std::vector<std::string>& operands) {
    if (operands.size() > 1)
        usage_error("score takes one nodes directory, got '" + operands[0] + "' and '" + operands[1] + "'");
    const std::string dir = operands.empty() ? "" : operands[0];
    const std::string &values_path = a.values, &id = a.id, &ref_dir = a.reference, &out = a.out;
    if (dir.empty() || values_path.empty() || id.empty() || ref_dir.empty() || out.empty())
        usage_error("score: gonio score " + std::string(kScoreUsage));
    if (!usable_model_id(id))
        usage_error("score: --id '" + id +
                    "' cannot name a model (not 'reference', no comma, quote or control character)");
    if (same_path(out, ref_dir) || same_path(out, dir))
        usage_error("score: --out " + out + " is the " + (same_path(out, ref_dir) ? "reference's" : "nodes'") +
                    " directory, which is left as it is: give another");
    const NodesFile nf = read_nodes_json(dir);
    const Stack& s = nf.stack;
    const std::vector<double>& theta_i = nf.theta_i;
    const double dtheta = nf.dtheta, dphi = nf.dphi;
    const int k = nf.k, sides = nf.sides;
    const SimResult ref = load_state(ref_dir + "/state.gonio");
    // the reference must be a run of the same stack, angles and bins
    auto differs = [&](const std::string& what) {
        usage_error("score: " + ref_dir + " is not a run of the nodes' stack, angles and bins (" + what + ")");
    };
    if (stack_to_toml(ref.stack) != stack_to_toml(s)) differs("another stack");
    if (ref.options.theta_i_deg != theta_i) differs("other incident angles");
    if (ref.options.phi_i_deg != nf.phi_i)
        differs("incident azimuth " + format_g9(ref.options.phi_i_deg) + ", the nodes' " + format_g9(nf.phi_i));
    if (ref.options.dtheta_deg != dtheta || ref.options.dphi_deg != dphi) differs("other bins");
    const bool npy = values_path.size() > 4 && values_path.substr(values_path.size() - 4) == ".npy";
    const std::vector<glm::dvec3> values = npy ? read_values_npy(values_path) : read_values(values_path);
    const ModelGrid g = grid_of(theta_i, dtheta, dphi, nf.phi_i);
    if (values.size() != nf.nodes)
        throw StackError(values_path, int(values.size()),
                         std::to_string(values.size()) + " values for " + std::to_string(nf.nodes) +
                             " nodes (one row r,g,b per row of nodes.csv, in its order)");
    std::vector<ModelSlices> slices{slices_from_node_values(id, g, sides, k, values)};
    slices[0].file = values_path;   // a user's model: its energy measured, its reciprocity not (gonio does not run it)
    const ModelsOnCase models = models_on_case(ref, std::move(slices));
    warn_energy_gains(ref, models.slices, models.comparison);
    write_models_beside(out, ref, models);
    print_model_metrics(ref, models.slices, models.comparison);
    std::printf("wrote %s/{%s.exr,slices.csv,summary.json}\n", out.c_str(), safe_file_name(ref.stack.name).c_str());
    const int rc = check_finite_json();
    if (!a.no_report) run_python_tool("report.py", out, "the figures and report.html");
    return rc;
}

}   // namespace

Command score_command() {
    return {"score", kScoreUsage,
            "the values of f at the nodes of gonio nodes on the bins of a simulate run of the same stack, angles and "
            "bins: what compare writes for a model (slices.csv, summary.json, EXR, report.html)",
            "", invocation(&score_options, &run_score)};
}

}   // namespace gonio
