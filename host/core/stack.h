// The layer stack: what a stack file (stacks/*.toml) describes, after parsing and validation.
// Layers are listed top to bottom; each is one interface and the medium right under it.
#pragma once
#include "spectral_table.h"

#include <glm/glm.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace gonio {

constexpr int kMaxLayers = 16;   // most layers a stack may have (stack_params.glsl MAX_LAYERS)
// The channels of every spectral quantity: RGB (stack_params.glsl CHANNELS; both tied in stack_vocabulary.cpp)
constexpr int kChannels = 3;

// The valid range of every stack parameter (stacks/README.md): wide enough for every real material, narrow enough
// that the walk and the models stay finite and energy-conserving. Outside it a stack file is refused (file:line).
struct ParameterRange {
    float lo, hi;
};
inline constexpr ParameterRange kDielectricIorRange{
    1.0f, 10.0f};   // absolute IOR: vacuum 1 to silicon 5.6 (400 nm), with room
inline constexpr ParameterRange kExteriorIorRange{1.0f, 10.0f};   // the medium above the stack (air 1, water 1.33)
inline constexpr ParameterRange kConductorIorRange{0.01f, 20.0f};   // real part n of a metal's IOR (silver ~0.05)
inline constexpr ParameterRange kConductorKRange{0.0f, 100.0f};   // extinction k (aluminium ~9 at 800 nm)
inline constexpr ParameterRange kRoughnessRange{1e-4f, 1.0f};   // microfacet alpha; or exactly 0 (smooth)
inline constexpr ParameterRange kOpticalDepthRange{0.0f, 1e4f};   // tau = sigma_t d (1e4: nothing comes through)
// Henyey-Greenstein asymmetry g: the open interval (-1, 1) (at +-1 the phase function is a delta: no medium)
inline constexpr ParameterRange kPhaseGRange{-1.0f, 1.0f};
inline constexpr ParameterRange kAlbedoRange{0.0f, 1.0f};
// A microflake medium's alpha (sigma = alpha^2 its fibres' cross-section): the sheen authors' table spans [0.01, 1]
// (tizian/ltc-sheen); below it S holds alpha^8 in its determinant, and the flakes are all but a delta
inline constexpr ParameterRange kFibreRoughnessRange{0.01f, 1.0f};

enum class InterfaceKind { Dielectric = 0, Conductor = 1, Lambertian = 2 };
// A rough interface's microsurface (keys `distribution`, `shadowing` and `microfacets`; shaders/lib/microsurface.glsl,
// shaders/lib/microsurface_walk.glsl)
enum class MicrofacetDistribution { Ggx = 0, Beckmann = 1 };
enum class Shadowing { HeightCorrelated = 0, Separable = 1 };
enum class Microfacets { Single = 0, Multiple = 1 };   // light scatters once on the microsurface, or walks on it
// A medium's phase function (key `phase`; shaders/lib/medium.glsl MEDIUM_PHASE_*): Henyey-Greenstein, or specular SGGX
// microflakes, fibres along the normal or flakes facing it
enum class MediumPhase { Hg = 0, SggxFibre = 1, SggxFlake = 2 };

const char* to_string(InterfaceKind k);

// The wavelength an RGB run reads a dispersive IOR at (one value in every channel: refraction sends the channels one
// way): the helium d line, 587.56 nm, at which a glass's n_d is given.
constexpr double kDispersionRgbNm = 587.56;

// A layer key given as a spectrum (`optical_depth = [[400, 0.8], [550, 0.2], [700, 0.1]]`: pairs of nm and value,
// linear between them): the table, and the RGB its run takes (the values at the sRGB primaries' dominant
// wavelengths, as a measured material's; a dispersive IOR's at kDispersionRgbNm; docs/SPECTRAL.md). Where the key's
// RGB value is no longer that (a sweep or a fit changed it), the spectrum no longer describes the layer
// (Layer::intact_spectrum).
struct KeySpectrum {
    std::string key;   // the layer key's name
    SpectralTable table;   // one column, "value"
    glm::vec3 rgb{0.0f};
    std::string given;   // a named glass's or a dispersion formula's TOML ("N-BK7"); "" for pairs
};

