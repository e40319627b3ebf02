// test_render.cpp: gonio render (host/render): white furnaces where every pixel is the directional albedo at its
// view angle (cos theta_v = n.z), for the models on the device and for the reference from its table; determinism;
// the environment maps.
#include "environment.h"
#include "exact.h"
#include "gpu_fixture.h"
#include "materialx_fit.h"
#include "model_quadrature.h"
#include "model_render.h"
#include "reference_render.h"
#include "colour_difference.h"
#include "spectral_sphere.h"
#include "model_twin.h"   // the adobe-energy set's layout
#include "stack_tables.h"
#include "render_interface.glsl"
#include "user_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <stdexcept>

using namespace gonio;
using gonio_test::context;

namespace {

// A smooth coat of index `ior` over a Lambertian base of albedo rho
Stack coat_over_lambertian(double ior, double rho) {
    char text[512];
    std::snprintf(text, sizeof text,
                  "name = \"furnace-%g-%g\"\nexterior_ior = 1.0\n[[layer]]\ninterface = \"dielectric\"\nroughness = 0\n"
                  "ior = %.9g\n[[layer]]\ninterface = \"lambertian\"\nalbedo = [%.9g, %.9g, %.9g]\n",
                  ior, rho, ior, rho, rho, rho);
    return parse_stack_string(text, "test");
}

// Exact unpolarised Fresnel reflectance of a dielectric interface from index 1 to eta (Born & Wolf)
double fresnel(double cos_i, double eta) {
    const double s2 = 1 - cos_i * cos_i, ct = std::sqrt(1 - s2 / (eta * eta));
    const double rs = (cos_i - eta * ct) / (cos_i + eta * ct), rp = (eta * cos_i - ct) / (eta * cos_i + ct);
    return 0.5 * (rs * rs + rp * rp);
}

ReferenceTable furnace_table(const Stack& s, uint64_t paths) {
    SimOptions o;
    o.theta_i_deg.clear();
    for (double t = 0; t <= 88; t += 2) o.theta_i_deg.push_back(t);
    o.paths = paths;
    o.seed = 7;
    const SimResult a = simulate_gpu(context(), s, o);
    o.seed = 8;
    const SimResult b = simulate_gpu(context(), s, o);
    return table_from_halves(a, b);
}

constexpr uint32_t kSize = 32;
// The models' iterations per pixel in the furnaces: a cosine sample in the GGX-1e-4 lobe's tail (within ~1e-2 rad of
// the mirror direction, where the lobe's density exceeds the cosine's) gets a power-heuristic weight near 0 and the
// lobe's samples make its share up in small parts: unbiased, but a pixel then misses about 1 / spp of its value
// (measured: 0.4% of the pixels at 64 spp). 1024 keeps that below 1e-3.
constexpr uint32_t kFurnaceSpp = 1024;

class Render : public gonio_test::GpuTest {};

// The reference of stack s in the furnace: every pixel rho within its noise (its two halves' difference per pixel)
void expect_reference_in_furnace(const Stack& s, const Environment& env, double rho) {
    const ReferenceRender ref = render_reference(furnace_table(s, 100000), env, kSize, 2);
    double worst = 0, rms_half = 0;
    int n_on = 0;
    for (size_t p = 0; p < ref.image.rgba.size(); ++p) {
        if (!(ref.image.rgba[p].w > 0)) continue;
        ++n_on;
        for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, std::fabs(ref.image.rgba[p][c] - rho));
            const double d = 0.5 * (ref.half[0].rgba[p][c] - ref.half[1].rgba[p][c]);
            rms_half += d * d;
        }
    }
    rms_half = std::sqrt(rms_half / (3.0 * n_on));   // the whole table's noise per pixel
    std::printf("furnace, index-matched coat: reference worst |pixel - rho| = %.2e, noise %.2e\n", worst, rms_half);
    EXPECT_LT(worst, 5 * rms_half + 1e-5);
}

}   // namespace

