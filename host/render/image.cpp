#include "image.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gonio {

void write_rgba_exr(const std::string& path, const Image& im,
                    const std::vector<std::pair<std::string, std::string>>& attributes) {
    const int n = int(im.size);
    Imf::Header h(n, n);
    h.compression() = Imf::ZIP_COMPRESSION;
    for (const char* c : {"R", "G", "B", "A"}) h.channels().insert(c, Imf::Channel(Imf::FLOAT));
    for (auto& [k, v] : attributes) h.insert(k, Imf::StringAttribute(v));
    Imf::OutputFile f(path.c_str(), h);
    Imf::FrameBuffer fb;
    char* base = reinterpret_cast<char*>(const_cast<glm::vec4*>(im.rgba.data()));
    const size_t xs = sizeof(glm::vec4), ys = xs * n;
    int c = 0;
    for (const char* name : {"R", "G", "B", "A"}) fb.insert(name, Imf::Slice(Imf::FLOAT, base + 4 * c++, xs, ys));
    f.setFrameBuffer(fb);
    f.writePixels(n);
}

Image read_rgba_exr(const std::string& path) {
    Imf::InputFile in(path.c_str());
    const Imath::Box2i dw = in.header().dataWindow();
    const int w = dw.max.x - dw.min.x + 1, hgt = dw.max.y - dw.min.y + 1;
    if (w != hgt) throw std::runtime_error(path + ": not a square image");
    Image im;
    im.size = uint32_t(w);
    im.rgba.assign(size_t(w) * w, glm::vec4(0));
    Imf::FrameBuffer fb;
    const size_t xs = sizeof(glm::vec4), ys = xs * w;
    char* base = reinterpret_cast<char*>(im.rgba.data()) - (dw.min.x * xs + size_t(dw.min.y) * ys);
    int c = 0;
    for (const char* name : {"R", "G", "B", "A"}) fb.insert(name, Imf::Slice(Imf::FLOAT, base + 4 * c++, xs, ys));
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    return im;
}

namespace {
double luminance(const glm::vec4& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }
uint8_t to_byte(double x) { return uint8_t(std::lround(std::clamp(x, 0.0, 1.0) * 255.0)); }
double srgb(double x) {   // IEC 61966-2-1
    x = std::clamp(x, 0.0, 1.0);
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
}
void write_png(const std::string& path, uint32_t n, const std::vector<uint8_t>& rgba) {
    if (!stbi_write_png(path.c_str(), int(n), int(n), 4, rgba.data(), int(n) * 4))
        throw std::runtime_error("cannot write " + path);
}
}   // namespace

double auto_exposure(const Image& im) {
    std::vector<double> y;
    for (auto& c : im.rgba)
        if (c.w > 0) y.push_back(luminance(c));
    if (y.empty()) return 1.0;
    const size_t k = std::min(y.size() - 1, size_t(0.99 * y.size()));
    std::nth_element(y.begin(), y.begin() + k, y.end());
    return y[k] > 0 ? 1.0 / y[k] : 1.0;
}

void write_tonemapped_png(const std::string& path, const Image& im, double exposure) {
    std::vector<uint8_t> px(size_t(im.size) * im.size * 4);
    for (size_t i = 0; i < im.rgba.size(); ++i) {
        const glm::vec4& c = im.rgba[i];
        for (int k = 0; k < 3; ++k) {
            const double x = std::max(0.0, exposure * c[k]);
            px[4 * i + k] = to_byte(srgb(x / (1 + x)) * (c.w > 0 ? 1 : 0));
        }
        px[4 * i + 3] = to_byte(c.w);
    }
    write_png(path, im.size, px);
}

Image difference(const Image& a, const Image& b) {
    Image d = a;
    for (size_t i = 0; i < d.rgba.size(); ++i)
        d.rgba[i] = glm::vec4(glm::vec3(a.rgba[i]) - glm::vec3(b.rgba[i]), a.rgba[i].w);
    return d;
}

void write_difference_png(const std::string& path, const Image& d, double scale) {
    std::vector<uint8_t> px(size_t(d.size) * d.size * 4);
    for (size_t i = 0; i < d.rgba.size(); ++i) {
        const double t = std::clamp(scale > 0 ? luminance(d.rgba[i]) / scale : 0.0, -1.0, 1.0);
        // white at 0, towards red (1, 0, 0) above and blue (0, 0, 1) below
        const double r = t < 0 ? 1 + t : 1, g = 1 - std::fabs(t), b = t > 0 ? 1 - t : 1;
        const bool on = d.rgba[i].w > 0;
        px[4 * i] = to_byte(on ? r : 0);
        px[4 * i + 1] = to_byte(on ? g : 0);
        px[4 * i + 2] = to_byte(on ? b : 0);
        px[4 * i + 3] = on ? 255 : 0;
    }
    write_png(path, d.size, px);
}

double relative_l1(const Image& a, const Image& b) {
    double num = 0, den = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) {
        if (!(b.rgba[i].w > 0)) continue;
        for (int k = 0; k < 3; ++k) {
            num += std::fabs(double(a.rgba[i][k]) - b.rgba[i][k]);
            den += std::fabs(double(b.rgba[i][k]));
        }
    }
    return den > 0 ? num / den : 0.0;
}

}   // namespace gonio
