#include "help.h"

#include <sstream>

namespace gonio {

namespace {

constexpr const char* kHelpTitle =
    "gonio " GONIO_VERSION " - a virtual gonio-photometer for layered materials (Vulkan compute)\n";
constexpr const char* kHelpUsage = R"(
usage:
  gonio devices                         list Vulkan devices; '*' marks the one gonio uses
  gonio check STACK.toml                parse and validate a stack file, print it, exit
  gonio simulate STACK.toml [options]   trace paths through the stack, write calibrated BRDF/BTDF histograms
  gonio compare STACK.toml [options]    simulate, then evaluate every analytic model that can represent the
                                        stack on the same bins, and write how far each is from the reference
  gonio models                          list the models: id, citation, which stacks each can represent
  gonio bench [STACK.toml ...] [options]
                                        paths per second per stack on the device and on the CPU twin
                                        (default: every stacks/*.toml); --out DIR adds convergence, the
                                        models' cost against their error, and an error atlas
  gonio random-stack --seed N [--count K] [--out DIR]
                                        seeded random stacks over the whole valid parameter space, as
                                        TOML (stdout, or DIR/random-N-i.toml); same seed, same stacks
  gonio sweep SWEEP.toml [--out DIR] [--shard K/N] [--resume] [--batch B] [--bench N] [--keep-results] [--quiet]
                                        vary stack parameters (sweeps/*.toml), run the reference and every
                                        model per configuration, and tabulate their errors in DIR/sweep.csv;
                                        --batch: configurations traced per dispatch (default 16; results do not
                                        depend on it); --bench N: time N configurations batched and as a loop
                                        of compare, in one run (DIR/sweep-bench.json); --keep-results: also
                                        each configuration's EXR, slices.csv and summary.json (DIR/configs/c-N/).
                                        A sweep file gives paths per configuration and angle, or rse = R (each
                                        configuration runs as simulate --rse R, paths then the cap)
  gonio merge DIR                       gather the shards of a sweep (DIR/configs/) into DIR/sweep.csv
  gonio export DIR --format merl|rgl-bsdf --out FILE [--source reference|MODEL_ID]
                                        a simulate / compare output over incident angles 0 to >= 80 degrees, at
                                        most 5 apart (--theta-i 0,2,...,88), as a file renderers read: MERL
                                        .binary (BRDF Explorer, libbsdf) or RGL .bsdf (Mitsuba 3's measured;
                                        needs pip's mitsuba); runs tools/export.py (python/gonio)
  gonio nodes STACK.toml --out DIR [--theta-i A,B,...] [--dtheta D --dphi P] [--nodes-per-bin K]
                                        a model in any language, through files: DIR/nodes.csv, one row per
                                        quadrature node, theta_i,side,bin,lx,ly,lz,vx,vy,vz,weight (K x K
                                        Gauss-Legendre nodes per bin, default 4; a bin's average of f is the
                                        sum of weight x f(l, v) over its nodes; directions away from the
                                        surface, v.z < 0 the transmission side), nodes.npy (the same,
                                        float64; side 0 = R, 1 = T) and nodes.json
  gonio score NODES_DIR --values FILE --id ID --reference SIMULATE_DIR --out DIR [--no-report]
                                        the values of f at the nodes (FILE: one row r,g,b per node, in
                                        nodes.csv's order, or a .npy of shape (nodes, 3); 1/sr, cosine
                                        excluded) on the bins of a simulate
                                        run of the same stack, angles and bins: what compare writes for a
                                        model (slices.csv, summary.json, EXR, report.html)
  gonio render STACK.toml --out DIR [--env NAME|FILE.exr] [--size N] [--reference DIR] [options]
                                        the reference and every model that can represent the stack on a
                                        sphere under an environment map; their differences and HDR-FLIP
                                        (gonio render --help)
  gonio view STACK.toml [options]       the interactive viewer (a window; runs gonio-view, built beside
                                        gonio when GLFW and Dear ImGui are installed; gonio view --help)
  gonio help | --help                   this text

)";
constexpr const char* kHelpRender = R"(render options:
  --out DIR             where the images and render.json go                    (required)
  --env NAME|FILE.exr   the light: furnace (uniform radiance 1), studio (three disc lights over a dim
                        gradient, procedural), one of Debian blender-data's maps city, courtyard, forest,
                        interior, night, sunrise, sunset (and its studio as a file:
                        /usr/share/blender/datafiles/studiolights/world/studio.exr), or an EXR file;
                        equirectangular, z up, row 0 the zenith; negative texels set to 0 and
                        counted                                                 (default studio)
  --size N              pixels per side, 8 to 2048; an orthographic camera along -z, the unit sphere
                        filling the frame                                      (default 256)
  --reference DIR       the reference's table: a render output (DIR/table-a, DIR/table-b: two
                        independent halves) or a simulate output over incident angles (DIR/state.gonio;
                        its floor from f +- se); without it render simulates two halves of --paths
                        per angle at --theta-i and keeps them in OUT/table-{a,b}
  --paths N             paths per incident angle of the table, both halves     (default 2e6)
  --theta-i LIST        the table's incident angles (A:B:S ranges)             (default 0:88:2)
  --spp N               the models' iterations per pixel, each one sample of the environment, the
                        cosine hemisphere and the GGX lobe, combined by MIS    (default 64)
  --seed S              seed of the table and of the models' samples (same seed, same bytes)
  --models ID,ID        render only these models (gonio models, or the ids of --model files)
  --model FILE          also render your own model, one GLSL file as compare takes it (repeatable;
                        render.comp is compiled with it before anything is simulated)
  --no-report           no FLIP and no figure (tools/render_report.py)
  --device I, --quiet

render writes: reference.exr and MODEL.exr (RGBA float, A = the sphere), reference.png and MODEL.png
(the same exposure, x / (1 + x), sRGB), diff-MODEL.exr/png (MODEL - reference, red above, blue below),
reference-half-a.exr / -half-b.exr, render.json (per model: relative L1 and HDR-FLIP mean and 95th
percentile against the reference, beside the reference's own floor between its halves; times) and
figure.png (the spheres in a row, their FLIP maps below; FLIP needs pip's flip-evaluator).

)";
constexpr const char* kHelpSimulate = R"(simulate options:
  --theta-i A,B,...     incident polar angles in degrees, in [0, 90)           (default 0)
                        an item FROM:TO:STEP is a range: 0:88:2 is 0, 2, ..., 88
  --paths N             paths per incident angle, e.g. 1e8                     (default 1e6)
  --seed S              random seed (same seed, same bytes)                    (default 1)
  --out DIR             output directory                                       (default out/<stack name>)
  --dtheta D --dphi P   bin widths in degrees; D divides 90, P divides 180     (default 1, 2)
  --orders              also split the histograms by path class: 0 = top reflection only / direct
                        transmission, 1 = one internal reversal (one trip to the base and back),
                        2 = two or more (inter-reflections). Classes sum exactly to the total.
  --max-events N        event cap per path; energy still inside is reported as truncated (default 256)
  --rse R               run until the relative standard errors of the bins above 1% of their slice's peak
                        are below R (e.g. 0.01) at the --rse-quantile; paths grow in rounds of 2^20 x 2^k
                        per angle, --paths is the cap (default then 1e10). summary.json says what stopped
                        each angle, and the median, 90th percentile and worst relative se
  --rse-quantile Q      which bins --rse stops on: the quantile Q of their relative standard errors
                        (default 0.5, the median; 1: the worst bin, which can take hours)
  --checkpoint-seconds S  write DIR/state.gonio atomically at least every S seconds of tracing (default 30;
                        0: only at the end): a killed run continues with the same command and --resume DIR,
                        to the same bytes as one uninterrupted run
  --max-seconds S       stop an incident angle after S seconds (reported as stopped_by max_seconds); the
                        angles run side by side, each taking its share of the time by paths
  --angles-per-dispatch N  trace at most N incident angles side by side in shared dispatches (default 0: every
                        angle the device's memory holds; 1: one angle after the other). The same bytes
  --resume DIR          continue the run whose output is in DIR (its state.gonio) up to --paths: the result
                        is exactly that of one longer run. Same stack, seed, bins, angles, options required
  --cpu-twin            run the walk on the CPU (same shader sources via GLM) instead of the device
  --general-walk        use the general N-layer walk instead of the stack-specialised shader
  --no-series           trace every trip between a Lambertian base and its coat instead of summing them
                        as the Lambertian series (docs/PHYSICS.md; the default where it applies: a
                        dielectric coat over a Lambertian base, without --orders)
  --no-baked-stack      read the stack's parameters from a uniform buffer at run time instead of compiling
                        them into the shader (the default for a specialised walk of one or two layers;
                        docs/PERFORMANCE.md). The same paths and estimator; the last bits of rounding can
                        differ, and this is what a sweep's batches compute: use it to reproduce one
                        configuration of a sweep byte for byte
  --device I            Vulkan device index (see `gonio devices`)
  --validate            enable the Khronos validation layer; any message makes the run fail
  --quiet               no progress line

)";
constexpr const char* kHelpSimulateOutputs = R"(simulate writes, in DIR:
  <name>.exr      OpenEXR, one part per incident angle and side (R: reflection, T: transmission);
                  rows = theta bins, columns = phi bins (centred on multiples of dphi); channels R,G,B
                  (bin average of f, 1/sr) and se.R, se.G, se.B (standard errors); header: stack, angles,
                  paths, seed, device, gonio version
  slices.csv      one row per bin: source,theta_i,side,theta_lo,theta_hi,phi_lo,phi_hi,r,g,b,se_r,se_g,se_b
  summary.json    per incident angle and channel: reflected, transmitted, absorbed, microfacet_loss and
                  truncated energy fractions (they sum to 1); paths, seconds, paths per second, device

)";
constexpr const char* kHelpCompare = R"(compare options (and the simulate options above, but --cpu-twin):
  --no-report           no figures, no report.html
  --no-belcour-tables   Belcour's models without their FGD and TIR tables (see below)
  --models ID,ID,...    run only these models (ids of `gonio models` or of --model files; the others are
                        reported as not selected)
  --model FILE          also run your own model, one GLSL file (repeatable; docs/MODELS.md "Your own
                        model", examples/user_model.glsl): its header (gonio-model, citation, represents,
                        reciprocal, energy-conserving), then vec3 model_f(vec3 l, vec3 v), f in 1/sr without
                        the cosine. Compiled before the simulation starts (a compile error: FILE:LINE, exit
                        2), integrated as a black box (graded at the stack's narrowest roughness about the
                        mirror direction, then refined where the nodes disagree) and scored as the built-in
                        models are. Values that are NaN, infinite or negative are reported with where they
                        are (summary.json "invalid_values"), never scored or written, and compare exits 1
  --render ENV          also render the reference and the built-in models on a sphere under ENV (furnace,
                        studio, a Blender map's name, FILE.exr; as gonio render --env) into DIR/render;
                        report.html shows the figure and each model's relative L1 and HDR-FLIP beside the
                        reference's floor (docs/RENDER.md), --model files' too. The render's table is its
                        own: 0:88:2 in two halves of --render-paths per angle (default 1e6), seeded by --seed
  --render-size N       the render's pixels across (default 128)
  --render-paths N      the render's table, paths per angle (default 1e6)

compare writes everything simulate writes, plus: model rows in slices.csv (source = model id, reflection
side, se 0), and in summary.json per model and incident angle: RMSE and mean absolute error in the seed's
remapped space log(1 + sqrt f), RMSE and mean relative error in f, directional albedo (model, reference,
error), the largest remapped error and its bin, the reference's own noise on the same bins (remapped), and
whether the model is within that noise, and whether its albedo (reflected + transmitted) breaks the white-furnace
bound (reflects_more_than_it_receives: flagged and warned on stderr, never clamped). A model that cannot represent
the stack is listed with the reason.
It then draws, with tools/report.py (Python 3 + matplotlib): slices.png (the seed's in-plane slice diagrams,
log(1 + sqrt f) of luminance), albedo.png, topview-<i>.png (top view of the hemisphere: reference, models,
signed differences), and report.html with the metric tables. --no-report skips them.
--no-belcour-tables runs Belcour's models without their FGD and TIR tables (Fresnel at the mean cosine, no TIR
term), as the seed does for slabs. The tables are computed on the device for the stack's interfaces and cached in
$GONIO_CACHE_DIR (default $XDG_CACHE_HOME/gonio or ~/.cache/gonio; GONIO_NO_CACHE=1 turns the cache off).

)";
constexpr const char* kHelpBench =
    R"(bench options: --paths N (device, default 2e7), --cpu-paths N (default 1e6), --theta-i A, --device I,
  --out DIR: also measure, per stack, the reference's convergence (relative RMS error against a 2^25-path run
  and median relative standard error, against paths and seconds, with the 1/sqrt(N) fit and the seconds to
  reach 1% and 0.1%), and every model on the 2^25-path run's bins (device seconds per evaluation and per
  grid against its RMSE in log(1 + sqrt f)); then the error atlas: --atlas K random two-layer stacks (a coat
  over a conductor; default 16, 0: none; --seed picks them), the reference (--atlas-paths per angle, default
  2e6) and every model at 0/30/60/80 degrees, the best model per stack and angle. Writes DIR/bench.json,
  convergence.png, pareto.png, atlas.png and bench.html (tools/bench_plot.py).
  Prints, per stack, paths per second of the stack-specialised walk, of the general N-layer walk, and of
  the CPU twin (same shader sources, all cores), measured in one run, with their ratios, and the mean
  events per path (interface events and collisions in scattering media; 2^16 paths of the CPU twin).
  --model FILE (repeatable), --models ID,ID: users' model files and the models to run, as for compare.
  --render ENV [--render-size N]: also time gonio render's stages per stack under ENV (as render --env;
  a 1024 x 512 map such as forest): the 0:88:2 table in two halves, the reference's sum on the CPU, every
  model that represents the stack on the device (N x N pixels, default 256; 64 iterations each).

)";
constexpr const char* kHelpRandomStack =
    R"(random-stack options: --seed N (default 1), --count K (default 1), --out DIR (default: print to stdout)

)";
constexpr const char* kHelpTail =
    R"(Exit codes: 0 success; 2 refused input (a stack, sweep or state file that is invalid, with file:line, or an
option that cannot work; nothing is run); 1 a failure while running (a device error, a write that failed, a
Vulkan validation message under --validate, paths whose weight stopped being finite, a model whose values
could not be used).

Conventions (docs/PHYSICS.md): directions point away from the surface, z is the stack normal, the light
arrives from (theta_i, phi_i = 0); f excludes the cosine.
)";

}   // namespace

std::string full_help() {
    return std::string(kHelpTitle) + "\n" + kHelpUsage + kHelpSimulate + kHelpSimulateOutputs + kHelpCompare +
           kHelpBench + kHelpRandomStack + kHelpTail;
}

std::string short_help() { return std::string(kHelpTitle) + "\n" + kHelpUsage + kHelpTail; }

std::string command_help(const std::string& cmd) {
    std::string usage_line, l;
    std::istringstream in(kHelpUsage);
    bool mine = false;   // a command's block: its "  gonio CMD" line and the indented lines under it
    while (std::getline(in, l)) {
        if (l.rfind("  gonio ", 0) == 0)
            mine = l.rfind("  gonio " + cmd + " ", 0) == 0 || l == "  gonio " + cmd;
        else if (l.rfind("      ", 0) != 0)
            mine = false;
        if (mine) usage_line += l + "\n";
    }
    std::string h = std::string(kHelpTitle) + "\nusage:\n" + usage_line + "\n";
    if (cmd == "simulate")
        h += std::string(kHelpSimulate) + kHelpSimulateOutputs;
    else if (cmd == "compare")
        h += std::string(kHelpSimulate) + kHelpCompare;
    else if (cmd == "bench")
        h += kHelpBench;
    else if (cmd == "random-stack")
        h += kHelpRandomStack;
    else if (cmd == "render")
        h += kHelpRender;
    else if (cmd == "check" || cmd == "models" || cmd == "devices")
        h += "(no options)\n\n";
    return h + kHelpTail;
}

}   // namespace gonio
