// The analytic models on the reference's bins: exact limits, bin integration against an independent
// quadrature of the same model, energy, finiteness, and stacks a model cannot represent.
#include "model_twin_on_stack.h"
#include "exact.h"
#include "gpu_fixture.h"
#include "materialx_fit.h"
#include "models.h"
#include "model_file.h"
#include "model_quadrature.h"
#include "stack_gpu.h"
#include "stack_tables.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <functional>

using namespace gonio;
using namespace gonio_test;

namespace {

class Models : public GpuTest {};

size_t model_index(const std::string& id) {
    for (size_t i = 0; i < model_registry().size(); ++i)
        if (model_registry()[i].id == id) return i;
    throw std::runtime_error("no model " + id);
}

// The model a registry variant belongs to ("belcour18-forward+g2" -> "belcour18-forward").
std::string base_id(const std::string& id) { return id.substr(0, id.find('+')); }

ModelGrid default_grid(std::vector<double> angles) { return {90, 180, 1.0, 2.0, std::move(angles)}; }

double omega(const ModelGrid& g, uint32_t t) {
    double lo = t * g.dtheta_deg * M_PI / 180, hi = (t + 1) * g.dtheta_deg * M_PI / 180;
    return 0.5 * (std::pow(std::sin(hi), 2) - std::pow(std::sin(lo), 2)) * g.dphi_deg * M_PI / 180;
}

// Directional albedo of a model by quadrature (model_quadrature.h), fine enough for the 1e-3 bin-sum test.
glm::dvec3 albedo_quadrature(size_t model, const Stack& s, double theta_i_deg, double a) {
    return albedo_by_quadrature(model, s, theta_i_deg, a, false, 4000, 720);
}

// The directions the formula tests compare a model at: l at theta_i = 0, 35, 70, 85 degrees (in the x-z plane) and v
// at theta_o = 10, 40, 75 degrees or (at_table_nodes) at mu_v = i / 64 for the coat-albedo table's nodes i = 16, 40, 64,
// where the table is read without interpolation; v at azimuths 0, 60, 180 degrees
struct FormulaDirection {
    exact::V3 l, v;
    double theta_i, theta_o, phi;
    uint32_t node;   // the table node of mu_v (at_table_nodes), else 0
};
std::vector<FormulaDirection> formula_directions(bool at_table_nodes = false) {
    std::vector<FormulaDirection> out;
    for (double ti : {0.0, 35.0, 70.0, 85.0})
        for (int k = 0; k < 3; ++k)
            for (double phi : {0.0, 60.0, 180.0}) {
                const uint32_t node = at_table_nodes ? std::array<uint32_t, 3>{16, 40, 64}[k] : 0u;
                const double to =
                    at_table_nodes ? std::acos(node / 64.0) * 180 / M_PI : std::array{10.0, 40.0, 75.0}[k];
                const double mu_v = at_table_nodes ? node / 64.0 : std::cos(to * M_PI / 180);
                const double a = ti * M_PI / 180, p = phi * M_PI / 180, sv = std::sqrt(1 - mu_v * mu_v);
                out.push_back(
                    {{std::sin(a), 0, std::cos(a)}, {sv * std::cos(p), sv * std::sin(p), mu_v}, ti, to, phi, node});
            }
    return out;
}

// Model m's value (the CPU twin) at a formula direction, in float as the shader takes it
glm::dvec3 model_at(size_t m, const Stack& s, const FormulaDirection& d) {
    return model_value_cpu(m, s, glm::vec3(float(d.l.x), 0.0f, float(d.l.z)),
                           glm::vec3(float(d.v.x), float(d.v.y), float(d.v.z)));
}

// ww-corrected on a smooth coat over a Lambertian base is the single-scattering part of the exact answer:
// F(theta_i) in the mirror bin plus (1-F(i)) e^(-tau/mu_i) rho/pi e^(-tau/mu_o) (1-F(o)) / n^2.
TEST_F(Models, WwCorrectedIsTheSingleScatteringOfASmoothCoat) {
    const glm::vec3 tau(0.0f, 0.3f, 1.0f), rho(0.9f, 0.5f, 0.7f);
    const double n = 1.5;
    Stack s = make_stack("coat-lambert", {dielectric(float(n), 0.0f, tau), lambertian(rho)});
    ModelGrid g = default_grid({30.5, 70.5});
    auto all = evaluate_models(context(), s, g);
    const auto& m = all[model_index("ww-corrected")];
    ASSERT_TRUE(m.not_applicable.empty()) << m.not_applicable;
    double worst = 0;
    for (size_t a = 0; a < g.theta_i_deg.size(); ++a) {
        double ci = std::cos(g.theta_i_deg[a] * M_PI / 180);
        uint32_t mt = uint32_t(g.theta_i_deg[a]), mp = 90;
        for (uint32_t t = 0; t < g.n_theta; ++t) {
            for (int c = 0; c < 3; ++c) {
                exact::CoatLambert ex(1.0, n, tau[c], 0.0);   // rho = 0: no internal reflections
                double lo = t * M_PI / 180, hi = (t + 1) * M_PI / 180, acc = 0;
                const int K = 64;
                for (int k = 0; k < K; ++k) {
                    double th = lo + (k + 0.5) * (hi - lo) / K, co = std::cos(th);
                    double fd = (1 - exact::fresnel(ci, 1.0, n)) * std::exp(-tau[c] / exact::snell_cos(ci, 1.0, n)) *
                                rho[c] / M_PI * std::exp(-tau[c] / exact::snell_cos(co, 1.0, n)) *
                                (1 - exact::fresnel(co, 1.0, n)) / (n * n);
                    acc += fd * co * std::sin(th);
                }
                double fd_bin = acc * (hi - lo) / K * (2 * M_PI / 180) / omega(g, t);
                for (uint32_t p = 0; p < g.n_phi; ++p) {
                    double want = fd_bin + ((t == mt && p == mp) ? ex.specular(ci) / omega(g, t) : 0.0);
                    double got = m.f[a][size_t(t) * g.n_phi + p][c];
                    double rel = std::fabs(got - want) / want;
                    worst = std::max(worst, rel);
                    ASSERT_LT(rel, 2e-3) << "theta_i " << g.theta_i_deg[a] << " bin (" << t << "," << p << ") channel "
                                         << c << ": model " << got << ", exact " << want;
                }
            }
        }
    }
    std::printf("ww-corrected vs single-scattering closed form: worst relative error %.2e\n", worst);
}

// The albedo-scaling model's coat table: E(mu) of a nearly smooth coat is the Fresnel reflectance, and of a
// rough one at normal incidence what the rough-interface BSDF of tests/exact.h integrates to.
TEST(ModelsTables, CoatAlbedoTable) {
    Stack smooth = make_stack("smooth", {dielectric(1.5f, 1e-3f), lambertian(glm::vec3(0.5f))});
    auto t = coat_albedo_table(smooth);
    ASSERT_EQ(t.size(), size_t(COAT_ALBEDO_NODES));
    for (uint i = 4; i < COAT_ALBEDO_NODES; i += 4) {
        const double mu = coat_albedo_node_mu(i);
        EXPECT_NEAR(t[i], exact::fresnel(mu, 1.0, 1.5), 2e-3) << "mu " << mu;
    }
    Stack rough = make_stack("rough", {dielectric(1.5f, 0.5f), lambertian(glm::vec3(0.5f))});
    auto r = coat_albedo_table(rough);
    double acc = 0;
    const int N = 400;
    for (int a = 0; a < N; ++a)
        for (int b = 0; b < N; ++b) {
            double th = (a + 0.5) / N * M_PI / 2, ph = (b + 0.5) / N * 2 * M_PI;
            exact::V3 o{std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)};
            acc += exact::rough_reflection({0, 0, 1}, o, 0.5, 1.0, 1.5) * std::cos(th) * std::sin(th);
        }
    acc *= (M_PI / 2 / N) * (2 * M_PI / N);
    EXPECT_NEAR(r[COAT_ALBEDO_NODES - 1], acc, 1e-3);   // mu = 1
}

