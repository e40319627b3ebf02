#include "model_fit.h"

#include "histogram.h"
#include "model_applicability.h"
#include "models.h"
#include "text_format.h"
#include "user_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace gonio {

namespace {

// The cells the loss is taken over, each cell's three channels consecutive, over every incident angle and side:
// consecutive bins pooled until the reference's relative se over them is below kTrustedRse in every channel, so that
// sparse bins do not bias the fit. Where the pooling stops is decided either by the reference's own sums
// (compare.h verdict_cells: the first descent) or by a model's bins (planned_cells: the second); the reference's
// mean and se over each cell come from its sums either way.
struct Target {
    struct Cell {
        uint32_t angle, side, channel;
        size_t first, last;   // bins
        double mean, se, omega;   // reference energy fraction, its se, the cell's projected solid angle
    };
    std::vector<Cell> cells;
    std::vector<double> noise;   // the reference's noise in the residual's units
    std::vector<double> row_omega;   // the projected solid angle of a bin of each theta row
    uint32_t n_phi = 0;
    bool unbiased_log = true;   // the log residual against remapped_unbiased (FitOptions::bias_corrections)
};

// Cells whose ends the model's bins `side` (f per bin and channel of one angle and side) decide, not the reference's
// realized sums: a cell that closes where its own sums first reach the threshold closes after an upward fluctuation
// more often than not (optional stopping), which biased the fit by about one standard error (docs/MODELS.md).
// Consecutive bins pool until the se the model predicts for them, sqrt(c / (N e)), e the model's energy fraction
// through the cell, is below kTrustedRse of e in every channel; c, the reference's relative variance per unit energy
// fraction, is the median over its own cells `data` of N e se^2 / e^2 (one number per channel from all the cells,
// so that no cell's own noise decides where it ends). Empty where the model has no bins on this side.
std::vector<VerdictCell> planned_cells(const BinGrid& g, const Slice& s, uint64_t paths,
                                       const std::vector<VerdictCell>& data, const std::vector<glm::dvec3>* side) {
    if (!side || side->empty() || data.empty()) return {};
    const double N = double(paths);
    glm::dvec3 c(0.0);
    for (int k = 0; k < 3; ++k) {
        std::vector<double> v;
        for (const VerdictCell& d : data)
            if (d.mean[k] > 0) v.push_back(N * d.se[k] * d.se[k] / d.mean[k]);
        if (v.empty()) return {};
        std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
        c[k] = v[v.size() / 2];
    }
    glm::dvec3 e(0.0);   // the model's energy fraction through the open cell
    return pool_cells(g, s, paths, [&](size_t b, const CellSums&) {
        e += (*side)[b] * g.projected_solid_angle(uint32_t(b / g.n_phi));
        for (int k = 0; k < 3; ++k)
            if (!(e[k] > 0 && c[k] < kTrustedRse * kTrustedRse * N * e[k])) return false;
        e = glm::dvec3(0.0);
        return true;
    });
}

// plan: the model whose bins decide the cells' ends (planned_cells); null: the reference's sums (verdict_cells)
Target target_of(const SimResult& ref, FitLoss loss, const ModelSlices* plan = nullptr) {
    Target t;
    const BinGrid g(ref);
    for (uint32_t row = 0; row < g.n_theta; ++row) t.row_omega.push_back(g.projected_solid_angle(row));
    t.n_phi = g.n_phi;
    for (size_t a = 0; a < ref.angles.size(); ++a)
        for (uint32_t side = 0; side < ref.n_sides; ++side) {
            const Slice s = make_slice(ref, a, Side(side));
            std::vector<VerdictCell> cells = verdict_cells(g, s, ref.angles[a].paths, -1);
            if (plan) {
                const auto& m = side == 0 ? plan->f : plan->t;
                std::vector<VerdictCell> planned =
                    planned_cells(g, s, ref.angles[a].paths, cells, m.empty() ? nullptr : &m[a]);
                if (!planned.empty()) cells = std::move(planned);
            }
            for (const VerdictCell& v : cells) {
                double omega = 0;
                for (size_t b = v.first; b < v.last; ++b) omega += t.row_omega[b / g.n_phi];
                for (uint32_t c = 0; c < 3; ++c)
                    t.cells.push_back({uint32_t(a), side, c, v.first, v.last, v.mean[c], v.se[c], omega});
            }
        }
    for (const Target::Cell& c : t.cells)
        t.noise.push_back(loss == FitLoss::Chi2     ? 1.0
                          : loss == FitLoss::Cosine ? c.se / std::sqrt(c.omega)
                                                    : remapped_noise(c.mean / c.omega, c.se / c.omega));
    return t;
}

// The residuals of the model's cells against the target (empty: the model cannot be evaluated there)
std::vector<double> residuals(const Target& t, const ModelSlices& m, FitLoss loss) {
    if (!model_has_bins(m)) return {};
    std::vector<double> r(t.cells.size());
    for (size_t i = 0; i < r.size(); ++i) {
        const Target::Cell& c = t.cells[i];
        const auto& side = c.side == 0 ? m.f : m.t;
        double e = 0;   // the model's energy fraction through the cell
        if (!side.empty())
            for (size_t b = c.first; b < c.last; ++b) e += side[c.angle][b][c.channel] * t.row_omega[b / t.n_phi];
        // f over the cell is its energy fraction over its projected solid angle
        // log: against the reference's remapped value corrected for the curvature of g (its noise alone would pull
        // g down, and the fit with it)
        const double g_ref =
            t.unbiased_log ? remapped_unbiased(c.mean / c.omega, c.se / c.omega) : remapped(c.mean / c.omega);
        r[i] = loss == FitLoss::Log      ? remapped(e / c.omega) - g_ref
               : loss == FitLoss::Cosine ? (e - c.mean) / std::sqrt(c.omega)
                                         : (e - c.mean) / c.se;
    }
    return r;
}

double mean_square(const std::vector<double>& r) {
    if (r.empty()) return std::numeric_limits<double>::infinity();
    double s = 0;
    for (double x : r) s += x * x;
    return s / double(r.size());
}

// Solves the small symmetric system A x = b (Gaussian elimination with partial pivoting); false if singular.
bool solve(std::vector<std::vector<double>> A, std::vector<double> b, std::vector<double>& x) {
    const size_t n = b.size();
    for (size_t c = 0; c < n; ++c) {
        size_t p = c;
        for (size_t r = c + 1; r < n; ++r)
            if (std::fabs(A[r][c]) > std::fabs(A[p][c])) p = r;
        if (!(std::fabs(A[p][c]) > 0)) return false;
        std::swap(A[p], A[c]);
        std::swap(b[p], b[c]);
        for (size_t r = c + 1; r < n; ++r) {
            const double k = A[r][c] / A[c][c];
            for (size_t j = c; j < n; ++j) A[r][j] -= k * A[c][j];
            b[r] -= k * b[c];
        }
    }
    x.assign(n, 0.0);
    for (size_t c = n; c-- > 0;) {
        double s = b[c];
        for (size_t j = c + 1; j < n; ++j) s -= A[c][j] * x[j];
        x[c] = s / A[c][c];
    }
    return true;
}

std::vector<std::vector<double>> inverse(const std::vector<std::vector<double>>& A, bool& ok) {
    const size_t n = A.size();
    std::vector<std::vector<double>> inv(n, std::vector<double>(n, 0.0));
    ok = true;
    for (size_t j = 0; j < n; ++j) {
        std::vector<double> e(n, 0.0), x;
        e[j] = 1;
        if (!solve(A, e, x)) {
            ok = false;
            return inv;
        }
        for (size_t i = 0; i < n; ++i) inv[i][j] = x[i];
    }
    return inv;
}

// The covariance of the constrained parameters' estimates (`use`: their indices): the reference's noise (sigma per
// residual, in the residual's units) through the linearised fit, cov = A^-1 (J^T Sigma J) A^-1 with A = J^T J.
// Empty where A cannot be inverted.
std::vector<std::vector<double>> parameter_covariance(const Target& target, const std::vector<std::vector<double>>& J,
                                                      const std::vector<std::vector<double>>& A,
                                                      std::vector<size_t>& use) {
    const size_t P = J.size(), n = target.cells.size();
    // The channels of a cell share their paths: their noises are taken as fully correlated (the residuals of one
    // bin range, consecutive in the target, summed before squaring), which bounds the variance from above
    std::vector<std::vector<double>> B(P, std::vector<double>(P, 0.0));
    for (size_t k0 = 0; k0 < n;) {
        size_t k1 = k0;
        std::vector<double> s(P, 0.0);
        const Target::Cell& c0 = target.cells[k0];
        while (k1 < n && target.cells[k1].angle == c0.angle && target.cells[k1].side == c0.side &&
               target.cells[k1].first == c0.first && target.cells[k1].last == c0.last) {
            for (size_t i = 0; i < P; ++i) s[i] += J[i][k1] * target.noise[k1];
            ++k1;
        }
        for (size_t i = 0; i < P; ++i)
            for (size_t j = 0; j < P; ++j) B[i][j] += s[i] * s[j];
        k0 = k1;
    }
    // a parameter is constrained where the loss moves with it: its column of J is not nothing next to the others'
    double largest = 0;
    for (size_t i = 0; i < P; ++i) largest = std::max(largest, A[i][i]);
    use.clear();
    for (size_t i = 0; i < P; ++i)
        if (A[i][i] > 1e-12 * largest && A[i][i] > 0) use.push_back(i);
    std::vector<std::vector<double>> Au(use.size(), std::vector<double>(use.size())), Bu = Au;
    for (size_t a = 0; a < use.size(); ++a)
        for (size_t b = 0; b < use.size(); ++b) Au[a][b] = A[use[a]][use[b]], Bu[a][b] = B[use[a]][use[b]];
    bool ok = false;
    const std::vector<std::vector<double>> Ai = inverse(Au, ok);
    if (!ok) return {};
    std::vector<std::vector<double>> cov(use.size(), std::vector<double>(use.size(), 0.0));
    for (size_t a = 0; a < use.size(); ++a)
        for (size_t b = 0; b < use.size(); ++b)
            for (size_t c = 0; c < use.size(); ++c)
                for (size_t d = 0; d < use.size(); ++d) cov[a][b] += Ai[a][c] * Bu[c][d] * Ai[d][b];
    return cov;
}

double lower_of(const FitKey& k) { return k.key && k.key->or_zero ? 0.0 : double(k.range.lo); }
// The bottom of the continuous part of a key's valid set, where a descent stops: a roughness is 0 (smooth) or in
// [1e-4, 1], never between (a stack file refuses it), so a descent runs in [1e-4, 1] and 0 is a start of its own
double descent_lower_of(const FitKey& k) { return double(k.range.lo); }
bool zero_allowed(const FitKey& k) { return k.key && k.key->or_zero; }

}   // namespace

