#include "colours.h"

#include <algorithm>
#include <cmath>

namespace gonio::view {

namespace {

float shape(float f, bool remap) { return remap ? std::log1p(std::sqrt(std::max(f, 0.0f))) : std::max(f, 0.0f); }

uint32_t pack(float r, float g, float b) {
    auto u = [](float x) { return uint32_t(std::lround(std::clamp(x, 0.0f, 1.0f) * 255.0f)); };
    return u(r) | (u(g) << 8) | (u(b) << 16) | (255u << 24);
}

// a perceptual ramp, dark blue - teal - green - yellow (stops of the viridis palette)
uint32_t ramp(float t) {
    static const float s[5][3] = {{0.267f, 0.005f, 0.329f},
                                  {0.229f, 0.322f, 0.546f},
                                  {0.128f, 0.567f, 0.551f},
                                  {0.369f, 0.789f, 0.383f},
                                  {0.993f, 0.906f, 0.144f}};
    t = std::clamp(t, 0.0f, 1.0f) * 4.0f;
    int i = std::min(int(t), 3);
    float w = t - float(i);
    return pack(s[i][0] + w * (s[i + 1][0] - s[i][0]), s[i][1] + w * (s[i + 1][1] - s[i][1]),
                s[i][2] + w * (s[i + 1][2] - s[i][2]));
}

// signed: blue (model below the reference) - white - red (above)
uint32_t diverging(float t) {
    t = std::clamp(t, -1.0f, 1.0f);
    const float w = 0.97f;
    if (t < 0) return pack(w + (0.13f - w) * -t, w + (0.40f - w) * -t, w + (0.80f - w) * -t);
    return pack(w + (0.80f - w) * t, w + (0.15f - w) * t, w + (0.15f - w) * t);
}

}   // namespace

float shown_value(const float* rgb, int channel, bool remap) {
    if (channel >= 1 && channel <= 3) return shape(rgb[channel - 1], remap);
    return shape(0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2],
                 remap);   // as tools/report.py: remap(luminance)
}

bool PanelColours::update(const Display& d, const ColourSettings& s, std::chrono::milliseconds min_interval) {
    auto now = std::chrono::steady_clock::now();
    const bool other = !built_ || !(s == seen_settings_) || d.models_version != seen_models_;
    if (!other && (d.version == seen_ref_ || now - last_ < min_interval)) return false;
    built_ = true;
    seen_settings_ = s;
    seen_models_ = d.models_version;
    seen_ref_ = d.version;
    last_ = now;
    bins_ = size_t(d.n_theta) * d.n_phi;
    n_models_ = s.models.size();
    rgba_.assign((1 + 2 * n_models_) * bins_, pack(0, 0, 0));
    static const std::vector<float> none;
    const std::vector<float>& ref = d.values[s.side].size() == 3 * bins_ ? d.values[s.side] : none;
    // the reference's peak sets the exposure (per channel in RGB mode)
    float peak = 0;
    for (size_t b = 0; b < ref.size() / 3; ++b) {
        if (s.channel == 0)
            for (int c = 0; c < kChannels; ++c) peak = std::max(peak, shape(ref[3 * b + c], s.remap));
        else
            peak = std::max(peak, shown_value(&ref[3 * b], s.channel, s.remap));
    }
    const float gain = (peak > 0 ? 1.0f / peak : 1.0f) * std::exp2(s.exposure);
    auto paint = [&](const std::vector<float>& v, uint32_t* out) {
        if (v.size() != 3 * bins_) return;
        for (size_t b = 0; b < bins_; ++b) {
            const float* f = &v[3 * b];
            out[b] = s.channel == 0
                         ? pack(shape(f[0], s.remap) * gain, shape(f[1], s.remap) * gain, shape(f[2], s.remap) * gain)
                         : ramp(shown_value(f, s.channel, s.remap) * gain);
        }
    };
    paint(ref, rgba_.data());
    // differences, remapped, on one symmetric scale: the 99th percentile of |difference| over the shown models
    // (a near-delta lobe a model puts one bin off would otherwise wash everything else out)
    std::vector<std::vector<float>> diffs(n_models_);
    std::vector<float> mags;
    for (size_t i = 0; i < n_models_; ++i) {
        const auto& mv = d.values[2 * (1 + s.models[i]) + s.side];
        paint(mv, rgba_.data() + model(i));
        if (mv.size() != 3 * bins_ || ref.empty()) continue;
        diffs[i].resize(bins_);
        for (size_t b = 0; b < bins_; ++b) {
            diffs[i][b] = shown_value(&mv[3 * b], s.channel, s.remap) - shown_value(&ref[3 * b], s.channel, s.remap);
            mags.push_back(std::fabs(diffs[i][b]));
        }
    }
    diff_scale_ = 1e-3f;
    if (!mags.empty()) {
        size_t k = std::min(mags.size() - 1, size_t(0.99 * double(mags.size())));
        std::nth_element(mags.begin(), mags.begin() + k, mags.end());
        diff_scale_ = std::max(mags[k], 1e-3f);
    }
    for (size_t i = 0; i < n_models_; ++i)
        for (size_t b = 0; b < diffs[i].size(); ++b) rgba_[difference(i) + b] = diverging(diffs[i][b] / diff_scale_);
    ++version_;
    return true;
}

}   // namespace gonio::view
