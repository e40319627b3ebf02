// rgb_uplift.cpp: see rgb_uplift.h. Jakob & Hanika 2019 (CGF 38(2)): the sigmoid-of-a-quadratic spectrum (eqs. 3-4)
// fitted to a colour by minimising its CIE76 difference (eq. 6). The optimisation follows the authors' own (pbrt-v4
// src/pbrt/cmd/rgb2spec_opt.cpp, commit 0dc9e4fcd9caf2119b302dcc521d119756c78f8f: a Gauss-Newton step on the CIELAB
// residual, the wavelength normalised to [0, 1] over 360-830 nm, continuation from grey); gonio's code differs in its
// colour (gonio's 1 nm bands, white balanced), its analytic Jacobian, its Levenberg-Marquardt damping and in
// continuing per colour, not over a table.
#include "rgb_uplift.h"
#include "spectral_bands.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace gonio {

const char* const kUpliftMethod =
    "Jakob & Hanika 2019 (A Low-Dimensional Function Space for Efficient Spectral Upsampling, CGF 38(2)): s(nm) = "
    "S(a nm^2 + b nm + c), S(x) = 1/2 + x / (2 sqrt(1 + x^2)), fitted to the linear sRGB colour under D65 (CIE76)";

namespace {

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<Vec3, 3>;

double sigmoid_slope(double x) { return 0.5 / std::pow(1.0 + x * x, 1.5); }

// Solves m x = b by Cramer's rule; false where m is singular.
bool solve3(const Mat3& m, const Vec3& b, Vec3& x) {
    auto det = [](const Mat3& a) {
        return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
               a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    };
    const double d = det(m);
    if (!(std::fabs(d) > 0) || !std::isfinite(d)) return false;
    for (size_t c = 0; c < 3; ++c) {
        Mat3 mc = m;
        for (size_t r = 0; r < 3; ++r) mc[r][c] = b[r];
        x[c] = det(mc) / d;
    }
    return true;
}

// The colour model of rgb_uplift.h: the 1 nm bands' normalised wavelengths and XYZ weights, the white (s = 1), and
// the map from a white-balanced linear sRGB colour to XYZ.
struct Model {
    std::vector<double> u;
    std::vector<Vec3> w;
    Vec3 white_xyz{0, 0, 0}, white_rgb{};
    Mat3 rgb_to_xyz{};   // the inverse of xyz_to_linear_srgb's matrix

    Model() {
        SpectralBands bands;
        bands.width_nm = 1.0;
        for (const auto& wb : xyz_weights(bands)) w.push_back({wb[0], wb[1], wb[2]});
        for (size_t b = 0; b < w.size(); ++b) {
            u.push_back((bands.centre_nm(b) - SigmoidSpectrum::kFirstNm) /
                        (SigmoidSpectrum::kLastNm - SigmoidSpectrum::kFirstNm));
            for (size_t i = 0; i < 3; ++i) white_xyz[i] += w[b][i];
        }
        white_rgb = xyz_to_linear_srgb(white_xyz);
        Mat3 m{};   // xyz_to_linear_srgb's matrix, column by column
        for (size_t c = 0; c < 3; ++c) {
            Vec3 e{0, 0, 0};
            e[c] = 1;
            const Vec3 col = xyz_to_linear_srgb(e);
            for (size_t r = 0; r < 3; ++r) m[r][c] = col[r];
        }
        for (size_t c = 0; c < 3; ++c) {
            Vec3 e{0, 0, 0}, x{};
            e[c] = 1;
            if (!solve3(m, e, x)) throw std::logic_error("rgb_uplift: xyz_to_linear_srgb is singular");
            for (size_t r = 0; r < 3; ++r) rgb_to_xyz[r][c] = x[r];
        }
    }

    Vec3 target_xyz(const Vec3& rgb) const {
        Vec3 xyz{0, 0, 0};
        for (size_t r = 0; r < 3; ++r)
            for (size_t c = 0; c < 3; ++c) xyz[r] += rgb_to_xyz[r][c] * rgb[c] * white_rgb[c];
        return xyz;
    }

