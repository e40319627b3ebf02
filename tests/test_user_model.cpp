// A user's model file compiled at run time and integrated as a black box (host/models/user_model.h,
// ModelEvaluator; docs/MODELS.md "Your own model"):
//   * a rewrite of ww-corrected from the paper gives the built-in model's bins, though it is integrated as one term
//     with no plan (the built-in: two terms, each graded at its own lobe);
//   * the stack reaches the file as the stack file gives it (absolute indices, layers from the top);
//   * NaN, infinite and negative values are reported with where they are, never scored;
//   * a narrow lobe away from the mirror direction that nothing announces is found: its albedo is exact;
//   * a 1e-4 lobe away from the mirror direction that model_lobes announces is integrated bin by bin as one at the
//     mirror direction is (on both sides), and only with its hint; unusable hints are reported;
//   * a model whose own loops exceed lavapipe's loop limiter is integrated on fewer pieces, never cut short;
//   * a file that does not compile is refused with FILE:LINE;
//   * a built-in model with no plan is integrated the same way, from its own module;
//   * its reciprocity is measured at direction pairs, and a layer the stack lacks reads as NaN.
#include "exact.h"
#include "gpu_fixture.h"
#include "models.h"
#include "user_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

using namespace gonio;
using namespace gonio_test;

namespace {

class UserModels : public GpuTest {};

const std::string kDir = std::string(GONIO_SOURCE_DIR) + "/tests/user_models/";

ModelGrid default_grid(std::vector<double> angles) { return {90, 180, 1.0, 2.0, std::move(angles)}; }

double projected_omega(const ModelGrid& g, uint32_t t) {
    double lo = t * g.dtheta_deg * M_PI / 180, hi = std::min((t + 1) * g.dtheta_deg, 90.0) * M_PI / 180;
    return 0.5 * (std::pow(std::sin(hi), 2) - std::pow(std::sin(lo), 2)) * g.dphi_deg * M_PI / 180;
}

const ModelSlices& by_id(const std::vector<ModelSlices>& all, const std::string& id) {
    for (const auto& m : all)
        if (m.id == id) return m;
    throw std::runtime_error("no model " + id);
}

std::vector<ModelSlices> run(const Stack& s, const ModelGrid& g, const std::vector<std::string>& files,
                             std::vector<std::string> selected) {
    ModelOptions o;
    for (const auto& f : files) o.user_models.push_back(load_user_model(kDir + f));
    for (const auto& u : o.user_models) selected.push_back(u->header.id);
    o.selected = selected;
    return evaluate_models(context(), s, g, nullptr, o);
}

TEST_F(UserModels, RewriteOfWwCorrectedGivesTheBuiltInBins) {
    // the plastic stack of the seed (stacks/plastic.toml) and a rougher, more absorbing coat
    for (float alpha : {0.05f, 0.3f}) {
        Stack s = make_stack("coat", {dielectric(1.5f, alpha, {0.05f, 0.05f, 0.3f}), lambertian({0.2f, 0.6f, 0.3f})});
        ModelGrid g = default_grid({0, 30, 60, 80});
        auto all = run(s, g, {"ww_corrected_rewrite.glsl"}, {"ww-corrected"});
        const ModelSlices &a = by_id(all, "ww-corrected"), &b = by_id(all, "ww-corrected-rewrite");
        ASSERT_TRUE(model_has_bins(a)) << a.not_applicable << a.invalid;
        ASSERT_TRUE(model_has_bins(b)) << b.not_applicable << b.invalid;
        EXPECT_EQ(b.integration, "black box");
        double worst = 0, worst_albedo = 0;
        for (size_t i = 0; i < g.theta_i_deg.size(); ++i) {
            glm::dvec3 alb_a(0.0), alb_b(0.0);
            for (size_t bin = 0; bin < a.f[i].size(); ++bin) {
                const double om = projected_omega(g, uint32_t(bin / g.n_phi));
                alb_a += a.f[i][bin] * om;
                alb_b += b.f[i][bin] * om;
                for (int c = 0; c < 3; ++c) {
                    const double fa = a.f[i][bin][c], fb = b.f[i][bin][c];
                    // 1e-6 relative, plus the two integrations' own error estimates (the built-in's graded pieces
                    // and the black box's are not the same nodes) and float rounding of f
                    const double tol = 1e-6 * std::fabs(fa) + a.f_err[i][bin][c] + b.f_err[i][bin][c] + 1e-7;
                    worst = std::max(worst, std::fabs(fa - fb) / tol);
                }
            }
            // the albedos: within 1e-6 of it plus the bins' error estimates, summed over the hemisphere
            glm::dvec3 err(0.0);
            for (size_t bin = 0; bin < a.f[i].size(); ++bin)
                err += (a.f_err[i][bin] + b.f_err[i][bin]) * projected_omega(g, uint32_t(bin / g.n_phi));
            for (int c = 0; c < 3; ++c)
                worst_albedo =
                    std::max(worst_albedo, std::fabs(alb_a[c] - alb_b[c]) / (1e-6 * alb_a[c] + err[c] + 1e-7));
        }
        EXPECT_LE(worst, 1.0) << "alpha " << alpha;
        EXPECT_LE(worst_albedo, 1.0) << "alpha " << alpha;
        std::printf("alpha %g: largest |bin difference| / tolerance %.3g, albedo's %.2g\n", alpha, worst, worst_albedo);
    }
}

// A built-in model file with no plan (model_plan.cpp) is integrated as a black box, as a user's, from its own
// module (models_N_spv): ww-corrected so integrated gives its planned bins, within the same tolerance as its rewrite
TEST_F(UserModels, ABuiltInModelWithNoPlanIsIntegratedAsABlackBox) {
    for (float alpha : {0.05f, 0.3f}) {
        Stack s = make_stack("coat", {dielectric(1.5f, alpha, {0.05f, 0.05f, 0.3f}), lambertian({0.2f, 0.6f, 0.3f})});
        ModelGrid g = default_grid({0, 30, 60, 80});
        ModelOptions o;
        o.selected = {"ww-corrected"};
        const std::vector<ModelSlices> planned = evaluate_models(context(), s, g, nullptr, o);
        o.as_black_box = {"ww-corrected"};
        const std::vector<ModelSlices> boxed = evaluate_models(context(), s, g, nullptr, o);
        const ModelSlices &a = by_id(planned, "ww-corrected"), &b = by_id(boxed, "ww-corrected");
        ASSERT_TRUE(model_has_bins(a)) << a.not_applicable << a.invalid;
        ASSERT_TRUE(model_has_bins(b)) << b.not_applicable << b.invalid;
        EXPECT_EQ(a.integration, "planned");
        EXPECT_EQ(b.integration, "black box");
        double worst = 0;
        for (size_t i = 0; i < g.theta_i_deg.size(); ++i)
            for (size_t bin = 0; bin < a.f[i].size(); ++bin)
                for (int c = 0; c < 3; ++c) {
                    const double fa = a.f[i][bin][c], fb = b.f[i][bin][c];
                    const double tol = 1e-6 * std::fabs(fa) + a.f_err[i][bin][c] + b.f_err[i][bin][c] + 1e-7;
                    worst = std::max(worst, std::fabs(fa - fb) / tol);
                }
        EXPECT_LE(worst, 1.0) << "alpha " << alpha;
        std::printf("alpha %g: largest |bin difference| / tolerance %.3g\n", alpha, worst);
    }
}

TEST_F(UserModels, TheFileSeesTheStackAsItsFileGivesIt) {
    Layer mid = dielectric(1.8f, 0.2f, {0.1f, 0.2f, 0.4f});
    Stack s = make_stack("three",
                         {dielectric(1.5f, 0.1f), mid, conductor({0.2f, 0.9f, 1.1f}, {3.0f, 2.5f, 2.2f}, 0.3f)}, 1.2f);
    ModelGrid g = default_grid({0, 60});
    auto all = run(s, g, {"layer_values.glsl"}, {"ww09"});
    const ModelSlices& m = by_id(all, "layer-values");
    ASSERT_TRUE(model_has_bins(m)) << m.not_applicable << m.invalid;
    // layer 1 (the second): ior 1.8, layer count 3; layer 2 (the conductor): n.y 0.9, exterior 1.2; k.z 2.2, layer
    // 1's optical depth 0.4 and roughness 0.2
    // a constant's bin average is exact up to the quadrature's own error (the pieces mapped towards the mirror
    // direction are not polynomial in the rule's variable), which its error estimate bounds; a wrong accessor is off
    // by 0.1 or more; plus the float32 sums of a bin's nodes (up to 6400 of them)
    const glm::dvec3 want(1.8 + 30.0, 0.9 + 12.0, 2.2 + 4.0 + 20.0);
    double worst = 0;
    for (size_t i = 0; i < m.f.size(); ++i)
        for (size_t b = 0; b < m.f[i].size(); ++b)
            for (int c = 0; c < 3; ++c) {
                EXPECT_LE(std::fabs(m.f[i][b][c] - want[c]), m.f_err[i][b][c] + 3e-5 * want[c]) << i << " " << b;
                worst = std::max(worst, std::fabs(m.f[i][b][c] / want[c] - 1.0));
            }
    EXPECT_LT(worst, 1e-4);
    std::printf("largest relative departure from the constant: %.2g\n", worst);
}

TEST_F(UserModels, NanInfiniteAndNegativeValuesAreReportedWhereTheyAre) {
    Stack s = make_stack("coat", {dielectric(1.5f, 0.1f), lambertian({0.5f, 0.5f, 0.5f})});
    ModelGrid g = default_grid({30});
    auto all = run(s, g, {"nan_where_v_x_above_half.glsl"}, {"ww09"});
    const ModelSlices& m = by_id(all, "nan-test");
    EXPECT_FALSE(model_has_bins(m));
    EXPECT_NE(m.invalid.find("NaN, infinite or negative"), std::string::npos) << m.invalid;
    ASSERT_GT(m.invalid_bins.size(), 0u);
    // every bin reported holds a direction with v.x > 0.5 or v.y > 0.8 (its corners bound it: v.x = sin cos phi),
    // and every bin wholly inside those regions is reported
    size_t inside = 0, reported_inside = 0;
    std::vector<bool> reported(g.n_theta * g.n_phi, false);
    for (const auto& r : m.invalid_bins) reported[r.bin] = true;
    for (uint32_t t = 0; t < g.n_theta; ++t)
        for (uint32_t p = 0; p < g.n_phi; ++p) {
            double best_x = -2, best_y = -2, worst_x = 2, worst_y = 2;
            for (double th : {t * 1.0, t + 1.0})
                for (double ph : {p * 2.0 - 1.0, p * 2.0 + 1.0, p * 2.0}) {
                    const double st = std::sin(th * M_PI / 180), x = st * std::cos(ph * M_PI / 180),
                                 y = st * std::sin(ph * M_PI / 180);
                    best_x = std::max(best_x, x);
                    best_y = std::max(best_y, y);
                    worst_x = std::min(worst_x, x);
                    worst_y = std::min(worst_y, y);
                }
            const bool can = best_x > 0.5 - 0.02 || best_y > 0.8 - 0.02, must = worst_x > 0.5 || worst_y > 0.8;
            if (reported[size_t(t) * g.n_phi + p]) { EXPECT_TRUE(can) << "bin " << t << "," << p; }
            if (must) {
                ++inside;
                reported_inside += reported[size_t(t) * g.n_phi + p];
            }
        }
    EXPECT_GT(inside, 1000u);
    EXPECT_EQ(reported_inside, inside);
}

TEST_F(UserModels, AnUnannouncedNarrowLobeIsFound) {
    // a retroreflection lobe 0.57 degrees wide about l, whose albedo is 0.5 (tests/user_models/retro_lobe.glsl)
    Stack s = make_stack("coat", {dielectric(1.5f, 0.3f), lambertian({0.5f, 0.5f, 0.5f})});
    ModelGrid g = default_grid({30, 55});
    auto all = run(s, g, {"retro_lobe.glsl"}, {"ww09"});
    const ModelSlices& m = by_id(all, "retro-lobe");
    ASSERT_TRUE(model_has_bins(m)) << m.invalid;
    EXPECT_GT(m.refined_bins, 0u);
    const double sigma2 = 1e-4, exact = 0.5 * (1.0 - std::exp(-2.0 / sigma2));
    for (size_t i = 0; i < g.theta_i_deg.size(); ++i) {
        double albedo = 0, err = 0;
        for (size_t bin = 0; bin < m.f[i].size(); ++bin) {
            const double om = projected_omega(g, uint32_t(bin / g.n_phi));
            albedo += m.f[i][bin].x * om;
            err += m.f_err[i][bin].x * om;
        }
        EXPECT_NEAR(albedo, exact, 1e-4) << "theta_i " << g.theta_i_deg[i];
        // the error estimate bounds the error, up to the float sums of each bin's nodes (1e-5 of the albedo)
        EXPECT_LE(std::fabs(albedo - exact), err + 1e-5 * exact);
        std::printf("theta_i %g: albedo %.7f (exact %.7f), estimated error %.2g, refined bins %u\n", g.theta_i_deg[i],
                    albedo, exact, err, m.refined_bins);
    }
}

std::string read_text(const std::string& path) {
    std::ifstream f(path);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}
// `text` with `from` replaced by `to` (which must be there)
std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    if (at == std::string::npos) throw std::runtime_error("no '" + from + "' in the model file");
    return text.replace(at, from.size(), to);
}

