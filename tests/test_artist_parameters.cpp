// What an artist would set (host/models/artist_parameters.h, each model's GONIO_MODEL_ARTIST_PARAMETERS hook): every
// production model's parameters for a stack map back to that stack (where the model's parameters hold all of it;
// the inverse written here from the definitions, artist_parameters_inverse.h) and to the same parameters; each
// parameter is one the model's header names in its `mapping:` line; the values are those the models' definitions
// give (checked here from the definitions' text, not from the code under test).
#include "artist_parameters.h"
#include "artist_parameters_inverse.h"
#include "model_applicability.h"
#include "models.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace gonio;
using gonio::test::stack_from_artist_parameters;

Layer coat(float ior, float alpha, glm::vec3 tau = glm::vec3(0.0f)) {
    Layer L;
    L.kind = InterfaceKind::Dielectric;
    L.ior = glm::vec3(ior);
    L.roughness = alpha;
    L.optical_depth = tau;
    return L;
}
const auto lambertian = &test::lambertian_layer;   // the layers the inverse builds, written once
const auto conductor = &test::conductor_layer;
Stack stack(const std::string& name, std::vector<Layer> layers, float exterior = 1.0f) {
    Stack s;
    s.name = name;
    s.exterior_ior = exterior;
    s.layers = std::move(layers);
    return s;
}

std::vector<Stack> stacks() {
    const glm::vec3 cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f), au_n(0.18f, 0.42f, 1.37f),
        au_k(3.4f, 2.35f, 1.77f);
    return {
        stack("clear-over-grey", {coat(1.5f, 0.05f), lambertian(glm::vec3(0.5f))}),
        stack("tinted-over-colour", {coat(1.6f, 0.3f, glm::vec3(0.1f, 0.3f, 0.6f)), lambertian({0.8f, 0.4f, 0.1f})}),
        stack("clear-over-copper", {coat(1.5f, 0.01f), conductor(cu_n, cu_k, 0.2f)}),
        stack("tinted-over-gold", {coat(1.45f, 0.2f, glm::vec3(0.05f, 0.1f, 0.2f)), conductor(au_n, au_k, 0.4f)}),
        stack("under-water", {coat(1.5f * 1.33f, 0.1f), conductor(cu_n * 1.33f, cu_k * 1.33f, 0.3f)}, 1.33f),
        // three layers: a dielectric base (a specular interface over a Lambertian) under the coat
        stack("coated-plastic", {coat(1.5f, 0.02f), coat(1.59f, 0.15f), lambertian({0.7f, 0.2f, 0.1f})}),
        stack("tinted-over-glaze",
              {coat(1.6f, 0.1f, glm::vec3(0.1f, 0.2f, 0.3f)), coat(1.3f, 0.3f), lambertian({0.3f, 0.6f, 0.9f})}),
    };
}

double largest_difference(const std::vector<ArtistParameter>& a, const std::vector<ArtistParameter>& b) {
    EXPECT_EQ(a.size(), b.size());
    double d = 0;
    for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        EXPECT_EQ(a[i].name, b[i].name);
        for (int c = 0; c < 3; ++c) d = std::max(d, double(std::fabs(a[i].value[c] - b[i].value[c])));
    }
    return d;
}

double relative(float a, float b) { return std::fabs(a - b) / std::max(1e-6f, std::fabs(b)); }

// the physical parameters of two stacks, largest relative difference
double stack_difference(const Stack& a, const Stack& b) {
    EXPECT_EQ(a.layers.size(), b.layers.size());
    double d = relative(a.exterior_ior, b.exterior_ior);
    for (size_t i = 0; i < std::min(a.layers.size(), b.layers.size()); ++i) {
        const Layer &x = a.layers[i], &y = b.layers[i];
        EXPECT_EQ(int(x.kind), int(y.kind)) << "layer " << i;
        d = std::max(d, double(std::fabs(x.roughness - y.roughness)));
        for (int c = 0; c < 3; ++c) {
            d = std::max({d, double(std::fabs(x.optical_depth[c] - y.optical_depth[c])),
                          double(std::fabs(x.albedo[c] - y.albedo[c]))});
            if (x.kind != InterfaceKind::Lambertian)
                d = std::max({d, relative(x.ior[c], y.ior[c]), relative(x.k[c], y.k[c])});
        }
    }
    return d;
}

