// Chi-square goodness of fit of every sampling routine of the walk against its density (CPU twin: the very
// shader functions of shaders/lib compiled through GLM), with a Sidak correction over all cases.
#include "chi2.h"
#include "cpu_twin.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace {

struct Case {
    std::string name;
    std::function<glm::vec3(int)> sample;
    std::function<double(glm::vec3)> pdf;
};

glm::vec3 dir_from_theta(double deg) {
    double t = deg * M_PI / 180.0;
    return glm::vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

vec4 uniform4(uint32_t case_id, int i) {
    Rng r = rng_init(uint32_t(i), 0u, 12345u + case_id, 7u);
    return rng_next4(r);
}

std::vector<Case> make_cases() {
    std::vector<Case> cases;
    uint32_t id = 0;
    for (double alpha : {0.15, 0.4, 1.0})
        for (double theta : {10.0, 50.0, 80.0}) {
            glm::vec3 wi = dir_from_theta(theta);
            float a = float(alpha);
            char buf[128];
            // dielectric, entering a denser medium (eta 1.5) and leaving it (eta 1/1.5: total internal reflection)
            for (float eta : {1.5f, 1.0f / 1.5f}) {
                std::snprintf(buf, sizeof buf, "dielectric alpha=%g theta=%g eta=%.3f", alpha, theta, eta);
                uint32_t cid = id++;
                cases.push_back({buf, [=](int i) { return sample_dielectric(wi, a, eta, uniform4(cid, i)).wo; },
                                 [=](glm::vec3 wo) { return double(pdf_dielectric(wi, wo, a, eta)); }});
            }
            std::snprintf(buf, sizeof buf, "conductor (visible-normal reflection) alpha=%g theta=%g", alpha, theta);
            uint32_t cid = id++;
            cases.push_back(
                {buf, [=](int i) { return sample_conductor(wi, a, vec3(0.2f), vec3(3.0f), uniform4(cid, i)).wo; },
                 [=](glm::vec3 wo) { return double(pdf_conductor(wi, wo, a)); }});
        }
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

TEST(Sampling, ChiSquareAgainstDensity) {
    auto cases = make_cases();
    const double alpha_total = 0.01;
    const double alpha_each = 1.0 - std::pow(1.0 - alpha_total, 1.0 / double(cases.size()));   // Sidak
    const int n = 1000000;
    for (auto& c : cases) {
        chi2::Result r = chi2::test(c.sample, c.pdf, n);
        std::printf("%-60s chi2 %10.1f dof %5d p %.4f  integral %.5f\n", c.name.c_str(), r.chi2, r.dof, r.p_value,
                    r.pdf_integral);
        EXPECT_TRUE(r.failure.empty()) << c.name << ": " << r.failure;
        EXPECT_NEAR(r.pdf_integral, 1.0, 5e-3) << c.name << ": density does not integrate to 1";
        EXPECT_GT(r.p_value, alpha_each) << c.name << ": sampler does not follow its density (Sidak-corrected level "
                                         << alpha_each << ")";
    }
}

// The test must be able to fail: a deliberately wrong density (visible normals without the G1 factor's
// dependence) is rejected.
TEST(Sampling, ChiSquareRejectsAWrongDensity) {
    glm::vec3 wi = dir_from_theta(50.0);
    float a = 0.4f;
    chi2::Result r =
        chi2::test([=](int i) { return sample_conductor(wi, a, vec3(0.2f), vec3(3.0f), uniform4(999u, i)).wo; },
                   [=](glm::vec3 wo) { return double(pdf_conductor(wi, wo, a * 1.1f)); }, 1000000);
    EXPECT_LT(r.p_value, 1e-6);
}

}   // namespace
