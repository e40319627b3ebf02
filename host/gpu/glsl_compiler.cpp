// glsl_compiler.cpp: glslang as a library (see glsl_compiler.h).
#include "glsl_compiler.h"
#include "shader_sources.h"
#include "input_file.h"

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

// #include "x": beside the including file (on disk, or among the embedded sources for an embedded one), then in
// the include folders, then the virtual files, then gonio's embedded shaders/lib. Each result names its file, so
// that glslang's messages say which file holds an error.
// An #include nested deeper than kMaxIncludeDepth is refused with the chain that led there (a file that includes
// itself, directly or not, and has no include guard would otherwise expand without end), and so is a file that is
// not a regular file or is larger than kMaxTextFileBytes (input_file.h).
constexpr size_t kMaxIncludeDepth = 32;

class FileIncluder : public glslang::TShader::Includer {
public:
    FileIncluder(const GlslCompileInput& in) : in_(in) {}

    // why the last parse failed where an include was refused ("" otherwise)
    const std::string& error() const { return error_; }

    IncludeResult* includeLocal(const char* header, const char* includer, size_t depth) override {
        IncludeResult* r = resolve(header, includer ? includer : "");
        if (!error_.empty()) {   // refused once: nothing more is read (glslang goes on after a failed include)
            releaseInclude(r);
            return nullptr;
        }
        if (!r) return r;
        // glslang's depth: 1 for a file the main source includes; chain_[d - 1] the file at depth d
        chain_.resize(std::min(chain_.size(), depth > 0 ? depth - 1 : 0));
        chain_.push_back(r->headerName);
        if (depth <= kMaxIncludeDepth) return r;
        releaseInclude(r);
        error_ = cycle_text() + " (an include guard, #ifndef X / #define X ... #endif, stops a file included twice)";
        return nullptr;
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
    // "a.glsl: #include nested deeper than 32 files: a cycle, a.glsl -> b.glsl -> a.glsl", from the first file of
    // the chain that comes again (else the chain's first file)
    std::string cycle_text() const {
        const std::string deeper = ": #include nested deeper than " + std::to_string(kMaxIncludeDepth) + " files";
        for (size_t i = 0; i < chain_.size(); ++i)
            for (size_t j = i + 1; j < chain_.size(); ++j)
                if (chain_[j] == chain_[i]) {
                    std::string out = chain_[i] + deeper + ": a cycle, ";
                    for (size_t k = i; k <= j; ++k) out += (k > i ? " -> " : "") + chain_[k];
                    return out;
                }
        return chain_.front() + deeper;
    }

    IncludeResult* resolve(const char* header, const std::string& from) {
        if (from.rfind("gonio/", 0) == 0)
            if (auto* r = embedded((fs::path(from).parent_path() / header).lexically_normal().string())) return r;
        std::vector<fs::path> tries;
        if (!from.empty() && from.rfind("gonio/", 0) != 0) tries.push_back(fs::path(from).parent_path() / header);
        for (const auto& d : in_.include_dirs) tries.push_back(fs::path(d) / header);
        for (const auto& p : tries) {
            std::error_code ec;
            if (!fs::exists(p, ec)) continue;
            const std::string name = p.lexically_normal().string();
            const std::string why = input_file_refusal(p.string(), "file to #include", kMaxTextFileBytes);
            if (!why.empty()) {
                error_ = name + ": " + why;
                return nullptr;
            }
            auto text = std::make_unique<std::string>(read_input_file(p.string(), "file to #include"));
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

    IncludeResult* embedded(const std::string& name) {
        const char* text = in_.gonio_sources ? embedded_shader_source(name) : nullptr;
        return text ? new IncludeResult(name, text, std::strlen(text), nullptr) : nullptr;
    }
    const GlslCompileInput& in_;
    std::vector<std::string> chain_;   // the files being included, outermost first
    std::string error_;
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
        throw std::invalid_argument(includer.error().empty() ? tidy_log(shader.getInfoLog()) : includer.error());
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
    const std::string why = input_file_refusal(path, "shader file", kMaxTextFileBytes);
    if (!why.empty()) throw std::invalid_argument(path + ": " + why);
    GlslCompileInput in;
    in.source = read_input_file(path, "shader file");
    in.name = path;
    in.include_dirs = include_dirs;
    in.defines = defines;
    return compile_compute_glsl(in);
}

}   // namespace gonio
