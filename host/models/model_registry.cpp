#include "model_registry.h"

#include <algorithm>
#include "model_twin.h"

#include <span>

static_assert(gonio::MODEL_CONVENTION_G2 == CONVENTION_G2 &&
              gonio::MODEL_CONVENTION_TIR_BELOW_MEDIA == CONVENTION_TIR_BELOW_MEDIA);

namespace gonio {

const std::vector<ModelInfo>& model_registry() {
    static const std::vector<ModelInfo> r = [] {
        std::vector<ModelInfo> r = {
            {"ww09",
             "Weidlich & Wilkie 2009 (SIGGRAPH Asia course), variant of Weidlich & Wilkie 2007; Bati et al. 2019 eq. 2",
             "T01/T10 from the top microfacet normal, base at unrefracted directions, TIR term t = (1 - G) + T10 G",
             "one dielectric coat over a Lambertian or conductor base",
             true,   // h0-based T01 = T10 (l.h0 = v.h0), t and the base at (l, v) are symmetric
             false,
             "the base is added to the full top reflection without the energy the top reflects; t = (1 - G) + T10 G can exceed T10"},
            {"elek10", "Elek 2010 (CESCG), as described by Bati et al. 2019 section 2.1",
             "as ww09 but the base at Snell-refracted directions, alpha1 <- max(alpha0, alpha1)",
             "one dielectric coat over a Lambertian or conductor base",
             true,   // as ww09, and Snell refraction of l and v is the same map
             false, "as ww09"},
            {"ww-corrected", "Bati, Pacanowski & Barla 2019, eq. 4",
             "geometric normal for T01, T10 and refraction, 1/eta^2 solid-angle factor, Elek's roughness rule",
             "one dielectric coat over a Lambertian or conductor base",
             true,   // T01(l) T10(v) / eta^2 with the geometric normal
             true, ""},
            {"albedo-scaling",
             "OpenPBR Surface v1.1 layering (Andersson et al. 2024), as used by Autodesk Standard Surface (Georgiev et al. 2019)",
             "f_coat + T_coat (1 - E_coat(v)) f_base(l, v): albedo scaling with view-dependent coat absorption",
             "one dielectric coat over a Lambertian or conductor base", false,   // E_coat of v only
             false, "the base is scaled by 1 - E_coat(v), the coat's albedo seen from v, not from l"},
            {"belcour18-forward", "Belcour 2018, ACM TOG 37(4) 73, sections 4-6 (atomic operators, adding)",
             "sum of GGX lobes (separable Smith G, as the official code) from energy/variance statistics of the incident "
             "direction, FGD and TIR tables (separable G); no TIR term below an absorbing medium (as the official code)",
             "any number of dielectric interfaces over a conductor base, or a slab (dielectric stack in one medium); "
             "not a Lambertian base",
             false, true,
             ""},   // lobe energies sum to at most 1 (adding equations), each GGX lobe (F = 1) reflects at most its energy
            {"belcour18-symmetric", "Belcour 2018, section 7.2 (symmetric model)",
             "as belcour18-forward with statistics from |h.l|, h = normalize(l + v): reciprocal",
             "dielectric interfaces over a conductor base (reflection only)", true, false,
             "each direction v has its own lobe energies (from |h.l|): their sum over v is not bounded by 1 (1.215 measured at 89.9 degrees on stacks/hard/ior-3-metal)"},
            {"belcour18-toplobe", "Bati, Pacanowski & Barla 2019 section 4.2, on Belcour 2018",
             "exact top-interface BRDF f_r0 for lobe 0, belcour18-forward for the lobes below", "as belcour18-forward",
             false, false,
             "the exact lobe 0 reflects the exact top albedo while the lobes below get 1 - FGD from the table; near grazing the two differ (not bounded by construction; no excess found on the hard cases with the separable tables: largest 1.000)"},
            {"tm21",
             "Randrianandrasana, Callet & Lucas 2021, ACM TOG 40(4) (two-flux transfer matrices, the authors' tm2)",
             "lobe energies from 2x2 transfer matrices of FGD/TIR albedos, roughness from Henyey-Greenstein asymmetry "
             "through the same matrices, exact top lobe; separable Smith G in the lobes below and the tables (as the authors' code)",
             "dielectric interfaces (absorbing media: gonio's extension) over a conductor base", false, false,
             "as belcour18-toplobe: the exact lobe 0 and the table's FGD differ near grazing (not bounded by construction; no excess found on the hard cases: largest 0.996)"},
        };
        for (size_t i = 0; i < r.size(); ++i) r[i].shader_model = uint32_t(i);   // registry order = MODEL_* (all.glsl)
        // gonio's alternatives to the official codes' conventions (docs/MODELS.md, "Conventions"), as variants of the
        // same code: +g2, the reference's height-correlated G2 in the GGX lobes and in the FGD/TIR tables instead of
        // the separable G1(l) G1(v); +tir (Belcour's adding loop only), the TIR term of an interface kept when an
        // absorbing medium lies under it; +g2+tir, both
        struct Variant {
            const char* suffix;
            uint32_t convention;
            const char* what;
        };
        const Variant belcour_variants[] = {
            {"+g2", CONVENTION_G2,
             "with height-correlated Smith G2 in its GGX lobes and FGD/TIR tables (gonio's alternative to the separable G of the official code)"},
            {"+tir", CONVENTION_TIR_BELOW_MEDIA,
             "with the TIR term kept for an interface over an absorbing medium (the official code loses it there)"},
            {"+g2+tir", CONVENTION_G2 | CONVENTION_TIR_BELOW_MEDIA,
             "with both: height-correlated G2 and the TIR term kept below absorbing media"},
        };
        const Variant tm_variants[] = {
            {"+g2", CONVENTION_G2,
             "with height-correlated Smith G2 in its lobes below lobe 0 and in the FGD/TIR tables (gonio's alternative to the separable G of the authors' code)"},
        };
        const size_t bases = r.size();
        for (size_t i = 0; i < bases; ++i) {
            const bool belcour = i >= MODEL_BELCOUR18_FORWARD && i <= MODEL_BELCOUR18_TOPLOBE;
            if (!belcour && i != MODEL_TM21) continue;
            for (const Variant& v :
                 belcour ? std::span<const Variant>(belcour_variants) : std::span<const Variant>(tm_variants)) {
                ModelInfo m = r[i];
                m.id += v.suffix;
                m.citation = "gonio's variant of " + r[i].id + " (" + r[i].citation + ")";
                m.summary = "as " + r[i].id + ", " + v.what;
                m.convention = v.convention;
                // the energy excess measured for this variant on the hard cases (tests/test_hard_cases.cpp)
                const struct {
                    const char* id;
                    const char* note;
                } measured[] = {
                    {"belcour18-symmetric+g2",
                     "as belcour18-symmetric (1.318 measured at 89.9 degrees on stacks/hard/ior-3-metal)"},
                    {"belcour18-symmetric+tir",
                     "as belcour18-symmetric (1.040 measured at 89.9 degrees on stacks/hard/ior-3-metal)"},
                    {"belcour18-symmetric+g2+tir",
                     "as belcour18-symmetric (1.069 measured at 89.9 degrees on stacks/hard/ior-3-metal)"},
                    {"belcour18-toplobe+g2",
                     "as belcour18-toplobe (1.003 measured at 89.9 degrees on stacks/hard/tir-trap-slab)"},
                    {"belcour18-toplobe+tir",
                     "as belcour18-toplobe (not bounded by construction; no excess found on the hard cases: largest 1.000)"},
                    {"belcour18-toplobe+g2+tir",
                     "as belcour18-toplobe (1.003 measured at 89.9 degrees on stacks/hard/tir-trap-slab)"},
                    {"tm21+g2",
                     "as tm21 (not bounded by construction; no excess found on the hard cases: largest 0.996)"},
                };
                for (const auto& e : measured)
                    if (m.id == e.id) m.energy_note = e.note;
                r.push_back(m);
            }
        }
        return r;
    }();
    return r;
}

uint32_t shader_model_of(size_t index) { return model_registry().at(index).shader_model; }
bool is_belcour(size_t index) {
    const uint32_t m = shader_model_of(index);
    return m >= MODEL_BELCOUR18_FORWARD && m <= MODEL_BELCOUR18_TOPLOBE;
}
bool uses_tables(size_t index) { return is_belcour(index) || shader_model_of(index) == MODEL_TM21; }

std::string model_not_selected(size_t index, const ModelOptions& o) {
    return model_id_not_selected(model_registry().at(index).id, o);
}

std::string model_id_not_selected(const std::string& id, const ModelOptions& o) {
    if (o.selected.empty()) return "";
    if (std::find(o.selected.begin(), o.selected.end(), id) != o.selected.end()) return "";
    std::string list;
    for (const std::string& s : o.selected) list += (list.empty() ? "" : ",") + s;
    return id + " not selected (--models " + list + ")";
}

}   // namespace gonio
