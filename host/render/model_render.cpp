#include "model_render.h"
#include "belcour_tables_host.h"
#include "coat_albedo.h"
#include "compute_kernel.h"
#include "model_applicability.h"
#include "model_plan.h"
#include "user_model.h"
#include "model_twin.h"
#include "render_spv_table.h"   // generated (CMakeLists.txt): render_N_spv.h, one per built-in model file
#include "render_interface.glsl"
#include "stack_gpu.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <future>
#include <map>
#include <memory>
#include <thread>

namespace gonio {

namespace {

struct RenderSpv {
    const uint32_t* code;
    size_t bytes;
};
// render.comp, one module per built-in model file (CMakeLists.txt: GONIO_MODEL_ONLY), by code
const RenderSpv kRenderSpv[] = {GONIO_RENDER_SPV};

// Iterations per dispatch: lavapipe ends an invocation's loops after 65535 trips in all (docs/ARCHITECTURE.md);
// an iteration makes 3 model evaluations (a few to a few dozen trips each: Belcour's and tm21's loops over the
// layers) and two binary searches of the environment's CDFs (log2 of its size, 20 for 1024 x 512), so 16
// iterations stay far below it.
constexpr uint32_t kSamplesPerDispatch = 16;

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::vector<vk::DescriptorType> render_descriptor_types() {
    std::vector<vk::DescriptorType> t(RENDER_BINDINGS, vk::DescriptorType::eStorageBuffer);
    t[RENDER_BINDING_STACK] = vk::DescriptorType::eUniformBuffer;
    return t;
}

// The lobe strategy's roughnesses (render.comp): the top interface's (a smooth one as the models evaluate it,
// GGX at MODEL_MIN_ALPHA), and a conductor base's (else the top's again)
void lobe_roughness(const Stack& s, float& a0, float& a1) {
    a0 = std::max(float(s.layers.front().roughness), MODEL_MIN_ALPHA);
    a1 = a0;
    const Layer& base = s.layers.back();
    if (s.layers.size() > 1 && base.kind == InterfaceKind::Conductor)
        a1 = std::max(float(base.roughness), MODEL_MIN_ALPHA);
}

}   // namespace

std::vector<ModelRender> render_models(VkContext& ctx, const Stack& s, const Environment& env,
                                       const ModelRenderOptions& o, ModelRenderStage* stage) {
    const auto t0 = Clock::now();
    ModelRenderStage st;
    st.samples_per_dispatch = kSamplesPerDispatch;
    auto& dev = ctx.device();
    const auto& reg = model_registry();
    std::vector<ModelRender> out;
    std::vector<size_t> todo;
    bool need_tables = false;
    for (size_t m = 0; m < reg.size(); ++m) {
        ModelRender r;
        r.model = m;
        r.id = reg[m].id;
        r.not_applicable = model_not_selected(m, o.models);
        if (r.not_applicable.empty()) r.not_applicable = model_cannot_represent(m, s);
        if (r.not_applicable.empty()) {
            todo.push_back(out.size());
            need_tables |= uses_tables(m);
        }
        out.push_back(std::move(r));
    }
    for (const auto& um : o.models.user_models) {   // after the built-in ones, as compare lists them
        ModelRender r;
        r.model = SIZE_MAX;
        r.user = um.get();
        r.id = um->header.id;
        r.not_applicable = model_id_not_selected(r.id, o.models);
        if (r.not_applicable.empty()) r.not_applicable = model_file_cannot_represent(um->header, s);
        if (r.not_applicable.empty()) todo.push_back(out.size());
        out.push_back(std::move(r));
    }
    if (todo.empty()) {
        if (stage) *stage = st;
        return out;
    }

    // buffers: the stack, the sums, E_coat, Belcour's tables, the environment and its CDFs
    const size_t pixels = size_t(o.size) * o.size;
    Buffer ubo = ctx.make_buffer(sizeof(StackGpu), vk::BufferUsageFlagBits::eUniformBuffer, true);
    Buffer accum = ctx.make_buffer(pixels * sizeof(glm::vec4), vk::BufferUsageFlagBits::eStorageBuffer, true);
    Buffer albedo = ctx.make_buffer(COAT_ALBEDO_NODES * 4, vk::BufferUsageFlagBits::eStorageBuffer, true);
    Buffer tables = ctx.make_buffer(TABLE_FLOATS * 4, vk::BufferUsageFlagBits::eStorageBuffer, true);
    const size_t texels = size_t(env.width) * env.height;
    Buffer envb = ctx.make_buffer(texels * sizeof(glm::vec4), vk::BufferUsageFlagBits::eStorageBuffer, true);
    bool env_sampled = true;
    const std::vector<float> cdf = environment_cdf(env, &env_sampled);
    Buffer cdfb = ctx.make_buffer(cdf.size() * 4, vk::BufferUsageFlagBits::eStorageBuffer, true);
    Buffer lobes = ctx.make_device_buffer(BELCOUR_MU_NODES * BELCOUR_LOBE_STRIDE * sizeof(glm::vec4),
                                          vk::BufferUsageFlagBits::eStorageBuffer);
    StackGpu sg = pack_stack(s);
    sg.info.z = s.exterior_ior;   // for a user's model (models/user_model.glsl gonio_exterior_ior)
    std::memcpy(ubo.mapped, &sg, sizeof(sg));
    std::vector<float> coat(COAT_ALBEDO_NODES, 0.0f);
    if (s.layers.size() == 2 && !s.transmissive()) coat = coat_albedo_table(s);
    std::memcpy(albedo.mapped, coat.data(), COAT_ALBEDO_NODES * 4);
    std::memset(tables.mapped, 0, TABLE_FLOATS * 4);
    if (need_tables) {
        BelcourTableKernel table_kernel(ctx);
        const std::vector<float>& t = table_kernel.tables(s);
        std::memcpy(tables.mapped, t.data(), std::min<size_t>(t.size(), TABLE_FLOATS) * 4);
    }
    auto* texel_dst = static_cast<glm::vec4*>(envb.mapped);
    for (size_t t = 0; t < texels; ++t) texel_dst[t] = glm::vec4(env.texels[t], 0.0f);
    std::memcpy(cdfb.mapped, cdf.data(), cdf.size() * 4);
    std::vector<const Buffer*> bufs(RENDER_BINDINGS, nullptr);
    bufs[RENDER_BINDING_STACK] = &ubo;
    bufs[RENDER_BINDING_ACCUM] = &accum;
    bufs[RENDER_BINDING_COAT_ALBEDO] = &albedo;
    bufs[RENDER_BINDING_BELCOUR_TABLES] = &tables;
    bufs[RENDER_BINDING_ENV] = &envb;
    bufs[RENDER_BINDING_ENV_CDF] = &cdfb;
    bufs[RENDER_BINDING_LOBES] = &lobes;
    st.setup_seconds = since(t0);

    // the pipelines, concurrently (lavapipe compiles each on the creating thread; nothing is shared between them)
    const auto tp = Clock::now();
    std::vector<std::unique_ptr<ComputeKernel>> kernels(todo.size());
    std::atomic<size_t> next{0};
    // a user's model: render.comp compiled with its file (here, one at a time: glslang's front end is not
    // shared between threads)
    std::map<size_t, std::vector<uint32_t>> user_code;
    const std::vector<uint32_t> no_code;
    for (size_t i : todo)
        if (out[i].user) user_code[i] = compile_user_render_kernel(*out[i].user);
    auto make = [&] {
        for (size_t i; (i = next++) < todo.size();) {
            const auto tk = Clock::now();
            const ModelRender& r = out[todo[i]];
            const auto uc = user_code.find(todo[i]);   // find, not [], from several threads
            const std::vector<uint32_t>& user_spirv = uc == user_code.end() ? no_code : uc->second;
            const uint32_t code = r.user ? 0u : shader_model_of(r.model);
            const uint32_t convention = r.user ? 0u : reg[r.model].convention;
            auto k = r.user ? std::make_unique<ComputeKernel>(dev, user_spirv.data(), user_spirv.size() * 4,
                                                              render_descriptor_types(), uint32_t(sizeof(RenderPush)))
                            : std::make_unique<ComputeKernel>(dev, kRenderSpv[code].code, kRenderSpv[code].bytes,
                                                              render_descriptor_types(), uint32_t(sizeof(RenderPush)));
            const uint32_t spec[2] = {code, convention};
            k->build(dev, {{MODEL_SPEC_MODEL, 0, 4}, {MODEL_SPEC_CONVENTION, 4, 4}}, spec, sizeof spec);
            k->bind(dev, bufs);
            kernels[i] = std::move(k);
            out[todo[i]].pipeline_seconds = since(tk);
        }
    };
    const unsigned threads = std::min<unsigned>(std::max(1u, std::thread::hardware_concurrency()), todo.size());
    std::vector<std::future<void>> pool;
    for (unsigned t = 1; t < threads; ++t) pool.push_back(std::async(std::launch::async, make));
    make();
    for (auto& f : pool) f.get();
    st.pipelines_seconds = since(tp);

    float a0, a1;
    lobe_roughness(s, a0, a1);
    const float mu_jump = float(mu_jump_of(s));
    const uint32_t groups = uint32_t((pixels + RENDER_GROUP_SIZE - 1) / RENDER_GROUP_SIZE);
    for (size_t i = 0; i < todo.size(); ++i) {
        ModelRender& r = out[todo[i]];
        const auto tr = Clock::now();
        std::memset(accum.mapped, 0, pixels * sizeof(glm::vec4));
        ComputeKernel& k = *kernels[i];
        ctx.run_now([&](vk::CommandBuffer cb) {
            cb.bindPipeline(vk::PipelineBindPoint::eCompute, *k.pipeline);
            cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *k.layout, 0, {*k.set}, {});
            if (!r.user &&
                uses_tables(r.model)) {   // the lobe pass: the lobes at the nodes of mu, read by every dispatch after
                RenderPush pc{};
                pc.use_tables = o.models.belcour_tables ? 1u : 0u;
                pc.mu_jump = mu_jump;
                pc.lobe_pass = 1u;
                cb.pushConstants<RenderPush>(*k.layout, vk::ShaderStageFlagBits::eCompute, 0, pc);
                cb.dispatch((BELCOUR_MU_NODES + RENDER_GROUP_SIZE - 1) / RENDER_GROUP_SIZE, 1, 1);
                vk::MemoryBarrier lb{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                     .dstAccessMask = vk::AccessFlagBits::eShaderRead};
                cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader,
                                   {}, lb, {}, {});
            }
            for (uint32_t first = 0; first < o.spp; first += kSamplesPerDispatch) {
                RenderPush pc{};
                pc.mu_jump = mu_jump;
                pc.size = o.size;
                pc.first_sample = first;
                pc.samples = std::min(kSamplesPerDispatch, o.spp - first);
                pc.seed = o.seed;
                pc.env_w = env.width;
                pc.env_h = env.height;
                pc.use_tables = o.models.belcour_tables ? 1u : 0u;
                pc.env_sampled = env_sampled ? 1u : 0u;
                pc.alpha_lobe0 = a0;
                pc.alpha_lobe1 = a1;
                cb.pushConstants<RenderPush>(*k.layout, vk::ShaderStageFlagBits::eCompute, 0, pc);
                cb.dispatch(groups, 1, 1);
                // the next dispatch adds to the same sums
                vk::MemoryBarrier mb{
                    .srcAccessMask = vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eShaderRead,
                    .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
                vk::AccessFlags host =
                    first + kSamplesPerDispatch >= o.spp ? vk::AccessFlagBits::eHostRead : vk::AccessFlags{};
                if (host) {
                    vk::MemoryBarrier hb{.srcAccessMask = vk::AccessFlagBits::eShaderWrite, .dstAccessMask = host};
                    cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eHost, {},
                                       hb, {}, {});
                } else {
                    cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                                       vk::PipelineStageFlagBits::eComputeShader, {}, mb, {}, {});
                }
            }
        });
        r.image.size = o.size;
        r.image.rgba.resize(pixels);
        const auto* sums = static_cast<const glm::vec4*>(accum.mapped);
        for (uint32_t y = 0; y < o.size; ++y)
            for (uint32_t x = 0; x < o.size; ++x) {
                vec3 n;
                const bool on = sphere_normal(x, y, o.size, n);
                const glm::vec4 v = sums[size_t(y) * o.size + x];
                r.image.at(x, y) = on ? glm::vec4(glm::vec3(v) / float(o.spp), 1.0f) : glm::vec4(0.0f);
            }
        r.render_seconds = since(tr);
    }
    st.wall_seconds = since(t0);
    if (stage) *stage = st;
    return out;
}

}   // namespace gonio