TEST_F(Render, FurnaceIndexMatchedCoatGivesRho) {
    const double rho = 0.8;
    const Stack s = coat_over_lambertian(1.0, rho);
    const Environment env = load_environment("furnace");
    ModelRenderOptions o;
    o.size = kSize;
    o.spp = kFurnaceSpp;
    const std::vector<ModelRender> models = render_models(context(), s, env, o);
    int rendered = 0;
    for (const ModelRender& m : models) {
        if (!m.not_applicable.empty()) continue;
        ++rendered;
        // OpenPBR darkens the base by (1 - K) / (1 - rho K), K = 1 - (1 - E_F(1)) / 1 = E_F(1), with the specification's
        // fit of the Fresnel albedo, which at eta = 1 is ln(9454.8 / 9438.6) = 0.0017, not 0: its index-matched coat
        // keeps that much darkening
        double want = rho;
        const bool adobe = m.id.rfind("openpbr-adobe", 0) == 0;
        if (m.id.rfind("openpbr", 0) == 0 && m.id != "openpbr+materialx" && !adobe) {   // and its variants of the spec
            const double k = std::log((10893.0 - 1438.2) / (-774.4 + 10212.0 + 1.0));
            want = rho * (1 - k) / (1 - rho * k);
        }
        // Adobe's: K = avgF(1) = 0.00267 (Kulla & Conty's fit, the branch below 1 at 1) and E_b = mix(rho, 1, K), and
        // its diffuse's compensation OD(1, 0, mu_v) OD(1, 0, mu_l) / ODA (specular roughness 0 under an index-matched
        // coat: the table at IOR 1.0001 and roughness 0, 1 - F(mu, 1.0001), which falls at mu < 1/31); over l it
        // integrates to int OD(mu_l) 2 mu_l dmu_l / ODA: 1 but for the table's linear reading along mu, so the pixel is
        // rho Delta OD(1, 0, mu_v) times that
        const double k_adobe = 0.997118 + 0.1014 - 0.965241 - 0.130607, e_b = rho + (1 - rho) * k_adobe;
        const std::vector<float> adobe_tables = stack_tables(pack_stack(s), STACK_TABLES_ADOBE_ENERGY);
        auto adobe_od = [&](double mu) {
            const double x = std::min(mu, 1.0) * 31, t = x - std::min(std::floor(x), 30.0);
            const uint32_t i = uint32_t(x - t);
            return adobe_tables[STACK_TABLE_ADOBE_DIFFUSE + i] +
                   (adobe_tables[STACK_TABLE_ADOBE_DIFFUSE + i + 1] - adobe_tables[STACK_TABLE_ADOBE_DIFFUSE + i]) * t;
        };
        double over_l = 0;
        for (int i = 0; i < 100000; ++i) over_l += adobe_od((i + 0.5) / 100000) * 2 * (i + 0.5) / 100000 / 100000;
        over_l /= adobe_tables[STACK_TABLE_ADOBE_DIFFUSE + ADOBE_TABLE_NODES];
        // MaterialX's layer: its dielectric_bsdf's throughput 1 - (F0 A + F90 B) comp takes F90 = 1 whatever the IOR,
        // so at IOR 1 (F0 = 0, no reflection) the base still loses B comp, most of it at grazing views; OpenPBR's
        // MaterialX graph twice (its coat, and the diffuse's specular layer of specular_weight 0, both smooth here, at
        // the models' stand-in alpha 1e-4; its darkening is 1 at eta 1)
        const bool materialx = m.id == "materialx-layer" || m.id == "openpbr+materialx";
        double worst = 0, darkest = 1, sum_d = 0, sum_d2 = 0;
        int n_d = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                vec3 n;
                if (!sphere_normal(x, y, kSize, n)) continue;
                const double mu = std::max(double(n.z), 1e-8);
                double w = materialx ? rho * mx::dielectric_throughput(mu, 1e-4, 1.0) : want;
                if (m.id == "openpbr+materialx") w *= mx::dielectric_throughput(mu, 1e-4, 1.0);
                if (adobe) w = rho * (1 - k_adobe) / (1 - e_b * k_adobe) * adobe_od(mu) * over_l;
                darkest = std::min(darkest, w);
                for (int c = 0; c < 3; ++c) {
                    const double d = m.image.rgba[y * kSize + x][c] - w;
                    worst = std::max(worst, std::fabs(d));
                    sum_d += d;
                    sum_d2 += d * d;
                    ++n_d;
                }
            }
        // Adobe's f varies with l (its compensation falls near grazing), so its pixels are noisier than the constant
        // f of the others (rms 3.1e-4 against 2.6e-4 at 1024 spp, measured): unbiased (mean within 2e-5) and its worst
        // pixel within 4.5 of its rms over the 2436 values
        const double mean = sum_d / n_d, rms = std::sqrt(sum_d2 / n_d);
        if (adobe) {
            std::printf("furnace, index-matched coat: %s mean departure %.2e, rms %.2e\n", m.id.c_str(), mean, rms);
            EXPECT_LT(std::fabs(mean), 2e-5) << m.id;
            EXPECT_LT(worst, 4.5 * rms) << m.id;
        } else {
            EXPECT_LT(worst, 1e-3) << m.id;
        }
        if (materialx) {
            std::printf("furnace, index-matched coat: %s keeps down to %.4f of the base's %.1f\n", m.id.c_str(),
                        darkest, rho);
            EXPECT_LT(darkest, 0.9 * rho);
        }
        std::printf("furnace, index-matched coat: %s worst |pixel - %s| = %.2e\n", m.id.c_str(),
                    materialx ? "rho (1 - B comp)"
                    : adobe   ? "rho Delta OD(mu_v)"
                              : std::to_string(want).c_str(),
                    worst);
        if (adobe) std::printf("  (Adobe's diffuse compensation integrates to %.6f over l)\n", over_l);
    }
    EXPECT_GE(rendered, 4);
    expect_reference_in_furnace(s, env, rho);
}

