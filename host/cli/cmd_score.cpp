// cmd_score.cpp: `gonio score`: a model in any language, through files: the values of f the user's code wrote at the
// nodes of gonio nodes (cmd_nodes.cpp), put on a reference run's bins and written as compare writes a model.
#include "cmd_score.h"

#include "model_table.h"
#include "bin_nodes.h"
#include "compare.h"
#include "json.h"
#include "models_json.h"
#include "node_files.h"
#include "output.h"
#include "python_tool.h"
#include "stack.h"
#include "state.h"
#include "validation.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

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
        {"--id", "ID", "the model's name in the outputs: not 'reference', no comma or quote (required)",
         [&a](const std::string& v) { a.id = v; }},
        {"--reference", "SIMULATE_DIR", "a simulate run of the same stack, angles and bins (required)",
         [&a](const std::string& v) { a.reference = v; }},
        {"--out", "DIR", "where slices.csv, summary.json, the EXR and report.html go (required)",
         [&a](const std::string& v) { a.out = v; }},
        {"--no-report", nullptr, "no figures, no report.html", [&a](const std::string&) { a.no_report = true; }},
    };
}

// The values file: one row per node, in nodes.csv's order, "r,g,b" (an optional header line r,g,b first).
std::vector<glm::dvec3> read_values(const std::string& path) {
    std::ifstream f(path);
    if (!f) throw StackError(path, 0, "cannot open the values file for reading");
    std::vector<glm::dvec3> v;
    std::string line;
    int n = 0, bad = 0, first_bad = 0;
    while (std::getline(f, line)) {
        ++n;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (n == 1 && line == "r,g,b") continue;
        if (line.empty()) throw StackError(path, n, "an empty line (expected r,g,b: three numbers per node)");
        std::stringstream ss(line);
        std::string cell;
        glm::dvec3 x;
        int c = 0;
        while (std::getline(ss, cell, ',')) {
            if (c == 3) throw StackError(path, n, "more than three numbers (expected r,g,b)");
            char* end = nullptr;
            x[c] = std::strtod(cell.c_str(), &end);
            if (cell.empty() || end == cell.c_str() || *end != '\0')
                throw StackError(path, n, "'" + cell + "' is not a number (expected r,g,b)");
            ++c;
        }
        if (c != 3) throw StackError(path, n, "expected three numbers r,g,b, got " + std::to_string(c));
        for (int k = 0; k < 3; ++k)
            if (!std::isfinite(x[k]) || x[k] < 0) {
                if (bad++ == 0) first_bad = n;
            }
        v.push_back(x);
    }
    if (bad > 0)
        throw StackError(path, first_bad,
                         std::to_string(bad) +
                             " values are negative, NaN or infinite (the first on this line): a BRDF is finite and "
                             "non-negative; nothing is clamped");
    return v;
}

// Values as .npy: shape (nodes, 3), float64 or float32, C order, little-endian (numpy.save of an array r,g,b).
std::vector<glm::dvec3> read_values_npy(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw StackError(path, 0, "cannot open the values file for reading");
    char magic[8];
    if (!f.read(magic, 8) || std::string(magic, 6) != "\x93NUMPY")
        throw StackError(path, 0, "not a .npy file (numpy.save of an array of shape (nodes, 3))");
    uint32_t hl = 0;
    if (magic[6] == 1) {
        unsigned char b[2];
        f.read(reinterpret_cast<char*>(b), 2);
        hl = b[0] | (b[1] << 8);
    } else {
        unsigned char b[4];
        f.read(reinterpret_cast<char*>(b), 4);
        hl = b[0] | (b[1] << 8) | (b[2] << 16) | (uint32_t(b[3]) << 24);
    }
    std::string h(hl, '\0');
    f.read(h.data(), hl);
    const bool f8 = h.find("'descr': '<f8'") != std::string::npos, f4 = h.find("'descr': '<f4'") != std::string::npos;
    if (!(f8 || f4) || h.find("'fortran_order': False") == std::string::npos)
        throw StackError(path, 0, "a .npy of little-endian float64 or float32 in C order expected, header " + h);
    const size_t open = h.find("'shape': ("), comma = h.find(',', open), close = h.find(')', open);
    if (open == std::string::npos || comma == std::string::npos || close == std::string::npos)
        throw StackError(path, 0, "no shape in the .npy header " + h);
    const size_t rows = std::stoull(h.substr(open + 10, comma - open - 10));
    const std::string cols = h.substr(comma + 1, close - comma - 1);
    if (std::stoull(cols.empty() ? "0" : cols) != 3)
        throw StackError(path, 0, "shape (nodes, 3) expected (r, g, b per node), header " + h);
    std::vector<glm::dvec3> v(rows);
    for (size_t i = 0; i < rows; ++i)
        for (int c = 0; c < kChannels; ++c) {
            double x;
            if (f8) {
                f.read(reinterpret_cast<char*>(&x), 8);
            } else {
                float y;
                f.read(reinterpret_cast<char*>(&y), 4);
                x = y;
            }
            if (!f) throw StackError(path, 0, "the data end before " + std::to_string(rows) + " rows");
            if (!std::isfinite(x) || x < 0)
                throw StackError(path, 0,
                                 "row " + std::to_string(i) +
                                     " (from 0) holds a negative, NaN or infinite value: a BRDF is finite and "
                                     "non-negative; nothing is clamped");
            v[i][c] = x;
        }
    return v;
}