// Bin integration: for every model and shipped stack it can represent, the bin averages times their
// projected solid angles sum to the directional albedo computed by the independent quadrature above. The +tir
// variants are left out: they change a lobe's energy only (the TIR term), never its shape, which is what the bin
// integration sees; their defaults and +g2 variants (other lobe shapes) are checked.
TEST_F(Models, BinSumsEqualTheDirectionalAlbedo) {
    std::vector<std::string> files;
    for (auto& e : std::filesystem::directory_iterator("stacks"))
        if (e.path().extension() == ".toml") files.push_back(e.path().string());
    int checked = 0;
    for (auto& file : files) {
        Stack s = parse_stack_file(file);
        ModelGrid g = default_grid({0, 30, 60, 80});
        auto all = evaluate_models(context(), s, g);
        double a_min = std::max(1e-4, double(s.layers[0].roughness));
        if (s.layers.back().kind == InterfaceKind::Conductor)
            a_min = std::min(a_min, std::max(1e-4, double(s.layers.back().roughness)));
        for (size_t m = 0; m < all.size(); ++m) {
            if (!all[m].not_applicable.empty()) continue;
            if (model_registry()[m].convention & MODEL_CONVENTION_TIR_BELOW_MEDIA) continue;
            for (size_t a = 0; a < g.theta_i_deg.size(); ++a) {
                glm::dvec3 sum(0);
                for (size_t b = 0; b < all[m].f[a].size(); ++b) sum += all[m].f[a][b] * omega(g, uint32_t(b / g.n_phi));
                glm::dvec3 want = albedo_quadrature(m, s, g.theta_i_deg[a], a_min);
                std::printf("%-16s %-14s theta_i %2g: bins %.5f %.5f %.5f  quadrature %.5f %.5f %.5f\n", s.name.c_str(),
                            all[m].id.c_str(), g.theta_i_deg[a], sum.x, sum.y, sum.z, want.x, want.y, want.z);
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], want[c], 1e-3) << s.name << " " << all[m].id;
                // the white-furnace bound on the shipped stacks where a model claims it (its header's
                // energy-conserving: yes); the others may give more than they receive, and do: glTF's clearcoat and
                // Standard Surface 1.14 and 1.12 at 80 degrees on the coated plastic, whose coat's Fresnel taken from v
                // alone lets a grazing light reflect off the coat and still reach the base nearly whole (R + T below, on
                // the shipped slabs: every model)
                if (model_registry()[m].energy_conserving) {
                    for (int c = 0; c < 3; ++c) EXPECT_LE(sum[c], 1.0) << s.name << " " << all[m].id;
                }
                if (!all[m].t.empty()) {
                    glm::dvec3 tsum(0);
                    for (size_t b = 0; b < all[m].t[a].size(); ++b)
                        tsum += all[m].t[a][b] * omega(g, uint32_t(b / g.n_phi));
                    for (int c = 0; c < 3; ++c)
                        EXPECT_LE(sum[c] + tsum[c], 1.0) << s.name << " " << all[m].id << " R + T";
                }
                checked++;
            }
        }
    }
    EXPECT_GE(checked, 3 * 3 * 4);
}

// A model that cannot represent a stack says why and computes nothing; one that can computes both sides of a
// transmissive stack.
TEST_F(Models, StacksAModelCannotRepresentAreRefusedWithAReason) {
    const glm::vec3 cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f);
    Stack slab = make_stack("slab", {dielectric(1.5f, 0.1f), dielectric(1.0f, 0.2f)});
    Stack three = make_stack("three", {dielectric(1.5f, 0.1f), dielectric(1.3f, 0.1f), lambertian(glm::vec3(0.5f))});
    Stack three_metal =
        make_stack("three-metal", {dielectric(1.5f, 0.1f), dielectric(1.3f, 0.1f), conductor(cu_n, cu_k, 0.2f)});
    Stack into_glass = make_stack("into-glass", {dielectric(1.3f, 0.1f), dielectric(1.5f, 0.2f)});
    // which models must refuse each stack (by id prefix), all others must accept it
    auto refuses = [](const std::string& variant_id, const std::string& stack) {
        // no stack here has an absorbing medium: a +tir variant equals its base model on it, and says so
        if (variant_id.size() > 4 && variant_id.substr(variant_id.size() - 4) == "+tir") return true;
        const std::string id = base_id(variant_id);   // a variant represents what its base model does
        bool belcour = id.rfind("belcour18", 0) == 0;
        if (stack == "slab") return !belcour || id == "belcour18-symmetric";
        // 3 layers for WW, Lambertian for Belcour; the production models whose definitions have a dielectric base
        // take it (a coat over a dielectric interface over a Lambertian; glTF's with a coat of IOR 1.5), but
        // openpbr+dev1.2, which equals openpbr where nothing absorbs
        if (stack == "three")
            return !(id == "openpbr" || id == "standard-surface" || id == "gltf-clearcoat") ||
                   variant_id == "openpbr+dev1.2";
        if (stack == "three-metal") return !belcour && id != "tm21";
        return true;   // into-glass: no model has that transmitted lobe
    };
    for (const Stack* s : {&slab, &three, &three_metal, &into_glass}) {
        auto all = evaluate_models(context(), *s, default_grid({30}));
        for (auto& m : all) {
            if (refuses(m.id, s->name)) {
                EXPECT_FALSE(m.not_applicable.empty()) << m.id << " on " << s->name;
                EXPECT_TRUE(m.f.empty()) << m.id;
            } else {
                EXPECT_TRUE(m.not_applicable.empty()) << m.id << " on " << s->name << ": " << m.not_applicable;
                ASSERT_EQ(m.f.size(), 1u) << m.id;
                EXPECT_EQ(m.t.size(), s->transmissive() ? 1u : 0u) << m.id;
            }
        }
    }
    EXPECT_NE(model_cannot_represent(0, slab).find("transmissive"), std::string::npos);
    EXPECT_NE(model_cannot_represent(0, three).find("3 layers"), std::string::npos);
    EXPECT_NE(model_cannot_represent(model_index("belcour18-forward"), three).find("Lambertian"), std::string::npos);
    EXPECT_NE(model_cannot_represent(model_index("belcour18-forward"), into_glass).find("substrate"),
              std::string::npos);
}

// With a black base every model whose top lobe is the exact interface BRDF is the top interface's reflection
// alone. (Belcour's forward and symmetric variants are not: their lobe 0 is a GGX lobe scaled by FGD, checked
// in test_belcour.cpp.) The base is black as a Lambertian of albedo 0, or as a conductor index-matched to the
// coat (eta 1, k 0: Fresnel 0), for the models that take no Lambertian base.
TEST_F(Models, BlackBaseLeavesTheTopReflection) {
    Stack lam = make_stack("black", {dielectric(1.5f, 0.3f, glm::vec3(0.2f)), lambertian(glm::vec3(0.0f))});
    Stack cond = make_stack("black-conductor", {dielectric(1.5f, 0.3f, glm::vec3(0.2f)),
                                                conductor(glm::vec3(1.5f), glm::vec3(0.0f), 0.2f)});
    int checked = 0, skipped = 0;
    for (size_t m = 0; m < model_registry().size(); ++m) {
        const std::string& id = model_registry()[m].id;
        // glTF's and Enterprise PBR's coat lobes are weighed by Schlick's Fresnel, MaterialX's by Turquin's
        // compensation, Cycles' by its energy compensation, Adobe's, openpbr+separable's and the interfaced Lambertian's
        // have the separable G: not the exact interface BRDF
        // (their own tests: GltfClearcoatIsTheSpecificationsFormula, EnterprisePbrIsTheSpecificationsFormula,
        // MaterialxLayerIsItsGlslCode, OpenpbrIsTheSpecificationsFormula, tests/test_production_models.cpp)
        // the sheen models' top is the fibres' lobe, over an index-matched interface (tests/test_sheen_models.cpp)
        if (base_id(id) == "belcour18-forward" || base_id(id) == "belcour18-symmetric" ||
            model_registry()[m].header.family == "sheen" || base_id(id) == "gltf-clearcoat" || id == "enterprise-pbr" ||
            id == "materialx-layer" || id == "openpbr+materialx" || id == "openpbr+separable" ||
            base_id(id) == "openpbr-adobe" || id == "cycles-principled" || id == "interfaced-lambertian" ||
            model_cannot_represent(m, lam).find(" equals ") != std::string::npos) {   // the last: a variant that is
            skipped++;   // its base model here
            continue;
        }
        const Stack& s = model_cannot_represent(m, lam).empty() ? lam : cond;
        ASSERT_TRUE(model_cannot_represent(m, s).empty()) << id;
        for (double th : {10.0, 50.0, 80.0})
            for (double to : {5.0, 40.0, 85.0}) {
                glm::vec3 l(float(std::sin(th * M_PI / 180)), 0.0f, float(std::cos(th * M_PI / 180)));
                glm::vec3 v(float(-std::sin(to * M_PI / 180) * 0.6), float(std::sin(to * M_PI / 180) * 0.8),
                            float(std::cos(to * M_PI / 180)));
                exact::V3 le{l.x, l.y, l.z}, ve{v.x, v.y, v.z};
                double want = exact::rough_reflection(le, ve, 0.3, 1.0, 1.5);
                glm::dvec3 got = model_value_cpu(m, s, l, v);
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want, 1e-5 * std::max(1.0, want)) << id;
            }
        checked++;
    }
    EXPECT_EQ(checked, int(model_registry().size()) - skipped);
    EXPECT_GE(checked, 6);   // ww09, elek10, ww-corrected, albedo-scaling, belcour18-toplobe, tm21 (and their variants)
}

