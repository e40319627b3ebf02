// node_files.cpp: see node_files.h.
#include "node_files.h"

#include <algorithm>
#include "json.h"
#include "sim_options.h"
#include "text_format.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace gonio {

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

std::string node_count_refusal(size_t angles, int sides, double bins, int k) {
    const double n = double(angles) * sides * bins * k * k;
    if (n <= double(kMaxNodes)) return "";
    char b[400];
    std::snprintf(b, sizeof b,
                  "%.4g nodes (%zu angles x %d side%s x %.0f bins x %d x %d) is more than the %llu whose values a "
                  "values file of %s holds as .npy (24 bytes a node): fewer angles (--theta-i), wider bins (--dtheta, "
                  "--dphi) or fewer nodes (--nodes-per-bin)",
                  n, angles, sides, sides == 2 ? "s" : "", bins, k, k, (unsigned long long)kMaxNodes,
                  byte_size_text(kMaxValuesFileBytes).c_str());
    return b;
}

NodesFile read_nodes_json(const std::string& dir) {
    const std::string path = dir + "/nodes.json";
    const Json j = read_json_file(path);
    auto bad = [&](const std::string& field, const std::string& why) -> StackError {
        return StackError(path, 1, field + ": " + why + " (not as gonio nodes writes it)");
    };
    if (!j.is_object() || !j.contains("gonio_nodes") || j["gonio_nodes"] != kNodesFormat)
        throw StackError(path, 1,
                         "not a nodes.json of this gonio (gonio_nodes " + std::to_string(kNodesFormat) + " expected)");
    NodesFile f;
    const char* field = "";
    try {
        field = "stack";
        f.stack = parse_stack_string(j.at("stack").get<std::string>(), path + " (stack)");
        field = "theta_i";
        f.theta_i = j.at("theta_i").get<std::vector<double>>();
        field = "dtheta";
        f.dtheta = j.at("dtheta").get<double>();
        field = "dphi";
        f.dphi = j.at("dphi").get<double>();
        field = "k";
        f.k = j.at("k").get<int>();
        field = "sides";
        f.sides = j.at("sides").get<int>();
        field = "nodes";
        f.nodes = j.at("nodes").get<uint64_t>();
        field = "phi_i";
        if (j.contains("phi_i")) f.phi_i = j.at("phi_i").get<double>();
    } catch (const Json::exception& e) { throw bad(field, std::string("missing or of the wrong type: ") + e.what()); }
    SimOptions o;   // the angles and bins, as simulate checks them
    o.theta_i_deg = f.theta_i;
    o.dtheta_deg = f.dtheta;
    o.dphi_deg = f.dphi;
    o.phi_i_deg = f.phi_i;
    try {
        validate_options(o);
    } catch (const std::invalid_argument& e) { throw bad("theta_i, phi_i, dtheta or dphi", e.what()); }
    if (f.k < 1 || f.k > kMaxNodesPerBinSide)
        throw bad("k", "expected 1 to " + std::to_string(kMaxNodesPerBinSide) + ", got " + std::to_string(f.k));
    if (f.sides != (f.stack.transmissive() ? 2 : 1))
        throw bad("sides", "the stack has " + std::string(f.stack.transmissive() ? "2" : "1") + ", got " +
                               std::to_string(f.sides));
    const ModelGrid g = grid_of(f.theta_i, f.dtheta, f.dphi, f.phi_i);
    const std::string too_many = node_count_refusal(f.theta_i.size(), f.sides, double(g.n_theta) * g.n_phi, f.k);
    if (!too_many.empty()) throw bad("the grid", too_many);
    const uint64_t n = uint64_t(f.theta_i.size()) * uint64_t(f.sides) * g.n_theta * g.n_phi * uint64_t(f.k * f.k);
    if (f.nodes != n) throw bad("nodes", "the grid has " + std::to_string(n) + ", got " + std::to_string(f.nodes));
    return f;
}

