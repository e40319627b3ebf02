// tools/fgd_quadrature_measure.cpp: the measurement behind models/fgd_quadrature.glsl, not built by CMake.
// A converged double-precision reference (Gauss-Legendre in phi over the visible range, midpoint in the
// tan(theta_m) = alpha (e^(L u) - 1) variable) against fgd_quadrature and against two separate midpoint rules that
// fgd_quadrature stands in for, kept here verbatim: old_entry (a Belcour table entry, 256 u x 64 phi midpoint nodes
// over phi in [0, pi], in float; columns "old2") and old_coat (a coat-albedo node, 600 u x 48 phi midpoint nodes over
// [0, pi] of the coat's top_reflection, in double; column "old1"). Columns "new": fgd_quadrature.
//   g++ -O2 -std=c++20 -I shaders/lib tools/fgd_quadrature_measure.cpp -o /tmp/fgdm -lpthread
//   /tmp/fgdm NU NPHI NT NP THREADS   (reference u x phi nodes, 0 0 to skip it; fgd_quadrature's nodes)
// One line per (interface, use, alpha, mu): use 1 coat-albedo node, 2 Belcour table node, 4 mu = 1e-3.
#include "compat.glsl"
#include "kernel_interface.glsl"
#include "models/common.glsl"
#include "models/fgd_quadrature.glsl"
#include <cstdio>
#include <complex>
#include <vector>
#include <thread>
#include <atomic>
#include <algorithm>
#include <string>
using glm::dvec3;

// ---- old method 2: a Belcour table entry by its own midpoint rule (256 u x 64 phi nodes, float) ----
const uint TABLE_NODES_THETA = 256u, TABLE_NODES_PHI = 64u;
vec4 old_entry(LayerGpu L, float mu, float alpha, bool g2) {
    uint kind = layer_kind(L);
    float a = max(alpha, MODEL_MIN_ALPHA);
    float c = max(mu, 1e-4f);
    vec3 l = vec3(sqrt(max(0.0f, 1.0f - c * c)), 0.0f, c);
    float eta = layer_eta(L);
    float eta_c = kind == KIND_DIELECTRIC ? min(eta, 1.0f / eta) : 2.0f;
    vec3 cond_eta = layer_conductor_eta(L), cond_k = layer_conductor_k(L);
    float theta_max = min(0.5f * (0.5f * PI + acos(c)), 1.5706f);
    float log_range = log(tan(theta_max) / a + 1.0f);
    vec3 fgd = vec3(0.0f);
    float lobe = 0.0f, outside = 0.0f;
    float dphi = PI / float(TABLE_NODES_PHI);
    float cd = cos(dphi), sd = sin(dphi);
    for (uint i = 0u; i < TABLE_NODES_THETA; ++i) {
        float u = (float(i) + 0.5f) / float(TABLE_NODES_THETA);
        float e = exp(log_range * u);
        float tan_m = a * (e - 1.0f);
        float cos_m = 1.0f / sqrt(1.0f + tan_m * tan_m), sin_m = tan_m * cos_m;
        float dtheta = a * log_range * e * cos_m * cos_m;
        float d = ggx_D(vec3(sin_m, 0.0f, cos_m), a) * sin_m * dtheta;
        float cp = cos(0.5f * dphi), sp = sin(0.5f * dphi);
        for (uint j = 0u; j < TABLE_NODES_PHI; ++j) {
            vec3 m = vec3(sin_m * cp, sin_m * sp, cos_m);
            float lm = dot(l, m);
            vec3 v = reflect_about(l, m);
            float cn = cp * cd - sp * sd;
            sp = sp * cd + cp * sd;
            cp = cn;
            if (lm <= 0.0f || v.z <= 0.0f) continue;
            float w = d * (g2 ? ggx_G2(l, v, a) : ggx_G2_separable(l, v, a)) * lm;
            if (kind == KIND_CONDUCTOR) fgd += w * fresnel_conductor(lm, cond_eta, cond_k);
            else if (kind == KIND_DIELECTRIC) fgd += vec3(w * fresnel_dielectric(lm, eta));
            lobe += w;
            if (1.0f - v.z * v.z > eta_c * eta_c) outside += w;
        }
    }
    float norm = 2.0f * dphi / (float(TABLE_NODES_THETA) * c);
    float tir = (eta_c >= 1.0f || !(lobe > 0.0f)) ? 1.0f : 1.0f - outside / lobe;
    return vec4(fgd.x * norm, fgd.y * norm, fgd.z * norm, tir);
}
// ---- old method 1: a coat-albedo node by its own midpoint rule (600 u x 48 phi nodes, double) ----
float old_coat(float alpha0, float eta, float mu_node) {
    const double a = alpha0, L = std::log(1e4 / a + 1);
    const int NU = 600, NP = 96;
    double mu = std::max(double(mu_node), 1e-3);
    glm::dvec3 l(std::sqrt(1 - mu * mu), 0, mu);
    double acc = 0;
    for (int k = 0; k < NU; ++k) {
        double u = (k + 0.5) / NU, tan_m = a * (std::exp(L * u) - 1), tm = std::atan(tan_m);
        double dtm = a * L * std::exp(L * u) / (1 + tan_m * tan_m);
        for (int j = 0; j < NP / 2; ++j) {
            double pm = (j + 0.5) / NP * 2 * M_PI;
            glm::dvec3 m(std::sin(tm) * std::cos(pm), std::sin(tm) * std::sin(pm), std::cos(tm));
            double lm = glm::dot(l, m);
            if (lm <= 0) continue;
            glm::dvec3 v = 2 * lm * m - l;
            if (v.z <= 0) continue;
            acc += 2 * top_reflection(glm::vec3(l), glm::vec3(glm::normalize(v)), alpha0, eta) * v.z * 4 * lm *
                   std::sin(tm) * dtm;
        }
    }
    return float(std::min(1.0, acc / NU * 2 * M_PI / NP));
}

