#include "artist_parameters.h"

#include "model_twin.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace gonio {

namespace {

std::string base_of(const std::string& id) { return id.substr(0, id.find('+')); }

ArtistParameter scalar(const std::string& name, float v) { return {name, glm::vec3(v), false}; }
ArtistParameter colour(const std::string& name, glm::vec3 v) { return {name, v, true}; }

// The stack's coat and base as the models' twins read them (CoatParams, models/common.glsl): eta the coat's IOR
// relative to the exterior, a conductor's n and k relative to the coat
CoatParams coat_of(const Stack& s) {
    CoatParams p{};
    const Layer &coat = s.layers[0], &base = s.layers[1];
    p.alpha0 = coat.roughness;
    p.eta = coat.ior.x / s.exterior_ior;
    p.tau = coat.optical_depth;
    p.alpha1 = base.roughness;
    p.base_kind = base.kind == InterfaceKind::Lambertian ? KIND_LAMBERTIAN : KIND_CONDUCTOR;
    p.base_c0 = base.kind == InterfaceKind::Lambertian ? base.albedo : base.ior / coat.ior.x;
    p.base_c1 = base.kind == InterfaceKind::Lambertian ? glm::vec3(0.0f) : base.k / coat.ior.x;
    return p;
}

const ArtistParameter& find(const std::vector<ArtistParameter>& ps, const std::string& model, const std::string& name) {
    for (const ArtistParameter& p : ps)
        if (p.name == name) return p;
    throw std::invalid_argument(model + ": no parameter '" + name + "'");
}

// n and k of the conductor whose normal-incidence reflectance is f0 and whose F(1/7) is tint times Schlick's there
// (OpenPBR's F82-tint, the inverse of metal_f82_tint): on the curve of reflectance f0, k^2 = (f0 (n + 1)^2 -
// (n - 1)^2) / (1 - f0) for n in [n_min, n_max] (Gulbrandsen's bounds), the n whose tint is closest, by a scan and a
// golden-section refinement, per channel
glm::vec2 conductor_of_f82(float f0, float tint) {
    const float n_lo = (1.0f - f0) / (1.0f + f0), n_hi = (1.0f + std::sqrt(f0)) / (1.0f - std::sqrt(f0));
    const float mu_b = 1.0f / 7.0f, xb = 1.0f - mu_b;
    const float fs_b = f0 + (1.0f - f0) * std::pow(xb, 5.0f);
    auto k_of = [&](double n) {
        return float(std::sqrt(std::max(0.0, (f0 * (n + 1) * (n + 1) - (n - 1) * (n - 1)) / (1.0 - f0))));
    };
    auto miss = [&](double n) {
        const float t = std::min(1.0f, fresnel_conductor(mu_b, vec3(float(n)), vec3(k_of(n))).x / fs_b);
        return std::fabs(double(t) - tint);
    };
    const int steps = 4000;
    double best = n_lo, best_miss = miss(n_lo);
    for (int i = 1; i <= steps; ++i) {
        const double n = n_lo + (n_hi - n_lo) * i / steps;
        const double m = miss(n);
        if (m < best_miss) best = n, best_miss = m;
    }
    double a = std::max(double(n_lo), best - (n_hi - n_lo) / steps),
           b = std::min(double(n_hi), best + (n_hi - n_lo) / steps);
    const double g = (std::sqrt(5.0) - 1) / 2;
    for (int i = 0; i < 60; ++i) {
        const double c = b - g * (b - a), d = a + g * (b - a);
        if (miss(c) < miss(d))
            b = d;
        else
            a = c;
    }
    const double n = (a + b) / 2;
    return {float(n), k_of(n)};
}

Layer lambertian_layer(glm::vec3 albedo) {
    Layer L;
    L.kind = InterfaceKind::Lambertian;
    L.albedo = albedo;
    return L;
}

Layer conductor_layer(glm::vec3 n, glm::vec3 k, float alpha) {
    Layer L;
    L.kind = InterfaceKind::Conductor;
    L.ior = n;
    L.k = k;
    L.roughness = alpha;
    return L;
}

// The parameters of a dielectric base under the coat (three layers): the coat's as over a Lambertian, then the base's
// specular interface (its IOR relative to the exterior, sqrt of its roughness) and its diffuse
std::vector<ArtistParameter> dielectric_base_parameters(const std::string& model_id, const Stack& s) {
    const std::string id = base_of(model_id);
    const Layer &coat = s.layers[0], &interface = s.layers[1], &diffuse = s.layers[2];
    const float eta = coat.ior.x / s.exterior_ior, ior = interface.ior.x / s.exterior_ior;
    const float r_coat = std::sqrt(coat.roughness), r_base = std::sqrt(interface.roughness);
    const glm::vec3 coat_color = glm::exp(-2.0f * coat.optical_depth);
    if (id == "openpbr")
        return {scalar("coat_weight", 1),
                scalar("coat_darkening", 1),
                scalar("coat_ior", eta),
                scalar("coat_roughness", r_coat),
                colour("coat_color", coat_color),
                scalar("base_metalness", 0),
                colour("base_color", diffuse.albedo),
                scalar("specular_weight", 1),
                scalar("specular_ior", ior),
                scalar("specular_roughness", r_base)};
    if (id == "gltf-clearcoat")
        return {scalar("clearcoat", 1),
                scalar("clearcoatRoughness", r_coat),
                scalar("metallic", 0),
                colour("baseColor", diffuse.albedo),
                scalar("ior", ior),
                scalar("specularFactor", 1),
                colour("specularColorFactor", glm::vec3(1.0f)),
                scalar("roughness", r_base)};
    if (id == "standard-surface")
        return {scalar("coat", 1),
                scalar("coat_IOR", eta),
                scalar("coat_roughness", r_coat),
                colour("coat_color", coat_color),
                scalar("coat_affect_color", 0),
                scalar("coat_affect_roughness", 0),
                scalar("base", 1),
                colour("base_color", diffuse.albedo),
                scalar("diffuse_roughness", 0),
                scalar("metalness", 0),
                scalar("specular", 1),
                colour("specular_color", glm::vec3(1.0f)),
                scalar("specular_IOR", ior),
                scalar("specular_roughness", r_base)};
    throw std::invalid_argument(model_id + " takes one dielectric coat over a Lambertian or a conductor");
}

}   // namespace

