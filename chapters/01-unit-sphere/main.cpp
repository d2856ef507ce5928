// main.cpp — chapter 01's program: the unit sphere seen by a pinhole camera.
//
// Each pixel's ray is tested against the sphere with *your*
// intersect_unit_sphere. A hit is coloured by its surface normal (for the
// unit sphere at the origin the normal at p is p itself), mapped from
// [-1, 1] to [0, 1] per channel, so the shape reads as a rounded ball:
// reddish to the right, greenish at the top, bluish facing the camera.
#include "unit_sphere.hpp"

#include "common/camera.hpp"
#include "common/program.hpp"
#include "common/render.hpp"

namespace {

using namespace rt;

template <class T>
image render_unit_sphere(const program_options& opt) {
    // The eye at (0, 0, 3), or turned about the sphere's centre with --view.
    const vec3d eye = turned_eye(opt.view, {0, 0, 3}, {0, 0, 0}, {0, 1, 0});
    auto frame = camera_frame<T>::look_at(convert<T>(eye), {0, 0, 0}, {0, 1, 0});
    pinhole_camera<T> camera(frame, T(45), opt.width, opt.height);
    return render(opt.width, opt.height, [&](int col, int row) {
        ray<T> r = camera.primary_ray(col, row);
        // t > 1: only what lies beyond the image plane is visible (README, "why t > 1").
        if (auto t = ch01::intersect_unit_sphere(r, interval<T>::in_front_of_image_plane())) {
            vec3<T> normal = r.at(*t);
            return color(convert<float>(normal) * 0.5f + 0.5f);
        }
        return color(0.1f, 0.1f, 0.12f);  // background
    });
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch01";
    program.title = "unit sphere";
    program.render = rt::by_precision(render_unit_sphere<float>, render_unit_sphere<double>);
    return rt::run_chapter_program(argc, argv, program);
}