double FitKey::get(const Stack& s) const {
    if (parameter >= 0) return parameter_default;
    if (stack_key) return double(s.*(stack_key->value));
    const glm::vec3 v = key->get(s.layers[size_t(layer)]);
    if (channel >= 0) return double(v[channel]);
    return (double(v.x) + v.y + v.z) / 3.0;
}

std::string FitKey::channels() const {
    if (!key || key->shape != KeyShape::Rgb) return "";
    return channel < 0 ? "rgb" : std::string(1, "rgb"[channel]);
}

void FitKey::set(Stack& s, double v) const {
    if (parameter >= 0) return;
    if (stack_key) {
        s.*(stack_key->value) = float(v);
        return;
    }
    Layer& y = s.layers[size_t(layer)];
    glm::vec3 value = glm::vec3(float(v));
    if (channel >= 0) {
        value = key->get(y);
        value[channel] = float(v);
    }
    key->set(y, value);
}

void FitKey::set_parameter(ModelOptions& o, double v) const {
    if (parameter < 0) return;
    std::vector<double>& values = o.parameters[model_header->id];   // a variant's are its model's
    if (values.empty())
        for (const ModelParameter& p : model_header->parameters) values.push_back(p.value);
    values.at(size_t(parameter)) = v;
}

FitKey parse_fit_key(const Stack& s, const std::string& text, const ModelFileHeader* h) {
    FitKey k;
    k.name = text;
    if (text.rfind("param.", 0) == 0) {   // the model's own parameter
        std::string names;
        for (size_t i = 0; h && i < h->parameters.size(); ++i) {
            const ModelParameter& p = h->parameters[i];
            names += std::string(names.empty() ? "" : ", ") + "param." + p.name;
            if ("param." + p.name != text) continue;
            k.parameter = int(i);
            k.parameter_default = p.value;
            k.model_header = h;
            k.range = {float(p.lo), float(p.hi)};
            return k;
        }
        throw std::invalid_argument(
            "free key " + text + ": model " + (h ? h->id : std::string("?")) + " has " +
            (names.empty() ? std::string("no parameters of its own") : "the parameters " + names) +
            " (its file's parameter: lines)");
    }
    if (const StackKey* sk = find_stack_key(text)) {
        k.stack_key = sk;
        k.range = sk->range;
        return k;
    }
    const std::string form = "expected layer.N.KEY (N from 1 to " + std::to_string(s.layers.size()) +
                             ", top to bottom) or a key of the stack (exterior_ior)";
    if (text.rfind("layer.", 0) != 0) throw std::invalid_argument("free key " + text + ": " + form);
    const size_t dot = text.find('.', 6);
    if (dot == std::string::npos) throw std::invalid_argument("free key " + text + ": " + form);
    int n = 0;
    try {
        size_t used = 0;
        n = std::stoi(text.substr(6, dot - 6), &used);
        if (used != dot - 6) throw std::invalid_argument("");
    } catch (const std::exception&) { throw std::invalid_argument("free key " + text + ": " + form); }
    if (n < 1 || n > int(s.layers.size()))
        throw std::invalid_argument("free key " + text + ": the stack has layers 1 to " +
                                    std::to_string(s.layers.size()));
    std::string name = text.substr(dot + 1);
    const InterfaceKind kind = s.layers[size_t(n - 1)].kind;
    const LayerKey* key = find_layer_key(kind, name);
    const size_t last = name.rfind('.');
    if (!key && last != std::string::npos && last + 2 == name.size() &&
        std::string("rgb").find(name[last + 1]) != std::string::npos) {   // one channel of an RGB key
        key = find_layer_key(kind, name.substr(0, last));
        if (key && (key->shape != KeyShape::Rgb || key->one_value))
            throw std::invalid_argument("free key " + text + ": " + key->name + " is one number, not one per RGB " +
                                        "channel: free " + text.substr(0, text.size() - 2));
        if (key) k.channel = int(std::string("rgb").find(name[last + 1]));
    }
    if (!key) {
        std::string keys;
        for (const LayerKey* lk : keys_of(kind)) keys += std::string(keys.empty() ? "" : ", ") + lk->name;
        throw std::invalid_argument("free key " + text + ": layer " + std::to_string(n) + " is a " + to_string(kind) +
                                    " interface, which takes " + keys);
    }
    if (key->medium && s.transmissive() && n == int(s.layers.size()))   // as a stack file refuses it
        throw std::invalid_argument("free key " + text + ": layer " + std::to_string(n) +
                                    " is the last of a transmissive stack, whose substrate has no medium (" +
                                    key->name + " is the medium's)");
    k.layer = n - 1;
    k.key = key;
    k.range = key->range;
    return k;
}

