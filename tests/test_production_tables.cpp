// The production models' energy tables, recomputed by gonio's quadrature at their authors' nodes
// (host/models/stack_tables.cpp), against the published tables: adobe/openpbr-bsdf's opaque-dielectric and
// ideal-metal energy complements and their averages (impl/data/*.h @a29da969, unorm16, "generated using a custom
// Monte Carlo integration tool"), Cycles' ggx_E, ggx_Eavg and ggx_gen_schlick_ior_s (src/scene/shader.tables @ v5.0.0,
// Monte Carlo over visible normals, 2^23, 2^26 and 2^20 samples a cell). The rows below are copied from those files.
// Each recomputed entry is held to the published one within 5e-4: the published tables' own resolution (the unorm16
// step 1.5e-5, their generators' Monte Carlo noise) and gonio's quadrature's error (1.4e-4, models/fgd_quadrature.glsl);
// the largest and median departures are printed (docs/MODELS.md, "The production models' tables"). Then the per-stack
// sets the models read (stack_tables): the published tables interpolated as the authors' lookups interpolate them, at
// an IOR and roughnesses between the nodes.
#include "model_twin.h"
#include "stack_tables.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace gonio;

namespace {

struct AdobeRow {
    int a, b;
    int v[32];
};
struct CyclesRow {
    int a, b;
    float v[32];
};

// adobe/openpbr-bsdf @a29da969 impl/data/*.h (Apache-2.0): unorm16 values (/ 65535); OD rows [ior i][roughness j]
// over the 32 cosine nodes k, ODA rows [i] over j, IM rows [j] over k, IMA over j
const AdobeRow kAdobeOd[] = {
    {21, 0, {380,   11071, 20065, 27417, 33461, 38451, 42587, 46025, 48890, 51282, 53282,
             54955, 56357, 57530, 58511, 59332, 60017, 60588, 61062, 61454, 61778, 62043,
             62258, 62432, 62570, 62678, 62761, 62822, 62865, 62893, 62909, 62914}},
    {21, 15, {52742, 53210, 53808, 54466, 55146, 55820, 56475, 57102, 57696, 58256, 58781,
              59270, 59723, 60140, 60522, 60871, 61186, 61470, 61724, 61950, 62148, 62322,
              62473, 62603, 62714, 62807, 62884, 62947, 62996, 63034, 63062, 63081}},
    {21, 31, {62392, 62587, 62771, 62938, 63091, 63230, 63359, 63476, 63584, 63683, 63774,
              63858, 63936, 64007, 64074, 64135, 64192, 64245, 64294, 64340, 64382, 64422,
              64459, 64493, 64526, 64556, 64584, 64611, 64636, 64660, 64682, 64703}},
    {22, 10, {41882, 42524, 43697, 45022, 46394, 47794, 49200, 50586, 51920, 53178, 54343,
              55406, 56363, 57217, 57972, 58634, 59212, 59712, 60143, 60513, 60826, 61092,
              61314, 61499, 61650, 61772, 61870, 61946, 62002, 62042, 62068, 62082}},
    {31, 31, {57022, 57353, 57670, 57963, 58237, 58491, 58729, 58952, 59160, 59355, 59539,
              59712, 59875, 60029, 60175, 60313, 60444, 60568, 60686, 60799, 60906, 61008,
              61105, 61198, 61287, 61373, 61454, 61533, 61608, 61680, 61750, 61816}},
    {16, 3, {61396, 65414, 65525, 65533, 65534, 65535, 65535, 65535, 65535, 65535, 65535,
             65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535,
             65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535}},
    {16, 9, {65488, 65527, 65533, 65534, 65535, 65535, 65535, 65535, 65535, 65535, 65535,
             65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535,
             65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535}},
    {26, 20, {54230, 54618, 55021, 55420, 55808, 56181, 56533, 56865, 57175, 57462, 57728,
              57973, 58198, 58403, 58590, 58761, 58915, 59054, 59179, 59291, 59391, 59480,
              59557, 59625, 59683, 59732, 59773, 59807, 59833, 59853, 59866, 59873}},
    {8, 12, {8490,  9445,  10303, 10840, 11016, 10884, 10536, 10056, 9513,  8960, 8431,
             7944,  7520,  7157,  6878,  6680,  6579,  6593,  6758,  7125,  7796, 8934,
             10864, 14163, 19744, 28241, 38385, 47174, 53141, 56752, 58861, 60092}},
    {21, 11, {45242, 45823, 46833, 48001, 49215, 50436, 51646, 52828, 53966, 55042, 56045,
              56968, 57805, 58558, 59228, 59820, 60338, 60789, 61179, 61513, 61799, 62040,
              62243, 62412, 62550, 62663, 62753, 62823, 62876, 62914, 62939, 62953}},
    {21, 12, {47515, 48062, 48933, 49940, 50987, 52032, 53057, 54052, 55007, 55912, 56761,
              57549, 58271, 58926, 59517, 60043, 60510, 60920, 61278, 61588, 61855, 62083,
              62276, 62437, 62571, 62681, 62770, 62839, 62892, 62931, 62958, 62974}},
    {22, 11, {44438, 45029, 46035, 47187, 48375, 49566, 50744, 51898, 53010, 54068, 55058,
              55972, 56807, 57561, 58236, 58835, 59363, 59825, 60227, 60574, 60872, 61125,
              61339, 61518, 61665, 61786, 61883, 61958, 62016, 62057, 62084, 62100}},
    {22, 12, {46684, 47239, 48109, 49106, 50137, 51162, 52165, 53139, 54075, 54965, 55803,
              56583, 57302, 57958, 58552, 59084, 59558, 59977, 60345, 60666, 60943, 61181,
              61383, 61554, 61697, 61814, 61908, 61983, 62041, 62082, 62111, 62129}},
};
const AdobeRow kAdobeOda[] = {
    {21, 0, {59520, 59521, 59528, 59552, 59600, 59678, 59786, 59924, 60089, 60275, 60478,
             60694, 60916, 61142, 61369, 61594, 61815, 62031, 62241, 62445, 62642, 62832,
             63015, 63190, 63359, 63519, 63672, 63817, 63955, 64084, 64205, 64319}},
    {22, 0, {58572, 58573, 58580, 58604, 58652, 58731, 58841, 58982, 59151, 59344, 59557,
             59783, 60020, 60262, 60508, 60755, 61000, 61242, 61480, 61714, 61942, 62165,
             62381, 62591, 62793, 62988, 63175, 63353, 63523, 63683, 63835, 63977}},
    {16, 0, {65533, 65533, 65534, 65534, 65535, 65535, 65535, 65535, 65535, 65535, 65535,
             65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535,
             65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535}},
    {31, 0, {50995, 50996, 51003, 51025, 51071, 51147, 51254, 51395, 51570, 51778, 52017,
             52286, 52583, 52906, 53254, 53626, 54019, 54433, 54866, 55314, 55775, 56247,
             56726, 57210, 57694, 58175, 58649, 59114, 59566, 60003, 60421, 60821}},
};
const AdobeRow kAdobeIm[] = {
    {10, 0, {4725, 6595, 7926, 8385, 8175, 7584, 6828, 6051, 5322, 4671, 4104, 3619, 3206, 2856, 2560, 2308,
             2094, 1910, 1753, 1617, 1499, 1397, 1306, 1228, 1158, 1095, 1042, 994,  945,  905,  873,  848}},
    {15, 0, {6405, 7440, 8427, 9271, 9933, 10403, 10690, 10816, 10804, 10684, 10482, 10218, 9911, 9576, 9228, 8874,
             8521, 8175, 7840, 7518, 7211, 6918,  6641,  6381,  6136,  5906,  5691,  5489,  5301, 5125, 4961, 4804}},
    {20, 0, {10138, 11042, 11912, 12717, 13452, 14115, 14704, 15220, 15664, 16039, 16349,
             16598, 16791, 16932, 17026, 17077, 17091, 17072, 17023, 16949, 16852, 16736,
             16603, 16457, 16300, 16133, 15959, 15778, 15593, 15405, 15215, 15023}},
    {31, 0, {25355, 26572, 27754, 28865, 29912, 30902, 31838, 32725, 33566, 34365, 35125,
             35849, 36540, 37199, 37828, 38431, 39007, 39560, 40090, 40599, 41088, 41558,
             42011, 42446, 42866, 43271, 43661, 44039, 44403, 44755, 45096, 45425}},
};
const int kAdobeIma[32] = {0,     0,     7,     30,    85,    188,   353,   599,   943,   1404,  1993,
                           2721,  3599,  4630,  5823,  7177,  8687,  10352, 12162, 14101, 16153, 18304,
                           20540, 22835, 25168, 27516, 29859, 32175, 34446, 36654, 38786, 40831};
// Blender Cycles v5.0.0 @2eba4102 src/scene/shader.tables (Apache-2.0): ggx_E rows j (mu node), over the
// roughness nodes i; ggx_Eavg over i; ggx_gen_schlick_ior_s rows (z node k, mu node j) over i
const CyclesRow kCyclesE[] = {
    {0, 0, {1.000000, 0.980405, 0.994967, 0.997749, 0.998725, 0.999173, 0.999411, 0.999550,
            0.999634, 0.999686, 0.999716, 0.999732, 0.999738, 0.999735, 0.999726, 0.999712,
            0.999693, 0.999671, 0.999645, 0.999615, 0.999583, 0.999548, 0.999511, 0.999471,
            0.999429, 0.999385, 0.999338, 0.999290, 0.999240, 0.999188, 0.999134, 0.999079}},
    {1, 0, {1.000000, 0.999451, 0.990086, 0.954714, 0.911203, 0.891678, 0.893893, 0.905010,
            0.917411, 0.928221, 0.936755, 0.943104, 0.947567, 0.950455, 0.952036, 0.952526,
            0.952096, 0.950879, 0.948983, 0.946495, 0.943484, 0.940010, 0.936122, 0.931864,
            0.927272, 0.922380, 0.917217, 0.911810, 0.906184, 0.900361, 0.894361, 0.888202}},
    {4, 0, {1.000000, 0.999967, 0.999442, 0.996987, 0.989925, 0.975437, 0.953654, 0.929078,
            0.907414, 0.891877, 0.882635, 0.878166, 0.876572, 0.876236, 0.876004, 0.875144,
            0.873238, 0.870080, 0.865601, 0.859812, 0.852774, 0.844571, 0.835302, 0.825069,
            0.813976, 0.802123, 0.789609, 0.776523, 0.762954, 0.748982, 0.734682, 0.720122}},
    {8, 0, {1.000000, 0.999991, 0.999858, 0.999255, 0.997533, 0.993686, 0.986490, 0.974988,
            0.959173, 0.940264, 0.920251, 0.901030, 0.883794, 0.868900, 0.856078, 0.844728,
            0.834154, 0.823720, 0.812914, 0.801368, 0.788846, 0.775227, 0.760476, 0.744623,
            0.727744, 0.709946, 0.691355, 0.672105, 0.652332, 0.632172, 0.611753, 0.591195}},
    {16, 0, {1.000000, 0.999998, 0.999959, 0.999786, 0.999307, 0.998254, 0.996252, 0.992808,
             0.987348, 0.979302, 0.968235, 0.953973, 0.936669, 0.916763, 0.894859, 0.871576,
             0.847421, 0.822737, 0.797698, 0.772347, 0.746651, 0.720547, 0.693982, 0.666934,
             0.639428, 0.611535, 0.583366, 0.555065, 0.526792, 0.498719, 0.471015, 0.443841}},
    {31, 0, {1.000000, 0.999999, 0.999983, 0.999911, 0.999716, 0.999296, 0.998513, 0.997184,
             0.995072, 0.991884, 0.987261, 0.980785, 0.971982, 0.960355, 0.945407, 0.926694,
             0.903873, 0.876756, 0.845349, 0.809871, 0.770757, 0.728630, 0.684249, 0.638454,
             0.592102, 0.546006, 0.500893, 0.457373, 0.415925, 0.376893, 0.340499, 0.306853}},
};
const float kCyclesEavg[32] = {1.000000, 0.999992, 0.999897, 0.999548, 0.998729, 0.997199, 0.994703, 0.990986,
                               0.985805, 0.978930, 0.970160, 0.959321, 0.946279, 0.930937, 0.913247, 0.893209,
                               0.870874, 0.846345, 0.819774, 0.791360, 0.761345, 0.730001, 0.697631, 0.664547,
                               0.631068, 0.597509, 0.564165, 0.531311, 0.499191, 0.468013, 0.437950, 0.409137};
const CyclesRow kCyclesS[] = {
    {7,
     0,
     {0.999398, 0.902088, 0.744723, 0.592705, 0.463498, 0.360123, 0.280132, 0.219410, 0.173793, 0.139681, 0.114186,
      0.095092, 0.080726, 0.069858, 0.061580, 0.055228}},
    {7,
     2,
     {0.460273, 0.459081, 0.446430, 0.409329, 0.350883, 0.287211, 0.229441, 0.181408, 0.143357, 0.113993, 0.091606,
      0.074583, 0.061584, 0.051575, 0.043779, 0.037621}},
    {7,
     8,
     {0.042986, 0.043007, 0.043167, 0.043465, 0.043604, 0.043065, 0.041397, 0.038509, 0.034703, 0.030469, 0.026246,
      0.022308, 0.018803, 0.015756, 0.013159, 0.010966}},
    {7,
     15,
     {0.000000, 0.000000, 0.000005, 0.000023, 0.000069, 0.000159, 0.000302, 0.000498, 0.000732, 0.000980, 0.001210,
      0.001395, 0.001514, 0.001564, 0.001549, 0.001484}},
    {6,
     0,
     {0.999374, 0.898694, 0.736620, 0.581057, 0.449900, 0.345942, 0.266319, 0.206511, 0.162051, 0.129141, 0.104780,
      0.086696, 0.073199, 0.063064, 0.055394, 0.049543}},
    {6,
     2,
     {0.441042, 0.439861, 0.427339, 0.390653, 0.332989, 0.270476, 0.214213, 0.167896, 0.131578, 0.103825, 0.082854,
      0.067036, 0.055041, 0.045862, 0.038751, 0.033160}},
    {6,
     8,
     {0.034928, 0.034949, 0.035121, 0.035476, 0.035767, 0.035527, 0.034327, 0.032055, 0.028951, 0.025439, 0.021907,
      0.018599, 0.015650, 0.013086, 0.010903, 0.009064}},
    {6,
     15,
     {0.000000, 0.000000, 0.000003, 0.000017, 0.000051, 0.000117, 0.000223, 0.000368, 0.000543, 0.000728, 0.000900,
      0.001039, 0.001129, 0.001168, 0.001158, 0.001110}},
    {3,
     4,
     {0.068675, 0.068694, 0.068589, 0.067288, 0.063203, 0.055930, 0.046884, 0.037891, 0.030044, 0.023645, 0.018615,
      0.014729, 0.011738, 0.009435, 0.007648, 0.006251}},
    {10,
     1,
     {0.602849, 0.598587, 0.558416, 0.471435, 0.374735, 0.289881, 0.222188, 0.170866, 0.132817, 0.104797, 0.084137,
      0.068785, 0.057270, 0.048520, 0.041788, 0.036542}},
    {12,
     6,
     {0.000000, 0.000000, 0.000001, 0.000004, 0.000012, 0.000022, 0.000030, 0.000034, 0.000031, 0.000026, 0.000021,
      0.000015, 0.000011, 0.000008, 0.000006, 0.000004}},
};

constexpr double kTolerance = 5e-4;

// The departures of recomputed entries from the published ones, the worst named
struct Departures {
    std::vector<double> d;
    std::vector<std::string> where;
    void add(double got, double want, const std::string& at) {
        d.push_back(std::fabs(got - want));
        where.push_back(at + ": " + std::to_string(got) + " against " + std::to_string(want));
    }
    double largest() const { return *std::max_element(d.begin(), d.end()); }
    double median() const {
        std::vector<double> s = d;
        std::nth_element(s.begin(), s.begin() + s.size() / 2, s.end());
        return s[s.size() / 2];
    }
    void report(const char* name) const {
        std::printf("%-32s %4zu entries: largest departure %.2e (%s), median %.2e\n", name, d.size(), largest(),
                    where[std::max_element(d.begin(), d.end()) - d.begin()].c_str(), median());
        EXPECT_LT(largest(), kTolerance) << name;
    }
};

std::string at(const char* t, int a, int b, int c) {
    return std::string(t) + "[" + std::to_string(a) + "][" + std::to_string(b) + "][" + std::to_string(c) + "]";
}

const AdobeRow& adobe_od_row(int i, int j) {
    for (const AdobeRow& r : kAdobeOd)
        if (r.a == i && r.b == j) return r;
    throw std::logic_error("no published row");
}
const CyclesRow& cycles_row(const CyclesRow* rows, size_t n, int a, int b) {
    for (size_t i = 0; i < n; ++i)
        if (rows[i].a == a && rows[i].b == b) return rows[i];
    throw std::logic_error("no published row");
}

Stack coat_over(float eta, float alpha_coat, Layer base) {
    Stack s;
    s.name = "coat";
    Layer coat;
    coat.kind = InterfaceKind::Dielectric;
    coat.ior = glm::vec3(eta);
    coat.roughness = alpha_coat;
    s.layers = {coat, base};
    return s;
}
Layer lambertian_base() {
    Layer L;
    L.kind = InterfaceKind::Lambertian;
    L.albedo = glm::vec3(0.5f);
    return L;
}

TEST(ProductionTables, AdobeEnergyComplementsAreThePublishedOnes) {
    Departures od, oda, im, ima;
    for (const AdobeRow& r : kAdobeOd)
        for (int k = 0; k < 32; ++k)
            od.add(adobe_opaque_dielectric_complement(r.a, r.b, k), r.v[k] / 65535.0, at("OD", r.a, r.b, k));
    for (const AdobeRow& r : kAdobeOda)
        for (int j = 0; j < 32; ++j)
            oda.add(adobe_opaque_dielectric_average_complement(r.a, j), r.v[j] / 65535.0, at("ODA", r.a, j, 0));
    for (const AdobeRow& r : kAdobeIm)
        for (int k = 0; k < 32; ++k)
            im.add(adobe_ideal_metal_complement(r.a, k), r.v[k] / 65535.0, at("IM", r.a, k, 0));
    for (int j = 0; j < 32; ++j)
        ima.add(adobe_ideal_metal_average_complement(j), kAdobeIma[j] / 65535.0, at("IMA", j, 0, 0));
    od.report("adobe opaque dielectric (OD)");
    oda.report("adobe its average (ODA)");
    im.report("adobe ideal metal (IM)");
    ima.report("adobe its average (IMA)");
}

TEST(ProductionTables, CyclesGgxTablesAreThePublishedOnes) {
    Departures e, eavg, s;
    for (const CyclesRow& r : kCyclesE)
        for (int i = 0; i < 32; ++i) e.add(cycles_ggx_e(i, r.a), r.v[i], at("ggx_E", r.a, i, 0));
    for (int i = 0; i < 32; ++i) eavg.add(cycles_ggx_e_avg(i), kCyclesEavg[i], at("ggx_Eavg", i, 0, 0));
    for (const CyclesRow& r : kCyclesS)
        for (int i = 0; i < 16; ++i) s.add(cycles_schlick_ior_s(i, r.b, r.a), r.v[i], at("s", r.a, r.b, i));
    e.report("cycles ggx_E");
    eavg.report("cycles ggx_Eavg");
    s.report("cycles ggx_gen_schlick_ior_s");
}

// The per-stack sets at IOR 1.55 (Adobe's index 21.5, Cycles' z 0.4588: between its nodes 6 and 7) and coat roughness
// r_c = sqrt(alpha) between the nodes: the published tables interpolated as the authors' lookups are
TEST(ProductionTables, PerStackSetsInterpolateAsTheAuthorsLookupsDo) {
    const float eta = 1.55f;
    // Adobe: r_c index 11.6 (between the rows 11 and 12), trilinear
    const float rc_a = 11.6f / 31.0f;
    const std::vector<float> ta =
        stack_tables(pack_stack(coat_over(eta, rc_a * rc_a, lambertian_base())), STACK_TABLES_ADOBE_ENERGY);
    const float ti = adobe_ior_index(eta) - 21.0f, tj = 0.6f;
    Departures adobe;
    for (int k = 0; k < 32; ++k) {
        auto v = [&](int i, int j) { return adobe_od_row(i, j).v[k] / 65535.0; };
        const double od =
            (1 - tj) * ((1 - ti) * v(21, 11) + ti * v(22, 11)) + tj * ((1 - ti) * v(21, 12) + ti * v(22, 12));
        adobe.add(ta[STACK_TABLE_ADOBE_COAT + k], 1.0 - od, at("E_c", k, 0, 0));
    }
    adobe.report("adobe E_c at IOR 1.55, r_c 11.6/31");
    // beyond IOR 2.5 the opaque-dielectric table's last IOR slice, extrapolated towards F0 = 1: at 2.8, r_c = 1
    const std::vector<float> te =
        stack_tables(pack_stack(coat_over(2.8f, 1.0f, lambertian_base())), STACK_TABLES_ADOBE_ENERGY);
    const double f0_max = std::pow(1.5 / 3.5, 2), f0 = std::pow(1.8 / 3.8, 2);
    Departures beyond;
    for (int k = 0; k < 32; ++k)
        beyond.add(te[STACK_TABLE_ADOBE_COAT + k],
                   1.0 - (1 - (f0 - f0_max) / (1 - f0_max)) * adobe_od_row(31, 31).v[k] / 65535.0, at("E_c", k, 0, 0));
    beyond.report("adobe E_c at IOR 2.8, r_c 1");
    // Cycles: r_c = 0.3 (ggx_E's column 9.3, ggx_gen_schlick_ior_s' column 4.5), at the published rows
    const float rc = 0.3f;
    const std::vector<float> tc =
        stack_tables(pack_stack(coat_over(eta, rc * rc, lambertian_base())), STACK_TABLES_CYCLES_ENERGY);
    Departures cycles;
    for (const CyclesRow& r : kCyclesE) {
        const double x = rc * 31.0, t = x - 9.0;
        cycles.add(tc[STACK_TABLE_CYCLES_COAT_E + r.a], (1 - t) * r.v[9] + t * r.v[10], at("ggx_E", r.a, 0, 0));
    }
    {
        const double x = rc * 31.0, t = x - 9.0;
        cycles.add(tc[STACK_TABLE_CYCLES_COAT_E + CYCLES_E_NODES], (1 - t) * kCyclesEavg[9] + t * kCyclesEavg[10],
                   "ggx_Eavg");
    }
    const double tz = std::sqrt((eta - 1.0) / (eta + 1.0)) * 15.0 - 6.0, tr = rc * 15.0 - 4.0;
    for (int j : {0, 2, 8, 15}) {
        auto v = [&](int k, int i) { return cycles_row(kCyclesS, std::size(kCyclesS), k, j).v[i]; };
        const double want = (1 - tz) * ((1 - tr) * v(6, 4) + tr * v(6, 5)) + tz * ((1 - tr) * v(7, 4) + tr * v(7, 5));
        cycles.add(tc[STACK_TABLE_CYCLES_COAT_S + j], want, at("s", j, 0, 0));
    }
    cycles.report("cycles coat sets at IOR 1.55, r_c 0.3");
}

}   // namespace
