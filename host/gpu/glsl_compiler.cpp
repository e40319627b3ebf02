// glsl_compiler.cpp: glslang as a library (see glsl_compiler.h).
#include "glsl_compiler.h"
#include "shader_sources.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <cstring>
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

// #include "x": beside the including file (on disk, or among the embedded sources for an embedded one), then in
// the include folders, then the virtual files, then gonio's embedded shaders/lib. Each result names its file, so
// that glslang's messages say which file holds an error.
class FileIncluder : public glslang::TShader::Includer {
public:
    FileIncluder(const GlslCompileInput& in) : in_(in) {}

    IncludeResult* includeLocal(const char* header, const char* includer, size_t) override {
        const std::string from = includer ? includer : "";
        if (from.rfind("gonio/", 0) == 0)
            if (auto* r = embedded((fs::path(from).parent_path() / header).lexically_normal().string())) return r;
        std::vector<fs::path> tries;
        if (!from.empty() && from.rfind("gonio/", 0) != 0) tries.push_back(fs::path(from).parent_path() / header);
        for (const auto& d : in_.include_dirs) tries.push_back(fs::path(d) / header);
        for (const auto& p : tries) {
            std::error_code ec;
            if (!fs::is_regular_file(p, ec)) continue;
            auto text = std::make_unique<std::string>(read_text(p.string()));
            const std::string name = p.lexically_normal().string();
            auto* r = new IncludeResult(name, text->data(), text->size(), text.get());
            text.release();
            return r;
        }
        for (const auto& v : in_.virtual_files)
            if (v.key == header) return new IncludeResult(v.name, v.text.data(), v.text.size(), nullptr);
        if (in_.gonio_sources)
            if (auto* r = embedded((fs::path("gonio/lib") / header).lexically_normal().string())) return r;
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
    IncludeResult* embedded(const std::string& name) {
        const char* text = in_.gonio_sources ? embedded_shader_source(name) : nullptr;
        return text ? new IncludeResult(name, text, std::strlen(text), nullptr) : nullptr;
    }
    const GlslCompileInput& in_;
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

const char* embedded_shader_source(const std::string& name) {
    for (const EmbeddedSource& e : embedded_shader_sources())
        if (name == e.name) return e.text;
    return nullptr;
}

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
    FileIncluder includer(in);
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
    GlslCompileInput in;
    in.source = s.str();
    in.name = path;
    in.include_dirs = include_dirs;
    in.defines = defines;
    return compile_compute_glsl(in);
}

}   // namespace gonio
