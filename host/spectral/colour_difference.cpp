// colour_difference.cpp: see colour_difference.h.
#include "colour_difference.h"
#include "colorimetry.h"

#include <cmath>

namespace gonio {

namespace {

constexpr double kPi = 3.14159265358979323846;
// D65's white at Y = 1 from its chromaticity (IEC 61966-2-1: x 0.3127, y 0.3290)
constexpr Colour3 kD65WhiteXyz{kD65White.x / kD65White.y, 1.0, (1 - kD65White.x - kD65White.y) / kD65White.y};

double deg(double rad) { return rad * 180.0 / kPi; }
double rad(double deg) { return deg * kPi / 180.0; }

Colour3 mul(const double m[3][3], const Colour3& v) {
    return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

// CIE 015:2018 eq. 8.9: the cube root, continued linearly below (6/29)^3
double lab_f(double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

// SMPTE ST 2084 (PQ) of a luminance in units of 10000 cd/m^2
double pq(double y) {
    constexpr double m1 = 2610.0 / 16384.0, m2 = 2523.0 / 4096.0 * 128.0, c1 = 3424.0 / 4096.0,
                     c2 = 2413.0 / 4096.0 * 32.0, c3 = 2392.0 / 4096.0 * 32.0;
    const double p = std::pow(std::fmax(y, 0.0), m1);
    return std::pow((c1 + c2 * p) / (1 + c3 * p), m2);
}

}   // namespace

Colour3 xyz_to_lab(const Colour3& xyz) {
    const double fx = lab_f(xyz[0] / kD65WhiteXyz[0]), fy = lab_f(xyz[1] / kD65WhiteXyz[1]),
                 fz = lab_f(xyz[2] / kD65WhiteXyz[2]);
    return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

double delta_e_2000(const Colour3& lab1, const Colour3& lab2) {
    const double L1 = lab1[0], a1 = lab1[1], b1 = lab1[2], L2 = lab2[0], a2 = lab2[1], b2 = lab2[2];
    const double C1 = std::hypot(a1, b1), C2 = std::hypot(a2, b2), Cbar = 0.5 * (C1 + C2);
    const double Cbar7 = std::pow(Cbar, 7);
    const double G = 0.5 * (1 - std::sqrt(Cbar7 / (Cbar7 + std::pow(25.0, 7))));   // eq. 4
    const double a1p = (1 + G) * a1, a2p = (1 + G) * a2;
    const double C1p = std::hypot(a1p, b1), C2p = std::hypot(a2p, b2);
    auto hue = [](double b, double ap) {   // eq. 7, degrees in [0, 360)
        if (b == 0 && ap == 0) return 0.0;
        const double h = deg(std::atan2(b, ap));
        return h < 0 ? h + 360 : h;
    };
    const double h1p = hue(b1, a1p), h2p = hue(b2, a2p);
    const double dLp = L2 - L1, dCp = C2p - C1p;
    double dhp = 0;   // eq. 10
    if (C1p * C2p != 0) {
        dhp = h2p - h1p;
        if (dhp > 180)
            dhp -= 360;
        else if (dhp < -180)
            dhp += 360;
    }
    const double dHp = 2 * std::sqrt(C1p * C2p) * std::sin(rad(dhp / 2));
    const double Lbp = 0.5 * (L1 + L2), Cbp = 0.5 * (C1p + C2p);
    double hbp = h1p + h2p;   // eq. 14
    if (C1p * C2p != 0) {
        if (std::fabs(h1p - h2p) <= 180)
            hbp = 0.5 * (h1p + h2p);
        else
            hbp = h1p + h2p < 360 ? 0.5 * (h1p + h2p + 360) : 0.5 * (h1p + h2p - 360);
    }
    const double T = 1 - 0.17 * std::cos(rad(hbp - 30)) + 0.24 * std::cos(rad(2 * hbp)) +
                     0.32 * std::cos(rad(3 * hbp + 6)) - 0.20 * std::cos(rad(4 * hbp - 63));
    const double dtheta = 30 * std::exp(-std::pow((hbp - 275) / 25, 2));
    const double Cbp7 = std::pow(Cbp, 7);
    const double RC = 2 * std::sqrt(Cbp7 / (Cbp7 + std::pow(25.0, 7)));
    const double SL = 1 + 0.015 * (Lbp - 50) * (Lbp - 50) / std::sqrt(20 + (Lbp - 50) * (Lbp - 50));
    const double SC = 1 + 0.045 * Cbp, SH = 1 + 0.015 * Cbp * T;
    const double RT = -std::sin(rad(2 * dtheta)) * RC;
    const double x = dLp / SL, y = dCp / SC, z = dHp / SH;
    return std::sqrt(x * x + y * y + z * z + RT * y * z);
}

Colour3 xyz_to_ictcp(const Colour3& xyz_cd_m2) {
    // XYZ to BT.2020 RGB (ITU-R BT.2020's primaries and D65), then BT.2100's LMS (Table 6)
    static constexpr double to2020[3][3] = {{1.7166511880, -0.3556707838, -0.2533662814},
                                            {-0.6666843518, 1.6164812366, 0.0157685458},
                                            {0.0176398574, -0.0427706133, 0.9421031212}};
    static constexpr double toLms[3][3] = {{1688.0 / 4096, 2146.0 / 4096, 262.0 / 4096},
                                           {683.0 / 4096, 2951.0 / 4096, 462.0 / 4096},
                                           {99.0 / 4096, 309.0 / 4096, 3688.0 / 4096}};
    const Colour3 lms = mul(toLms, mul(to2020, xyz_cd_m2));
    const double L = pq(lms[0] / 10000), M = pq(lms[1] / 10000), S = pq(lms[2] / 10000);
    return {0.5 * L + 0.5 * M, (6610 * L - 13613 * M + 7003 * S) / 4096, (17933 * L - 17390 * M - 543 * S) / 4096};
}

double delta_e_itp(const Colour3& a, const Colour3& b) {
    const double dI = a[0] - b[0], dT = 0.5 * (a[1] - b[1]), dP = a[2] - b[2];
    return 720 * std::sqrt(dI * dI + dT * dT + dP * dP);
}

Colour3 linear_srgb_to_xyz(const Colour3& rgb) {
    static constexpr double m[3][3] = {{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
    return mul(m, rgb);
}

ColourDifference colour_difference(const Colour3& xyz1, const Colour3& xyz2) {
    auto cd = [](const Colour3& x) {
        return Colour3{x[0] * kItpWhiteCdM2, x[1] * kItpWhiteCdM2, x[2] * kItpWhiteCdM2};
    };
    return {delta_e_2000(xyz_to_lab(xyz1), xyz_to_lab(xyz2)),
            delta_e_itp(xyz_to_ictcp(cd(xyz1)), xyz_to_ictcp(cd(xyz2)))};
}

}   // namespace gonio
