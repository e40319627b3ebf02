// stack_tables.cpp: see stack_tables.h. The generic builder: what a set holds is its model file's (its
// GONIO_MODEL_TABLES hook); here the buffer, the quadrature primitives the hooks integrate with (model_twin.h), and
// the call of every hook that declares a set asked for.
#include "stack_tables.h"
#include "model_twin.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>

namespace {

thread_local std::vector<float>* g_filling = nullptr;   // the buffer stack_tables() fills on this thread

// Gauss-Legendre nodes and weights on [0, 1] (Newton on the Legendre polynomial)
void gauss_legendre(uint32_t n, std::vector<double>& x, std::vector<double>& w) {
    x.resize(n);
    w.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            double p1 = 1, p2 = 0;
            for (uint32_t j = 0; j < n; ++j) {
                const double p3 = p2;
                p2 = p1;
                p1 = ((2.0 * j + 1) * z * p2 - j * p3) / (j + 1);
            }
            dp = n * (z * p1 - p2) / (z * z - 1);
            const double step = p1 / dp;
            z -= step;
            if (std::fabs(step) < 1e-15) break;
        }
        x[i] = 0.5 * (1 - z);
        w[i] = 1.0 / ((1 - z * z) * dp * dp);
    }
}

struct GaussLegendreRule {
    std::vector<double> x, w;
};
const GaussLegendreRule& gauss_legendre_rule(uint32_t n) {
    static std::mutex mutex;
    static std::map<uint32_t, GaussLegendreRule> rules;
    std::lock_guard<std::mutex> lock(mutex);
    auto it = rules.find(n);
    if (it == rules.end()) {
        GaussLegendreRule r;
        gauss_legendre(n, r.x, r.w);
        it = rules.emplace(n, std::move(r)).first;
    }
    return it->second;
}

// A smooth dielectric interface of relative IOR eta, as gonio's quadrature of an albedo takes it (kind and eta)
LayerGpu dielectric_interface(float eta) {
    LayerGpu L{};
    L.p0 = vec4(float(KIND_DIELECTRIC), 0.0f, eta, 1.0f / eta);
    return L;
}

}   // namespace

void model_stack_table_store(uint i, float value) {
    if (!g_filling || i >= g_filling->size())
        throw std::logic_error("model_stack_table_store: element " + std::to_string(i) + " outside the buffer");
    (*g_filling)[i] = value;
}

uint table_stack_shape(const StackGpu& s) {
    const uint32_t layers = stack_layer_count(s.info);
    if (layers == 3 && layer_kind(s.layers[0]) == KIND_DIELECTRIC && layer_kind(s.layers[1]) == KIND_DIELECTRIC &&
        layer_kind(s.layers[2]) == KIND_LAMBERTIAN)
        return TABLE_SHAPE_THREE_LAYER_DIELECTRIC_BASE;
    if (layers == 2 && layer_kind(s.layers[1]) != KIND_DIELECTRIC) return TABLE_SHAPE_TWO_LAYER_OPAQUE;
    return TABLE_SHAPE_OTHER;
}

FgdSums table_interface_sums(float eta, float alpha, float mu, uint g_mode) {
    // below MODEL_MIN_ALPHA (Adobe's roughness node 0, Cycles' 1e-4, alpha 1e-8) the smooth interface's: its Fresnel
    // at mu, the whole lobe (the tables' own values there: exact Fresnel, ggx_E = 1)
    if (alpha < MODEL_MIN_ALPHA) {
        FgdSums smooth;
        const float f = fresnel_dielectric(mu, eta), f0 = (eta - 1.0f) * (eta - 1.0f) / ((eta + 1.0f) * (eta + 1.0f));
        smooth.fgd = vec3((g_mode & FGD_FRESNEL_REMAPPED) != 0u ? std::clamp((f - f0) / (1.0f - f0), 0.0f, 1.0f) : f);
        smooth.lobe = 1.0f;
        smooth.tir = 1.0f;
        return smooth;
    }
    // below IOR 1 the Fresnel steps to 1 at the critical angle, which the midpoint rule in phi_m crosses: 256 nodes
    // there (32: 6.2e-4 off at Adobe's OD[8][12][25], IOR 1 / 1.7; 256: 8e-5)
    return fgd_quadrature_sums(dielectric_interface(eta), mu, alpha, g_mode, FGD_NODES_THETA,
                               eta < 1.0f ? 8u * FGD_NODES_PHI : FGD_NODES_PHI);
}

double table_cosine_average(uint e, float eta, float alpha, uint g_mode) {
    static const double x[12] = {0.0640568928626056, 0.1911188674736163, 0.3150426796961634, 0.4337935076260451,
                                 0.5454214713888396, 0.6480936519369755, 0.7401241915785544, 0.8200019859739029,
                                 0.8864155270044010, 0.9382745520027328, 0.9747285559713095, 0.9951872199970214};
    static const double w[12] = {0.1279381953467522, 0.1258374563468283, 0.1216704729278034, 0.1155056680537256,
                                 0.1074442701159656, 0.0976186521041139, 0.0861901615319533, 0.0733464814110803,
                                 0.0592985849154368, 0.0442774388174198, 0.0285313886289337, 0.0123412297999872};
    auto value = [&](float mu) {
        if (e == TABLE_MEAN_FRESNEL) return double(fresnel_dielectric(mu, eta));
        const FgdSums s = table_interface_sums(eta, alpha, mu, g_mode);
        return double(e == TABLE_MEAN_FGD ? s.fgd.x : s.lobe);
    };
    double sum = 0.0;
    for (int i = 0; i < 12; ++i)
        for (int s = -1; s <= 1; s += 2) {
            const double mu = 0.5 * (1.0 + s * x[i]);
            sum += 0.5 * w[i] * 2.0 * mu * value(float(mu));
        }
    return sum;
}

void table_store_interface_albedo(uint offset, float eta, float alpha, uint g_mode) {
    for (uint i = 0; i < COAT_ALBEDO_NODES; ++i)
        model_stack_table_store(
            offset + i,
            std::min(
                1.0f,
                table_interface_sums(eta, std::max(alpha, MODEL_MIN_ALPHA), coat_albedo_node_mu(i), g_mode).fgd.x));
}

void table_store_lobe_albedo(uint offset, float alpha, uint g_mode) {
    // F = 1: the lobe alone, whatever the interface's IOR (1.5 here)
    for (uint i = 0; i < COAT_ALBEDO_NODES; ++i)
        model_stack_table_store(
            offset + i,
            std::min(
                1.0f,
                table_interface_sums(1.5f, std::max(alpha, MODEL_MIN_ALPHA), coat_albedo_node_mu(i), g_mode).lobe));
}

double table_gauss_legendre_node(uint n, uint j) { return gauss_legendre_rule(n).x.at(j); }
double table_gauss_legendre_weight(uint n, uint j) { return gauss_legendre_rule(n).w.at(j); }

namespace gonio {

std::vector<float> stack_tables(const StackGpu& sg, uint32_t sets) {
    std::vector<float> t(STACK_TABLE_FLOATS, 0.0f);
    if (table_stack_shape(sg) == TABLE_SHAPE_OTHER) return t;   // no set is defined there
    std::vector<float>* outer = g_filling;
    g_filling = &t;
    try {
        eval_stack_table_sets(sg, sets);
    } catch (...) {
        g_filling = outer;
        throw;
    }
    g_filling = outer;
    return t;
}

}   // namespace gonio