// tests/user_models/narrow_lobe_hinted.glsl with its lobe's centre, id, and hints as given
std::shared_ptr<const UserModel> narrow_lobe(const std::string& id, const std::string& centre, bool hints,
                                             const std::string& hint_body = "") {
    std::string t = read_text(kDir + "narrow_lobe_hinted.glsl");
    t = replaced(t, "gonio-model: narrow-lobe", "gonio-model: " + id);
    t = replaced(t, "vec3 lobe_centre(vec3 l) { return l; }", "vec3 lobe_centre(vec3 l) { return " + centre + "; }");
    if (!hints) t = t.substr(0, t.find("uint model_lobes("));
    if (!hint_body.empty())
        t = replaced(t, "lobes[0] = GonioLobe(lobe_centre(l), 1e-4, vec3(0.0));\n    return 1u;", hint_body);
    return compile_user_model(t, "/tmp/" + id + ".glsl");
}

// A lobe 2e-4 wide (tests/user_models/narrow_lobe_hinted.glsl) away from the mirror direction, over a smooth coat
// (the black box's attractor: the mirror direction at 1e-4). Announced by model_lobes it is integrated as the same
// lobe turned by pi in phi onto the mirror direction is, bin for bin (its bins are those bins 180 degrees away; the
// grid's 2-degree bins are centred on 0 and 180); unannounced it is not. The same on the transmission side of a
// slab, the lobe at l mirrored through the surface against the one straight through (-l).
TEST_F(UserModels, AnnouncedLobesAreIntegratedAsTheMirrorLobeIs) {
    struct Case {
        const char* name;
        Stack stack;
        int side;
        std::string off, on;   // the lobe's centre: away from the attractor, on it
    };
    const std::vector<Case> cases = {
        {"reflection", make_stack("coat", {dielectric(1.5f, 0.0f), lambertian({0.5f, 0.5f, 0.5f})}), 0, "l",
         "vec3(-l.x, -l.y, l.z)"},
        {"transmission", make_stack("slab", {dielectric(1.5f, 0.0f), dielectric(1.0f, 0.0f)}), 1,
         "vec3(l.x, l.y, -l.z)", "-l"},
    };
    const ModelGrid g = default_grid({30, 55});
    for (const Case& c : cases) {
        ModelOptions o;
        o.user_models = {narrow_lobe("hinted", c.off, true), narrow_lobe("unhinted", c.off, false),
                         narrow_lobe("at-attractor", c.on, false)};
        o.selected = {"hinted", "unhinted", "at-attractor"};
        const auto all = evaluate_models(context(), c.stack, g, nullptr, o);
        const ModelSlices &h = by_id(all, "hinted"), &u = by_id(all, "unhinted"), &m = by_id(all, "at-attractor");
        for (const ModelSlices* x : {&h, &u, &m}) ASSERT_TRUE(model_has_bins(*x)) << x->id << ": " << x->invalid;
        EXPECT_EQ(h.integration, "black box with lobe hints");
        EXPECT_EQ(u.integration, "black box");
        const auto& hs = c.side ? h.t : h.f;
        const auto& us = c.side ? u.t : u.f;
        const auto& ms = c.side ? m.t : m.f;
        const auto& he = c.side ? h.t_err : h.f_err;
        const auto& me = c.side ? m.t_err : m.f_err;
        for (size_t i = 0; i < g.theta_i_deg.size(); ++i) {
            double worst_h = 0, worst_u = 0, albedo_h = 0, albedo_m = 0;
            for (uint32_t t = 0; t < g.n_theta; ++t)
                for (uint32_t p = 0; p < g.n_phi; ++p) {
                    const size_t b = size_t(t) * g.n_phi + p,
                                 turned = size_t(t) * g.n_phi + (p + g.n_phi / 2) % g.n_phi;
                    const double ref = ms[i][turned].x;
                    // 1e-5 of the value (float sums of f about 4e6 at the peak) and the two integrations' estimates
                    const double tol = 1e-5 * std::fabs(ref) + he[i][b].x + me[i][turned].x + 1e-7;
                    worst_h = std::max(worst_h, std::fabs(hs[i][b].x - ref) / tol);
                    worst_u = std::max(worst_u, std::fabs(us[i][b].x - ref) / tol);
                    albedo_h += hs[i][b].x * projected_omega(g, t);
                    albedo_m += ms[i][turned].x * projected_omega(g, t);
                }
            EXPECT_LE(worst_h, 1.0) << c.name << " theta_i " << g.theta_i_deg[i];
            // without its hint the lobe is missed or misplaced: far outside the same tolerance
            EXPECT_GT(worst_u, 10.0) << c.name << " theta_i " << g.theta_i_deg[i];
            // and the announced lobe's albedo is the closed form's (0.5 less the tails below the horizon, < 1e-7)
            EXPECT_NEAR(albedo_h, 0.5, 2e-5) << c.name << " theta_i " << g.theta_i_deg[i];
            std::printf(
                "%s theta_i %g: largest |bin - turned mirror lobe's| / tolerance: hinted %.3g, unhinted %.3g; "
                "albedo hinted %.7f, at the attractor %.7f\n",
                c.name, g.theta_i_deg[i], worst_h, worst_u, albedo_h, albedo_m);
        }
    }
}

