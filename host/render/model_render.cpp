#include "model_render.h"
#include "belcour_tables_host.h"
#include "compute_kernel.h"
#include "model_applicability.h"
#include "model_plan.h"
#include "model_stack.h"
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

// Which models render here, and why not the others (registry order, then the users' files, as compare lists them);
// `todo`: the indices into the result of those that render.
std::vector<ModelRender> select_models(const ModelStack& ms, const Stack& s, const ModelRenderOptions& o,
                                       std::vector<size_t>& todo) {
    std::vector<ModelRender> out;
    for (size_t m = 0; m < model_registry().size(); ++m) {
        ModelRender r;
        r.model = m;
        r.id = model_registry()[m].id;
        r.not_applicable = ms.skipped[m];
        if (r.not_applicable.empty()) todo.push_back(out.size());
        out.push_back(std::move(r));
    }
    for (const auto& um : o.models.user_models) {
        ModelRender r;
        r.model = SIZE_MAX;
        r.user = um.get();
        r.id = um->header.id;
        r.not_applicable = model_id_not_selected(r.id, o.models);
        if (r.not_applicable.empty()) r.not_applicable = model_file_cannot_represent(um->header, s);
        if (r.not_applicable.empty()) todo.push_back(out.size());
        out.push_back(std::move(r));
    }
    return out;
}

// render.comp's inputs on the device: the models' (model_stack.h), the sums, the environment and its CDFs, the lobes
struct RenderBuffers {
    ModelStackBuffers inputs;
    Buffer accum, env, cdf, lobes;
    bool env_sampled = true;

    RenderBuffers(VkContext& ctx, const ModelStack& ms, const Environment& e, size_t pixels) : inputs(ctx) {
        inputs.upload(ms);
        accum = ctx.make_buffer(pixels * sizeof(glm::vec4), vk::BufferUsageFlagBits::eStorageBuffer, true);
        const size_t texels = size_t(e.width) * e.height;
        env = ctx.make_buffer(texels * sizeof(glm::vec4), vk::BufferUsageFlagBits::eStorageBuffer, true);
        auto* texel_dst = static_cast<glm::vec4*>(env.mapped);
        for (size_t t = 0; t < texels; ++t) texel_dst[t] = glm::vec4(e.texels[t], 0.0f);
        const std::vector<float> c = environment_cdf(e, &env_sampled);
        cdf = ctx.make_buffer(c.size() * 4, vk::BufferUsageFlagBits::eStorageBuffer, true);
        std::memcpy(cdf.mapped, c.data(), c.size() * 4);
        lobes = ctx.make_device_buffer(BELCOUR_MU_NODES * BELCOUR_LOBE_STRIDE * sizeof(glm::vec4),
                                       vk::BufferUsageFlagBits::eStorageBuffer);
    }
    std::vector<const Buffer*> bindings() const {   // indexed by RENDER_BINDING_*
        std::vector<const Buffer*> b(RENDER_BINDINGS, nullptr);
        b[RENDER_BINDING_STACK] = &inputs.stack;
        b[RENDER_BINDING_ACCUM] = &accum;
        b[RENDER_BINDING_COAT_ALBEDO] = &inputs.coat_albedo;
        b[RENDER_BINDING_BELCOUR_TABLES] = &inputs.tables;
        b[RENDER_BINDING_ENV] = &env;
        b[RENDER_BINDING_ENV_CDF] = &cdf;
        b[RENDER_BINDING_LOBES] = &lobes;
        return b;
    }
};

// The pipelines of the models in todo, concurrently (lavapipe compiles each on the creating thread); a user's model
// is render.comp compiled with its file first (one at a time: glslang's front end is not shared between threads).
std::vector<std::unique_ptr<ComputeKernel>> make_pipelines(VkContext& ctx, std::vector<ModelRender>& out,
                                                           const std::vector<size_t>& todo, const RenderBuffers& b) {
    auto& dev = ctx.device();
    std::vector<std::unique_ptr<ComputeKernel>> kernels(todo.size());
    std::map<size_t, std::vector<uint32_t>> user_code;
    for (size_t i : todo)
        if (out[i].user) user_code[i] = compile_user_render_kernel(*out[i].user);
    const auto bufs = b.bindings();
    make_concurrently(todo.size(), [&](size_t i) {
        const auto tk = Clock::now();
        const ModelRender& r = out[todo[i]];
        const uint32_t code = r.user ? 0u : shader_model_of(r.model);
        const uint32_t convention = r.user ? 0u : model_registry()[r.model].convention;
        const uint32_t* spv =
            r.user ? user_code.find(todo[i])->second.data() : kRenderSpv[code].code;   // find: threads
        const size_t bytes = r.user ? user_code.find(todo[i])->second.size() * 4 : kRenderSpv[code].bytes;
        auto k =
            std::make_unique<ComputeKernel>(dev, spv, bytes, render_descriptor_types(), uint32_t(sizeof(RenderPush)));
        const uint32_t spec[2] = {code, convention};
        k->build(dev, {{MODEL_SPEC_MODEL, 0, 4}, {MODEL_SPEC_CONVENTION, 4, 4}}, spec, sizeof spec);
        k->bind(dev, bufs);
        kernels[i] = std::move(k);
        out[todo[i]].pipeline_seconds = since(tk);
    });
    return kernels;
}

