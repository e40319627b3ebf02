// materialx_fit.h: MaterialX's GGX directional-albedo fit and Turquin compensation, transcribed in double from
// AcademySoftwareFoundation/MaterialX @4177b2cb libraries/pbrlib/genglsl/lib/mx_microfacet_specular.glsl
// (mx_ggx_dir_albedo_analytic, mx_ggx_energy_compensation, mx_fresnel_average), for the tests of materialx-layer.
#pragma once
#include "exact.h"

#include <algorithm>
#include <cmath>

namespace mx {

// mx_ggx_dir_albedo_analytic's A (which 0) or B (which 1): the GGX albedo at n.v = x, alpha = y is F0 A + F90 B
inline double fit_ab(double x, double y, int which) {
    const double c[9][4] = {
        {0.1003, 0.9345, 1.0, 1.0},      {-0.6303, -2.323, -1.765, 0.2281}, {9.748, 2.229, 8.263, 15.94},
        {-2.038, -3.748, 11.53, -55.83}, {29.34, 1.424, 28.96, 13.08},      {-8.245, -0.7684, -7.507, 41.26},
        {-26.44, 1.436, -36.11, 54.9},   {19.99, 0.2913, 15.86, 300.2},     {-5.448, 0.6286, 33.37, -285.1}};
    const double t[9] = {1, x, y, x * y, x * x, y * y, x * x * y, x * y * y, x * x * y * y};
    double num = 0, den = 0;
    for (int i = 0; i < 9; ++i) {
        num += c[i][which] * t[i];
        den += c[i][which + 2] * t[i];
    }
    return std::clamp(num / den, 0.0, 1.0);
}

// The single-scattering GGX albedo E_ss = A + B (F = 1)
inline double albedo_ss(double mu, double alpha) { return fit_ab(mu, alpha, 0) + fit_ab(mu, alpha, 1); }

// mx_ggx_energy_compensation: 1 + F_avg (1 - E_ss) / E_ss, F_avg = F0 + (1 - F0) / 21
inline double compensation(double mu, double alpha, double f0) {
    const double e = albedo_ss(mu, alpha);
    return 1 + (f0 + (1 - f0) / 21) * (1 - e) / e;
}

// mx_dielectric_bsdf's throughput 1 - (F0 A + B) comp, F0 = ((eta - 1) / (eta + 1))^2
inline double dielectric_throughput(double mu, double alpha, double eta) {
    const double f0 = (eta - 1) * (eta - 1) / ((eta + 1) * (eta + 1));
    return 1 - (f0 * fit_ab(mu, alpha, 0) + fit_ab(mu, alpha, 1)) * compensation(mu, alpha, f0);
}

// mx_fresnel_hoffman_schlick at exponent 5, F90 = 1: Schlick less a (1 - F82) x (1 - x)^6 term anchored at x = 1/7
inline double fresnel_f82(double x, double f0, double f82) {
    const double xm = 1.0 / 7, factor = 1 / (xm * std::pow(1 - xm, 6));
    const double a = (f0 + (1 - f0) * std::pow(1 - xm, 5)) * (1 - f82) * factor;
    return f0 + (1 - f0) * std::pow(1 - x, 5) - a * x * std::pow(1 - x, 6);
}

// D G / (4 n.l n.v) of MaterialX's responses, G its mx_ggx_smith_G2 (the height-correlated form, written as its code
// writes it)
inline double ggx_lobe(exact::V3 l, exact::V3 v, double a) {
    const exact::V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
    const double a2 = a * a, ll = std::sqrt(a2 + (1 - a2) * l.z * l.z), lv = std::sqrt(a2 + (1 - a2) * v.z * v.z);
    return exact::ggx_D(h, a) * (2 * l.z * v.z / (ll * v.z + lv * l.z)) / (4 * l.z * v.z);
}

}   // namespace mx