TEST_F(UserModels, UnusableLobeHintsAreReported) {
    Stack s = make_stack("coat", {dielectric(1.5f, 0.0f), lambertian({0.5f, 0.5f, 0.5f})});
    const ModelGrid g = default_grid({30});
    const std::vector<std::pair<std::string, std::string>> bad = {
        {"negative-roughness", "lobes[0] = GonioLobe(l, -1e-3, vec3(0.0));\n    return 1u;"},
        {"zero-direction", "lobes[0] = GonioLobe(vec3(0.0), 1e-3, vec3(0.0));\n    return 1u;"},
        {"nine-lobes",
         "for (uint k = 0u; k < GONIO_MAX_LOBES; ++k) lobes[k] = GonioLobe(l, 1e-3, vec3(0.0));\n    return 9u;"},
    };
    for (const auto& [id, body] : bad) {
        ModelOptions o;
        o.user_models = {narrow_lobe(id, "l", true, body)};
        o.selected = {id};
        const auto all = evaluate_models(context(), s, g, nullptr, o);
        const ModelSlices& m = by_id(all, id);
        EXPECT_FALSE(model_has_bins(m)) << id;
        EXPECT_NE(m.invalid.find("model_lobes gave an unusable lobe"), std::string::npos) << id << ": " << m.invalid;
        EXPECT_NE(m.invalid.find("theta_i 30 R"), std::string::npos) << id << ": " << m.invalid;
    }
}