struct Layer {
    InterfaceKind kind = InterfaceKind::Dielectric;
    float roughness = 0.0f;   // the microfacets' alpha (dielectric, conductor); 0 = perfectly smooth (delta)
    MicrofacetDistribution distribution = MicrofacetDistribution::Ggx;   // of a rough interface's microfacets
    Shadowing shadowing = Shadowing::HeightCorrelated;   // Smith's masking-shadowing of a rough interface
    Microfacets microfacets = Microfacets::Single;   // single or multiple scattering on a rough interface
    glm::vec3 ior{1.0f};   // absolute IOR of the medium under a dielectric interface,
        // or the real part of a conductor's complex IOR
    glm::vec3 k{0.0f};   // conductor extinction coefficient (imaginary part of the IOR)
    glm::vec3 optical_depth{0.0f};   // extinction optical depth tau = sigma_t * d of the medium under this interface
    glm::vec3 scattering_albedo{0.0f};   // its single-scattering albedo sigma_s / sigma_t (0: it only absorbs)
    float phase_g = 0.0f;   // its Henyey-Greenstein asymmetry (g > 0 forward), in (-1, 1)
    MediumPhase phase = MediumPhase::Hg;   // its phase function
    float fibre_roughness = 0.0f;   // a microflake medium's alpha (0 where the phase is Henyey-Greenstein's)
    glm::vec3 albedo{0.0f};   // lambertian base albedo
    std::string material;   // a conductor's measured material ("Au": host/spectral/measured_materials.h), ior and k
        // its RGB reduction; "" where the stack gives ior and k
    std::vector<KeySpectrum> spectra;   // the keys given as spectra
    int line = 0;   // line of the [[layer]] header in the file (for messages)

    // Whether the layer names a measured material whose n and k are still its RGB reduction (a sweep or a fit may
    // have changed them: the material then no longer describes the layer).
    bool material_intact() const;
    // The spectrum of key `name` where the key still has the spectrum's RGB value, else nullptr.
    const KeySpectrum* intact_spectrum(const std::string& name, glm::vec3 value) const;
};

struct Stack {
    std::string name;
    std::string description;
    std::string source_path;   // file it was read from ("" if built in code)
    std::string source_text;   // the file's text, recorded in output headers
    float exterior_ior = 1.0f;
    std::vector<Layer> layers;   // top to bottom

    bool transmissive() const;   // last layer is a dielectric: light can leave through the bottom
    // Whether a path in the medium under layer i takes free flights: optical depth and scattering albedo above 0 in
    // some channel, or a microflake medium with optical depth above 0 (stack_params.glsl layer_medium_scatters).
    bool medium_scatters(size_t i) const;
    const Layer& base() const { return layers.back(); }
    // IOR of the medium above interface i (exterior for i == 0), per channel.
    glm::vec3 ior_above(size_t i) const;
};

// Error in a stack file: carries file, line and a message saying what was expected.
struct StackError : std::runtime_error {
    std::string file;
    int line;
    StackError(std::string file_, int line_, const std::string& what_)
        : std::runtime_error(file_ + ":" + std::to_string(line_) + ": " + what_), file(std::move(file_)), line(line_) {}
};

// Parse and validate. Throws StackError (file, line, what was expected) on any problem.
Stack parse_stack_file(const std::string& path);
Stack parse_stack_string(const std::string& text, const std::string& path_for_messages);

// Validate a stack built in code (also called by the parsers). Throws StackError.
void validate_stack(const Stack& s);

// Whether a layer key (roughness, ior, k, optical_depth, scattering_albedo, phase_g, albedo) is a parameter of an interface kind (the keys a
// stack file accepts in such a [[layer]]).
bool layer_key_applies(InterfaceKind kind, const std::string& key);

// Human-readable multi-line description, used by `gonio check`.
std::string describe_stack(const Stack& s);

// Serialise back to TOML (round-trips through parse_stack_string).
std::string stack_to_toml(const Stack& s);

}   // namespace gonio