TEST_F(Render, FurnaceSmoothCoatOverBlackGivesFresnel) {
    const Stack s = coat_over_lambertian(1.5, 0.0);
    const Environment env = load_environment("furnace");
    ModelRenderOptions o;
    o.size = kSize;
    o.spp = kFurnaceSpp;
    const std::vector<ModelRender> models = render_models(context(), s, env, o);
    int rendered = 0;
    for (const ModelRender& m : models) {
        if (!m.not_applicable.empty()) continue;
        ++rendered;
        double worst = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                vec3 n;
                if (!sphere_normal(x, y, kSize, n)) continue;
                // glTF's clearcoat: its lobe weighed by Schlick's 0.04 + 0.96 (1 - n.v)^5, f0 fixed (KHR_materials_clearcoat)
                // (Enterprise PBR's: at h.v, which the mirror direction makes n.v)
                const bool schlick = m.id.rfind("gltf-clearcoat", 0) == 0 || m.id == "enterprise-pbr";
                double F = schlick ? 0.04 + 0.96 * std::pow(1.0 - n.z, 5) : fresnel(n.z, 1.5);
                // MaterialX's lobe: times Turquin's compensation at the models' smooth stand-in alpha 1e-4
                if (m.id == "materialx-layer" || m.id == "openpbr+materialx")
                    F *= mx::compensation(n.z, 1e-4, fresnel(1.0, 1.5));
                for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(m.image.rgba[y * kSize + x][c] - F));
            }
        EXPECT_LT(worst, 1e-3) << m.id;
        std::printf("furnace, smooth coat over black: %s worst |pixel - F(n.z)| = %.2e\n", m.id.c_str(), worst);
    }
    EXPECT_GE(rendered, 4);
    // the reference: the table's slices interpolated linearly in theta_i, so within its noise of the same
    // interpolation of the exact F at the tabulated angles
    const ReferenceTable t = furnace_table(s, 100000);
    const ReferenceRender ref = render_reference(t, env, kSize, 2);
    double worst = 0, worst_exact = 0, rms_half = 0;
    int n_on = 0;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            vec3 n;
            if (!sphere_normal(x, y, kSize, n)) continue;
            const double tv = std::acos(double(n.z)) * 180 / M_PI;
            if (tv > 88) continue;   // beyond the table
            const size_t k = std::min<size_t>(size_t(tv / 2), 43);
            const double u = (tv - 2.0 * k) / 2.0;
            const double Fi = (1 - u) * fresnel(std::cos(2.0 * k * M_PI / 180), 1.5) +
                              u * fresnel(std::cos(2.0 * (k + 1) * M_PI / 180), 1.5);
            const size_t p = size_t(y) * kSize + x;
            ++n_on;
            for (int c = 0; c < 3; ++c) {
                worst = std::max(worst, std::fabs(ref.image.rgba[p][c] - Fi));
                worst_exact = std::max(worst_exact, std::fabs(ref.image.rgba[p][c] - fresnel(n.z, 1.5)));
                const double d = 0.5 * (ref.half[0].rgba[p][c] - ref.half[1].rgba[p][c]);
                rms_half += d * d;
            }
        }
    rms_half = std::sqrt(rms_half / (3.0 * n_on));
    std::printf(
        "furnace, smooth coat over black: reference worst |pixel - F interpolated| = %.2e (noise %.2e), "
        "|pixel - F(n.z)| = %.2e\n",
        worst, rms_half, worst_exact);
    EXPECT_LT(worst, 5 * rms_half + 1e-5);
}

