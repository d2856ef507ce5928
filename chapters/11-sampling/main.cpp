// main.cpp — chapter 11's program: soft shadows and depth of field, several samples per pixel.
//
// The scene is scenes/ch11-sampling.json (or --scene FILE): spheres at three
// depths on a checkered ground, lit by one sphere light, seen through a lens
// focused on the middle sphere. Every pixel takes --spp samples (16 unless
// told; a square number: they are stratified), each through *your*
// thin_lens_ray from a point of the tent filter's square around the pixel's
// centre, and each lights its hit with one point of the sphere light chosen
// by *your* sample_sphere_light; *your* pixel_estimate weighs them with
// *your* filter_weight. What to look for (README, "the expected picture"):
// shadows whose edges fade (a penumbra, widest far from the sphere that casts
// it), the near and far spheres blurred and the middle one sharp, smooth edges
// without staircases, and noise that fades as --spp grows.
#include "picture.hpp"

#include "common/program.hpp"

namespace {

using namespace rt;

template <class T>
image render_scene(const program_options& opt, long& rays) {
    const ch11::sampled_scene<T> scene(opt.scene, opt.width, opt.height);
    ch11::picture_settings settings;
    settings.samples = opt.spp;
    image img = ch11::render_picture(scene, settings);
    rays = scene.rays();
    return img;
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch11";
    program.title = "sampling";
    program.draws_scene = true;
    program.default_spp = 16;
    program.render = rt::by_precision(render_scene<float>, render_scene<double>);  // counts its shadow rays
    return rt::run_chapter_program(argc, argv, program);
}
