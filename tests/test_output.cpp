// What `simulate` writes: slices.csv, summary.json and the EXR agree with the histograms and with each other.
#include "crc32c.h"
#include "gpu_fixture.h"
#include "json.h"
#include "output.h"
#include "state.h"
#include "text_format.h"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputPart.h>
#include <ImfMultiPartInputFile.h>
#include <ImfStringAttribute.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace gonio;
using namespace gonio_test;

namespace {

class Output : public GpuTest {};

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) out.push_back(cell);
    return out;
}

TEST_F(Output, FilesAgreeWithTheHistograms) {
    Stack s = make_stack("slab", {dielectric(1.5f, 0.2f, glm::vec3(0.1f, 0.2f, 0.3f)), dielectric(1.0f, 0.3f)});
    s.source_text = "# the stack file's text\n";
    SimOptions o;
    o.theta_i_deg = {10, 60};
    o.paths = 200000;
    o.dtheta_deg = 5;
    o.dphi_deg = 10;
    o.orders = true;
    SimResult r = simulate_gpu(context(), s, o);
    auto dir = std::filesystem::temp_directory_path() / ("gonio-output-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    write_slices_csv((dir / "slices.csv").string(), r);
    write_summary_json((dir / "summary.json").string(), r);
    write_exr((dir / "slab.exr").string(), r);
    BinGrid g(r);

    // slices.csv: exact header; one row per bin, side and angle, for the total and each path class
    std::ifstream csv(dir / "slices.csv");
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "source,theta_i,side,theta_lo,theta_hi,phi_lo,phi_hi,r,g,b,se_r,se_g,se_b");
    size_t rows = 0;
    double reflected_from_csv = 0;
    while (std::getline(csv, line)) {
        auto c = split(line);
        ASSERT_EQ(c.size(), 13u) << line;
        ++rows;
        if (c[0] == "reference" && c[1] == "10" && c[2] == "R") {
            double tlo = std::stod(c[3]), thi = std::stod(c[4]);
            double omega = 0.5 * (std::pow(std::sin(thi * M_PI / 180), 2) - std::pow(std::sin(tlo * M_PI / 180), 2)) *
                           (std::stod(c[6]) - std::stod(c[5])) * M_PI / 180;
            reflected_from_csv += std::stod(c[7]) * omega;
        }
    }
    EXPECT_EQ(rows, size_t(4) * 2 * 2 * g.n_theta * g.n_phi);   // (total + 3 classes) x angles x sides x bins
    EnergyBook e = energy_book(r, 0);
    EXPECT_NEAR(reflected_from_csv, e.reflected.x, 1e-6);

    // summary.json: the energy fractions and their sum
    std::ifstream js(dir / "summary.json");
    std::string json((std::istreambuf_iterator<char>(js)), std::istreambuf_iterator<char>());
    for (const char* key : {"\"paths_per_second\"", "\"device\"", "\"reflected\"", "\"transmitted\"", "\"absorbed\"",
                            "\"truncated\"", "\"microfacet_loss\"", "\"seconds\""})
        EXPECT_NE(json.find(key), std::string::npos) << key;
    size_t pos = 0;
    int sums = 0;
    while ((pos = json.find("\"sum\": ", pos)) != std::string::npos) {
        pos += 7;
        EXPECT_NEAR(std::stod(json.substr(pos, 20)), 1.0, 1e-5);
        ++sums;
    }
    EXPECT_EQ(sums, 6);   // 2 angles x 3 channels
    const Json summary = read_json_file((dir / "summary.json").string());
    ASSERT_EQ(summary["angles"].size(), 2u);
    EXPECT_EQ(summary["angles"][1]["theta_i"], 60);
    EXPECT_EQ(summary["bins"]["n_phi"], g.n_phi);

    // EXR: one part per angle and side; channels; header; pixels equal the bin values
    Imf::MultiPartInputFile exr((dir / "slab.exr").string().c_str());
    ASSERT_EQ(exr.parts(), 4);
    const Imf::Header& h = exr.header(3);
    EXPECT_EQ(h.name(), "theta_i=60 T");
    for (const char* ch : {"R", "G", "B", "se.R", "se.G", "se.B", "order0.R", "order2.se.B"})
        EXPECT_NE(h.channels().findChannel(ch), nullptr) << ch;
    EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("gonio_stack").value(), s.source_text);
    EXPECT_EQ(h.typedAttribute<Imf::DoubleAttribute>("gonio_theta_i_deg").value(), 60.0);
    Imf::InputPart part(exr, 3);
    const int W = int(g.n_phi), H = int(g.n_theta);
    std::vector<float> R(size_t(W) * H), seB(size_t(W) * H);
    Imf::FrameBuffer fb;
    fb.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(R.data()), sizeof(float), sizeof(float) * W));
    fb.insert("se.B", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(seB.data()), sizeof(float), sizeof(float) * W));
    part.setFrameBuffer(fb);
    part.readPixels(0, H - 1);
    Slice sl = make_slice(r, 1, kTransmission);
    for (size_t b = 0; b < R.size(); ++b) {
        EXPECT_EQ(R[b], float(sl.f[b].x));
        EXPECT_EQ(seB[b], float(sl.se[b].z));
    }
    std::filesystem::remove_all(dir);
}

