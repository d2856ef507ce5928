// picture.hpp — chapter 12's picture: many paths per pixel through a pinhole.
//
// One pixel's colour is a pure function of the scene, the settings and the
// pixel: its paths take their numbers from the pixel's own stream
// (pixel_random.hpp), so the picture is the same on every run and every
// thread count. Used by the chapter's program (main.cpp) and its error study
// (path_study.cpp), so both draw exactly the same estimator.
//
// A path: a point drawn uniformly in the pixel's square (a box filter),
// the camera ray through it, and *your* path_radiance along that ray. The
// pixel is the mean of its paths.
#pragma once

#include "path_tracing.hpp"
#include "pixel_random.hpp"

#include "common/camera.hpp"
#include "common/render.hpp"
#include "common/scene_file.hpp"

#include <cstdint>
#include <stdexcept>

namespace rt::ch12 {

// Longest path: vertices beyond it are rare (roulette ends most paths after
// a few bounces), and each costs its five numbers whether used or not.
inline constexpr int max_vertices = 24;

struct picture_settings {
    int paths = 16;           // per pixel
    std::uint64_t seed = 1;   // the picture's seed: one stream per pixel from it
    path_settings estimator;  // which of the lecture's four estimators
};

// The camera a scene file describes, in precision T, at width x height.
// Chapter 12 draws through a pinhole only.
template <class T>
pinhole_camera<T> path_camera(const scene_description& d, int width, int height) {
    const camera_description& c = d.camera;
    if (c.type != camera_description::kind::pinhole)
        throw std::invalid_argument(d.source + ": camera.type: chapter 12 draws through a pinhole camera, "
                                    "not an orthographic one");
    return pinhole_camera<T>(camera_frame<T>::look_at(convert<T>(c.eye), convert<T>(c.look_at), convert<T>(c.up)),
                             T(c.fov_degrees), width, height);
}

// The colour of pixel (col, row): the mean of its paths.
template <class T>
color pixel_colour(const path_scene<T>& s, const pinhole_camera<T>& camera, const picture_settings& how, int col,
                   int row) {
    const interval<T> camera_range{T(1), infinity<T>};  // beyond the image plane (chapter 01)
    pixel_random random(how.seed, std::uint64_t(row) * std::uint64_t(camera.width) + std::uint64_t(col));
    color sum(0.0f);
    for (int k = 0; k < how.paths; ++k) {
        // A point drawn in the pixel's square: x right, y up, as camera.hpp's pixel centre.
        const T x = (T(col) + random.uniform<T>()) / T(camera.width) * T(2) - T(1);
        const T y = T(1) - (T(row) + random.uniform<T>()) / T(camera.height) * T(2);
        const vec3<T> on_plane = x * camera.half_height * camera.aspect() * camera.frame.u +
                                 y * camera.half_height * camera.frame.v - camera.frame.w;
        const ray<T> r{camera.frame.eye, on_plane};
        sum += path_radiance(s, r, camera_range, random.path_numbers<T>(max_vertices), how.estimator);
    }
    return sum / float(how.paths);
}

// The whole picture, rows shared among the threads (common/render.hpp).
template <class T>
image render_picture(const path_scene<T>& s, const pinhole_camera<T>& camera, const picture_settings& how) {
    return render(camera.width, camera.height, [&](int col, int row) { return pixel_colour(s, camera, how, col, row); });
}

}  // namespace rt::ch12
