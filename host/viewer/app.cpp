#include "app.h"
#include "histogram.h"
#include "output.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace gonio::view {

namespace {

constexpr double kDtheta = 1.0, kDphi = 2.0;   // the CLI's default bins

std::vector<float> to_floats(const std::vector<glm::dvec3>& v) {
    std::vector<float> out(v.size() * 3);
    for (size_t i = 0; i < v.size(); ++i)
        for (int c = 0; c < kChannels; ++c) out[3 * i + c] = std::isfinite(v[i][c]) ? float(v[i][c]) : 0.0f;
    return out;
}

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot read the stack file");
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}   // namespace

glm::dvec3 albedo_of(const std::vector<float>& f, uint32_t n_theta, uint32_t n_phi, double dtheta_deg,
                     double dphi_deg) {
    glm::dvec3 sum(0.0);
    if (f.size() < size_t(n_theta) * n_phi * 3) return sum;
    for (uint32_t t = 0; t < n_theta; ++t) {
        double lo = t * dtheta_deg * M_PI / 180.0, hi = (t + 1) * dtheta_deg * M_PI / 180.0;
        double omega = 0.5 * (std::sin(hi) * std::sin(hi) - std::sin(lo) * std::sin(lo)) * dphi_deg * M_PI / 180.0;
        for (uint32_t p = 0; p < n_phi; ++p)
            for (int c = 0; c < kChannels; ++c) sum[c] += double(f[(size_t(t) * n_phi + p) * 3 + c]) * omega;
    }
    return sum;
}

App::App(VkContext& ctx, const AppOptions& opt)
    : ctx_(ctx),
      opt_(opt),
      theta_i_(opt.theta_i_deg),
      phi_i_(opt.phi_i_deg),
      session_(ctx, SessionOptions{.seed = opt.seed, .dtheta_deg = kDtheta, .dphi_deg = kDphi}),
      evaluator_(ctx) {
    file_text_ = read_text(opt.stack_path);
    stack_ = parse_stack_string(file_text_, opt.stack_path);   // a bad file at startup is an error (StackError)
    stack_.source_path = opt.stack_path;
    edit_ = stack_;
    std::error_code ec;
    file_time_ = std::filesystem::last_write_time(opt.stack_path, ec);
    if (!(theta_i_ >= 0.0 && theta_i_ < 90.0)) throw std::invalid_argument("--theta-i must be in [0, 90) degrees");
    if (!(phi_i_ >= 0.0 && phi_i_ < 360.0)) throw std::invalid_argument("--phi-i must be in [0, 360) degrees");
    display_.n_theta = uint32_t(std::lround(90.0 / kDtheta));
    display_.n_phi = uint32_t(std::lround(360.0 / kDphi));
    display_.bin_floats = size_t(display_.n_theta) * display_.n_phi * 3;
    model_options_.belcour_tables = opt.belcour_tables;
    for (const std::string& f : opt.model_files) {   // refused at start (FILE:LINE), as gonio compare does
        UserFile u;
        u.path = f;
        u.time = std::filesystem::last_write_time(f, ec);
        model_options_.user_models.push_back(load_user_model(f));
        u.text = model_options_.user_models.back()->text;
        user_files_.push_back(u);
    }
    const size_t sources = 1 + model_count();
    display_.values.assign(sources * 2, {});
    display_.albedo.assign(sources * 2, glm::dvec3(0.0));
    restart();
}

void App::restart() {
    session_.restart(stack_, theta_i_, phi_i_);
    display_.values[0].assign(display_.bin_floats, 0.0f);
    display_.values[1] = transmissive() ? std::vector<float>(display_.bin_floats, 0.0f) : std::vector<float>{};
    display_.albedo[0] = display_.albedo[1] = glm::dvec3(0.0);
    display_.paths = 0;
    collected_ = 0;
    last_refresh_ = {};
    display_.median_rse[0] = display_.median_rse[1] = 0.0;
    display_.version++;
    models_due_ = true;
}

