// colours.h: the hemisphere panels' colours, one RGBA8 value per bin, computed on the host from the bin averages
// (remap, channel, exposure; signed differences on one symmetric scale) and rebuilt only when something changed
// (the reference at most ten times a second): lavapipe then shades a panel pixel with a single load.
#pragma once
#include "app.h"

#include <chrono>
#include <cstdint>
#include <vector>

namespace gonio::view {

struct ColourSettings {
    int channel = 0;   // 0 RGB, 1 R, 2 G, 3 B, 4 luminance
    bool remap = true;   // log(1 + sqrt f)
    float exposure = 0;   // stops over the reference's peak
    int side = 0;   // 0 reflection, 1 transmission
    std::vector<size_t> models;   // shown models (registry indices), in panel order
    bool operator==(const ColourSettings&) const = default;
};

class PanelColours {
public:
    // Rebuilds when the settings or the models changed, or the reference changed and the last build is older
    // than `min_interval`. Returns whether it did.
    bool update(const Display& d, const ColourSettings& s,
                std::chrono::milliseconds min_interval = std::chrono::milliseconds(100));
    const std::vector<uint32_t>& rgba() const { return rgba_; }
    uint64_t version() const { return version_; }
    size_t panel_bins() const { return bins_; }
    // first colour of the reference panel, of shown model i and of its difference to the reference
    uint32_t reference() const { return 0; }
    uint32_t model(size_t i) const { return uint32_t((1 + i) * bins_); }
    uint32_t difference(size_t i) const { return uint32_t((1 + n_models_ + i) * bins_); }
    float difference_scale() const { return diff_scale_; }   // |model - reference| shown at full colour

private:
    std::vector<uint32_t> rgba_;
    size_t bins_ = 0, n_models_ = 0;
    float diff_scale_ = 0;
    uint64_t version_ = 0, seen_ref_ = ~0ull, seen_models_ = ~0ull;
    ColourSettings seen_settings_;
    bool built_ = false;
    std::chrono::steady_clock::time_point last_{};
};

// The shown value of one bin: the remap of one channel or of the luminance (RGB mode: luminance).
float shown_value(const float* rgb, int channel, bool remap);

}   // namespace gonio::view
