// main.cpp — chapter 12's program: a Cornell box, path traced.
//
//   ch12-path-tracing [--spp N] [--seed S] [--estimator nee|bounce] [--sampling cosine|uniform]
//                     [the usual options: --out, --width, --height, --precision, --compare, --view]
//
// Every pixel averages N paths (--spp, default 16), each through a point
// drawn uniformly in the pixel (a box filter), each traced by *your*
// path_radiance. The numbers come from the pixel's own stream
// (pixel_random.hpp), seeded by --seed and the pixel's number: the picture is
// the same on every run and every thread count. --estimator bounce turns
// next-event estimation off (light only when a bounce hits the lamp),
// --sampling uniform bounces uniformly instead of by the cosine: the four
// estimators the lecture compares, all with the same expected picture.
// With --compare the picture is judged by statistics (a noisy picture never
// matches pixel for pixel): common/image_compare.hpp, compare_noisy_images.
#include "cornell_box.hpp"
#include "path_tracing.hpp"
#include "pixel_random.hpp"

#include "common/camera.hpp"
#include "common/program.hpp"
#include "common/render.hpp"

#include <CLI/CLI.hpp>

#include <atomic>
#include <cstdint>

namespace {

using namespace rt;

struct chapter_options {
    std::uint64_t seed = 1;
    std::string estimator = "nee";
    std::string sampling = "cosine";
} chosen;

// Longest path: vertices beyond it are rare (roulette ends most paths after
// a few bounces), and each costs its five numbers whether used or not.
constexpr int max_vertices = 24;

template <class T>
image render_box(const program_options& opt, long& rays) {
    const ch12::path_scene<T> box = ch12::cornell_box<T>();
    const ch12::cornell_view<double> view;
    const vec3d eye = turned_eye(opt.view, view.eye, view.look_at, view.up);
    const pinhole_camera<T> camera(camera_frame<T>::look_at(convert<T>(eye), convert<T>(view.look_at), convert<T>(view.up)),
                                   T(view.vertical_fov_degrees), opt.width, opt.height);
    ch12::path_settings settings;
    settings.next_event = chosen.estimator == "nee";
    settings.cosine_sampling = chosen.sampling == "cosine";
    const interval<T> camera_range{T(1), infinity<T>};  // beyond the image plane (chapter 01)

    image img = render(opt.width, opt.height, [&](int col, int row) {
        ch12::pixel_random random(chosen.seed, std::uint64_t(row) * std::uint64_t(opt.width) + std::uint64_t(col));
        color sum(0.0f);
        for (int k = 0; k < opt.spp; ++k) {
            // A point drawn in the pixel's square: x right, y up, as camera.hpp's pixel centre.
            const T x = (T(col) + random.uniform<T>()) / T(opt.width) * T(2) - T(1);
            const T y = T(1) - (T(row) + random.uniform<T>()) / T(opt.height) * T(2);
            const vec3<T> on_plane = x * camera.half_height * camera.aspect() * camera.frame.u +
                                     y * camera.half_height * camera.frame.v - camera.frame.w;
            const ray<T> r{camera.frame.eye, on_plane};
            sum += ch12::path_radiance(box, r, camera_range, random.path_numbers<T>(max_vertices), settings);
        }
        return sum / float(opt.spp);
    });
    rays = long(opt.width) * opt.height * opt.spp;  // paths, not rays: the report's figure is paths/s
    return img;
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch12";
    program.title = "path tracing";
    program.default_width = 160;
    program.default_height = 160;
    program.default_spp = 16;  // --spp N (common/program.hpp)
    program.noisy_picture = true;
    program.render = rt::by_precision(render_box<float>, render_box<double>);
    program.add_options = [](CLI::App& app) {
        app.add_option("--seed", chosen.seed, "seed of every pixel's random stream")->capture_default_str();
        app.add_option("--estimator", chosen.estimator, "nee: sample the light at every bounce; bounce: only by hitting it")
            ->check(CLI::IsMember({"nee", "bounce"}))
            ->capture_default_str();
        app.add_option("--sampling", chosen.sampling, "how a bounce draws its direction")
            ->check(CLI::IsMember({"cosine", "uniform"}))
            ->capture_default_str();
    };
    return rt::run_chapter_program(argc, argv, program);
}