int run_score(ScoreSettings& a, const std::vector<std::string>& operands) {
    if (operands.size() > 1)
        usage_error("score takes one nodes directory, got '" + operands[0] + "' and '" + operands[1] + "'");
    const std::string dir = operands.empty() ? "" : operands[0];
    const std::string &values_path = a.values, &id = a.id, &ref_dir = a.reference, &out = a.out;
    if (dir.empty() || values_path.empty() || id.empty() || ref_dir.empty() || out.empty())
        usage_error("score: gonio score " + std::string(kScoreUsage));
    if (id == "reference" || id.find(',') != std::string::npos || id.find('"') != std::string::npos)
        usage_error("score: --id '" + id + "' cannot name a model (not 'reference', no comma or quote)");
    const Json j = read_json_file(dir + "/nodes.json");
    if (!j.contains("gonio_nodes") || j["gonio_nodes"] != kNodesFormat)
        throw StackError(dir + "/nodes.json", 1,
                         "not a nodes.json of this gonio (gonio_nodes " + std::to_string(kNodesFormat) + " expected)");
    const Stack s = parse_stack_string(j["stack"].get<std::string>(), dir + "/nodes.json (stack)");
    const std::vector<double> theta_i = j["theta_i"].get<std::vector<double>>();
    const double dtheta = j["dtheta"].get<double>(), dphi = j["dphi"].get<double>();
    const int k = j["k"].get<int>(), sides = j["sides"].get<int>();
    const SimResult ref = load_state(ref_dir + "/state.gonio");
    // the reference must be a run of the same stack, angles and bins
    auto differs = [&](const std::string& what) {
        usage_error("score: " + ref_dir + " is not a run of the nodes' stack, angles and bins (" + what + ")");
    };
    if (stack_to_toml(ref.stack) != stack_to_toml(s)) differs("another stack");
    if (ref.options.theta_i_deg != theta_i) differs("other incident angles");
    if (ref.options.dtheta_deg != dtheta || ref.options.dphi_deg != dphi) differs("other bins");
    const bool npy = values_path.size() > 4 && values_path.substr(values_path.size() - 4) == ".npy";
    const std::vector<glm::dvec3> values = npy ? read_values_npy(values_path) : read_values(values_path);
    const ModelGrid g = grid_of(theta_i, dtheta, dphi);
    if (values.size() != j["nodes"].get<size_t>())
        throw StackError(values_path, int(values.size()),
                         std::to_string(values.size()) + " values for " + std::to_string(j["nodes"].get<size_t>()) +
                             " nodes (one row r,g,b per row of nodes.csv, in its order)");
    std::vector<ModelSlices> models{slices_from_node_values(id, g, sides, k, values)};
    models[0].file = values_path;   // a user's model: its energy measured, its reciprocity not (gonio does not run it)
    warn_energy_gains(ref, models);
    fs::create_directories(out);
    const Json models_summary = models_json(ref, models, {});
    write_exr(out + "/" + safe_file_name(ref.stack.name) + ".exr", ref, &models);
    write_slices_csv(out + "/slices.csv", ref, &models);
    write_summary_json(out + "/summary.json", ref, &models_summary);
    print_model_metrics(ref, models);
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