// gltf-clearcoat is KHR_materials_clearcoat over glTF's metal-rough base as the specification writes it, here
// transcribed again in double from the specification's text (KhronosGroup/glTF @77b44be7: the clearcoat README l.
// 140-144, Appendix B l. 3095-3132 and 3195-3196): clearcoat_fresnel = 0.04 + 0.96 (1 - |n.v|)^5 weighs the coat's
// D Vis (height-correlated G / (4 |n.l| |n.v|)) and takes 1 - clearcoat_fresnel from the base: Lambertian albedo / pi
// (specular off), or a metal of F0 the conductor's normal-incidence reflectance in the exterior, with Schlick at
// |v.h|. Direction by direction through the CPU twin, on both bases and three roughnesses; and its refusals.
// gltf-clearcoat+viewer, the glTF Sample Viewer's punctual lights (punctual.glsl @6386b1d8
// getPunctualRadianceClearCoat, brdf.glsl @00536c7d BRDF_specularGGX): the same, but the coat's lobe weighed by
// Schlick's 0.04 + 0.96 (1 - |v.h|)^5; the base still by 1 - clearcoat_fresnel(n.v).
TEST_F(Models, GltfClearcoatIsTheSpecificationsFormula) {
    for (const bool viewer : {false, true}) {
        const size_t m = model_index(viewer ? "gltf-clearcoat+viewer" : "gltf-clearcoat");
        auto D = [](double nh, double a) {
            const double a2 = a * a, d = nh * nh * (a2 - 1) + 1;
            return a2 / (M_PI * d * d);
        };
        auto G = [](double nl, double nv, double a) {   // Appendix B l. 3098-3125, height-correlated
            const double a2 = a * a;
            return 2 * nl * nv / (nv * std::sqrt(a2 + (1 - a2) * nl * nl) + nl * std::sqrt(a2 + (1 - a2) * nv * nv));
        };
        auto specular = [&](const glm::dvec3& l, const glm::dvec3& v, double a) {
            const glm::dvec3 h = glm::normalize(l + v);
            return D(h.z, a) * G(l.z, v.z, a) / (4 * l.z * v.z);
        };
        auto schlick = [](double f0, double c) { return f0 + (1 - f0) * std::pow(1 - c, 5); };
        const glm::vec3 albedo(0.9f, 0.5f, 0.2f), cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f);
        int checked = 0;
        for (float ac : {0.02f, 0.2f, 0.6f})
            for (int base = 0; base < 2; ++base) {
                const float ab = 0.3f;
                const Stack s = make_stack(
                    "gltf", {dielectric(1.5f, ac), base == 0 ? lambertian(albedo) : conductor(cu_n, cu_k, ab)});
                ASSERT_EQ(model_cannot_represent(m, s), "");
                for (double ti : {0.0, 35.0, 70.0, 85.0})
                    for (double to : {10.0, 40.0, 75.0})
                        for (double phi : {0.0, 60.0, 180.0}) {
                            const double a = ti * M_PI / 180, b = to * M_PI / 180, p = phi * M_PI / 180;
                            const glm::dvec3 l(std::sin(a), 0, std::cos(a));
                            const glm::dvec3 v(std::sin(b) * std::cos(p), std::sin(b) * std::sin(p), std::cos(b));
                            const double fc = schlick(0.04, v.z);
                            const glm::dvec3 got = model_value_cpu(m, s, glm::vec3(l), glm::vec3(v));
                            for (int c = 0; c < 3; ++c) {
                                double material = albedo[c] / M_PI;
                                if (base == 1) {
                                    const double n = cu_n[c], k = cu_k[c];
                                    const double f0 = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
                                    material =
                                        schlick(f0, std::fabs(glm::dot(v, glm::normalize(l + v)))) * specular(l, v, ab);
                                }
                                const double fl = viewer ? schlick(0.04, glm::dot(v, glm::normalize(l + v))) : fc;
                                const double want = (1 - fc) * material + fl * specular(l, v, ac);
                                EXPECT_NEAR(got[c], want, 2e-5 * want + 1e-7)
                                    << (viewer ? "+viewer " : "") << "alpha " << ac
                                    << (base ? " over copper" : " over Lambertian") << " theta_i " << ti << " theta_o "
                                    << to << " phi " << phi << " channel " << c;
                            }
                            ++checked;
                        }
            }
        EXPECT_EQ(checked, 3 * 2 * 4 * 3 * 3);
        // what glTF's clearcoat cannot take, each refused with its reason
        const Stack tinted = make_stack("tinted", {dielectric(1.5f, 0.1f, glm::vec3(0.1f)), lambertian(albedo)});
        const Stack ior_16 = make_stack("ior-1.6", {dielectric(1.6f, 0.1f), lambertian(albedo)});
        const Stack four = make_stack(
            "four", {dielectric(1.5f, 0.1f), dielectric(1.3f, 0.1f), dielectric(1.4f, 0.1f), lambertian(albedo)});
        EXPECT_NE(model_cannot_represent(m, tinted).find("colourless (layer 1's medium absorbs: optical depth 0.1"),
                  std::string::npos)
            << model_cannot_represent(m, tinted);
        // the relative IOR as written (1.6), not the float's 1.60000002
        const std::string why_16 = model_cannot_represent(m, ior_16),
                          tail = "fixed at 1.5 (f0 = 0.04); this coat's IOR relative to the exterior is 1.6";
        EXPECT_TRUE(why_16.size() >= tail.size() && why_16.compare(why_16.size() - tail.size(), tail.size(), tail) == 0)
            << why_16;
        EXPECT_NE(model_cannot_represent(m, four).find("4 layers"), std::string::npos)
            << model_cannot_represent(m, four);
        Stack denser_outside = make_stack("water", {dielectric(1.5f, 0.1f), lambertian(albedo)});
        denser_outside.exterior_ior = 1.33f;
        EXPECT_NE(model_cannot_represent(m, denser_outside).find("relative to the exterior is"), std::string::npos);
    }
}

namespace {

// A conductor's F0 in the exterior, and OpenPBR's F82-tint metal (F0 and the tint from n, k; Kutz et al. 2021 through
// the specification's "Metal") at the half vector of l and v
double conductor_f0(double n, double k) { return ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k); }
double openpbr_f82_at(double n, double k, double mu) {
    auto schlick = [](double f0, double mu) { return f0 + (1 - f0) * std::pow(1 - mu, 5); };
    const double f0 = conductor_f0(n, k), mb = 1.0 / 7;
    const double tint = std::min(1.0, exact::fresnel(mb, 1.0, std::complex<double>(n, k)) / schlick(f0, mb));
    return schlick(f0, mu) -
           mu * std::pow(1 - mu, 6) / (mb * std::pow(1 - mb, 6)) * (schlick(f0, mb) - tint * schlick(f0, mb));
}
double openpbr_f82(double n, double k, exact::V3 l, exact::V3 v) {
    const exact::V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
    return openpbr_f82_at(n, k, std::fabs(exact::dot(l, h)));
}
// F_avg = 2 int_0^1 F82(mu) mu dmu by a 2000-node midpoint rule (the compensation's average Fresnel)
double openpbr_f82_average(double n, double k) {
    double sum = 0;
    for (int j = 0; j < 2000; ++j) {
        const double mu = (j + 0.5) / 2000;
        sum += 2 * openpbr_f82_at(n, k, mu) * mu / 2000;
    }
    return sum;
}

// A directional albedo set (COAT_ALBEDO_NODES values of mu = i / 64 from `offset` of t) against a midpoint quadrature
// over the hemisphere of lobe(v, o), at its nodes 16, 40 and 64
template <class Lobe>
void expect_albedo_set(const std::vector<float>& t, uint32_t offset, Lobe lobe, const std::string& what) {
    for (uint32_t i : {16u, 40u, 64u}) {
        const double mu = i / 64.0;
        const exact::V3 v{std::sqrt(1 - mu * mu), 0, mu};
        const double e = hemisphere_integral(
                             [&](glm::vec3 o) {
                                 return glm::dvec3(o.z > 0 ? lobe(v, {o.x, o.y, o.z}) : 0);
                             },
                             400)
                             .x;
        EXPECT_NEAR(t[offset + i], e, 2e-3) << what << " at mu " << mu;
    }
}

}   // namespace

