// state.cpp: a run's raw sums on disk (<out>/state.gonio), so that --resume can continue it exactly.
// Binary, little-endian, versioned; everything that decides the sums is stored and compared on resume. A state file
// is data from outside when it is read: it is checked field by field against what a run could have written, and
// from version 8 against its CRC-32C, before any of it is used.
#include "state.h"
#include "angle_policy.h"
#include "crc32c.h"
#include "input_file.h"
#include "text_format.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace gonio {

namespace {

// 2: series flag, opaque stacks' one side; 3: the baked-stack flag (a version-2 run continued by this build would
// not round exactly as one longer run); 4: the energy book's invalid class (12 entries); 5: the walk that ran (specialised,
// baked, series: SimResult::walk, as its host recorded it); 6: how long it was to run (--paths, --rse, --rse-quantile,
// --max-seconds), which --resume continues with unless given anew; 7: the booking estimators (--no-branching, and
// the walk's entry branch and exit estimate); 8: the same fields, then the CRC-32C of every byte before it (4 bytes,
// little-endian); 9: the incident azimuth (--phi-i, a double after the booking estimators). Versions 5 to 8 are read
// too (phi_i 0, the only azimuth they ran), checked field by field without a checksum (then --resume's defaults
// for what versions 5 and 6 lack are the paths it has, no --rse or --max-seconds, and the analog walk they ran).
const char kMagic[8] = {'G', 'O', 'N', 'I', 'O', 'S', 'T', '9'};
constexpr char kOldestRead = '5';
// The largest state file read (a run of 90 angles at 0.25 x 0.5 degree bins with --orders holds about 5 GiB)
constexpr std::uintmax_t kMaxStateFileBytes = std::uintmax_t(64) << 30;

struct Writer {
    std::ofstream f;
    uint32_t crc = 0;
    void bytes(const void* p, size_t n) {
        f.write(static_cast<const char*>(p), std::streamsize(n));
        crc = crc32c_update(crc, p, n);
    }
    template <class T>
    void put(const T& v) {
        bytes(&v, sizeof v);
    }
    void str(const std::string& s) {
        put(uint64_t(s.size()));
        bytes(s.data(), s.size());
    }
};

// Reads with the running CRC and the bytes left, so that a size read from the file is checked against what the file
// holds before anything of that size is allocated
struct Reader {
    std::ifstream f;
    std::string path;
    std::uintmax_t left = 0;
    uint32_t crc = 0;
    void bytes(void* p, std::uintmax_t n) {
        if (n > left || !f.read(static_cast<char*>(p), std::streamsize(n)))
            throw std::invalid_argument(path + ": truncated state file");
        left -= n;
        crc = crc32c_update(crc, p, size_t(n));
    }
    template <class T>
    T get() {
        T v{};
        bytes(&v, sizeof v);
        return v;
    }
    std::string str() {
        const uint64_t n = get<uint64_t>();
        if (n > left || n > (1u << 26)) throw std::invalid_argument(path + ": corrupt state file (a string's length)");
        std::string s(n, '\0');
        bytes(s.data(), n);
        return s;
    }
};

// A state file field that no run writes: refused with the field, its value and what a run writes
[[noreturn]] void refuse(const std::string& path, const std::string& field, const std::string& value,
                         const std::string& expected) {
    throw std::invalid_argument(path + ": not a state file a run wrote: " + field + " " + value + " (expected " +
                                expected + ")");
}

std::string hex32(uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%08x", v);
    return buf;
}

// The options and the bin grid against what a run could have written (sim_options.cpp validate_options,
// angle_policy.cpp walk_grid)
void check_options(const std::string& path, const SimResult& r, bool has_targets) {
    const SimOptions& o = r.options;
    if (!bin_width_divides(o.dtheta_deg, 90.0))
        refuse(path, "dtheta", format_g9(o.dtheta_deg), "a width that divides 90");
    if (!bin_width_divides(o.dphi_deg, 180.0)) refuse(path, "dphi", format_g9(o.dphi_deg), "a width that divides 180");
    const WalkGrid g = walk_grid(o.dtheta_deg, o.dphi_deg, o.orders, r.stack.transmissive());
    if (r.n_theta != g.n_theta || r.n_phi != g.n_phi)
        refuse(path, "bin grid", std::to_string(r.n_theta) + " x " + std::to_string(r.n_phi),
               std::to_string(g.n_theta) + " x " + std::to_string(g.n_phi) + " for bins of " + format_g9(o.dtheta_deg) +
                   " x " + format_g9(o.dphi_deg) + " degrees");
    if (r.n_classes != g.n_classes)
        refuse(path, "classes", std::to_string(r.n_classes),
               std::to_string(g.n_classes) + (o.orders ? " with --orders" : ""));
    if (o.max_events < 1) refuse(path, "max_events", "0", "at least 1");
    if (!(o.phi_i_deg >= 0.0 && o.phi_i_deg < 360.0))
        refuse(path, "incident azimuth", format_g9(o.phi_i_deg), "an azimuth in [0, 360) degrees");
    if (!has_targets) return;
    if (o.paths < 1 || o.paths > kMaxPathsPerAngle)
        refuse(path, "paths", std::to_string(o.paths), "1 to " + format_g9(double(kMaxPathsPerAngle)));
    if (!(o.rse_target >= 0 && o.rse_target < 1)) refuse(path, "rse", format_g9(o.rse_target), "0 (off) or in (0, 1)");
    if (!(o.rse_quantile > 0 && o.rse_quantile <= 1))
        refuse(path, "rse_quantile", format_g9(o.rse_quantile), "a quantile in (0, 1]");
    if (!(o.max_seconds >= 0 && std::isfinite(o.max_seconds)))
        refuse(path, "max_seconds", format_g9(o.max_seconds), "0 (off) or a positive number of seconds");
}

// One incident angle's fields: its angle in [0, 90) and not an earlier one's, paths within the run's range,
// non-negative times and energy book, and nothing booked where no path ran (a checkpoint's angles still to come)
void check_angle(const std::string& path, const SimResult& r, const AngleResult& a) {
    const std::string at = "angle " + format_g9(a.theta_i_deg) + ": ";
    if (!(a.theta_i_deg >= 0.0 && a.theta_i_deg < 90.0))
        refuse(path, "incident angle", format_g9(a.theta_i_deg), "an angle in [0, 90) degrees");
    for (const AngleResult& b : r.angles)
        if (b.theta_i_deg == a.theta_i_deg) refuse(path, "incident angle", format_g9(a.theta_i_deg), "each once");
    if (a.paths > kMaxPathsPerAngle)
        refuse(path, at + "paths", std::to_string(a.paths), "at most " + format_g9(double(kMaxPathsPerAngle)));
    if (!(a.seconds >= 0 && std::isfinite(a.seconds) && a.device_seconds >= 0 && std::isfinite(a.device_seconds)))
        refuse(path, at + "seconds", format_g9(a.seconds) + " (device " + format_g9(a.device_seconds) + ")",
               "finite times, 0 or more");
    for (int64_t e : a.energy)
        if (e < 0) refuse(path, at + "energy book entry", format_g9(double(e) / kEnergyScale), "0 or more");
    if (a.paths == 0) {
        bool empty = std::all_of(a.raw.begin(), a.raw.end(), [](uint64_t v) { return v == 0; });
        for (int64_t e : a.energy) empty &= e == 0;
        if (!empty) refuse(path, at + "sums", "booked with 0 paths", "none where no path ran");
    }
}

}   // namespace