bool model_takes_artist_colours(const std::string& model_id) {
    const std::string id = base_of(model_id);
    return id == "gltf-clearcoat" || id == "openpbr" || id == "enterprise-pbr" || id == "standard-surface" ||
           id == "materialx-layer" || id == "cycles-principled" || id == "openpbr-adobe" ||
           id == "interfaced-lambertian";
}

std::vector<ArtistParameter> artist_parameters(const std::string& model_id, const Stack& s) {
    const std::string id = base_of(model_id);
    if (!model_takes_artist_colours(model_id)) return {};
    // a dielectric base: the coat over a dielectric interface over a Lambertian (a production model's dielectric
    // base, "specular over diffuse")
    const bool dielectric_base = s.layers.size() == 3 && s.layers[0].kind == InterfaceKind::Dielectric &&
                                 s.layers[1].kind == InterfaceKind::Dielectric &&
                                 s.layers[2].kind == InterfaceKind::Lambertian;
    if (dielectric_base) return dielectric_base_parameters(model_id, s);
    if (s.layers.size() != 2 || s.layers[0].kind != InterfaceKind::Dielectric ||
        (s.base().kind != InterfaceKind::Lambertian && s.base().kind != InterfaceKind::Conductor))
        throw std::invalid_argument(model_id + " takes one dielectric coat over a Lambertian or a conductor");
    const CoatParams p = coat_of(s);
    const bool metal = p.base_kind == KIND_CONDUCTOR;
    const glm::vec3 n = p.base_c0 * p.eta, k = p.base_c1 * p.eta;   // the conductor's, relative to the exterior
    const glm::vec3 f0 = metal ? glm::vec3(conductor_normal_reflectance(n, k)) : glm::vec3(0.0f);
    const float r_coat = std::sqrt(p.alpha0), r_base = std::sqrt(p.alpha1);
    const glm::vec3 coat_color = glm::exp(-2.0f * p.tau);
    std::vector<ArtistParameter> out;
    if (id == "gltf-clearcoat") {
        out = {scalar("clearcoat", 1), scalar("clearcoatRoughness", r_coat)};
        if (metal)
            out.insert(out.end(), {scalar("metallic", 1), colour("baseColor", f0), scalar("roughness", r_base)});
        else
            out.insert(out.end(), {scalar("metallic", 0), colour("baseColor", p.base_c0), scalar("specularFactor", 0)});
    } else if (id == "openpbr") {
        out = {scalar("coat_weight", 1), scalar("coat_darkening", 1), scalar("coat_ior", p.eta),
               scalar("coat_roughness", r_coat), colour("coat_color", coat_color)};
        if (metal)
            out.insert(out.end(),
                       {scalar("base_metalness", 1), colour("base_color", f0),
                        colour("specular_color", metal_f82_tint(p, f0)), scalar("specular_roughness", r_base)});
        else
            out.insert(out.end(), {scalar("base_metalness", 0), colour("base_color", p.base_c0),
                                   scalar("specular_weight", 0), scalar("specular_roughness", 0)});
    } else if (id == "openpbr-adobe") {
        out = {scalar("coat_weight", 1),         scalar("coat_darkening", 1),      scalar("coat_ior", p.eta),
               scalar("coat_roughness", r_coat), colour("coat_color", coat_color), scalar("fuzz_weight", 0)};
        if (metal)
            out.insert(out.end(), {scalar("base_metalness", 1), colour("base_color", f0),
                                   colour("specular_color", metal_f82_tint(p, f0)), scalar("specular_weight", 1),
                                   scalar("specular_roughness", r_base)});
        else
            out.insert(out.end(), {scalar("base_metalness", 0), colour("base_color", p.base_c0),
                                   scalar("base_weight", 1), scalar("specular_weight", 0),
                                   scalar("specular_roughness", 0), scalar("base_diffuse_roughness", 0)});
    } else if (id == "interfaced-lambertian") {   // Meneveaux et al.'s parameters: the binder's index, alpha, k_d
        out = {scalar("n", p.eta), scalar("alpha", p.alpha0)};
        if (metal) throw std::invalid_argument(model_id + " takes a Lambertian base");
        out.push_back(colour("k_d", p.base_c0));
    } else if (id == "cycles-principled") {
        out = {scalar("Coat Weight", 1), scalar("Coat IOR", p.eta), scalar("Coat Roughness", r_coat),
               colour("Coat Tint", coat_color)};
        if (metal)
            out.insert(out.end(), {scalar("Metallic", 1), colour("Base Color", f0),
                                   colour("Specular Tint", metal_f82_tint(p, f0)), scalar("Roughness", r_base)});
        else
            out.insert(out.end(), {scalar("Metallic", 0), colour("Base Color", p.base_c0),
                                   scalar("Specular IOR Level", 0), scalar("Diffuse Roughness", 0)});
    } else if (id == "enterprise-pbr") {
        out = {scalar("clearcoat", 1),     scalar("clearcoat roughness", r_coat),
               scalar("metallic", 0),      scalar("transparency", 0),
               scalar("translucency", 0),  scalar("specular", 0),
               colour("albedo", p.base_c0)};
        if (metal) throw std::invalid_argument(model_id + " takes a Lambertian base");
    } else if (id == "standard-surface") {
        out = {scalar("coat", 1),
               scalar("coat_IOR", p.eta),
               scalar("coat_roughness", r_coat),
               colour("coat_color", coat_color),
               scalar("coat_affect_color", 0),
               scalar("coat_affect_roughness", 0)};
        if (metal) {
            const glm::vec3 lo = standard_surface_n_min(f0), hi = standard_surface_n_max(f0);
            out.insert(out.end(),
                       {scalar("metalness", 1), colour("base_color", f0),
                        colour("specular_color", (hi - n) / (hi - lo)), scalar("specular_roughness", r_base)});
        } else {
            out.insert(out.end(), {scalar("base", 1), colour("base_color", p.base_c0), scalar("diffuse_roughness", 0),
                                   scalar("specular", 0), scalar("metalness", 0)});
        }
    } else {   // materialx-layer: layer(top = dielectric_bsdf, base = oren_nayar_diffuse_bsdf | conductor_bsdf)
        out = {scalar("dielectric_bsdf.weight", 1), colour("dielectric_bsdf.tint", glm::vec3(1.0f)),
               scalar("dielectric_bsdf.ior", p.eta), scalar("dielectric_bsdf.roughness", p.alpha0)};
        if (metal)
            out.insert(out.end(), {colour("conductor_bsdf.ior", n), colour("conductor_bsdf.extinction", k),
                                   scalar("conductor_bsdf.roughness", p.alpha1)});
        else
            out.insert(out.end(), {colour("oren_nayar_diffuse_bsdf.color", p.base_c0),
                                   scalar("oren_nayar_diffuse_bsdf.roughness", 0)});
    }
    return out;
}

