// cmd_nodes.cpp: `gonio nodes`: a model in any language, through files. nodes writes where to evaluate f
// (bin_nodes.h); the user's code writes f there; gonio score (cmd_score.cpp) puts those values on a reference run's
// bins.
#include "cmd_nodes.h"

#include "bin_nodes.h"
#include "node_files.h"
#include "sim_options.h"
#include "stack.h"

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace gonio {

namespace {

struct NodesSettings {
    std::string out;
    std::vector<double> theta_i{0.0};
    double dtheta = 1.0, dphi = 2.0;
    double phi_i = 0.0;
    uint64_t k = 4;   // k x k nodes per bin
};

OptionTable nodes_options(NodesSettings& a) {
    return {
        {"--out", "DIR", "where nodes.csv, nodes.npy and nodes.json go (required)",
         [&a](const std::string& v) { a.out = v; }},
        {"--theta-i", "A,B,...", "incident polar angles in degrees, as simulate takes them (default 0)",
         [&a](const std::string& v) { a.theta_i = parse_list("--theta-i", v); }},
        {"--phi-i", "DEG",
         "the incident azimuth in degrees, as simulate takes it (default 0): l = (sin theta_i cos phi_i, sin theta_i "
         "sin phi_i, cos theta_i), the bins in the surface's frame",
         [&a](const std::string& v) { a.phi_i = parse_number("--phi-i", v); }},
        {"--dtheta", "D", "bin width in theta, degrees, as simulate's (default 1)",
         [&a](const std::string& v) { a.dtheta = parse_number("--dtheta", v); }},
        {"--dphi", "P", "bin width in phi, degrees, as simulate's (default 2)",
         [&a](const std::string& v) { a.dphi = parse_number("--dphi", v); }},
        {"--nodes-per-bin", "K", "K x K Gauss-Legendre nodes per bin, K from 1 to 16 (default 4)",
         [&a](const std::string& v) { a.k = parse_count("--nodes-per-bin", v); }},
    };
}

int run_nodes(NodesSettings& a, const std::vector<std::string>& operands) {
    if (operands.empty()) usage_error("nodes: which stack file?");
    if (operands.size() > 1)
        usage_error("nodes takes one stack file, got '" + operands[0] + "' and '" + operands[1] + "'");
    const std::string& stack_path = operands[0];
    const std::string& out = a.out;
    const std::vector<double>& theta_i = a.theta_i;
    const double dtheta = a.dtheta, dphi = a.dphi;
    const uint64_t k = a.k;
    if (out.empty()) usage_error("nodes: --out DIR");
    if (k < 1 || k > uint64_t(kMaxNodesPerBinSide))
        usage_error("--nodes-per-bin must be 1 to " + std::to_string(kMaxNodesPerBinSide) +
                    " (k x k nodes per bin), got " + std::to_string(k));
    const Stack s = parse_stack_file(stack_path);
    SimOptions o;   // the angles and bins, checked as simulate checks them
    o.theta_i_deg = theta_i;
    o.dtheta_deg = dtheta;
    o.dphi_deg = dphi;
    o.phi_i_deg = a.phi_i;
    try {
        validate_options(o);
    } catch (const std::invalid_argument& e) { usage_error(e.what()); }
    const ModelGrid g = grid_of(theta_i, dtheta, dphi, a.phi_i);
    const int sides = s.transmissive() ? 2 : 1;
    const std::string too_many = node_count_refusal(theta_i.size(), sides, double(g.n_theta) * g.n_phi, int(k));
    if (!too_many.empty()) usage_error("nodes: " + too_many);
    const std::vector<BinNode> nodes = bin_nodes(g, sides, int(k));
    NodesFile f{s, theta_i, dtheta, dphi, int(k), sides, nodes.size(), a.phi_i};
    write_nodes_files(out, stack_path, f, nodes);
    std::printf("wrote %s/nodes.csv (%zu nodes: %zu angles x %d side%s x %u bins x %llu), nodes.npy and nodes.json\n",
                out.c_str(), nodes.size(), theta_i.size(), sides, sides == 2 ? "s" : "", g.n_theta * g.n_phi,
                (unsigned long long)(k * k));
    return 0;
}

}   // namespace

Command nodes_command() {
    return {"nodes", "STACK.toml --out DIR [options]",
            "a model in any language, through files: DIR/nodes.csv, one row per quadrature node, "
            "theta_i,side,bin,lx,ly,lz,vx,vy,vz,weight (K x K Gauss-Legendre nodes per bin; a bin's average of f is "
            "the sum of weight x f(l, v) over its nodes; directions away from the surface, v.z < 0 the transmission "
            "side), nodes.npy (the same, float64; side 0 = R, 1 = T) and nodes.json; gonio score takes f there",
            "", invocation(&nodes_options, &run_nodes)};
}

}   // namespace gonio
