// Chi-square goodness of fit of every sampling routine of the walk against its density (CPU twin: the very
// shader functions of shaders/lib compiled through GLM), with a Sidak correction over all cases.
#include "chi2.h"
#include "cpu_twin.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace {

struct Case {
    std::string name;
    std::function<glm::vec3(int)> sample;
    std::function<double(glm::vec3)> pdf;
    bool fine = false;   // the density's quadrature on the grid twice as fine (a lobe the default grid misses)
};

glm::vec3 dir_from_theta(double deg) {
    double t = deg * M_PI / 180.0;
    return glm::vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

vec4 uniform4(uint32_t case_id, int i) {
    Rng r = rng_init(uint32_t(i), 0u, 12345u + case_id, 7u);
    return rng_next4(r);
}

// The interfaces' routines on a microsurface (microsurface.glsl MICROSURFACE_*: GGX, the default, at three alphas
// and three angles; Beckmann at two of each; separable shadowing changes weights, not directions:
// BothBranchesHaveTheAnalogExpectation holds those).
void add_interface_cases(std::vector<Case>& cases, uint32_t& id, uint micro, std::initializer_list<double> alphas,
                         std::initializer_list<double> thetas) {
    const char* name = micro == MICROSURFACE_BECKMANN ? "beckmann " : "";
    // Beckmann's lobes, with no long tail, are narrower at one alpha than GGX's: on the default grid the density of
    // its refracted lobe at alpha 0.3, 10 degrees, integrates to 1.0005 over the cells (p 5e-6), on the fine one to
    // 1.00002 (p 0.60)
    const bool fine = micro == MICROSURFACE_BECKMANN;
    for (double alpha : alphas)
        for (double theta : thetas) {
            glm::vec3 wi = dir_from_theta(theta);
            float a = float(alpha);
            char buf[128];
            // dielectric, entering a denser medium (eta 1.5) and leaving it (eta 1/1.5: total internal reflection)
            for (float eta : {1.5f, 1.0f / 1.5f}) {
                std::snprintf(buf, sizeof buf, "%sdielectric alpha=%g theta=%g eta=%.3f", name, alpha, theta, eta);
                uint32_t cid = id++;
                cases.push_back({buf, [=](int i) { return sample_dielectric(wi, a, micro, eta, uniform4(cid, i)).wo; },
                                 [=](glm::vec3 wo) { return double(pdf_dielectric(wi, wo, a, micro, eta)); }, fine});
            }
            std::snprintf(buf, sizeof buf, "%sconductor (visible-normal reflection) alpha=%g theta=%g", name, alpha,
                          theta);
            uint32_t cid = id++;
            cases.push_back(
                {buf,
                 [=](int i) { return sample_conductor(wi, a, micro, vec3(0.2f), vec3(3.0f), uniform4(cid, i)).wo; },
                 [=](glm::vec3 wo) { return double(pdf_conductor(wi, wo, a, micro)); }, fine});
        }
}

std::vector<Case> make_cases() {
    std::vector<Case> cases;
    uint32_t id = 0;
    add_interface_cases(cases, id, 0u, {0.15, 0.4, 1.0}, {10.0, 50.0, 80.0});
    uint32_t cid = id++;
    cases.push_back({"cosine hemisphere",
                     [=](int i) {
                         vec4 u = uniform4(cid, i);
                         return sample_cosine_hemisphere(u.x, u.y);
                     },
                     [](glm::vec3 wo) { return wo.z > 0 ? double(wo.z) / M_PI : 0.0; }});
    // the Lambertian series' emission: a cone with probability 0.75 or 0.5, or a cone alone (a smooth coat's escape
    // cone); emit.z, emit.w are weights, not used for the direction. The cones' edges (cos 0.6, 0.75, 0.95) fall on
    // edges of the test's cells (cos theta in steps of 0.05), where the density jumps.
    for (vec4 emit :
         {vec4(0.64f, 0.75f, 0.0f, 0.0f), vec4(0.4375f, 1.0f, 0.0f, 0.0f), vec4(0.0975f, 0.5f, 0.0f, 0.0f)}) {
        char buf[128];
        std::snprintf(buf, sizeof buf, "Lambertian series emission cone sin^2=%.4f p=%.2f", emit.x, emit.y);
        uint32_t sid = id++;
        cases.push_back({buf, [=](int i) { return sample_lambertian_series(vec3(1.0f), emit, uniform4(sid, i)).wo; },
                         [=](glm::vec3 wo) { return double(pdf_lambertian_series(wo, emit)); }});
    }
    return cases;
}

// Every case's sampler against its density, at a Sidak-corrected level.
void expect_follow_their_densities(const std::vector<Case>& cases, int n = 1000000) {
    const double alpha_total = 0.01;
    const double alpha_each = 1.0 - std::pow(1.0 - alpha_total, 1.0 / double(cases.size()));   // Sidak
    for (auto& c : cases) {
        chi2::Result r = c.fine ? chi2::test(c.sample, c.pdf, n, 80, 160, 48) : chi2::test(c.sample, c.pdf, n);
        std::printf("%-60s chi2 %10.1f dof %5d p %.4f  integral %.5f\n", c.name.c_str(), r.chi2, r.dof, r.p_value,
                    r.pdf_integral);
        EXPECT_TRUE(r.failure.empty()) << c.name << ": " << r.failure;
        EXPECT_NEAR(r.pdf_integral, 1.0, 5e-3) << c.name << ": density does not integrate to 1";
        EXPECT_GT(r.p_value, alpha_each) << c.name << ": sampler does not follow its density (Sidak-corrected level "
                                         << alpha_each << ")";
    }
}

TEST(Sampling, ChiSquareAgainstDensity) { expect_follow_their_densities(make_cases()); }

// The interfaces on Beckmann microsurfaces (label slow: the fine grid's quadrature takes most of a minute), with 4e6
// samples each: at 1e6 one stream of twelve gave p 6e-4 (alpha 0.15, 80 degrees, eta 1.5), the same stream at 4e6 p
// 0.38 and six other streams at 1e6 p 0.19 to 0.81, as chance has it.
TEST(Sampling, BeckmannChiSquareAgainstDensity) {
    std::vector<Case> cases;
    uint32_t id = 500;
    add_interface_cases(cases, id, MICROSURFACE_BECKMANN, {0.15, 1.0}, {10.0, 80.0});
    expect_follow_their_densities(cases, 4000000);
}

// The test must be able to fail: a deliberately wrong density (visible normals without the G1 factor's
// dependence) is rejected.
TEST(Sampling, ChiSquareRejectsAWrongDensity) {
    glm::vec3 wi = dir_from_theta(50.0);
    float a = 0.4f;
    chi2::Result r =
        chi2::test([=](int i) { return sample_conductor(wi, a, 0u, vec3(0.2f), vec3(3.0f), uniform4(999u, i)).wo; },
                   [=](glm::vec3 wo) { return double(pdf_conductor(wi, wo, a * 1.1f, 0u)); }, 1000000);
    EXPECT_LT(r.p_value, 1e-6);
}

// The dielectric event with both branches (sample_dielectric_branches, trace_book.glsl) has the expectation of the
// analog event (sample_dielectric_inv) cell by cell: the weighted directions of the two, binned on the sphere, differ
// by no more than their noise (a two-sample z per cell with enough samples, chi-square over the cells). scale_reflected
// multiplies the reflected branch's weight (the test of the test).
chi2::Result branches_against_analog(glm::vec3 wi, float alpha, float eta, uint32_t case_id, int n,
                                     float scale_reflected = 1.0f, uint micro = 0u) {
    const int n_cos = 20, n_phi = 40, cells = n_cos * n_phi;
    auto cell = [&](glm::vec3 w) {
        double c = std::clamp(double(w.z), -1.0, 1.0), phi = std::atan2(double(w.y), double(w.x));
        if (phi < 0) phi += 2 * M_PI;
        return std::min(n_cos - 1, int((c + 1) * 0.5 * n_cos)) * n_phi +
               std::min(n_phi - 1, int(phi / (2 * M_PI) * n_phi));
    };
    std::vector<double> s1a(cells, 0), s2a(cells, 0), s1b(cells, 0), s2b(cells, 0);
    std::vector<int> hits_a(cells, 0), hits_b(cells, 0);
    for (int i = 0; i < n; ++i) {
        const vec4 u = uniform4(case_id, i);
        Scatter a = sample_dielectric_inv(wi, alpha, micro, eta, 1.0f / eta, true, u);
        if (a.valid) {
            const int k = cell(a.wo);
            s1a[k] += a.weight.x;
            s2a[k] += a.weight.x * a.weight.x;
            hits_a[k]++;
        }
        const vec4 v = uniform4(case_id + 100000u, i);   // independent of the analog sample
        vec4 refl;
        Scatter b = sample_dielectric_branches(wi, alpha, micro, eta, 1.0f / eta, true, vec2(v.x, v.y), refl);
        // the two branches lie on opposite sides of the surface: never in one cell
        if (refl.w > 0.0f) {
            const int k = cell(glm::vec3(refl.x, refl.y, refl.z));
            const double w = double(refl.w) * scale_reflected;
            s1b[k] += w;
            s2b[k] += w * w;
            hits_b[k]++;
        }
        if (b.valid) {
            const int k = cell(b.wo);
            s1b[k] += b.weight.x;
            s2b[k] += b.weight.x * b.weight.x;
            hits_b[k]++;
        }
    }
    chi2::Result r;
    for (int k = 0; k < cells; ++k) {
        if (hits_a[k] == 0 && hits_b[k] == 0) continue;
        const double N = n, ma = s1a[k] / N, mb = s1b[k] / N;
        const double va = std::max(0.0, s2a[k] / N - ma * ma) / N, vb = std::max(0.0, s2b[k] / N - mb * mb) / N;
        if (va + vb <= 1e-12 * (ma + mb) * (ma + mb)) {   // both exact (total internal reflection): equal
            if (std::fabs(ma - mb) > 1e-6 * (ma + mb)) r.failure = "cell " + std::to_string(k) + " differs exactly";
            continue;
        }
        if (hits_a[k] < 50 || hits_b[k] < 50) continue;   // too few samples for a normal z
        r.chi2 += (ma - mb) * (ma - mb) / (va + vb);
        r.dof++;
    }
    r.p_value = r.dof > 0 ? gonio::gamma_q(0.5 * r.dof, 0.5 * r.chi2) : 0.0;
    return r;
}

struct BranchCase {
    float alpha, theta, eta;
    uint micro = 0u;
};

// Each case's chi-square of both branches against the analog walk, at Sidak's level over the cases
void expect_branches_match_analog(const std::vector<BranchCase>& cases, uint32_t id) {
    const double alpha_each = 1.0 - std::pow(1.0 - 0.01, 1.0 / double(cases.size()));   // Sidak
    for (const BranchCase& c : cases) {
        chi2::Result r = branches_against_analog(dir_from_theta(c.theta), c.alpha, c.eta, id++, 400000, 1.0f, c.micro);
        std::printf("both branches micro=%u alpha=%g theta=%g eta=%.3f: chi2 %.1f dof %d p %.4f\n", c.micro, c.alpha,
                    c.theta, c.eta, r.chi2, r.dof, r.p_value);
        EXPECT_TRUE(r.failure.empty()) << r.failure;
        if (r.dof == 0) continue;   // total internal reflection of a smooth interface: checked exactly above
        EXPECT_GT(r.p_value, alpha_each) << "alpha " << c.alpha << " theta " << c.theta << " eta " << c.eta;
    }
}

TEST(Sampling, BothBranchesHaveTheAnalogExpectation) {
    std::vector<BranchCase> cases;
    for (float alpha : {0.0f, 0.05f, 0.4f})
        for (float theta : {10.0f, 50.0f, 85.0f})
            for (float eta : {1.5f, 1.0f / 1.5f}) cases.push_back({alpha, theta, eta});
    expect_branches_match_analog(cases, 5000u);
    // the test can fail: the reflected branch 10% too heavy (at 80 degrees, where it carries a third of the light)
    chi2::Result wrong = branches_against_analog(dir_from_theta(80.0f), 0.4f, 1.5f, 9999u, 1000000, 1.1f);
    EXPECT_LT(wrong.p_value, 1e-6) << "chi2 " << wrong.chi2 << " dof " << wrong.dof;
}

// Beckmann with separable shadowing: both branches' weights G1(wo) (labelled slow with the Beckmann samplers)
TEST(Sampling, BothBranchesHaveTheAnalogExpectationBeckmannSeparable) {
    std::vector<BranchCase> cases;
    for (float theta : {50.0f, 85.0f})
        for (float eta : {1.5f, 1.0f / 1.5f})
            cases.push_back({0.4f, theta, eta, MICROSURFACE_BECKMANN | MICROSURFACE_SEPARABLE});
    expect_branches_match_analog(cases, 5018u);
}

}   // namespace