const char* to_string(FitLoss l) { return l == FitLoss::Log ? "log" : l == FitLoss::Cosine ? "cosine" : "chi2"; }

FitLoss parse_fit_loss(const std::string& text) {
    if (text == "log") return FitLoss::Log;
    if (text == "cosine") return FitLoss::Cosine;
    if (text == "chi2") return FitLoss::Chi2;
    throw std::invalid_argument("loss: log, cosine or chi2, got '" + text + "'");
}

namespace {

// The model a fit names: a built-in (its registry index) or one of the model files (index: none); its header
std::pair<const ModelFileHeader*, size_t> fitted_model(const std::string& model,
                                                       const std::vector<std::shared_ptr<const UserModel>>& users) {
    for (size_t i = 0; i < model_registry().size(); ++i)
        if (model_registry()[i].id == model) return {&model_registry()[i].header, i};
    for (const auto& u : users)
        if (u->header.id == model) return {&u->header, SIZE_MAX};
    throw std::invalid_argument("model " + model + ": no such model (gonio models lists them; or a model file's id)");
}

// Every combination of the keys' starting values, the first key's slowest; a key without a start: the stack's value
std::vector<std::vector<double>> starting_points(
    const Stack& s, const std::vector<FitKey>& free,
    const std::vector<std::pair<std::string, std::vector<double>>>& start) {
    std::vector<std::vector<double>> values;   // per free key, the values it starts from
    for (const FitKey& k : free) values.push_back({k.get(s)});
    std::vector<bool> given(free.size(), false);
    for (const auto& [key, vs] : start) {
        size_t i = 0;
        while (i < free.size() && free[i].name != key) ++i;
        if (i == free.size()) throw std::invalid_argument("start " + key + ": not one of the free keys");
        const double lo = descent_lower_of(free[i]), hi = free[i].range.hi;
        for (double v : vs)
            if (!((v >= lo && v <= hi) || (v == 0.0 && zero_allowed(free[i]))))
                throw std::invalid_argument("start " + key + "=" + format_g9(v) + ": outside the key's range [" +
                                            format_shortest(float(lo)) + ", " + format_shortest(float(hi)) + "]" +
                                            (zero_allowed(free[i]) ? " or 0" : ""));
        if (!given[i]) values[i].clear();
        given[i] = true;
        values[i].insert(values[i].end(), vs.begin(), vs.end());
    }
    std::vector<std::vector<double>> points = {{}};
    for (const std::vector<double>& vs : values) {
        std::vector<std::vector<double>> grown;
        for (const std::vector<double>& p : points)
            for (double v : vs) {
                grown.push_back(p);
                grown.back().push_back(v);
            }
        points = std::move(grown);
    }
    if (points.size() > 64)
        throw std::invalid_argument("start: " + std::to_string(points.size()) +
                                    " starting points (every combination of the keys' values): at most 64");
    return points;
}

}   // namespace

