// environment.h: gonio render's light: an equirectangular environment map (z up; render_interface.glsl states the
// convention), by name (Debian blender-data's eight maps, `furnace`, the procedural `studio`) or from an EXR file;
// the sampling CDF the device reads, and a box-filtered copy for the reference's bin averages.
#pragma once
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

struct Environment {
    std::string name;   // what --env said
    std::string source;   // the file read, or "procedural"
    uint32_t width = 0, height = 0;
    std::vector<glm::vec3> texels;   // row-major, row 0 the zenith (radiance, W / (m^2 sr), linear RGB)
    uint64_t negative_texels = 0;   // texels with a negative channel in the file: those channels set to 0
    double most_negative = 0;   // the most negative value read (0: none)
    uint64_t non_finite_texels = 0;   // NaN or infinite channels in the file: set to 0 as well
    glm::vec3 texel(uint32_t i, uint32_t j) const { return texels[size_t(j) * width + i]; }
};

// Blender's maps (Debian blender-data): where they live, and their names.
extern const char* const kBlenderWorldDir;
const std::vector<std::string>& blender_environment_names();

// --env: a Blender map's name, `furnace` (uniform radiance 1), `studio` (three disc lights over a dim gradient) or
// an EXR file. Refused (std::invalid_argument: exit 2): an unknown name (listing the valid ones), a missing file,
// an unreadable EXR, a map without R, G and B.
Environment load_environment(const std::string& env);

// The device's sampling CDFs: the marginal CDF over rows (height values, the last 1), then per row the conditional
// CDF over its columns (width values each), of max(luminance - its mean over the sphere, 0) x sin(theta) at the
// texel's centre (MIS compensation). *sampled: false where that is 0 everywhere (a constant map): no environment
// sampling then.
std::vector<float> environment_cdf(const Environment& e, bool* sampled = nullptr);

// The map box-filtered: a texel of the result is the mean of fx x fy texels (fx along phi, fy along theta)
Environment box_filtered(const Environment& e, uint32_t fx, uint32_t fy);

// atan(x) on [0, 1], minimax polynomial (error about 1e-5 rad), and atan2 from it: the reference's inner loop
inline float atan01(float x) {
    const float x2 = x * x;
    return x * (0.99997726f + x2 * (-0.33262347f +
                                    x2 * (0.19354346f + x2 * (-0.11643287f + x2 * (0.05265332f + x2 * -0.01172120f)))));
}
inline float fast_atan2(float y, float x) {
    const float ax = std::fabs(x), ay = std::fabs(y);
    const float mx = std::max(ax, ay), mn = std::min(ax, ay);
    float a = mx > 0 ? atan01(mn / mx) : 0.0f;
    if (ay > ax) a = float(M_PI / 2) - a;
    if (x < 0) a = float(M_PI) - a;
    return y < 0 ? -a : a;
}
// Bilinear lookup of direction w (unit), wrapping in phi and clamped in theta (the reference's inner loop).
inline glm::vec3 environment_bilinear(const Environment& e, const glm::vec3& w) {
    float phi = fast_atan2(w.y, w.x);
    if (phi < 0) phi += float(2 * M_PI);
    const float theta = fast_atan2(std::sqrt(w.x * w.x + w.y * w.y), w.z);
    // texel centres at (i + 0.5) / W, (j + 0.5) / H; phi in [0, 2 pi): i0 in [-1, W - 1] (no integer division)
    const float x = phi * float(0.5 / M_PI) * e.width - 0.5f, y = theta * float(1 / M_PI) * e.height - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float tx = x - fx, ty = y - fy;
    const int W = int(e.width), H = int(e.height);
    int i0 = int(fx), i1 = i0 + 1;
    if (i0 < 0) i0 += W;
    if (i0 >= W) i0 -= W;
    if (i1 >= W) i1 -= W;
    const int j0 = int(fy), ja = j0 < 0 ? 0 : (j0 >= H ? H - 1 : j0),
              jb = j0 + 1 >= H ? H - 1 : (j0 + 1 < 0 ? 0 : j0 + 1);
    const glm::vec3* ra = e.texels.data() + size_t(ja) * W;
    const glm::vec3* rb = e.texels.data() + size_t(jb) * W;
    return (ra[i0] * (1 - tx) + ra[i1] * tx) * (1 - ty) + (rb[i0] * (1 - tx) + rb[i1] * tx) * ty;
}

}   // namespace gonio