// ---- double reference ----
struct If { int kind; double eta; dvec3 n, k; };
double Fd(double c, double eta) {
    double s2t = (1 - c * c) / (eta * eta);
    if (s2t >= 1) return 1;
    double ct = std::sqrt(1 - s2t);
    double rs = (c - eta * ct) / (c + eta * ct), rp = (eta * c - ct) / (eta * c + ct);
    return 0.5 * (rs * rs + rp * rp);
}
double Fc1(double c, double n, double k) {   // exact conductor, complex arithmetic
    std::complex<double> e(n, k), s2(1 - c * c, 0);
    std::complex<double> ct = std::sqrt(e * e - s2);
    std::complex<double> rs = (c - ct) / (c + ct), rp = (e * e * c - ct) / (e * e * c + ct);
    return 0.5 * (std::norm(rs) + std::norm(rp));
}
double lam(double z, double sx2, double a) { return 0.5 * (std::sqrt(1 + a * a * sx2 / (z * z)) - 1); }
// Gauss-Legendre nodes on [-1, 1]
void gl(int n, std::vector<double>& x, std::vector<double>& w) {
    x.resize(n); w.resize(n);
    for (int i = 0; i < n; ++i) {
        double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), pp;
        for (int it = 0; it < 100; ++it) {
            double p1 = 1, p2 = 0;
            for (int j = 1; j <= n; ++j) { double p3 = p2; p2 = p1; p1 = ((2 * j - 1) * z * p2 - (j - 1) * p3) / j; }
            pp = n * (z * p1 - p2) / (z * z - 1);
            double z1 = z; z = z1 - p1 / pp;
            if (std::fabs(z - z1) < 1e-15) break;
        }
        x[i] = z; w[i] = 2 / ((1 - z * z) * pp * pp);
    }
}
// returns rgb for G2 (out g2) and separable (out sep)
void reference(const If& I, double mu, double a, int NU, int NPHI, dvec3& g2, dvec3& sep) {
    std::vector<double> gx, gw; gl(NPHI, gx, gw);
    double c = std::max(mu, 1e-12), sl = std::sqrt(1 - c * c), tl = std::acos(c);
    double tmax = 0.5 * (0.5 * M_PI + tl);
    double tanmax = std::tan(std::min(tmax, M_PI / 2 - 1e-9));
    double L = std::log(tanmax / a + 1);
    double lamL = lam(c, sl * sl, a);
    g2 = sep = dvec3(0);
    for (int i = 0; i < NU; ++i) {
        double u = (i + 0.5) / NU, e = std::exp(L * u), tan_m = a * (e - 1);
        double cm = 1 / std::sqrt(1 + tan_m * tan_m), sm = tan_m * cm;
        double dth = a * L * e * cm * cm;
        double s = (sm * sm) / (a * a) + cm * cm;
        double D = 1 / (M_PI * a * a * s * s);
        // visible phi range: v.z > 0 <=> cos(phi) > -c cos(2 tm) / (sl sin(2 tm))
        double phimax = M_PI;
        if (sl * sm > 0) {
            double c0 = -c * (cm * cm - sm * sm) / (sl * 2 * sm * cm);
            if (c0 >= 1) continue;
            phimax = c0 <= -1 ? M_PI : std::acos(c0);
        }
        dvec3 ag(0), as(0);
        for (int j = 0; j < NPHI; ++j) {
            double ph = 0.5 * phimax * (gx[j] + 1), wj = 0.5 * phimax * gw[j];
            dvec3 m(sm * std::cos(ph), sm * std::sin(ph), cm);
            dvec3 l(sl, 0, c);
            double lm = glm::dot(l, m);
            dvec3 v = 2 * lm * m - l;
            if (lm <= 0 || v.z <= 0) continue;
            double lv = lam(v.z, v.x * v.x + v.y * v.y, a);
            double G2 = 1 / (1 + lamL + lv), GS = 1 / (1 + lamL) / (1 + lv);
            dvec3 F;
            if (I.kind == 1) F = dvec3(Fd(lm, I.eta));
            else F = dvec3(Fc1(lm, I.n.x, I.k.x), Fc1(lm, I.n.y, I.k.y), Fc1(lm, I.n.z, I.k.z));
            double wt = wj * D * lm / c;
            ag += F * (wt * G2); as += F * (wt * GS);
        }
        g2 += ag * (sm * dth); sep += as * (sm * dth);
    }
    g2 *= 2.0 / NU; sep *= 2.0 / NU;
}
LayerGpu layer(const If& I) {
    LayerGpu L;
    L.p0 = vec4(I.kind == 1 ? float(KIND_DIELECTRIC) : float(KIND_CONDUCTOR), 0.1f, float(I.eta), float(1 / I.eta));
    L.tau = vec4(0);
    L.c0 = vec4(float(I.n.x), float(I.n.y), float(I.n.z), 0);
    L.c1 = vec4(float(I.k.x), float(I.k.y), float(I.k.z), 0);
    return L;
}
int main(int argc, char** argv) {
    int NU = argc > 1 ? atoi(argv[1]) : 4096, NPHI = argc > 2 ? atoi(argv[2]) : 64;
    int nt_new = argc > 3 ? atoi(argv[3]) : 256, np_new = argc > 4 ? atoi(argv[4]) : 64;
    std::vector<If> ifs;
    for (double e : {1.1, 1.33, 1.5, 2.0, 3.0}) ifs.push_back({1, e, dvec3(0), dvec3(0)});
    ifs.push_back({2, 1.0, dvec3(0.143, 0.374, 1.442), dvec3(3.983, 2.385, 1.603)});   // gold-like
    std::vector<float> alphas = {1e-4f, 0.01f, 0.05f, 0.1f, 0.3f, 0.6f, 1.0f};
    struct Pt { int iface; float alpha, mu; int use; };   // use bit 1: coat node, bit 2: Belcour node
    std::vector<Pt> pts;
    for (int f = 0; f < int(ifs.size()); ++f)
        for (float a : alphas) {
            std::vector<std::pair<float, int>> mus;
            if (ifs[f].kind == 1) for (uint i = 0; i < COAT_ALBEDO_NODES; ++i) mus.push_back({coat_albedo_node_mu(i), 1});
            for (uint c = 0; c < TABLE_NMU; ++c) mus.push_back({table_node_mu(c), 2});
            mus.push_back({1e-3f, 4});
            for (auto [mu, u] : mus) pts.push_back({f, a, mu, u});
        }
    std::vector<std::string> out(pts.size());
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t i; (i = next++) < pts.size();) {
            const Pt& p = pts[i];
            const If& I = ifs[p.iface];
            dvec3 rg, rs;
            if (NU > 0) reference(I, p.mu, p.alpha, NU, NPHI, rg, rs); else rg = rs = dvec3(0);
            LayerGpu L = layer(I);
            vec4 o2g = old_entry(L, p.mu, p.alpha, true), o2s = old_entry(L, p.mu, p.alpha, false);
            vec4 ng = fgd_quadrature(L, p.mu, p.alpha, true, nt_new, np_new), ns = fgd_quadrature(L, p.mu, p.alpha, false, nt_new, np_new);
            float o1 = I.kind == 1 ? old_coat(std::max(p.alpha, MODEL_MIN_ALPHA), float(I.eta), p.mu) : -1.f;
            char b[512];
            std::snprintf(b, sizeof b, "%d %d %g %.7g %.10g %.10g %.10g %.10g %.8g %.8g %.8g %.8g %.8g %.8g %.8g %.8g %.8g %.8g %.8g %.8g %.8g %.8g\n", p.iface, p.use, p.alpha, p.mu,
                          rg.x, rg.z, rs.x, rs.z, o1, o2g.x, o2g.z, o2s.x, o2s.z, ng.x, ng.z, ns.x, ns.z, o2g.w, ng.w, o2s.w, ns.w, 0.0);
            out[i] = b;
        }
    };
    int nth = argc > 5 ? atoi(argv[5]) : 2;
    std::vector<std::thread> pool;
    for (int t = 0; t < nth; ++t) pool.emplace_back(work);
    for (auto& t : pool) t.join();
    std::printf("# iface use alpha mu refG2_r refG2_b refS_r refS_b old1 old2G2_r old2G2_b old2S_r old2S_b newG2_r newG2_b newS_r newS_b old2G2tir newG2tir old2Stir newStir\n");
    for (auto& s : out) std::fputs(s.c_str(), stdout);
}
