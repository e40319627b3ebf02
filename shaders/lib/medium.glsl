// medium.glsl: scattering inside a layer's medium (GLSL and C++ through compat.glsl): the Henyey-Greenstein phase
// function and its sampler, the SGGX specular microflake phase function, its projected area and its sampler, and
// free-flight sampling of an RGB medium up to the next interface.
// Conventions here: d is the direction of propagation (not "away from the surface" as at interfaces), g > 0
// scatters forward; distances are in units of the layer's thickness along the path, so a medium of optical depth
// tau (per thickness) has extinction sigma = tau per unit distance, and a path at cosine mu to the normal reaches
// the other interface after s_max = (distance in z) / |mu|.
#ifndef GONIO_MEDIUM_GLSL
#define GONIO_MEDIUM_GLSL
#include "compat.glsl"

// Below this |g| the phase function is sampled as isotropic: the inversion below loses all its digits to
// cancellation as g -> 0 (the density differs from isotropic by at most 3 |g|, 3e-4).
const float HG_ISOTROPIC_BELOW = 1e-4f;

// The Henyey-Greenstein phase function (Henyey & Greenstein 1941), 1/sr, normalised over the sphere:
// p(cos) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^(3/2)), cos between the directions before and after.
GONIO_INLINE float phase_hg(float cos_theta, float g) {
    float denom = 1.0f + g * g - 2.0f * g * cos_theta;
    return (1.0f - g * g) / (4.0f * PI * denom * sqrt(max(denom, 1e-30f)));
}

// cos_theta with the density of phase_hg, by inversion of its CDF in cos, F(cos) = (1 - g^2) / (2 g) *
// ((1 + g^2 - 2 g cos)^(-1/2) - 1 / (1 + g)): cos = (1 + g^2 - ((1 - g^2) / (1 - g + 2 g u))^2) / (2 g).
// u = 0 gives -1, u = 1 gives 1 (as the isotropic branch 2u - 1 does).
GONIO_INLINE float sample_hg_cos(float g, float u) {
    if (abs(g) < HG_ISOTROPIC_BELOW) return clamp(2.0f * u - 1.0f, -1.0f, 1.0f);
    float q = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
    return clamp((1.0f + g * g - q * q) / (2.0f * g), -1.0f, 1.0f);
}

// A direction of propagation after scattering from d (unit), with the density phase_hg(dot(d, result), g).
GONIO_INLINE vec3 sample_henyey_greenstein(vec3 d, float g, float u1, float u2) {
    float c = sample_hg_cos(g, u1);
    float s = sqrt(max(0.0f, 1.0f - c * c));
    float phi = 2.0f * PI * u2;
    // an orthonormal frame around d (Duff et al. 2017, "Building an orthonormal basis, revisited")
    float sign = d.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sign + d.z);
    float b = d.x * d.y * a;
    vec3 t1 = vec3(1.0f + sign * d.x * d.x * a, sign * b, -sign * d.x);
    vec3 t2 = vec3(b, sign + d.y * d.y * a, -d.y);
    return normalize(t1 * (s * cos(phi)) + t2 * (s * sin(phi)) + d * c);
}

// ----- Microflake media: the SGGX distribution (Heitz, Dupuy, Crassin & Dachsbacher 2015, "The SGGX microflake
// distribution") with specular flakes. A medium of fibres along the layer's normal or of flakes facing it has a
// diagonal S in the layer's frame (z the normal), which is all the walk needs: S is carried as its diagonal.
// sigma = alpha^2 is the fibres' cross-section as the sheen authors set it (Zeltner, Burley & Chiang 2022;
// tizian/ltc-sheen fitting/src/sggx.h from_fiber, commit 92624114: S = sigma^2 t t^T + (I - t t^T), t the fibre).
// Conventions: wi and wo point away from the scattering point (wi = -d, d the direction of propagation before).
const uint MEDIUM_PHASE_HG = 0u;   // Henyey-Greenstein (phase_g)
const uint MEDIUM_PHASE_SGGX_FIBRE = 1u;   // SGGX fibres along the normal: S = diag(1, 1, sigma^2)
const uint MEDIUM_PHASE_SGGX_FLAKE = 2u;   // SGGX flakes facing the normal: S = diag(sigma^2, sigma^2, 1)

