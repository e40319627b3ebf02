// cmd_nodes.cpp: `gonio nodes` and `gonio score`: a model in any language, through files. nodes writes where to
// evaluate f (bin_nodes.h); the user's code writes f there; score puts those values on a reference run's bins and
// writes what compare writes for a model.
#include "cmd_nodes.h"

#include "args.h"
#include "bin_nodes.h"
#include "compare.h"
#include "json.h"
#include "output.h"
#include "python_tool.h"
#include "stack.h"
#include "state.h"
#include "text_format.h"

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

constexpr int kNodesFormat = 1;

ModelGrid grid_of(const std::vector<double>& theta_i, double dtheta, double dphi) {
    return {uint32_t(std::lround(90.0 / dtheta)), uint32_t(std::lround(360.0 / dphi)), dtheta, dphi, theta_i};
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

// NumPy's .npy format 1.0 (numpy.lib.format): the magic, a little-endian header length, a dict padded with spaces to
// a multiple of 64 bytes ending in a newline, then the data in C order.
void write_npy_f8(const std::string& path, const std::vector<double>& data, size_t rows, size_t cols) {
    std::string h = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ", " +
                    std::to_string(cols) + "), }";
    while ((10 + h.size() + 1) % 64 != 0) h += ' ';
    h += '\n';
    std::ofstream f(path, std::ios::binary);
    const uint16_t n = uint16_t(h.size());
    f.write("\x93NUMPY\x01\x00", 8);
    f.put(char(n & 0xff));
    f.put(char(n >> 8));
    f.write(h.data(), std::streamsize(h.size()));
    f.write(reinterpret_cast<const char*>(data.data()), std::streamsize(data.size() * sizeof(double)));
    if (!f) throw std::runtime_error("cannot write " + path);
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
        for (int c = 0; c < 3; ++c) {
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

}   // namespace

int cmd_nodes(int argc, char** argv) {
    std::string stack_path, out;
    std::vector<double> theta_i{0.0};
    double dtheta = 1.0, dphi = 2.0;
    uint64_t k = 4;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() {
            if (i + 1 >= argc) usage_error(a + " needs a value");
            return std::string(argv[++i]);
        };
        if (a == "--theta-i")
            theta_i = parse_list(a, value());
        else if (a == "--dtheta")
            dtheta = parse_number(a, value());
        else if (a == "--dphi")
            dphi = parse_number(a, value());
        else if (a == "--nodes-per-bin")
            k = parse_count(a, value());
        else if (a == "--out")
            out = value();
        else if (a.rfind("--", 0) == 0)
            usage_error("unknown option " + a +
                        " for nodes (it takes --theta-i, --dtheta, --dphi, --nodes-per-bin, --out)");
        else if (stack_path.empty())
            stack_path = a;
        else
            usage_error("nodes takes one stack file, got '" + stack_path + "' and '" + a + "'");
    }
    if (stack_path.empty()) usage_error("nodes: which stack file?");
    if (out.empty()) usage_error("nodes: --out DIR");
    if (k < 1 || k > 16) usage_error("--nodes-per-bin must be 1 to 16 (k x k nodes per bin), got " + std::to_string(k));
    const Stack s = parse_stack_file(stack_path);
    SimOptions o;   // the angles and bins, checked as simulate checks them
    o.theta_i_deg = theta_i;
    o.dtheta_deg = dtheta;
    o.dphi_deg = dphi;
    try {
        validate_options(o);
    } catch (const std::invalid_argument& e) { usage_error(e.what()); }
    const ModelGrid g = grid_of(theta_i, dtheta, dphi);
    const int sides = s.transmissive() ? 2 : 1;
    const std::vector<BinNode> nodes = bin_nodes(g, sides, int(k));
    fs::create_directories(out);
    {
        std::ofstream f(out + "/nodes.csv");
        f << "theta_i,side,bin,lx,ly,lz,vx,vy,vz,weight\n";
        char b[320];
        for (const BinNode& n : nodes) {
            std::snprintf(b, sizeof b, "%s,%s,%u,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                          format_g9(g.theta_i_deg[n.angle]).c_str(), n.side ? "T" : "R", n.bin, n.l.x, n.l.y, n.l.z,
                          n.v.x, n.v.y, n.v.z, n.weight);
            f << b;
        }
        if (!f) throw std::runtime_error("cannot write " + out + "/nodes.csv");
    }
    {   // the same as nodes.npy, float64 (theta_i, side 0 = R / 1 = T, bin, lx, ly, lz, vx, vy, vz, weight)
        std::vector<double> d;
        d.reserve(nodes.size() * 10);
        for (const BinNode& n : nodes)
            d.insert(d.end(), {g.theta_i_deg[n.angle], double(n.side), double(n.bin), n.l.x, n.l.y, n.l.z, n.v.x, n.v.y,
                               n.v.z, n.weight});
        write_npy_f8(out + "/nodes.npy", d, nodes.size(), 10);
    }
    Json j;
    j["gonio_nodes"] = kNodesFormat;
    j["stack_file"] = stack_path;
    j["stack"] = stack_to_toml(s);
    j["theta_i"] = theta_i;
    j["dtheta"] = dtheta;
    j["dphi"] = dphi;
    j["nodes_per_bin"] = k * k;
    j["k"] = k;
    j["sides"] = sides;
    j["nodes"] = nodes.size();
    write_json_file(out + "/nodes.json", j);
    std::printf("wrote %s/nodes.csv (%zu nodes: %zu angles x %d side%s x %u bins x %llu), nodes.npy and nodes.json\n",
                out.c_str(), nodes.size(), theta_i.size(), sides, sides == 2 ? "s" : "", g.n_theta * g.n_phi,
                (unsigned long long)(k * k));
    return 0;
}

int cmd_score(int argc, char** argv) {
    std::string dir, values_path, id, ref_dir, out;
    bool report = true;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() {
            if (i + 1 >= argc) usage_error(a + " needs a value");
            return std::string(argv[++i]);
        };
        if (a == "--values")
            values_path = value();
        else if (a == "--id")
            id = value();
        else if (a == "--reference")
            ref_dir = value();
        else if (a == "--out")
            out = value();
        else if (a == "--no-report")
            report = false;
        else if (a.rfind("--", 0) == 0)
            usage_error("unknown option " + a +
                        " for score (it takes --values, --id, --reference, --out, --no-report)");
        else if (dir.empty())
            dir = a;
        else
            usage_error("score takes one nodes directory, got '" + dir + "' and '" + a + "'");
    }
    if (dir.empty() || values_path.empty() || id.empty() || ref_dir.empty() || out.empty())
        usage_error("score: gonio score NODES_DIR --values FILE --id ID --reference SIMULATE_DIR --out DIR");
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
    warn_energy_gains(ref, models);
    fs::create_directories(out);
    const Json models_summary = models_json(ref, models, {});
    write_exr(out + "/" + safe_file_name(ref.stack.name) + ".exr", ref, &models);
    write_slices_csv(out + "/slices.csv", ref, &models);
    write_summary_json(out + "/summary.json", ref, &models_summary);
    print_model_metrics(ref, models);
    std::printf("wrote %s/{%s.exr,slices.csv,summary.json}\n", out.c_str(), safe_file_name(ref.stack.name).c_str());
    int rc = 0;
    if (non_finite_json_numbers() > 0) {
        std::fprintf(stderr,
                     "gonio: %llu numbers of summary.json were not finite (written as null): a bug, please report it\n",
                     (unsigned long long)non_finite_json_numbers());
        rc = 1;
    }
    if (report) run_python_tool("report.py", out, "the figures and report.html");
    return rc;
}

}   // namespace gonio
