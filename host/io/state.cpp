// state.cpp: a run's raw sums on disk (<out>/state.gonio), so that --resume can continue it exactly.
// Binary, little-endian, versioned; everything that decides the sums is stored and compared on resume.
#include "state.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace gonio {

namespace {

// 2: series flag, opaque stacks' one side; 3: the baked-stack flag (a version-2 run continued by this build would
// not round exactly as one longer run); 4: the energy book's invalid class (12 entries); 5: the walk that ran (specialised,
// baked, series: SimResult::walk, as its host recorded it); 6: how long it was to run (--paths, --rse, --rse-quantile,
// --max-seconds), which --resume continues with unless given anew; 7: the booking estimators (--no-branching, and
// the walk's entry branch and exit estimate). Versions 5 and 6 are read too (then --resume's defaults for what
// they lack are the paths it has, no --rse or --max-seconds, and the analog walk they ran).
const char kMagic[8] = {'G', 'O', 'N', 'I', 'O', 'S', 'T', '7'};
constexpr char kOldestRead = '5';

struct Writer {
    std::ofstream f;
    template <class T>
    void put(const T& v) {
        f.write(reinterpret_cast<const char*>(&v), sizeof v);
    }
    void str(const std::string& s) {
        put(uint64_t(s.size()));
        f.write(s.data(), std::streamsize(s.size()));
    }
};

struct Reader {
    std::ifstream f;
    std::string path;
    template <class T>
    T get() {
        T v{};
        if (!f.read(reinterpret_cast<char*>(&v), sizeof v))
            throw std::invalid_argument(path + ": truncated state file");
        return v;
    }
    std::string str() {
        uint64_t n = get<uint64_t>();
        if (n > (1u << 26)) throw std::invalid_argument(path + ": corrupt state file");
        std::string s(n, '\0');
        if (!f.read(s.data(), std::streamsize(n))) throw std::invalid_argument(path + ": truncated state file");
        return s;
    }
};

}   // namespace

void save_state(const std::string& path, const SimResult& r) {
    Writer w{std::ofstream(path + ".tmp", std::ios::binary)};
    if (!w.f) throw std::runtime_error("cannot write " + path);
    w.f.write(kMagic, 8);
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
        w.f.write(reinterpret_cast<const char*>(a.raw.data()), std::streamsize(a.raw.size() * 8));
    }
    w.f.close();
    if (!w.f) throw std::runtime_error("error writing " + path);
    std::rename((path + ".tmp").c_str(), path.c_str());   // a finished state file replaces the old one at once
}

SimResult load_state(const std::string& path) {
    Reader rd{std::ifstream(path, std::ios::binary), path};
    if (!rd.f)
        throw std::invalid_argument("--resume: cannot read " + path +
                                    " (is it the output directory of a simulate run?)");
    char magic[8];
    if (!rd.f.read(magic, 8) || std::memcmp(magic, kMagic, 7) != 0 || magic[7] < kOldestRead || magic[7] > kMagic[7])
        throw std::invalid_argument(path + ": not a gonio state file (or written by another version)");
    const bool has_targets = magic[7] >= '6';
    SimResult r;
    r.stack = parse_stack_string(rd.str(), path + " (stored stack)");
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
    r.n_theta = rd.get<uint32_t>();
    r.n_phi = rd.get<uint32_t>();
    r.n_classes = rd.get<uint32_t>();
    uint64_t n = rd.get<uint64_t>();
    if (n > 1000) throw std::invalid_argument(path + ": corrupt state file");
    r.options.theta_i_deg.clear();
    r.n_sides = r.stack.transmissive() ? 2 : 1;
    const size_t expect = size_t(r.n_classes) * r.n_sides * r.n_theta * r.n_phi * 6;
    for (uint64_t i = 0; i < n; ++i) {
        AngleResult a;
        a.theta_i_deg = rd.get<double>();
        a.paths = rd.get<uint64_t>();
        a.seconds = rd.get<double>();
        a.device_seconds = rd.get<double>();
        for (int64_t& e : a.energy) e = rd.get<int64_t>();
        uint64_t m = rd.get<uint64_t>();
        if (m != expect) throw std::invalid_argument(path + ": corrupt state file (histogram size)");
        a.raw.resize(m);
        if (!rd.f.read(reinterpret_cast<char*>(a.raw.data()), std::streamsize(m * 8)))
            throw std::invalid_argument(path + ": truncated state file");
        r.options.theta_i_deg.push_back(a.theta_i_deg);
        target_paths = has_targets ? target_paths : std::max(target_paths, a.paths);
        r.angles.push_back(std::move(a));
    }
    r.options.paths = target_paths;
    return r;
}

}   // namespace gonio