void save_state(const std::string& path, const SimResult& r) {
    const std::string tmp = path + ".tmp";
    Writer w{std::ofstream(tmp, std::ios::binary)};
    if (!w.f) throw std::runtime_error("cannot write " + tmp);
    w.bytes(kMagic, 8);
    w.str(stack_to_toml(r.stack));
    w.put(r.options.seed);
    w.put(r.options.dtheta_deg);
    w.put(r.options.dphi_deg);
    w.put(r.options.max_events);
    w.put(uint8_t(r.options.orders));
    w.put(uint8_t(r.options.specialised));
    w.put(uint8_t(r.options.series));
    w.put(uint8_t(r.options.baked_stack));
    w.put(r.options.paths);
    w.put(r.options.rse_target);
    w.put(r.options.rse_quantile);
    w.put(r.options.max_seconds);
    w.put(uint8_t(r.walk.specialised));
    w.put(uint8_t(r.walk.baked_stack));
    w.put(uint8_t(r.walk.series));
    w.put(uint8_t(r.options.branching));
    w.put(uint8_t(r.walk.entry_branch));
    w.put(uint8_t(r.walk.exit_estimates));
    w.put(r.options.phi_i_deg);
    w.put(r.n_theta);
    w.put(r.n_phi);
    w.put(r.n_classes);
    w.put(uint64_t(r.angles.size()));
    for (const AngleResult& a : r.angles) {
        w.put(a.theta_i_deg);
        w.put(a.paths);
        w.put(a.seconds);
        w.put(a.device_seconds);
        for (int64_t e : a.energy) w.put(e);
        w.put(uint64_t(a.raw.size()));
        w.bytes(a.raw.data(), a.raw.size() * 8);
    }
    const uint32_t crc = w.crc;
    w.f.write(reinterpret_cast<const char*>(&crc), sizeof crc);
    w.f.close();
    if (!w.f) throw std::runtime_error("error writing " + tmp);
    // a finished state file replaces the old one at once, or the write fails
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
        throw std::runtime_error("cannot replace " + path + " by " + tmp + ": " + std::strerror(errno));
}

