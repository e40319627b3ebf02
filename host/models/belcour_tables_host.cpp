#include "belcour_tables_host.h"
#include "compute_kernel.h"
#include "model_twin.h"
#include "tables_spv.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <unistd.h>

namespace gonio {

namespace {

// ---- the on-disk cache of Belcour tables -------------------------------------------------------------------
// $GONIO_CACHE_DIR, else $XDG_CACHE_HOME/gonio, else $HOME/.cache/gonio; GONIO_NO_CACHE=1 turns it off (the
// tests do). A file holds one stack's tables, named by a hash of what they depend on: the interfaces' (kind,
// eta, k) and the SPIR-V of the shader that computes them, so any change to the table code misses the cache.
// The file repeats the key, which is checked on reading; a file that does not match is ignored and replaced.
std::string table_cache_dir() {
    const char* off = std::getenv("GONIO_NO_CACHE");
    if (off && *off && std::string(off) != "0") return "";
    if (const char* d = std::getenv("GONIO_CACHE_DIR"); d && *d) return d;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/gonio";
    if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/gonio";
    return "";
}
uint64_t fnv1a(const void* data, size_t n, uint64_t h = 1469598103934665603ull) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}
std::string table_cache_file(const std::string& key) {
    std::string dir = table_cache_dir();
    if (dir.empty()) return "";
    uint64_t h = fnv1a(tables_spv, sizeof(tables_spv));
    h = fnv1a(key.data(), key.size(), h);
    char name[64];
    std::snprintf(name, sizeof name, "/belcour-tables-%016llx.bin", (unsigned long long)h);
    return dir + name;
}
const char kTableMagic[8] = {'G', 'O', 'N', 'I', 'O', 'T', 'B', '1'};
bool load_cached_tables(const std::string& key, std::vector<float>& out) {
    std::string path = table_cache_file(key);
    if (path.empty()) return false;
    std::ifstream f(path, std::ios::binary);
    if (!f) return false;
    char magic[8];
    uint64_t klen = 0, spv = 0;
    if (!f.read(magic, 8) || std::memcmp(magic, kTableMagic, 8) != 0) return false;
    if (!f.read(reinterpret_cast<char*>(&spv), 8) || spv != fnv1a(tables_spv, sizeof(tables_spv))) return false;
    if (!f.read(reinterpret_cast<char*>(&klen), 8) || klen != key.size()) return false;
    std::string k(klen, '\0');
    if (!f.read(k.data(), std::streamsize(klen)) || k != key) return false;
    out.assign(TABLE_FLOATS, 0.0f);
    if (!f.read(reinterpret_cast<char*>(out.data()), std::streamsize(TABLE_FLOATS * 4))) return false;
    for (float v : out)
        if (!std::isfinite(v)) return false;
    return true;
}
void store_cached_tables(const std::string& key, const std::vector<float>& t) {
    std::string path = table_cache_file(key);
    if (path.empty()) return;
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
    std::string tmp = path + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream f(tmp, std::ios::binary);
        uint64_t spv = fnv1a(tables_spv, sizeof(tables_spv)), klen = key.size();
        f.write(kTableMagic, 8);
        f.write(reinterpret_cast<const char*>(&spv), 8);
        f.write(reinterpret_cast<const char*>(&klen), 8);
        f.write(key.data(), std::streamsize(klen));
        f.write(reinterpret_cast<const char*>(t.data()), std::streamsize(t.size() * 4));
        if (!f) {
            static bool warned = false;
            if (!warned)
                std::fprintf(stderr, "gonio: warning: cannot write the table cache %s (computing tables each run)\n",
                             path.c_str());
            warned = true;
            std::filesystem::remove(tmp, ec);
            return;
        }
    }
    std::filesystem::rename(tmp, path, ec);   // atomic: readers see the old file or the whole new one
    if (ec) std::filesystem::remove(tmp, ec);
}

