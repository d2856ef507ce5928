// main.cpp — chapter 05's program (first version): one triangle.
#include "triangle.hpp"

#include "common/camera.hpp"
#include "common/program.hpp"
#include "common/render.hpp"

#include <cmath>

namespace {

using namespace rt;

template <class T>
image render_triangle(const program_options& opt) {
    auto frame = camera_frame<T>::look_at({0, 0, 3}, {0, 0, 0}, {0, 1, 0});
    pinhole_camera<T> camera(frame, T(45), opt.width, opt.height);
    triangle<T> tri{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, 0};
    return render(opt.width, opt.height, [&](int col, int row) {
        ray<T> r = camera.primary_ray(col, row);
        if (auto hit = ch05::intersect_triangle(tri, r, interval<T>::in_front_of_image_plane())) {
            vec3<T> w = ch05::barycentric(tri, hit->point);
            return color(convert<float>(w));
        }
        return color(0.1f, 0.1f, 0.12f);
    });
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch05";
    program.title = "triangle";
    program.render = [](const rt::program_options& opt, long& rays) {
        rays = long(opt.width) * opt.height;
        return opt.prec == rt::precision::single ? render_triangle<float>(opt) : render_triangle<double>(opt);
    };
    return rt::run_chapter_program(argc, argv, program);
}
