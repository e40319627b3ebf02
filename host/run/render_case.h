// render_case.h: the reference and every model that can represent a stack on a sphere under an environment map,
// their differences and HDR-FLIP (docs/RENDER.md): what `gonio render` and `compare --render` run.
#pragma once
#include "sphere_stage.h"
#include "measured_materials.h"
#include "model_registry.h"
#include "reference.h"
#include "spectral_bands.h"
#include "stack.h"
#include "vk_context.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

// What a render is asked for (gonio render's options).
struct RenderRequest {
    std::string stack, env = "studio", out, reference;
    uint32_t size = 256, spp = 64, seed = 1;
    uint64_t paths = 2000000;   // the table's paths per angle, split into two halves (without --reference)
    std::vector<double> theta_i = default_table_angles();
    ModelOptions models;
    ContextOptions ctx;
    bool quiet = false, no_report = false;
    // --spectral: the table traced band by band, and the stack's RGB run (its materials reduced by `reduction`)
    // rendered beside it for the colour difference on the sphere (docs/RENDER.md)
    bool spectral = false, bands_given = false, reduction_given = false;
    SpectralBands bands;
    RgbReduction reduction = RgbReduction::Dominant;

    static std::vector<double> default_table_angles() {   // 0:88:2
        std::vector<double> t;
        for (int d = 0; d <= 88; d += 2) t.push_back(d);
        return t;
    }
};

// The options of one half of the table render traces now: r's angles, half its paths, its seed (checked).
SimOptions table_half_options(const RenderRequest& r);

// Renders the reference and the models into r.out (the table too, unless r.reference names one) by the render's
// stage (sphere_stage.h), under env if given, else r.env read first: the images, render.json and, unless
// r.no_report, FLIP and figure.png by tools/render_report.py. Returns 1 if a model's image could not be used
// (pixels that are NaN or infinite: said, and its images not written), else 0.
int render_to_directory(VkContext& ctx, const Stack& s, const RenderRequest& r, const Environment* env = nullptr);

}   // namespace gonio
