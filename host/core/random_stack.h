// random_stack.h: seeded random layer stacks over the whole valid parameter space (gonio random-stack), for
// robustness tests (tests/test_hard_cases.cpp) and the error atlas of `gonio bench --out`.
//
// The same (seed, index, options) gives the same stack on every platform (own 64-bit generator, no
// std::*_distribution). Values are rounded to 3 significant digits, so that the TOML reads well, and every
// stack is built by parsing its own TOML text: what the function returns is exactly what `gonio check` reads.
#pragma once
#include "stack.h"

#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

struct RandomStackOptions {
    int min_layers = 1;   // layer count range, 1..kMaxLayers (base included)
    int max_layers = kMaxLayers;
    // which bases may be drawn (at least one): an opaque Lambertian or conductor base, or a dielectric last
    // layer (a transmissive stack)
    bool lambertian_base = true;
    bool conductor_base = true;
    bool transmissive = true;
    bool exterior_other_than_air = true;   // sometimes draw an exterior IOR other than 1
    double max_optical_depth = 50.0;   // optical depths are drawn in [0, this] (> 0)
    bool scattering = true;   // media with optical depth may scatter
    bool microsurfaces = true;   // rough interfaces may set the microsurface's word keys
    bool microflakes = true;   // scattering media may be SGGX microflake media
};

// Throws std::invalid_argument if the options admit no stack.
void check_random_stack_options(const RandomStackOptions& o);

// Stack `index` of the sequence seeded by `seed`. Name "random-<seed>-<index>".
//
// What is drawn (each layer independently; special values with fixed probabilities, so that the edges of the
// valid space are hit often, not by luck):
//   layers      1 + a few (most stacks 1..4), 1 in 6 stacks 8..16 layers (within [min_layers, max_layers])
//   exterior    1 (air), or 1 in 5 stacks uniform in [1, 2]
//   roughness   0, 1e-4 or 1 (1 in 8 each), else log-uniform in [1e-3, 1] or uniform in [0, 1]
//   dielectric  absolute IOR: 1 in 8 equal to the medium above (an index-matched interface), 1 in 10 exactly 3,
//               else uniform in [1, 3] (so relative IORs run from 1/3 to 3: total internal reflection both ways)
//   optical     0 (1 in 3), 50 (1 in 12), else log-uniform in [1e-3, 50]; RGB-coloured half of the time
//               (50 stands for options.max_optical_depth; log-uniform from min(1e-3, max / 10))
//   depth
//   conductor   n uniform in [0.1, 3] per channel, k uniform in [0, 10] per channel (1 in 8: exactly 10)
//   scattering  a medium with optical depth scatters 1 in 3 times: single-scattering albedo uniform in [0, 0.99]
//               (grey or RGB), Henyey-Greenstein g uniform in (-0.9, 0.9), 1 in 8 exactly 0 (from a stream of its
//               own: the other draws do not depend on it)
//   micro-      a scattering medium is one of SGGX microflakes 1 in 4 times (fibres or flakes, 1 in 2 each;
//   flakes      fibre_roughness 0.01 or 1, 1 in 8 each, else uniform in [0.01, 1]; phase_g 0), from a stream of its
//               own
//   Lambertian  albedo uniform in [0, 1] per channel (1 in 8: white, 1 in 16: black)
//   micro-      a rough dielectric or conductor interface: distribution "beckmann", shadowing "separable",
//   surface     microfacets "multiple", each 1 in 6 (from a stream of its own; a walk on the microsurface keeps the
//               height-correlated shadowing it is built on)
Stack random_stack(uint64_t seed, uint64_t index, const RandomStackOptions& options = {});

// The stack's TOML text (what `gonio random-stack` writes; parse_stack_string reads it back to the same stack).
std::string random_stack_toml(uint64_t seed, uint64_t index, const RandomStackOptions& options = {});

}   // namespace gonio