// The diagonal of S for a microflake medium of roughness alpha (sigma = alpha^2).
GONIO_INLINE vec3 sggx_diagonal(uint phase, float alpha) {
    float sigma = alpha * alpha;
    float s2 = sigma * sigma;
    return phase == MEDIUM_PHASE_SGGX_FIBRE ? vec3(1.0f, 1.0f, s2) : vec3(s2, s2, 1.0f);
}

// The adjugate of a diagonal S, det(S) S^-1, as its diagonal: the quadratic forms below read it instead of S^-1, which
// at sigma 1e-4 would hold 1e8.
GONIO_INLINE vec3 sggx_adjugate(vec3 S) { return vec3(S.y * S.z, S.x * S.z, S.x * S.y); }

// The projected area of the flakes seen from w (unit), sigma(w) = sqrt(w^T S w) (Heitz et al. 2015, Eq. 9): the
// extinction along w is the density times this, the same for w and -w.
GONIO_INLINE float sggx_projected_area(vec3 S, vec3 w) { return sqrt(max(dot(w * w, S), 0.0f)); }

// The distribution of flake normals (1/sr), D(m) = 1 / (pi sqrt|S| (m^T S^-1 m)^2) = |S|^(3/2) / (pi (m^T adj(S) m)^2)
// (Heitz et al. 2015, Eq. 7): over the sphere, <w, m>+ D(m) integrates to sigma(w).
GONIO_INLINE float sggx_ndf(vec3 S, vec3 m) {
    float det = S.x * S.y * S.z;
    float q = dot(m * m, sggx_adjugate(S));
    return q > 0.0f ? det * sqrt(det) / (PI * q * q) : 0.0f;
}

// The specular microflake phase function (1/sr, normalised over the sphere), f(wi, wo) = D(h) / (4 sigma(wi)),
// h = (wi + wo) / |wi + wo| (Heitz et al. 2015, Eq. 15). sigma(wi) f(wi, wo) is symmetric: reciprocity.
GONIO_INLINE float phase_sggx_specular(vec3 S, vec3 wi, vec3 wo) {
    vec3 h = wi + wo;
    float len2 = dot(h, h);
    float area = sggx_projected_area(S, wi);
    if (!(len2 > 0.0f) || !(area > 0.0f)) return 0.0f;
    return sggx_ndf(S, h * inversesqrt(len2)) / (4.0f * area);
}

// A flake normal m seen from wi, with density <wi, m>+ D(m) / sigma(wi) (Heitz et al. 2015, supplemental material,
// "sample_VNDF"): a uniform point of the unit disc lifted to the hemisphere and mapped by the ellipsoid's
// transform in the frame (wk, wj, wi). For a diagonal S the 2x2 and 3x3 minors are read from adj(S) and det(S)
// directly (the same numbers; no cancellation between O(1) products where sigma is small).
GONIO_INLINE vec3 sample_sggx_visible_normal(vec3 S, vec3 wi, float u1, float u2) {
    float r = sqrt(u1);
    float phi = 2.0f * PI * u2;
    float u = r * cos(phi), v = r * sin(phi);
    float w = sqrt(max(0.0f, 1.0f - u * u - v * v));
    // an orthonormal frame (wk, wj) around wi (Duff et al. 2017)
    float sign = wi.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sign + wi.z);
    float b = wi.x * wi.y * a;
    vec3 wk = vec3(1.0f + sign * wi.x * wi.x * a, sign * b, -sign * wi.x);
    vec3 wj = vec3(b, sign + wi.y * wi.y * a, -wi.y);
    vec3 A = sggx_adjugate(S);
    float S_ii = dot(wi * wi, S), S_ki = dot(wk * wi, S), S_ji = dot(wj * wi, S);
    float sqrt_det = sqrt(S.x * S.y * S.z);
    float tmp = sqrt(max(dot(wk * wk, A), 1e-37f));   // sqrt(S_jj S_ii - S_ji^2)
    float cof_kj = dot(wk * wj, A);   // S_ki S_ji - S_kj S_ii
    float inv_sqrt_ii = inversesqrt(max(S_ii, 1e-37f));
    vec3 Mk = vec3(sqrt_det / tmp, 0.0f, 0.0f);
    vec3 Mj = vec3(-inv_sqrt_ii * cof_kj / tmp, inv_sqrt_ii * tmp, 0.0f);
    vec3 Mi = vec3(inv_sqrt_ii * S_ki, inv_sqrt_ii * S_ji, inv_sqrt_ii * S_ii);
    vec3 m = normalize(Mk * u + Mj * v + Mi * w);
    return normalize(wk * m.x + wj * m.y + wi * m.z);
}