// Beyond float's resolution in v (2 alpha cos theta < 2e-5, model_plan.h kFloatUnresolved) a black box's quadrature
// fails (ww-corrected's rewrite on a smooth coat: albedo 0.244 against the planned 0.990 at 89.9 degrees, measured):
// the model is refused there, whether the lobe is announced or assumed (the stack's narrowest interface); a model
// that announces only wide lobes is not.
TEST_F(UserModels, LobesNarrowerThanFloatResolvesAreRefused) {
    Stack s = make_stack("coat", {dielectric(1.5f, 0.0f), lambertian({0.5f, 0.5f, 0.5f})});
    const ModelGrid g = default_grid({30, 89.5});
    ModelOptions o;
    o.user_models = {narrow_lobe("announced", "l", true), narrow_lobe("assumed", "l", false),
                     narrow_lobe("wide", "l", true, "lobes[0] = GonioLobe(l, 0.3, vec3(0.0));\n    return 1u;")};
    o.selected = {"announced", "assumed", "wide"};
    const auto all = evaluate_models(context(), s, g, nullptr, o);
    for (const char* id : {"announced", "assumed"}) {
        const ModelSlices& m = by_id(all, id);
        EXPECT_FALSE(model_has_bins(m)) << id;
        ASSERT_EQ(m.float_unresolved.size(), 1u) << id;
        EXPECT_EQ(m.float_unresolved[0].angle, 1u) << id;
        EXPECT_NE(m.invalid.find("narrower in v than float resolves"), std::string::npos) << id << ": " << m.invalid;
        EXPECT_NE(m.invalid.find("theta_i 89.5 R"), std::string::npos) << id << ": " << m.invalid;
    }
    const ModelSlices& w = by_id(all, "wide");
    EXPECT_TRUE(w.float_unresolved.empty()) << w.invalid;
}

