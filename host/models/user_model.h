// user_model.h: a model written as one GLSL file by a user (docs/MODELS.md, "Your own model"), read, checked and
// compiled at run time (glslang's library) into models.comp's quadrature kernel, before any simulation starts.
#pragma once
#include "model_file.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace gonio {

struct UserModel {
    ModelFileHeader header;   // id, citation, represents, claims (model_file.h)
    std::string text;   // the file's text
    std::vector<uint32_t> spirv;   // models.comp with the file in place of the built-in models
    double compile_seconds = 0;   // reading, checking and compiling (host clock)
};

// Reads, checks and compiles model file `path`. Throws StackError (FILE:LINE: what was expected) for a bad header
// and std::invalid_argument with glslang's messages (FILE:LINE: message, in the file that holds the error) for code
// that does not compile.
std::shared_ptr<const UserModel> load_user_model(const std::string& path);

// render.comp (gonio render) with the model's file in place of the built-in models, compiled now (the first
// render of the model; the quadrature kernel is compiled at load).
std::vector<uint32_t> compile_user_render_kernel(const UserModel& m);

// The same for a file's text (for tests): `path` names it in messages and is where its #include are resolved from.
std::shared_ptr<const UserModel> compile_user_model(const std::string& text, const std::string& path);

}   // namespace gonio