// openpbr is OpenPBR Surface v1.1.1's coat as its specification writes it (AcademySoftwareFoundation/OpenPBR
// index.html @f8d6d94), transcribed again in double from the text at coat_weight 1, coat_darkening 1:
//   f = f_coat + T^(1/mu_l^t + 1/mu_v^t) (1 - E_coat(v)) Delta f_base
// f_coat the coat's exact GGX dielectric reflection (height-correlated G2); E_coat(v) its directional albedo at the
// table's nodes of mu_v (the table itself checked here against an independent quadrature of that reflection);
// Delta = (1 - K) / (1 - E_b K), K = lerp(F(mu_v, eta), K_r, r_b), K_r = 1 - (1 - E_F(eta)) / eta^2 with d'Eon's fit;
// a Lambertian base (K = K_r, E_b its albedo) or a metal in F82-tint (F0 and the tint from the conductor's n, k in
// the exterior, E_b = F0, r_b = sqrt(alpha_base)) roughened to sqrt(min(1, alpha_B^2 + 2 alpha_C^2)), its lobe times
// the energy compensation 1 + F_avg (1 - E_ss(mu_v)) / E_ss(mu_v) ("Microfacet model"; F_avg the F82 Fresnel's
// cosine-weighted average, E_ss the lobe's albedo at F = 1: the stack's set, checked against a quadrature; +single:
// 1). On both bases, clear and absorbing coats, three coat roughnesses and two coat IORs, direction by direction
// through the CPU twin; the white furnaces it claims (a white Lambertian under a clear coat and a metal of F = 1 return
// all light, integrated over l at fixed v, OpenpbrPassesItsWhiteFurnaceAndRefusesWithReasons); and its refusals.
TEST_F(Models, OpenpbrIsTheSpecificationsFormula) {
    using exact::V3;
    const auto E_F = exact::openpbr_fresnel_albedo;   // OpenPBR footnote avg_fresnel
    const auto mu_t = exact::refracted_cosine;
    const glm::vec3 albedo(0.9f, 0.5f, 0.2f), cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f),
        tint_tau(0.1f, 0.3f, 0.6f);
    int checked = 0;
    // +separable: Smith's G in every lobe the separable G1(l) G1(v) (Walter et al. 2007 eq. 34's G1), E_coat with it
    for (const std::string id : {"openpbr", "openpbr+dev1.2", "openpbr+pr261", "openpbr+separable", "openpbr+single"})
        for (double eta : {1.5, 1.6})
            for (float ac : {0.02f, 0.2f, 0.6f})
                for (int base = 0; base < 3; ++base)   // Lambertian, copper alpha 0.3, smooth copper
                    for (int absorbs = 0; absorbs < 2; ++absorbs) {
                        const float ab = base == 1 ? 0.3f : 0.0f;
                        const glm::vec3 tau = absorbs ? tint_tau : glm::vec3(0.0f);
                        const Stack s =
                            make_stack("openpbr", {dielectric(float(eta), ac, tau),
                                                   base == 0 ? lambertian(albedo) : conductor(cu_n, cu_k, ab)});
                        const size_t m = model_index(id);
                        const bool dev12 = id == "openpbr+dev1.2", pr261 = id == "openpbr+pr261",
                                   separable = id == "openpbr+separable", single = id == "openpbr+single";
                        auto ggx = [&](V3 l, V3 v, double a) {   // D G / (4 mu_l mu_v)
                            const V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
                            return separable ? exact::ggx_D(h, a) * exact::G2_separable(l, v, a) / (4 * l.z * v.z)
                                             : exact::ggx_lobe(l, v, a);
                        };
                        auto coat_lobe = [&](V3 l, V3 v) {
                            const V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
                            return exact::fresnel(exact::dot(l, h), 1.0, eta) * ggx(l, v, ac);
                        };
                        if ((dev12 && !absorbs) || (single && base == 0)) {   // dev_1.2 differs only under an
                            // absorbing coat, +single only where the base has a GGX lobe
                            EXPECT_NE(model_cannot_represent(m, s).find("equals openpbr on this stack"),
                                      std::string::npos);
                            continue;
                        }
                        ASSERT_EQ(model_cannot_represent(m, s), "");
                        std::vector<float> table = coat_albedo_table(s);
                        if (separable) {   // the separable set of the stack's tables
                            const std::vector<float> t = stack_tables(pack_stack(s), STACK_TABLES_OPENPBR_SEPARABLE);
                            table.assign(t.begin() + STACK_TABLE_OPENPBR_SEPARABLE_COAT,
                                         t.begin() + STACK_TABLE_OPENPBR_SEPARABLE_COAT + COAT_ALBEDO_NODES);
                        }
                        if ((id == "openpbr" || separable) && ac >= 0.2f && base == 0 && absorbs == 0)
                            expect_albedo_set(table, 0, coat_lobe, id + " E_coat, eta " + std::to_string(eta));
                        const double k_r = 1 - (1 - E_F(eta)) / (eta * eta);
                        double a_rough = std::sqrt(std::min(1.0, double(ab) * ab + 2.0 * ac * ac));
                        if (pr261) {   // OpenPBR PR #261
                            const double B = 1.05 * (eta - 1) * std::sqrt(1 + eta * eta) / eta;
                            a_rough = 0.85 * std::tanh(std::hypot(eta * ab, B * ac) / 0.85);
                        }
                        // the metal lobe's E_ss at F = 1 (alpha'_B, the variant's G): the stack's set, checked
                        const std::vector<float> sets = stack_tables(pack_stack(s), STACK_TABLES_OPENPBR_LOBE_ALBEDO);
                        const uint32_t lobe_set = pr261       ? STACK_TABLE_OPENPBR_LOBE_PR261
                                                  : separable ? STACK_TABLE_OPENPBR_LOBE_SEPARABLE
                                                              : STACK_TABLE_OPENPBR_LOBE;
                        if (base == 1 && absorbs == 0 && eta == 1.5 && !single)
                            expect_albedo_set(
                                sets, lobe_set, [&](V3 l, V3 v) { return ggx(l, v, a_rough); }, id + " E_ss");
                        for (const FormulaDirection& d : formula_directions(true)) {
                            const V3 l = d.l, v = d.v;
                            const uint32_t i = d.node;
                            const double mu_v = v.z, ti = d.theta_i, phi = d.phi;
                            const glm::dvec3 got = model_at(m, s, d);
                            const double coat = coat_lobe(l, v), e_ss = sets[lobe_set + i];
                            for (int c = 0; c < 3; ++c) {
                                const double T = std::exp(-tau[c] * (1 / mu_t(l.z, eta) + 1 / mu_t(v.z, eta)));
                                double f_base = albedo[c] / M_PI, e_b = albedo[c], K = k_r;
                                if (base > 0) {
                                    const double f0 = conductor_f0(cu_n[c], cu_k[c]);
                                    const double compensation =
                                        single ? 1.0 : 1 + openpbr_f82_average(cu_n[c], cu_k[c]) * (1 - e_ss) / e_ss;
                                    f_base = openpbr_f82(cu_n[c], cu_k[c], l, v) * ggx(l, v, a_rough) * compensation;
                                    e_b = f0;
                                    const double r_b = std::sqrt(double(ab));
                                    K = (1 - r_b) * exact::fresnel(mu_v, 1.0, eta) + r_b * k_r;
                                }
                                const double t2 = dev12 ? std::exp(-2.0 * tau[c]) : 1.0;   // coat_color
                                const double delta = (1 - K) / (1 - e_b * t2 * K);
                                const double want = coat + T * (1 - table[i]) * delta * f_base;
                                EXPECT_NEAR(got[c], want, 5e-5 * want + 1e-7)
                                    << id << " eta " << eta << " alpha " << ac << " base " << base << " absorbs "
                                    << absorbs << " theta_i " << ti << " mu_v " << mu_v << " phi " << phi << " channel "
                                    << c;
                            }
                            ++checked;
                        }
                    }
    // dev_1.2 on absorbing coats only, +single on the two copper bases only
    EXPECT_EQ(checked, ((2 + 1 + 2 + 2) * 2 * 3 * 3 + 2 * 2 * 3 * 2) * 4 * 3 * 3);
}

// openpbr's white furnace as the specification claims it, and what it refuses
TEST_F(Models, OpenpbrPassesItsWhiteFurnaceAndRefusesWithReasons) {
    const glm::vec3 albedo(0.9f, 0.5f, 0.2f);
    const size_t m = model_index("openpbr");
    // the white furnace the specification claims: a white Lambertian under a clear coat (Delta = 1) returns all the
    // light that reaches v, E_coat(v) + (1 - E_coat(v)) = 1, integrated over l
    const Stack white = make_stack("white", {dielectric(1.5f, 0.3f), lambertian(glm::vec3(1.0f))});
    for (double to : {0.0, 40.0, 75.0}) {
        const glm::vec3 v(float(std::sin(to * M_PI / 180)), 0.0f, float(std::cos(to * M_PI / 180)));
        const glm::dvec3 e = hemisphere_integral([&](glm::vec3 l) { return model_value_cpu(m, white, l, v); }, 600);
        std::printf("openpbr, white Lambertian under a clear coat: albedo seen from theta_o %g: %.5f\n", to, e.x);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c], 1.0, 3e-3) << "theta_o " << to;
    }
    // the energy compensation's furnace ("Microfacet model"): a metal of F = 1 (n 1, k 100: F0 = 1 - 4e-4) under an
    // index-matched smooth coat (no coat lobe, Delta = 1) returns all the light at every mu_v, E_ss C = 1; +single
    // only its single scattering, E_ss (0.877 at alpha 0.3, 0.307 at alpha 1, normal incidence: the table)
    const size_t single = model_index("openpbr+single");
    for (float alpha : {0.3f, 0.6f, 1.0f}) {
        const Stack mirror =
            make_stack("white-metal", {dielectric(1.0f, 0.0f), conductor(glm::vec3(1.0f), glm::vec3(100.0f), alpha)});
        for (double to : {0.0, 40.0, 75.0}) {
            const glm::vec3 v(float(std::sin(to * M_PI / 180)), 0.0f, float(std::cos(to * M_PI / 180)));
            const double e = hemisphere_integral([&](glm::vec3 l) { return model_value_cpu(m, mirror, l, v); }, 600).x;
            const double e1 =
                hemisphere_integral([&](glm::vec3 l) { return model_value_cpu(single, mirror, l, v); }, 600).x;
            std::printf("openpbr, a white metal of alpha %.1f: albedo seen from theta_o %g: %.5f (+single %.5f)\n",
                        alpha, to, e, e1);
            EXPECT_NEAR(e, 1.0, 3e-3) << "alpha " << alpha << " theta_o " << to;
            EXPECT_LT(e1, 0.99) << "+single is single-scattering: alpha " << alpha << " theta_o " << to;
        }
    }
    // what it cannot take, each refused with its reason
    const Stack dense = make_stack("ior-3.5", {dielectric(3.5f, 0.1f), lambertian(albedo)});
    EXPECT_NE(
        model_cannot_represent(m, dense).find("valid for a relative coat IOR in [1/3, 3]; this coat's IOR relative "
                                              "to the exterior is 3.5"),
        std::string::npos)
        << model_cannot_represent(m, dense);
    const Stack four = make_stack(
        "four", {dielectric(1.5f, 0.1f), dielectric(1.3f, 0.1f), dielectric(1.4f, 0.1f), lambertian(albedo)});
    EXPECT_NE(model_cannot_represent(m, four).find("4 layers"), std::string::npos) << model_cannot_represent(m, four);
    const Stack tinted_base = make_stack(
        "tinted-base", {dielectric(1.5f, 0.1f), dielectric(1.3f, 0.1f, glm::vec3(0.2f)), lambertian(albedo)});
    EXPECT_NE(model_cannot_represent(m, tinted_base)
                  .find("no medium between its specular interface and its diffuse "
                        "(layer 2's medium absorbs"),
              std::string::npos)
        << model_cannot_represent(m, tinted_base);
}

