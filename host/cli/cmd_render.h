// cmd_render.h: `gonio render STACK`: the reference and every model that can represent the stack on a sphere
// under an environment map, their differences and HDR-FLIP (docs/RENDER.md; the pipeline: render_case.h).
#pragma once
#include "common_options.h"
#include "options.h"
#include "render_case.h"

namespace gonio {

Command render_command();

// What render's options set, its table (the Python module's render takes them), and the checks after them: the
// options that go with --spectral alone, and the --model files read and compiled (into r.models).
struct RenderSettings {
    RenderRequest r;
    ModelSettings m;   // --models, --model
};
OptionTable render_options(RenderSettings& a);
void check_render_settings(RenderSettings& settings);

}   // namespace gonio