// One model's render: the lobe pass where its lobes come from a table over mu (render.comp), then o.spp iterations in
// dispatches of kSamplesPerDispatch adding to the same sums.
void record_render(vk::CommandBuffer cb, const ComputeKernel& k, bool lobe_pass, RenderPush pc, uint32_t spp,
                   uint32_t groups) {
    if (lobe_pass) {   // the lobes at the nodes of mu, read by every dispatch after
        RenderPush lp{};
        lp.use_tables = pc.use_tables;
        lp.mu_jump = pc.mu_jump;
        lp.lobe_pass = 1u;
        k.record(cb, lp, groups_for(BELCOUR_MU_NODES, RENDER_GROUP_SIZE));
        barrier(cb, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderRead);
    }
    for (uint32_t first = 0; first < spp; first += kSamplesPerDispatch) {
        pc.first_sample = first;
        pc.samples = std::min(kSamplesPerDispatch, spp - first);
        k.record(cb, pc, groups);
        if (first + kSamplesPerDispatch >= spp)
            barrier(cb, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                    vk::PipelineStageFlagBits::eHost, vk::AccessFlagBits::eHostRead);
        else   // the next dispatch adds to the same sums
            barrier(cb, vk::PipelineStageFlagBits::eComputeShader,
                    vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eShaderRead,
                    vk::PipelineStageFlagBits::eComputeShader,
                    vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
    }
}

// The sums as the image: the mean over the samples on the sphere, 0 off it
Image read_image(const Buffer& accum, uint32_t size, uint32_t spp) {
    Image im;
    im.size = size;
    im.rgba.resize(size_t(size) * size);
    const auto* sums = static_cast<const glm::vec4*>(accum.mapped);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            vec3 n;
            const bool on = sphere_normal(x, y, size, n);
            const glm::vec4 v = sums[size_t(y) * size + x];
            im.at(x, y) = on ? glm::vec4(glm::vec3(v) / float(spp), 1.0f) : glm::vec4(0.0f);
        }
    return im;
}

}   // namespace

std::vector<ModelRender> render_models(VkContext& ctx, const Stack& s, const Environment& env,
                                       const ModelRenderOptions& o, ModelRenderStage* stage) {
    const auto t0 = Clock::now();
    ModelRenderStage st;
    st.samples_per_dispatch = kSamplesPerDispatch;
    BelcourTableKernel table_kernel(ctx);
    const ModelStack ms = model_stack(s, o.models, table_kernel);
    std::vector<size_t> todo;
    std::vector<ModelRender> out = select_models(ms, s, o, todo);
    if (todo.empty()) {
        if (stage) *stage = st;
        return out;
    }
    const size_t pixels = size_t(o.size) * o.size;
    RenderBuffers b(ctx, ms, env, pixels);
    st.setup_seconds = since(t0);
    const auto tp = Clock::now();
    std::vector<std::unique_ptr<ComputeKernel>> kernels = make_pipelines(ctx, out, todo, b);
    st.pipelines_seconds = since(tp);

    RenderPush pc{};
    lobe_roughness(s, pc.alpha_lobe0, pc.alpha_lobe1);
    pc.mu_jump = float(ms.mu_jump);
    pc.size = o.size;
    pc.seed = o.seed;
    pc.env_w = env.width;
    pc.env_h = env.height;
    pc.use_tables = o.models.belcour_tables ? 1u : 0u;
    pc.env_sampled = b.env_sampled ? 1u : 0u;
    const uint32_t groups = groups_for(pixels, RENDER_GROUP_SIZE);
    for (size_t i = 0; i < todo.size(); ++i) {
        ModelRender& r = out[todo[i]];
        const auto tr = Clock::now();
        std::memset(b.accum.mapped, 0, pixels * sizeof(glm::vec4));
        const bool lobe_pass = !r.user && uses_tables(r.model);
        ctx.run_now([&](vk::CommandBuffer cb) { record_render(cb, *kernels[i], lobe_pass, pc, o.spp, groups); });
        r.image = read_image(b.accum, o.size, o.spp);
        r.render_seconds = since(tr);
    }
    st.wall_seconds = since(t0);
    if (stage) *stage = st;
    return out;
}

}   // namespace gonio
