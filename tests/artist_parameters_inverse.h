// artist_parameters_inverse.h: the stack a production model's artist parameters stand for, the inverse of each
// model's mapping (host/models/artist_parameters.h runs the mappings, the GONIO_MODEL_ARTIST_PARAMETERS hooks of
// shaders/lib/models/builtin/), written here from the definitions' text and not from the code under test, for the
// round trip of tests/test_artist_parameters.cpp. Where a model's parameters hold less than the stack (glTF's and
// Enterprise PBR's metal: F0 alone), the conductor of that F0 with k = 0 (one of many: its parameters are the same).
#pragma once
#include "artist_parameters.h"
#include "stack.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace gonio::test {

inline std::string base_model_of(const std::string& id) { return id.substr(0, id.find('+')); }

// A conductor's exact unpolarised Fresnel reflectance at cosine mu (n, k relative to the medium above)
inline double conductor_fresnel(double mu, double n, double k) {
    const double s2 = 1 - mu * mu, a = n * n - k * k - s2, r = std::sqrt(a * a + 4 * n * n * k * k);
    const double A = std::sqrt((r + a) / 2);
    const double rs = (r + mu * mu - 2 * A * mu) / (r + mu * mu + 2 * A * mu);
    const double rp = rs * (r * mu * mu + s2 * s2 - 2 * A * mu * s2) / (r * mu * mu + s2 * s2 + 2 * A * mu * s2);
    return (rs + rp) / 2;
}

// n and k of the conductor whose normal-incidence reflectance is f0 and whose F(1/7) is tint times Schlick's there
// (OpenPBR's F82-tint inverted): on the curve of reflectance f0, k^2 = (f0 (n + 1)^2 - (n - 1)^2) / (1 - f0) for n in
// Gulbrandsen's bounds [n_min, n_max], the n whose tint is closest, by a scan and a golden-section refinement
inline void conductor_of_f82(double f0, double tint, double& n_out, double& k_out) {
    const double n_lo = (1 - f0) / (1 + f0), n_hi = (1 + std::sqrt(f0)) / (1 - std::sqrt(f0));
    const double mu_b = 1.0 / 7, schlick = f0 + (1 - f0) * std::pow(1 - mu_b, 5);
    auto k_of = [&](double n) {
        return std::sqrt(std::max(0.0, (f0 * (n + 1) * (n + 1) - (n - 1) * (n - 1)) / (1 - f0)));
    };
    auto miss = [&](double n) {
        return std::fabs(std::min(1.0, conductor_fresnel(mu_b, n, k_of(n)) / schlick) - tint);
    };
    const int steps = 4000;
    double best = n_lo, best_miss = miss(n_lo);
    for (int i = 1; i <= steps; ++i) {
        const double n = n_lo + (n_hi - n_lo) * i / steps, m = miss(n);
        if (m < best_miss) best = n, best_miss = m;
    }
    double a = std::max(n_lo, best - (n_hi - n_lo) / steps), b = std::min(n_hi, best + (n_hi - n_lo) / steps);
    const double g = (std::sqrt(5.0) - 1) / 2;
    for (int i = 0; i < 60; ++i) {
        const double c = b - g * (b - a), d = a + g * (b - a);
        if (miss(c) < miss(d))
            b = d;
        else
            a = c;
    }
    n_out = (a + b) / 2;
    k_out = k_of(n_out);
}

inline Layer lambertian_layer(glm::vec3 albedo) {
    Layer L;
    L.kind = InterfaceKind::Lambertian;
    L.albedo = albedo;
    return L;
}
inline Layer conductor_layer(glm::vec3 n, glm::vec3 k, float alpha) {
    Layer L;
    L.kind = InterfaceKind::Conductor;
    L.ior = n;
    L.k = k;
    L.roughness = alpha;
    return L;
}

// Gulbrandsen's bounds on n for a reflectivity r (Standard Surface's metal)
inline glm::vec3 gulbrandsen_n_min(glm::vec3 r) { return (1.0f - r) / (1.0f + r); }
inline glm::vec3 gulbrandsen_n_max(glm::vec3 r) { return (1.0f + glm::sqrt(r)) / (1.0f - glm::sqrt(r)); }

// The metal base of a production model's parameters (base colour c, exterior IOR ext): its n and k as the model's
// definition inverts its colours, and its roughness
template <class Get>
Layer metal_base_of(const std::string& id, const Get& get, glm::vec3 c, float ext) {
    glm::vec3 n, k;
    if (id == "standard-surface") {   // Gulbrandsen's inverse, as reference/standard_surface.osl computes it
        n = glm::mix(gulbrandsen_n_max(c), gulbrandsen_n_min(c), get("specular_color"));
        k = glm::sqrt(glm::max(glm::vec3(0.0f), ((n + 1.0f) * (n + 1.0f) * c - (n - 1.0f) * (n - 1.0f)) / (1.0f - c)));
    } else if (id == "openpbr" || id == "openpbr-adobe" || id == "cycles-principled") {   // the same F82-tint metal
        const glm::vec3 t = get(id == "cycles-principled" ? "Specular Tint" : "specular_color");
        for (int ch = 0; ch < 3; ++ch) {
            double nn, kk;
            conductor_of_f82(c[ch], t[ch], nn, kk);
            n[ch] = float(nn);
            k[ch] = float(kk);
        }
    } else {   // glTF: F0 alone; the conductor of that F0 with k = 0
        n = (1.0f + glm::sqrt(c)) / (1.0f - glm::sqrt(c));
        k = glm::vec3(0.0f);
    }
    const char* roughness_key = id == "gltf-clearcoat"      ? "roughness"
                                : id == "cycles-principled" ? "Roughness"
                                                            : "specular_roughness";
    return conductor_layer(n * ext, k * ext, std::pow(get(roughness_key).x, 2.0f));
}

