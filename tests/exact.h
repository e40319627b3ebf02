// exact.h: closed-form answers for smooth (delta) interfaces, written independently of the code under test
// (double precision, complex arithmetic for conductors; Born & Wolf 1.5.2 and 14.2).
#pragma once
#include <cmath>
#include <complex>

namespace exact {

// Unpolarised Fresnel reflectance from medium n1 to medium n2 (complex: n + i k), cos_i >= 0.
inline double fresnel(double cos_i, std::complex<double> n1, std::complex<double> n2) {
    using C = std::complex<double>;
    C sin_i2 = 1.0 - cos_i * cos_i;
    C cos_t = std::sqrt(1.0 - (n1 * n1 / (n2 * n2)) * sin_i2);
    if (std::imag(n1) == 0 && std::imag(n2) == 0 && std::real(1.0 - (n1 * n1 / (n2 * n2)) * sin_i2) <= 0)
        return 1.0;   // TIR
    C rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    C rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    return 0.5 * (std::norm(rs) + std::norm(rp));
}
inline double fresnel(double cos_i, double n1, double n2) {
    return fresnel(cos_i, std::complex<double>(n1), std::complex<double>(n2));
}

// Cosine of the refracted angle (Snell), n1 sin_i = n2 sin_t; requires no TIR.
inline double snell_cos(double cos_i, double n1, double n2) {
    double s = n1 / n2 * std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i));
    return std::sqrt(std::max(0.0, 1.0 - s * s));
}

// Smooth absorbing slab (index n, optical depth tau) in a medium of index n0, incidence cos_i:
// all internal reflections summed (geometric series).
struct RT {
    double R, T;
};
inline RT smooth_slab(double cos_i, double n0, double n, double tau) {
    double F = fresnel(cos_i, n0, n);
    double mu = snell_cos(cos_i, n0, n);
    double a = std::exp(-tau / mu);
    double den = 1.0 - F * F * a * a;
    return {F + (1 - F) * (1 - F) * F * a * a / den, (1 - F) * (1 - F) * a / den};
}

// Smooth coat (index n, optical depth tau) over a smooth conductor (nc + i kc), exterior n0: reflectance.
inline double smooth_coat_conductor(double cos_i, double n0, double n, double tau, double nc, double kc) {
    double F = fresnel(cos_i, n0, n);
    double mu = snell_cos(cos_i, n0, n);
    double Fc = fresnel(mu, std::complex<double>(n), std::complex<double>(nc, kc));
    double a2 = std::exp(-2 * tau / mu);
    return F + (1 - F) * (1 - F) * Fc * a2 / (1 - F * Fc * a2);
}

// Smooth coat (index n, optical depth tau) over a Lambertian base (albedo rho), exterior index n0:
// the diffuse part of the BRDF, f_d(theta_i, theta_o), with all internal reflections.
// Light enters with 1 - F(theta_i), is attenuated by exp(-tau/mu_i), reflected diffusely; of the upwelling
// isotropic radiance a fraction r = rho * int_0^1 2 mu exp(-2 tau/mu) F_int(mu) dmu returns to the base
// (internal reflection at the top, attenuated down and up), so the base sees E1 / (1 - r). Radiance leaving
// at mu_o is attenuated by exp(-tau/mu_o), transmitted with 1 - F, and divided by (n/n0)^2 (radiance
// invariant L/n^2).
struct CoatLambert {
    double n0, n, tau, rho, r;
    CoatLambert(double n0_, double n_, double tau_, double rho_) : n0(n0_), n(n_), tau(tau_), rho(rho_) {
        const int N = 200000;   // midpoint rule in mu; the integrand is smooth
        double s = 0;
        for (int i = 0; i < N; ++i) {
            double mu = (i + 0.5) / N;
            s += 2 * mu * std::exp(-2 * tau / mu) * fresnel(mu, n, n0);
        }
        r = rho * s / N;
    }
    double diffuse(double cos_i, double cos_o) const {
        double mui = snell_cos(cos_i, n0, n), muo = snell_cos(cos_o, n0, n);
        return (1 - fresnel(cos_i, n0, n)) * std::exp(-tau / mui) * rho / (M_PI * (1 - r)) * std::exp(-tau / muo) *
               (1 - fresnel(cos_o, n0, n)) * (n0 * n0) / (n * n);
    }
    double specular(double cos_i) const { return fresnel(cos_i, n0, n); }
};

}   // namespace exact

