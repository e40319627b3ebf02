#include "reference_render.h"
#include "histogram.h"
#include "render_interface.glsl"

#include <algorithm>
#include <immintrin.h>
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

// The bilinear reads of environment_bilinear (environment.h) for n local directions (d, in the frame t1, t2, nn):
// per direction the texel offsets of the two rows' first texels (ia, ib: row x W + i0), the column step to i1 (da:
// 1, or 1 - W where i0 is the last column) and the weights (wx, wy). bilinear_indices_avx2 is the same arithmetic
// 8 directions at a time (FMA contractions aside), used where the CPU has AVX2 and FMA.
void bilinear_indices_scalar(const Environment& e, size_t n, const float* __restrict dx, const float* __restrict dy,
                             const float* __restrict dz, glm::vec3 t1, glm::vec3 t2, glm::vec3 nn,
                             int32_t* __restrict ia, int32_t* __restrict ib, int32_t* __restrict da,
                             float* __restrict wx, float* __restrict wy) {
    const int W = int(e.width), H = int(e.height);
    const float sw = float(0.5 / M_PI) * e.width, sh = float(1 / M_PI) * e.height;
    for (size_t b = 0; b < n; ++b) {
        const float x0 = dx[b] * t1.x + dy[b] * t2.x + dz[b] * nn.x;
        const float y0 = dx[b] * t1.y + dy[b] * t2.y + dz[b] * nn.y;
        const float z0 = dx[b] * t1.z + dy[b] * t2.z + dz[b] * nn.z;
        // fast_atan2 (environment.h) twice, its branches as selects, written out here: a function with other
        // optimisation options is not inlined into this one
        const float r = __builtin_sqrtf(x0 * x0 + y0 * y0);
        const float ax = __builtin_fabsf(x0), ay = __builtin_fabsf(y0), az = __builtin_fabsf(z0);
        const float m1 = ax > ay ? ax : ay, n1 = ax > ay ? ay : ax;
        const float m2 = r > az ? r : az, n2 = r > az ? az : r;
        const float q1 = n1 / (m1 > 0 ? m1 : 1.0f), q2 = n2 / (m2 > 0 ? m2 : 1.0f);
        const float p1 = q1 * q1, p2 = q2 * q2;
        float a1 =
            q1 *
            (0.99997726f +
             p1 * (-0.33262347f + p1 * (0.19354346f + p1 * (-0.11643287f + p1 * (0.05265332f + p1 * -0.01172120f)))));
        float a2 =
            q2 *
            (0.99997726f +
             p2 * (-0.33262347f + p2 * (0.19354346f + p2 * (-0.11643287f + p2 * (0.05265332f + p2 * -0.01172120f)))));
        a1 = ay > ax ? float(M_PI / 2) - a1 : a1;
        a1 = x0 < 0 ? float(M_PI) - a1 : a1;
        a1 = y0 < 0 ? -a1 : a1;
        const float phi = a1 < 0 ? a1 + float(2 * M_PI) : a1;
        a2 = r > az ? float(M_PI / 2) - a2 : a2;
        const float theta = z0 < 0 ? float(M_PI) - a2 : a2;
        const float x = phi * sw - 0.5f, y = theta * sh - 0.5f;
        const float fx = __builtin_floorf(x), fy = __builtin_floorf(y);
        wx[b] = x - fx;
        wy[b] = y - fy;
        int i0 = int(fx);
        i0 = i0 < 0 ? i0 + W : i0;
        i0 = i0 >= W ? i0 - W : i0;
        const int i1 = i0 + 1 >= W ? i0 + 1 - W : i0 + 1;
        const int j0 = int(fy);
        const int ja = j0 < 0 ? 0 : (j0 >= H ? H - 1 : j0);
        const int jb = j0 + 1 >= H ? H - 1 : (j0 + 1 < 0 ? 0 : j0 + 1);
        ia[b] = ja * W + i0;
        ib[b] = jb * W + i0;
        da[b] = i1 - i0;
    }
}

