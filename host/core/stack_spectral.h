// stack_spectral.h: a stack seen at three wavelengths, one per channel: what a spectral run traces (three bands per
// pass of the RGB walk, docs/SPECTRAL.md). A measured material takes its n and k at each wavelength; every other
// value is the same at every wavelength, so it must be one value (grey) in the stack: a spectrum made from RGB is
// not defined yet.
#pragma once

#include "stack.h"

#include <array>
#include <string>

namespace gonio {

// "" where the stack can be traced spectrally, else why not (a layer's RGB key that is not one value).
std::string spectral_refusal(const Stack& s);

// The stack with channel c at wavelength nm[c]: each measured material's n and k there (throws std::out_of_range
// outside its table); the rest as it is.
Stack stack_at_wavelengths(const Stack& s, const std::array<double, 3>& nm);

}   // namespace gonio
