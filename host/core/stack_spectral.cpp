// stack_spectral.cpp: see stack_spectral.h.
#include "stack_spectral.h"
#include "measured_materials.h"
#include "stack_vocabulary.h"
#include "spectral_table.h"
#include "text_format.h"

#include <cmath>
#include <stdexcept>

namespace gonio {

namespace {

std::string rgb_text(glm::vec3 v) {
    return "[" + format_shortest(v.x) + ", " + format_shortest(v.y) + ", " + format_shortest(v.z) + "]";
}

// Whether layer y's key is given per RGB channel: three values not all equal, neither a spectrum nor a material's.
bool given_per_channel(const Layer& y, const LayerKey& key) {
    const std::string_view name(key.name);
    if (y.material_intact() && (name == "ior" || name == "k")) return false;
    const glm::vec3 v = key.get(y);
    return !y.intact_spectrum(key.name, v) && (v.x != v.y || v.y != v.z);
}

KeyUplift solve_uplift(size_t layer, const Layer& y, const LayerKey& key) {
    KeyUplift u;
    u.layer = layer;
    u.key = key.name;
    u.through_transmittance = std::string_view(key.name) == "optical_depth";
    u.given = key.get(y);
    std::array<double, 3> colour{};
    for (int c = 0; c < 3; ++c)
        colour[size_t(c)] = u.through_transmittance ? std::exp(-double(u.given[c])) : double(u.given[c]);
    u.uplift = uplift_rgb(colour);
    return u;
}

// Why a stack's RGB key is not uplifted ("" where it is, and reaches its colour).
std::string uplift_refusal(const KeyUplift& u) {
    if (u.uplift.reached) return "";
    const auto& r = u.uplift.rgb_reached;
    return std::string(u.key) + " " + rgb_text(u.given) + " is given per RGB channel and its " +
           (u.through_transmittance ? "transmittance exp(-optical_depth) " : "colour ") + "is not reached by a " +
           "smooth spectrum in [0, 1] (Jakob & Hanika 2019): the closest has linear sRGB [" + format_shortest(r[0]) +
           ", " + format_shortest(r[1]) + ", " + format_shortest(r[2]) + "], CIE76 difference " +
           format_shortest(float(u.uplift.delta_e76)) + " (at most " + format_shortest(float(kUpliftMaxDeltaE)) +
           "); give it as a spectrum (pairs [nm, value]) (docs/SPECTRAL.md)";
}

}   // namespace

double KeyUplift::value_at(double nm) const {
    const double s = uplift.spectrum.at(nm);
    return through_transmittance ? -std::log(s) : s;
}

bool key_uplifts(InterfaceKind k, const std::string& key) {
    return (k == InterfaceKind::Lambertian && key == "albedo") ||
           (k == InterfaceKind::Dielectric && (key == "scattering_albedo" || key == "optical_depth"));
}

std::vector<KeyUplift> stack_uplifts(const Stack& s) {
    std::vector<KeyUplift> out;
    for (size_t i = 0; i < s.layers.size(); ++i)
        for (const LayerKey* key : keys_of(s.layers[i].kind))
            if (key_uplifts(key->kind, key->name) && given_per_channel(s.layers[i], *key))
                out.push_back(solve_uplift(i, s.layers[i], *key));
    return out;
}

std::string spectral_refusal(const Stack& s, double first_nm, double last_nm) {
    auto covers = [&](const SpectralTable& t) { return t.first_nm() <= first_nm && t.last_nm() >= last_nm; };
    auto range = [](const SpectralTable& t) {
        return format_shortest(float(t.first_nm())) + " to " + format_shortest(float(t.last_nm())) + " nm";
    };
    const std::string needs = "; the run reads it from " + format_shortest(float(first_nm)) + " to " +
                              format_shortest(float(last_nm)) + " nm (the bands' centres)";
    for (size_t i = 0; i < s.layers.size(); ++i) {
        const Layer& y = s.layers[i];
        const std::string layer = "layer " + std::to_string(i + 1) + "'s ";
        const bool material = y.material_intact();
        if (!y.material.empty() && !material)
            return layer + "ior or k was changed from material " + y.material +
                   "'s RGB reduction (a sweep's or a fit's value): a spectral run would not know their spectra";
        if (material) {
            const SpectralTable& t = embedded_spectral_table(find_measured_conductor(y.material)->file);
            if (!covers(t)) return layer + "material " + y.material + " is measured from " + range(t) + needs;
        }
        for (const LayerKey* key : keys_of(y.kind)) {
            if (const KeySpectrum* sp = y.intact_spectrum(key->name, key->get(y))) {
                if (!covers(sp->table)) return layer + key->name + " spectrum covers " + range(sp->table) + needs;
                continue;
            }
            if (!given_per_channel(y, *key)) continue;
            if (key_uplifts(y.kind, key->name)) {
                if (std::string why = uplift_refusal(solve_uplift(i, y, *key)); !why.empty()) return layer + why;
                continue;
            }
            return layer + key->name + " is given per RGB channel (" + rgb_text(key->get(y)) +
                   "): a spectral run takes one value for it (the same at every wavelength), a spectrum (pairs [nm, "
                   "value]) or, for a conductor, a measured material (material = \"Au\": " +
                   measured_conductor_names() +
                   "); it is not uplifted from RGB: an uplift gives a smooth spectrum in [0, 1] of the colour, and " +
                   "an index of refraction or an extinction coefficient is neither in [0, 1] nor seen as a colour " +
                   "(docs/SPECTRAL.md)";
        }
    }
    return "";
}

bool stack_disperses(const Stack& s) {
    for (const Layer& y : s.layers)
        for (const KeySpectrum& sp : y.spectra) {
            const LayerKey* key = find_layer_key(y.kind, sp.key);
            if (key->one_value && y.intact_spectrum(sp.key, key->get(y))) return true;
        }
    return false;
}

Stack stack_at_wavelengths(const Stack& s, const std::array<double, 3>& nm) {
    Stack out = s;
    for (Layer& y : out.layers) {
        if (y.material_intact()) {
            const MeasuredConductor& m = *find_measured_conductor(y.material);
            for (int c = 0; c < 3; ++c) {
                y.ior[c] = float(measured_n(m, nm[size_t(c)]));
                y.k[c] = float(measured_k(m, nm[size_t(c)]));
            }
        }
        for (const KeySpectrum& sp : s.layers[size_t(&y - out.layers.data())].spectra) {
            const LayerKey* key = find_layer_key(y.kind, sp.key);
            if (!y.intact_spectrum(sp.key, key->get(y))) continue;
            if (key->one_value && (nm[0] != nm[1] || nm[1] != nm[2]))
                throw std::logic_error(std::string("stack_at_wavelengths: the dispersive ") + key->name +
                                       " at three wavelengths in one pass");
            glm::vec3 v;
            for (int c = 0; c < 3; ++c) v[c] = float(sp.table.at(0, nm[size_t(c)]));
            key->set(y, v);
        }
    }
    for (const KeyUplift& u : stack_uplifts(s)) {
        if (!uplift_refusal(u).empty())
            throw std::logic_error("stack_at_wavelengths: layer " + std::to_string(u.layer + 1) + "'s " +
                                   uplift_refusal(u));
        Layer& y = out.layers[u.layer];
        const LayerKey* key = find_layer_key(y.kind, u.key);
        glm::vec3 v;
        for (int c = 0; c < 3; ++c) v[c] = float(u.value_at(nm[size_t(c)]));
        for (int c = 0; c < 3; ++c)
            if (!(v[c] >= key->range.lo && v[c] <= key->range.hi))
                throw std::logic_error("stack_at_wavelengths: layer " + std::to_string(u.layer + 1) + "'s uplifted " +
                                       u.key + " is " + format_shortest(v[c]) + " at " +
                                       format_shortest(float(nm[size_t(c)])) + " nm, outside " + key->range_text());
        key->set(y, v);
    }
    return out;
}

Stack stack_reduced_to_rgb(const Stack& s, RgbReduction r, std::string& clipped) {
    Stack out = s;
    clipped.clear();
    for (Layer& y : out.layers) {
        if (y.material.empty()) continue;
        const ConductorRgb c = conductor_rgb(*find_measured_conductor(y.material), r);
        y.ior = glm::vec3(float(c.n[0]), float(c.n[1]), float(c.n[2]));
        y.k = glm::vec3(float(c.k[0]), float(c.k[1]), float(c.k[2]));
        if (!c.clipped.empty()) clipped += (clipped.empty() ? "" : "; ") + c.clipped;
    }
    return out;
}

}   // namespace gonio
