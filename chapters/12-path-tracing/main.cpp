// main.cpp — chapter 12's program: a Cornell box, path traced.
//
//   ch12-path-tracing [--spp N] [--seed S] [--estimator nee|bounce] [--sampling cosine|uniform]
//                     [--scene FILE] [the usual options: --out, --width, --height, --precision, --compare, --view]
//
// The scene is scenes/ch12-cornell-box.json (or --scene FILE), made into the
// path tracer's world by path_scene_of (path_scene.hpp), which says what a
// file may hold that a path tracer of matte surfaces leaves out; the program
// names what it leaves out of the file it draws.
//
// Every pixel averages N paths (--spp, default 16), each through a point
// drawn uniformly in the pixel (a box filter), each traced by *your*
// path_radiance (picture.hpp). The numbers come from the pixel's own stream
// (pixel_random.hpp), seeded by --seed and the pixel's number: the picture is
// the same on every run and every thread count. --estimator bounce turns
// next-event estimation off (light only when a bounce hits the lamp),
// --sampling uniform bounces uniformly instead of by the cosine: the four
// estimators the lecture compares, all with the same expected picture.
// With --compare the picture is judged by statistics (a noisy picture never
// matches pixel for pixel): common/image_compare.hpp, compare_noisy_images.
#include "picture.hpp"

#include "common/program.hpp"
#include "common/scene_file.hpp"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace {

using namespace rt;

struct chapter_options {
    std::uint64_t seed = 1;
    std::string estimator = "nee";
    std::string sampling = "cosine";
} chosen;

// Says on stderr what of the file the path tracer leaves out (path_scene_of).
void say_what_is_left_out(const scene_description& d) {
    int points = 0, highlights = 0, mirrors = 0, checkers = 0;
    for (const point_light& l : d.world.lights) points += !(l.radius > 0);
    for (const material& m : d.world.materials) {
        highlights += m.specular.r > 0 || m.specular.g > 0 || m.specular.b > 0;
        mirrors += m.mirror.r > 0 || m.mirror.g > 0 || m.mirror.b > 0;
        checkers += m.checker;
    }
    std::string out;
    const auto note = [&](int n, const char* what) {
        if (n > 0) out += (out.empty() ? "" : ", ") + std::to_string(n) + " " + what;
    };
    note(points, points > 1 ? "point lights (no area: no path can hit one)" : "point light (no area: no path can hit it)");
    note(highlights, highlights > 1 ? "materials' highlights" : "material's highlight");
    note(mirrors, mirrors > 1 ? "materials' mirrors" : "material's mirror");
    note(checkers, checkers > 1 ? "materials' checker patterns" : "material's checker pattern");
    if (d.camera.aperture > 0) out += std::string(out.empty() ? "" : ", ") + "the camera's lens (a pinhole here)";
    if (!out.empty()) std::fprintf(stderr, "ch12: the scene's %s are left out (matte surfaces only)\n", out.c_str());
}

template <class T>
image render_box(const program_options& opt, long& rays) {
    // The camera is the file's, already turned by --view (common/program.hpp).
    const pinhole_camera<T> camera = ch12::path_camera<T>(opt.scene, opt.width, opt.height);
    say_what_is_left_out(opt.scene);
    const ch12::path_scene<T> box = ch12::path_scene_of<T>(opt.scene);
    ch12::picture_settings how;
    how.paths = opt.spp;
    how.seed = chosen.seed;
    how.estimator.next_event = chosen.estimator == "nee";
    how.estimator.cosine_sampling = chosen.sampling == "cosine";
    image img = ch12::render_picture(box, camera, how);
    rays = long(opt.width) * opt.height * opt.spp;  // paths, not rays: the report's figure is paths/s
    return img;
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch12";
    program.title = "path tracing";
    program.draws_scene = true;
    program.draws_triangles = false;  // the path tracer's world is spheres and planes
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
