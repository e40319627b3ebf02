// glsl_compiler.h: GLSL compute shaders compiled to SPIR-V at run time with glslang's library (Debian's
// glslang-dev), as the build compiles the built-in kernels with glslangValidator: Vulkan 1.2 rules, #include
// resolved in the including file's folder, then in the include folders (shaders/lib). For models written by users:
// a compile error is refused (std::invalid_argument) with FILE:LINE: message.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace gonio {

// A file #include can name that is not on disk: `#include "KEY"` gives TEXT, and messages name it NAME.
struct GlslVirtualFile {
    std::string key, name, text;
};

struct GlslCompileInput {
    std::string source;   // the shader's text
    std::string name;   // its file name, for messages and for resolving its own #include
    std::vector<std::string> include_dirs;
    std::vector<std::pair<std::string, std::string>> defines;   // -D NAME=VALUE, before the first line
    std::vector<GlslVirtualFile> virtual_files;   // looked up after the disk
    bool gonio_sources = false;   // last: gonio's own shaders/lib, embedded in the binary (shader_sources.h)
};

// SPIR-V words of a compute shader. Throws std::invalid_argument with glslang's messages, one per line, each as
// FILE:LINE: message, where FILE is the file that holds the error (an included file names itself).
std::vector<uint32_t> compile_compute_glsl(const GlslCompileInput& in);

// The same for a file on disk (FILE names it in messages); a file that cannot be read is refused.
std::vector<uint32_t> compile_compute_glsl_file(const std::string& path, const std::vector<std::string>& include_dirs,
                                                const std::vector<std::pair<std::string, std::string>>& defines = {});

}   // namespace gonio