// atan01 (environment.h), 8 at a time
__attribute__((target("avx2,fma"))) inline __m256 atan01_avx2(__m256 q) {
    const __m256 p = _mm256_mul_ps(q, q);
    __m256 a = _mm256_set1_ps(-0.01172120f);
    a = _mm256_fmadd_ps(p, a, _mm256_set1_ps(0.05265332f));
    a = _mm256_fmadd_ps(p, a, _mm256_set1_ps(-0.11643287f));
    a = _mm256_fmadd_ps(p, a, _mm256_set1_ps(0.19354346f));
    a = _mm256_fmadd_ps(p, a, _mm256_set1_ps(-0.33262347f));
    a = _mm256_fmadd_ps(p, a, _mm256_set1_ps(0.99997726f));
    return _mm256_mul_ps(q, a);
}
__attribute__((target("avx2,fma"))) void bilinear_indices_avx2(const Environment& e, size_t n,
                                                               const float* __restrict dx, const float* __restrict dy,
                                                               const float* __restrict dz, glm::vec3 t1, glm::vec3 t2,
                                                               glm::vec3 nn, int32_t* __restrict ia,
                                                               int32_t* __restrict ib, int32_t* __restrict da,
                                                               float* __restrict wx, float* __restrict wy) {
    const int W = int(e.width), H = int(e.height);
    const __m256 sw = _mm256_set1_ps(float(0.5 / M_PI) * e.width), sh = _mm256_set1_ps(float(1 / M_PI) * e.height);
    const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f), half = _mm256_set1_ps(0.5f);
    const __m256 pi = _mm256_set1_ps(float(M_PI)), pi2 = _mm256_set1_ps(float(M_PI / 2)),
                 twopi = _mm256_set1_ps(float(2 * M_PI));
    const __m256 sign = _mm256_set1_ps(-0.0f);
    const __m256i vW = _mm256_set1_epi32(W), vH1 = _mm256_set1_epi32(H - 1), i0z = _mm256_setzero_si256(),
                  ione = _mm256_set1_epi32(1);
    const __m256 t1x = _mm256_set1_ps(t1.x), t1y = _mm256_set1_ps(t1.y), t1z = _mm256_set1_ps(t1.z);
    const __m256 t2x = _mm256_set1_ps(t2.x), t2y = _mm256_set1_ps(t2.y), t2z = _mm256_set1_ps(t2.z);
    const __m256 nx = _mm256_set1_ps(nn.x), ny = _mm256_set1_ps(nn.y), nz = _mm256_set1_ps(nn.z);
    size_t b = 0;
    for (; b + 8 <= n; b += 8) {
        const __m256 a = _mm256_loadu_ps(dx + b), c = _mm256_loadu_ps(dy + b), d = _mm256_loadu_ps(dz + b);
        const __m256 x0 =
            _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a, t1x), _mm256_mul_ps(c, t2x)), _mm256_mul_ps(d, nx));
        const __m256 y0 =
            _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a, t1y), _mm256_mul_ps(c, t2y)), _mm256_mul_ps(d, ny));
        const __m256 z0 =
            _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a, t1z), _mm256_mul_ps(c, t2z)), _mm256_mul_ps(d, nz));
        const __m256 r = _mm256_sqrt_ps(_mm256_add_ps(_mm256_mul_ps(x0, x0), _mm256_mul_ps(y0, y0)));
        const __m256 ax = _mm256_andnot_ps(sign, x0), ay = _mm256_andnot_ps(sign, y0), az = _mm256_andnot_ps(sign, z0);
        const __m256 m1 = _mm256_max_ps(ax, ay), n1 = _mm256_min_ps(ax, ay);
        const __m256 m2 = _mm256_max_ps(r, az), n2 = _mm256_min_ps(r, az);
        const __m256 q1 = _mm256_div_ps(n1, _mm256_blendv_ps(one, m1, _mm256_cmp_ps(m1, zero, _CMP_GT_OQ)));
        const __m256 q2 = _mm256_div_ps(n2, _mm256_blendv_ps(one, m2, _mm256_cmp_ps(m2, zero, _CMP_GT_OQ)));
        __m256 a1 = atan01_avx2(q1), a2 = atan01_avx2(q2);
        a1 = _mm256_blendv_ps(a1, _mm256_sub_ps(pi2, a1), _mm256_cmp_ps(ay, ax, _CMP_GT_OQ));
        a1 = _mm256_blendv_ps(a1, _mm256_sub_ps(pi, a1), _mm256_cmp_ps(x0, zero, _CMP_LT_OQ));
        a1 = _mm256_blendv_ps(a1, _mm256_xor_ps(a1, sign), _mm256_cmp_ps(y0, zero, _CMP_LT_OQ));
        const __m256 phi = _mm256_blendv_ps(a1, _mm256_add_ps(a1, twopi), _mm256_cmp_ps(a1, zero, _CMP_LT_OQ));
        a2 = _mm256_blendv_ps(a2, _mm256_sub_ps(pi2, a2), _mm256_cmp_ps(r, az, _CMP_GT_OQ));
        const __m256 theta = _mm256_blendv_ps(a2, _mm256_sub_ps(pi, a2), _mm256_cmp_ps(z0, zero, _CMP_LT_OQ));
        const __m256 x = _mm256_sub_ps(_mm256_mul_ps(phi, sw), half), y = _mm256_sub_ps(_mm256_mul_ps(theta, sh), half);
        const __m256 fx = _mm256_floor_ps(x), fy = _mm256_floor_ps(y);
        _mm256_storeu_ps(wx + b, _mm256_sub_ps(x, fx));
        _mm256_storeu_ps(wy + b, _mm256_sub_ps(y, fy));
        __m256i i0 = _mm256_cvttps_epi32(fx);
        i0 = _mm256_add_epi32(i0, _mm256_and_si256(_mm256_cmpgt_epi32(i0z, i0), vW));   // i0 < 0: + W
        i0 = _mm256_sub_epi32(i0, _mm256_andnot_si256(_mm256_cmpgt_epi32(vW, i0), vW));   // i0 >= W: - W
        __m256i i1 = _mm256_add_epi32(i0, ione);
        i1 = _mm256_sub_epi32(i1, _mm256_andnot_si256(_mm256_cmpgt_epi32(vW, i1), vW));
        const __m256i j0 = _mm256_cvttps_epi32(fy);
        const __m256i ja = _mm256_max_epi32(i0z, _mm256_min_epi32(j0, vH1));
        const __m256i jb = _mm256_max_epi32(i0z, _mm256_min_epi32(_mm256_add_epi32(j0, ione), vH1));
        _mm256_storeu_si256((__m256i*)(ia + b), _mm256_add_epi32(_mm256_mullo_epi32(ja, vW), i0));
        _mm256_storeu_si256((__m256i*)(ib + b), _mm256_add_epi32(_mm256_mullo_epi32(jb, vW), i0));
        _mm256_storeu_si256((__m256i*)(da + b), _mm256_sub_epi32(i1, i0));
    }
    if (b < n)
        bilinear_indices_scalar(e, n - b, dx + b, dy + b, dz + b, t1, t2, nn, ia + b, ib + b, da + b, wx + b, wy + b);
}
void bilinear_indices(const Environment& e, size_t n, const float* dx, const float* dy, const float* dz, glm::vec3 t1,
                      glm::vec3 t2, glm::vec3 nn, int32_t* ia, int32_t* ib, int32_t* da, float* wx, float* wy) {
    static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    if (avx2)
        bilinear_indices_avx2(e, n, dx, dy, dz, t1, t2, nn, ia, ib, da, wx, wy);
    else
        bilinear_indices_scalar(e, n, dx, dy, dz, t1, t2, nn, ia, ib, da, wx, wy);
}