namespace {

// The metal base of a production model's parameters (base colour c, exterior IOR ext): its n and k as the model's
// definition inverts its colours, and its roughness
template <class Get>
Layer metal_base_from_artist_parameters(const std::string& id, const Get& get, glm::vec3 c, float ext) {
    glm::vec3 n, k;
    if (id == "standard-surface") {   // Gulbrandsen's inverse, as reference/standard_surface.osl computes it
        const glm::vec3 g = get("specular_color");
        n = glm::mix(standard_surface_n_max(c), standard_surface_n_min(c), g);
        k = glm::sqrt(glm::max(glm::vec3(0.0f), ((n + 1.0f) * (n + 1.0f) * c - (n - 1.0f) * (n - 1.0f)) / (1.0f - c)));
    } else if (id == "openpbr" || id == "openpbr-adobe" || id == "cycles-principled") {   // the same F82-tint metal
        const glm::vec3 t = get(id == "cycles-principled" ? "Specular Tint" : "specular_color");
        for (int ch = 0; ch < 3; ++ch) {
            const glm::vec2 nk = conductor_of_f82(c[ch], t[ch]);
            n[ch] = nk.x;
            k[ch] = nk.y;
        }
    } else {   // glTF: F0 alone; the conductor of that F0 with k = 0
        n = (1.0f + glm::sqrt(c)) / (1.0f - glm::sqrt(c));
        k = glm::vec3(0.0f);
    }
    const char* roughness_key = id == "gltf-clearcoat"      ? "roughness"
                                : id == "cycles-principled" ? "Roughness"
                                                            : "specular_roughness";
    const float r = std::pow(get(roughness_key).x, 2.0f);
    return conductor_layer(n * ext, k * ext, r);
}

}   // namespace