// A rough coat (alpha 0.3, IOR 1.5) over a black base: only the coat's own reflection leaves, which every
// Weidlich-Wilkie-family model computes exactly (f_r0, the reference's GGX with height-correlated G2 and exact
// Fresnel). Rendered under the studio lights, each model must be within the reference's floor: with r the mean
// of the halves a and b, E|m - r| = E|a - b| / 2 for an exact, noiseless model (r's noise is half of a - b's), so
// 0.75 of the floor leaves the models' own MIS noise room. The same models of a coat at alpha 0.25 must fall
// outside the floor: the test can tell a 17% error in roughness at these paths.
Stack rough_coat_over_black(double alpha) {
    char text[512];
    std::snprintf(text, sizeof text,
                  "name = \"black-%g\"\nexterior_ior = 1.0\n[[layer]]\ninterface = \"dielectric\"\nroughness = %.9g\n"
                  "ior = 1.5\n[[layer]]\ninterface = \"lambertian\"\nalbedo = [0, 0, 0]\n",
                  alpha, alpha);
    return parse_stack_string(text, "test");
}

TEST_F(Render, ExactModelIsWithinTheReferenceFloor) {
    const Stack s = rough_coat_over_black(0.3);
    const Environment env = load_environment("studio");
    const ReferenceRender ref = render_reference(furnace_table(s, 100000), env, kSize, 2);
    const double floor = relative_l1(ref.half[0], ref.half[1]);
    ModelRenderOptions o;
    o.size = kSize;
    o.spp = 256;
    int rendered = 0;
    for (const ModelRender& m : render_models(context(), s, env, o)) {
        // glTF's and Enterprise PBR's coat lobes are not the exact interface reflection (Schlick's Fresnel): no floor
        if (!m.not_applicable.empty() || m.id.rfind("gltf-clearcoat", 0) == 0 || m.id == "enterprise-pbr") continue;
        ++rendered;
        const double l1 = relative_l1(m.image, ref.image);
        std::printf("rough coat over black under studio: %s relative L1 %.4f, floor (halves) %.4f\n", m.id.c_str(), l1,
                    floor);
        EXPECT_LT(l1, 0.75 * floor) << m.id;
    }
    EXPECT_GE(rendered, 4);
    for (const ModelRender& m : render_models(context(), rough_coat_over_black(0.25), env, o)) {
        if (!m.not_applicable.empty()) continue;
        const double l1 = relative_l1(m.image, ref.image);
        std::printf("alpha 0.25 models against the alpha 0.3 reference: %s relative L1 %.4f\n", m.id.c_str(), l1);
        EXPECT_GT(l1, floor) << m.id;
    }
}

