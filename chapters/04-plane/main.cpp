// main.cpp — chapter 04's program (first version): a checkered ground plane.
#include "plane.hpp"

#include "common/camera.hpp"
#include "common/program.hpp"
#include "common/render.hpp"

#include <cmath>

namespace {

using namespace rt;

template <class T>
image render_plane(const program_options& opt) {
    auto frame = camera_frame<T>::look_at({0, 1, 4}, {0, 0.5, 0}, {0, 1, 0});
    pinhole_camera<T> camera(frame, T(45), opt.width, opt.height);
    plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    return render(opt.width, opt.height, [&](int col, int row) {
        ray<T> r = camera.primary_ray(col, row);
        if (auto hit = ch04::intersect_plane(ground, r, interval<T>::in_front_of_image_plane())) {
            bool dark = (long(std::floor(hit->point.x)) + long(std::floor(hit->point.z))) % 2 != 0;
            return dark ? color(0.2f) : color(0.8f);
        }
        return color(0.5f, 0.7f, 1.0f);
    });
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch04";
    program.title = "plane";
    program.render = [](const rt::program_options& opt, long& rays) {
        rays = long(opt.width) * opt.height;
        return opt.prec == rt::precision::single ? render_plane<float>(opt) : render_plane<double>(opt);
    };
    return rt::run_chapter_program(argc, argv, program);
}