Stack stack_from_artist_parameters(const std::string& model_id, const std::vector<ArtistParameter>& ps,
                                   float exterior_ior) {
    const std::string id = base_of(model_id);
    auto get = [&](const std::string& name) { return find(ps, model_id, name).value; };
    Stack s;
    s.name = model_id + "-parameters";
    s.exterior_ior = exterior_ior;
    Layer coat;
    coat.kind = InterfaceKind::Dielectric;
    float eta = 1.5f, alpha = 0.0f;
    glm::vec3 tau(0.0f);
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
        throw std::invalid_argument(model_id + " has no artist parameters (it takes the stack itself)");
    if (id == "openpbr" || id == "openpbr-adobe" || id == "standard-surface") tau = -0.5f * glm::log(get("coat_color"));
    if (id == "cycles-principled") tau = -0.5f * glm::log(get("Coat Tint"));
    coat.ior = glm::vec3(eta * exterior_ior);
    coat.roughness = alpha;
    coat.optical_depth = tau;
    s.layers.push_back(coat);

    const float ext = exterior_ior;
    if (id == "materialx-layer") {
        bool metal = false;
        for (const ArtistParameter& p : ps) metal |= p.name == "conductor_bsdf.ior";
        s.layers.push_back(metal ? conductor_layer(get("conductor_bsdf.ior") * ext,
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
    bool specular_on = false;
    for (const ArtistParameter& a : ps) specular_on |= specular_key && a.name == specular_key && a.value.x > 0.0f;
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
    if (get(metal_key).x != 1.0f) {
        s.layers.push_back(lambertian_layer(c));
        return s;
    }
    s.layers.push_back(metal_base_from_artist_parameters(id, get, c, ext));
    return s;
}

std::string format_artist_parameters(const std::vector<ArtistParameter>& ps) {
    std::string out;
    char buf[128];
    for (const ArtistParameter& p : ps) {
        if (p.colour)
            std::snprintf(buf, sizeof buf, "%s (%.4g, %.4g, %.4g)", p.name.c_str(), p.value.x, p.value.y, p.value.z);
        else
            std::snprintf(buf, sizeof buf, "%s %.4g", p.name.c_str(), p.value.x);
        out += (out.empty() ? "" : ", ") + std::string(buf);
    }
    return out;
}

}   // namespace gonio