// The bins of the table: the local directions of their sample points (phi = 0 towards the view) as
// structure-of-arrays (the per-pixel pass over them vectorises) and their projected solid angles.
struct BinDirections {
    std::vector<float> dx, dy, dz, omega;
};
BinDirections bin_directions(const ReferenceTable& t) {
    const double deg = M_PI / 180;
    const size_t nb = size_t(t.n_theta) * t.n_phi;
    std::vector<glm::vec3> dir(nb);
    BinDirections d;
    d.omega.resize(nb);
    for (uint32_t i = 0; i < t.n_theta; ++i) {
        const double lo = i * t.dtheta_deg * deg, hi = std::min(90.0, (i + 1) * t.dtheta_deg) * deg;
        const double s2lo = std::sin(lo) * std::sin(lo), s2hi = std::sin(hi) * std::sin(hi);
        const double th = std::asin(std::sqrt(0.5 * (s2lo + s2hi)));   // the middle of the bin in sin^2(theta)
        for (uint32_t j = 0; j < t.n_phi; ++j) {
            const size_t b = size_t(i) * t.n_phi + j;
            d.omega[b] = float(0.5 * (s2hi - s2lo) * t.dphi_deg * deg);
            const double ph = j * t.dphi_deg * deg;   // bins centred on j dphi
            dir[b] = glm::vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
        }
    }
    d.dx.resize(nb);
    d.dy.resize(nb);
    d.dz.resize(nb);
    for (size_t b = 0; b < nb; ++b) d.dx[b] = dir[b].x, d.dy[b] = dir[b].y, d.dz[b] = dir[b].z;
    return d;
}

