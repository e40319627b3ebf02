#include "compare.h"
#include "text_format.h"
#include "histogram.h"
#include "statistics.h"

#include <algorithm>

#include <cmath>
#include <cstdio>

namespace gonio {

double remapped(double f) { return std::log1p(std::sqrt(std::max(f, 0.0))); }
double remapped_noise(double f, double se) {
    double sq = std::sqrt(std::max(f, se));
    return sq > 0 ? se / (2 * sq * (1 + sq)) : 0.0;
}

double remapped_unbiased(double f, double se) {
    if (!(f > 0)) return remapped(f);
    const double q = std::sqrt(f), g2 = -(1 + 2 * q) / (4 * f * q * (1 + q) * (1 + q));
    return remapped(f) - 0.5 * g2 * se * se;
}

void CellSums::add(const BinGrid& g, const Slice& s, size_t b, double N) {
    // the bin's S1 / N, and its S2 / N from se^2 = (S2 / N - mean^2) / (N - 1)
    const double omega = g.projected_solid_angle(uint32_t(b / g.n_phi));
    const glm::dvec3 se = s.se[b] * omega, m = s.sum[b];
    mean += m;
    second += se * se * (N - 1) + m * m;
}

glm::dvec3 CellSums::se(double N) const {
    glm::dvec3 e(0.0);
    for (int k = 0; k < 3; ++k) e[k] = N > 1 ? std::sqrt(std::max(0.0, second[k] - mean[k] * mean[k]) / (N - 1)) : 0.0;
    return e;
}

std::vector<VerdictCell> pool_cells(const BinGrid& g, const Slice& s, uint64_t paths,
                                    const std::function<bool(size_t, const CellSums&)>& closes) {
    const double N = double(paths);
    std::vector<VerdictCell> cells;
    std::vector<CellSums> sums;
    CellSums cell;
    size_t first = 0;
    const size_t n = size_t(g.n_theta) * g.n_phi;
    for (size_t b = 0; b < n; ++b) {
        cell.add(g, s, b, N);
        if (!closes(b, cell)) continue;
        cells.push_back({first, b + 1, cell.mean, cell.se(N)});
        sums.push_back(cell);
        cell = CellSums{};
        first = b + 1;
    }
    if (first < n && !cells.empty()) {
        CellSums& last = sums.back();
        last.mean += cell.mean;
        last.second += cell.second;
        cells.back() = {cells.back().first, n, last.mean, last.se(N)};
    }
    return cells;
}

std::vector<VerdictCell> verdict_cells(const BinGrid& g, const Slice& s, uint64_t paths, int c) {
    const double N = double(paths);
    return pool_cells(g, s, paths, [&](size_t, const CellSums& cell) {
        const glm::dvec3 se = cell.se(N);
        for (int k = 0; k < 3; ++k)
            if ((c < 0 || k == c) && !(cell.mean[k] > 0 && se[k] > 0 && se[k] < kTrustedRse * cell.mean[k]))
                return false;
        return true;
    });
}

namespace {

// The statistical verdict (compare.h, Agreement; docs/MODELS.md "Verdicts").
Agreement agreement_of(const BinGrid& g, const Slice& s, uint64_t paths, const std::vector<glm::dvec3>& model,
                       const std::vector<glm::dvec3>* model_error) {
    Agreement a;
    const bool have_error = model_error && model_error->size() == model.size();
    const double z_crit = normal_upper_quantile(0.5 * kVerdictLevel / 3);   // two-sided, Bonferroni over 3 channels
    double best_p_chi2 = 1, best_p_bias = 1, chi2_all = 0, z_all = 0, err2 = 0, detect = 0;
    uint64_t n_all = 0;
    for (int c = 0; c < kChannels; ++c) {
        double chi2 = 0, zsum = 0, inv_rse = 0;
        uint64_t cells = 0;
        for (const VerdictCell& cell : verdict_cells(g, s, paths, c)) {
            double mod = 0, err = 0;
            for (size_t b = cell.first; b < cell.last; ++b) {
                const double omega = g.projected_solid_angle(uint32_t(b / g.n_phi));
                mod += model[b][c] * omega;
                if (have_error) err += (*model_error)[b][c] * omega;
            }
            const double z = (mod - cell.mean[c]) / cell.se[c];
            chi2 += z * z;
            zsum += z;
            inv_rse += cell.mean[c] / cell.se[c];
            ++cells;
            if (have_error) err2 += (err / cell.se[c]) * (err / cell.se[c]);
            if (cell.last - cell.first == 1)
                ++a.cells;
            else
                a.pooled_bins += cell.last - cell.first, ++a.pooled_cells;
        }
        for (size_t b = 0; b < s.se.size(); ++b)
            if (!(s.se[b][c] > 0)) ++a.bins_without_paths;
        if (cells == 0) continue;
        best_p_chi2 = std::min(best_p_chi2, chi2_p_value(chi2, double(cells)));
        best_p_bias = std::min(best_p_bias, normal_two_sided_p(zsum / std::sqrt(double(cells))));
        chi2_all += chi2;
        z_all += zsum;
        n_all += cells;
        // a relative bias b moves each cell's z by b / rse, the bias statistic by b sum(1 / rse) / sqrt(cells)
        const double b = z_crit * std::sqrt(double(cells)) / inv_rse;
        detect = detect > 0 ? std::min(detect, b) : b;
    }
    a.chi2_per_dof = n_all ? chi2_all / double(n_all) : 0.0;
    a.mean_z = n_all ? z_all / double(n_all) : 0.0;
    a.chi2_p_value = std::min(1.0, 3 * best_p_chi2);
    a.bias_p_value = std::min(1.0, 3 * best_p_bias);
    a.smallest_detectable_relative_bias = detect;
    if (have_error) a.integration_error_over_noise = n_all ? std::sqrt(std::max(0.0, err2) / double(n_all)) : 0.0;
    if (n_all == 0) {
        a.reason = "too few paths for a verdict: all the bins together have a relative standard error above " +
                   format_g9(kTrustedRse);
    } else if (a.chi2_p_value < kVerdictLevel) {
        a.reason = "the chi-square test rejects agreement (p " + format_g9(a.chi2_p_value) + ")";
    } else if (a.bias_p_value < kVerdictLevel) {
        a.reason = "the bias test rejects agreement (p " + format_g9(a.bias_p_value) + ")";
    } else if (a.integration_error_over_noise > kIntegrationErrorShare) {
        a.reason = "the model's own bin integration error is " + format_g9(a.integration_error_over_noise) +
                   " of the reference's noise: its bins are not known well enough";
    } else {
        a.within_noise = true;
    }
    return a;
}

}   // namespace

ModelMetrics compare_model(const SimResult& ref, size_t angle, const std::vector<glm::dvec3>& model, Side side,
                           const std::vector<glm::dvec3>* model_error) {
    ModelMetrics m;
    BinGrid g(ref);
    Slice s = make_slice(ref, angle, side);
    double n = 0, nrel = 0, se2 = 0;
    for (uint32_t t = 0; t < g.n_theta; ++t) {
        double omega = g.projected_solid_angle(t);
        for (uint32_t p = 0; p < g.n_phi; ++p) {
            size_t b = size_t(t) * g.n_phi + p;
            for (int c = 0; c < kChannels; ++c) {
                double fr = s.f[b][c], fm = model[b][c];
                double d = remapped(fm) - remapped(fr);
                m.rmse_remapped += d * d;
                m.mean_abs_remapped += std::fabs(d);
                m.rmse_linear += (fm - fr) * (fm - fr);
                if (fr > 0) {
                    m.mean_rel_linear += std::fabs(fm - fr) / fr;
                    nrel++;
                }
                double noise = remapped_noise(fr, s.se[b][c]);
                se2 += noise * noise;
                n++;
                if (std::fabs(d) > m.max_abs_remapped) {
                    m.max_abs_remapped = std::fabs(d);
                    m.max_theta_deg = 0.5 * (g.theta_lo(t) + g.theta_hi(t));
                    m.max_phi_deg = p * g.dphi_deg;
                    m.max_channel = c;
                }
            }
            m.albedo_model += model[b] * omega;
            m.albedo_reference += s.f[b] * omega;
        }
    }
    m.rmse_remapped = std::sqrt(m.rmse_remapped / n);
    m.mean_abs_remapped /= n;
    m.rmse_linear = std::sqrt(m.rmse_linear / n);
    m.mean_rel_linear = nrel > 0 ? m.mean_rel_linear / nrel : 0.0;
    m.reference_noise_remapped = std::sqrt(se2 / n);
    m.agreement = agreement_of(g, s, ref.angles.at(angle).paths, model, model_error);
    m.within_noise = m.agreement.within_noise;
    return m;
}

BestModel separate_models(const SimResult& ref, size_t angle, Side side, const ModelSlices& best,
                          const ModelSlices& runner_up) {
    BestModel out{best.id, runner_up.id};
    const auto& fa = (side == kReflection ? best.f : best.t)[angle];
    const auto& fb = (side == kReflection ? runner_up.f : runner_up.t)[angle];
    Slice s = make_slice(ref, angle, side);
    // D = sum (g_a - g_r)^2 - (g_b - g_r)^2; with g_r = g_true + e: D = D_true - 2 sum (g_a - g_b) e
    double d = 0, var = 0;
    for (size_t b = 0; b < s.f.size(); ++b)
        for (int c = 0; c < kChannels; ++c) {
            const double gr = remapped(s.f[b][c]), ga = remapped(fa[b][c]), gb = remapped(fb[b][c]);
            const double sg = remapped_noise(s.f[b][c], s.se[b][c]);
            d += (ga - gr) * (ga - gr) - (gb - gr) * (gb - gr);
            var += 4 * (ga - gb) * (ga - gb) * sg * sg;
        }
    if (var > 0) {
        out.separation_z = -d / std::sqrt(var);
        out.tie = out.separation_z < normal_upper_quantile(0.5 * kVerdictLevel);
    } else {
        out.tie = d == 0;   // no noise where they differ: the smaller error is the better, unless they are equal
    }
    return out;
}

}   // namespace gonio