bool App::set_stack(const Stack& s, const std::string& origin) {
    try {
        validate_stack(s);
    } catch (const StackError& e) {
        error_ = std::string(e.what()) + " (" + origin + "; keeping the previous stack)";
        std::fprintf(stderr, "gonio-view: %s\n", error_.c_str());
        return false;
    }
    stack_ = s;
    edit_ = s;
    error_.clear();
    restart();
    return true;
}

void App::set_theta_i(double deg) {
    deg = std::clamp(deg, 0.0, 89.9);
    if (deg == theta_i_) return;
    theta_i_ = deg;
    restart();
}

void App::set_phi_i(double deg) {
    deg = std::fmod(deg, 360.0);
    if (deg < 0.0) deg += 360.0;
    if (!(deg < 360.0)) deg = 0.0;   // fmod of a value just below 0 rounds to 360
    if (deg == phi_i_) return;
    phi_i_ = deg;
    restart();
}

size_t App::model_count() const { return model_registry().size() + model_options_.user_models.size(); }
const std::string& App::model_id(size_t m) const {
    const size_t n = model_registry().size();
    return m < n ? model_registry()[m].id : model_options_.user_models.at(m - n)->header.id;
}
std::string App::model_description(size_t m) const {
    const size_t n = model_registry().size();
    if (m < n) return model_registry()[m].citation + "\n" + model_registry()[m].summary;
    const auto& h = model_options_.user_models.at(m - n)->header;
    return h.citation + "\n" + h.path;
}
std::string App::model_family(size_t m) const {
    return m < model_registry().size() ? model_registry()[m].header.family : "your models";
}
std::string App::model_cannot_represent_here(size_t m) const {
    const size_t n = model_registry().size();
    return m < n ? model_cannot_represent(m, stack_)
                 : model_file_cannot_represent(model_options_.user_models.at(m - n)->header, stack_);
}

void App::check_model_files() {
    for (size_t i = 0; i < user_files_.size(); ++i) {
        UserFile& u = user_files_[i];
        std::error_code ec;
        auto t = std::filesystem::last_write_time(u.path, ec);
        if (ec || t == u.time) continue;
        std::string text;
        try {
            text = read_text(u.path);
        } catch (const std::exception&) {
            continue;   // being replaced: try again later
        }
        u.time = t;
        if (text == u.text) continue;
        u.text = text;
        try {
            auto m = compile_user_model(text, u.path);
            if (m->header.id != model_options_.user_models[i]->header.id)
                throw std::invalid_argument(u.path + ": the model's id changed from '" +
                                            model_options_.user_models[i]->header.id + "' to '" + m->header.id +
                                            "' (restart gonio-view for a new model)");
            model_options_.user_models[i] = m;
            models_due_ = true;
            error_.clear();
            std::fprintf(stderr, "gonio-view: recompiled %s (%.2f s)\n", u.path.c_str(), m->compile_seconds);
        } catch (const std::exception& e) {   // StackError (header) or the compiler's FILE:LINE messages
            error_ = std::string(e.what()) + " (the model file changed; keeping the previous model)";
            std::fprintf(stderr, "gonio-view: %s\n", error_.c_str());
        }
    }
}

void App::check_file() {
    last_file_check_ = std::chrono::steady_clock::now();
    std::error_code ec;
    auto t = std::filesystem::last_write_time(opt_.stack_path, ec);
    if (ec || t == file_time_) return;
    std::string text;
    try {
        text = read_text(opt_.stack_path);
    } catch (const std::exception&) {
        return;   // being replaced: try again later
    }
    file_time_ = t;
    if (text == file_text_) return;
    file_text_ = text;
    try {
        Stack s = parse_stack_string(text, opt_.stack_path);
        s.source_path = opt_.stack_path;
        if (set_stack(s, "reloaded")) std::fprintf(stderr, "gonio-view: reloaded %s\n", opt_.stack_path.c_str());
    } catch (const StackError& e) {
        error_ = std::string(e.what()) + " (the file changed; keeping the previous stack)";
        std::fprintf(stderr, "gonio-view: %s\n", error_.c_str());
    }
}