// f x omega per incident angle of one half, 3 floats per bin: omega folded in once instead of per pixel
std::vector<std::vector<float>> weighted_slices(const std::vector<std::vector<glm::vec3>>& half,
                                                const std::vector<float>& omega) {
    const size_t nb = omega.size();
    std::vector<std::vector<float>> fw;
    for (const auto& sl : half) {
        std::vector<float> v(3 * nb + 1, 0.0f);   // + 1: the last bin's 4-float read
        for (size_t b = 0; b < nb; ++b)
            for (int c = 0; c < 3; ++c) v[3 * b + c] = sl[b][c] * omega[b];
        fw.push_back(std::move(v));
    }
    return fw;
}

// the filtered map as floats, + 1 for the last texel's 4-float read
std::vector<float> texels_rgb(const Environment& fe) {
    std::vector<float> tex3(3 * fe.texels.size() + 1, 0.0f);
    for (size_t i = 0; i < fe.texels.size(); ++i)
        for (int c = 0; c < 3; ++c) tex3[3 * i + c] = fe.texels[i][c];
    return tex3;
}

// What every pixel of the sphere reads: the box-filtered map (fe) and its texels, the bins, f x omega per half and
// slice.
struct SphereInputs {
    const ReferenceTable& t;
    const Environment& fe;
    std::vector<float> tex3;
    BinDirections bins;
    std::vector<std::vector<float>> fw[2];
    size_t nb;
};

