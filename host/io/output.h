// output.h: what `gonio simulate` writes: <name>.exr, slices.csv, summary.json.
#pragma once
#include "reference.h"

#include <nlohmann/json_fwd.hpp>

#include <iosfwd>
#include <string>
#include <vector>

namespace gonio {

// slices.csv: one row per bin, columns source,theta_i,side,theta_lo,theta_hi,phi_lo,phi_hi,r,g,b,se_r,se_g,se_b.
// With --orders, rows of each path class follow with source reference:order0 / order1 / order2.
// Model rows (gonio compare) follow with source = the model id, reflection side, standard errors 0.
struct ModelSlices;
void write_slices_csv(const std::string& path, const SimResult& r, const std::vector<ModelSlices>* models = nullptr);
void write_slices_csv(std::ostream& f, const SimResult& r, const std::vector<ModelSlices>* models = nullptr);
// The same text in memory (the Python module's runs: gonio._core).
std::string slices_csv_text(const SimResult& r, const std::vector<ModelSlices>* models = nullptr);
// summary.json: energy fractions per angle and channel, paths, seconds, paths per second, device; the members of
// `extra` (a JSON object, e.g. the model metrics of gonio compare, models_json) are added at the end.
void write_summary_json(const std::string& path, const SimResult& r, const nlohmann::ordered_json* extra = nullptr);
// Its JSON in memory (json_text gives the file's bytes).
nlohmann::ordered_json summary_json(const SimResult& r, const nlohmann::ordered_json* extra = nullptr);
// OpenEXR, one part per incident angle and side; image rows = theta bins, columns = phi bins. With models
// (gonio compare), one more part per applicable model and incident angle ("theta_i=30 R model=ww09").
void write_exr(const std::string& path, const SimResult& r, const std::vector<ModelSlices>* models = nullptr);

// A stack's (or sweep's) name as a file name: letters, digits, '.', '-' and '_' are kept, anything else (a '/',
// "..", a space, a control character) becomes '_', and a leading '.' too: nothing that comes from an input file
// can name a path outside the output directory.
std::string safe_file_name(const std::string& name);

}   // namespace gonio
