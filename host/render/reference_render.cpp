#include "reference_render.h"
#include "histogram.h"
#include "render_interface.glsl"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <thread>

namespace gonio {

namespace {

ReferenceTable empty_table(const SimResult& r) {
    ReferenceTable t;
    t.n_theta = r.n_theta;
    t.n_phi = r.n_phi;
    t.dtheta_deg = r.options.dtheta_deg;
    t.dphi_deg = r.options.dphi_deg;
    return t;
}
// the run's angles in ascending order
std::vector<size_t> ascending(const SimResult& r) {
    std::vector<size_t> idx(r.angles.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::sort(idx.begin(), idx.end(),
              [&](size_t a, size_t b) { return r.angles[a].theta_i_deg < r.angles[b].theta_i_deg; });
    return idx;
}
std::vector<glm::vec3> to_float(const std::vector<glm::dvec3>& v) { return std::vector<glm::vec3>(v.begin(), v.end()); }

}   // namespace

ReferenceTable table_from_halves(const SimResult& a, const SimResult& b) {
    ReferenceTable t = empty_table(a);
    t.independent_halves = true;
    for (size_t k : ascending(a)) {
        t.theta_i_deg.push_back(a.angles[k].theta_i_deg);
        t.half[0].push_back(to_float(make_slice(a, k, kReflection).f));
        t.half[1].push_back(to_float(make_slice(b, k, kReflection).f));
        t.paths_per_angle = a.angles[k].paths + b.angles[k].paths;
    }
    return t;
}

ReferenceTable table_from_run(const SimResult& r, uint32_t seed) {
    ReferenceTable t = empty_table(r);
    std::mt19937_64 rng(0x72656e646572ull ^ seed);   // "render"
    std::normal_distribution<double> z;
    for (size_t k : ascending(r)) {
        const Slice s = make_slice(r, k, kReflection);
        std::vector<glm::vec3> a(s.f.size()), b(s.f.size());
        for (size_t i = 0; i < s.f.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                const double d = s.se[i][c] * z(rng);
                a[i][c] = float(s.f[i][c] + d);
                b[i][c] = float(s.f[i][c] - d);
            }
        t.theta_i_deg.push_back(r.angles[k].theta_i_deg);
        t.half[0].push_back(std::move(a));
        t.half[1].push_back(std::move(b));
        t.paths_per_angle = r.angles[k].paths;
    }
    return t;
}

ReferenceRender render_reference(const ReferenceTable& t, const Environment& env, uint32_t size, unsigned threads) {
    const auto t0 = std::chrono::steady_clock::now();
    if (t.theta_i_deg.empty()) throw std::invalid_argument("render: the reference table has no incident angles");
    ReferenceRender out;
    out.threads = std::max(1u, threads);
    // the environment averaged over about a bin: box-filtered to about the bin's size in theta and in phi
    // (texels of at most the bin's width), then read (bilinear) at the bin's centre
    out.env_filter[0] = std::max(1u, uint32_t(env.width * t.dphi_deg / 360.0));
    out.env_filter[1] = std::max(1u, uint32_t(env.height * t.dtheta_deg / 180.0));
    const Environment fe = box_filtered(env, out.env_filter[0], out.env_filter[1]);
    out.samples_per_bin = 1;
    // the bins: local directions of the sample points (phi = 0 towards the view) and projected solid angles
    const double deg = M_PI / 180;
    const size_t nb = size_t(t.n_theta) * t.n_phi;
    std::vector<glm::vec3> dir(nb);
    std::vector<float> omega(nb);
    for (uint32_t i = 0; i < t.n_theta; ++i) {
        const double lo = i * t.dtheta_deg * deg, hi = std::min(90.0, (i + 1) * t.dtheta_deg) * deg;
        const double s2lo = std::sin(lo) * std::sin(lo), s2hi = std::sin(hi) * std::sin(hi);
        const double th = std::asin(std::sqrt(0.5 * (s2lo + s2hi)));   // the middle of the bin in sin^2(theta)
        for (uint32_t j = 0; j < t.n_phi; ++j) {
            const size_t b = size_t(i) * t.n_phi + j;
            omega[b] = float(0.5 * (s2hi - s2lo) * t.dphi_deg * deg);
            const double ph = j * t.dphi_deg * deg;   // bins centred on j dphi
            dir[b] = glm::vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
        }
    }
    for (Image* im : {&out.image, &out.half[0], &out.half[1]}) {
        im->size = size;
        im->rgba.assign(size_t(size) * size, glm::vec4(0));
    }
    std::vector<uint64_t> beyond(out.threads, 0);
    auto work = [&](unsigned w) {
        for (uint32_t y = w; y < size; y += out.threads)
            for (uint32_t x = 0; x < size; ++x) {
                vec3 n;
                if (!sphere_normal(x, y, size, n)) continue;
                const glm::vec3 nn(n.x, n.y, n.z);
                glm::vec3 t1(-n.x * n.z, -n.y * n.z, 1 - n.z * n.z);
                const float tl = glm::length(t1);
                t1 = tl > 1e-6f ? t1 / tl : glm::vec3(1, 0, 0);
                const glm::vec3 t2 = glm::cross(nn, t1);
                // the slices around theta_v
                const double tv = std::acos(std::clamp(double(n.z), -1.0, 1.0)) / deg;
                const auto& a = t.theta_i_deg;
                size_t k1 = std::upper_bound(a.begin(), a.end(), tv) - a.begin();
                size_t k0 = k1 == 0 ? 0 : k1 - 1;
                if (k1 >= a.size()) k1 = a.size() - 1;
                if (tv < a.front() || tv > a.back()) ++beyond[w];
                const float u = k0 == k1 ? 0.0f : float(std::clamp((tv - a[k0]) / (a[k1] - a[k0]), 0.0, 1.0));
                const std::vector<glm::vec3>* f[2][2] = {{&t.half[0][k0], &t.half[0][k1]},
                                                         {&t.half[1][k0], &t.half[1][k1]}};
                glm::vec3 sum[2] = {glm::vec3(0), glm::vec3(0)};
                for (size_t b = 0; b < nb; ++b) {
                    const glm::vec3& d = dir[b];
                    const glm::vec3 L = environment_bilinear(fe, d.x * t1 + d.y * t2 + d.z * nn) * omega[b];
                    for (int h = 0; h < 2; ++h) sum[h] += ((1 - u) * (*f[h][0])[b] + u * (*f[h][1])[b]) * L;
                }
                const size_t p = size_t(y) * size + x;
                out.half[0].rgba[p] = glm::vec4(sum[0], 1);
                out.half[1].rgba[p] = glm::vec4(sum[1], 1);
                out.image.rgba[p] = glm::vec4(0.5f * (sum[0] + sum[1]), 1);
            }
    };
    std::vector<std::thread> pool;
    for (unsigned w = 1; w < out.threads; ++w) pool.emplace_back(work, w);
    work(0);
    for (auto& th : pool) th.join();
    for (uint64_t b : beyond) out.pixels_beyond_table += b;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}   // namespace gonio
