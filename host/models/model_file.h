// model_file.h: a model written as one GLSL file (docs/MODELS.md, "A model is one file"): its header, which says
// what the model is and which stacks it represents, read and checked before the file is compiled.
//
//   // gonio-model: my-coat
//   // citation: Doe 2027, "A better coat", eq. 3
//   // represents: coat-over-lambertian, coat-over-conductor
//   // reciprocal: yes
//   // energy-conserving: no (the base is not attenuated by the coat's reflection)
//   vec3 model_f(vec3 l, vec3 v) { ... }   // f in 1/sr, cosine excluded; z up, directions away from the surface
//
// A user's file needs only its first line (gonio-model): without `represents:` the model runs on every stack; without
// `reciprocal:` or `energy-conserving:` it claims neither, and gonio measures both for every user's model (compare:
// its reciprocity at direction pairs, its albedo on the stack) and reports them beside what the header claims.
//
// The header is the file's first comment lines; a line "// key: value" sets a key, a comment line without a key
// continues the value before it. Every problem is refused with FILE:LINE and what was expected.
//
// gonio's built-in models are files of the same form (shaders/lib/models/builtin/NN-ID.glsl, docs/MODELS.md "How
// to add a model"), read by the same parser (ModelFileKind::BuiltIn), with the keys a built-in's entry in `gonio
// models` needs besides:
//   // summary: what it does, in one line                (required)
//   // family: the family it is grouped with in reports   (required: Weidlich-Wilkie, Belcour 2018, production, ...)
//   // stacks: which stacks it represents, in words       (required)
//   // mapping: what its parameters are for a stack (a production model's: what an artist would set)
//   // artist-parameters: coat-over-lambertian = base_color (colour), coat_ior   (those parameters' names, one line
//   //   per shape it represents, in the order its GONIO_MODEL_ARTIST_PARAMETERS hook gives their values)
//   // variant: +g2 = convention g2: what the variant does differently (any number; conventions by name,
//   //   comma-separated: model_conventions(), CONVENTION_* of models/common.glsl)
//   // variant-energy-note: +g2 = the variant's own energy note (else its base model's)
//   // variant-reciprocal: +g2 = yes                   (the variant's own reciprocity claim, else its base model's)
//   // plan: coat                                      (how its terms are integrated, PlanKind; else a black box)
//   // table: coat-albedo 65                           (a per-stack table set it declares and fills: its name and
//   //   size in floats; any number. Its GONIO_MODEL_TABLES hook fills it on the host, models/all.glsl)
//   // tables: coat-albedo                             (the per-stack table sets it reads, any file's, by name)
//   // refuses: transmissive = {id} models reflection only (any number: a stack condition and the reason)
// and defines its entry   vec3 model_ID(CoatParams p, uint terms, vec3 l, vec3 v)   (ID with - . + as _) in place
// of model_f. In a built-in's header every key's value continues on the comment lines after it, and an empty
// comment line ("//") ends the header (the file's own description follows).
#pragma once
#include "stack.h"

#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

// The stacks a model may say it represents (`represents:`), each a shape of stack (layers top to bottom).
enum class StackShape {
    Any,   // every stack
    CoatOverLambertian,   // one dielectric interface over a Lambertian base
    CoatOverConductor,   // one dielectric interface over a conductor
    // a dielectric coat over a dielectric interface over a Lambertian: a production model's dielectric base
    // ("specular over diffuse") under its coat
    CoatOverDielectricOverLambertian,
    DielectricsOverLambertian,   // any number (0 or more) of dielectric interfaces over a Lambertian base
    DielectricsOverConductor,   // any number (0 or more) of dielectric interfaces over a conductor
    Slab,   // dielectric interfaces only, the substrate of the exterior's IOR (transmissive)
    Transmissive,   // dielectric interfaces only (the last one's medium is the substrate)
    // a fibre layer (a smooth interface index-matched to the exterior over an SGGX fibre medium) over a Lambertian:
    // the sheen models' one shape, the only one a model may take microflakes in
    FibresOverLambertian,
};

const char* to_string(StackShape s);
bool stack_has_shape(const Stack& s, StackShape shape);