// enterprise-pbr is Enterprise PBR 2025x's clearcoat over its opaque dielectric at specular 0 (a Lambertian core), as
// the specification writes it (DassaultSystemes-Technology/EnterprisePBRShadingModel spec-2025x.md.html @28d1c266),
// transcribed again in double: Coated = rho / pi (1 - max(F_c(v.n), F_c(l.n))) + F_c(h.v) D G / (4 |v.n| |l.n|),
// F_c Schlick of IOR 1.5, D GGX and G the height-correlated Smith term of alpha = r_c^2. Direction by direction
// through the CPU twin, three coat roughnesses; the reciprocity the max of the two Fresnels gives it; its refusals.
TEST_F(Models, EnterprisePbrIsTheSpecificationsFormula) {
    const size_t m = model_index("enterprise-pbr");
    using exact::V3;
    auto Fc = [](double c) { return 0.04 + 0.96 * std::pow(1 - std::fabs(c), 5); };
    const glm::vec3 albedo(0.9f, 0.5f, 0.2f);
    int checked = 0;
    double asym = 0;
    for (float ac : {0.02f, 0.2f, 0.6f}) {
        const Stack s = make_stack("enterprise", {dielectric(1.5f, ac), lambertian(albedo)});
        ASSERT_EQ(model_cannot_represent(m, s), "");
        for (const FormulaDirection& d : formula_directions()) {
            const V3 l = d.l, v = d.v;
            [[maybe_unused]] const double ti = d.theta_i, to = d.theta_o, phi = d.phi;
            const V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
            const double coat = Fc(exact::dot(h, v)) * exact::ggx_D(h, ac) * exact::G2(l, v, ac) / (4 * l.z * v.z);
            const glm::vec3 lf(float(l.x), float(l.y), float(l.z)), vf(float(v.x), float(v.y), float(v.z));
            const glm::dvec3 got = model_value_cpu(m, s, lf, vf), back = model_value_cpu(m, s, vf, lf);
            for (int c = 0; c < 3; ++c) {
                const double want = albedo[c] / M_PI * (1 - std::max(Fc(v.z), Fc(l.z))) + coat;
                EXPECT_NEAR(got[c], want, 2e-5 * want + 1e-7)
                    << "alpha " << ac << " theta_i " << ti << " theta_o " << to << " phi " << phi;
                asym = std::max(asym, std::fabs(got[c] - back[c]) / want);
            }
            ++checked;
        }
    }
    EXPECT_EQ(checked, 3 * 4 * 3 * 3);
    std::printf("enterprise-pbr: largest relative asymmetry |f(l,v) - f(v,l)| / f = %.2g\n", asym);
    EXPECT_LT(asym, 1e-4);   // reciprocal, as its header claims
    // its energy over a white Lambertian, integrated over v: below 1 (no excess, as its header says), and far below
    // it at grazing light, where both Fresnels tend to 1 and the lobe's microfacets see less of it
    for (float ac : {0.1f, 0.3f}) {
        const Stack white = make_stack("white", {dielectric(1.5f, ac), lambertian(glm::vec3(1.0f))});
        for (double ti : {0.0, 60.0, 75.0, 89.0}) {
            const glm::vec3 l(float(std::sin(ti * M_PI / 180)), 0.0f, float(std::cos(ti * M_PI / 180)));
            const double e = hemisphere_integral([&](glm::vec3 v) { return model_value_cpu(m, white, l, v); }, 500).x;
            std::printf("enterprise-pbr over white, coat alpha %g, theta_i %g: albedo %.4f\n", ac, ti, e);
            EXPECT_LT(e, 1.0);
            if (ti == 89.0) { EXPECT_LT(e, 0.5); }
        }
    }
    const Stack metal = make_stack("metal", {dielectric(1.5f, 0.1f), conductor(glm::vec3(0.27f, 0.68f, 1.22f),
                                                                               glm::vec3(3.6f, 2.6f, 2.3f), 0.2f)});
    const Stack tinted = make_stack("tinted", {dielectric(1.5f, 0.1f, glm::vec3(0.1f)), lambertian(albedo)});
    const Stack ior_16 = make_stack("ior-1.6", {dielectric(1.6f, 0.1f), lambertian(albedo)});
    EXPECT_NE(model_cannot_represent(m, metal).find("not a conductor: its metal's multiple-scattering compensation"),
              std::string::npos)
        << model_cannot_represent(m, metal);
    EXPECT_NE(model_cannot_represent(m, tinted).find("colourless"), std::string::npos);
    EXPECT_NE(model_cannot_represent(m, ior_16).find("fixed at 1.5"), std::string::npos);
}

// standard-surface is Autodesk Standard Surface 1.0's coat as its specification writes it (Autodesk/standard-surface
// index.html @34b1d5bd "Coating"), transcribed again in double at coat = 1:
//   f = coat_brdf + coat_color (1 - reflectance(coat_brdf)) f_base
// coat_brdf the coat's exact GGX dielectric reflection, reflectance its directional albedo E_coat(v) at the table's
// nodes (the table checked against a quadrature in OpenpbrIsTheSpecificationsFormula), coat_color = exp(-2 tau); the
// base unrefracted: albedo / pi, or the metal of reference/standard_surface.osl: ArtisticToConductorFresnel of
// (r, g) = (F0, Gulbrandsen's edge tint) of the conductor in the exterior, in a GGX lobe. +osl: 1 - F(n.v) in place of
// 1 - E_coat(v). Then the mapping's round trip: where F0 <= 0.99 the metal is the stack's own conductor, exactly.
TEST_F(Models, StandardSurfaceIsTheSpecificationsFormula) {
    using exact::V3;
    const auto ggx = exact::ggx_lobe;
    // reference/standard_surface.osl's ArtisticToConductorFresnel, and the edge tint g an artist sets for (n, k)
    auto n_min = [](double r) { return (1 - r) / (1 + r); };
    auto n_max = [](double r) { return (1 + std::sqrt(r)) / (1 - std::sqrt(r)); };
    auto artistic_fresnel = [&](double mu, double n_ext, double k_ext) {
        const double f0 = ((n_ext - 1) * (n_ext - 1) + k_ext * k_ext) / ((n_ext + 1) * (n_ext + 1) + k_ext * k_ext);
        const double g = (n_max(f0) - n_ext) / (n_max(f0) - n_min(f0));
        const double r = std::min(f0, 0.99);
        const double n = n_max(r) + g * (n_min(r) - n_max(r));
        const double k = std::sqrt(std::max(0.0, ((n + 1) * (n + 1) * r - (n - 1) * (n - 1)) / (1 - r)));
        return exact::fresnel(mu, 1.0, std::complex<double>(n, k));
    };
    const glm::vec3 albedo(0.9f, 0.5f, 0.2f), cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f),
        tint_tau(0.1f, 0.3f, 0.6f);
    // a metal whose F0 is above 0.99 in one channel (0.998), where the OSL's clamp of r changes it
    const glm::vec3 bright_n(0.05f, 0.27f, 1.0f), bright_k(10.0f, 3.6f, 10.0f);
    int checked = 0, round_trips = 0;
    for (const std::string id : {"standard-surface", "standard-surface+osl"})
        for (double eta : {1.5, 1.6})
            for (float ac : {0.02f, 0.2f, 0.6f})
                for (int base = 0; base < 3; ++base)   // Lambertian, copper alpha 0.3, the bright metal alpha 0.1
                    for (int absorbs = 0; absorbs < 2; ++absorbs) {
                        const float ab = base == 1 ? 0.3f : 0.1f;
                        const glm::vec3 tau = absorbs ? tint_tau : glm::vec3(0.0f);
                        // the conductor's n, k: the stack's, relative to the exterior (of IOR 1)
                        const glm::vec3 nb = base == 1 ? cu_n : bright_n, kb = base == 1 ? cu_k : bright_k;
                        const Stack s = make_stack(
                            "standard-surface",
                            {dielectric(float(eta), ac, tau), base == 0 ? lambertian(albedo) : conductor(nb, kb, ab)});
                        const size_t m = model_index(id);
                        ASSERT_EQ(model_cannot_represent(m, s), "");
                        const std::vector<float> table = coat_albedo_table(s);
                        for (const FormulaDirection& d : formula_directions(true)) {
                            const V3 l = d.l, v = d.v;
                            const uint32_t i = d.node;
                            const double mu_v = v.z, ti = d.theta_i, phi = d.phi;
                            const glm::dvec3 got = model_at(m, s, d);
                            const double coat = exact::rough_reflection(l, v, ac, 1.0, eta);
                            const double pass = id == "standard-surface"
                                                    ? 1 - table[i]
                                                    : std::clamp(1 - exact::fresnel(mu_v, 1.0, eta), 0.0, 1.0);
                            const V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
                            const double mu_h = std::fabs(exact::dot(l, h));
                            for (int c = 0; c < 3; ++c) {
                                const double n_ext = nb[c], k_ext = kb[c];
                                double f_base = albedo[c] / M_PI;
                                if (base > 0) {
                                    f_base = artistic_fresnel(mu_h, n_ext, k_ext) * ggx(l, v, ab);
                                    const double f0 = ((n_ext - 1) * (n_ext - 1) + k_ext * k_ext) /
                                                      ((n_ext + 1) * (n_ext + 1) + k_ext * k_ext);
                                    if (f0 <= 0.99) {   // the round trip (r, g) -> (n, k): the conductor
                                        const double own =
                                            exact::fresnel(mu_h, 1.0, std::complex<double>(n_ext, k_ext));
                                        EXPECT_NEAR(artistic_fresnel(mu_h, n_ext, k_ext), own, 1e-9);
                                        ++round_trips;
                                    }
                                }
                                const double want = coat + std::exp(-2.0 * tau[c]) * pass * f_base;
                                EXPECT_NEAR(got[c], want, 5e-5 * want + 1e-7)
                                    << id << " eta " << eta << " alpha " << ac << " base " << base << " absorbs "
                                    << absorbs << " theta_i " << ti << " mu_v " << mu_v << " phi " << phi << " channel "
                                    << c;
                            }
                            ++checked;
                        }
                    }
    EXPECT_EQ(checked, 2 * 2 * 3 * 3 * 2 * 4 * 3 * 3);
    EXPECT_GT(round_trips, 0);
}