// json.h: a number keeps the value and the JSON type of its %.9g text; one that is not finite is null and counted.
// summary.json's "walk" says what ran, as the host that ran it recorded it: the baked stack where simulate compiled
// the stack into its shader; never for the sweeps' batch, which reads its stacks from a buffer (a sweep's
// --keep-results summary.json once said "baked_stack": true there), nor for the CPU twin; and a state file keeps it.
TEST_F(Output, TheWalkThatRanIsRecordedNotDerived) {
    const Stack s = parse_stack_file("stacks/plastic.toml");
    SimOptions o;
    o.theta_i_deg = {30.0};
    o.paths = 20000;
    const auto dir = std::filesystem::temp_directory_path() / "gonio_test_walk_record";
    std::filesystem::create_directories(dir);
    auto walk_of = [&](const SimResult& r) {
        write_summary_json((dir / "summary.json").string(), r);
        return read_json_file((dir / "summary.json").string())["walk"];
    };
    const SimResult baked = simulate_gpu(context(), s, o);
    EXPECT_TRUE(baked.walk.baked_stack);
    EXPECT_EQ(walk_of(baked)["baked_stack"], true);
    EXPECT_EQ(walk_of(baked)["lambertian_series"]["applied"], true);
    const std::vector<SimResult> batch = simulate_gpu_batch(context(), {s, s}, {1u, 2u}, o);
    EXPECT_FALSE(batch[0].walk.baked_stack);
    EXPECT_EQ(walk_of(batch[0])["baked_stack"], false);
    EXPECT_EQ(walk_of(simulate_cpu(s, o, 1))["baked_stack"], false);
    save_state((dir / "state.gonio").string(), batch[1]);
    EXPECT_EQ(walk_of(load_state((dir / "state.gonio").string()))["baked_stack"], false);
    save_state((dir / "state.gonio").string(), baked);
    EXPECT_EQ(walk_of(load_state((dir / "state.gonio").string()))["baked_stack"], true);
    std::filesystem::remove_all(dir);
}

// A state file keeps how long its run was to run (--paths, --rse, --rse-quantile, --max-seconds), which --resume
// continues with, and the incident azimuth; a file of the version before, which did not keep them, still reads (then
// the paths it has); so does one of version 7 (no checksum, no azimuth: 0), and a damaged one of version 9 is refused.
TEST_F(Output, TheStateKeepsHowLongTheRunWasToRun) {
    const Stack s = parse_stack_file("stacks/plastic.toml");
    SimOptions o;
    o.theta_i_deg = {30.0, 60.0};
    o.paths = 20000;   // the cap below --rse's first round of 2^20
    o.rse_target = 0.05;
    o.rse_quantile = 0.9;
    o.max_seconds = 100.0;
    o.phi_i_deg = 45.0;
    const SimResult r = simulate_gpu(context(), s, o);
    const auto dir = std::filesystem::temp_directory_path() / "gonio_test_state_targets";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "state.gonio").string();
    save_state(path, r);
    const SimResult back = load_state(path);
    EXPECT_EQ(back.options.paths, 20000u);
    EXPECT_EQ(back.options.rse_target, 0.05);
    EXPECT_EQ(back.options.rse_quantile, 0.9);
    EXPECT_EQ(back.options.max_seconds, 100.0);
    EXPECT_EQ(back.options.theta_i_deg, o.theta_i_deg);
    EXPECT_EQ(back.options.phi_i_deg, 45.0);
    EXPECT_EQ(back.angles[1].phi_i_deg, 45.0);
    EXPECT_TRUE(back.options.branching);
    // version 7: the same file without version 9's azimuth and version 8's checksum (its last 4 bytes), read as it
    // was
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    ASSERT_EQ(bytes.substr(0, 8), "GONIOST9");
    std::string damaged = bytes;
    damaged[damaged.size() / 2] ^= 1;   // one bit of the histograms: the checksum refuses it
    std::ofstream((dir / "damaged.gonio").string(), std::ios::binary) << damaged;
    EXPECT_THROW(load_state((dir / "damaged.gonio").string()), std::invalid_argument);
    bytes.resize(bytes.size() - 4);
    uint64_t stack_chars;
    std::memcpy(&stack_chars, bytes.data() + 8, 8);
    const size_t targets = 8 + 8 + stack_chars + 4 + 8 + 8 + 4 + 4;
    bytes.erase(targets + 8 + 3 * 8 + 3 + 3, 8);   // the azimuth, after version 7's booking estimators
    bytes[7] = '7';
    std::ofstream((dir / "v7.gonio").string(), std::ios::binary) << bytes;
    const SimResult v7 = load_state((dir / "v7.gonio").string());
    EXPECT_EQ(v7.options.rse_quantile, 0.9);
    EXPECT_EQ(v7.options.phi_i_deg, 0.0);
    EXPECT_EQ(v7.angles[1].raw, r.angles[1].raw);
    // version 5: without the four targets (after the magic, the stack's text and 28 bytes of options) and without
    // version 7's booking estimators (3 bytes after the walk's three flags)
    bytes.erase(targets + 8 + 3 * 8 + 3, 3);
    bytes.erase(targets, 8 + 3 * 8);
    bytes[7] = '5';
    std::ofstream((dir / "v5.gonio").string(), std::ios::binary) << bytes;
    const SimResult v5 = load_state((dir / "v5.gonio").string());
    EXPECT_EQ(v5.options.paths, 20000u);
    EXPECT_EQ(v5.options.rse_target, 0.0);
    EXPECT_EQ(v5.options.max_seconds, 0.0);
    EXPECT_FALSE(v5.options.branching);   // what the earlier versions ran
    ASSERT_EQ(v5.angles.size(), 2u);
    EXPECT_EQ(v5.angles[1].raw, r.angles[1].raw);
    bytes[7] = '4';
    std::ofstream((dir / "v4.gonio").string(), std::ios::binary) << bytes;
    EXPECT_THROW(load_state((dir / "v4.gonio").string()), std::invalid_argument);
    std::filesystem::remove_all(dir);
}

