// embedded_spectra.h: the files of data/spectra/ (measured n and k of metals, the CIE tables) as text in the binary,
// written by cmake/embed_spectra.cmake at build time.
#pragma once

#include <vector>

namespace gonio {

struct EmbeddedSpectrum {
    const char* file;   // its name in data/spectra/, e.g. "au-johnson-christy-1972.csv"
    const char* text;   // the file as it is
};

const std::vector<EmbeddedSpectrum>& embedded_spectra();

}   // namespace gonio