// The coat a model's parameters stand for: its IOR (relative), alpha, optical depth
template <class Get>
Layer coat_of_parameters(const std::string& id, const Get& get, float exterior_ior) {
    Layer coat;
    coat.kind = InterfaceKind::Dielectric;
    float eta = 1.5f, alpha = 0.0f;
    if (id == "gltf-clearcoat")
        alpha = std::pow(get("clearcoatRoughness").x, 2.0f);
    else if (id == "enterprise-pbr")
        alpha = std::pow(get("clearcoat roughness").x, 2.0f);
    else if (id == "openpbr" || id == "openpbr-adobe")
        eta = get("coat_ior").x, alpha = std::pow(get("coat_roughness").x, 2.0f);
    else if (id == "cycles-principled")
        eta = get("Coat IOR").x, alpha = std::pow(get("Coat Roughness").x, 2.0f);
    else if (id == "interfaced-lambertian")
        eta = get("n").x, alpha = get("alpha").x;
    else if (id == "standard-surface")
        eta = get("coat_IOR").x, alpha = std::pow(get("coat_roughness").x, 2.0f);
    else if (id == "materialx-layer")
        eta = get("dielectric_bsdf.ior").x, alpha = get("dielectric_bsdf.roughness").x;
    else
        throw std::invalid_argument(id + " has no artist parameters (it takes the stack itself)");
    if (id == "openpbr" || id == "openpbr-adobe" || id == "standard-surface")
        coat.optical_depth = -0.5f * glm::log(get("coat_color"));
    if (id == "cycles-principled") coat.optical_depth = -0.5f * glm::log(get("Coat Tint"));
    coat.ior = glm::vec3(eta * exterior_ior);
    coat.roughness = alpha;
    return coat;
}

// The stack the parameters stand for, in an exterior of IOR exterior_ior. Throws std::invalid_argument for a missing
// parameter.
inline Stack stack_from_artist_parameters(const std::string& model_id, const std::vector<ArtistParameter>& ps,
                                          float exterior_ior) {
    const std::string id = base_model_of(model_id);
    auto has = [&](const std::string& name) {
        for (const ArtistParameter& p : ps)
            if (p.name == name) return true;
        return false;
    };
    auto get = [&](const std::string& name) {
        for (const ArtistParameter& p : ps)
            if (p.name == name) return p.value;
        throw std::invalid_argument(model_id + ": no parameter '" + name + "'");
    };
    Stack s;
    s.name = model_id + "-parameters";
    s.exterior_ior = exterior_ior;
    s.layers.push_back(coat_of_parameters(id, get, exterior_ior));
    const float ext = exterior_ior;
    if (id == "materialx-layer") {
        s.layers.push_back(has("conductor_bsdf.ior") ? conductor_layer(get("conductor_bsdf.ior") * ext,
                                                                       get("conductor_bsdf.extinction") * ext,
                                                                       get("conductor_bsdf.roughness").x)
                                                     : lambertian_layer(get("oren_nayar_diffuse_bsdf.color")));
        return s;
    }
    if (id == "enterprise-pbr" || id == "interfaced-lambertian") {
        s.layers.push_back(lambertian_layer(get(id == "enterprise-pbr" ? "albedo" : "k_d")));
        return s;
    }
    const bool openpbr_like = id == "openpbr" || id == "openpbr-adobe";
    const char* metal_key = openpbr_like                ? "base_metalness"
                            : id == "standard-surface"  ? "metalness"
                            : id == "cycles-principled" ? "Metallic"
                                                        : "metallic";
    const char* colour_key = id == "gltf-clearcoat"      ? "baseColor"
                             : id == "cycles-principled" ? "Base Color"
                                                         : "base_color";
    const glm::vec3 c = get(colour_key);
    // a dielectric base: a specular lobe on (OpenPBR's specular_weight, glTF's specularFactor, Standard Surface's
    // specular), its IOR and roughness, over the diffuse
    const char* specular_key = id == "openpbr"            ? "specular_weight"
                               : id == "gltf-clearcoat"   ? "specularFactor"
                               : id == "standard-surface" ? "specular"
                                                          : nullptr;
    const bool specular_on = specular_key && has(specular_key) && get(specular_key).x > 0.0f;
    if (get(metal_key).x != 1.0f && specular_on) {
        Layer interface;
        interface.kind = InterfaceKind::Dielectric;
        const char* ior_key = id == "openpbr" ? "specular_ior" : id == "gltf-clearcoat" ? "ior" : "specular_IOR";
        interface.ior = glm::vec3(get(ior_key).x * exterior_ior);
        interface.roughness = std::pow(get(id == "gltf-clearcoat" ? "roughness" : "specular_roughness").x, 2.0f);
        s.layers.push_back(interface);
        s.layers.push_back(lambertian_layer(c));
        return s;
    }
    s.layers.push_back(get(metal_key).x != 1.0f ? lambertian_layer(c) : metal_base_of(id, get, c, ext));
    return s;
}

}   // namespace gonio::test
