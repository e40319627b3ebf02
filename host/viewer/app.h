// app.h: the viewer's state and work, without any drawing: the stack being looked at (and the file it came
// from, watched for edits), the progressive reference for the current incident angle, the models evaluated on
// the reference's bins, what the panels show (bin values, slices, albedos), and saving.
#pragma once
#include "models.h"
#include "user_model.h"
#include "reference_session.h"
#include "stack.h"

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace gonio::view {

struct AppOptions {
    std::string stack_path;
    double theta_i_deg = 30.0;
    double phi_i_deg = 0.0;   // the incident azimuth, degrees in [0, 360)
    uint32_t seed = 1;
    double slice_ms = 10.0;   // device time of one reference slice (one per frame)
    bool belcour_tables = true;
    std::vector<std::string> model_files;   // --model FILE: users' models, recompiled when the file changes
};

// What the panels show, refreshed as the reference accumulates and when the models change.
struct Display {
    uint32_t n_theta = 0, n_phi = 0;
    size_t bin_floats = 0;   // n_theta * n_phi * 3
    // sources: 0 reference, 1 + i model i of the registry; per source and side, bin averages of f (RGB)
    std::vector<std::vector<float>> values;   // [source * 2 + side]; empty when the source has nothing there
    std::vector<glm::dvec3> albedo;   // [source * 2 + side]: directional albedo (R) / transmittance (T)
    uint64_t version = 0;   // bumps when the reference's values change
    uint64_t models_version = 0;   // bumps when the models' values change
    uint64_t paths = 0;
    double median_rse[2] = {0, 0};   // reference, per side
    double mpaths_per_s = 0;   // reference, device throughput of the last slice
};

class App {
public:
    App(VkContext& ctx, const AppOptions& opt);

    // Every frame: collect the finished reference slice, refresh the display, submit the next slice; watch the
    // stack file; re-evaluate the models when due.
    void tick(bool interacting);

    // A changed stack (from the controls, --set or the file): validated; if bad, the previous one stays and the
    // error is shown. Returns whether it was taken.
    bool set_stack(const Stack& s, const std::string& origin);
    void set_theta_i(double deg);
    double theta_i() const { return theta_i_; }
    void set_phi_i(double deg);   // taken modulo 360
    double phi_i() const { return phi_i_; }

    const Stack& stack() const { return stack_; }   // the stack in use (always valid)
    Stack& edit() { return edit_; }   // what the controls edit (may be invalid)
    const std::string& error() const { return error_; }
    const std::string& notice() const { return notice_; }
    void set_notice(const std::string& s) { notice_ = s; }
    const Display& display() const { return display_; }
    bool transmissive() const { return stack_.transmissive(); }
    const std::vector<ModelSlices>& models() const { return models_; }
    double model_seconds() const { return model_seconds_; }
    const std::string& stack_path() const { return opt_.stack_path; }
    // The models shown: the registry's, then the users' files (--model), in that order (Display's sources 1 + m).
    size_t model_count() const;
    const std::string& model_id(size_t m) const;
    std::string model_description(size_t m) const;   // citation and summary, for the tooltip
    // the family it is listed under: a built-in's header's (its variants share it), "your models" for a --model file
    std::string model_family(size_t m) const;
    std::string model_cannot_represent_here(size_t m) const;   // "" where model m represents the stack

    // Saving: write <path> and return it; throw std::runtime_error with the reason.
    std::string save_stack(const std::string& path) const;
    std::string save_exr(const std::string& path);

    // Where a reload of the stack file came from / failed (tests watch stderr for these lines).
    void check_file();
    // The users' model files: a changed file is read and compiled again (a broken edit keeps the previous model
    // and shows why).
    void check_model_files();

private:
    void restart();
    void evaluate_models();
    void refresh_reference();

    VkContext& ctx_;
    AppOptions opt_;
    Stack stack_, edit_;
    double theta_i_, phi_i_;
    std::string error_, notice_;
    ReferenceSession session_;
    ModelEvaluator evaluator_;
    std::vector<ModelSlices> models_;
    bool models_due_ = true;
    double model_seconds_ = 0;
    std::chrono::steady_clock::time_point last_models_{}, last_refresh_{}, last_file_check_{};
    uint64_t slice_paths_ = 16384;
    uint64_t collected_ = 0;
    Display display_;
    std::filesystem::file_time_type file_time_{};
    std::string file_text_;
    struct UserFile {
        std::string path;
        std::filesystem::file_time_type time{};
        std::string text;
    };
    std::vector<UserFile> user_files_;
    ModelOptions model_options_;   // the Belcour tables switch and the users' models
};

// The directional albedo of bin averages f over one hemisphere (sum of f times each bin's projected solid angle).
glm::dvec3 albedo_of(const std::vector<float>& f, uint32_t n_theta, uint32_t n_phi, double dtheta_deg, double dphi_deg);

}   // namespace gonio::view
