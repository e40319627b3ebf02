// stack_spectral.h: a stack seen at three wavelengths, one per channel: what a spectral run traces (three bands per
// pass of the RGB walk, docs/SPECTRAL.md). A measured material takes its n and k at each wavelength and a key given as
// a spectrum its value there; a reflectance-like key given per RGB channel takes its colour's smooth spectrum (Jakob &
// Hanika 2019, rgb_uplift.h: KeyUplift); every other value is the same at every wavelength, so it must be one value
// (grey) in the stack.
#pragma once

#include "measured_materials.h"
#include "rgb_uplift.h"
#include "stack.h"

#include <array>
#include <string>
#include <vector>

namespace gonio {

// A layer key given per RGB channel (three values not all equal, not a spectrum) that a spectral run turns into a
// spectrum (uplift_rgb): a Lambertian albedo and a medium's scattering albedo (in [0, 1]) as they are; a medium's
// optical depth tau (>= 0) through its transmittance: the colour exp(-tau) per channel is uplifted to s and the
// optical depth at lambda is -ln s(lambda) (> 0: s < 1 everywhere, also where a channel's tau is 0).
struct KeyUplift {
    size_t layer = 0;   // index into Stack::layers
    std::string key;
    bool through_transmittance = false;   // optical_depth: s is exp(-tau)
    glm::vec3 given{0.0f};   // the key's RGB value
    RgbUplift uplift;   // of given, or of exp(-given)
    double value_at(double nm) const;   // the key's value at nm: s, or -ln s
};
// Whether a key of a layer of kind k is uplifted where it is RGB (albedo, scattering_albedo, optical_depth).
bool key_uplifts(InterfaceKind k, const std::string& key);
// The stack's RGB keys that a spectral run uplifts, in layer and key order, each solved (check uplift.reached).
std::vector<KeyUplift> stack_uplifts(const Stack& s);

// "" where the stack can be traced spectrally at first_nm..last_nm, else why not: a layer's RGB key that is neither
// one value nor uplifted (a conductor's n or k: no physical uplift), an uplift that does not reach its colour, a
// spectrum or a material that does not cover the range, a material's n or k changed from its reduction.
std::string spectral_refusal(const Stack& s, double first_nm, double last_nm);

// The stack with channel c at wavelength nm[c]: each measured material's n and k there, each key spectrum's value
// and each uplifted key's (stack_uplifts) value (throws std::out_of_range outside a table; std::logic_error where a
// dispersive key would take three wavelengths, or an uplift was refused or leaves its key's range); the rest as it
// is.
Stack stack_at_wavelengths(const Stack& s, const std::array<double, 3>& nm);

// Whether the stack disperses: a key that takes one value in every channel (a dielectric's IOR) given as a spectrum.
// A spectral run then traces one wavelength per pass (refraction sends each wavelength its own way).
bool stack_disperses(const Stack& s);

// The stack an RGB run of reduction r traces: each measured material's n and k per channel by r (a stack file's own
// RGB run uses RgbReduction::Dominant, as parsed). clipped: what the reduction could not reach (ConductorRgb::clipped).
Stack stack_reduced_to_rgb(const Stack& s, RgbReduction r, std::string& clipped);

}   // namespace gonio
