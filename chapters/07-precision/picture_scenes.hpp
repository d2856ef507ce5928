// picture_scenes.hpp — the two scenes of chapter 07's picture, their cameras,
// and the file of reference answers for their rays (README, "The picture").
//
// Shared by the chapter program (main.cpp), which draws the scenes and, with
// --error, measures your tests against reference_hits.bin, and by the tool
// that writes that file from the reference solution (instructor side).
#pragma once

#include "common/camera.hpp"
#include "common/program.hpp"
#include "common/interval.hpp"
#include "common/ray.hpp"
#include "common/shapes.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace rt::ch07_picture {

// The three far spheres: unit radius, at these distances from the camera.
inline const double far_distances[] = {100.0, 4100.0, 20000.0};
inline const double far_spacing = 2.1;      // centre-to-centre, side by side across the panel
inline const double far_view_height = 4.8;  // orthographic view rectangle height

// The huge ground.
inline const double ground_radius = 1e6;
inline const double camera_height = 1.0;

enum class which_scene { far_spheres, huge_ground };
inline const which_scene both_scenes[] = {which_scene::far_spheres, which_scene::huge_ground};

template <class T>
std::vector<sphere<T>> spheres_of(which_scene sc) {
    std::vector<sphere<T>> s;
    if (sc == which_scene::far_spheres) {
        for (int i = 0; i < 3; ++i)
            s.push_back({{T((i - 1) * far_spacing), T(0), T(-far_distances[i])}, T(1), i});
    } else {
        s.push_back({{T(0), T(-ground_radius), T(0)}, T(ground_radius), 0});  // the ground: top at y = 0
        s.push_back({{T(-0.6), T(0.5), T(-4.0)}, T(0.5), 1});                  // balls resting on it
        s.push_back({{T(0.9), T(0.3), T(-3.0)}, T(0.3), 2});
    }
    return s;
}

// A panel's camera: the primary ray through pixel (col, row) of a panel of
// the given size. Both cameras are built in T, so the rays themselves carry
// the rounding of the chosen precision.
//
// --view (common/program.hpp) turns the huge ground's camera about the point
// it looks at, as in every chapter. The far spheres' camera is orthographic
// and its spheres lie 100 to 20000 units away: any turn would sweep its
// parallel rays off them, so it moves sideways instead, YAW/2 percent of its
// view height to the right and PITCH/2 percent up (the distances, which are
// the experiment, stay). The chapter's own view (0,0) gives the same rays,
// bit for bit, as the camera without a view.
template <class T>
ray<T> panel_ray(which_scene sc, const view_turn& view, int col, int row, int width, int height) {
    if (sc == which_scene::far_spheres) {
        const vec3d eye{view.yaw_degrees / 200 * far_view_height, view.pitch_degrees / 200 * far_view_height, 0};
        auto frame = camera_frame<T>::look_at(convert<T>(eye), convert<T>(eye + vec3d{0, 0, -1}), {0, 1, 0});
        return orthographic_camera<T>(frame, T(far_view_height), width, height).primary_ray(col, row);
    }
    const vec3d target{0, 0.35, -4};
    const vec3d eye = turned_eye(view, {0, camera_height, 0}, target, {0, 1, 0});
    auto frame = camera_frame<T>::look_at(convert<T>(eye), convert<T>(target), {0, 1, 0});
    return pinhole_camera<T>(frame, T(50), width, height).primary_ray(col, row);
}

// The chapter's own view.
template <class T>
ray<T> panel_ray(which_scene sc, int col, int row, int width, int height) {
    return panel_ray<T>(sc, view_turn{}, col, row, width, height);
}

template <class T>
interval<T> visible_range(which_scene sc) {
    // Orthographic rays start on the image plane (t > 0); pinhole rays need t > 1.
    return sc == which_scene::far_spheres ? interval<T>{T(0), infinity<T>} : interval<T>::in_front_of_image_plane();
}

// ---------------------------------------------------- the reference answers
//
// reference_hits.bin holds, for the default picture's panels (width x
// height each), float and double, both scenes, the reference solution's t
// of every (pixel, sphere) pair that hits: numbers, not code. Layout
// (little-endian): the line "rt-ch07-reference-hits 1\n", u32 width, u32
// height; then for float, then double, for each scene: u32 count and count
// records (u32 key = (row * width + col) * 3 + sphere, T t).

// One scene's answers in T: t per (pixel, sphere), NaN for a miss.
template <class T>
struct reference_answers {
    int width = 0, height = 0;
    std::vector<T> t;  // indexed by key
    std::optional<T> at(int col, int row, int sphere) const {
        const T x = t[(std::size_t(row) * std::size_t(width) + std::size_t(col)) * 3 + std::size_t(sphere)];
        return x == x ? std::optional<T>(x) : std::nullopt;
    }
};

inline const char reference_magic[] = "rt-ch07-reference-hits 1\n";

// Reads the answers of one precision and one scene; nullopt (and a reason)
// when the file is missing, damaged or made for another panel size.
template <class T>
std::optional<reference_answers<T>> read_reference(const std::string& path, which_scene sc, int width, int height,
                                                   std::string& why) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        why = path + " is missing";
        return std::nullopt;
    }
    char magic[sizeof reference_magic - 1] = {};
    std::uint32_t w = 0, h = 0;
    in.read(magic, sizeof magic);
    in.read(reinterpret_cast<char*>(&w), 4).read(reinterpret_cast<char*>(&h), 4);
    if (!in || std::memcmp(magic, reference_magic, sizeof magic) != 0) {
        why = path + " is not a reference file of this chapter";
        return std::nullopt;
    }
    if (int(w) != width || int(h) != height) {
        why = path + " holds " + std::to_string(w) + "x" + std::to_string(h) + " panels, not " +
              std::to_string(width) + "x" + std::to_string(height);
        return std::nullopt;
    }
    const std::size_t keys = std::size_t(w) * h * 3;
    for (int part = 0; part < 4; ++part) {  // float far, float ground, double far, double ground
        const bool is_float = part < 2;
        const std::size_t t_size = is_float ? sizeof(float) : sizeof(double);
        std::uint32_t count = 0;
        in.read(reinterpret_cast<char*>(&count), 4);
        if (!in || count > keys) break;
        const bool wanted = (is_float == (sizeof(T) == sizeof(float))) && (part % 2 == 0) == (sc == which_scene::far_spheres);
        if (!wanted) {
            in.seekg(std::streamoff(count * (4 + t_size)), std::ios::cur);
            continue;
        }
        reference_answers<T> ref;
        ref.width = width, ref.height = height;
        ref.t.assign(keys, std::numeric_limits<T>::quiet_NaN());
        for (std::uint32_t i = 0; i < count; ++i) {
            std::uint32_t key = 0;
            T t = 0;
            in.read(reinterpret_cast<char*>(&key), 4).read(reinterpret_cast<char*>(&t), sizeof t);
            if (!in || key >= keys) break;
            ref.t[key] = t;
        }
        if (in) return ref;
        break;
    }
    why = path + " is damaged";
    return std::nullopt;
}

}  // namespace rt::ch07_picture
