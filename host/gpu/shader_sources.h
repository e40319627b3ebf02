// shader_sources.h: gonio's GLSL sources as text, embedded at build time (cmake/embed_shader_sources.cmake), named
// "gonio/models.comp", "gonio/lib/models/common.glsl" and so on: what a model compiled at run time includes.
#pragma once
#include <string>
#include <vector>

namespace gonio {

struct EmbeddedSource {
    const char* name;   // "gonio/" + the path under shaders/
    const char* text;
};
const std::vector<EmbeddedSource>& embedded_shader_sources();

// The text of embedded file `name` ("gonio/lib/ggx.glsl"), or nullptr.
const char* embedded_shader_source(const std::string& name);

}   // namespace gonio
