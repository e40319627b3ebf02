// stack_spectral.cpp: see stack_spectral.h.
#include "stack_spectral.h"
#include "measured_materials.h"
#include "stack_vocabulary.h"
#include "spectral_table.h"
#include "text_format.h"

#include <stdexcept>

namespace gonio {

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
            const std::string_view name(key->name);
            if (material && (name == "ior" || name == "k")) continue;
            const glm::vec3 v = key->get(y);
            if (const KeySpectrum* sp = y.intact_spectrum(key->name, v)) {
                if (!covers(sp->table)) return layer + key->name + " spectrum covers " + range(sp->table) + needs;
                continue;
            }
            if (v.x != v.y || v.y != v.z)
                return layer + key->name + " is given per RGB channel ([" + format_shortest(v.x) + ", " +
                       format_shortest(v.y) + ", " + format_shortest(v.z) +
                       "]): a spectral run takes one value for it (the same at every wavelength), a spectrum "
                       "(pairs [nm, value]) or, for a conductor, a measured material (material = \"Au\": " +
                       measured_conductor_names() + "); an RGB value is not turned into a spectrum (docs/SPECTRAL.md)";
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
