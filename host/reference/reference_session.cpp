// reference_session.cpp: ReferenceSession, the walk runner with shaders/simulate.comp kept alive, in slices that do
// not block the host.
#include "reference_session.h"
#include "compute_kernel.h"
#include "histogram.h"
#include "stack_gpu.h"
#include "vk_context.h"
#include "walk_runner.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>
#include <tuple>

#include "walk_spirv.h"

namespace gonio {

struct ReferenceSession::Impl {
    VkContext& ctx;
    SessionOptions opt;
    WalkGrid grid;   // both sides: the capacity
    size_t n_active = 0;   // values of the current stack's sides (an opaque stack has no transmission bins)
    WalkRunner runner;
    // simulate.comp pipelines by specialisation (one entry for the general walk)
    std::map<std::tuple<uint32_t, uint32_t, uint32_t, uint32_t, uint32_t, uint32_t, uint32_t, uint32_t, bool, bool>,
             std::unique_ptr<ComputeKernel>>
        sims;
    ComputeKernel* sim = nullptr;
    WalkPush pc{};
    bool started = false, in_flight = false;
    uint64_t done = 0, flight_paths = 0, last_paths = 0;
    uint64_t staged = 0;   // paths in the staging histogram, not yet folded into the totals
    uint32_t staging_shift = 0;   // the staging holds weights x 2^-shift (the Lambertian series; fold.comp)
    uint64_t readable = 0;   // paths in the readback copy
    bool flight_readback = false;
    double last_device = 0, device_total = 0;
    SimResult res;

    static SimOptions sim_options(const SessionOptions& o) {
        SimOptions so;
        so.dtheta_deg = o.dtheta_deg;
        so.dphi_deg = o.dphi_deg;
        so.max_events = o.max_events;
        so.paths_per_invocation = o.paths_per_invocation;
        validate_options(so);
        return so;
    }

    Impl(VkContext& c, const SessionOptions& o, const SimOptions& so)
        : ctx(c),
          opt(o),
          grid(walk_grid(o.dtheta_deg, o.dphi_deg, false, true)),
          runner(c, grid.values(), 1, vk::DescriptorType::eUniformBuffer, sizeof(StackGpu),
                 "a grid of " + std::to_string(grid.n_theta) + " x " + std::to_string(grid.n_phi) + " bins") {
        res.options = so;
        res.options.theta_i_deg = {0.0};
        res.options.seed = o.seed;
        res.options.specialised = o.specialised;
        res.device = ctx.device_info().name;
        res.driver = ctx.driver_string();
        res.n_theta = grid.n_theta;
        res.n_phi = grid.n_phi;
        res.n_classes = 1;
        res.angles.resize(1);
    }

    // azimuth: the walk's kernel for an incident azimuth other than 0 (SPEC_INCIDENT_AZIMUTH)
    ComputeKernel* pipeline_for(const WalkSpec& spec, bool azimuth) {
        // the general walk reads everything from the uniform block: one pipeline for every stack
        auto key = opt.specialised
                       ? std::make_tuple(spec.layer_count, spec.base_kind, spec.rough_mask, spec.absorb_mask,
                                         spec.scatter_mask, spec.microsurface_mask, spec.multiple_mask,
                                         spec.microflake_mask, spec.series, azimuth)
                       : std::make_tuple(0u, 0u, 0u, 0u, spec.scatter_mask != 0 ? 1u : 0u,
                                         spec.microsurface_mask != 0 ? 1u : 0u, spec.multiple_mask != 0 ? 1u : 0u,
                                         spec.microflake_mask != 0 ? 1u : 0u, false, azimuth);
        auto& k = sims[key];
        if (!k) {
            // the general walk: one pipeline for every stack, with the free-flight code where the stack scatters
            const WalkSpec ws = opt.specialised ? spec
                                                : WalkSpec{.specialised = false,
                                                           .layer_count = 2,
                                                           .scatter_mask = spec.scatter_mask,
                                                           .microsurface_mask = spec.microsurface_mask,
                                                           .multiple_mask = spec.multiple_mask,
                                                           .microflake_mask = spec.microflake_mask};
            const Spirv spv = walk_spirv(ws, WalkShader::one_stack);
            k = runner.make_kernel(spv.words, spv.bytes);
            build_walk_kernel(*k, ctx.device(), ws, false, opt.paths_per_invocation, azimuth);
        }
        return k.get();
    }