// Belcour's models and tm21 read their lobes from the render's lobe pass, a table over mu = cos theta_l
// (BELCOUR_LOBES_OF_MU). Under the furnace a pixel is the integral over w of f(w, v) cos theta_w: here against that
// integral of the CPU twin's f, which computes the lobes at every evaluation (model_value_cpu), by the half-vector
// quadrature about v (model_quadrature.h), at pixels spread over the sphere, on metallic paint (a 0.001 coat over
// a rough conductor, lobes below the top one). The render's own noise (the 0.001 coat's reflection is carried by
// the lobe strategy) is measured by two seeds: with m their mean and d = (a - b) / 2, which has m's spread, the
// RMS of (m - exact) / RMS of d is about 1 for a right render (the table's interpolation, 5e-6 of the image, is far
// below it) and must be under 1.5 (99 channel values: a chi-square of 99 dof above 2.25 x 99 has p < 1e-9); the
// mean of (m - exact) / exact, the bias, must be within 4 standard errors.
TEST_F(Render, FurnaceBelcourAndTm21LobeTableMatchTheirCpuTwin) {
    const Stack s = parse_stack_file("stacks/metallic-paint.toml");
    const Environment env = load_environment("furnace");
    ModelRenderOptions o;
    o.size = kSize;
    o.spp = kFurnaceSpp;
    o.models.selected = {"belcour18-forward", "belcour18-symmetric", "belcour18-toplobe", "tm21", "tm21+g2"};
    const std::vector<ModelRender> a = render_models(context(), s, env, o);
    o.seed = 2;
    const std::vector<ModelRender> b = render_models(context(), s, env, o);
    int rendered = 0;
    const StackGpu sg = pack_stack(s);
    for (size_t k = 0; k < a.size(); ++k) {
        const ModelRender& m = a[k];
        if (!m.not_applicable.empty()) continue;
        ++rendered;
        double err2 = 0, noise2 = 0, bias = 0, bias2 = 0;
        int n = 0;
        for (uint32_t y = 1; y < kSize; y += 5)
            for (uint32_t x = 2; x < kSize; x += 5) {
                vec3 nrm;
                if (!sphere_normal(x, y, kSize, nrm)) continue;
                const double cv = nrm.z, sv = std::sqrt(std::max(0.0, 1 - cv * cv));
                const glm::dvec3 v(sv, 0, cv);   // the pixel's frame: x towards the view
                const glm::dvec3 want = half_vector_quadrature(
                    [&](glm::vec3 w) { return model_value_cpu(m.model, sg, w, glm::vec3(v)); }, v, 0.001, 400, 90);
                const size_t p = size_t(y) * kSize + x;
                for (int c = 0; c < 3; ++c) {
                    const double pa = m.image.rgba[p][c], pb = b[k].image.rgba[p][c];
                    const double e = (0.5 * (pa + pb) - want[c]) / want[c], d = 0.5 * (pa - pb) / want[c];
                    err2 += e * e;
                    noise2 += d * d;
                    bias += e;
                    bias2 += d * d;
                    ++n;
                }
            }
        const double ratio = std::sqrt(err2 / noise2), mean = bias / n, se = std::sqrt(bias2 / n / n);
        std::printf(
            "furnace, metallic paint: %s against the CPU twin's integral over %d values: RMS relative error "
            "%.2e, its noise %.2e (ratio %.2f), mean %.1e (se %.1e)\n",
            m.id.c_str(), n, std::sqrt(err2 / n), std::sqrt(noise2 / n), ratio, mean, se);
        EXPECT_LT(ratio, 1.5) << m.id;
        EXPECT_LT(std::fabs(mean), 4 * se) << m.id;
    }
    EXPECT_EQ(rendered, 5);
}

// A user's model file (render.comp compiled with it at run time): ww-corrected written again from the paper
// (tests/user_models/ww_corrected_rewrite.glsl) renders what the built-in one does, sample for sample (the same
// seed, the same directions): relative L1 between the two images within float rounding (measured 2e-9 at 64²)
// the render of model `id` in r, or null
const ModelRender* render_of(const std::vector<ModelRender>& r, const std::string& id) {
    for (const ModelRender& m : r)
        if (m.id == id) return &m;
    return nullptr;
}

TEST_F(Render, UserModelFileRendersAsTheBuiltInItRewrites) {
    const Stack s = parse_stack_file("stacks/plastic.toml");
    const Environment env = load_environment("studio");
    ModelRenderOptions o;
    o.size = 24;
    o.spp = 32;
    o.models.user_models.push_back(load_user_model("tests/user_models/ww_corrected_rewrite.glsl"));
    o.models.selected = {"ww-corrected", "ww-corrected-rewrite"};
    const std::vector<ModelRender> r = render_models(context(), s, env, o);
    const ModelRender *builtin = render_of(r, "ww-corrected"), *user = render_of(r, "ww-corrected-rewrite");
    ASSERT_TRUE(builtin && user);
    ASSERT_TRUE(builtin->not_applicable.empty() && user->not_applicable.empty()) << user->not_applicable;
    const double l1 = relative_l1(user->image, builtin->image);
    std::printf("user's ww-corrected rewrite against the built-in, rendered: relative L1 %.2e\n", l1);
    EXPECT_LT(l1, 1e-6);
    double lit = 0;   // not two black images
    for (const glm::vec4& p : user->image.rgba) lit += p.x + p.y + p.z;
    EXPECT_GT(lit, 1.0);
}

