# builtin_models.cmake: the dispatch of the built-in models (shaders/lib/models/all.glsl) from their files, one
# per model (shaders/lib/models/builtin/*.glsl, in name order: a file's place is its code, as in CMakeLists.txt's
# per-model SPIR-V modules and host/models/model_registry.cpp's registry): each file's #include, under
# GONIO_HAS_MODEL(code), and eval_model's call of its entry model_ID (the id of its '// gonio-model:' line, - . + as _).
#   cmake -DMODEL_DIR=shaders/lib/models/builtin -DINCLUDE_PREFIX=models/builtin/ -DOUT=builtin_models.glsl -P ...
# or -DMODEL_FILES=a.glsl|b.glsl|... (CMakeLists.txt: its own glob's list, in the command line, so that a file
# removed changes the command and ninja writes the dispatch again)
if(DEFINED MODEL_FILES)
  string(REPLACE "|" ";" files "${MODEL_FILES}")
else()
  file(GLOB files ${MODEL_DIR}/*.glsl)
endif()
list(SORT files)
set(includes "")
set(dispatch "")
set(lobes_dispatch "")
set(base_alpha_dispatch "")
set(artist_dispatch "")
set(tables_dispatch "")
set(layout "")
set(layout_list "")
set(table_bit 1)
set(table_offset 0)
set(code 0)
foreach(f ${files})
  get_filename_component(name ${f} NAME)
  file(STRINGS ${f} id_line REGEX "^// gonio-model:" LIMIT_COUNT 1)
  if(NOT id_line)
    message(FATAL_ERROR "${f}: a built-in model's file starts with '// gonio-model: ID' (docs/MODELS.md)")
  endif()
  string(REGEX REPLACE "^// gonio-model:[ \t]*([^ \t]*).*$" "\\1" id "${id_line}")
  string(REGEX REPLACE "[^A-Za-z0-9]" "_" entry "model_${id}")
  # its own parameters (`// parameter: NAME default ...` lines, in order): param_NAME reads the i-th
  # (models/stack_tables.glsl model_parameter); defined around the file's #include only
  file(STRINGS ${f} parameter_lines REGEX "^// parameter:")
  set(param_defines "")
  set(param_undefs "")
  set(i 0)
  foreach(line ${parameter_lines})
    string(REGEX REPLACE "^// parameter:[ \t]*([A-Za-z0-9_]*).*$" "\\1" pname "${line}")
    string(APPEND param_defines "#define param_${pname} model_parameter(${i}u)\n")
    string(APPEND param_undefs "#undef param_${pname}\n")
    math(EXPR i "${i} + 1")
  endforeach()
  # the per-stack table sets it declares (`// table: NAME FLOATS` lines): each set's bit (STACK_TABLES_NAME, what a
  # `tables:` line names), its offset in the buffer (STACK_TABLE_NAME, from STACK_TABLE_SETS, in the files' order)
  # and its size (STACK_TABLE_NAME_FLOATS); the file's GONIO_MODEL_TABLES(s, sets) hook fills them (the CPU twin)
  file(STRINGS ${f} table_lines REGEX "^// table:")
  foreach(line ${table_lines})
    if(NOT line MATCHES "^// table:[ \t]*([a-z0-9-]+)[ \t]+([0-9]+)[ \t]*$")
      message(FATAL_ERROR "${f}: '${line}': a table line is '// table: NAME FLOATS' (docs/MODELS.md)")
    endif()
    set(tname ${CMAKE_MATCH_1})
    set(tfloats ${CMAKE_MATCH_2})
    string(TOUPPER ${tname} TNAME)
    string(REPLACE "-" "_" TNAME ${TNAME})
    string(APPEND layout "// ${tname}: ${tfloats} floats, filled by ${name}\n"
           "const uint STACK_TABLES_${TNAME} = ${table_bit}u;\n"
           "const uint STACK_TABLE_${TNAME} = STACK_TABLE_SETS + ${table_offset}u;\n"
           "const uint STACK_TABLE_${TNAME}_FLOATS = ${tfloats}u;\n")
    string(APPEND layout_list "    {\"${tname}\", ${table_bit}u, STACK_TABLE_SETS + ${table_offset}u, ${tfloats}u, ${code}u},\n")
    math(EXPR table_bit "${table_bit} * 2")
    math(EXPR table_offset "${table_offset} + ${tfloats}")
  endforeach()
  # the CPU twin (C++) keeps each file's GONIO_MODEL_LOBES hook as a function before the next file's replaces it:
  # what host/models/model_plan.cpp plans a `plan: lobes` model's terms from; and its GONIO_MODEL_BASE_ALPHA hook
  # (the roughness a `plan: coat` model's base lobe has), what it plans that lobe's term from; and its
  # GONIO_MODEL_ARTIST_PARAMETERS hook (a production model's mapping), what host/models/artist_parameters.cpp runs
  string(APPEND includes "#if GONIO_HAS_MODEL(${code})\n${param_defines}#include \"${INCLUDE_PREFIX}${name}\"   // ${id}\n"
         "#if defined(__cplusplus) && defined(GONIO_MODEL_LOBES)\n"
         "GONIO_INLINE BelcourLobes ${entry}_lobes(float mu, bool tables) { return GONIO_MODEL_LOBES(mu, tables); }\n"
         "#define GONIO_MODEL_${code}_HAS_LOBES 1\n#endif\n"
         "#if defined(__cplusplus) && defined(GONIO_MODEL_BASE_ALPHA)\n"
         "GONIO_INLINE float ${entry}_base_alpha(CoatParams p) { return GONIO_MODEL_BASE_ALPHA(p); }\n"
         "#define GONIO_MODEL_${code}_HAS_BASE_ALPHA 1\n#endif\n"
         "#if defined(__cplusplus) && defined(GONIO_MODEL_ARTIST_PARAMETERS)\n"
         "GONIO_INLINE void ${entry}_artist_parameters(CoatParams p, vec3 diffuse, ArtistValues& a) {\n"
         "    GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a);\n}\n"
         "#define GONIO_MODEL_${code}_HAS_ARTIST_PARAMETERS 1\n#endif\n"
         "#if defined(__cplusplus) && defined(GONIO_MODEL_TABLES)\n"
         "GONIO_INLINE void ${entry}_tables(const StackGpu& s, uint sets) { GONIO_MODEL_TABLES(s, sets); }\n"
         "#define GONIO_MODEL_${code}_HAS_TABLES 1\n#endif\n"
         "#ifndef GONIO_MODEL_ONLY\n#undef GONIO_MODEL_LOBES\n#undef GONIO_MODEL_LOBE_TABLE\n#undef GONIO_MODEL_EXACT\n"
         "#undef GONIO_MODEL_BASE_ALPHA\n#undef GONIO_MODEL_ARTIST_PARAMETERS\n#undef GONIO_MODEL_TABLES\n"
         "#endif\n${param_undefs}#endif\n")
  string(APPEND lobes_dispatch "#ifdef GONIO_MODEL_${code}_HAS_LOBES\n"
         "    if (model == ${code}u) {\n        out = ${entry}_lobes(mu, tables);\n        return true;\n    }\n#endif\n")
  string(APPEND base_alpha_dispatch "#ifdef GONIO_MODEL_${code}_HAS_BASE_ALPHA\n"
         "    if (model == ${code}u) return ${entry}_base_alpha(p);\n#endif\n")
  string(APPEND artist_dispatch "#ifdef GONIO_MODEL_${code}_HAS_ARTIST_PARAMETERS\n"
         "    if (model == ${code}u) {\n        ${entry}_artist_parameters(p, diffuse, a);\n        return true;\n    }\n#endif\n")
  string(APPEND tables_dispatch "#ifdef GONIO_MODEL_${code}_HAS_TABLES\n    ${entry}_tables(s, sets);\n#endif\n")
  string(APPEND dispatch "#if GONIO_HAS_MODEL(${code})\n    if (model == ${code}u) return ${entry}(p, terms, l, v);\n#endif\n")
  math(EXPR code "${code} + 1")
endforeach()
set(body "// generated by cmake/builtin_models.cmake from ${MODEL_DIR}: do not edit\n")
string(APPEND body "// (models/all.glsl: the built-in models, one file each; a file's code is its place in name order)\n")
string(APPEND body "#ifndef GONIO_BUILTIN_MODELS_GLSL\n#define GONIO_BUILTIN_MODELS_GLSL\n")
if(table_bit GREATER 4294967296)
  message(FATAL_ERROR "more than 32 table sets: STACK_TABLES_* are bits of a uint")
endif()
string(APPEND body "// the per-stack table sets the files declare (their `// table:` lines), from STACK_TABLE_SETS in the files' order\n")
string(APPEND body "${layout}const uint STACK_TABLE_SETS_END = STACK_TABLE_SETS + ${table_offset}u;\n")
string(APPEND body "#ifdef __cplusplus\n")
string(APPEND body "static_assert(STACK_TABLE_SETS_END <= STACK_TABLE_FLOATS, \"the table sets outgrow the buffer (STACK_TABLE_FLOATS)\");\n")
string(APPEND body "// the sets for the registry (host/models/model_registry.cpp resolves `tables:` names by them)\n")
string(APPEND body "struct StackTableSetInfo {\n    const char* name;\n    uint bit, offset, floats, model;   // model: the code of the file that declares it\n};\n")
string(APPEND body "inline const StackTableSetInfo STACK_TABLE_SET_LIST[] = {\n${layout_list}    {nullptr, 0u, 0u, 0u, 0u}};\n#endif\n")
string(APPEND body "${includes}\n")
string(APPEND body "// the model of code `model` (a module built with GONIO_MODEL_ONLY holds that one only)\n")
string(APPEND body "GONIO_INLINE vec3 eval_model(uint model, CoatParams p, uint terms, vec3 l, vec3 v) {\n")
string(APPEND body "${dispatch}    return vec3(0.0f);\n}\n")
string(APPEND body "#if defined(__cplusplus) && defined(GONIO_MODEL_BELCOUR18_GLSL)\n")
string(APPEND body "// the CPU twin: whether code `model` has lobes (its file's GONIO_MODEL_LOBES), and them at mu\n")
string(APPEND body "inline bool eval_model_lobes(uint model, float mu, bool tables, BelcourLobes& out) {\n")
string(APPEND body "${lobes_dispatch}    return false;\n}\n#endif\n")
string(APPEND body "#if defined(__cplusplus)\n")
string(APPEND body "// the CPU twin: the roughness a `plan: coat` model evaluates its base lobe at (its file's GONIO_MODEL_BASE_ALPHA,\n")
string(APPEND body "// a coat's roughening of the base), else the base's own\n")
string(APPEND body "inline float eval_model_base_alpha(uint model, CoatParams p) {\n")
string(APPEND body "${base_alpha_dispatch}    return p.alpha1;\n}\n")
string(APPEND body "// the CPU twin: a production model's artist parameters for the stack (its file's GONIO_MODEL_ARTIST_PARAMETERS);\n")
string(APPEND body "// false for a model without a mapping\n")
string(APPEND body "inline bool eval_model_artist_parameters(uint model, CoatParams p, vec3 diffuse, ArtistValues& a) {\n")
string(APPEND body "${artist_dispatch}    return false;\n}\n")
string(APPEND body "// the CPU twin: the per-stack table sets named in `sets` (STACK_TABLES_* bits), each by the GONIO_MODEL_TABLES hook\n")
string(APPEND body "// of the file that declares it, through model_stack_table_store (host/models/stack_tables.cpp)\n")
string(APPEND body "inline void eval_stack_table_sets(const StackGpu& s, uint sets) {\n${tables_dispatch}}\n#endif\n#endif\n")
file(WRITE ${OUT}.tmp "${body}")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
file(REMOVE ${OUT}.tmp)