    void collect() {
        if (!in_flight) return;
        runner.wait();
        finish();
    }
    void finish() {
        last_device = runner.timer_seconds();
        device_total += last_device;
        done += flight_paths;
        if (flight_readback) readable = done;
        last_paths = flight_paths;
        flight_paths = 0;
        in_flight = false;
    }
};

ReferenceSession::ReferenceSession(VkContext& ctx, const SessionOptions& opt)
    : impl_(std::make_unique<Impl>(ctx, opt, Impl::sim_options(opt))) {}

ReferenceSession::~ReferenceSession() {
    if (impl_) impl_->collect();
}

void ReferenceSession::restart(const Stack& stack, double theta_i_deg, double phi_i_deg) {
    Impl& m = *impl_;
    validate_stack(stack);
    if (!(theta_i_deg >= 0.0 && theta_i_deg < 90.0))
        throw std::invalid_argument("incident angle must be in [0, 90) degrees, got " + std::to_string(theta_i_deg));
    if (!(phi_i_deg >= 0.0 && phi_i_deg < 360.0))
        throw std::invalid_argument("incident azimuth must be in [0, 360) degrees, got " + std::to_string(phi_i_deg));
    m.collect();
    const WalkStack walk = walk_stack_for(stack, m.res.options);   // res.options.specialised: the session's
    m.sim = m.pipeline_for(walk.spec, phi_i_deg != 0.0);
    m.staging_shift = uint32_t(walk.staging_shift);
    m.res.n_sides = stack.transmissive() ? 2 : 1;
    m.n_active = size_t(m.res.n_sides) * m.grid.n_theta * m.grid.n_phi * 6;
    std::memcpy(m.runner.stack_mapped(), &walk.gpu, sizeof(walk.gpu));
    m.runner.clear();
    // stream 0: one incident angle
    m.pc =
        walk_push(m.grid, m.opt.dtheta_deg, m.opt.dphi_deg, m.opt.max_events, theta_i_deg, phi_i_deg, m.opt.seed, 0u);
    m.done = 0;
    m.staged = 0;
    m.readable = 0;
    m.device_total = 0;
    m.last_device = 0;
    m.last_paths = 0;
    m.res.stack = stack;
    m.res.walk = walk_ran(walk, m.res.options, false);   // the viewer reads the stack from its buffer
    m.res.options.theta_i_deg = {theta_i_deg};
    m.res.options.phi_i_deg = phi_i_deg;
    m.res.angles.assign(1, AngleResult{});
    m.res.angles[0].theta_i_deg = theta_i_deg;
    m.res.angles[0].phi_i_deg = phi_i_deg;
    m.started = true;
}

bool ReferenceSession::submit(uint64_t paths, bool readback) {
    Impl& m = *impl_;
    if (!m.started) throw std::logic_error("ReferenceSession::submit before restart");
    if (m.in_flight) return false;
    const WalkDispatch wd(m.opt.paths_per_invocation);
    const uint64_t per_group = wd.per_group, max_batch = wd.max_paths;
    const uint64_t n = std::clamp<uint64_t>((paths + per_group - 1) / per_group * per_group, per_group, max_batch);
    m.pc.path_base_lo = uint32_t(m.done);
    m.pc.path_base_hi = uint32_t(m.done >> 32);
    m.pc.path_count = uint32_t(n);
    WalkRunner& r = m.runner;
    r.angles_mapped()[0] = walk_angle(m.pc, 0);   // one incident angle: workgroup row 0, histograms of slot 0
    vk::CommandBuffer c = r.begin();
    r.record_start_timer(c);
    // the previous slices' atomics, fold and readback copy touch what this slice's dispatches touch
    r.record_barrier(c);
    auto fold = [&] {
        r.record_fold(c, m.n_active / 2, m.staging_shift);
        m.staged = 0;
    };
    // the packed staging sums must not carry (bins.glsl): at most MAX_PATHS_PER_DISPATCH paths between folds
    if (m.staged + n > MAX_PATHS_PER_DISPATCH) {
        fold();
        r.record_barrier(c);
    }
    r.record_walk(c, *m.sim, m.pc, wd.groups(n), 1);
    m.staged += n;
    if (readback) {
        r.record_barrier(c);
        fold();
        r.record_copy_to_host(c, m.n_active);
    }
    r.record_stop_timer(c);
    r.submit();
    m.in_flight = true;
    m.flight_paths = n;
    m.flight_readback = readback;
    return true;
}

bool ReferenceSession::poll() {
    Impl& m = *impl_;
    if (!m.in_flight) return true;
    if (!m.runner.done()) return false;
    m.finish();
    return true;
}

void ReferenceSession::wait() { impl_->collect(); }

uint64_t ReferenceSession::paths() const { return impl_->done; }
uint64_t ReferenceSession::readable_paths() const { return impl_->readable; }
double ReferenceSession::last_slice_device_seconds() const { return impl_->last_device; }
uint64_t ReferenceSession::last_slice_paths() const { return impl_->last_paths; }
double ReferenceSession::device_seconds() const { return impl_->device_total; }
bool ReferenceSession::busy() const { return impl_->in_flight; }

const SimResult& ReferenceSession::result() {
    Impl& m = *impl_;
    if (m.in_flight) throw std::logic_error("ReferenceSession::result while a slice is in flight");
    AngleResult& a = m.res.angles[0];
    const AngleResult copy = m.runner.angle(0, m.readable, m.n_active);
    a.paths = copy.paths;
    a.raw = copy.raw;
    std::memcpy(a.energy, copy.energy, sizeof(a.energy));
    a.device_seconds = m.device_total;
    m.res.options.paths = std::max<uint64_t>(m.readable, 1);
    return m.res;
}

}   // namespace gonio
