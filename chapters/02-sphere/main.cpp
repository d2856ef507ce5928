// main.cpp — chapter 02's program: one red sphere on a sky gradient.
//
// Each pixel's ray is tested with *your* intersect_sphere. The scene holds
// the red sphere in front of the camera and a second ball *behind* it. The
// picture is split down the middle to show two steps of the lecture:
//   * left half:  the first picture, hit or miss only, asked about the whole
//     line (any t, which is what a discriminant test alone answers): flat red
//     discs, and one of them is the ball behind the camera (the t < 0 trap);
//   * right half: the range test of the lecture, t > 1, which a ball behind
//     the camera can never pass; the sphere is coloured by its outward unit
//     normal, mapped from [-1, 1] to [0, 1] per channel (reddish to the
//     right, greenish at the top, bluish facing the camera).
// A miss shows the sky: white at the horizon blending to blue overhead.
#include "sphere.hpp"

#include "common/camera.hpp"
#include "common/program.hpp"
#include "common/render.hpp"

namespace {

using namespace rt;

// The sky behind everything: blend white to light blue by how far up the ray points.
template <class T>
color sky(const ray<T>& r) {
    const float up = float(normalize(r.direction).y);
    const float s = 0.5f * (up + 1.0f);
    return (1.0f - s) * color(1.0f, 1.0f, 1.0f) + s * color(0.5f, 0.7f, 1.0f);
}

template <class T>
image render_sphere(const program_options& opt) {
    // The eye at the origin looking down -z at the ball, or turned about the
    // ball's centre with --view.
    const vec3d centre{0, 0, -5};
    const vec3d eye = turned_eye(opt.view, {0, 0, 0}, centre, {0, 1, 0});
    auto frame = camera_frame<T>::look_at(convert<T>(eye), convert<T>(centre), {0, 1, 0});
    pinhole_camera<T> camera(frame, T(60), opt.width, opt.height);
    const sphere<T> ball{convert<T>(centre), T(1.5)};
    // Behind the camera (z > 0). The line through the eye and a pixel meets it
    // at t < 0 for the pixels toward its centre mirrored through the eye,
    // (-3, -1.2, -6): down and to the left, inside the left half, clear of the red sphere.
    const sphere<T> behind{{3, 1.2, 6}, T(1)};
    return render(opt.width, opt.height, [&](int col, int row) {
        ray<T> r = camera.primary_ray(col, row);
        if (col < opt.width / 2) {
            // The whole line, -inf < t < inf: "is the discriminant positive?" and nothing more.
            const interval<T> whole_line{};
            const bool line_meets_a_ball =
                ch02::intersect_sphere(ball, r, whole_line) || ch02::intersect_sphere(behind, r, whole_line);
            return line_meets_a_ball ? color(1.0f, 0.0f, 0.0f) : sky(r);
        }
        // t > 1: only what lies beyond the image plane is visible (chapter 01).
        auto hit = ch02::intersect_sphere(ball, r, interval<T>::in_front_of_image_plane());
        if (!hit) return sky(r);
        return color(convert<float>(hit->normal) * 0.5f + 0.5f);
    });
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch02";
    program.title = "sphere";
    program.render = rt::by_precision(render_sphere<float>, render_sphere<double>);
    return rt::run_chapter_program(argc, argv, program);
}
