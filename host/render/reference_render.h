// reference_render.h: the reference on the sphere, from a table of simulate's bins over incident angles, on the
// CPU. By reciprocity f(w, v) = f(v, w): the table's incident direction is put at the pixel's view direction
// (theta_v = acos(n.z) in the local frame, the table's phi = 0 towards v), its slices interpolated linearly in
// theta_i, and a pixel is the sum over the reflection bins of f_bin x (the environment averaged over the bin) x
// the bin's projected solid angle.
#pragma once
#include "environment.h"
#include "image.h"
#include "reference.h"

#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

// Two tables of the same bins: independent halves of the reference's paths, or (one run) f + se z and f - se z
// with z a seeded standard normal per bin and channel, whose mean is the run and whose difference has the
// variance of two independent halves'.
struct ReferenceTable {
    uint32_t n_theta = 0, n_phi = 0;
    double dtheta_deg = 1, dphi_deg = 2;
    std::vector<double> theta_i_deg;   // ascending
    std::vector<std::vector<glm::vec3>> half[2];   // per angle: reflection bins, theta-major
    bool independent_halves = false;
    uint64_t paths_per_angle = 0;   // both halves together
};
ReferenceTable table_from_halves(const SimResult& a, const SimResult& b);
ReferenceTable table_from_run(const SimResult& r, uint32_t seed);

struct ReferenceRender {
    Image image;   // the mean of the halves: the render of the whole table
    Image half[2];
    uint32_t env_filter[2] = {1, 1};   // the environment's box filter for the bin averages: texels along phi, theta
    uint32_t samples_per_bin = 0;
    uint64_t pixels_beyond_table = 0;   // pixels whose theta_v lies outside the table's angles (nearest slice)
    double seconds = 0;   // host clock
    unsigned threads = 1;
};
ReferenceRender render_reference(const ReferenceTable& t, const Environment& env, uint32_t size, unsigned threads);

}   // namespace gonio