void write_nodes_files(const std::string& out, const std::string& stack_file, const NodesFile& nf,
                       const std::vector<BinNode>& nodes) {
    std::filesystem::create_directories(out);
    {
        std::ofstream f(out + "/nodes.csv");
        f << "theta_i,side,bin,lx,ly,lz,vx,vy,vz,weight\n";
        char b[320];
        for (const BinNode& n : nodes) {
            std::snprintf(b, sizeof b, "%s,%s,%u,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                          format_g9(nf.theta_i[n.angle]).c_str(), n.side ? "T" : "R", n.bin, n.l.x, n.l.y, n.l.z, n.v.x,
                          n.v.y, n.v.z, n.weight);
            f << b;
        }
        if (!f) throw std::runtime_error("cannot write " + out + "/nodes.csv");
    }
    {   // the same as nodes.npy, float64 (theta_i, side 0 = R / 1 = T, bin, lx, ly, lz, vx, vy, vz, weight)
        std::vector<double> d;
        d.reserve(nodes.size() * 10);
        for (const BinNode& n : nodes)
            d.insert(d.end(), {nf.theta_i[n.angle], double(n.side), double(n.bin), n.l.x, n.l.y, n.l.z, n.v.x, n.v.y,
                               n.v.z, n.weight});
        write_npy_f8(out + "/nodes.npy", d, nodes.size(), 10);
    }
    Json j;
    j["gonio_nodes"] = kNodesFormat;
    j["stack_file"] = stack_file;
    j["stack"] = stack_to_toml(nf.stack);
    j["theta_i"] = nf.theta_i;
    if (nf.phi_i != 0.0) j["phi_i"] = nf.phi_i;   // the plane of incidence's files have none
    j["dtheta"] = nf.dtheta;
    j["dphi"] = nf.dphi;
    j["nodes_per_bin"] = nf.k * nf.k;
    j["k"] = nf.k;
    j["sides"] = nf.sides;
    j["nodes"] = nf.nodes;
    write_json_file(out + "/nodes.json", j);
}

bool usable_model_value(double x) {
    return std::isfinite(x) && x >= 0 && x <= double(std::numeric_limits<float>::max());
}

bool usable_model_id(const std::string& id) {
    const bool control = std::any_of(id.begin(), id.end(), [](char c) { return (unsigned char)c < 0x20 || c == 0x7f; });
    return !id.empty() && id != "reference" && id.find(',') == std::string::npos && id.find('"') == std::string::npos &&
           !control;
}

// The values file: one row per node, in nodes.csv's order, "r,g,b" (an optional header line r,g,b first).
std::vector<glm::dvec3> read_values(const std::string& path) {
    const std::string why = input_file_refusal(path, "values file", kMaxValuesFileBytes);
    if (!why.empty()) throw StackError(path, 0, why);
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
            if (!usable_model_value(x[k])) {
                if (bad++ == 0) first_bad = n;
            }
        v.push_back(x);
    }
    if (bad > 0)
        throw StackError(path, first_bad,
                         std::to_string(bad) +
                             " values are negative, NaN, infinite or beyond the largest float (3.4e38: the bins and "
                             "the EXR hold floats; the first on this line): a BRDF is finite and non-negative; "
                             "nothing is clamped");
    return v;
}

// Values as .npy: shape (nodes, 3), float64 or float32, C order, little-endian (numpy.save of an array r,g,b).
std::vector<glm::dvec3> read_values_npy(const std::string& path) {
    const std::string why = input_file_refusal(path, "values file", kMaxValuesFileBytes);
    if (!why.empty()) throw StackError(path, 0, why);
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
            if (!usable_model_value(x))
                throw StackError(path, 0,
                                 "row " + std::to_string(i) +
                                     " (from 0) holds a negative, NaN, infinite value or one beyond the largest float "
                                     "(3.4e38: the bins and the EXR hold floats): a BRDF is finite and non-negative; "
                                     "nothing is clamped");
            v[i][c] = x;
        }
    return v;
}

}   // namespace gonio
