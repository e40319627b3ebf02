// spectral_sphere.cpp: see spectral_sphere.h.
#include "spectral_sphere.h"
#include "colour_difference.h"
#include "colour_error.h"
#include "histogram.h"
#include "statistics.h"

#include <cmath>
#include <stdexcept>

namespace gonio {

namespace {

constexpr double kPi = 3.14159265358979323846;

Colour3 pixel_xyz(const glm::vec4& p, double white_y) {
    const Colour3 xyz = linear_srgb_to_xyz({p.x, p.y, p.z});
    return {xyz[0] / white_y, xyz[1] / white_y, xyz[2] / white_y};
}

double white_luminance(const glm::vec4& p) { return linear_srgb_to_xyz({p.x, p.y, p.z})[1]; }

Image blank_like(const Image& im) {
    Image out;
    out.size = im.size;
    out.rgba.assign(im.rgba.size(), glm::vec4(0));
    return out;
}

}   // namespace

ReferenceTable table_from_spectral_halves(const SpectralResult& a, const SpectralResult& b) {
    const SimResult& first = a.groups.front();
    const SimResult& other = b.groups.front();
    if (first.angles.size() != other.angles.size() || first.n_theta != other.n_theta || first.n_phi != other.n_phi)
        throw std::logic_error("table_from_spectral_halves: the halves differ in angles or bins");
    ReferenceTable t;
    t.n_theta = first.n_theta;
    t.n_phi = first.n_phi;
    t.dtheta_deg = first.options.dtheta_deg;
    t.dphi_deg = first.options.dphi_deg;
    t.independent_halves = true;
    for (size_t k = 0; k < first.angles.size(); ++k) {
        if (k > 0 && !(first.angles[k].theta_i_deg > first.angles[k - 1].theta_i_deg))
            throw std::logic_error("table_from_spectral_halves: the angles are not ascending");
        t.theta_i_deg.push_back(first.angles[k].theta_i_deg);
        const SpectralResult* half[2] = {&a, &b};
        for (int h = 0; h < 2; ++h) {
            const SpectralSlice s = spectral_slice(*half[h], k, kReflection);
            t.half[h].emplace_back(s.srgb.begin(), s.srgb.end());
        }
        uint64_t paths = 0;   // every pass's paths, both halves
        for (const SpectralResult* r : half)
            for (const SimResult& g : r->groups) paths += g.angles[k].paths;
        t.paths_per_angle = paths;
    }
    return t;
}

ReferenceTable white_diffuser_table(const ReferenceTable& t) {
    ReferenceTable w = t;
    const glm::vec3 white(float(1 / kPi));
    for (auto& half : w.half)
        for (std::vector<glm::vec3>& bins : half) bins.assign(bins.size(), white);
    w.paths_per_angle = 0;
    return w;
}

SphereColourError sphere_colour_error(const ReferenceRender& a, const ReferenceRender& b, const Image& white) {
    if (a.image.size != b.image.size || a.image.size != white.size)
        throw std::logic_error("sphere_colour_error: the renders differ in size");
    SphereColourError e;
    e.de2000 = blank_like(a.image);
    e.de_itp = blank_like(a.image);
    e.noise = blank_like(a.image);
    std::vector<double> de2000, itp, noise;
    for (size_t i = 0; i < a.image.rgba.size(); ++i) {
        const double wy = white_luminance(white.rgba[i]);
        if (!(a.image.rgba[i].w > 0) || !(wy > 0)) continue;
        const Colour3 xa = pixel_xyz(a.image.rgba[i], wy), xb = pixel_xyz(b.image.rgba[i], wy);
        if (!(xa[1] >= kLitReflectanceFactor)) continue;
        const ColourDifference d = colour_difference(xa, xb);
        const double da =
            delta_e_2000(xyz_to_lab(pixel_xyz(a.half[0].rgba[i], wy)), xyz_to_lab(pixel_xyz(a.half[1].rgba[i], wy)));
        const double db =
            delta_e_2000(xyz_to_lab(pixel_xyz(b.half[0].rgba[i], wy)), xyz_to_lab(pixel_xyz(b.half[1].rgba[i], wy)));
        const double n = 0.5 * std::sqrt(da * da + db * db);
        e.de2000.rgba[i] = glm::vec4(glm::vec3(float(d.de2000)), 1);
        e.de_itp.rgba[i] = glm::vec4(glm::vec3(float(d.de_itp)), 1);
        e.noise.rgba[i] = glm::vec4(glm::vec3(float(n)), 1);
        de2000.push_back(d.de2000);
        itp.push_back(d.de_itp);
        noise.push_back(n);
    }
    e.lit = de2000.size();
    e.median_de2000 = nearest_rank_quantile(de2000, 0.5);
    e.p95_de2000 = nearest_rank_quantile(de2000, 0.95);
    e.max_de2000 = nearest_rank_quantile(de2000, 1);
    e.median_de_itp = nearest_rank_quantile(itp, 0.5);
    e.p95_de_itp = nearest_rank_quantile(itp, 0.95);
    e.max_de_itp = nearest_rank_quantile(itp, 1);
    e.median_noise = nearest_rank_quantile(noise, 0.5);
    return e;
}

}   // namespace gonio