FitOptions fit_options_for(const Stack& s, const FitSpec& spec,
                           const std::vector<std::shared_ptr<const UserModel>>& user_models) {
    if (spec.model.empty()) throw std::invalid_argument("no model to fit");
    if (spec.free.empty()) throw std::invalid_argument("no free keys (which stack keys the fit may change)");
    const auto [header, index] = fitted_model(spec.model, user_models);
    FitOptions fo;
    fo.model = spec.model;
    fo.loss = spec.loss;
    fo.bias_corrections = spec.bias_corrections;
    fo.models.user_models = user_models;
    for (const std::string& k : spec.free) {
        const FitKey key = parse_fit_key(s, k, header);
        for (const FitKey& other : fo.free) {   // each value free once: not a key twice, nor a key and its channel
            const bool same = other.name == key.name;
            const bool overlap =
                other.key && other.key == key.key && other.layer == key.layer && (other.channel < 0 || key.channel < 0);
            if (same || overlap)
                throw std::invalid_argument("free keys: " + other.name + (same ? " is given twice" : " and " + k) +
                                            (same ? "" : " overlap (a key and one of its channels): free one of them"));
        }
        fo.free.push_back(key);
    }
    fo.starts = starting_points(s, fo.free, spec.start);
    for (const std::vector<double>& x : fo.starts) {
        Stack at_start = s;
        for (size_t i = 0; i < fo.free.size(); ++i) fo.free[i].set(at_start, x[i]);
        const std::string why = index != SIZE_MAX ? model_cannot_represent(index, at_start)
                                                  : model_file_cannot_represent(*header, at_start);
        if (!why.empty()) throw std::invalid_argument(why);
    }
    return fo;
}