// A model's conventions (ModelInfo::convention bits, CONVENTION_* in shaders/lib/models/common.glsl, which
// model_registry.cpp checks against these), named in a header's `variant:` lines as model_conventions() lists them.
constexpr uint32_t MODEL_CONVENTION_G2 = 1;   // height-correlated Smith G2 in lobes and FGD/TIR tables
constexpr uint32_t MODEL_CONVENTION_TIR_BELOW_MEDIA = 2;   // Belcour's TIR term kept below an absorbing medium
constexpr uint32_t MODEL_CONVENTION_DARKENING_T2 = 4;   // OpenPBR dev_1.2's darkening with the coat's T^2
constexpr uint32_t MODEL_CONVENTION_ROUGHENING_PR261 = 8;   // OpenPBR PR #261's roughening
constexpr uint32_t MODEL_CONVENTION_REFLECTANCE_FRESNEL = 16;   // Standard Surface OSL's reflectance(): F(n.v)
constexpr uint32_t MODEL_CONVENTION_MATERIALX_GRAPH = 32;   // OpenPBR's reference MaterialX graph
constexpr uint32_t MODEL_CONVENTION_COAT_FRESNEL_VH = 64;   // the glTF Sample Viewer's coat lobe: Schlick at v.h
constexpr uint32_t MODEL_CONVENTION_CYCLES_4_4 = 128;   // Blender 4.0-4.4's Principled coat (before fix #129306)
constexpr uint32_t MODEL_CONVENTION_RECIPROCAL_COAT = 256;   // adobe/openpbr-bsdf's OPENPBR_RECIPROCAL_COAT_AND_FUZZ
constexpr uint32_t MODEL_CONVENTION_SEPARABLE_G = 512;   // OpenPBR with the separable Smith G1(l) G1(v)
constexpr uint32_t MODEL_CONVENTION_DARKENING_NUMERATOR = 1024;   // OpenPBR's darkening with #269's numerator
constexpr uint32_t MODEL_CONVENTION_SINGLE_SCATTERING_LOBES = 2048;   // OpenPBR's base lobes uncompensated

// A per-stack table set a built-in model file declares (`table: NAME FLOATS`): cmake/builtin_models.cmake lays the
// sets out (their STACK_TABLES_* bits and STACK_TABLE_* offsets) from the same lines
struct TableSetDeclaration {
    std::string name;
    uint32_t floats = 0;
    int line = 0;
};

struct ModelConvention {
    const char* name;   // in a `variant:` line
    uint32_t bit;
    // gonio's own alternative to the official code's convention (a variant "gonio's variant of X"), else another
    // reading the model's authors published ("a variant of X")
    bool gonios;
};
const std::vector<ModelConvention>& model_conventions();

// How a built-in model's terms are integrated over the bins (`plan:`, host/models/model_plan.cpp): by name in a
// header, coat | coat-refracted | lobes | lobes-symmetric; a file without one (and every user's model) is integrated
// as a black box.
enum class PlanKind {
    BlackBox,   // no plan: one term, the black box's quadrature
    Coat,   // two layers, top lobe + base at the unrefracted directions with its own roughness (ww09, albedo-scaling)
    // two layers, the base at Snell-refracted directions, alpha1 <- max(alpha0, alpha1) (elek10, ww-corrected)
    CoatRefracted,
    // lobes (energies, roughnesses) at mu = cos theta_i from the file's own GONIO_MODEL_LOBES, computed once per
    // dispatch (models.comp KERNEL 2), with Belcour's FGD and TIR tables (Belcour's forward and top-lobe, tm21)
    Lobes,
    LobesSymmetric,   // the same lobes tabulated over mu = |h.l| (GONIO_MODEL_LOBE_TABLE: belcour18-symmetric)
};
const char* to_string(PlanKind k);

// The stack conditions a built-in's `refuses:` lines name, each with the model's reason.
enum class StackCondition {
    ScatteringMedium,   // scattering-medium: some medium scatters
    BackwardScatteringMedium,   // backward-scattering-medium: some scattering medium has phase_g <= 0
    LambertianBase,   // lambertian-base
    Transmissive,   // transmissive: the last layer is a dielectric
    SubstrateNotExterior,   // substrate-not-exterior: transmissive, the substrate's IOR other than the exterior's
    BaseNotLambertianOrConductor,   // base-not-lambertian-or-conductor
    BaseNotLambertian,   // base-not-lambertian
    NotTwoLayers,   // not-two-layers
    AbsorbingMedium,   // absorbing-medium: some medium has an optical depth above 0
    CoatIorNot1_5,   // coat-ior-not-1.5: the top interface's IOR relative to the exterior is not 1.5 (glTF's coat)
    CoatIorBeyond3,   // coat-ior-beyond-3: that IOR, or its inverse, is above 3 (OpenPBR's Fresnel-albedo fit)
    CoatIorBelow1,   // coat-ior-below-1: that IOR is below 1 (a coat less dense than the exterior: Cycles clamps it)
    AbsorbingBaseMedium,   // absorbing-base-medium: three layers, the medium under the base's interface absorbs
    // not-coat-over-base: neither two layers nor three of a dielectric base (dielectric, dielectric, Lambertian)
    NotCoatOverBase,
    // fibre-depth-not-1: a fibre layer over a Lambertian (fibres-over-lambertian) whose optical depth is not 1 in every
    // channel (the sheen authors' unit slab)
    FibreDepthNot1,
};
// refuses: CONDITION = REASON. The reason may name {id} (the registry entry's), {layer} ("layer N's medium
// scatters": the first medium the condition found), {phase_g} (its), {substrate_ior}, {exterior_ior}, {base} (the base
// kind), {layers} (the count), {coat_eta} (the top interface's IOR relative to the exterior) and {optical_depth} (the
// top layer's).
struct Refusal {
    StackCondition when;
    std::string reason;
    int line = 0;
};

