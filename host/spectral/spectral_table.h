// spectral_table.h: a table of values against wavelength, read from the CSV files of data/spectra/ ('#' comment
// lines, a header row "wavelength_nm,COLUMN,...", rows of numbers in increasing wavelength), and read between its
// rows by linear interpolation in wavelength.
#pragma once

#include <string>
#include <vector>

namespace gonio {

struct SpectralTable {
    std::string file;   // where it came from (an embedded file's name)
    std::vector<std::string> columns;   // the value columns, after wavelength_nm
    std::vector<double> wavelength_nm;   // strictly increasing
    std::vector<std::vector<double>> values;   // values[c][row]

    double first_nm() const { return wavelength_nm.front(); }
    double last_nm() const { return wavelength_nm.back(); }
    size_t column(const std::string& name) const;   // throws std::invalid_argument naming the columns there are
    // Column c at nm, linearly interpolated between the two rows around it; throws std::out_of_range outside
    // [first_nm, last_nm] (nothing is extrapolated).
    double at(size_t c, double nm) const;
};

// Parses a table's text; throws std::runtime_error naming file:line and what was expected.
SpectralTable parse_spectral_table(const std::string& text, const std::string& file);

// An embedded file of data/spectra/ by name, parsed once; throws std::logic_error where the build has no such file.
const SpectralTable& embedded_spectral_table(const std::string& file);

}   // namespace gonio