namespace {

// The Jacobian of the residuals r at x, [param][residual], by forward differences (backward at the top of a key's
// range); residuals_at(x') gives the residuals at x' (empty where the model cannot be evaluated: a zero column)
template <class ResidualsAt>
std::vector<std::vector<double>> forward_jacobian(const FitOptions& o, const std::vector<double>& x,
                                                  const std::vector<double>& r, ResidualsAt residuals_at) {
    std::vector<std::vector<double>> J(x.size(), std::vector<double>(r.size(), 0.0));
    for (size_t i = 0; i < x.size(); ++i) {
        const double lo = lower_of(o.free[i]), hi = o.free[i].range.hi;
        double h = 1e-3 * std::max(std::fabs(x[i]), 0.01 * (hi - lo));
        if (x[i] + h > hi) h = -h;
        std::vector<double> xh = x;
        xh[i] += h;
        const std::vector<double> rh = residuals_at(xh);
        if (rh.size() == r.size())
            for (size_t k = 0; k < r.size(); ++k) J[i][k] = (rh[k] - r[k]) / h;
    }
    return J;
}

// J^T J, J [param][residual]
std::vector<std::vector<double>> normal_matrix(const std::vector<std::vector<double>>& J) {
    const size_t P = J.size();
    std::vector<std::vector<double>> A(P, std::vector<double>(P, 0.0));
    for (size_t i = 0; i < P; ++i)
        for (size_t j = 0; j < P; ++j)
            for (size_t k = 0; k < J[i].size(); ++k) A[i][j] += J[i][k] * J[j][k];
    return A;
}

// The fitted parameters (value, start, range limit) and, for the constrained ones (`use`, with their covariance
// `cov`; empty: none), the standard errors and correlation
void describe_parameters(const FitOptions& o, const std::vector<double>& start, const std::vector<double>& x,
                         const std::vector<size_t>& use, const std::vector<std::vector<double>>& cov, FitResult& res) {
    const size_t P = x.size();
    const bool ok = !use.empty() && !cov.empty();
    res.parameters.resize(P);
    for (size_t i = 0; i < P; ++i) {
        FitParameter& p = res.parameters[i];
        p.name = o.free[i].name;
        p.channels = o.free[i].channels();
        p.start = start[i];
        p.value = x[i];
        p.constrained = false;
        const double lo = descent_lower_of(o.free[i]), hi = o.free[i].range.hi;
        p.at_limit = x[i] <= lo + 1e-9 * (hi - lo) || x[i] >= hi - 1e-9 * (hi - lo);
    }
    res.correlation.assign(use.size(), std::vector<double>(use.size(), 0.0));
    for (size_t a = 0; a < use.size() && ok; ++a) {
        FitParameter& p = res.parameters[use[a]];
        p.constrained = cov[a][a] > 0;
        p.se = p.constrained ? std::sqrt(cov[a][a]) : 0.0;
        for (size_t b = 0; b < use.size(); ++b)
            res.correlation[a][b] = cov[a][a] > 0 && cov[b][b] > 0 ? cov[a][b] / std::sqrt(cov[a][a] * cov[b][b]) : 0;
    }
}

// A fit's state: the model's bins at a point of the free keys, recomputed as compare computes them, and the residuals
// of its cells against the reference's
struct Fitter {
    ModelEvaluator& ev;
    const Stack& stack;
    const FitOptions& o;
    const ModelGrid grid;
    const SimResult& ref;
    Target target;
    ModelOptions mo;
    int evaluations = 0;

