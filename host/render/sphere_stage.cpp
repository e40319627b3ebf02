// sphere_stage.cpp: see sphere_stage.h.
#include "sphere_stage.h"
#include "vk_context.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

namespace gonio {

Environment load_render_environment(const std::string& name) {
    Environment env = load_environment(name);
    if (env.negative_texels || env.non_finite_texels)
        std::fprintf(stderr,
                     "render: %s: %llu texels with negative values (down to %.3g) and %llu not finite, set to 0\n",
                     env.source.c_str(), (unsigned long long)env.negative_texels, env.most_negative,
                     (unsigned long long)env.non_finite_texels);
    return env;
}

std::array<SimResult, 2> simulate_table_halves(VkContext& ctx, const Stack& s, SimOptions o) {
    std::array<SimResult, 2> half;
    const uint32_t seed = o.seed;
    for (int h = 0; h < 2; ++h) {
        o.seed = seed + uint32_t(h) * 0x9e3779b9u;
        half[h] = simulate_gpu(ctx, s, o);
    }
    return half;
}

SphereStage render_sphere_stage(VkContext& ctx, const SphereStageRequest& r) {
    using clock = std::chrono::steady_clock;
    SphereStage st;
    st.env = r.environment ? *r.environment : load_render_environment(r.env);
    const auto tt = clock::now();
    if (r.table) {
        st.table = *r.table;
    } else {
        st.halves = simulate_table_halves(ctx, *r.stack, r.table_half);
        st.table = table_from_halves((*st.halves)[0], (*st.halves)[1]);
    }
    st.table_seconds = std::chrono::duration<double>(clock::now() - tt).count();

    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    st.reference = render_reference(st.table, st.env, r.models.size, threads);
    if (!r.quiet)
        std::fprintf(stderr, "render: reference %.2f s on %u threads\n", st.reference.seconds, st.reference.threads);
    st.models = render_models(ctx, *r.stack, st.env, r.models, &st.model_stage);
    if (!r.quiet)
        std::fprintf(stderr, "render: models %.2f s (pipelines %.2f s, the samples they share %.2f s)\n",
                     st.model_stage.wall_seconds, st.model_stage.pipelines_seconds, st.model_stage.samples_seconds);
    return st;
}

}   // namespace gonio