// standard-surface's energy as its specification claims it ("energy conservation by construction", with the
// reflectance the coat's albedo): a white Lambertian under a clear coat returns all the light that reaches v,
// integrated over l; the OSL reference's Fresnel at the normal in its place does not; what it refuses
TEST_F(Models, StandardSurfaceConservesEnergySeenFromTheViewer) {
    const Stack white = make_stack("white", {dielectric(1.5f, 0.3f), lambertian(glm::vec3(1.0f))});
    for (const std::string id : {"standard-surface", "standard-surface+osl"})
        for (double to : {0.0, 40.0, 75.0}) {
            const size_t m = model_index(id);
            const glm::vec3 v(float(std::sin(to * M_PI / 180)), 0.0f, float(std::cos(to * M_PI / 180)));
            const glm::dvec3 e = hemisphere_integral([&](glm::vec3 l) { return model_value_cpu(m, white, l, v); }, 600);
            std::printf("%s, white Lambertian under a clear coat of alpha 0.3: albedo seen from theta_o %g: %.5f\n",
                        id.c_str(), to, e.x);
            if (id == "standard-surface") {
                EXPECT_NEAR(e.x, 1.0, 3e-3) << "theta_o " << to;
            } else if (to == 75.0) {   // F(n.v) above the rough coat's albedo at grazing: light lost (0.849)
                EXPECT_LT(e.x, 0.9);
            }
        }
    const glm::vec3 albedo(0.9f, 0.5f, 0.2f);
    const size_t m = model_index("standard-surface");
    const Stack four = make_stack(
        "four", {dielectric(1.5f, 0.1f), dielectric(1.3f, 0.1f), dielectric(1.4f, 0.1f), lambertian(albedo)});
    EXPECT_NE(model_cannot_represent(m, four).find("4 layers"), std::string::npos) << model_cannot_represent(m, four);
    const Stack slab = make_stack("slab", {dielectric(1.5f, 0.1f), dielectric(1.0f, 0.1f)});
    EXPECT_NE(model_cannot_represent(m, slab).find("transmissive"), std::string::npos);
}

// materialx-layer is MaterialX pbrlib's layer(dielectric_bsdf, base) as its GLSL generator computes it
// (AcademySoftwareFoundation/MaterialX @4177b2cb, libraries/pbrlib/genglsl), transcribed again in double:
//   f = F(v.h) D G comp_c / (4 n.l n.v) + (1 - (F0 A + B) comp_c) f_base,   comp = 1 + F_avg (1 - (A + B)) / (A + B)
// (A, B) the rational fit mx_ggx_dir_albedo_analytic, G MaterialX's height-correlated form, F_avg = F0 + (1 - F0) / 21;
// f_base albedo / pi or the conductor's D F G comp_m / (4 n.l n.v) in the exterior. Then the fit against gonio's own
// quadrature of the GGX albedo it stands for, and the light a white Lambertian under a clear coat returns to v.
TEST_F(Models, MaterialxLayerIsItsGlslCode) {
    using exact::V3;
    const size_t m = model_index("materialx-layer");
    const auto ggx_mx = mx::ggx_lobe;
    const auto comp = mx::compensation;
    const glm::vec3 albedo(0.9f, 0.5f, 0.2f), cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f);
    int checked = 0;
    for (double eta : {1.5, 1.6})
        for (float ac : {0.02f, 0.2f, 0.6f})
            for (int base = 0; base < 2; ++base) {   // Lambertian, copper alpha 0.3
                const Stack s = make_stack("materialx", {dielectric(float(eta), ac),
                                                         base == 0 ? lambertian(albedo) : conductor(cu_n, cu_k, 0.3f)});
                ASSERT_EQ(model_cannot_represent(m, s), "");
                const double f0c = std::pow((eta - 1) / (eta + 1), 2);
                for (const FormulaDirection& d : formula_directions()) {
                    const V3 l = d.l, v = d.v;
                    [[maybe_unused]] const double ti = d.theta_i, to = d.theta_o, phi = d.phi;
                    const V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
                    const double vh = exact::dot(v, h);
                    const double top = exact::fresnel(vh, 1.0, eta) * ggx_mx(l, v, ac) * comp(v.z, ac, f0c);
                    const double pass =
                        1 - (f0c * mx::fit_ab(v.z, ac, 0) + mx::fit_ab(v.z, ac, 1)) * comp(v.z, ac, f0c);
                    const glm::dvec3 got = model_at(m, s, d);
                    for (int c = 0; c < 3; ++c) {
                        double f_base = albedo[c] / M_PI;
                        if (base == 1) {
                            const std::complex<double> nk(cu_n[c], cu_k[c]);
                            f_base = exact::fresnel(vh, 1.0, nk) * ggx_mx(l, v, 0.3) *
                                     comp(v.z, 0.3, exact::fresnel(1.0, 1.0, nk));
                        }
                        const double want = top + pass * f_base;
                        EXPECT_NEAR(got[c], want, 5e-5 * want + 1e-7)
                            << "eta " << eta << " alpha " << ac << " base " << base << " theta_i " << ti << " theta_o "
                            << to << " phi " << phi << " channel " << c;
                    }
                    ++checked;
                }
            }
    EXPECT_EQ(checked, 2 * 3 * 2 * 4 * 3 * 3);

    // the fit against the GGX albedo it stands for (F = 1, G height-correlated), by gonio's quadrature
    double worst = 0;
    for (double a : {0.1, 0.2, 0.6, 1.0})
        for (double mu : {0.1, 0.5, 1.0}) {
            const V3 v{std::sqrt(1 - mu * mu), 0, mu};
            const double e = hemisphere_integral(
                                 [&](glm::vec3 o) {
                                     return glm::dvec3(ggx_mx({o.x, o.y, o.z}, v, a));
                                 },
                                 500)
                                 .x;
            const double fit = mx::albedo_ss(mu, a);
            std::printf("materialx-layer: GGX albedo at alpha %g, mu %g: fit %.4f, quadrature %.4f\n", a, mu, fit, e);
            worst = std::max(worst, std::fabs(fit - e));
        }
    std::printf("materialx-layer: the fit's largest error on these nodes: %.4f\n", worst);
    EXPECT_LT(worst, 0.04);   // a fit, not the integral: 0.032 at alpha 0.1, mu 0.1 (docs/MODELS.md)
    EXPECT_GT(worst, 0.01);

    // the light returned to v by a white Lambertian under a clear coat, integrated over l: the top's albedo (exact
    // Fresnel) plus its throughput (the fit with Schlick's split) need not make 1
    const Stack white = make_stack("white", {dielectric(1.5f, 0.2f), lambertian(glm::vec3(1.0f))});
    for (double to : {0.0, 60.0, 80.0}) {
        const glm::vec3 v(float(std::sin(to * M_PI / 180)), 0.0f, float(std::cos(to * M_PI / 180)));
        const double e = hemisphere_integral([&](glm::vec3 l) { return model_value_cpu(m, white, l, v); }, 600).x;
        std::printf("materialx-layer, white Lambertian under a clear coat of alpha 0.2: seen from theta_o %g: %.5f\n",
                    to, e);
        EXPECT_NEAR(e, 1.0, 0.03);
    }
    const Stack tinted = make_stack("tinted", {dielectric(1.5f, 0.1f, glm::vec3(0.1f)), lambertian(albedo)});
    EXPECT_NE(model_cannot_represent(m, tinted).find("has no medium between them"), std::string::npos)
        << model_cannot_represent(m, tinted);
}

