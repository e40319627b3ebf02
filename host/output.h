// output.h: what `gonio simulate` writes: <name>.exr, slices.csv, summary.json.
#pragma once
#include "reference.h"

#include <string>

namespace gonio {

// slices.csv: one row per bin, columns source,theta_i,side,theta_lo,theta_hi,phi_lo,phi_hi,r,g,b,se_r,se_g,se_b.
// With --orders, rows of each path class follow with source reference:order0 / order1 / order2.
void write_slices_csv(const std::string& path, const SimResult& r);
// summary.json: energy fractions per angle and channel, paths, seconds, paths per second, device.
void write_summary_json(const std::string& path, const SimResult& r);
// OpenEXR, one part per incident angle and side; image rows = theta bins, columns = phi bins.
void write_exr(const std::string& path, const SimResult& r);

std::string json_escape(const std::string& s);

}  // namespace gonio