    Fitter(ModelEvaluator& e, const SimResult& ref, const Stack& s, const FitOptions& fo)
        : ev(e), stack(s), o(fo), grid(model_grid(ref)), ref(ref), target(target_of(ref, fo.loss)), mo(fo.models) {
        mo.selected = {o.model};
        target.unbiased_log = fo.bias_corrections;
    }
    Stack stack_at(const std::vector<double>& x) const {
        Stack s = stack;
        for (size_t i = 0; i < x.size(); ++i) o.free[i].set(s, x[i]);
        return s;
    }
    ModelOptions options_at(const std::vector<double>& x) const {   // the model's own parameters among the keys
        ModelOptions m = mo;
        for (size_t i = 0; i < x.size(); ++i) o.free[i].set_parameter(m, x[i]);
        return m;
    }
    ModelSlices evaluate(const std::vector<double>& x) {
        ++evaluations;
        for (const ModelSlices& m : ev.evaluate(stack_at(x), grid, nullptr, options_at(x)))
            if (m.id == o.model) return m;
        throw std::invalid_argument("no model '" + o.model + "' (gonio models lists them)");
    }
    double loss_of(const ModelSlices& m, std::vector<double>* r) const {
        std::vector<double> rr = residuals(target, m, o.loss);
        const double l = mean_square(rr);
        if (r) *r = std::move(rr);
        return l;
    }
    std::vector<std::vector<double>> jacobian(const std::vector<double>& x, const std::vector<double>& r) {
        return forward_jacobian(o, x, r, [&](const std::vector<double>& xh) {
            std::vector<double> rh;
            loss_of(evaluate(xh), &rh);
            return rh;
        });
    }