// A user's delta lobe (model_lobes, roughness 0; left out of model_f) is rendered: under the furnace each pixel of
// tests/user_models/ww_corrected_delta.glsl on a smooth coat exceeds the same file without its delta by the delta's
// weight, F(n.z) (L = 1 from the mirror direction), to float rounding.
TEST_F(Render, UserModelDeltaLobeIsRenderedFromTheMirrorDirection) {
    const Stack s = gonio_test::make_stack(
        "coat", {gonio_test::dielectric(1.5f, 0.0f), gonio_test::lambertian({0.5f, 0.5f, 0.5f})});
    const Environment env = load_environment("furnace");
    std::string text;
    read_model_file("tests/user_models/ww_corrected_delta.glsl", &text);
    std::string no_delta = text;
    no_delta.replace(no_delta.find("gonio-model: ww-corrected-delta"), 31, "gonio-model: no-delta");
    no_delta.replace(no_delta.find("    return 1u;"), 14, "    return 0u;");
    ModelRenderOptions o;
    o.size = 24;
    o.spp = 16;
    o.models.user_models = {compile_user_model(text, "tests/user_models/ww_corrected_delta.glsl"),
                            compile_user_model(no_delta, "/tmp/no-delta.glsl")};
    o.models.selected = {"ww-corrected-delta", "no-delta"};
    const std::vector<ModelRender> r = render_models(context(), s, env, o);
    const ModelRender *with = render_of(r, "ww-corrected-delta"), *without = render_of(r, "no-delta");
    ASSERT_TRUE(with && without);
    ASSERT_TRUE(with->not_applicable.empty() && without->not_applicable.empty()) << with->not_applicable;
    double worst = 0;
    int pixels = 0;
    for (uint32_t y = 0; y < o.size; ++y)
        for (uint32_t x = 0; x < o.size; ++x) {
            vec3 n;
            if (!sphere_normal(x, y, o.size, n)) continue;
            const double F = exact::fresnel(double(n.z), 1.0, 1.5);
            const size_t i = size_t(y) * o.size + x;
            const double d = double(with->image.rgba[i].x) - double(without->image.rgba[i].x);
            worst = std::max(worst, std::fabs(d - F) / F);
            ++pixels;
        }
    std::printf("%d pixels: largest |(with - without) / F(n.z) - 1| %.2e\n", pixels, worst);
    EXPECT_GT(pixels, 300);
    EXPECT_LT(worst, 1e-5);
}

TEST_F(Render, SameSeedSameBytes) {
    const Stack s = parse_stack_file("stacks/plastic.toml");
    const Environment env = load_environment("studio");
    ModelRenderOptions o;
    o.size = 24;
    o.spp = 32;
    o.models.selected = {"ww09", "belcour18-forward"};
    const auto a = render_models(context(), s, env, o), b = render_models(context(), s, env, o);
    o.seed = 2;
    const auto c = render_models(context(), s, env, o);
    for (size_t m = 0; m < a.size(); ++m) {
        if (!a[m].not_applicable.empty()) continue;
        const size_t bytes = a[m].image.rgba.size() * sizeof(glm::vec4);
        EXPECT_EQ(std::memcmp(a[m].image.rgba.data(), b[m].image.rgba.data(), bytes), 0) << a[m].id;
        EXPECT_NE(std::memcmp(a[m].image.rgba.data(), c[m].image.rgba.data(), bytes), 0) << a[m].id;
    }
}

