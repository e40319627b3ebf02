// exr_parts.cpp: see exr_parts.h.
#include "exr_parts.h"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfStringAttribute.h>

namespace gonio {

void write_exr_parts(const std::string& path, int width, int height, const std::vector<ExrPart>& parts) {
    std::vector<Imf::Header> headers;
    for (const ExrPart& p : parts) {
        Imf::Header h(width, height);
        h.setName(p.name);
        h.setType(Imf::SCANLINEIMAGE);
        for (const auto& [key, value] : p.attributes) {
            if (const auto* s = std::get_if<std::string>(&value))
                h.insert(key, Imf::StringAttribute(*s));
            else if (const auto* d = std::get_if<double>(&value))
                h.insert(key, Imf::DoubleAttribute(*d));
            else
                h.insert(key, Imf::IntAttribute(std::get<int>(value)));
        }
        for (const auto& plane : p.planes) h.channels().insert(plane.first, Imf::Channel(Imf::FLOAT));
        headers.push_back(h);
    }
    Imf::MultiPartOutputFile file(path.c_str(), headers.data(), int(headers.size()));
    for (size_t i = 0; i < parts.size(); ++i) {
        Imf::OutputPart part(file, int(i));
        Imf::FrameBuffer fb;
        for (const auto& [channel, values] : parts[i].planes)
            fb.insert(channel, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(values.data())),
                                          sizeof(float), sizeof(float) * size_t(width)));
        part.setFrameBuffer(fb);
        part.writePixels(height);
    }
}

}   // namespace gonio
