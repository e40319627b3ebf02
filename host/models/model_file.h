// model_file.h: a model written as one GLSL file (docs/MODELS.md, "A model is one file"): its header, which says
// what the model is and which stacks it represents, read and checked before the file is compiled.
//
//   // gonio-model: my-coat
//   // citation: Doe 2027, "A better coat", eq. 3
//   // represents: coat-over-lambertian, coat-over-conductor
//   // reciprocal: yes
//   // energy-conserving: no (the base is not attenuated by the coat's reflection)
//   vec3 model_f(vec3 l, vec3 v) { ... }   // f in 1/sr, cosine excluded; z up, directions away from the surface
//
// The header is the file's first comment lines; a line "// key: value" sets a key, a comment line without a key
// continues the value before it. Every problem is refused with FILE:LINE and what was expected.
#pragma once
#include "stack.h"

#include <string>
#include <vector>

namespace gonio {

// The stacks a model may say it represents (`represents:`), each a shape of stack (layers top to bottom).
enum class StackShape {
    Any,   // every stack
    CoatOverLambertian,   // one dielectric interface over a Lambertian base
    CoatOverConductor,   // one dielectric interface over a conductor
    DielectricsOverLambertian,   // any number (0 or more) of dielectric interfaces over a Lambertian base
    DielectricsOverConductor,   // any number (0 or more) of dielectric interfaces over a conductor
    Slab,   // dielectric interfaces only, the substrate of the exterior's IOR (transmissive)
    Transmissive,   // dielectric interfaces only (the last one's medium is the substrate)
};

const char* to_string(StackShape s);
bool stack_has_shape(const Stack& s, StackShape shape);

struct ModelFileHeader {
    std::string path;
    std::string id;   // gonio-model:
    std::string citation;   // citation:
    std::vector<StackShape> represents;   // represents: (comma-separated)
    bool reciprocal = false;   // reciprocal: yes | no
    bool energy_conserving = false;   // energy-conserving: yes | no, then an optional reason
    std::string energy_note;   // the reason, if given ("(...)" after yes/no)
    bool has_lobe_hints = false;   // the file defines model_lobes(...)
};

// Parse the header of a model file's text; also checks that the file defines vec3 model_f(vec3, vec3).
// Throws StackError (file, line, what was expected) on any problem.
ModelFileHeader parse_model_header(const std::string& text, const std::string& path);
ModelFileHeader read_model_file(const std::string& path, std::string* text_out = nullptr);

// "" where the model represents the stack, else why not (naming the shapes it represents).
std::string model_file_cannot_represent(const ModelFileHeader& h, const Stack& s);

}   // namespace gonio
