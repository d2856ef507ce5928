// camera.hpp — turning a pixel into a primary ray.
//
// Both cameras place an image plane in front of the eye and send one ray
// through the centre of each pixel. Pixel (col, row) has its centre at
//     x = (col + 0.5) / width  * 2 - 1        (-1 at the left edge, +1 at the right)
//     y = 1 - (row + 0.5) / height * 2        (+1 at the top: row 0 is the top row)
// scaled by the half-width and half-height of the image plane.
//
// The camera's own frame is right-handed: u points right, v up, and w
// backwards, so the camera looks down -w (down -z when it sits at the
// origin with the default orientation).
#pragma once

#include "math.hpp"
#include "ray.hpp"

#include <cmath>
#include <stdexcept>

namespace rt {

// An orthonormal frame looking from eye towards target.
template <class T>
struct camera_frame {
    vec3<T> eye{0, 0, 0};
    vec3<T> u{1, 0, 0};  // right
    vec3<T> v{0, 1, 0};  // up
    vec3<T> w{0, 0, 1};  // backwards: the camera looks down -w

    static camera_frame look_at(vec3<T> eye, vec3<T> target, vec3<T> up) {
        vec3<T> back = eye - target;
        if (!(length(back) > T(0)))
            throw std::invalid_argument("camera: eye and look-at point coincide");
        camera_frame f;
        f.eye = eye;
        f.w = normalize(back);
        vec3<T> right = cross(up, f.w);
        if (!(length(right) > T(0)))
            throw std::invalid_argument("camera: the up vector is parallel to the view direction");
        f.u = normalize(right);
        f.v = cross(f.w, f.u);
        return f;
    }
};

// Pixel centre in normalised image coordinates, each in (-1, 1).
template <class T>
void pixel_center(int col, int row, int width, int height, T& x, T& y) {
    x = (T(col) + T(0.5)) / T(width) * T(2) - T(1);
    y = T(1) - (T(row) + T(0.5)) / T(height) * T(2);
}

// The lecture's perspective camera: the image plane is at distance 1 in
// front of the eye, and a primary ray's direction goes from the eye to the
// pixel on that plane. Its direction is not normalised, so the image plane
// is at t = 1 and objects in front of it have t > 1.
template <class T>
struct pinhole_camera {
    camera_frame<T> frame;
    int width = 0, height = 0;
    T half_height = T(1);  // tan(vertical field of view / 2)

    pinhole_camera() = default;
    pinhole_camera(camera_frame<T> f, T vertical_fov_degrees, int w, int h)
        : frame(f), width(w), height(h) {
        if (!(w > 0 && h > 0)) throw std::invalid_argument("camera: image size must be positive");
        if (!(vertical_fov_degrees > T(0) && vertical_fov_degrees < T(180)))
            throw std::invalid_argument("camera: field of view must be between 0 and 180 degrees");
        half_height = std::tan(vertical_fov_degrees * T(3.14159265358979323846) / T(360));
    }

    T aspect() const { return T(width) / T(height); }

    ray<T> primary_ray(int col, int row) const {
        T x, y;
        pixel_center(col, row, width, height, x, y);
        vec3<T> on_plane = x * half_height * aspect() * frame.u + y * half_height * frame.v - frame.w;
        return {frame.eye, on_plane};
    }
};

// Orthographic camera: parallel rays along -w, one from each pixel of a
// view rectangle of the given height centred on the eye. The direction is a
// unit vector and the origin lies on the image plane, so hits need t > 0.
template <class T>
struct orthographic_camera {
    camera_frame<T> frame;
    int width = 0, height = 0;
    T view_height = T(2);

    orthographic_camera() = default;
    orthographic_camera(camera_frame<T> f, T view_h, int w, int h)
        : frame(f), width(w), height(h), view_height(view_h) {
        if (!(w > 0 && h > 0)) throw std::invalid_argument("camera: image size must be positive");
        if (!(view_h > T(0))) throw std::invalid_argument("camera: view height must be positive");
    }

    ray<T> primary_ray(int col, int row) const {
        T x, y;
        pixel_center(col, row, width, height, x, y);
        T half_h = view_height / T(2);
        T half_w = half_h * T(width) / T(height);
        return {frame.eye + x * half_w * frame.u + y * half_h * frame.v, -frame.w};
    }
};

}  // namespace rt