// stack -> parameters -> stack, and parameters -> stack -> parameters, for every production model and stack it takes
TEST(ArtistParameters, MapToTheStackAndBack) {
    int round_trips = 0, exact_stacks = 0;
    for (size_t m = 0; m < model_registry().size(); ++m) {
        const ModelInfo& info = model_registry()[m];
        if (info.header.mapping.empty()) {
            EXPECT_TRUE(artist_parameters(info.id, stacks()[0]).empty()) << info.id;
            continue;
        }
        for (const Stack& s : stacks()) {
            if (!model_cannot_represent(m, s).empty()) continue;
            const std::vector<ArtistParameter> p = artist_parameters(info.id, s);
            ASSERT_FALSE(p.empty()) << info.id;
            // each parameter is named in the model's `mapping:` line, as its definition spells it
            for (const ArtistParameter& a : p) {
                const std::string name = a.name.substr(a.name.find('.') + 1);
                EXPECT_NE(info.header.mapping.find(name), std::string::npos) << info.id << ": " << a.name;
            }
            const Stack back = stack_from_artist_parameters(info.id, p, s.exterior_ior);
            EXPECT_LT(largest_difference(artist_parameters(info.id, back), p), 2e-4) << info.id << " on " << s.name;
            // glTF's metal is its F0 alone: the stack comes back only where the base is a Lambertian
            const bool holds_the_stack =
                info.id.rfind("gltf-clearcoat", 0) != 0 || s.base().kind == InterfaceKind::Lambertian;
            if (holds_the_stack) {
                EXPECT_LT(stack_difference(back, s), 2e-3) << info.id << " on " << s.name;
                ++exact_stacks;
            }
            ++round_trips;
        }
    }
    // gltf x2 (grey, and the copper as F0), openpbr x4 x5 stacks ..., counted loosely: every production model ran
    EXPECT_GE(round_trips, 25);
    EXPECT_GE(exact_stacks, 20);
}

// The values, from the definitions' text: OpenPBR's coat_color "the square of the normal-incidence transmittance",
// perceptual roughness sqrt(alpha), F0 ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2), F82-tint's specular_color the
// conductor's F(1/7) over Schlick's at 1/7; Standard Surface's edge tint g = (n_max - n) / (n_max - n_min)
TEST(ArtistParameters, AreTheDefinitionsNumbers) {
    const Stack s = stacks()[3];   // tinted coat over gold
    const double n = 0.42 / 1.0, k = 2.35, f0 = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
    auto value = [](const std::vector<ArtistParameter>& ps, const std::string& name) {
        for (const ArtistParameter& p : ps)
            if (p.name == name) return double(p.value.y);
        ADD_FAILURE() << "no " << name;
        return 0.0;
    };
    const auto o = artist_parameters("openpbr", s);
    EXPECT_NEAR(value(o, "coat_color"), std::exp(-0.2), 1e-6);
    EXPECT_NEAR(value(o, "coat_roughness"), std::sqrt(0.2), 1e-6);
    EXPECT_NEAR(value(o, "coat_ior"), 1.45, 1e-6);
    EXPECT_NEAR(value(o, "base_color"), f0, 1e-5);
    // the conductor's exact Fresnel at mu = 1/7 (unpolarised), written out
    const double mu = 1.0 / 7, s2 = 1 - mu * mu, a = n * n - k * k - s2, r = std::sqrt(a * a + 4 * n * n * k * k);
    const double A2 = (r + a) / 2, A = std::sqrt(A2), rs = (r + mu * mu - 2 * A * mu) / (r + mu * mu + 2 * A * mu);
    const double rp = rs * (r * mu * mu + s2 * s2 - 2 * A * mu * s2) / (r * mu * mu + s2 * s2 + 2 * A * mu * s2);
    const double f82 = (rs + rp) / 2, schlick = f0 + (1 - f0) * std::pow(1 - mu, 5);
    EXPECT_NEAR(value(o, "specular_color"), std::min(1.0, f82 / schlick), 1e-4);
    const auto ss = artist_parameters("standard-surface", s);
    const double n_min = (1 - f0) / (1 + f0), n_max = (1 + std::sqrt(f0)) / (1 - std::sqrt(f0));
    EXPECT_NEAR(value(ss, "specular_color"), (n_max - n) / (n_max - n_min), 1e-4);
    EXPECT_NEAR(value(artist_parameters("materialx-layer", s), "dielectric_bsdf.roughness"), 0.2, 1e-7);
    // Cycles' Coat Tint, its colour at normal incidence (two passes), and its metal's Specular Tint as OpenPBR's F82
    const auto c = artist_parameters("cycles-principled", s);
    EXPECT_NEAR(value(c, "Coat Tint"), std::exp(-0.2), 1e-6);
    EXPECT_NEAR(value(c, "Specular Tint"), std::min(1.0, f82 / schlick), 1e-4);
    EXPECT_NEAR(value(artist_parameters("openpbr-adobe", s), "specular_roughness"), std::sqrt(0.4), 1e-6);
    // a research model takes the stack itself; a stack of another shape is refused
    EXPECT_TRUE(artist_parameters("ww-corrected", s).empty());
    EXPECT_THROW(artist_parameters("openpbr", stack("one", {coat(1.5f, 0.1f)})), std::invalid_argument);
    EXPECT_THROW(artist_parameters("no-such-model", s), std::invalid_argument);
}

}   // namespace
