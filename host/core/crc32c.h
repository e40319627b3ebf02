// crc32c.h: CRC-32C (Castagnoli, the polynomial 0x82F63B78 reflected; iSCSI, ext4, Btrfs), the checksum of gonio's
// state files (host/io/state.cpp). crc32c_update(0, "123456789", 9) = 0xE3069283, its check value.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

namespace gonio {

inline const std::array<uint32_t, 256>& crc32c_table() {
    static const std::array<uint32_t, 256> table = [] {
        std::array<uint32_t, 256> t{};
        for (uint32_t i = 0; i < 256; ++i) {
            uint32_t c = i;
            for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0x82F63B78u ^ (c >> 1) : c >> 1;
            t[i] = c;
        }
        return t;
    }();
    return table;
}

// The CRC-32C of `bytes` continued from `crc` (0 for the first block): crc32c_update(crc32c_update(0, a), b) is the
// CRC of a followed by b.
inline uint32_t crc32c_update(uint32_t crc, const void* bytes, size_t n) {
    const auto& t = crc32c_table();
    const unsigned char* p = static_cast<const unsigned char*>(bytes);
    crc = ~crc;
    for (size_t i = 0; i < n; ++i) crc = t[(crc ^ p[i]) & 0xFFu] ^ (crc >> 8);
    return ~crc;
}

}   // namespace gonio
