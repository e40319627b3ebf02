// glsl_compiler.cpp: glslang as a library (see glsl_compiler.h).
#include "glsl_compiler.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace fs = std::filesystem;

namespace {

std::string read_text(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) return {};
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

// #include "x": the including file's folder first, then the include folders. Each result names its file, so that
// glslang's messages say which file holds an error.
class FileIncluder : public glslang::TShader::Includer {
public:
    explicit FileIncluder(std::vector<std::string> dirs) : dirs_(std::move(dirs)) {}

    IncludeResult* includeLocal(const char* header, const char* includer, size_t) override {
        std::vector<fs::path> tries;
        if (includer && *includer) tries.push_back(fs::path(includer).parent_path() / header);
        for (const auto& d : dirs_) tries.push_back(fs::path(d) / header);
        for (const auto& p : tries) {
            std::error_code ec;
            if (!fs::is_regular_file(p, ec)) continue;
            auto text = std::make_unique<std::string>(read_text(p.string()));
            const std::string name = p.lexically_normal().string();
            auto* r = new IncludeResult(name, text->data(), text->size(), text.get());
            text.release();
            return r;
        }
        return nullptr;   // glslang reports the include it could not find
    }
    IncludeResult* includeSystem(const char* header, const char* includer, size_t depth) override {
        return includeLocal(header, includer, depth);
    }
    void releaseInclude(IncludeResult* r) override {
        if (!r) return;
        delete static_cast<std::string*>(r->userData);
        delete r;
    }

private:
    std::vector<std::string> dirs_;
};

// glslang's "ERROR: file:line: 'token' : message" lines as "file:line: 'token' : message".
std::string tidy_log(const std::string& log) {
    std::istringstream in(log);
    std::string line, out;
    static const std::regex prefix(R"(^(ERROR|WARNING): )");
    while (std::getline(in, line)) {
        if (line.empty() || line.find("compilation terminated") != std::string::npos ||
            line.find("errors generated") != std::string::npos)
            continue;
        if (!std::regex_search(line, prefix)) continue;
        out += std::regex_replace(line, prefix, "") + "\n";
    }
    if (out.empty()) out = log;
    while (!out.empty() && out.back() == '\n') out.pop_back();
    return out;
}

}   // namespace

std::vector<uint32_t> compile_compute_glsl(const GlslCompileInput& in) {
    static std::once_flag init;
    std::call_once(init, [] { glslang::InitializeProcess(); });

    glslang::TShader shader(EShLangCompute);
    const char* text = in.source.c_str();
    const int length = int(in.source.size());
    const char* name = in.name.c_str();
    shader.setStringsWithLengthsAndNames(&text, &length, &name, 1);
    std::string preamble;
    for (const auto& [k, v] : in.defines) preamble += "#define " + k + " " + v + "\n";
    shader.setPreamble(preamble.c_str());
    shader.setEnvInput(glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
    FileIncluder includer(in.include_dirs);
    const EShMessages messages = EShMessages(EShMsgSpvRules | EShMsgVulkanRules);
    if (!shader.parse(GetDefaultResources(), 100, false, messages, includer))
        throw std::invalid_argument(tidy_log(shader.getInfoLog()));
    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages)) throw std::invalid_argument(tidy_log(program.getInfoLog()));
    std::vector<uint32_t> spirv;
    glslang::SpvOptions options;
    options.validate = false;
    glslang::GlslangToSpv(*program.getIntermediate(EShLangCompute), spirv, &options);
    return spirv;
}

std::vector<uint32_t> compile_compute_glsl_file(const std::string& path, const std::vector<std::string>& include_dirs,
                                                const std::vector<std::pair<std::string, std::string>>& defines) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw std::invalid_argument(path + ": no such file");
    std::ifstream f(path, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    if (!f) throw std::invalid_argument(path + ": cannot be read");
    return compile_compute_glsl({s.str(), path, include_dirs, defines});
}

}   // namespace gonio
