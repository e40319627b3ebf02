// spectral_table.cpp: see spectral_table.h.
#include "spectral_table.h"
#include "embedded_spectra.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace {

std::vector<std::string> split_commas(const std::string& line) {
    std::vector<std::string> out;
    std::string cell;
    std::istringstream in(line);
    while (std::getline(in, cell, ',')) out.push_back(cell);
    if (!line.empty() && line.back() == ',') out.emplace_back();
    return out;
}

}   // namespace

size_t SpectralTable::column(const std::string& name) const {
    for (size_t c = 0; c < columns.size(); ++c)
        if (columns[c] == name) return c;
    std::string known;
    for (const std::string& c : columns) known += (known.empty() ? "" : ", ") + c;
    throw std::invalid_argument(file + " has no column '" + name + "' (it has " + known + ")");
}

double SpectralTable::at(size_t c, double nm) const {
    if (!(nm >= first_nm() && nm <= last_nm()))
        throw std::out_of_range(file + " covers " + std::to_string(first_nm()) + " to " + std::to_string(last_nm()) +
                                " nm, not " + std::to_string(nm) + " nm");
    const auto hi = std::lower_bound(wavelength_nm.begin(), wavelength_nm.end(), nm);
    const size_t j = size_t(hi - wavelength_nm.begin());
    if (*hi == nm) return values.at(c)[j];
    const double t = (nm - wavelength_nm[j - 1]) / (wavelength_nm[j] - wavelength_nm[j - 1]);
    return values.at(c)[j - 1] + t * (values.at(c)[j] - values.at(c)[j - 1]);
}

SpectralTable parse_spectral_table(const std::string& text, const std::string& file) {
    SpectralTable t;
    t.file = file;
    std::istringstream in(text);
    std::string line;
    int n = 0;
    bool header = false;
    auto fail = [&](const std::string& what) {
        throw std::runtime_error(file + ":" + std::to_string(n) + ": " + what);
    };
    while (std::getline(in, line)) {
        ++n;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty() || line[0] == '#') continue;
        const std::vector<std::string> cells = split_commas(line);
        if (!header) {
            if (cells.size() < 2 || cells[0] != "wavelength_nm")
                fail("expected the header row 'wavelength_nm,COLUMN,...', got '" + line + "'");
            t.columns.assign(cells.begin() + 1, cells.end());
            t.values.assign(t.columns.size(), {});
            header = true;
            continue;
        }
        if (cells.size() != t.columns.size() + 1)
            fail("expected " + std::to_string(t.columns.size() + 1) + " numbers, got " + std::to_string(cells.size()));
        std::vector<double> row;
        for (const std::string& cell : cells) {
            size_t used = 0;
            double v = 0;
            try {
                v = std::stod(cell, &used);
            } catch (const std::exception&) { used = 0; }
            if (used != cell.size() || cell.empty() || !std::isfinite(v)) fail("'" + cell + "' is not a number");
            row.push_back(v);
        }
        if (!t.wavelength_nm.empty() && !(row[0] > t.wavelength_nm.back()))
            fail("wavelengths must increase: " + cells[0] + " nm after " + std::to_string(t.wavelength_nm.back()));
        t.wavelength_nm.push_back(row[0]);
        for (size_t c = 0; c < t.columns.size(); ++c) t.values[c].push_back(row[c + 1]);
    }
    if (!header) fail("no header row 'wavelength_nm,COLUMN,...'");
    if (t.wavelength_nm.size() < 2) fail("a table needs at least two rows");
    return t;
}

const SpectralTable& embedded_spectral_table(const std::string& file) {
    static std::mutex m;
    static std::map<std::string, SpectralTable> parsed;
    std::lock_guard<std::mutex> lock(m);
    if (auto it = parsed.find(file); it != parsed.end()) return it->second;
    for (const EmbeddedSpectrum& e : embedded_spectra())
        if (file == e.file) return parsed.emplace(file, parse_spectral_table(e.text, file)).first->second;
    throw std::logic_error("data/spectra/" + file + " is not in this build");
}

}   // namespace gonio