// openpbr+materialx is OpenPBR as its reference MaterialX graph computes it (MaterialX @4177b2cb
// libraries/bxdf/open_pbr_surface.mtlx over pbrlib's GLSL), transcribed again in double at coat_weight 1,
// coat_darkening 1, specular_weight 0 for a diffuse base:
//   f = F(v.h) D G comp_c / (4 n.l n.v) + T_c(v) coat_color Delta base,   T(mu; alpha, eta) = 1 - (F0 A + B) comp
// Delta = (1 - K) / (1 - E_b K), K = 1 - (1 - F0_c) / eta^2, E_b = albedo or the metal's F0; base: albedo / pi
// T(v; alpha', 1) (the diffuse under its index-matched specular layer) or the metal's F82 D G comp / (4 n.l n.v), at
// alpha' = sqrt(min(1, alpha_B^2 + 2 alpha_C^2))
TEST_F(Models, OpenpbrMaterialxIsItsReferenceGraph) {
    using exact::V3;
    const size_t m = model_index("openpbr+materialx");
    const auto ggx_mx = mx::ggx_lobe;
    auto schlick = [](double f0, double mu) { return f0 + (1 - f0) * std::pow(1 - mu, 5); };
    const glm::vec3 albedo(0.9f, 0.5f, 0.2f), cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f),
        tint_tau(0.1f, 0.3f, 0.6f);
    int checked = 0;
    for (double eta : {1.5, 1.6})
        for (float ac : {0.02f, 0.2f, 0.6f})
            for (int base = 0; base < 2; ++base)   // Lambertian, copper alpha 0.3
                for (int absorbs = 0; absorbs < 2; ++absorbs) {
                    const glm::vec3 tau = absorbs ? tint_tau : glm::vec3(0.0f);
                    const double ab_own = base == 1 ? 0.3 : 0.0;
                    const Stack s = make_stack("openpbr-mtlx",
                                               {dielectric(float(eta), ac, tau),
                                                base == 0 ? lambertian(albedo) : conductor(cu_n, cu_k, float(ab_own))});
                    ASSERT_EQ(model_cannot_represent(m, s), "");
                    const double ab = std::sqrt(std::min(1.0, ab_own * ab_own + 2.0 * ac * ac));
                    const double f0c = std::pow((eta - 1) / (eta + 1), 2), K = 1 - (1 - f0c) / (eta * eta);
                    for (const FormulaDirection& d : formula_directions()) {
                        const V3 l = d.l, v = d.v;
                        [[maybe_unused]] const double ti = d.theta_i, to = d.theta_o, phi = d.phi;
                        const V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
                        const double vh = exact::dot(v, h);
                        const double top =
                            exact::fresnel(vh, 1.0, eta) * ggx_mx(l, v, ac) * mx::compensation(v.z, ac, f0c);
                        const glm::dvec3 got = model_at(m, s, d);
                        for (int c = 0; c < 3; ++c) {
                            double f_base = albedo[c] / M_PI * mx::dielectric_throughput(v.z, ab, 1.0), e_b = albedo[c];
                            if (base == 1) {
                                const std::complex<double> nk(cu_n[c], cu_k[c]);
                                const double f0 = ((cu_n[c] - 1) * (cu_n[c] - 1) + cu_k[c] * cu_k[c]) /
                                                  ((cu_n[c] + 1) * (cu_n[c] + 1) + cu_k[c] * cu_k[c]);
                                const double tint =
                                    std::min(1.0, exact::fresnel(1.0 / 7, 1.0, nk) / schlick(f0, 1.0 / 7));
                                f_base =
                                    mx::fresnel_f82(vh, f0, tint) * mx::compensation(v.z, ab, f0) * ggx_mx(l, v, ab);
                                e_b = f0;
                            }
                            const double want = top + mx::dielectric_throughput(v.z, ac, eta) *
                                                          std::exp(-2.0 * tau[c]) * (1 - K) / (1 - e_b * K) * f_base;
                            EXPECT_NEAR(got[c], want, 5e-5 * want + 1e-7)
                                << "eta " << eta << " alpha " << ac << " base " << base << " absorbs " << absorbs
                                << " theta_i " << ti << " theta_o " << to << " phi " << phi << " channel " << c;
                        }
                        ++checked;
                    }
                }
    EXPECT_EQ(checked, 2 * 3 * 2 * 2 * 4 * 3 * 3);
}

// Hard cases: finite everywhere; the directional albedo is reported and bounded by 1 for the models whose
// construction guarantees it. Those documented as not energy-conserving (ModelInfo::energy_note) must measurably
// exceed 1 somewhere: here, or, for Belcour's symmetric and top-lobe variants, whose excess shows only on
// stacks/hard (ior-3-metal, tir-trap-slab), in tests/test_hard_cases.cpp (ModelsAreFiniteAndBounded). The claim
// is measured, not assumed.
TEST_F(Models, HardCasesAreFinite) {
    const glm::vec3 cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f);
    std::vector<Stack> stacks = {
        make_stack("smooth-smooth", {dielectric(1.5f, 0.0f), conductor(cu_n, cu_k, 0.0f)}),
        make_stack("roughness-1e-4", {dielectric(1.5f, 1e-4f, glm::vec3(0.1f)), conductor(cu_n, cu_k, 1e-4f)}),
        make_stack("roughness-1", {dielectric(1.5f, 1.0f, glm::vec3(0.1f)), lambertian(glm::vec3(1.0f))}),
        make_stack("ior-3", {dielectric(3.0f, 0.2f), lambertian(glm::vec3(1.0f))}),
        make_stack("index-matched", {dielectric(1.0f, 0.3f), lambertian(glm::vec3(1.0f))}),
        make_stack("optical-depth-50", {dielectric(1.5f, 0.1f, glm::vec3(50.0f)), lambertian(glm::vec3(0.9f))}),
        make_stack("conductor-k-10", {dielectric(1.5f, 0.05f), conductor(glm::vec3(1.0f), glm::vec3(10.0f), 0.3f)}),
    };
    // the sheen models' one shape: white fibres (the sheen authors' unit slab) over a white Lambertian, thin and thick
    for (const char* alpha : {"0.1", "1.0"})
        stacks.push_back(parse_stack_string(
            std::string("name = \"white-fibres-") + alpha +
                "\"\nexterior_ior = 1.0\n[[layer]]\ninterface = \"dielectric\"\nior = 1.0\noptical_depth = 1.0\n"
                "scattering_albedo = 1.0\nphase = \"sggx-fibre\"\nfibre_roughness = " +
                alpha + "\n[[layer]]\ninterface = \"lambertian\"\nalbedo = 1.0\n",
            "white-fibres.toml"));
    std::vector<double> largest(model_registry().size(), 0.0);
    for (auto& s : stacks) {
        ModelGrid g = default_grid({0, 60, 89.9});
        auto all = evaluate_models(context(), s, g);
        for (auto& m : all) {
            if ((m.id.rfind("belcour18", 0) == 0 || base_id(m.id) == "tm21") &&
                s.base().kind == InterfaceKind::Lambertian) {
                EXPECT_FALSE(m.not_applicable.empty()) << m.id;
                continue;
            }
            // glTF's and Enterprise PBR's coats: colourless, IOR 1.5 (and Enterprise PBR's over a Lambertian only);
            // MaterialX's layer: colourless; the interfaced Lambertian: a colourless interface over a Lambertian
            if ((base_id(m.id) == "gltf-clearcoat" || m.id == "enterprise-pbr" || m.id == "materialx-layer" ||
                 m.id == "interfaced-lambertian") &&
                !m.not_applicable.empty()) {
                bool takes = m.id == "materialx-layer" || m.id == "interfaced-lambertian" || s.layers[0].ior.x == 1.5f;
                for (const Layer& L : s.layers) takes &= L.optical_depth == glm::vec3(0.0f);
                if (m.id == "enterprise-pbr" || m.id == "interfaced-lambertian")
                    takes &= s.base().kind == InterfaceKind::Lambertian;
                EXPECT_FALSE(takes) << m.id << " on " << s.name << ": " << m.not_applicable;
                continue;
            }
            // the sheen models take the fibres alone; every other model refuses them
            if (model_registry()[model_index(m.id)].header.family == "sheen" ||
                stack_has_shape(s, StackShape::FibresOverLambertian)) {
                EXPECT_EQ(m.not_applicable.empty(), model_registry()[model_index(m.id)].header.family == "sheen" &&
                                                        stack_has_shape(s, StackShape::FibresOverLambertian))
                    << m.id << " on " << s.name << ": " << m.not_applicable;
                if (!m.not_applicable.empty()) continue;
            }
            if (m.not_applicable.find(" equals ") != std::string::npos) {
                if (m.id == "openpbr+single") {   // over a Lambertian alone
                    EXPECT_EQ(s.base().kind, InterfaceKind::Lambertian) << m.id << " on " << s.name;
                    continue;
                }
                bool absorbing = false;   // a +tir or +dev1.2 variant where no medium absorbs
                for (size_t i = 0; i + 1 < s.layers.size(); ++i)
                    absorbing |= s.layers[i].optical_depth != glm::vec3(0.0f);
                EXPECT_FALSE(absorbing) << m.id << " on " << s.name;
                continue;
            }
            ASSERT_TRUE(m.not_applicable.empty()) << m.id << ": " << m.not_applicable;
            for (size_t a = 0; a < g.theta_i_deg.size(); ++a) {
                glm::dvec3 albedo(0);
                for (size_t b = 0; b < m.f[a].size(); ++b) {
                    for (int c = 0; c < 3; ++c)
                        ASSERT_TRUE(std::isfinite(m.f[a][b][c]) && m.f[a][b][c] >= 0)
                            << s.name << " " << m.id << " bin " << b;
                    albedo += m.f[a][b] * omega(g, uint32_t(b / g.n_phi));
                }
                std::printf("%-18s %-14s theta_i %4g: albedo %.4f %.4f %.4f\n", s.name.c_str(), m.id.c_str(),
                            g.theta_i_deg[a], albedo.x, albedo.y, albedo.z);
                if (model_registry()[model_index(m.id)].energy_conserving) {
                    for (int c = 0; c < 3; ++c) EXPECT_LE(albedo[c], 1.0 + 1e-3) << s.name;
                }
                for (int c = 0; c < 3; ++c)
                    largest[model_index(m.id)] = std::max(largest[model_index(m.id)], albedo[c]);
            }
        }
    }
    for (size_t m = 0; m < model_registry().size(); ++m) {
        std::printf("%-20s largest directional albedo on the hard cases: %.4f\n", model_registry()[m].id.c_str(),
                    largest[m]);
        const std::string id = base_id(model_registry()[m].id);
        // openpbr+dev1.2 runs only under an absorbing coat (elsewhere it is openpbr, whose excess is measured here)
        // enterprise-pbr takes none of these stacks (clear coats of IOR 1.5 over a Lambertian only): its bound is
        // measured in EnterprisePbrIsTheSpecificationsFormula; openpbr-adobe+reciprocal is not bounded by construction,
        // but no case here exceeds 1 (its registry note says so)
        if (!model_registry()[m].energy_conserving && id != "belcour18-symmetric" && id != "belcour18-toplobe" &&
            id != "tm21" && model_registry()[m].id != "openpbr+dev1.2" && id != "enterprise-pbr" &&
            model_registry()[m].id != "openpbr-adobe+reciprocal") {
            EXPECT_GT(largest[m], 1.0 + 1e-3)
                << model_registry()[m].id << " is documented as not energy-conserving, but measured bounded";
        }
    }
}

}   // namespace