namespace exact {

// ---- rough interfaces: the Walter et al. 2007 microfacet BSDF, GGX, height-correlated Smith G2 --------
// Written independently of shaders/lib (double precision). Directions: unit vectors, z = normal, the light
// direction i above (i.z > 0); o above for reflection, below for transmission.
struct V3 {
    double x, y, z;
};
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 norm(V3 a) {
    double l = std::sqrt(dot(a, a));
    return {a.x / l, a.y / l, a.z / l};
}

inline double ggx_D(V3 m, double a) {
    if (m.z <= 0) return 0;
    double t = (m.x * m.x + m.y * m.y) / (a * a) + m.z * m.z;
    return 1.0 / (M_PI * a * a * t * t);
}
inline double ggx_Lambda(V3 w, double a) {
    double t2 = (w.x * w.x + w.y * w.y) / (w.z * w.z);
    return 0.5 * (std::sqrt(1 + a * a * t2) - 1);
}
inline double G2(V3 i, V3 o, double a) { return 1.0 / (1 + ggx_Lambda(i, a) + ggx_Lambda(o, a)); }
// Separable Smith masking-shadowing G1(i) G1(o), with GGX's G1 = 2 / (1 + sqrt(1 + a^2 tan^2 theta)) (Walter et al.
// 2007, eq. 34; Mitsuba 0.6 MicrofacetDistribution::smithG1): what the analytic models' official codes use.
inline double ggx_G1_walter(V3 w, double a) {
    double t2 = (w.x * w.x + w.y * w.y) / (w.z * w.z);
    return 2.0 / (1 + std::sqrt(1 + a * a * t2));
}
inline double G2_separable(V3 i, V3 o, double a) { return ggx_G1_walter(i, a) * ggx_G1_walter(o, a); }
// The cosine of a direction at cosine mu refracted into a medium of relative IOR eta >= 1, sqrt(1 - (1 - mu^2) / eta^2)
inline double refracted_cosine(double mu, double eta) { return std::sqrt(1 - (1 - mu * mu) / (eta * eta)); }
// OpenPBR's hemispherical Fresnel albedo E_F(eta) (footnote avg_fresnel: d'Eon's fit, "within 0.2% in [1, 3]"), and
// below 1 by E_F(eta) = 1 - eta^2 (1 - E_F(1 / eta)), as the specification prints it
inline double openpbr_fresnel_albedo(double eta) {
    const double e = eta >= 1 ? eta : 1 / eta;
    const double ef = std::log((10893 * e - 1438.2) / (-774.4 * e * e + 10212 * e + 1));
    return eta >= 1 ? ef : 1 - eta * eta * (1 - ef);
}
// A GGX reflection lobe without Fresnel, D(h) G2(l, v) / (4 l.z v.z), height-correlated G2
inline double ggx_lobe(V3 l, V3 v, double a) {
    const V3 h = norm({l.x + v.x, l.y + v.y, l.z + v.z});
    return ggx_D(h, a) * G2(l, v, a) / (4 * l.z * v.z);
}

// Reflection (dielectric n1 -> n2, or conductor with complex n2).
inline double rough_reflection(V3 i, V3 o, double a, std::complex<double> n1, std::complex<double> n2) {
    if (i.z <= 0 || o.z <= 0) return 0;
    V3 h = norm({i.x + o.x, i.y + o.y, i.z + o.z});
    return fresnel(dot(i, h), n1, n2) * ggx_D(h, a) * G2(i, o, a) / (4 * i.z * o.z);
}
// Transmission from index ni (above) to no (below), radiance BTDF (Walter 2007, eq. 21).
inline double rough_transmission(V3 i, V3 o, double a, double ni, double no) {
    if (i.z <= 0 || o.z >= 0) return 0;
    V3 h = norm({-(ni * i.x + no * o.x), -(ni * i.y + no * o.y), -(ni * i.z + no * o.z)});
    if (h.z < 0) h = {-h.x, -h.y, -h.z};
    double ih = dot(i, h), oh = dot(o, h);
    if (ih <= 0 || oh >= 0) return 0;
    double den = ni * ih + no * oh;
    return std::fabs(ih) * std::fabs(oh) / (i.z * std::fabs(o.z)) * no * no * (1 - fresnel(ih, ni, no)) * ggx_D(h, a) *
           G2(i, o, a) / (den * den);
}

}   // namespace exact