SimResult load_state(const std::string& path) {
    const std::string why = input_file_refusal(path, "state file", kMaxStateFileBytes);
    if (!why.empty())
        throw std::invalid_argument(path + ": " + why + " (is it the output directory of a simulate run?)");
    Reader rd{std::ifstream(path, std::ios::binary), path};
    if (!rd.f) throw std::invalid_argument(path + ": cannot open the state file for reading");
    rd.left = std::filesystem::file_size(path);
    char magic[8];
    if (rd.left < 8 || !rd.f.read(magic, 8) || std::memcmp(magic, kMagic, 7) != 0 || magic[7] < kOldestRead ||
        magic[7] > kMagic[7])
        throw std::invalid_argument(path + ": not a gonio state file (or written by another version)");
    rd.left -= 8;
    rd.crc = crc32c_update(0, magic, 8);
    const bool has_targets = magic[7] >= '6', has_checksum = magic[7] >= '8';
    if (has_checksum) {
        if (rd.left < 4) throw std::invalid_argument(path + ": truncated state file");
        rd.left -= 4;   // the trailer
    }
    // read first, bounded by what the file holds; checked (checksum, then field by field) before any of it is used
    SimResult r;
    const std::string stack_text = rd.str();
    r.options.seed = rd.get<uint32_t>();
    r.options.dtheta_deg = rd.get<double>();
    r.options.dphi_deg = rd.get<double>();
    r.options.max_events = rd.get<uint32_t>();
    r.options.orders = rd.get<uint8_t>() != 0;
    r.options.specialised = rd.get<uint8_t>() != 0;
    r.options.series = rd.get<uint8_t>() != 0;
    r.options.baked_stack = rd.get<uint8_t>() != 0;
    uint64_t target_paths = 0;   // version 5: the most paths an angle has
    if (has_targets) {
        target_paths = rd.get<uint64_t>();
        r.options.rse_target = rd.get<double>();
        r.options.rse_quantile = rd.get<double>();
        r.options.max_seconds = rd.get<double>();
    }
    r.walk.specialised = rd.get<uint8_t>() != 0;
    r.walk.baked_stack = rd.get<uint8_t>() != 0;
    r.walk.series = rd.get<uint8_t>() != 0;
    r.options.branching = false;   // versions 5 and 6: the analog walk
    if (magic[7] >= '7') {
        r.options.branching = rd.get<uint8_t>() != 0;
        r.walk.entry_branch = rd.get<uint8_t>() != 0;
        r.walk.exit_estimates = rd.get<uint8_t>();
    }
    if (magic[7] >= '9') r.options.phi_i_deg = rd.get<double>();
    r.n_theta = rd.get<uint32_t>();
    r.n_phi = rd.get<uint32_t>();
    r.n_classes = rd.get<uint32_t>();
    const uint64_t n = rd.get<uint64_t>();
    if (n > kMaxIncidentAngles) throw std::invalid_argument(path + ": corrupt state file (angle count)");
    std::vector<AngleResult> angles;
    for (uint64_t i = 0; i < n; ++i) {
        AngleResult a;
        a.theta_i_deg = rd.get<double>();
        a.paths = rd.get<uint64_t>();
        a.seconds = rd.get<double>();
        a.device_seconds = rd.get<double>();
        for (int64_t& e : a.energy) e = rd.get<int64_t>();
        const uint64_t m = rd.get<uint64_t>();
        if (m > rd.left / 8) throw std::invalid_argument(path + ": truncated state file");
        a.raw.resize(m);
        rd.bytes(a.raw.data(), m * 8);
        angles.push_back(std::move(a));
    }
    if (rd.left != 0) throw std::invalid_argument(path + ": corrupt state file (data after its last angle)");
    if (has_checksum) {
        uint32_t stored = 0;
        if (!rd.f.read(reinterpret_cast<char*>(&stored), sizeof stored))
            throw std::invalid_argument(path + ": truncated state file");
        if (stored != rd.crc)
            throw std::invalid_argument(path + ": the state file's checksum does not match its contents (CRC-32C " +
                                        hex32(rd.crc) + ", stored " + hex32(stored) +
                                        "): it was damaged or edited after the run wrote it");
    }
    r.stack = parse_stack_string(stack_text, path + " (stored stack)");
    r.options.paths = target_paths;
    check_options(path, r, has_targets);
    if (n < 1) refuse(path, "angle count", "0", "1 to " + std::to_string(kMaxIncidentAngles));
    r.n_sides = r.stack.transmissive() ? 2 : 1;
    const uint64_t expect = uint64_t(r.n_classes) * r.n_sides * r.n_theta * r.n_phi * 6;   // the grid is checked
    r.options.theta_i_deg.clear();
    for (AngleResult& a : angles) {
        if (a.raw.size() != expect)
            refuse(path, "histogram size", std::to_string(a.raw.size()), std::to_string(expect) + " for its grid");
        check_angle(path, r, a);
        r.options.theta_i_deg.push_back(a.theta_i_deg);
        a.phi_i_deg = r.options.phi_i_deg;
        target_paths = has_targets ? target_paths : std::max(target_paths, a.paths);
        r.angles.push_back(std::move(a));
    }
    r.options.paths = target_paths;
    if (r.options.paths < 1) refuse(path, "paths", "0 in every angle", "a run with paths");
    return r;
}

}   // namespace gonio