// A pixel on the sphere: its index, the slices k0, k1 around its theta_v (weight u of k1) and its local frame.
struct Pixel {
    size_t p, k0, k1;
    float u;
    glm::vec3 t1, t2, nn;
};
// Pixel (x, y) if it is on the sphere; beyond: its theta_v is outside the table's incident angles.
bool sphere_pixel(const ReferenceTable& t, uint32_t x, uint32_t y, uint32_t size, Pixel& px, bool& beyond) {
    const double deg = M_PI / 180;
    vec3 n;
    if (!sphere_normal(x, y, size, n)) return false;
    px.p = size_t(y) * size + x;
    px.nn = glm::vec3(n.x, n.y, n.z);
    glm::vec3 t1(-n.x * n.z, -n.y * n.z, 1 - n.z * n.z);
    const float tl = glm::length(t1);
    px.t1 = tl > 1e-6f ? t1 / tl : glm::vec3(1, 0, 0);
    px.t2 = glm::cross(px.nn, px.t1);
    // the slices around theta_v
    const double tv = std::acos(std::clamp(double(n.z), -1.0, 1.0)) / deg;
    const auto& a = t.theta_i_deg;
    size_t k1 = std::upper_bound(a.begin(), a.end(), tv) - a.begin();
    size_t k0 = k1 == 0 ? 0 : k1 - 1;
    if (k1 >= a.size()) k1 = a.size() - 1;
    beyond = tv < a.front() || tv > a.back();
    px.u = k0 == k1 ? 0.0f : float(std::clamp((tv - a[k0]) / (a[k1] - a[k0]), 0.0, 1.0));
    px.k0 = k0;
    px.k1 = k1;
    return true;
}

// Per thread, rows y = w, w + threads, ...; in a row, runs of up to kRun neighbouring pixels between the same two
// slices share each chunk of kChunk bins (their f stays in the cache for the run): per pixel and chunk, the bins'
// texels and weights (bilinear_indices), then the four sums (half x slice), interpolated in the slice at the end.
// Each chunk's sum is added to the pixel's total (two levels: less rounding than one running sum).
constexpr size_t kChunk = 512, kRun = 8;

// A thread's texel offsets and weights of one chunk of bins (bilinear_indices)
struct ChunkReads {
    std::vector<int32_t> ia, ib, da;
    std::vector<float> wx, wy;
    ChunkReads() : ia(kChunk), ib(kChunk), da(kChunk), wx(kChunk), wy(kChunk) {}
};

// The four sums (half x slice) of a chunk of cn bins from c0 for one pixel: the environment read bilinearly in the
// bins' directions times f x omega of the pixel's two slices in each half (f). SSE, 4 lanes of which the first 3 are
// RGB (the 4th reads the next float, padded at the end, and is discarded).
void chunk_sums(const SphereInputs& in, const Pixel& px, size_t c0, size_t cn, const float* const f[4], ChunkReads& r,
                __m128 acc[4]) {
    bilinear_indices(in.fe, cn, in.bins.dx.data() + c0, in.bins.dy.data() + c0, in.bins.dz.data() + c0, px.t1, px.t2,
                     px.nn, r.ia.data(), r.ib.data(), r.da.data(), r.wx.data(), r.wy.data());
    const float* tex = in.tex3.data();
    const __m128 one = _mm_set1_ps(1.0f);
    for (int q = 0; q < 4; ++q) acc[q] = _mm_setzero_ps();
    for (size_t j = 0; j < cn; ++j) {
        const __m128 tx = _mm_set1_ps(r.wx[j]), ty = _mm_set1_ps(r.wy[j]);
        const __m128 sx = _mm_sub_ps(one, tx), sy = _mm_sub_ps(one, ty);
        const float* ra = tex + 3 * size_t(r.ia[j]);
        const float* rb = tex + 3 * size_t(r.ib[j]);
        const ptrdiff_t d = 3 * ptrdiff_t(r.da[j]);
        const __m128 la = _mm_add_ps(_mm_mul_ps(_mm_loadu_ps(ra), sx), _mm_mul_ps(_mm_loadu_ps(ra + d), tx));
        const __m128 lb = _mm_add_ps(_mm_mul_ps(_mm_loadu_ps(rb), sx), _mm_mul_ps(_mm_loadu_ps(rb + d), tx));
        const __m128 L = _mm_add_ps(_mm_mul_ps(la, sy), _mm_mul_ps(lb, ty));
        const size_t o = 3 * (c0 + j);
        for (int q = 0; q < 4; ++q) acc[q] = _mm_add_ps(acc[q], _mm_mul_ps(_mm_loadu_ps(f[q] + o), L));
    }
}