// The reference's vectorised sum against the plain one it replaced (one pixel at a time, the slices interpolated
// per bin, environment_bilinear per bin): a random table and map, bins not a multiple of the chunk or of 8
TEST(RenderReference, VectorisedSumMatchesThePlainSum) {
    ReferenceTable t;
    t.n_theta = 9;
    t.n_phi = 19;
    t.dtheta_deg = 10;
    t.dphi_deg = 360.0 / 19;
    t.theta_i_deg = {0, 30, 60, 85};
    const size_t nb = size_t(t.n_theta) * t.n_phi;
    uint32_t state = 12345;
    auto rnd = [&] { return float((state = state * 1664525u + 1013904223u) >> 8) / float(1 << 24); };
    for (int h = 0; h < 2; ++h)
        for (size_t k = 0; k < t.theta_i_deg.size(); ++k) {
            std::vector<glm::vec3> f(nb);
            for (auto& v : f) v = glm::vec3(rnd(), rnd(), rnd());
            t.half[h].push_back(f);
        }
    Environment env;
    env.width = 64;
    env.height = 32;
    env.texels.resize(size_t(env.width) * env.height);
    for (auto& v : env.texels) v = glm::vec3(rnd(), rnd(), rnd()) * 4.0f;
    const uint32_t size = 24;
    const ReferenceRender r = render_reference(t, env, size, 2);
    // the plain sum
    const Environment fe = box_filtered(env, r.env_filter[0], r.env_filter[1]);
    const double deg = M_PI / 180;
    double worst = 0;
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            vec3 n;
            if (!sphere_normal(x, y, size, n)) continue;
            const glm::vec3 nn(n.x, n.y, n.z);
            glm::vec3 t1(-n.x * n.z, -n.y * n.z, 1 - n.z * n.z);
            const float tl = glm::length(t1);
            t1 = tl > 1e-6f ? t1 / tl : glm::vec3(1, 0, 0);
            const glm::vec3 t2 = glm::cross(nn, t1);
            const double tv = std::acos(std::clamp(double(n.z), -1.0, 1.0)) / deg;
            const auto& a = t.theta_i_deg;
            size_t k1 = std::upper_bound(a.begin(), a.end(), tv) - a.begin();
            size_t k0 = k1 == 0 ? 0 : k1 - 1;
            if (k1 >= a.size()) k1 = a.size() - 1;
            const float u = k0 == k1 ? 0.0f : float(std::clamp((tv - a[k0]) / (a[k1] - a[k0]), 0.0, 1.0));
            glm::dvec3 sum[2] = {glm::dvec3(0), glm::dvec3(0)};
            for (uint32_t i = 0; i < t.n_theta; ++i) {
                const double lo = i * t.dtheta_deg * deg, hi = std::min(90.0, (i + 1) * t.dtheta_deg) * deg;
                const double s2lo = std::sin(lo) * std::sin(lo), s2hi = std::sin(hi) * std::sin(hi);
                const double th = std::asin(std::sqrt(0.5 * (s2lo + s2hi)));
                for (uint32_t j = 0; j < t.n_phi; ++j) {
                    const size_t b = size_t(i) * t.n_phi + j;
                    const float omega = float(0.5 * (s2hi - s2lo) * t.dphi_deg * deg);
                    const double ph = j * t.dphi_deg * deg;
                    const glm::vec3 d(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
                    const glm::vec3 L = environment_bilinear(fe, d.x * t1 + d.y * t2 + d.z * nn) * omega;
                    for (int h = 0; h < 2; ++h)
                        sum[h] += glm::dvec3(((1 - u) * t.half[h][k0][b] + u * t.half[h][k1][b]) * L);
                }
            }
            const size_t p = size_t(y) * size + x;
            for (int h = 0; h < 2; ++h)
                for (int c = 0; c < 3; ++c)
                    worst = std::max(worst, std::fabs(r.half[h].rgba[p][c] - sum[h][c]) / sum[h][c]);
        }
    std::printf("reference: vectorised against plain sum, worst relative difference %.2e\n", worst);
    EXPECT_LT(worst, 1e-5);
}

TEST(RenderEnvironment, NamedMapsLoadAndNegativeTexelsAreClamped) {
    EXPECT_THROW(load_environment("no-such-map"), std::invalid_argument);
    try {
        load_environment("no-such-map");
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("forest"), std::string::npos) << "the valid names are listed";
    }
    EXPECT_THROW(load_environment("/no/such/file.exr"), std::invalid_argument);
    const Environment f = load_environment("furnace");
    EXPECT_EQ(f.texels.front(), glm::vec3(1.0f));
    const Environment st = load_environment("studio");
    EXPECT_EQ(st.negative_texels, 0u);
    if (!std::filesystem::is_directory(kBlenderWorldDir))
        GTEST_SKIP() << kBlenderWorldDir << " is missing (blender-data)";
    uint64_t negative = 0;
    for (const std::string& name : blender_environment_names()) {
        if (name == "studio") continue;   // --env studio is the procedural one
        const Environment e = load_environment(name);
        EXPECT_EQ(e.width, 1024u) << name;
        EXPECT_EQ(e.height, 512u) << name;
        for (const glm::vec3& t : e.texels) ASSERT_TRUE(t.x >= 0 && t.y >= 0 && t.z >= 0) << name;
        negative += e.negative_texels;
        std::printf("%s: %llu negative texels clamped (down to %.3g)\n", name.c_str(),
                    (unsigned long long)e.negative_texels, e.most_negative);
    }
    EXPECT_GT(negative, 0u) << "the DWAB maps have a few negative texels";
}