void App::refresh_reference() {
    const SimResult& r = session_.result();
    const AngleResult& a = r.angles[0];
    for (int side = 0; side < (transmissive() ? 2 : 1); ++side) {
        Slice s = make_slice(r, a, Side(side));
        display_.values[side] = to_floats(s.f);
        display_.median_rse[side] = median_relative_se(r, a, side);
    }
    EnergyBook e = energy_book(r, 0);
    display_.albedo[0] = e.reflected;
    display_.albedo[1] = e.transmitted;
    display_.paths = a.paths;
    display_.version++;
}

void App::evaluate_models() {
    auto t0 = std::chrono::steady_clock::now();
    ModelGrid grid{display_.n_theta, display_.n_phi, kDtheta, kDphi, {theta_i_}, phi_i_};
    try {
        models_ = evaluator_.evaluate(stack_, grid, nullptr, model_options_);
    } catch (const std::exception& e) {
        error_ = std::string("models: ") + e.what();
        models_.clear();
    }
    for (size_t m = 0; m < model_count(); ++m) {
        auto& vr = display_.values[2 * (1 + m)];
        auto& vt = display_.values[2 * (1 + m) + 1];
        vr.clear();
        vt.clear();
        if (m < models_.size() && model_has_bins(models_[m])) {
            if (!models_[m].f.empty()) vr = to_floats(models_[m].f[0]);
            if (!models_[m].t.empty() && !models_[m].t[0].empty()) vt = to_floats(models_[m].t[0]);
        }
        display_.albedo[2 * (1 + m)] = albedo_of(vr, display_.n_theta, display_.n_phi, kDtheta, kDphi);
        display_.albedo[2 * (1 + m) + 1] = albedo_of(vt, display_.n_theta, display_.n_phi, kDtheta, kDphi);
    }
    models_due_ = false;
    last_models_ = std::chrono::steady_clock::now();
    model_seconds_ = std::chrono::duration<double>(last_models_ - t0).count();
    display_.models_version++;
}

void App::tick(bool interacting) {
    auto now = std::chrono::steady_clock::now();
    if (session_.poll()) {
        if (session_.paths() != collected_) {
            collected_ = session_.paths();
            // the next slice: about slice_ms of device time at the last slice's rate
            double dev = session_.last_slice_device_seconds();
            if (dev > 0 && session_.last_slice_paths() > 0) {
                double rate = double(session_.last_slice_paths()) / dev;
                display_.mpaths_per_s = rate * 1e-6;
                double want = rate * opt_.slice_ms * 1e-3;
                slice_paths_ = uint64_t(std::clamp(want, 1024.0, std::max(1024.0, double(slice_paths_) * 2.0)));
            }
        }
        if (session_.readable_paths() != display_.paths) refresh_reference();
        // the sums are read back (a pass over every bin, on the device and here) ten times a second
        const bool readback = now - last_refresh_ > std::chrono::milliseconds(100);
        if (readback) last_refresh_ = now;
        session_.submit(slice_paths_, readback);
    }
    if (models_due_ && (!interacting || now - last_models_ > std::chrono::milliseconds(400))) evaluate_models();
    if (now - last_file_check_ > std::chrono::milliseconds(300)) {
        check_file();
        check_model_files();
    }
}

std::string App::save_stack(const std::string& path) const {
    std::string text = stack_to_toml(stack_);
    parse_stack_string(text, path);   // round trip: what we write reads back
    std::filesystem::path p(path);
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
    std::ofstream out(path, std::ios::binary);
    if (!(out << text)) throw std::runtime_error(path + ": cannot write");
    return path;
}

std::string App::save_exr(const std::string& path) {
    session_.wait();
    if (models_due_) evaluate_models();
    SimResult r = session_.result();
    r.stack.source_text = stack_to_toml(stack_);
    std::filesystem::path p(path);
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
    write_exr(path, r, &models_);
    return path;
}

}   // namespace gonio::view