// The key of a stack's Belcour tables: what they depend on (each interface's kind, eta, k).
std::string table_key(const StackGpu& g) {
    std::string k;
    for (uint32_t i = 0; i < stack_layer_count(g.info); ++i) {
        const LayerGpu& L = g.layers[i];
        const glm::vec3 n = layer_conductor_eta(L), kk = layer_conductor_k(L);
        float v[8] = {float(layer_kind(L)), layer_eta(L), n.x, n.y, n.z, kk.x, kk.y, kk.z};
        k.append(reinterpret_cast<const char*>(v), sizeof v);
    }
    return k;
}

// One set of the stack's tables on the CPU twin, as tables.comp computes it (set 0: separable G, set 1:
// height-correlated G2), into t (TABLE_FLOATS floats).
void fill_table_set(const StackGpu& sg, uint32_t layers, uint32_t set, std::vector<float>& t) {
    const uint32_t per_layer = TABLE_NMU * TABLE_NALPHA, total = layers * per_layer;
    std::atomic<uint32_t> next{0};
    auto work = [&] {
        for (uint32_t id; (id = next++) < total;) {
            uint32_t layer = id / per_layer, r = id - layer * per_layer, a = r / TABLE_NMU, c = r - a * TABLE_NMU;
            vec4 e = belcour_table_entry(sg.layers[layer], table_node_mu(c), table_node_alpha(a), set == 1);
            uint32_t f = set * TABLE_SET_FLOATS + layer * TABLE_FGD_STRIDE + r * 3;
            t[f] = e.x;
            t[f + 1] = e.y;
            t[f + 2] = e.z;
            t[set * TABLE_SET_FLOATS + TABLE_TIR_OFFSET + layer * per_layer + r] = e.w;
        }
    };
    std::vector<std::thread> pool;
    for (unsigned i = 0; i < std::max(1u, std::thread::hardware_concurrency()); ++i) pool.emplace_back(work);
    for (auto& th : pool) th.join();
}

}   // namespace

// The CPU twin's tables for the last stack seen, per thread; each set computed when a model first reads it
// (convention: the reader's CONVENTION_* bits).
const std::vector<float>& belcour_tables_cpu_cached(const StackGpu& sg, uint32_t convention) {
    static thread_local std::string key;
    static thread_local std::vector<float> tables;
    static thread_local bool have[TABLE_SETS] = {false, false};
    std::string k = table_key(sg);
    if (k != key || tables.empty()) {
        tables.assign(TABLE_FLOATS, 0.0f);
        have[0] = have[1] = false;
        key = k;
    }
    const uint32_t set = (convention & CONVENTION_G2) != 0 ? 1 : 0;
    if (!have[set]) {
        fill_table_set(sg, stack_layer_count(sg.info), set, tables);
        have[set] = true;
    }
    return tables;
}

std::vector<float> belcour_tables_cpu(const StackGpu& sg) {
    std::vector<float> t(TABLE_FLOATS, 0.0f);
    for (uint32_t set = 0; set < TABLE_SETS; ++set) fill_table_set(sg, stack_layer_count(sg.info), set, t);
    return t;
}

BelcourTableGeometry belcour_table_geometry() { return {TABLE_NMU, TABLE_NALPHA}; }
double belcour_table_mu(uint32_t c) { return table_node_mu(c); }
double belcour_table_alpha(uint32_t a) { return table_node_alpha(a); }
glm::dvec3 belcour_table_fgd(const std::vector<float>& t, uint32_t layer, uint32_t a, uint32_t c, bool g2) {
    size_t i = (g2 ? TABLE_SET_FLOATS : 0) + layer * TABLE_FGD_STRIDE + (a * TABLE_NMU + c) * 3;
    return {t.at(i), t.at(i + 1), t.at(i + 2)};
}
double belcour_table_tir(const std::vector<float>& t, uint32_t layer, uint32_t a, uint32_t c, bool g2) {
    return t.at((g2 ? TABLE_SET_FLOATS : 0) + TABLE_TIR_OFFSET + layer * TABLE_NMU * TABLE_NALPHA + a * TABLE_NMU + c);
}

