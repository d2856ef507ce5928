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

#include <string>

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

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch09";
    program.title = "reflection";
    program.draws_scene = true;
    program.render = rt::by_precision(render_scene<float>, render_scene<double>);  // counts primary rays only
    program.add_options = [](CLI::App& app) {
        rt::add_whole_number_option(app, "--depth", depth_option, 0, max_depth,
                                    "bounces followed after the first hit (default " +
                                        std::to_string(ch09::default_depth) + ")");
    };
    return rt::run_chapter_program(argc, argv, program);
}