// A delta lobe announced by model_lobes (roughness 0, its weight) and left out of model_f goes whole into the bin of
// its direction, the same bin the built-in models book their deltas in, at any incident angle (no quadrature: no
// float limit). tests/user_models/ww_corrected_delta.glsl: ww-corrected with a smooth coat's reflection as the delta
// it is, weight F(cos theta_i); its variant with no lobes (return 0u) is the same model without the delta.
TEST_F(UserModels, AnnouncedDeltaLobesAreBookedInTheBinOfTheirDirection) {
    Stack s = make_stack("coat", {dielectric(1.5f, 0.0f, {0.05f, 0.05f, 0.3f}), lambertian({0.2f, 0.6f, 0.3f})});
    const ModelGrid g = default_grid({0, 30, 60, 89, 89.9});
    const std::string text = read_text(kDir + "ww_corrected_delta.glsl");
    std::string no_delta = replaced(text, "gonio-model: ww-corrected-delta", "gonio-model: no-delta");
    no_delta = replaced(no_delta, "    return 1u;", "    return 0u;");
    ModelOptions o;
    o.user_models = {compile_user_model(text, kDir + "ww_corrected_delta.glsl"),
                     compile_user_model(no_delta, "/tmp/no-delta.glsl")};
    o.selected = {"ww-corrected", "ww-corrected-delta", "no-delta"};
    const auto all = evaluate_models(context(), s, g, nullptr, o);
    const ModelSlices &w = by_id(all, "ww-corrected"), &d = by_id(all, "ww-corrected-delta"),
                      &n = by_id(all, "no-delta");
    for (const ModelSlices* x : {&w, &d, &n}) ASSERT_TRUE(model_has_bins(*x)) << x->id << ": " << x->invalid;
    EXPECT_EQ(d.integration, "black box with lobe hints");
    for (size_t i = 0; i < g.theta_i_deg.size(); ++i) {
        const double ct = std::cos(g.theta_i_deg[i] * M_PI / 180), F = exact::fresnel(ct, 1.0, 1.5);
        // the built-in's delta bin: where it exceeds the model without the delta by half the delta's bin average
        size_t wbin = SIZE_MAX, dbin = SIZE_MAX;
        double worst_rest = 0;
        for (size_t b = 0; b < w.f[i].size(); ++b) {
            const double om = projected_omega(g, uint32_t(b / g.n_phi));
            if (w.f[i][b].x - n.f[i][b].x > 0.5 * F / om) wbin = b;
            if (d.f[i][b].x != n.f[i][b].x) {
                EXPECT_EQ(dbin, SIZE_MAX) << "a second bin changed by the delta, theta_i " << g.theta_i_deg[i];
                dbin = b;
            }
        }
        ASSERT_NE(dbin, SIZE_MAX) << "theta_i " << g.theta_i_deg[i];
        EXPECT_EQ(dbin, wbin) << "theta_i " << g.theta_i_deg[i];
        // its weight, whole: F(cos theta_i) over the bin's projected solid angle (float: 1e-6 of it)
        const double om = projected_omega(g, uint32_t(dbin / g.n_phi));
        const double mass = (d.f[i][dbin].x - n.f[i][dbin].x) * om;
        EXPECT_NEAR(mass, F, 1e-6 * F) << "theta_i " << g.theta_i_deg[i];
        // every other bin is the built-in model's (the same base term), within 1e-6 plus the error estimates
        for (size_t b = 0; b < w.f[i].size(); ++b) {
            if (b == dbin) continue;
            for (int c = 0; c < 3; ++c) {
                const double fw = w.f[i][b][c], fd = d.f[i][b][c];
                const double tol = 1e-6 * std::fabs(fw) + w.f_err[i][b][c] + d.f_err[i][b][c] + 1e-7;
                worst_rest = std::max(worst_rest, std::fabs(fw - fd) / tol);
            }
        }
        EXPECT_LE(worst_rest, 1.0) << "theta_i " << g.theta_i_deg[i];
        const double builtin_mass = (w.f[i][wbin].x - n.f[i][wbin].x) * om;
        std::printf(
            "theta_i %g: delta booked in bin %zu (the built-in's %zu), weight %.7f (F %.7f; the built-in's "
            "GGX 1e-4 lobe %.7f); other bins / tolerance %.3g\n",
            g.theta_i_deg[i], dbin, wbin, mass, F, builtin_mass, worst_rest);
    }
}

