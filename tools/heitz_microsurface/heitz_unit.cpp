// heitz_unit.cpp: compiles the authors' MicrosurfaceScattering.cpp (Heitz, Hanika, d'Eon, Dachsbacher 2016,
// supplemental code), UNMODIFIED, as part of this translation unit, and adds one hook to seed its generator.
// Our own code (gonio project); the authors' file comes from the checkout named by -DHEITZ_SOURCE_DIR (README.md).
//
// Why a wrapper and not the .cpp on its own:
//  * The authors' file defines `static double erf(double)` and `static double gamma(double)` after including
//    <cmath>; glibc's math.h has already declared both `extern "C"`, and g++ refuses a static redefinition
//    ("was declared 'extern' and later 'static'"). MSVC, which the authors used, accepted it. We include every
//    system header the file includes first (their include guards make its own #includes no-ops) and then rename
//    the two names with macros, so the file's own erf/gamma become heitz_erf/heitz_gamma: every call in the file
//    then reaches the authors' functions, as on their compiler (with -fpermissive instead, `using namespace std`
//    would let calls with a float argument resolve to std::erf(float), not to the authors' erf).
//  * Its random generator (`static std::mt19937 gen(rd())`, seeded from std::random_device, and the double
//    distribution `dis` whose value generateRandomNumber() casts to float) has internal linkage: only code in this
//    unit can reseed it. heitz_seed() does, so that a run is reproducible (same --seed, same bytes).
//  * The file also redefines M_PI and M_PI_2 as float literals (a warning, harmless; the definitions stay local
//    to this unit, the driver uses <cmath>'s).
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>

#include <glm/glm.hpp>

#define erf heitz_erf
#define gamma heitz_gamma
#include "MicrosurfaceScattering.cpp"
#undef erf
#undef gamma

// Reseeds the authors' generator (std::mt19937's own seeding from one 32-bit value) and clears the distribution's
// state, so the whole sequence of generateRandomNumber() values is a function of the seed.
void heitz_seed(uint32_t seed) {
    gen.seed(seed);
    dis.reset();
}
