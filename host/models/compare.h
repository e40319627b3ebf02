// compare.h: how far each model is from the reference, on the same bins (gonio compare).
#pragma once
#include "models.h"
#include "histogram.h"
#include "reference.h"

#include <glm/glm.hpp>
#include <string>
#include <functional>
#include <vector>

namespace gonio {

// Whether a model can be told apart from the reference on one slice (docs/MODELS.md, "Verdicts"). The bins of each
// channel are grouped into cells: consecutive bins in theta-major order merged until the reference's relative
// standard error over the cell is below kTrustedRse (a bin with enough paths is a cell of its own; sparse bins pool
// with their neighbours; a path leaves through one bin only, so a cell's exact se follows from its bins' sums).
// Each cell gives z = (model - reference) / se over the cell. Per channel the chi-square test (sum z^2, as many
// degrees of freedom as cells) and the bias test (sum z / sqrt(cells) against a standard normal) give p-values;
// each verdict's p-value is the smallest over the channels times 3 (Bonferroni: the channels of a bin share their
// paths). Agreement is rejected when either is below kVerdictLevel.
inline constexpr double kTrustedRse = 0.05;   // a bin's own se is trusted from about 400 paths' worth
inline constexpr double kVerdictLevel = 0.01;   // the tests' level
// The model's own bin integration error counts too: if its RMS over the tested cells exceeds this fraction of the
// reference's standard error, the model's bins are not known well enough for a verdict of agreement.
inline constexpr double kIntegrationErrorShare = 0.3;

// The seed's remapped space g(f) = log(1 + sqrt f), and the reference's standard error mapped into it: g'(f) se,
// g'(f) = 1 / (2 sqrt f (1 + sqrt f)); at f = 0 the noise of a one-path bin (sqrt of se) instead.
double remapped(double f);
double remapped_noise(double f, double se);
// g of a noisy estimate is biased low (g is concave): E[g(f_hat)] = g(f) + g''(f) se^2 / 2 + O(se^3). This is
// g(f_hat) - g''(f_hat) se^2 / 2, g''(f) = -(1 + 2 sqrt f) / (4 f^(3/2) (1 + sqrt f)^2): the delta method's
// second-order correction (g(f) where f is not positive).
double remapped_unbiased(double f, double se);

// The verdict's cells of one slice (theta-major, bins [first, last)): consecutive bins pooled until the reference's
// relative standard error over the cell is below kTrustedRse in channel `channel`, or in all three at once (channel
// -1: the same cells for every channel, as a fit takes them); per channel the reference's mean energy fraction
// through the cell (S1 / N summed) and its exact standard error. g, s: the run's grid and slice.
struct VerdictCell {
    size_t first, last;
    glm::dvec3 mean, se;
};
std::vector<VerdictCell> verdict_cells(const BinGrid& g, const Slice& s, uint64_t paths, int channel);
// The reference's sums over a cell of bins added one by one: per channel the mean energy fraction per path (S1 / N)
// and its second moment (S2 / N; a path leaves through one bin only, so both add over bins), and the cell's exact se.
struct CellSums {
    glm::dvec3 mean{0.0}, second{0.0};
    void add(const BinGrid& g, const Slice& s, size_t bin, double paths);
    glm::dvec3 se(double paths) const;
};
// Cells of consecutive bins (theta-major) with the reference's mean and se over each: bin b joins the open cell, which
// closes after it where closes(b, the cell's sums) says so; what is left at the end joins the last cell (it cannot
// stand alone), or is left out if there is none. verdict_cells closes on the reference's own se; the fit's planned
// cells on a model's prediction (model_fit.cpp).
std::vector<VerdictCell> pool_cells(const BinGrid& g, const Slice& s, uint64_t paths,
                                    const std::function<bool(size_t, const CellSums&)>& closes);

struct Agreement {
    uint64_t cells = 0;   // bin-channels tested on their own (a cell of one bin)
    uint64_t pooled_bins = 0;   // bin-channels tested in cells of several bins
    uint64_t pooled_cells = 0;   // those cells
    uint64_t bins_without_paths = 0;   // bin-channels no path reached (in cells with their neighbours: the model's
        // energy there counts)
    double chi2_per_dof = 0;   // sum z^2 / (cells + pooled cells), all channels
    double mean_z = 0;   // signed mean of z (> 0: the model above the reference)
    double chi2_p_value = 1, bias_p_value = 1;
    double smallest_detectable_relative_bias =
        0;   // a model off by this factor everywhere would be seen by the bias test
    double integration_error_over_noise = -1;   // RMS of (integration error / se) over the cells; -1: not estimated
    bool within_noise = false;
    std::string reason;   // why within_noise is false, or what was not tested
};

// Per model, incident angle and side, in the seed's remapped space g(f) = log(1 + sqrt f)
// and in linear f, over all bins and channels.
struct ModelMetrics {
    double rmse_remapped = 0, mean_abs_remapped = 0, rmse_linear = 0, mean_rel_linear = 0;
    glm::dvec3 albedo_model{0}, albedo_reference{0};
    double max_abs_remapped = 0;   // the largest |g(model) - g(reference)|
    double max_theta_deg = 0, max_phi_deg = 0;   // its bin centre
    int max_channel = 0;
    double reference_noise_remapped = 0;   // RMS over bins of the reference's standard error mapped by g'
    Agreement agreement;
    bool within_noise = false;   // agreement.within_noise
};

// A model's directional albedo (reflected + transmitted, from its bin averages) above 1 + this breaks the white-
// furnace bound: summary.json flags it (reflects_more_than_it_receives), compare warns.
inline constexpr double kWhiteFurnaceTolerance = 1e-3;

// side: kReflection (model.f) or kTransmission (model.t); the albedo is then the directional transmittance.
// model_error: the model's bin integration error estimate, same shape as model (nullptr or empty: unknown).
ModelMetrics compare_model(const SimResult& ref, size_t angle, const std::vector<glm::dvec3>& model,
                           Side side = kReflection, const std::vector<glm::dvec3>* model_error = nullptr);

// The best model on one slice (the one of least rmse_remapped, comparison.h) and whether the reference's noise can
// tell the runner-up from it: the paired test of the difference of their squared remapped errors, whose noise
// (linearised, g' times se per bin) has variance 4 sum (g_a - g_b)^2 sigma_g^2; a tie when |separation_z| < the
// two-sided 1% point (2.576).
struct BestModel {
    std::string best, runner_up;   // runner_up empty: one model only
    double separation_z = 0;
    bool tie = false;
};
BestModel separate_models(const SimResult& ref, size_t angle, Side side, const ModelSlices& best,
                          const ModelSlices& runner_up);

// A model's largest directional albedo (reflected + transmitted) over the run's incident angles and channels: its
// energy conservation as measured on this stack, beside what it claims (comparison.h).
struct LargestAlbedo {
    double value = 0, theta_i = 0;
    int channel = 0;
};

}   // namespace gonio
