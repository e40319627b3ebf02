// render_case.cpp: see render_case.h.
#include "render_case.h"
#include "image.h"
#include "json.h"
#include "model_render.h"
#include "output.h"
#include "python_tool.h"
#include "refusal.h"
#include "reference_render.h"
#include "spectral_render.h"
#include "state.h"
#include "vk_context.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>

namespace gonio {

namespace fs = std::filesystem;

namespace {

// The table --reference DIR names: DIR/table-a and DIR/table-b (the halves render writes), or one simulate run in
// DIR.
ReferenceTable table_of_reference_directory(const RenderRequest& a, const Stack& s, Json& info) {
    auto same_stack = [&](const SimResult& r, const std::string& dir) {
        if (stack_to_toml(r.stack) != stack_to_toml(s))
            throw std::invalid_argument("--reference " + dir + ": a run of another stack (" + r.stack.name + ", not " +
                                        s.name + ")");
        require_plane_of_incidence(r.options, "a render's tables (--reference " + dir + ")");
        if (r.angles.size() < 2)
            throw std::invalid_argument("--reference " + dir +
                                        ": one incident angle; a sphere needs a table over angles (--theta-i 0:88:2)");
    };
    const std::string d = a.reference;
    if (!fs::is_directory(d)) throw std::invalid_argument("--reference " + d + ": no such directory");
    if (fs::exists(d + "/table-a/state.gonio") && fs::exists(d + "/table-b/state.gonio")) {
        const SimResult ra = load_state(d + "/table-a/state.gonio"), rb = load_state(d + "/table-b/state.gonio");
        same_stack(ra, d + "/table-a");
        same_stack(rb, d + "/table-b");
        if (ra.options.theta_i_deg != rb.options.theta_i_deg || ra.n_theta != rb.n_theta || ra.n_phi != rb.n_phi)
            throw std::invalid_argument("--reference " + d + ": its halves have other angles or bins");
        info["table"] = d + "/table-{a,b}";
        return table_from_halves(ra, rb);
    }
    if (!fs::exists(d + "/state.gonio"))
        throw std::invalid_argument("--reference " + d +
                                    ": no state.gonio (a directory of gonio simulate, or of render)");
    const SimResult r = load_state(d + "/state.gonio");
    same_stack(r, d);
    info["table"] = d;
    return table_from_run(r, a.seed);
}

}   // namespace

SimOptions table_half_options(const RenderRequest& a) {
    SimOptions o;
    o.theta_i_deg = a.theta_i;
    o.paths = a.paths / 2;
    o.progress = !a.quiet;
    validate_options(o);
    o.seed = a.seed;
    return o;
}

namespace {

using Attributes = std::vector<std::pair<std::string, std::string>>;

// render.json's description of the scene: the environment, the camera, the size, the seed and the tone map.
Json scene_json(const Stack& s, const Environment& env, const RenderRequest& a, double exposure, double diff_scale) {
    Json j;
    j["gonio_render"] = 1;
    j["stack"] = s.name;
    j["environment"] = {{"name", env.name},
                        {"source", env.source},
                        {"width", env.width},
                        {"height", env.height},
                        {"negative_texels_clamped", env.negative_texels},
                        {"most_negative", json_number(env.most_negative)},
                        {"non_finite_texels", env.non_finite_texels},
                        {"convention",
                         "equirectangular, z up: u = phi / 2pi (phi = atan2(y, x) from +x towards +y), v = theta / pi "
                         "(row 0 the zenith)"}};
    j["camera"] =
        "orthographic along -z onto the unit sphere; view direction +z; A = 1 where the pixel's centre is on "
        "the sphere";
    j["size"] = a.size;
    j["seed"] = a.seed;
    j["tone_map"] = {{"exposure", json_number(exposure)},
                     {"curve", "exposure x radiance, x / (1 + x), sRGB"},
                     {"difference_png_scale", json_number(diff_scale)}};
    return j;
}

// render.json's reference: its table, how its halves were made, its cost and its floor (between its halves).
Json reference_json(const Json& info, const ReferenceTable& table, const ReferenceRender& ref, double table_seconds) {
    Json rj;
    rj["table"] = info["table"];
    rj["theta_i_deg"] = table.theta_i_deg;
    rj["paths_per_angle"] = table.paths_per_angle;
    rj["halves"] = table.independent_halves ? "two independent halves of the paths (other seeds)"
                                            : "one run: f + se z and f - se z (z seeded standard normal per bin and "
                                              "channel), whose difference has the variance of two halves'";
    rj["pixels_beyond_table"] = ref.pixels_beyond_table;
    rj["env_box_filter_phi_theta"] = {ref.env_filter[0], ref.env_filter[1]};
    rj["env_samples_per_bin"] = ref.samples_per_bin;
    rj["table_seconds"] = json_number(table_seconds);
    rj["render_seconds"] = json_number(ref.seconds);
    rj["threads"] = ref.threads;
    rj["floor"] = {
        {"relative_l1_between_halves", json_number(relative_l1(ref.half[0], ref.half[1]))},
        {"relative_l1_estimate_of_full",
         json_number(0.5 * relative_l1(ref.half[0], ref.half[1]))}};   // a half's noise is twice the full's variance
    return rj;
}

// Pixels with a value that is NaN or infinite: the model's f is not finite somewhere it was sampled.
uint64_t non_finite_pixels(const Image& im) {
    uint64_t n = 0;
    for (const glm::vec4& c : im.rgba) n += !(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
    return n;
}

// Each model's images, its difference to the reference and render.json's entry. A model with pixels that are not
// finite is said on stderr, its images not written, and `unusable` counts it.
Json write_models(const std::vector<ModelRender>& models, const ReferenceRender& ref, const RenderRequest& a,
                  const Attributes& attrs, double exposure, double diff_scale, int& unusable) {
    Json mj = Json::array();
    for (const ModelRender& m : models) {
        Json e;
        e["id"] = m.id;
        std::string why = m.not_applicable;
        if (const uint64_t bad = why.empty() ? non_finite_pixels(m.image) : 0; bad > 0) {
            std::fprintf(stderr,
                         "render: %s: %llu pixels are NaN or infinite (its f is not finite where they sample it): "
                         "not scored, no image written\n",
                         m.id.c_str(), (unsigned long long)bad);
            why = std::to_string(bad) + " pixels NaN or infinite: its f is not finite somewhere";
            e["non_finite_pixels"] = bad;
            ++unusable;
        }
        if (!why.empty()) {
            e["not_rendered"] = why;
            mj.push_back(e);
            continue;
        }
        write_rgba_exr(a.out + "/" + m.id + ".exr", m.image, attrs);
        write_tonemapped_png(a.out + "/" + m.id + ".png", m.image, exposure);
        const Image d = difference(m.image, ref.image);
        write_rgba_exr(a.out + "/diff-" + m.id + ".exr", d, attrs);
        write_difference_png(a.out + "/diff-" + m.id + ".png", d, diff_scale);
        e["relative_l1"] = json_number(relative_l1(m.image, ref.image));
        e["spp"] = a.spp;
        e["pipeline_seconds"] = json_number(m.pipeline_seconds);
        e["render_seconds"] = json_number(m.render_seconds);
        mj.push_back(e);
    }
    return mj;
}

}   // namespace

int render_to_directory(VkContext& ctx, const Stack& s, const RenderRequest& a, const Environment* env) {
    using clock = std::chrono::steady_clock;
    auto since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
    const auto t0 = clock::now();
    Json info;
    std::optional<Environment> read_first;   // --spectral: the environment read before its tables are traced
    std::optional<SpectralRenderTables> spectral;   // --spectral: the table band by band, the RGB run's beside it
    std::optional<ReferenceTable> given;   // --reference DIR
    if (a.spectral) {
        if (!env) env = &read_first.emplace(load_render_environment(a.env));
        spectral = spectral_render_tables(ctx, s, a);
        info["table"] = a.out + "/spectral-{a,b} (made now, band by band)";
    } else if (!a.reference.empty()) {
        given = table_of_reference_directory(a, s, info);
    }
    const double given_seconds = since(t0);

    SphereStageRequest sr;
    sr.stack = spectral ? &spectral->rgb_stack : &s;
    sr.env = a.env;
    sr.environment = env;
    sr.table = spectral ? &spectral->spectral : given ? &*given : nullptr;
    if (!sr.table) sr.table_half = table_half_options(a);
    sr.models.size = a.size;
    sr.models.spp = a.spp;
    sr.models.seed = a.seed;
    sr.models.models = a.models;
    sr.quiet = a.quiet;
    const SphereStage st = render_sphere_stage(ctx, sr);
    const ReferenceRender& ref = st.reference;
    const double table_seconds = st.halves ? st.table_seconds : given_seconds;

    // files
    fs::create_directories(a.out);
    if (st.halves) {
        for (int h = 0; h < 2; ++h) {
            const std::string dir = a.out + (h ? "/table-b" : "/table-a");
            fs::create_directories(dir);
            save_state(dir + "/state.gonio", (*st.halves)[size_t(h)]);
        }
        info["table"] = a.out + "/table-{a,b} (made now)";
    }
    const Attributes attrs = {{"gonio_stack", s.source_text},
                              {"gonio_env", st.env.name + " (" + st.env.source + ")"},
                              {"gonio_seed", std::to_string(a.seed)}};
    const double exposure = auto_exposure(ref.image);
    write_rgba_exr(a.out + "/reference.exr", ref.image, attrs);
    write_tonemapped_png(a.out + "/reference.png", ref.image, exposure);
    write_rgba_exr(a.out + "/reference-half-a.exr", ref.half[0], attrs);
    write_rgba_exr(a.out + "/reference-half-b.exr", ref.half[1], attrs);
    const double diff_scale = 0.25 / exposure;   // a quarter of the tone map's white
    Json j = scene_json(s, st.env, a, exposure, diff_scale);
    j["reference"] = reference_json(info, st.table, ref, table_seconds);
    int unusable = 0;
    j["models"] = write_models(st.models, ref, a, attrs, exposure, diff_scale, unusable);
    if (spectral) {
        j["rgb_vs_spectral"] = rgb_vs_spectral_on_sphere(*spectral, ref, st.env, a, attrs, exposure);
        j["models_evaluated"] = std::string("in RGB, on the stack reduced by ") + to_string(a.reduction) +
                                ", against the spectral reference";
    }
    j["model_stage"] = {{"wall_seconds", json_number(st.model_stage.wall_seconds)},
                        {"setup_seconds", json_number(st.model_stage.setup_seconds)},
                        {"pipelines_seconds", json_number(st.model_stage.pipelines_seconds)},
                        {"samples_seconds", json_number(st.model_stage.samples_seconds)},
                        {"samples_per_dispatch", st.model_stage.samples_per_dispatch},
                        {"tiles", st.model_stage.tiles},
                        {"tile_pixels", st.model_stage.tile_pixels},
                        {"batch_iterations", st.model_stage.batch_iterations}};
    j["flip"] = "not computed: tools/render_report.py did not run";
    if (a.no_report) j["flip"] = "not computed (--no-report)";
    write_json_file(a.out + "/render.json", j);
    if (!a.no_report) {
        const int rc = run_python_command("render_report.py", {a.out});
        if (rc != 0) std::fprintf(stderr, "render: tools/render_report.py failed (exit %d): no FLIP, no figure\n", rc);
    }
    std::printf("wrote %s/{reference,MODEL}.{exr,png}, diff-MODEL.{exr,png}, render.json (%.1f s)\n", a.out.c_str(),
                since(t0));
    return unusable > 0 ? 1 : 0;
}

}   // namespace gonio