TEST_F(UserModels, LongLoopsInTheModelAreNeverCutShort) {
    Stack s = make_stack("coat", {dielectric(1.5f, 0.1f), lambertian({0.5f, 0.5f, 0.5f})});
    ModelGrid g = default_grid({0, 45});
    auto all = run(s, g, {"heavy_loop.glsl"}, {"ww09"});
    const ModelSlices& m = by_id(all, "heavy-loop");
    ASSERT_TRUE(model_has_bins(m)) << m.invalid;
    for (const auto& slice : m.f)
        for (const auto& f : slice) ASSERT_NEAR(f.x, 1.0 / M_PI, 1e-4);
}

TEST_F(UserModels, AnEvaluatorKeepsAUserModelAcrossGrids) {
    // the viewer, sweeps and bench keep one evaluator: a larger grid reallocates the buffers every kernel binds
    Stack s = make_stack("coat", {dielectric(1.5f, 0.2f), lambertian({0.5f, 0.4f, 0.3f})});
    ModelOptions o;
    o.user_models.push_back(load_user_model(kDir + "ww_corrected_rewrite.glsl"));
    o.selected = {"ww-corrected-rewrite"};
    ModelEvaluator ev(context());
    ev.evaluate(s, {3, 6, 30.0, 60.0, {40}}, nullptr, o);
    const ModelGrid g = default_grid({40});
    auto kept = ev.evaluate(s, g, nullptr, o);
    auto fresh = evaluate_models(context(), s, g, nullptr, o);
    const ModelSlices &a = by_id(kept, "ww-corrected-rewrite"), &b = by_id(fresh, "ww-corrected-rewrite");
    ASSERT_TRUE(model_has_bins(a) && model_has_bins(b));
    EXPECT_EQ(a.f, b.f);
}

