// image.h: gonio render's images (RGBA float, A = sphere coverage) and what is written of them: EXR, tone-mapped
// PNG, signed differences.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

struct Image {
    uint32_t size = 0;   // square: size x size, row 0 at the top
    std::vector<glm::vec4> rgba;
    glm::vec4& at(uint32_t x, uint32_t y) { return rgba[size_t(y) * size + x]; }
};

// RGBA float EXR (ZIP), with string attributes (name, value) in the header.
void write_rgba_exr(const std::string& path, const Image& im,
                    const std::vector<std::pair<std::string, std::string>>& attributes = {});
Image read_rgba_exr(const std::string& path);

// exposure x radiance, Reinhard's x / (1 + x) per channel, sRGB-encoded, 8 bits, alpha from A.
void write_tonemapped_png(const std::string& path, const Image& im, double exposure);
// The exposure that puts the 99th percentile of the image's luminance on the sphere at 1 (1 if it is 0).
double auto_exposure(const Image& im);
// (a - b) per pixel, RGB; A of a.
Image difference(const Image& a, const Image& b);
// A signed difference as a diverging PNG: luminance of d / scale, blue below 0, red above, white at 0.
void write_difference_png(const std::string& path, const Image& d, double scale);

// Relative L1 over the sphere: sum |a - b| / sum |b| over the pixels with A > 0 and the three channels.
double relative_l1(const Image& a, const Image& b);

}   // namespace gonio