// A built-in model's variant (`variant:`): the same code run with other conventions.
struct ModelVariant {
    std::string suffix;   // appended to the model's id ("+g2")
    uint32_t convention = 0;   // MODEL_CONVENTION_* bits
    std::string what;   // what it does differently (its summary is "as ID, " + what)
    std::string energy_note;   // `variant-energy-note:` (its energy measured on the hard cases), else empty
    bool has_energy_note = false;   // false: the base model's note
    // `variant-reciprocal: +SUFFIX = yes | no`: the variant's reciprocity where it differs from its base model's
    bool has_reciprocal = false, reciprocal = false;
};

// At most this many parameters a model (kernel_interface.glsl MODEL_MAX_PARAMETERS; model_registry.cpp checks)
constexpr uint32_t kModelMaxParameters = 8;

// A model's own parameter (`parameter: NAME default VALUE range [A, B] -- meaning`): read in GLSL as param_NAME
// (models/stack_tables.glsl model_parameter), set by a fit (`--free param.NAME`) or left at its default.
struct ModelParameter {
    std::string name;   // lower-case letters, digits, _; starts with a letter
    double value = 0;   // the default
    double lo = 0, hi = 0;   // its range, lo < hi, the default within
    std::string meaning;   // after "--"
    int line = 0;
};

enum class ModelFileKind {
    User,   // a user's model file (`--model FILE`): model_f(l, v), the keys above only
    // a built-in model (shaders/lib/models/builtin/): its entry model_ID(p, terms, l, v), and summary, stacks,
    // variants
    BuiltIn,
};

// A production model's artist parameters for one shape of stack (`artist-parameters: SHAPE = NAME, NAME (colour),
// ...`): the names its definition spells, in the order its GONIO_MODEL_ARTIST_PARAMETERS hook gives their values
// (models/common.glsl ArtistValues), "(colour)" marking a colour.
struct ArtistParameterName {
    std::string name;
    bool colour = false;
};
struct ArtistParameterList {
    StackShape shape = StackShape::Any;   // coat-over-lambertian, coat-over-conductor or
        // coat-over-dielectric-over-lambertian
    std::vector<ArtistParameterName> names;
    int line = 0;
};
// At most this many artist parameters per shape (models/common.glsl MODEL_MAX_ARTIST_PARAMETERS)
constexpr uint32_t kModelMaxArtistParameters = 16;

struct ModelFileHeader {
    std::string path;
    std::string id;   // gonio-model:
    std::string citation;   // citation:
    std::vector<StackShape> represents;   // represents: (comma-separated); a user's file without it: {Any}
    bool reciprocal = false;   // reciprocal: yes | no
    bool energy_conserving = false;   // energy-conserving: yes | no, then an optional reason
    // whether the header says so (a built-in's must; a user's may leave either out: it then claims nothing)
    bool states_reciprocity = false, states_energy = false;
    std::string energy_note;   // the reason, if given ("(...)" after yes/no)
    bool has_lobe_hints = false;   // the file defines model_lobes(...)
    std::vector<ModelParameter> parameters;   // parameter:, in the header's order (at most MODEL_MAX_PARAMETERS)
    // a built-in's (ModelFileKind::BuiltIn) keys
    std::string summary;   // summary:
    std::string family;   // family:
    std::string stacks;   // stacks:
    std::string mapping;   // mapping: (a production model's parameters for the stack, in words), else empty
    // artist-parameters: one per shape it represents of the three a mapping takes, else none (a model that takes the
    // stack itself); the hook that computes them is in the file (host/models/artist_parameters.h)
    std::vector<ArtistParameterList> artist_parameters;
    std::vector<ModelVariant> variants;   // variant: and variant-energy-note:, in the header's order
    PlanKind plan = PlanKind::BlackBox;   // plan:
    std::vector<TableSetDeclaration> table_sets;   // table:, in the header's order
    std::vector<std::string> table_names;   // tables:, the sets it reads by name
    int tables_line = 0;   // the tables: line
    uint32_t tables = 0;   // the sets it reads as STACK_TABLES_* bits (resolved by the registry, model_registry.cpp)
    std::vector<Refusal> refuses;   // refuses:, in the header's order (the first that holds says why)
};

// Parse the header of a model file's text; also checks that the file defines vec3 model_f(vec3, vec3).
// Throws StackError (file, line, what was expected) on any problem.
ModelFileHeader parse_model_header(const std::string& text, const std::string& path,
                                   ModelFileKind kind = ModelFileKind::User);
// The entry a built-in model file defines: "model_" + its id with every character other than a letter or digit as _.
std::string builtin_model_entry(const std::string& id);
ModelFileHeader read_model_file(const std::string& path, std::string* text_out = nullptr);

// "" where the model represents the stack, else why not: the first of its `refuses:` lines whose condition holds,
// else, where the stack is none of the shapes it represents, those shapes. id: the name in the reason (a variant's
// registry id; "": the header's).
std::string model_file_cannot_represent(const ModelFileHeader& h, const Stack& s, const std::string& id = "");

}   // namespace gonio