    // XYZ of the spectrum of coefficients c, and its derivatives d XYZ_i / d c_k in dxyz[i][k] (where non-null)
    Vec3 xyz(const Vec3& c, Mat3* dxyz) const {
        Vec3 out{0, 0, 0};
        if (dxyz) *dxyz = Mat3{};
        for (size_t b = 0; b < u.size(); ++b) {
            const double x = (c[0] * u[b] + c[1]) * u[b] + c[2], s = uplift_sigmoid(x);
            for (size_t i = 0; i < 3; ++i) out[i] += w[b][i] * s;
            if (!dxyz) continue;
            const double ds = sigmoid_slope(x);
            const Vec3 du{u[b] * u[b], u[b], 1.0};
            for (size_t i = 0; i < 3; ++i)
                for (size_t k = 0; k < 3; ++k) (*dxyz)[i][k] += w[b][i] * ds * du[k];
        }
        return out;
    }

    // CIELAB against the white s = 1, and d Lab / d XYZ (where non-null)
    Vec3 lab(const Vec3& xyz, Mat3* dlab) const {
        constexpr double d = 6.0 / 29.0;
        Vec3 f{}, df{};
        for (size_t i = 0; i < 3; ++i) {
            const double t = xyz[i] / white_xyz[i];
            const bool cube = t > d * d * d;
            f[i] = cube ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
            df[i] = (cube ? 1.0 / (3 * std::cbrt(t) * std::cbrt(t)) : 1.0 / (3 * d * d)) / white_xyz[i];
        }
        if (dlab) *dlab = Mat3{{{0, 116 * df[1], 0}, {500 * df[0], -500 * df[1], 0}, {0, 200 * df[1], -200 * df[2]}}};
        return {116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])};
    }

    Vec3 balanced_rgb(const Vec3& xyz) const {
        Vec3 rgb = xyz_to_linear_srgb(xyz);
        for (size_t c = 0; c < 3; ++c) rgb[c] /= white_rgb[c];
        return rgb;
    }
};

const Model& model() {
    static const Model m;
    return m;
}

double norm(const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// The Lab residual of coefficients c against the target, and its Jacobian d r / d c (where non-null).
Vec3 residual(const Model& m, const Vec3& c, const Vec3& target_lab, Mat3* jac) {
    Mat3 dxyz{}, dlab{};
    const Vec3 lab = m.lab(m.xyz(c, jac ? &dxyz : nullptr), jac ? &dlab : nullptr);
    if (jac)
        for (size_t i = 0; i < 3; ++i)
            for (size_t k = 0; k < 3; ++k) {
                (*jac)[i][k] = 0;
                for (size_t j = 0; j < 3; ++j) (*jac)[i][k] += dlab[i][j] * dxyz[j][k];
            }
    return {lab[0] - target_lab[0], lab[1] - target_lab[1], lab[2] - target_lab[2]};
}

// Levenberg-Marquardt from c towards the target; stops below tol (CIE76) or after max_steps; returns the residual.
double minimise(const Model& m, const Vec3& target_lab, Vec3& c, double tol, int max_steps, int& steps) {
    Mat3 jac{};
    Vec3 r = residual(m, c, target_lab, &jac);
    double cost = norm(r), mu = 1e-3;
    for (int n = 0; n < max_steps && cost >= tol; ++n) {
        ++steps;
        Mat3 a{};
        Vec3 g{0, 0, 0};
        for (size_t i = 0; i < 3; ++i)
            for (size_t k = 0; k < 3; ++k) {
                for (size_t j = 0; j < 3; ++j) a[i][k] += jac[j][i] * jac[j][k];
                g[i] -= jac[k][i] * r[k];
            }
        bool improved = false;
        while (!improved && mu < 1e12) {
            Mat3 damped = a;
            for (size_t i = 0; i < 3; ++i) damped[i][i] += mu * std::max(a[i][i], 1e-12);
            Vec3 step{};
            if (!solve3(damped, g, step)) {
                mu *= 10;
                continue;
            }
            const Vec3 trial{c[0] + step[0], c[1] + step[1], c[2] + step[2]};
            Mat3 trial_jac{};
            const Vec3 trial_r = residual(m, trial, target_lab, &trial_jac);
            if (std::isfinite(norm(trial_r)) && norm(trial_r) < cost) {
                c = trial, r = trial_r, jac = trial_jac, cost = norm(trial_r);
                mu = std::max(mu / 10, 1e-12);
                improved = true;
            } else {
                mu *= 10;
            }
        }
        if (!improved) break;   // no step along any damping lowers the residual: a local minimum
    }
    return cost;
}

}   // namespace

