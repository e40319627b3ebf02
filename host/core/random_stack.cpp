#include "random_stack.h"
#include "stack_vocabulary.h"

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace gonio {

namespace {

// splitmix64 (Steele, Lea & Flood 2014): a fixed, portable sequence.
struct Rng {
    uint64_t s;
    uint64_t next() {
        uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }   // [0, 1)
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    double log_uniform(double lo, double hi) { return lo * std::exp(std::log(hi / lo) * uniform()); }
    int integer(int lo, int hi) { return lo + int(next() % uint64_t(hi - lo + 1)); }   // [lo, hi]
    bool chance(double p) { return uniform() < p; }
};

// 3 significant digits (0 stays 0).
float round3(double v) {
    if (v == 0) return 0.0f;
    char b[32];
    std::snprintf(b, sizeof b, "%.3g", v);
    return std::strtof(b, nullptr);
}

glm::vec3 rgb3(Rng& r, double lo, double hi) {
    return glm::vec3(round3(r.uniform(lo, hi)), round3(r.uniform(lo, hi)), round3(r.uniform(lo, hi)));
}

float roughness(Rng& r) {
    double u = r.uniform();
    if (u < 0.125) return 0.0f;
    if (u < 0.25) return 1e-4f;
    if (u < 0.375) return 1.0f;
    if (u < 0.7) return round3(r.log_uniform(1e-3, 1.0));
    return std::max(round3(r.uniform(0.0, 1.0)), kRoughnessRange.lo);   // 0 < alpha < 1e-4 is no valid roughness
}

glm::vec3 optical_depth(Rng& r, double hi) {
    const double lo = std::min(1e-3, hi / 10);
    double u = r.uniform();
    if (u < 1.0 / 3) return glm::vec3(0.0f);
    if (u < 1.0 / 3 + 1.0 / 12) return glm::vec3(round3(hi));
    if (r.chance(0.5)) return glm::vec3(round3(r.log_uniform(lo, hi)));
    return glm::vec3(round3(r.log_uniform(lo, hi)), round3(r.log_uniform(lo, hi)), round3(r.log_uniform(lo, hi)));
}

// A medium with optical depth scatters 1 in 3 times: single-scattering albedo uniform in [0, 0.99] (grey or RGB),
// Henyey-Greenstein g uniform in (-0.9, 0.9), 1 in 8 exactly 0 (isotropic). Drawn from its own stream, so that the
// other draws of a (seed, index) do not depend on it.
void scattering(Rng& r, Layer& L) {
    if (L.optical_depth == glm::vec3(0.0f) || !r.chance(1.0 / 3)) return;
    L.scattering_albedo = r.chance(0.5) ? glm::vec3(round3(r.uniform(0.0, 0.99))) : rgb3(r, 0.0, 0.99);
    L.phase_g = r.chance(0.125) ? 0.0f : round3(r.uniform(-0.9, 0.9));
}

// A scattering medium of SGGX microflakes (`phase`, `fibre_roughness`) 1 in 4 times, from a stream of its own.
void microflakes(Rng& r, Layer& L) {
    if (L.scattering_albedo == glm::vec3(0.0f) || !r.chance(0.25)) return;
    L.phase = r.chance(0.5) ? MediumPhase::SggxFibre : MediumPhase::SggxFlake;
    const double u = r.uniform();
    L.fibre_roughness = u < 0.125 ? 0.01f : u < 0.25 ? 1.0f : std::max(0.01f, round3(r.uniform(0.01, 1.0)));
    L.phase_g = 0.0f;
}

// A rough interface's microsurface (the word keys, ChoiceKey: `distribution`, `shadowing`, `microfacets`): each
// away from its default 1 in 6 times, from a stream of its own (the other draws do not depend on it). The walk on the
// microsurface is height-correlated by construction: a layer drawn with both keeps its default shadowing.
void microsurface(Rng& r, Layer& L) {
    if (!(L.roughness > 0.0f)) return;
    for (const ChoiceKey& c : choice_keys())
        if (c.of_kind(L.kind) && !c.medium && r.chance(1.0 / 6)) c.set(L, 1);
    if (L.microfacets == Microfacets::Multiple) L.shadowing = Shadowing::HeightCorrelated;
}

// A key of a kind with no draw of its own above: uniform in its span (the viewer's, else its valid range), per channel
// for an RGB key.
glm::vec3 drawn(Rng& r, const LayerKey& key) {
    const ParameterRange span = key.typical.hi > key.typical.lo ? key.typical : key.range;
    const double lo = key.open ? span.lo + 1e-3 * (span.hi - span.lo) : span.lo,
                 hi = key.open ? span.hi - 1e-3 * (span.hi - span.lo) : span.hi;
    if (key.shape == KeyShape::Number || key.one_value) return glm::vec3(round3(r.uniform(lo, hi)));
    return glm::vec3(round3(r.uniform(lo, hi)), round3(r.uniform(lo, hi)), round3(r.uniform(lo, hi)));
}

}   // namespace

void check_random_stack_options(const RandomStackOptions& o) {
    if (o.min_layers < 1 || o.max_layers > kMaxLayers || o.min_layers > o.max_layers)
        throw std::invalid_argument(
            "random stacks: layer counts must satisfy 1 <= min <= max <= " + std::to_string(kMaxLayers) + ", got " +
            std::to_string(o.min_layers) + ".." + std::to_string(o.max_layers));
    if (!(o.max_optical_depth > 0) || !std::isfinite(o.max_optical_depth))
        throw std::invalid_argument("random stacks: the largest optical depth must be a positive number");
    if (!o.lambertian_base && !o.conductor_base && !o.transmissive)
        throw std::invalid_argument("random stacks: no kind of base allowed (Lambertian, conductor, transmissive)");
}

std::string random_stack_toml(uint64_t seed, uint64_t index, const RandomStackOptions& o) {
    check_random_stack_options(o);
    Rng r{seed * 0xD1B54A32D192ED03ull ^ (index + 1) * 0x8CB92BA72F3D8DD7ull};
    r.next();
    Rng media{(seed + 0x632BE59BD9B4E019ull) * 0x9E3779B97F4A7C15ull ^ (index + 1) * 0xC2B2AE3D27D4EB4Full};
    media.next();
    Rng micro{(seed + 0x2545F4914F6CDD1Dull) * 0xBF58476D1CE4E5B9ull ^ (index + 1) * 0x94D049BB133111EBull};
    micro.next();
    Rng flakes{(seed + 0x9E6C63D0676A9A99ull) * 0xD6E8FEB86659FD93ull ^ (index + 1) * 0xA0761D6478BD642Full};
    flakes.next();
    Stack s;
    s.name = "random-" + std::to_string(seed) + "-" + std::to_string(index);
    s.description =
        "generated: gonio random-stack --seed " + std::to_string(seed) + " (stack " + std::to_string(index) + ")";
    s.exterior_ior = o.exterior_other_than_air && r.chance(0.2) ? round3(r.uniform(1.0, 2.0)) : 1.0f;

    int n;
    if (r.chance(1.0 / 6))
        n = r.integer(8, kMaxLayers);
    else {
        static const int small[8] = {1, 2, 2, 2, 3, 3, 4, 5};
        n = small[r.integer(0, 7)];
    }
    if (n < o.min_layers || n > o.max_layers) n = r.integer(o.min_layers, o.max_layers);

    std::vector<InterfaceKind> bases;
    if (o.lambertian_base) bases.push_back(InterfaceKind::Lambertian);
    if (o.conductor_base) bases.push_back(InterfaceKind::Conductor);
    if (o.transmissive) bases.push_back(InterfaceKind::Dielectric);
    for (const KindInfo& k : interface_kinds())   // an opaque base of another kind: drawn from its keys' spans
        if (k.opaque && k.kind != InterfaceKind::Lambertian && k.kind != InterfaceKind::Conductor)
            bases.push_back(k.kind);
    InterfaceKind base = bases[size_t(r.integer(0, int(bases.size()) - 1))];

    float above = s.exterior_ior;
    for (int i = 0; i < n; ++i) {
        Layer L;
        L.kind = i + 1 < n ? InterfaceKind::Dielectric : base;
        switch (L.kind) {
            case InterfaceKind::Dielectric: {
                L.roughness = roughness(r);
                double u = r.uniform();
                float ior = u < 0.125 ? above : u < 0.225 ? 3.0f : round3(r.uniform(1.0, 3.0));
                L.ior = glm::vec3(ior);
                if (i + 1 < n) L.optical_depth = optical_depth(r, o.max_optical_depth);
                if (i + 1 < n && o.scattering) scattering(media, L);
                if (i + 1 < n && o.scattering && o.microflakes) microflakes(flakes, L);
                if (o.microsurfaces) microsurface(micro, L);
                above = ior;
                break;
            }
            case InterfaceKind::Conductor:
                L.roughness = roughness(r);
                L.ior = rgb3(r, 0.1, 3.0);
                L.k = r.chance(0.125) ? glm::vec3(10.0f) : rgb3(r, 0.0, 10.0);
                if (o.microsurfaces) microsurface(micro, L);
                break;
            case InterfaceKind::Lambertian: {
                double u = r.uniform();
                L.albedo = u < 0.125 ? glm::vec3(1.0f) : u < 0.1875 ? glm::vec3(0.0f) : rgb3(r, 0.0, 1.0);
                break;
            }
            default:   // a kind drawn by its vocabulary alone
                for (const LayerKey* key : keys_of(L.kind)) key->set(L, drawn(r, *key));
        }
        s.layers.push_back(L);
    }
    validate_stack(s);
    return stack_to_toml(s);
}

Stack random_stack(uint64_t seed, uint64_t index, const RandomStackOptions& o) {
    std::string name = "random-" + std::to_string(seed) + "-" + std::to_string(index);
    return parse_stack_string(random_stack_toml(seed, index, o), name + ".toml");
}

}   // namespace gonio
