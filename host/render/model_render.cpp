#include "model_render.h"
#include "belcour_tables_host.h"
#include "compute_kernel.h"
#include "model_applicability.h"
#include "model_plan.h"
#include "model_stack.h"
#include "user_model.h"
#include "model_twin.h"
#include "render_samples_spv.h"
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

// Iterations per dispatch: lavapipe ends an invocation's loops after 65535 trips in all (docs/ARCHITECTURE.md); an
// iteration makes two binary searches of the environment's CDFs in the samples' pass (log2 of its size, 20 for
// 1024 x 512) and 3 model evaluations in a model's (a few to a few dozen trips each: Belcour's and tm21's loops over
// the layers), so 16 iterations stay far below it.
constexpr uint32_t kSamplesPerDispatch = 16;
// The samples' buffer: a tile of pixels times a batch of iterations times 3 strategies, each a direction and a
// weight (two vec4), within this many bytes (a 256^2 render at 64 iterations: 4 tiles)
constexpr size_t kSampleBufferBytes = size_t(128) << 20;
constexpr size_t kSampleBytes = 2 * sizeof(glm::vec4);
constexpr uint32_t kBatchIterations = 4 * kSamplesPerDispatch;
constexpr size_t kLobesPerModel = size_t(BELCOUR_MU_NODES) * BELCOUR_LOBE_STRIDE;   // a model's slot in lobes

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
        r.user_slot = uint32_t(&um - o.models.user_models.data());
        r.id = um->header.id;
        r.not_applicable = model_id_not_selected(r.id, o.models);
        if (r.not_applicable.empty()) r.not_applicable = model_file_cannot_represent(um->header, s);
        if (r.not_applicable.empty()) todo.push_back(out.size());
        out.push_back(std::move(r));
    }
    return out;
}

// render.comp's inputs on the device: the models' (model_stack.h), the sums, the environment and its CDFs, the lobes,
// the samples
struct RenderBuffers {
    ModelStackBuffers inputs;
    Buffer accum, env, cdf, lobes, samples;
    bool env_sampled = true;