double uplift_sigmoid(double x) {
    if (std::isinf(x)) return x > 0 ? 1.0 : 0.0;
    const double r = std::sqrt(1.0 + x * x);
    // 1/2 - |x| / (2 r) = 1 / (2 r (r + |x|)) below 0, without cancellation
    return x >= 0 ? 0.5 + 0.5 * x / r : 0.5 / (r * (r - x));
}

double SigmoidSpectrum::at(double nm) const {
    if (c[0] == 0 && c[1] == 0) return uplift_sigmoid(c[2]);   // a constant, also at c2 = +-inf
    const double u = (nm - kFirstNm) / (kLastNm - kFirstNm);
    return uplift_sigmoid((c[0] * u + c[1]) * u + c[2]);
}

std::array<double, 3> SigmoidSpectrum::per_nm() const {
    // c0 u^2 + c1 u + c2 with u = (lambda - l0) k: a = c0 k^2, b = c1 k - 2 c0 l0 k^2, c = c2 - c1 l0 k + c0 (l0 k)^2
    const double l0 = kFirstNm, k = 1.0 / (kLastNm - kFirstNm);
    return {c[0] * k * k, c[1] * k - 2 * c[0] * l0 * k * k, c[2] - c[1] * l0 * k + c[0] * l0 * l0 * k * k};
}

std::array<double, 3> uplift_colour(const SigmoidSpectrum& s) {
    const Model& m = model();
    return m.balanced_rgb(m.xyz(s.c, nullptr));
}

std::array<double, 3> uplift_white_rgb() { return model().white_rgb; }

RgbUplift uplift_rgb(const std::array<double, 3>& rgb) {
    for (double v : rgb)
        if (!(v >= 0 && v <= 1))
            throw std::invalid_argument("uplift_rgb: a channel " + std::to_string(v) + " outside [0, 1]");
    RgbUplift out;
    out.rgb = rgb;
    auto inverse_sigmoid = [](double v) -> double {   // S^-1(v) = y / sqrt(1 - y^2), y = 2 v - 1
        if (v == 0 || v == 1) return v == 0 ? -INFINITY : INFINITY;
        const double y = 2 * v - 1;
        return y / std::sqrt((1 - y) * (1 + y));
    };
    if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) {
        out.grey = out.reached = true;
        out.spectrum.c = {0, 0, inverse_sigmoid(rgb[0])};
        out.rgb_reached = rgb;
        return out;
    }
    const Model& m = model();
    // continuation: from the grey of the same luminance (exactly its constant spectrum) along the straight line in
    // linear sRGB to the colour, each stage starting where the last one ended
    const double y = std::clamp(m.target_xyz(rgb)[1] / m.white_xyz[1], 1e-4, 1 - 1e-4);
    const Vec3 grey{y, y, y};
    out.spectrum.c = {0, 0, inverse_sigmoid(y)};
    constexpr int kStages = 8;
    double de = 0;
    for (int k = 1; k <= kStages; ++k) {
        const double t = double(k) / kStages;
        Vec3 at{};
        for (size_t i = 0; i < 3; ++i) at[i] = grey[i] + t * (rgb[i] - grey[i]);
        const bool last = k == kStages;
        de = minimise(m, m.lab(m.target_xyz(at), nullptr), out.spectrum.c, last ? 1e-9 : 1e-4, last ? 200 : 50,
                      out.iterations);
    }
    out.rgb_reached = uplift_colour(out.spectrum);
    out.delta_e76 = de;
    out.reached = de < kUpliftMaxDeltaE;
    return out;
}

}   // namespace gonio