TEST(RenderEnvironment, CdfIsMonotoneAndEndsAtOne) {
    const Environment e = load_environment("studio");
    bool sampled = false;
    const std::vector<float> cdf = environment_cdf(e, &sampled);
    EXPECT_TRUE(sampled);
    environment_cdf(load_environment("furnace"), &sampled);
    EXPECT_FALSE(sampled) << "MIS compensation leaves nothing to sample in a constant map";
    ASSERT_EQ(cdf.size(), e.height + size_t(e.width) * e.height);
    EXPECT_EQ(cdf[e.height - 1], 1.0f);
    for (uint32_t j = 1; j < e.height; ++j) EXPECT_GE(cdf[j], cdf[j - 1]);
    for (uint32_t j = 0; j < e.height; ++j) EXPECT_EQ(cdf[e.height + size_t(j) * e.width + e.width - 1], 1.0f);
}

// render --spectral's white (host/render/spectral_sphere.h): a perfect white diffuser under uniform radiance 1
// reflects radiance 1 at every pixel, whatever the view angle.
TEST(SpectralSphere, WhiteDiffuserUnderTheFurnaceIsOne) {
    ReferenceTable t;
    t.n_theta = 90;
    t.n_phi = 180;
    t.theta_i_deg = {0, 40, 80};
    for (auto& half : t.half) half.assign(3, std::vector<glm::vec3>(90 * 180, glm::vec3(0.3f, 0.2f, 0.1f)));
    const ReferenceRender r = render_reference(white_diffuser_table(t), load_environment("furnace"), 24, 2);
    size_t on = 0;
    for (const glm::vec4& p : r.image.rgba) {
        if (!(p.w > 0)) continue;
        ++on;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], 1.0, 2e-3);
    }
    EXPECT_GT(on, 300u);
}

// The colour difference on the sphere: none between a render and itself; the same when the renders and the white
// are all scaled (a pixel is measured against the white there); pixels off the sphere or darker than 1% of the white
// do not count; the noise floor is half the halves' difference.
TEST(SpectralSphere, ColourErrorIsMeasuredAgainstTheWhiteAndItsHalves) {
    auto image = [](glm::vec3 rgb, float scale) {
        Image im;
        im.size = 2;
        im.rgba = {glm::vec4(rgb * scale, 1), glm::vec4(rgb * scale, 1), glm::vec4(rgb * scale * 0.001f, 1),
                   glm::vec4(rgb * scale, 0)};
        return im;
    };
    auto render = [&](glm::vec3 a, glm::vec3 b, float scale) {
        ReferenceRender r;
        r.half[0] = image(a, scale);
        r.half[1] = image(b, scale);
        r.image = image(0.5f * (a + b), scale);
        return r;
    };
    auto white = [](float scale) {
        Image im;
        im.size = 2;
        im.rgba.assign(4, glm::vec4(scale, scale, scale, 1));
        return im;
    };
    const glm::vec3 gold(0.6f, 0.45f, 0.15f), copper(0.6f, 0.3f, 0.2f);
    const SphereColourError same = sphere_colour_error(render(gold, gold, 1), render(gold, gold, 1), white(1));
    EXPECT_EQ(same.lit, 2u);   // the dark pixel and the one off the sphere left out
    EXPECT_EQ(same.max_de2000, 0.0);
    EXPECT_EQ(same.median_noise, 0.0);
    const SphereColourError e = sphere_colour_error(render(gold, gold, 1), render(copper, copper, 1), white(1));
    const SphereColourError scaled = sphere_colour_error(render(gold, gold, 7), render(copper, copper, 7), white(7));
    EXPECT_GT(e.median_de2000, 5.0);   // gold against copper: plainly different
    EXPECT_NEAR(scaled.median_de2000, e.median_de2000, 1e-4 * e.median_de2000);
    EXPECT_NEAR(scaled.median_de_itp, e.median_de_itp, 1e-4 * e.median_de_itp);
    // one render's halves apart by gold to copper, the other's equal: the floor is half that difference
    const SphereColourError halves = sphere_colour_error(render(gold, copper, 1), render(gold, gold, 1), white(1));
    const double d = delta_e_2000(xyz_to_lab(linear_srgb_to_xyz({gold.x, gold.y, gold.z})),
                                  xyz_to_lab(linear_srgb_to_xyz({copper.x, copper.y, copper.z})));
    EXPECT_NEAR(halves.median_noise, 0.5 * d, 1e-4 * d);
}
