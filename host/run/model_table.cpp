// model_table.cpp: the models' scores on the console (model_table.h).
#include "model_table.h"
#include "text_format.h"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <string>

namespace gonio {

namespace {

constexpr size_t kWidth = 120;   // no line longer
constexpr size_t kCell = 10;   // a column: "  0.0123*=", the number right-aligned, then its marks

struct Column {
    size_t angle;
    Side side;
    const BestModel& best;
};

// `lead` then `text`, wrapped at word boundaries to kWidth, the following lines indented by `indent`
void print_wrapped(const std::string& lead, const std::string& text, size_t indent) {
    std::istringstream words(text);
    std::string line = lead, word;
    while (words >> word) {
        const bool blank = line.find_first_not_of(' ') == std::string::npos;
        if (!blank && line.size() + 1 + word.size() > kWidth) {
            std::printf("%s\n", line.c_str());
            line = std::string(indent, ' ');
        }
        line += line.empty() || line.back() == ' ' ? word : " " + word;
    }
    std::printf("%s\n", line.c_str());
}

void print_trimmed(const std::string& line) {
    std::printf("%s\n", line.substr(0, line.find_last_not_of(' ') + 1).c_str());
}

std::string cell_of(const ModelSlices& m, const ModelScores& scores, const Column& c) {
    const std::vector<ModelMetrics>& metrics = scores.side(c.side);
    if (c.angle >= metrics.size()) return std::string(kCell - 3, ' ') + "-  ";
    const ModelMetrics& mm = metrics[c.angle];
    char b[32];
    const std::string marks = std::string(mm.within_noise ? "*" : "") +
                              (c.best.best == m.id ? "=" : (c.best.tie && c.best.runner_up == m.id ? "~" : ""));
    std::snprintf(b, sizeof b, "%*.4f%-2s", int(kCell - 2), mm.rmse_remapped, marks.c_str());
    return b;
}

// the scores: rows of models, columns of (angle, side), in blocks that fit kWidth
void print_scores(const SimResult& r, const std::vector<size_t>& scored, const std::vector<ModelSlices>& models,
                  const Comparison& comparison, bool transmissive) {
    std::vector<Column> cols;
    for (size_t a = 0; a < r.angles.size(); ++a)
        for (Side side : {kReflection, kTransmission})
            if (side == kReflection || transmissive) cols.push_back({a, side, comparison.best_of(a, side)});
    const std::string head_first = "theta_i", head_cont = "theta_i (cont.)";
    size_t id_width = head_cont.size();   // the first column holds the ids and the row of angles' label
    for (size_t m : scored) id_width = std::max(id_width, models[m].id.size());
    const size_t per_block = std::max<size_t>(1, (kWidth - id_width - 1) / kCell);
    std::printf("RMSE of log(1 + sqrt f) per incident angle%s; * within the reference's noise, = best, ~ tied\n",
                transmissive ? " and side (R, T)" : "");
    for (size_t first = 0; first < cols.size(); first += per_block) {
        const size_t last = std::min(cols.size(), first + per_block);
        std::string head = first == 0 ? head_first : head_cont;
        head.resize(id_width + 1, ' ');
        for (size_t k = first; k < last; ++k) {
            std::string label = format_g9(r.angles[cols[k].angle].theta_i_deg);
            if (transmissive) label += cols[k].side == kReflection ? " R" : " T";
            head += std::string(kCell - 2 - std::min(kCell - 2, label.size()), ' ') + label + "  ";
        }
        print_trimmed(head);
        for (size_t m : scored) {
            std::string row = models[m].id;
            row.resize(id_width + 1, ' ');
            for (size_t k = first; k < last; ++k) row += cell_of(models[m], comparison.models[m], cols[k]);
            print_trimmed(row);
        }
    }
}

// What a user's model claims (its header may leave either out) beside what gonio measured of it
void print_claims(const ModelSlices& m, const ModelScores& scores) {
    auto claim = [](int c, const char* what) {
        return c < 0 ? std::string("its header does not say whether it is ") + what
                     : std::string("its header claims it ") + (c ? "is " : "is not ") + what;
    };
    std::string text;
    char b[256];
    const ModelAsymmetry& a = m.reciprocity;
    if (a.pairs == 0) {
        text = "reciprocity not measured (gonio measures a GLSL model's; it does not run a model from value files)";
    } else if (a.compared == 0) {
        std::snprintf(b, sizeof b, "reciprocity untested (f is 0 at all %u direction pairs)", a.pairs);
        text = b;
    } else if (a.reciprocal()) {
        std::snprintf(b, sizeof b,
                      "reciprocal as measured (f(l, v) against f(v, l) at %u direction pairs: at most %.2g "
                      "apart, relative)",
                      a.pairs, a.worst);
        text = b;
    } else {
        std::snprintf(b, sizeof b,
                      "not reciprocal as measured (f(l, v) and f(v, l) %.3g apart, relative, at theta_l "
                      "%g, theta_v %g, phi %g deg; %u direction pairs)",
                      a.worst, a.theta_l, a.theta_v, a.phi, a.pairs);
        text = b;
    }
    if (a.non_finite) text += " (" + std::to_string(a.non_finite) + " pairs left out: NaN, infinite or negative)";
    const bool contradicted = a.compared && m.claims_reciprocal >= 0 && (m.claims_reciprocal == 1) != a.reciprocal();
    text += "; " + claim(m.claims_reciprocal, "reciprocal") + (contradicted ? ", which this contradicts" : "");
    const LargestAlbedo& la = scores.largest;
    std::snprintf(b, sizeof b,
                  ". Reflects at most %.4f of the light it receives (theta_i %g, channel %c) on this stack", la.value,
                  la.theta_i, "RGB"[la.channel]);
    text += b;
    const bool gains = la.value > 1.0 + kWhiteFurnaceTolerance;
    text += "; " + claim(m.claims_energy_conserving, "energy-conserving") +
            (gains && m.claims_energy_conserving == 1 ? ", which this contradicts." : ".");
    print_wrapped("  " + m.id + ":", text, 4);
}

}   // namespace

void print_model_metrics(const SimResult& r, const std::vector<ModelSlices>& models, const Comparison& comparison) {
    size_t not_selected = 0, variants = 0;
    std::vector<size_t> scored, users;
    bool transmissive = false;
    for (size_t i = 0; i < models.size(); ++i) {
        const ModelSlices& m = models[i];
        if (m.not_selected) {   // one line for them all, below
            ++(m.not_applicable.find("(a variant: --models all") != std::string::npos ? variants : not_selected);
            continue;
        }
        if (!m.not_applicable.empty() || !m.invalid.empty()) continue;
        scored.push_back(i);
        transmissive = transmissive || !m.t.empty();
        if (!m.file.empty()) users.push_back(i);
    }
    if (!scored.empty()) print_scores(r, scored, models, comparison, transmissive);
    for (const ModelSlices& m : models) {
        if (m.not_selected) continue;
        if (!m.not_applicable.empty())
            print_wrapped(m.id + " not applicable:", m.not_applicable, 4);
        else if (!m.invalid.empty())
            print_wrapped(m.id + " not scored:", m.invalid, 4);
    }
    if (!users.empty()) std::printf("your models, measured:\n");
    for (size_t m : users) print_claims(models[m], comparison.models[m]);
    if (not_selected)
        print_wrapped("",
                      std::to_string(not_selected) + " more model" + (not_selected == 1 ? "" : "s") +
                          " not selected by --models (summary.json lists them; gonio models describes them)",
                      0);
    if (variants)
        print_wrapped("",
                      std::to_string(variants) + " variant" + (variants == 1 ? "" : "s") +
                          " of these models not run (--models all runs them; gonio models describes them)",
                      0);
}

}   // namespace gonio
