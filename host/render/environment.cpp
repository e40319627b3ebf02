#include "environment.h"
#include "stack.h"   // kChannels

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace gonio {

const char* const kBlenderWorldDir = "/usr/share/blender/datafiles/studiolights/world";

const std::vector<std::string>& blender_environment_names() {
    static const std::vector<std::string> names = {"city",  "courtyard", "forest",  "interior",
                                                   "night", "studio",    "sunrise", "sunset"};
    return names;
}

namespace {

std::string valid_names() {
    std::string s = "furnace, studio";
    for (auto& n : blender_environment_names())
        if (n != "studio") s += ", " + n;
    return s + " (Blender's " + std::string(kBlenderWorldDir) + "/NAME.exr; `studio` is procedural), or an EXR file";
}

// Reads R, G, B as float (OpenEXR converts half and decodes DWAB); clamps negative and non-finite values to 0.
Environment read_exr_environment(const std::string& name, const std::string& path) {
    Environment e;
    e.name = name;
    e.source = path;
    try {
        Imf::InputFile in(path.c_str());
        const Imath::Box2i dw = in.header().dataWindow();
        const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        for (const char* c : {"R", "G", "B"})
            if (!in.header().channels().findChannel(c))
                throw std::invalid_argument("--env " + path + ": the map has no channel " + c + " (RGB expected)");
        if (w < 2 || h < 2) throw std::invalid_argument("--env " + path + ": the map is smaller than 2 x 2 texels");
        std::vector<float> rgb(size_t(w) * h * 3);
        Imf::FrameBuffer fb;
        const size_t xs = 3 * sizeof(float), ys = size_t(w) * xs;
        char* base = reinterpret_cast<char*>(rgb.data()) - (dw.min.x * xs + size_t(dw.min.y) * ys);
        fb.insert("R", Imf::Slice(Imf::FLOAT, base, xs, ys));
        fb.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xs, ys));
        fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xs, ys));
        in.setFrameBuffer(fb);
        in.readPixels(dw.min.y, dw.max.y);
        e.width = uint32_t(w);
        e.height = uint32_t(h);
        e.texels.resize(size_t(w) * h);
        for (size_t t = 0; t < e.texels.size(); ++t) {
            bool negative = false, bad = false;
            for (int c = 0; c < kChannels; ++c) {
                float& v = rgb[3 * t + c];
                if (!std::isfinite(v)) {
                    bad = true;
                    v = 0;
                } else if (v < 0) {
                    negative = true;
                    e.most_negative = std::min(e.most_negative, double(v));
                    v = 0;
                }
            }
            e.negative_texels += negative;
            e.non_finite_texels += bad;
            e.texels[t] = glm::vec3(rgb[3 * t], rgb[3 * t + 1], rgb[3 * t + 2]);
        }
    } catch (const std::invalid_argument&) { throw; } catch (const std::exception& ex) {
        throw std::invalid_argument("--env " + path + ": not a readable EXR file (" + ex.what() + ")");
    }
    return e;
}

// A procedural studio: a dim vertical gradient (0.15 at the zenith, 0.05 at the horizon, 0.02 below) and three
// disc lights (key, fill, rim: centre theta, phi, radius in degrees and radiance), 512 x 256 texels.
Environment studio_environment() {
    Environment e;
    e.name = "studio";
    e.source = "procedural";
    e.width = 512;
    e.height = 256;
    e.texels.resize(size_t(e.width) * e.height);
    struct Disc {
        double theta, phi, radius;
        glm::vec3 radiance;
    };
    const Disc discs[] = {{35, 30, 12, {6.0f, 5.7f, 5.2f}}, {55, 200, 20, {1.2f, 1.3f, 1.5f}}, {78, 110, 8, {4, 4, 4}}};
    const double deg = M_PI / 180;
    for (uint32_t j = 0; j < e.height; ++j)
        for (uint32_t i = 0; i < e.width; ++i) {
            const double th = M_PI * (j + 0.5) / e.height, ph = 2 * M_PI * (i + 0.5) / e.width;
            const glm::dvec3 w(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
            glm::vec3 L = w.z > 0 ? glm::vec3(float(0.05 + 0.10 * w.z)) : glm::vec3(0.02f);
            for (const Disc& d : discs) {
                const glm::dvec3 c(std::sin(d.theta * deg) * std::cos(d.phi * deg),
                                   std::sin(d.theta * deg) * std::sin(d.phi * deg), std::cos(d.theta * deg));
                if (glm::dot(w, c) > std::cos(d.radius * deg)) L = d.radiance;
            }
            e.texels[size_t(j) * e.width + i] = L;
        }
    return e;
}

}   // namespace