// The halves and their mean at one pixel from its four sums, interpolated between its two slices.
void store_pixel(ReferenceRender& out, const Pixel& px, const __m128 s4[4]) {
    glm::vec3 sq[4];
    for (int q = 0; q < 4; ++q) {
        alignas(16) float v[4];
        _mm_store_ps(v, s4[q]);
        sq[q] = glm::vec3(v[0], v[1], v[2]);
    }
    const float u = px.u;
    const glm::vec3 sum[2] = {(1 - u) * sq[0] + u * sq[1], (1 - u) * sq[2] + u * sq[3]};
    const size_t p = px.p;
    out.half[0].rgba[p] = glm::vec4(sum[0], 1);
    out.half[1].rgba[p] = glm::vec4(sum[1], 1);
    out.image.rgba[p] = glm::vec4(0.5f * (sum[0] + sum[1]), 1);
}

// A run of count neighbouring pixels between the same two slices, summed chunk by chunk of bins, written to out.
void render_run(const SphereInputs& in, const Pixel* run, size_t count, ChunkReads& r, ReferenceRender& out) {
    const float* f[4] = {in.fw[0][run[0].k0].data(), in.fw[0][run[0].k1].data(), in.fw[1][run[0].k0].data(),
                         in.fw[1][run[0].k1].data()};
    __m128 s4[kRun][4];
    for (size_t i = 0; i < kRun; ++i)
        for (int q = 0; q < 4; ++q) s4[i][q] = _mm_setzero_ps();
    for (size_t c0 = 0; c0 < in.nb; c0 += kChunk) {
        const size_t cn = std::min(kChunk, in.nb - c0);
        for (size_t i = 0; i < count; ++i) {
            __m128 acc[4];
            chunk_sums(in, run[i], c0, cn, f, r, acc);
            for (int q = 0; q < 4; ++q) s4[i][q] = _mm_add_ps(s4[i][q], acc[q]);
        }
    }
    for (size_t i = 0; i < count; ++i) store_pixel(out, run[i], s4[i]);
}

// Thread w's rows of the image; returns how many of its pixels lie beyond the table's incident angles.
uint64_t render_rows(const SphereInputs& in, uint32_t size, unsigned w, unsigned threads, ReferenceRender& out) {
    ChunkReads r;
    std::vector<Pixel> row;
    uint64_t beyond = 0;
    for (uint32_t y = w; y < size; y += threads) {
        row.clear();
        for (uint32_t x = 0; x < size; ++x) {
            Pixel px;
            bool outside = false;
            if (!sphere_pixel(in.t, x, y, size, px, outside)) continue;
            if (outside) ++beyond;
            row.push_back(px);
        }
        for (size_t r0 = 0; r0 < row.size();) {
            size_t r1 = r0 + 1;
            while (r1 < row.size() && r1 - r0 < kRun && row[r1].k0 == row[r0].k0 && row[r1].k1 == row[r0].k1) ++r1;
            render_run(in, row.data() + r0, r1 - r0, r, out);
            r0 = r1;
        }
    }
    return beyond;
}
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
            for (int c = 0; c < kChannels; ++c) {
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
    SphereInputs in{t, fe, texels_rgb(fe), bin_directions(t), {}, size_t(t.n_theta) * t.n_phi};
    for (int h = 0; h < 2; ++h) in.fw[h] = weighted_slices(t.half[h], in.bins.omega);
    for (Image* im : {&out.image, &out.half[0], &out.half[1]}) {
        im->size = size;
        im->rgba.assign(size_t(size) * size, glm::vec4(0));
    }
    std::vector<uint64_t> beyond(out.threads, 0);
    auto work = [&](unsigned w) { beyond[w] = render_rows(in, size, w, out.threads, out); };
    std::vector<std::thread> pool;
    for (unsigned w = 1; w < out.threads; ++w) pool.emplace_back(work, w);
    work(0);
    for (auto& th : pool) th.join();
    for (uint64_t b : beyond) out.pixels_beyond_table += b;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}   // namespace gonio