    // One descent of Levenberg-Marquardt from the point x whose bins are m: steps clamped to each key's range, until
    // no step lowers the loss or the loss changes by less than 1e-7 (relative)
    struct Descent {
        std::vector<double> x, r;
        double loss = 0;
        ModelSlices bins;
        int iterations = 0;
        std::string stopped = "the largest number of iterations";
    };
    Descent descend(std::vector<double> x, ModelSlices m) {
        const size_t P = x.size();
        Descent d;
        d.loss = loss_of(m, &d.r);
        d.bins = std::move(m);
        double lambda = 1e-3;
        for (int it = 0; it < o.max_iterations; ++it) {
            d.iterations = it + 1;
            const std::vector<std::vector<double>> J = jacobian(x, d.r);
            const std::vector<std::vector<double>> A = normal_matrix(J);
            std::vector<double> g(P, 0.0);
            for (size_t i = 0; i < P; ++i)
                for (size_t k = 0; k < d.r.size(); ++k) g[i] -= J[i][k] * d.r[k];
            bool stepped = false;
            for (int tries = 0; tries < 12 && !stepped; ++tries) {
                std::vector<std::vector<double>> M = A;
                for (size_t i = 0; i < P; ++i) M[i][i] += lambda * std::max(A[i][i], 1e-30);
                std::vector<double> step;
                if (!solve(M, g, step)) {
                    lambda *= 10;
                    continue;
                }
                std::vector<double> xn = x;
                for (size_t i = 0; i < P; ++i)
                    xn[i] = std::clamp(x[i] + step[i], descent_lower_of(o.free[i]), double(o.free[i].range.hi));
                std::vector<double> rn;
                ModelSlices mn = evaluate(xn);
                const double ln = loss_of(mn, &rn);
                if (!(ln < d.loss)) {
                    lambda *= 4;
                    continue;
                }
                const double gain = (d.loss - ln) / d.loss;
                x = xn;
                d.r = std::move(rn);
                d.loss = ln;
                d.bins = std::move(mn);
                lambda = std::max(lambda / 3, 1e-7);
                stepped = true;
                if (o.progress)
                    std::fprintf(stderr, "gonio fit: iteration %d, loss %.6g (lambda %.1e)\n", it + 1, d.loss, lambda);
                if (gain < 1e-7) {
                    d.stopped = "the loss changed by less than 1e-7 (relative)";
                    it = o.max_iterations;
                }
            }
            if (!stepped) {
                d.stopped = "no step lowers the loss (a minimum)";
                break;
            }
        }
        d.x = std::move(x);
        return d;
    }
};

}   // namespace