Environment load_environment(const std::string& env) {
    if (env == "furnace") {
        Environment e;
        e.name = "furnace";
        e.source = "procedural";
        e.width = 64;
        e.height = 32;
        e.texels.assign(size_t(e.width) * e.height, glm::vec3(1.0f));
        return e;
    }
    if (env == "studio") return studio_environment();
    const auto& names = blender_environment_names();
    if (std::find(names.begin(), names.end(), env) != names.end()) {
        const std::string path = std::string(kBlenderWorldDir) + "/" + env + ".exr";
        if (!std::filesystem::exists(path))
            throw std::invalid_argument("--env " + env + ": " + path +
                                        " is missing (Debian: apt-get install blender-data)");
        return read_exr_environment(env, path);
    }
    const bool looks_like_file = env.find('/') != std::string::npos || env.find('.') != std::string::npos;
    if (!looks_like_file)
        throw std::invalid_argument("--env " + env + ": no such environment; valid: " + valid_names());
    if (!std::filesystem::is_regular_file(env)) throw std::invalid_argument("--env " + env + ": no such file");
    return read_exr_environment(env, env);
}

std::vector<float> environment_cdf(const Environment& e, bool* sampled) {
    const uint32_t W = e.width, H = e.height;
    // MIS compensation (Karlik et al. 2019, "MIS Compensation: Optimizing Sampling Techniques in Multiple
    // Importance Sampling"; pbrt-v4's ImageInfiniteLight): sample max(Y - mean Y, 0), the other strategies cover
    // the rest; a constant map (the furnace) is then not sampled at all
    auto lum = [&](uint32_t i, uint32_t j) {
        const glm::vec3 L = e.texel(i, j);
        return 0.2126 * L.x + 0.7152 * L.y + 0.0722 * L.z;   // Rec. 709 luminance
    };
    double mean = 0, wsum = 0;
    for (uint32_t j = 0; j < H; ++j) {
        const double s = std::sin(M_PI * (j + 0.5) / H);
        for (uint32_t i = 0; i < W; ++i) mean += lum(i, j) * s;
        wsum += s * W;
    }
    mean /= wsum;
    std::vector<float> cdf(H + size_t(W) * H);
    std::vector<double> row(H);
    double total = 0;
    for (uint32_t j = 0; j < H; ++j) {
        const double s = std::sin(M_PI * (j + 0.5) / H);
        double acc = 0;
        std::vector<double> c(W);
        for (uint32_t i = 0; i < W; ++i) {
            const double d = lum(i, j) - mean;
            acc += (d > 1e-6 * mean ? d : 0.0) * s;
            c[i] = acc;
        }
        for (uint32_t i = 0; i < W; ++i)
            cdf[H + size_t(j) * W + i] = acc > 0 ? float(c[i] / acc) : float(double(i + 1) / W);
        cdf[H + size_t(j) * W + W - 1] = 1.0f;
        row[j] = acc;
        total += acc;
    }
    double acc = 0;
    for (uint32_t j = 0; j < H; ++j) {
        acc += total > 0 ? row[j] : 1.0;
        cdf[j] = float(acc / (total > 0 ? total : double(H)));
    }
    cdf[H - 1] = 1.0f;
    if (sampled) *sampled = total > 0;
    return cdf;
}

Environment box_filtered(const Environment& e, uint32_t fx, uint32_t fy) {
    Environment r = e;
    fx = std::max(fx, 1u);
    fy = std::max(fy, 1u);
    if (fx == 1 && fy == 1) return r;
    r.width = std::max(1u, e.width / fx);
    r.height = std::max(1u, e.height / fy);
    r.texels.assign(size_t(r.width) * r.height, glm::vec3(0));
    for (uint32_t j = 0; j < r.height; ++j)
        for (uint32_t i = 0; i < r.width; ++i) {
            glm::dvec3 s(0);
            uint32_t n = 0;
            for (uint32_t b = j * fy; b < std::min(e.height, (j + 1) * fy); ++b)
                for (uint32_t a = i * fx; a < std::min(e.width, (i + 1) * fx); ++a, ++n) s += glm::dvec3(e.texel(a, b));
            r.texels[size_t(j) * r.width + i] = glm::vec3(s / double(std::max(n, 1u)));
        }
    return r;
}

}   // namespace gonio
