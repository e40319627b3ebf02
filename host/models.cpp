#include "models.h"
#include "compute_kernel.h"
#include "stack_gpu.h"

// The albedo-scaling model reads its coat's directional albedo E_coat(mu) from a table computed per stack
// (coat_albedo_table below); on the device from a buffer, here through this pointer.
static thread_local const float* g_coat_albedo = nullptr;
inline float model_coat_albedo(float mu) {
    float x = std::clamp(mu, 0.0f, 1.0f) * 64.0f;
    unsigned i = std::min(unsigned(x), 63u);
    return g_coat_albedo[i] + (g_coat_albedo[i + 1] - g_coat_albedo[i]) * (x - float(i));
}

#include "models/all.glsl"
#include "models_spv.h"

#include <algorithm>

#include <chrono>
#include <cmath>
#include <cstring>

namespace gonio {

namespace {

struct Push {
    uint32_t model, terms, n_theta, n_phi;
    float dtheta, dphi, sin_ti, cos_ti;
    uint32_t k, grid;
    float alpha_grid;
    uint32_t delta;
    float alpha_partner;
};

constexpr uint32_t kQuadratureNodes = 8;      // per bin side
constexpr uint32_t kLobeGrid = 512;           // per side: 2^18 visible-normal nodes per grid
constexpr double kNarrowAlpha = 0.03;         // lobes narrower than this use the lobe grid (8 x 8 nodes per 1 x 2 degree bin resolve wider ones)
constexpr double kWideGrid = 0.5;             // roughness of the wide partner grid (tails)
constexpr double kLobeScale = 1099511627776.0;   // 2^40, LOBE_SCALE in models.comp

// How each term of a model is integrated over the bins for this stack: by quadrature, or on a lobe grid of
// roughness alpha_grid (0: quadrature).
struct TermPlan { uint32_t term; double alpha_grid; bool delta; };

std::vector<TermPlan> plan(size_t model, const Stack& s) {
    const double a0 = s.layers[0].roughness, a1 = s.layers[1].roughness;
    const double eta = s.layers[0].ior.x / s.exterior_ior;
    std::vector<TermPlan> out;
    out.push_back({TERM_TOP, a0 < kNarrowAlpha ? std::max(a0, double(MODEL_MIN_ALPHA)) : 0.0, a0 == 0.0});
    const bool unrefracted = model == MODEL_WW09 || model == MODEL_ALBEDO_SCALING;   // base at (l, v), own roughness
    double base_alpha = unrefracted ? a1 : std::max(a0, a1);
    double width = unrefracted ? base_alpha : base_alpha * eta;   // refraction widens lobes by ~eta
    bool narrow = s.layers[1].kind == InterfaceKind::Conductor && base_alpha < kNarrowAlpha;
    out.push_back({TERM_BASE, narrow ? std::max(width, double(MODEL_MIN_ALPHA)) : 0.0, narrow && base_alpha == 0.0});
    return out;
}

}  // namespace

std::vector<float> coat_albedo_table(const Stack& s) {
    // E(mu) = integral of f_r0(l, v) cos(theta_v) dv, by quadrature in half-vector space (v = reflect(l, m),
    // dv = 4 (l.m) dm) with tan(theta_m) = a (e^(L u) - 1) to resolve narrow lobes; 65 nodes mu = i / 64.
    StackGpu sg = pack_stack(s);
    CoatParams p = coat_params(sg.layers[0], sg.layers[1]);
    const double a = p.alpha0, L = std::log(1e4 / a + 1);
    const int NU = 600, NP = 96;
    std::vector<float> table(65);
    for (int i = 0; i <= 64; ++i) {
        double mu = std::max(i / 64.0, 1e-3);
        glm::dvec3 l(std::sqrt(1 - mu * mu), 0, mu);
        double acc = 0;
        for (int k = 0; k < NU; ++k) {
            double u = (k + 0.5) / NU, tan_m = a * (std::exp(L * u) - 1), tm = std::atan(tan_m);
            double dtm = a * L * std::exp(L * u) / (1 + tan_m * tan_m);
            for (int j = 0; j < NP; ++j) {
                double pm = (j + 0.5) / NP * 2 * M_PI;
                glm::dvec3 m(std::sin(tm) * std::cos(pm), std::sin(tm) * std::sin(pm), std::cos(tm));
                double lm = glm::dot(l, m);
                if (lm <= 0) continue;
                glm::dvec3 v = 2 * lm * m - l;
                if (v.z <= 0) continue;
                acc += top_reflection(glm::vec3(l), glm::vec3(glm::normalize(v)), p.alpha0, p.eta) * v.z * 4 * lm * std::sin(tm) * dtm;
            }
        }
        table[i] = float(std::min(1.0, acc / NU * 2 * M_PI / NP));
    }
    return table;
}

const std::vector<ModelInfo>& model_registry() {
    static const std::vector<ModelInfo> r = {
        {"ww09", "Weidlich & Wilkie 2009 (SIGGRAPH Asia course), variant of Weidlich & Wilkie 2007; Bati et al. 2019 eq. 2",
         "T01/T10 from the top microfacet normal, base at unrefracted directions, TIR term t = (1 - G) + T10 G",
         "one dielectric coat over a Lambertian or conductor base",
         true},   // h0-based T01 = T10 (l.h0 = v.h0), t and the base at (l, v) are symmetric
        {"elek10", "Elek 2010 (CESCG), as described by Bati et al. 2019 section 2.1",
         "as ww09 but the base at Snell-refracted directions, alpha1 <- max(alpha0, alpha1)",
         "one dielectric coat over a Lambertian or conductor base",
         true},   // as ww09, and Snell refraction of l and v is the same map
        {"ww-corrected", "Bati, Pacanowski & Barla 2019, eq. 4",
         "geometric normal for T01, T10 and refraction, 1/eta^2 solid-angle factor, Elek's roughness rule",
         "one dielectric coat over a Lambertian or conductor base",
         true},   // T01(l) T10(v) / eta^2 with the geometric normal
        {"albedo-scaling", "OpenPBR Surface v1.1 layering (Andersson et al. 2024), as used by Autodesk Standard Surface (Georgiev et al. 2019)",
         "f_coat + T_coat (1 - E_coat(v)) f_base(l, v): albedo scaling with view-dependent coat absorption",
         "one dielectric coat over a Lambertian or conductor base", false},   // E_coat of v only
    };
    return r;
}

std::string model_cannot_represent(size_t index, const Stack& s) {
    const std::string& id = model_registry().at(index).id;
    if (s.transmissive())
        return id + " models reflection only (a BRDF); this stack is transmissive (its last layer is a dielectric)";
    if (s.layers.size() != 2)
        return id + " is implemented for one dielectric coat over an opaque base; this stack has " +
               std::to_string(s.layers.size()) + " layers";
    return "";
}

ModelGrid model_grid(const SimResult& r) {
    return {r.n_theta, r.n_phi, r.options.dtheta_deg, r.options.dphi_deg, r.options.theta_i_deg};
}

std::vector<ModelSlices> evaluate_models(VkContext& ctx, const Stack& s, const ModelGrid& grid,
                                         std::vector<ModelCost>* costs) {
    auto& dev = ctx.device();
    const size_t nb = size_t(grid.n_theta) * grid.n_phi;
    StackGpu sg = pack_stack(s);
    Buffer ubo = ctx.make_buffer(sizeof(StackGpu), vk::BufferUsageFlagBits::eUniformBuffer, true);
    std::memcpy(ubo.mapped, &sg, sizeof(sg));
    Buffer quad = ctx.make_device_buffer(nb * 3 * 4, vk::BufferUsageFlagBits::eStorageBuffer);
    Buffer lobe = ctx.make_device_buffer(nb * 3 * 8, vk::BufferUsageFlagBits::eStorageBuffer);
    Buffer host = ctx.make_buffer(nb * 3 * 12, vk::BufferUsageFlagBits::eTransferDst, false);
    Buffer albedo = ctx.make_buffer(65 * 4, vk::BufferUsageFlagBits::eStorageBuffer, true);
    std::vector<float> table(65, 0.0f);
    if (s.layers.size() == 2 && !s.transmissive()) table = coat_albedo_table(s);
    std::memcpy(albedo.mapped, table.data(), 65 * 4);
    std::vector<ComputeKernel> kernels;
    for (uint32_t k = 0; k < 2; ++k) {
        kernels.emplace_back(dev, models_spv, sizeof(models_spv), std::vector<vk::DescriptorType>{vk::DescriptorType::eUniformBuffer,
                             vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eStorageBuffer}, uint32_t(sizeof(Push)));
        kernels.back().bind(dev, {&ubo, &quad, &lobe, &albedo});
        kernels.back().build(dev, {{0, 0, 4}}, &k, 4);
    }
    vk::raii::QueryPool queries(dev, vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = 2});
    std::vector<ModelSlices> out;
    if (costs) costs->clear();
    for (size_t m = 0; m < model_registry().size(); ++m) {
        ModelSlices ms;
        ms.id = model_registry()[m].id;
        ms.not_applicable = model_cannot_represent(m, s);
        ModelCost cost;
        auto t0 = std::chrono::steady_clock::now();
        if (ms.not_applicable.empty()) {
            auto terms = plan(m, s);
            uint32_t quad_terms = 0;
            for (auto& t : terms) if (t.alpha_grid == 0) quad_terms |= t.term;
            for (double theta : grid.theta_i_deg) {
                double ti = theta * M_PI / 180;
                Push pc{uint32_t(m), quad_terms, grid.n_theta, grid.n_phi, float(grid.dtheta_deg * M_PI / 180),
                        float(grid.dphi_deg * M_PI / 180), float(std::sin(ti)), float(std::cos(ti)), kQuadratureNodes, kLobeGrid, 0.0f, 0u, 0.0f};
                ctx.run_now([&](vk::CommandBuffer c) {
                    c.resetQueryPool(*queries, 0, 2);
                    c.fillBuffer(*quad.buffer, 0, VK_WHOLE_SIZE, 0);
                    c.fillBuffer(*lobe.buffer, 0, VK_WHOLE_SIZE, 0);
                    vk::MemoryBarrier fill{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                           .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
                    c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, fill, nullptr, nullptr);
                    c.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries, 0);
                    if (quad_terms) {
                        c.bindPipeline(vk::PipelineBindPoint::eCompute, *kernels[0].pipeline);
                        c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *kernels[0].layout, 0, {*kernels[0].set}, nullptr);
                        c.pushConstants<Push>(*kernels[0].layout, vk::ShaderStageFlagBits::eCompute, 0, pc);
                        c.dispatch(uint32_t((nb + 63) / 64), 1, 1);
                    }
                    for (auto& t : terms) {
                        if (t.alpha_grid == 0) continue;
                        // the lobe's own grid and a wide one, combined by the balance heuristic (a delta: its own only)
                        for (int pass = 0; pass < (t.delta ? 1 : 2); ++pass) {
                            Push lp = pc;
                            lp.terms = t.term;
                            lp.alpha_grid = float(pass == 0 ? t.alpha_grid : kWideGrid);
                            lp.alpha_partner = t.delta ? 0.0f : float(pass == 0 ? kWideGrid : t.alpha_grid);
                            lp.delta = t.delta ? 1u : 0u;
                            c.bindPipeline(vk::PipelineBindPoint::eCompute, *kernels[1].pipeline);
                            c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *kernels[1].layout, 0, {*kernels[1].set}, nullptr);
                            c.pushConstants<Push>(*kernels[1].layout, vk::ShaderStageFlagBits::eCompute, 0, lp);
                            c.dispatch((kLobeGrid * kLobeGrid / 16 + 63) / 64, 1, 1);
                            vk::MemoryBarrier acc{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                                  .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
                            c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {}, acc, nullptr, nullptr);
                        }
                    }
                    c.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries, 1);
                    vk::MemoryBarrier done{.srcAccessMask = vk::AccessFlagBits::eShaderWrite, .dstAccessMask = vk::AccessFlagBits::eTransferRead};
                    c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eTransfer, {}, done, nullptr, nullptr);
                    c.copyBuffer(*quad.buffer, *host.buffer, vk::BufferCopy{0, 0, nb * 12});
                    c.copyBuffer(*lobe.buffer, *host.buffer, vk::BufferCopy{0, nb * 12, nb * 24});
                    vk::MemoryBarrier read{.srcAccessMask = vk::AccessFlagBits::eTransferWrite, .dstAccessMask = vk::AccessFlagBits::eHostRead};
                    c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eHost, {}, read, nullptr, nullptr);
                });
                auto [qr, ts] = queries.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                                                             vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
                cost.device_seconds += double(ts[1] - ts[0]) * ctx.timestamp_period_ns() * 1e-9;
                if (quad_terms)
                    for (uint32_t t = 0; t < grid.n_theta; ++t)   // kt x k nodes per bin, kt = 4k beyond 80 degrees
                        cost.evaluations += uint64_t(grid.n_phi) * kQuadratureNodes * kQuadratureNodes *
                                            ((t + 1) * grid.dtheta_deg > 80.0 + 1e-9 ? 4 : 1);
                for (auto& t : terms)
                    if (t.alpha_grid != 0) cost.evaluations += uint64_t(t.delta ? 1 : 2) * kLobeGrid * kLobeGrid;
                const float* q = static_cast<const float*>(host.mapped);
                const int64_t* lb = reinterpret_cast<const int64_t*>(static_cast<const char*>(host.mapped) + nb * 12);
                std::vector<glm::dvec3> f(nb);
                for (size_t b = 0; b < nb; ++b) {
                    uint32_t t = uint32_t(b / grid.n_phi);
                    double lo = t * grid.dtheta_deg * M_PI / 180, hi = (t + 1) * grid.dtheta_deg * M_PI / 180;
                    double omega = 0.5 * (std::pow(std::sin(hi), 2) - std::pow(std::sin(lo), 2)) * grid.dphi_deg * M_PI / 180;
                    for (int c = 0; c < 3; ++c) f[b][c] = double(q[b * 3 + c]) + double(lb[b * 3 + c]) / kLobeScale / omega;
                }
                ms.f.push_back(std::move(f));
            }
        }
        cost.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (costs) costs->push_back(cost);
        out.push_back(std::move(ms));
    }
    return out;
}

glm::dvec3 model_value_cpu(size_t index, const Stack& s, glm::vec3 l, glm::vec3 v) {
    // the coat-albedo table depends on the coat's roughness and IOR only: keep the last one per thread
    static thread_local float last_alpha = -1.0f, last_eta = -1.0f;
    static thread_local std::vector<float> table;
    if (s.layers.size() == 2 && !s.transmissive() &&
        (s.layers[0].roughness != last_alpha || s.layers[0].ior.x / s.exterior_ior != last_eta)) {
        table = coat_albedo_table(s);
        last_alpha = s.layers[0].roughness;
        last_eta = s.layers[0].ior.x / s.exterior_ior;
    }
    g_coat_albedo = table.data();
    StackGpu sg = pack_stack(s);
    CoatParams p = coat_params(sg.layers[0], sg.layers[1]);
    return glm::dvec3(eval_model(uint(index), p, TERM_TOP | TERM_BASE, l, v));
}

}  // namespace gonio