// The state file's checksum is CRC-32C: its published check value (the CRC of the ASCII digits 1 to 9, RFC 3720
// B.4's polynomial), and a CRC continued block by block equals the CRC of the whole
TEST(StateChecksum, IsCrc32c) {
    EXPECT_EQ(crc32c_update(0, "123456789", 9), 0xE3069283u);
    EXPECT_EQ(crc32c_update(crc32c_update(0, "1234", 4), "56789", 5), 0xE3069283u);
    EXPECT_EQ(crc32c_update(0, "", 0), 0u);
}

TEST(Json, NumbersAreTheirNineDigitText) {
    EXPECT_EQ(json_number(60.0).dump(), "60");
    EXPECT_TRUE(json_number(60.0).is_number_integer());
    EXPECT_EQ(json_number(-0.0).dump(), "0");
    EXPECT_TRUE(json_number(0.5).is_number_float());
    for (double v : {0.1, 0.38216479812345, 1.0 / 3.0, 1e20, 1234567890.0, 2.5e-300}) {
        const double nine = std::strtod(format_g9(v).c_str(), nullptr);
        EXPECT_EQ(json_number(v).get<double>(), nine) << v;
        EXPECT_EQ(Json::parse(json_number(v).dump()).get<double>(), nine) << v;   // the written text reads back to it
    }
    const uint64_t before = non_finite_json_numbers();
    EXPECT_TRUE(json_number(NAN).is_null());
    EXPECT_TRUE(json_rgb(glm::dvec3(1, INFINITY, 0))[1].is_null());
    EXPECT_EQ(non_finite_json_numbers(), before + 2);
    EXPECT_TRUE(json_rounded(NAN, 6).is_null());   // bench figures: null, not counted
    EXPECT_EQ(non_finite_json_numbers(), before + 2);
    EXPECT_EQ(json_rounded(2e7, 6).get<double>(), 2e7);
    EXPECT_TRUE(json_rounded(2e7, 6).is_number_float());   // "2e+07"
    EXPECT_EQ(json_rounded(123456, 6).dump(), "123456");
    EXPECT_EQ(json_fixed(1.23456, 4).get<double>(), 1.2346);
    non_finite_json_numbers() -= 2;
}

TEST(Json, FilesRoundTripAndRefuseWhatIsNotJson) {
    auto dir = std::filesystem::temp_directory_path() / ("gonio-json-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "a.json").string();
    const Json j = {{"name", "a \"quoted\"\tname\n\\"}, {"x", json_number(1.5)}, {"list", {1, 2}}};
    write_json_file(path, j);
    EXPECT_EQ(read_json_file(path), j);
    EXPECT_EQ(read_json_file(path).begin().key(), "name");   // members in the order written
    std::ofstream(dir / "b.json") << "{\"hash\": ";
    EXPECT_THROW(read_json_file((dir / "b.json").string()), std::invalid_argument);
    EXPECT_THROW(read_json_file((dir / "none.json").string()), std::invalid_argument);
    std::filesystem::remove_all(dir);
}

}   // namespace