struct BelcourTableKernel::Impl {
    VkContext& ctx;
    std::unique_ptr<ComputeKernel> kernel;
    vk::raii::QueryPool queries = nullptr;
    std::map<std::string, std::vector<float>> cache;
    double seconds = 0.0;

    explicit Impl(VkContext& c) : ctx(c) {
        queries = vk::raii::QueryPool(ctx.device(),
                                      vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = 2});
    }

    const std::vector<float>& tables(const StackGpu& sg) {
        std::string key = table_key(sg);
        auto it = cache.find(key);
        if (it != cache.end()) return it->second;
        std::vector<float> cached;
        if (load_cached_tables(key, cached)) return cache.emplace(key, std::move(cached)).first->second;
        auto& dev = ctx.device();
        if (!kernel) {
            std::vector<vk::DescriptorType> types(TABLES_BINDINGS);   // indexed by binding (kernel_interface.glsl)
            types[TABLES_BINDING_STACK] = vk::DescriptorType::eUniformBuffer;
            types[TABLES_BINDING_OUT] = vk::DescriptorType::eStorageBuffer;
            kernel = std::make_unique<ComputeKernel>(
                dev, tables_spv, sizeof(tables_spv), types,
                4u);   // tables.comp reads no push constants; a pipeline layout's range is never empty
            kernel->build(dev, {}, nullptr, 0);
        }
        Buffer u = ctx.make_buffer(sizeof(StackGpu), vk::BufferUsageFlagBits::eUniformBuffer, true);
        std::memcpy(u.mapped, &sg, sizeof sg);
        Buffer out = ctx.make_buffer(TABLE_FLOATS * 4, vk::BufferUsageFlagBits::eStorageBuffer, false);
        std::memset(out.mapped, 0, TABLE_FLOATS * 4);
        std::vector<const Buffer*> bound(TABLES_BINDINGS);
        bound[TABLES_BINDING_STACK] = &u;
        bound[TABLES_BINDING_OUT] = &out;
        kernel->bind(dev, bound);
        uint32_t invocations =
            TABLE_SETS * stack_layer_count(sg.info) * TABLE_NMU * TABLE_NALPHA;   // both sets (tables.comp)
        ctx.run_now([&](vk::CommandBuffer c) {
            c.resetQueryPool(*queries, 0, 2);
            c.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries, 0);
            c.bindPipeline(vk::PipelineBindPoint::eCompute, kernel->pipeline());
            c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, kernel->layout(), 0, {*kernel->set}, nullptr);
            c.dispatch((invocations + MODEL_GROUP_SIZE - 1) / MODEL_GROUP_SIZE, 1, 1);
            c.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries, 1);
            vk::MemoryBarrier read{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                   .dstAccessMask = vk::AccessFlagBits::eHostRead};
            c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eHost, {}, read,
                              nullptr, nullptr);
        });
        auto [qr, ts] = queries.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                                                     vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
        seconds += double(ts[1] - ts[0]) * ctx.timestamp_period_ns() * 1e-9;
        const float* p = static_cast<const float*>(out.mapped);
        const std::vector<float>& t = cache.emplace(key, std::vector<float>(p, p + TABLE_FLOATS)).first->second;
        store_cached_tables(key, t);
        return t;
    }
};

BelcourTableKernel::BelcourTableKernel(VkContext& ctx) : impl_(std::make_unique<Impl>(ctx)) {}
BelcourTableKernel::~BelcourTableKernel() = default;
const std::vector<float>& BelcourTableKernel::tables(const StackGpu& sg) { return impl_->tables(sg); }
double BelcourTableKernel::seconds() const { return impl_->seconds; }

}   // namespace gonio
