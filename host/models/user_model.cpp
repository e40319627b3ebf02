// user_model.cpp: a user's model file compiled at run time (user_model.h).
#include "user_model.h"
#include "glsl_compiler.h"
#include "model_registry.h"
#include "shader_sources.h"

#include <chrono>
#include <stdexcept>

namespace gonio {

namespace {

// One of gonio's kernels (an embedded source, "gonio/NAME.comp") with the user's file in place of the built-in
// models (GONIO_USER_MODEL; the file is the virtual include "gonio_user_model.glsl").
// h: the file's header: model_lobes defined (models/user_model.glsl; models.comp grades its quadrature towards them),
// its parameters (param_NAME, the i-th: models/stack_tables.glsl model_parameter(i))
std::vector<uint32_t> compile_with_user_model(const char* kernel, const std::string& text, const ModelFileHeader& h) {
    const char* comp = embedded_shader_source(kernel);
    if (!comp) throw std::runtime_error("gonio was built without its embedded shaders (shader_sources.cpp)");
    GlslCompileInput in;
    in.source = comp;
    in.name = kernel;
    in.defines = {{"GONIO_USER_MODEL", "1"}, {"GONIO_MODEL_ONLY", "1000"}};
    if (h.has_lobe_hints) in.defines.push_back({"GONIO_MODEL_HINTS", "1"});
    for (size_t i = 0; i < h.parameters.size(); ++i)
        in.defines.push_back({"param_" + h.parameters[i].name, "model_parameter(" + std::to_string(i) + "u)"});
    in.virtual_files = {{"gonio_user_model.glsl", h.path, text}};
    in.gonio_sources = true;
    return compile_compute_glsl(in);
}

}   // namespace

std::vector<uint32_t> compile_user_render_kernel(const UserModel& m) {
    return compile_with_user_model("gonio/render.comp", m.text, m.header);
}

std::shared_ptr<const UserModel> compile_user_model(const std::string& text, const std::string& path) {
    const auto t0 = std::chrono::steady_clock::now();
    auto m = std::make_shared<UserModel>();
    m->header = parse_model_header(text, path);
    for (const ModelInfo& b : model_registry())
        if (b.id == m->header.id)
            throw StackError(path, 1, "gonio-model: '" + m->header.id + "' is a built-in model's id (gonio models)");
    m->text = text;
    m->spirv = compile_with_user_model("gonio/models.comp", text, m->header);
    m->compile_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return m;
}

std::shared_ptr<const UserModel> load_user_model(const std::string& path) {
    std::string text;
    read_model_file(path, &text);   // refuses a missing or unreadable file, and a bad header
    return compile_user_model(text, path);
}

}   // namespace gonio