namespace {

// Reciprocity, measured for every model against what the registry says of it: a model that claims it must
// have f(l, v) = f(v, l); one documented as non-reciprocal must measurably not.
TEST(ModelsReciprocity, MeasuredAsClaimed) {
    const glm::vec3 cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f);
    std::vector<Stack> stacks = {
        make_stack("plastic",
                   {dielectric(1.5f, 0.05f, glm::vec3(0.05f, 0.05f, 0.3f)), lambertian(glm::vec3(0.2f, 0.6f, 0.3f))}),
        make_stack("metal", {dielectric(1.5f, 0.2f, glm::vec3(0.1f)), conductor(cu_n, cu_k, 0.3f)}),
        make_stack("clear-over-grey", {dielectric(1.5f, 0.1f), lambertian(glm::vec3(0.5f))}),
        make_stack("clear-over-metal", {dielectric(1.5f, 0.2f), conductor(cu_n, cu_k, 0.3f)}),
        parse_stack_file("stacks/velvet.toml")};   // the sheen models' fibres
    // stacks outside, models inside: the CPU twin keeps one stack's Belcour tables at a time; each model measured on
    // the stacks it takes (on the others it would be measured on a formula it does not claim)
    std::vector<double> worst_of(model_registry().size(), 0.0);
    std::vector<int> measured_on(model_registry().size(), 0);
    for (auto& s : stacks)
        for (size_t m = 0; m < model_registry().size(); ++m) {
            if (!model_cannot_represent(m, s).empty()) continue;
            ++measured_on[m];
            double& worst = worst_of[m];
            for (double a : {10.0, 35.0, 60.0, 80.0})
                for (double b : {5.0, 30.0, 55.0, 75.0})
                    for (double phi : {30.0, 120.0, 170.0}) {
                        double ra = a * M_PI / 180, rb = b * M_PI / 180, rp = phi * M_PI / 180;
                        glm::vec3 l(float(std::sin(ra)), 0.0f, float(std::cos(ra)));
                        glm::vec3 v(float(std::sin(rb) * std::cos(rp)), float(std::sin(rb) * std::sin(rp)),
                                    float(std::cos(rb)));
                        glm::dvec3 f1 = model_value_cpu(m, s, l, v), f2 = model_value_cpu(m, s, v, l);
                        for (int c = 0; c < 3; ++c)
                            worst = std::max(worst, std::fabs(f1[c] - f2[c]) / std::max(1e-12, 0.5 * (f1[c] + f2[c])));
                    }
        }
    for (size_t m = 0; m < model_registry().size(); ++m) {
        const double worst = worst_of[m];
        std::printf("%-14s largest relative asymmetry |f(l,v) - f(v,l)| / mean: %.3g (on %d stacks)\n",
                    model_registry()[m].id.c_str(), worst, measured_on[m]);
        EXPECT_GE(measured_on[m], 1) << model_registry()[m].id << " takes none of the reciprocity test's stacks";
        if (model_registry()[m].reciprocal)
            EXPECT_LT(worst, 1e-4) << model_registry()[m].id << " claims reciprocity";
        else
            EXPECT_GT(worst, 1e-3) << model_registry()[m].id
                                   << " is documented as non-reciprocal, but measured reciprocal";
    }
}

}   // namespace

// Over a Lambertian alone openpbr+single is not computed (it equals openpbr: the energy compensation changes a base's
// GGX lobes only): that is so, direction by direction, through the CPU twin, where over a rough metal the two part
TEST(ModelsConventions, SingleVariantEqualsOpenpbrOverALambertian) {
    const Stack lambertian_base =
        make_stack("grey", {dielectric(1.5f, 0.3f, glm::vec3(0.2f)), lambertian(glm::vec3(0.5f))});
    const Stack metal =
        make_stack("metal", {dielectric(1.5f, 0.3f), conductor(glm::vec3(0.27f), glm::vec3(3.6f), 0.5f)});
    const size_t single = model_index("openpbr+single"), openpbr = model_index("openpbr");
    EXPECT_NE(model_cannot_represent(single, lambertian_base).find(" equals openpbr "), std::string::npos);
    EXPECT_EQ(model_cannot_represent(single, metal), "");
    int compared = 0, parted = 0;
    for (double tl : {0.0, 40.0, 80.0})
        for (double tv : {10.0, 50.0, 85.0}) {
            const double a = tl * M_PI / 180, b = tv * M_PI / 180;
            const glm::vec3 l(float(std::sin(a)), 0.0f, float(std::cos(a)));
            const glm::vec3 v(float(-std::sin(b) * 0.8), float(std::sin(b) * 0.6), float(std::cos(b)));
            EXPECT_EQ(model_value_cpu(single, lambertian_base, l, v), model_value_cpu(openpbr, lambertian_base, l, v))
                << tl << ", " << tv;
            parted += model_value_cpu(single, metal, l, v).x < model_value_cpu(openpbr, metal, l, v).x;
            ++compared;
        }
    EXPECT_EQ(compared, 9);
    EXPECT_EQ(parted, 9);   // the compensation adds light at every direction over the rough metal
}

// Where no medium absorbs, a +tir variant is not computed (model_cannot_represent: it equals its base model): that
// is so, direction by direction, through the CPU twin of the shader code.
TEST(ModelsConventions, TirVariantEqualsItsBaseWhereNothingAbsorbs) {
    const glm::vec3 cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f);
    const Stack stacks[] = {
        make_stack("coat", {dielectric(1.5f, 0.1f), conductor(cu_n, cu_k, 0.2f)}),
        make_stack("two-coats", {dielectric(1.5f, 0.3f), dielectric(1.3f, 0.05f), conductor(cu_n, cu_k, 0.1f)})};
    int compared = 0;
    for (const Stack& s : stacks)
        for (size_t i = 0; i < model_registry().size(); ++i) {
            const std::string& id = model_registry()[i].id;
            if (id.size() < 4 || id.substr(id.size() - 4) != "+tir") continue;
            EXPECT_NE(model_cannot_represent(i, s).find(" equals "), std::string::npos) << id;
            const size_t base = model_index(id.substr(0, id.size() - 4));
            for (double tl : {0.0, 40.0, 80.0})
                for (double tv : {10.0, 50.0, 85.0}) {
                    const double a = tl * M_PI / 180, b = tv * M_PI / 180;
                    const glm::vec3 l(float(std::sin(a)), 0.0f, float(std::cos(a)));
                    const glm::vec3 v(float(-std::sin(b) * 0.8), float(std::sin(b) * 0.6), float(std::cos(b)));
                    const glm::dvec3 fv = model_value_cpu(i, s, l, v), fb = model_value_cpu(base, s, l, v);
                    EXPECT_EQ(fv, fb) << id << " on " << s.name << " at " << tl << ", " << tv;
                    ++compared;
                }
        }
    EXPECT_GE(compared, 2 * 3 * 9);
}
