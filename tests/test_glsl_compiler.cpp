// GLSL compiled at run time (host/gpu/glsl_compiler.h): the build's kernels compile to the very SPIR-V that
// glslangValidator embedded in the binary; errors are refused with FILE:LINE, in the file that holds them.
#include "glsl_compiler.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fold_spv.h"
#include "simulate_s1m1_spv.h"

namespace {

namespace fs = std::filesystem;
const std::string kShaders = std::string(GONIO_SOURCE_DIR) + "/shaders";

// the generator word (SPIR-V header word 2) names the tool; everything else must agree
std::vector<uint32_t> without_generator(std::vector<uint32_t> w) {
    if (w.size() > 2) w[2] = 0;
    return w;
}

template <size_t N>
std::vector<uint32_t> words(const uint32_t (&a)[N]) {
    return std::vector<uint32_t>(a, a + N);
}

TEST(GlslCompiler, BuiltInKernelsCompileToTheBuildsSpirv) {
    const std::vector<std::string> inc = {kShaders + "/lib"};
    auto sim = gonio::compile_compute_glsl_file(kShaders + "/simulate.comp", inc);
    auto fold = gonio::compile_compute_glsl_file(kShaders + "/fold.comp", inc);
    ASSERT_GT(sim.size(), 5u);
    EXPECT_EQ(sim[0], 0x07230203u);   // the SPIR-V magic number
    EXPECT_EQ(without_generator(sim), without_generator(words(simulate_s1m1_spv)));
    EXPECT_EQ(without_generator(fold), without_generator(words(fold_spv)));
}

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() /
               ("gonio-glsl-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    std::string write(const std::string& name, const std::string& text) const {
        std::ofstream(path / name) << text;
        return (path / name).string();
    }
};

const char* kMain = R"(#version 460
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Out { float v[]; };
#include "user_model.glsl"
void main() { v[gl_GlobalInvocationID.x] = model_value(float(gl_GlobalInvocationID.x)) * SCALE; }
)";

TEST(GlslCompiler, IncludesAndDefinesResolve) {
    TempDir t;
    const std::string main = t.write("main.comp", kMain);
    t.write("user_model.glsl", "// a model\nfloat model_value(float x) {\n    return 2.0 * x;\n}\n");
    auto spv = gonio::compile_compute_glsl_file(main, {kShaders + "/lib"}, {{"SCALE", "0.5"}});
    EXPECT_EQ(spv.at(0), 0x07230203u);
}

TEST(GlslCompiler, AnErrorNamesItsFileAndLine) {
    TempDir t;
    const std::string main = t.write("main.comp", kMain);
    const std::string model =
        t.write("user_model.glsl", "// a model\nfloat model_value(float x) {\n    return 2.0 * y;\n}\n");
    try {
        gonio::compile_compute_glsl_file(main, {}, {{"SCALE", "1.0"}});
        FAIL() << "an undeclared identifier was accepted";
    } catch (const std::invalid_argument& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find(fs::path(model).lexically_normal().string() + ":3:"), std::string::npos) << m;
        EXPECT_NE(m.find("'y'"), std::string::npos) << m;
        EXPECT_EQ(m.find("ERROR:"), std::string::npos) << m;
        std::printf("refused: %s\n", m.c_str());
    }
}

TEST(GlslCompiler, AMissingIncludeOrFileIsRefused) {
    TempDir t;
    const std::string main = t.write("main.comp", kMain);
    try {
        gonio::compile_compute_glsl_file(main, {}, {{"SCALE", "1.0"}});
        FAIL() << "a missing include was accepted";
    } catch (const std::invalid_argument& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("main.comp:5:"), std::string::npos) << m;
        EXPECT_NE(m.find("user_model.glsl"), std::string::npos) << m;
    }
    EXPECT_THROW(gonio::compile_compute_glsl_file((t.path / "nothing.comp").string(), {}), std::invalid_argument);
}

}   // namespace