FitResult fit_model(ModelEvaluator& ev, const SimResult& ref, const Stack& stack, const FitOptions& o) {
    Fitter fit(ev, ref, stack, o);
    std::vector<std::vector<double>> starts = o.starts;
    if (starts.empty()) {   // the stack's own values
        starts.emplace_back();
        for (const FitKey& k : o.free) starts.back().push_back(k.get(stack));
    }
    FitResult res;
    res.starts = starts.size();
    Fitter::Descent best;   // over the reference's own cells (verdict_cells), from every start
    size_t kept = 0;
    for (size_t k = 0; k < starts.size(); ++k) {
        ModelSlices m = fit.evaluate(starts[k]);
        if (!m.not_applicable.empty()) throw std::invalid_argument(m.not_applicable);
        if (!m.invalid.empty()) throw std::invalid_argument(o.model + ": " + m.invalid);
        if (k == 0) {   // the model at the (first) start, as the files show it beside the fit
            res.start_bins = m;
            res.loss_start = fit.loss_of(m, nullptr);
            if (!std::isfinite(res.loss_start)) {
                uint64_t paths = 0;
                for (const AngleResult& a : ref.angles) paths = std::max(paths, a.paths);
                throw std::invalid_argument("the reference gives the " + std::string(to_string(o.loss)) +
                                            " loss no cell to use (" + std::to_string(paths) +
                                            " paths per angle at most: its cells are empty or without a standard "
                                            "error); trace more paths");
            }
        }
        // a key at 0 (a smooth interface) starts its descent at the bottom of its continuous range
        std::vector<double> x0 = starts[k];
        bool moved = false;
        for (size_t i = 0; i < x0.size(); ++i)
            if (x0[i] < descent_lower_of(o.free[i])) x0[i] = descent_lower_of(o.free[i]), moved = true;
        Fitter::Descent d = moved ? fit.descend(x0, fit.evaluate(x0)) : fit.descend(x0, std::move(m));
        if (o.progress && starts.size() > 1)
            std::fprintf(stderr, "gonio fit: start %zu of %zu: loss %.6g\n", k + 1, starts.size(), d.loss);
        if (k == 0 || d.loss < best.loss) {
            best = std::move(d);
            kept = k;
        }
    }
    // again from there over cells whose ends that optimum's bins decide (planned_cells: the reference's own sums,
    // which decided them in the first descent, biased it), the start's loss on the same cells
    if (o.bias_corrections) {
        fit.target = target_of(ref, o.loss, &best.bins);
        const int first_iterations = best.iterations;
        best = fit.descend(best.x, std::move(best.bins));
        best.iterations += first_iterations;
    }
    res.loss_start = fit.loss_of(res.start_bins, nullptr);
    if (res.loss_start < best.loss) {   // never a point worse than the (first) start: the start, kept
        best.x = starts[0];
        best.bins = res.start_bins;
        best.loss = fit.loss_of(best.bins, &best.r);
        best.stopped = "no point found with a lower loss than the start's (the start is kept)";
        kept = 0;
    }
    const std::vector<std::vector<double>> J = fit.jacobian(best.x, best.r);
    const std::vector<std::vector<double>> A = normal_matrix(J);
    std::vector<size_t> use;   // the constrained parameters
    const std::vector<std::vector<double>> cov = parameter_covariance(fit.target, J, A, use);
    describe_parameters(o, starts[kept], best.x, use, cov, res);
    res.loss_best = best.loss;
    res.iterations = best.iterations;
    res.evaluations = fit.evaluations;
    res.stopped = best.stopped;
    res.best_stack = fit.stack_at(best.x);
    res.best_bins = std::move(best.bins);
    return res;
}

}   // namespace gonio
