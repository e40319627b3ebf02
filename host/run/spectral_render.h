// spectral_render.h: gonio render --spectral (docs/RENDER.md): the reference's table traced band by band, the stack's
// RGB run (its measured materials reduced to three channels) rendered beside it, and their colour difference on the
// sphere, CIEDE2000 and Delta E_ITP per pixel.
#pragma once

#include "render_case.h"
#include "json.h"
#include "reference_render.h"

#include <string>
#include <utility>
#include <vector>

namespace gonio {

struct SpectralRenderTables {
    ReferenceTable spectral, rgb;   // the same bins and angles, each two independent halves
    Stack rgb_stack;   // the stack the RGB run traced, and the models are evaluated on
    std::string clipped;   // what the reduction could not reach (ConductorRgb::clipped)
    double spectral_seconds = 0, rgb_seconds = 0;
};

// Both tables, traced now with a.paths / 2 per angle in each half (the spectral halves with seeds a.seed and a.seed +
// 0x9e3779b9, as simulate_table_halves's): the spectral halves' files in OUT/spectral-{a,b} (simulate --spectral's),
// the RGB halves' states in OUT/rgb-table-{a,b}. Refuses (exit 2) a stack that cannot be traced spectrally.
SpectralRenderTables spectral_render_tables(VkContext& ctx, const Stack& s, const RenderRequest& a);

// The RGB run's render beside the spectral reference's: OUT/reference-rgb.{exr,png} and the colour difference,
// OUT/rgb-vs-spectral-{de2000,de-itp,noise}.exr (the value in R, G and B, A = 1 on the pixels that count) and
// rgb-vs-spectral-de2000.png (CIEDE2000 / 10 in red); render.json's "rgb_vs_spectral" entry, which it returns.
Json rgb_vs_spectral_on_sphere(const SpectralRenderTables& t, const ReferenceRender& spectral, const Environment& env,
                               const RenderRequest& a, const std::vector<std::pair<std::string, std::string>>& attrs,
                               double exposure);

}   // namespace gonio
