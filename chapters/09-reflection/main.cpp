// main.cpp — chapter 09's program: Whitted's scene, a glass ball and a
// mirror ball over a checkered floor, lit by two lights, with shadows.
//
//   ch09-reflection [--depth N] [--scene FILE] [the usual options]
//
// The scene is scenes/ch09-whitted.json (or --scene FILE). Each pixel's
// colour is *your* trace() of its primary ray, which follows mirrors and
// glass for up to N bounces (default 5; --depth 0 is chapter 06's picture
// of the same scene). What to look for (README, "The expected picture"): the
// floor and the sky upside down in the glass ball, the glass ball and the
// checkers in the mirror ball, and no speckles on either (a ray that re-hits
// its own surface).
#include "whitted.hpp"

#include "common/program.hpp"
#include "common/render.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

using namespace rt;

constexpr int max_depth = 50;
int depth_option = ch09::default_depth;  // --depth N

template <class T>
image render_scene(const program_options& opt) {
    const scene<T> world = convert_scene<T>(opt.scene.world);
    const scene_camera<T> camera(opt.scene.camera, opt.width, opt.height);
    return render(opt.width, opt.height, [&](int col, int row) {
        const ray<T> r = camera.primary_ray(col, row);
        return ch09::trace(world, r, camera.primary_range(), depth_option, 1.0f);
    });
}

// Takes --depth N out of the arguments (the shared front end does not know it).
// Returns false, with a message, for a bad value.
bool take_depth_option(int& argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--depth") != 0) continue;
        char* end = nullptr;
        const long n = i + 1 < argc ? std::strtol(argv[i + 1], &end, 10) : -1;
        if (i + 1 >= argc || end == argv[i + 1] || *end != '\0' || n < 0 || n > max_depth) {
            std::fprintf(stderr, "ch09: --depth expects a whole number from 0 to %d (bounces after the first hit)\n",
                         max_depth);
            return false;
        }
        depth_option = int(n);
        for (int k = i; k + 2 <= argc; ++k) argv[k] = argv[k + 2];  // argv[argc] is the null pointer
        argc -= 2;
        --i;
    }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    if (!take_depth_option(argc, argv)) return 1;
    rt::chapter_program program;
    program.id = "ch09";
    program.title = "reflection";
    program.draws_scene = true;
    program.render = rt::by_precision(render_scene<float>, render_scene<double>);  // counts primary rays only
    bool help = false;
    for (int i = 1; i < argc; ++i) help = help || std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0;
    const int status = rt::run_chapter_program(argc, argv, program);
    // --depth is this program's own option (take_depth_option), so the shared help does not list it.
    if (help)
        std::printf("  --depth INT                 bounces followed after the first hit (0 to %d; default %d)\n",
                    max_depth, ch09::default_depth);
    return status;
}
