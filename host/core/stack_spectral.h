// stack_spectral.h: a stack seen at three wavelengths, one per channel: what a spectral run traces (three bands per
// pass of the RGB walk, docs/SPECTRAL.md). A measured material takes its n and k at each wavelength and a key given as
// a spectrum its value there; every other value is the same at every wavelength, so it must be one value (grey) in the
// stack: an RGB value is not turned into a spectrum.
#pragma once

#include "measured_materials.h"
#include "stack.h"

#include <array>
#include <string>

namespace gonio {

// "" where the stack can be traced spectrally at first_nm..last_nm, else why not: a layer's RGB key that is not one
// value, a spectrum or a material that does not cover the range, a material's n or k changed from its reduction.
std::string spectral_refusal(const Stack& s, double first_nm, double last_nm);

// The stack with channel c at wavelength nm[c]: each measured material's n and k there and each key spectrum's value
// (throws std::out_of_range outside a table; std::logic_error where a dispersive key would take three wavelengths);
// the rest as it is.
Stack stack_at_wavelengths(const Stack& s, const std::array<double, 3>& nm);

// Whether the stack disperses: a key that takes one value in every channel (a dielectric's IOR) given as a spectrum.
// A spectral run then traces one wavelength per pass (refraction sends each wavelength its own way).
bool stack_disperses(const Stack& s);

// The stack an RGB run of reduction r traces: each measured material's n and k per channel by r (a stack file's own
// RGB run uses RgbReduction::Dominant, as parsed). clipped: what the reduction could not reach (ConductorRgb::clipped).
Stack stack_reduced_to_rgb(const Stack& s, RgbReduction r, std::string& clipped);

}   // namespace gonio