TEST_F(UserModels, ABrokenFileIsRefusedWithItsLine) {
    try {
        load_user_model(kDir + "broken.glsl");
        FAIL() << "compiled";
    } catch (const std::invalid_argument& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(kDir + "broken.glsl:8:"), std::string::npos) << msg;
        EXPECT_NE(msg.find("undeclared_thing"), std::string::npos) << msg;
    }
    // a built-in model's id is refused
    try {
        compile_user_model(
            "// gonio-model: ww09\n// citation: x\n// represents: any\n// reciprocal: yes\n"
            "// energy-conserving: yes\nvec3 model_f(vec3 l, vec3 v) { return vec3(0.0); }\n",
            "/tmp/ww09.glsl");
        FAIL() << "compiled";
    } catch (const StackError& e) { EXPECT_NE(std::string(e.what()).find("built-in"), std::string::npos) << e.what(); }
}

}   // namespace

namespace {

// gonio measures a user's model's reciprocity at direction pairs (models.comp KERNEL 3, model_reciprocity.h): a
// reciprocal model (the example schlick-coat) is reciprocal within float; a model with a header of its id alone that
// scales the base by the coat's transmission on the light's side only, 1 - F(l.z), is measured as asymmetric by
// exactly max 2 |T(a) - T(b)| / (T(a) + T(b)) over the pairs' polar angles, computed here in double. Neither claim is
// made up for the header that says nothing.
TEST_F(UserModels, ReciprocityIsMeasuredAtDirectionPairs) {
    const Stack s = make_stack("coat", {dielectric(1.5f, 0.2f, {0.05f, 0.05f, 0.3f}), lambertian({0.2f, 0.6f, 0.3f})});
    ModelOptions o;
    o.user_models.push_back(load_user_model(std::string(GONIO_SOURCE_DIR) + "/examples/user_model.glsl"));
    o.user_models.push_back(load_user_model(kDir + "id_only.glsl"));
    o.selected = {"schlick-coat", "one-sided-fresnel"};
    const auto all = evaluate_models(context(), s, ModelGrid{18, 36, 5.0, 10.0, {30}}, nullptr, o);
    const ModelSlices &rec = by_id(all, "schlick-coat"), &one = by_id(all, "one-sided-fresnel");
    EXPECT_EQ(rec.reciprocity.pairs, 196u);
    EXPECT_EQ(rec.reciprocity.non_finite, 0u);
    EXPECT_TRUE(rec.reciprocity.reciprocal()) << rec.reciprocity.worst;
    EXPECT_EQ(rec.claims_reciprocal, 1);
    EXPECT_EQ(rec.claims_energy_conserving, 0);
    EXPECT_EQ(one.claims_reciprocal, -1);
    EXPECT_EQ(one.claims_energy_conserving, -1);
    double want = 0, want_a = 0, want_b = 0;
    for (double a : {5.0, 20.0, 35.0, 50.0, 65.0, 80.0, 88.0})
        for (double b : {5.0, 20.0, 35.0, 50.0, 65.0, 80.0, 88.0}) {
            const double ta = 1 - exact::fresnel(std::cos(a * M_PI / 180), 1.0, 1.5);
            const double tb = 1 - exact::fresnel(std::cos(b * M_PI / 180), 1.0, 1.5);
            const double r = 2 * std::fabs(ta - tb) / (ta + tb);
            if (r > want) want = r, want_a = a, want_b = b;
        }
    std::printf("one-sided-fresnel: measured asymmetry %.6f at %g, %g; in double %.6f at %g, %g\n",
                one.reciprocity.worst, one.reciprocity.theta_l, one.reciprocity.theta_v, want, want_a, want_b);
    EXPECT_EQ(one.reciprocity.pairs, 196u);
    EXPECT_FALSE(one.reciprocity.reciprocal());
    EXPECT_NEAR(one.reciprocity.worst, want, 1e-4 * want);
    EXPECT_EQ(std::min(one.reciprocity.theta_l, one.reciprocity.theta_v), std::min(want_a, want_b));
    EXPECT_EQ(std::max(one.reciprocity.theta_l, one.reciprocity.theta_v), std::max(want_a, want_b));
}

// A file without `represents:` runs on every stack; a layer the stack does not have reads as NaN, which is reported
// (never values from beyond the stack).
TEST_F(UserModels, ALayerBeyondTheStackIsNan) {
    const Stack bare = make_stack("bare", {dielectric(1.5f, 0.2f), lambertian({0.5f, 0.5f, 0.5f})});
    auto m = compile_user_model(
        "// gonio-model: beyond\nvec3 model_f(vec3 l, vec3 v) { return gonio_layer(2u).albedo + vec3(0.1); }\n",
        "beyond.glsl");
    ModelOptions o;
    o.user_models.push_back(m);
    o.selected = {"beyond"};
    const auto all = evaluate_models(context(), bare, ModelGrid{18, 36, 5.0, 10.0, {30}}, nullptr, o);
    const ModelSlices& b = by_id(all, "beyond");
    EXPECT_EQ(b.not_applicable, "");
    std::set<uint32_t> bins;   // every bin (each level of the black box's refinement books its own)
    for (const auto& r : b.invalid_bins) bins.insert(r.bin);
    EXPECT_EQ(bins.size(), size_t(18 * 36));
    EXPECT_NE(b.invalid.find("gonio_layer(i) is all NaN for a layer the stack does not have"), std::string::npos)
        << b.invalid;
}

}   // namespace