// A direction of propagation after a specular microflake scatters the path travelling along d: a visible normal
// from wi = -d and the mirror direction about it, density phase_sggx_specular(S, -d, result) (the Jacobian of the
// reflection, 1 / (4 <wi, m>), turns the visible normals' density into it): the weight is 1.
GONIO_INLINE vec3 sample_sggx_specular(vec3 S, vec3 d, float u1, float u2) {
    vec3 wi = -d;
    vec3 m = sample_sggx_visible_normal(S, wi, u1, u2);
    return normalize(m * (2.0f * dot(wi, m)) - wi);
}

// The outcome of a free flight: where the path scatters (scattered, at distance s < s_max) or that it reaches the
// next interface (s = s_max), and the weight that makes the estimate unbiased in every channel.
struct FreeFlight {
    float s;
    bool scattered;
    vec3 weight;   // scattered: sigma exp(-sigma s) / p(s); reached: exp(-sigma s_max) / P(reach); the caller
                   // multiplies by the single-scattering albedo at a scattering event
    float u_rest;  // a uniform number in [0, 1) independent of the flight: what u_channel leaves once the channel is
                   // chosen, (u_channel - P(channels before c)) / P(c) (for the caller's Russian roulette)
};

// Free-flight sampling in an RGB medium of extinction sigma (per unit distance) up to s_max: a channel c is
// chosen with probability channel_prob[c], s is drawn from sigma[c] exp(-sigma[c] s), and the weight divides by
// the density of the whole mixture, sum_k channel_prob[k] sigma[k] exp(-sigma[k] s) (the balance heuristic over
// channels, as pbrt-v4's spectral free flight; Wilkie et al. 2014 "hero wavelength" in RGB). Unbiased for every
// channel whose channel_prob > 0 wherever sigma > 0 (channel_prob sums to 1); a channel of sigma 0 never scatters.
// A grey medium (sigma the same in every channel) has weight 1 exactly: the mixture is the one density.
// u_channel picks the channel, u the distance.
GONIO_INLINE FreeFlight sample_free_flight(vec3 sigma, float s_max, vec3 channel_prob, float u_channel, float u) {
    bool first = u_channel < channel_prob.x, second = !first && u_channel < channel_prob.x + channel_prob.y;
    float sc = first ? sigma.x : (second ? sigma.y : sigma.z);
    float below = first ? 0.0f : (second ? channel_prob.x : channel_prob.x + channel_prob.y);
    float pc = first ? channel_prob.x : (second ? channel_prob.y : channel_prob.z);
    // -log(1 - u) / sigma_c: the distance to the next collision in the chosen channel (infinite for sigma_c = 0)
    float s = sc > 0.0f ? -log(max(1.0f - u, 1e-30f)) / sc : s_max;
    FreeFlight f;
    f.scattered = s < s_max;
    f.s = f.scattered ? s : s_max;
    f.u_rest = pc > 0.0f ? min((u_channel - below) / pc, 0.99999994f) : 0.0f;
    if (sigma.x == sigma.y && sigma.y == sigma.z) {
        f.weight = vec3(1.0f);
        return f;
    }
    vec3 tr = exp(-sigma * f.s);
    vec3 dens = f.scattered ? sigma * tr : tr;   // per channel: density of scattering at s, or probability of reaching
    float mix_density = dot(channel_prob, dens);
    f.weight = mix_density > 0.0f ? dens / mix_density : vec3(0.0f);
    return f;
}
#endif