    // models: how many render (a slot of lobes each); accum_sums: their sums over a tile (models x tile pixels);
    // sample_bytes: the tile's samples
    RenderBuffers(VkContext& ctx, const ModelStack& ms, const Environment& e, size_t models, size_t accum_sums,
                  size_t sample_bytes)
        : inputs(ctx) {
        inputs.upload(ms);
        accum = ctx.make_buffer(accum_sums * sizeof(glm::vec4), vk::BufferUsageFlagBits::eStorageBuffer, true);
        samples = ctx.make_device_buffer(sample_bytes, vk::BufferUsageFlagBits::eStorageBuffer);
        const size_t texels = size_t(e.width) * e.height;
        env = ctx.make_buffer(texels * sizeof(glm::vec4), vk::BufferUsageFlagBits::eStorageBuffer, true);
        auto* texel_dst = static_cast<glm::vec4*>(env.mapped);
        for (size_t t = 0; t < texels; ++t) texel_dst[t] = glm::vec4(e.texels[t], 0.0f);
        const std::vector<float> c = environment_cdf(e, &env_sampled);
        cdf = ctx.make_buffer(c.size() * 4, vk::BufferUsageFlagBits::eStorageBuffer, true);
        std::memcpy(cdf.mapped, c.data(), c.size() * 4);
        lobes = ctx.make_device_buffer(models * kLobesPerModel * sizeof(glm::vec4),
                                       vk::BufferUsageFlagBits::eStorageBuffer);
    }
    std::vector<const Buffer*> bindings() const {   // indexed by RENDER_BINDING_*
        std::vector<const Buffer*> b(RENDER_BINDINGS, nullptr);
        b[RENDER_BINDING_STACK] = &inputs.stack;
        b[RENDER_BINDING_ACCUM] = &accum;
        b[RENDER_BINDING_STACK_TABLES] = &inputs.stack_tables;
        b[RENDER_BINDING_BELCOUR_TABLES] = &inputs.tables;
        b[RENDER_BINDING_ENV] = &env;
        b[RENDER_BINDING_ENV_CDF] = &cdf;
        b[RENDER_BINDING_LOBES] = &lobes;
        b[RENDER_BINDING_SAMPLES] = &samples;
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
        // MODEL: a built-in's code; a user's model's slot of parameters (model_stack.h fill_model_parameters)
        const uint32_t code = r.user ? MODEL_USER_PARAMETER_SLOT0 + r.user_slot : shader_model_of(r.model);
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

void barrier_to_next_dispatch(vk::CommandBuffer cb) {   // the next dispatch reads (and adds to) what this wrote
    barrier(cb, vk::PipelineStageFlagBits::eComputeShader,
            vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eShaderRead,
            vk::PipelineStageFlagBits::eComputeShader,
            vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
}

// A model's lobes at the nodes of mu (Belcour's, tm21: render.comp's lobe pass), read by its dispatches after
void record_lobe_pass(vk::CommandBuffer cb, const ComputeKernel& k, const RenderPush& pc) {
    RenderPush lp{};
    lp.use_tables = pc.use_tables;
    lp.mu_jump = pc.mu_jump;
    lp.pass = RENDER_PASS_LOBES;
    lp.lobes_first = pc.lobes_first;
    k.record(cb, lp, groups_for(BELCOUR_MU_NODES, RENDER_GROUP_SIZE));
    barrier_to_next_dispatch(cb);
}

// pc's tile and batch: its samples (render_samples.comp), or a model's sums over them (render.comp), in dispatches
// of kSamplesPerDispatch iterations
void record_iterations(vk::CommandBuffer cb, const ComputeKernel& k, RenderPush pc, uint32_t iterations) {
    const uint32_t groups = groups_for(pc.tile_pixels, RENDER_GROUP_SIZE);
    for (uint32_t first = 0; first < iterations; first += kSamplesPerDispatch) {
        pc.first_sample = pc.batch_first + first;
        pc.samples = std::min(kSamplesPerDispatch, iterations - first);
        k.record(cb, pc, groups);
        barrier_to_next_dispatch(cb);
    }
}

// The tile's sums of one model (accum's slot) into its image: the mean over the samples on the sphere, 0 off it
void read_tile(Image& im, const Buffer& accum, size_t slot, const RenderPush& pc, uint32_t spp) {
    const auto* sums = static_cast<const glm::vec4*>(accum.mapped) + slot * pc.tile_pixels;
    for (uint32_t i = 0; i < pc.tile_pixels && pc.pixel_first + i < pc.size * pc.size; ++i) {
        const uint32_t pixel = pc.pixel_first + i, y = pixel / pc.size, x = pixel - y * pc.size;
        vec3 n;
        im.at(x, y) =
            sphere_normal(x, y, pc.size, n) ? glm::vec4(glm::vec3(sums[i]) / float(spp), 1.0f) : glm::vec4(0.0f);
    }
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
    // the tiling: tiles of pixels (a multiple of the group size) and batches of iterations whose samples fit the
    // buffer; every model's sums over a tile side by side in accum
    const size_t pixels = size_t(o.size) * o.size;
    const uint32_t batch = std::min(o.spp, kBatchIterations);
    const size_t fit = kSampleBufferBytes / (size_t(batch) * RENDER_STRATEGIES * kSampleBytes);
    const uint32_t tile =
        uint32_t(std::min(size_t(groups_for(pixels, RENDER_GROUP_SIZE)) * RENDER_GROUP_SIZE,
                          std::max<size_t>(RENDER_GROUP_SIZE, fit / RENDER_GROUP_SIZE * RENDER_GROUP_SIZE)));
    RenderBuffers b(ctx, ms, env, todo.size(), todo.size() * size_t(tile),
                    size_t(tile) * batch * RENDER_STRATEGIES * kSampleBytes);
    st.setup_seconds = since(t0);
    const auto tp = Clock::now();
    std::vector<std::unique_ptr<ComputeKernel>> kernels = make_pipelines(ctx, out, todo, b);
    auto sampler = std::make_unique<ComputeKernel>(ctx.device(), render_samples_spv, sizeof(render_samples_spv),
                                                   render_descriptor_types(), uint32_t(sizeof(RenderPush)));
    sampler->build(ctx.device(), {}, nullptr, 0);
    sampler->bind(ctx.device(), b.bindings());
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
    pc.tile_pixels = tile;
    for (size_t i : todo) {
        out[i].image.size = o.size;
        out[i].image.rgba.assign(pixels, glm::vec4(0.0f));
    }
    // the lobe passes, once, each model's into its slot: the lobes depend on the stack alone
    for (size_t i = 0; i < todo.size(); ++i)
        if (!out[todo[i]].user && uses_tables(out[todo[i]].model)) {
            const auto tr = Clock::now();
            pc.lobes_first = uint32_t(i * kLobesPerModel);
            ctx.run_now([&](vk::CommandBuffer cb) { record_lobe_pass(cb, *kernels[i], pc); });
            out[todo[i]].render_seconds += since(tr);
        }
    for (pc.pixel_first = 0; pc.pixel_first < pixels; pc.pixel_first += tile) {
        std::memset(b.accum.mapped, 0, todo.size() * size_t(tile) * sizeof(glm::vec4));
        for (pc.batch_first = 0; pc.batch_first < o.spp; pc.batch_first += batch) {
            const uint32_t iterations = std::min(batch, o.spp - pc.batch_first);
            const auto ts = Clock::now();
            pc.pass = RENDER_PASS_SAMPLES;
            ctx.run_now([&](vk::CommandBuffer cb) { record_iterations(cb, *sampler, pc, iterations); });
            st.samples_seconds += since(ts);
            pc.pass = RENDER_PASS_MODEL;
            for (size_t i = 0; i < todo.size(); ++i) {
                const auto tr = Clock::now();
                pc.accum_first = uint32_t(i * tile);
                pc.lobes_first = uint32_t(i * kLobesPerModel);
                ctx.run_now([&](vk::CommandBuffer cb) {
                    record_iterations(cb, *kernels[i], pc, iterations);
                    barrier(cb, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                            vk::PipelineStageFlagBits::eHost, vk::AccessFlagBits::eHostRead);
                });
                out[todo[i]].render_seconds += since(tr);
            }
        }
        for (size_t i = 0; i < todo.size(); ++i) read_tile(out[todo[i]].image, b.accum, i, pc, o.spp);
    }
    st.tiles = uint32_t(groups_for(pixels, tile));
    st.tile_pixels = tile;
    st.batch_iterations = batch;
    st.wall_seconds = since(t0);
    if (stage) *stage = st;
    return out;
}

}   // namespace gonio
