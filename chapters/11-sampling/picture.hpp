// picture.hpp — chapter 11's picture: many samples per pixel, soft shadows, depth of field.
//
// One pixel's colour is a pure function of the scene, the settings and the
// pixel: its samples come from its own stream (sample_sequences.hpp), so the
// picture is the same on every run and every thread count. Used by the
// chapter's program (main.cpp), its error study (sampling_study.cpp) and the
// test that the picture does not depend on the threads.
//
// A sample: a point of the filter's square around the pixel's centre
// (filter_radius), a lens point (thin_lens_ray), the closest hit (chapter
// 03's loop over chapters 02, 04 and 05), and at the hit one light sample per
// light: a point light as in chapter 06, a sphere light by its cone
// (sample_sphere_light) with a shadow ray to the chosen point. The pixel is
// pixel_estimate of its samples.
//
// Shading is chapter 06's diffuse term: the diffuse colour times the light
// arriving per unit area (irradiance). From a sphere light of radiance L the
// one-sample estimate of that irradiance is L cos(theta) V / pdf (V: 1 when
// the shadow ray is free, 0 when blocked); L = intensity / (pi r^2), so far
// from the light it equals the point light's intensity cos(theta) / d^2
// (common/scene.hpp). Highlights are left out (chapter 12 brings materials
// that reflect light, with their densities).
#pragma once

#include "sample_sequences.hpp"
#include "sampling.hpp"

#include "02-sphere/sphere.hpp"
#include "03-scene-loop/scene_loop.hpp"
#include "04-plane/plane.hpp"
#include "05-triangle/triangle.hpp"
#include "06-shading/shading.hpp"

#include "common/object_dispatch.hpp"
#include "common/random.hpp"
#include "common/render.hpp"
#include "common/scene.hpp"
#include "common/scene_file.hpp"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <vector>

namespace rt::ch11 {

struct picture_settings {
    int samples = 16;                          // per pixel
    sequence_kind sequence = sequence_kind::stratified;
    filter_kind filter = filter_kind::tent;
    std::uint64_t seed = 11;                   // the picture's seed: one stream per pixel from it
};

// The scene with its camera and lens, in precision T.
template <class T>
class sampled_scene {
public:
    sampled_scene(const scene_description& d, int width, int height)
        : world_(convert_scene<T>(d.world)),
          camera_(camera_frame<T>::look_at(convert<T>(d.camera.eye), convert<T>(d.camera.look_at),
                                           convert<T>(d.camera.up)),
                  T(d.camera.fov_degrees), width, height),
          intersect_(object_dispatch(world_, ch02::intersect_sphere<T>, ch04::intersect_plane<T>,
                                     ch05::intersect_triangle<T>)
                         .intersector()) {
        if (d.camera.type != camera_description::kind::pinhole)
            throw std::invalid_argument("chapter 11 draws a pinhole camera with a thin lens, not an orthographic one");
        lens_.aperture = T(d.camera.aperture);
        // Focused on the point the camera looks at, unless the file says otherwise.
        lens_.focus_distance =
            T(d.camera.focus_distance > 0 ? d.camera.focus_distance : length(d.camera.look_at - d.camera.eye));
    }

    int width() const { return camera_.width; }
    int height() const { return camera_.height; }

    // The colour of pixel (col, row): a pure function of its arguments.
    color pixel(int col, int row, const picture_settings& s) const {
        pixel_sequence<T> sequence(s.sequence, s.samples, pixel_stream(s.seed, col, row, camera_.width));
        const T radius = filter_radius<T>(s.filter);
        std::vector<pixel_sample<T>> samples(size_t(s.samples));
        for (int k = 0; k < s.samples; ++k) {
            const vec2<T> film = sequence.point(0, k);
            const vec2<T> offset = (T(2) * film - T(1)) * radius;
            const ray<T> r = thin_lens_ray(camera_, lens_, T(col) + T(0.5) + offset.x, T(row) + T(0.5) + offset.y,
                                           sequence.point(1, k));
            samples[size_t(k)] = {offset, radiance(r, sequence.point(2, k))};
        }
        return pixel_estimate(s.filter, samples);
    }

    // Rays cast so far (primary and shadow), for the program's report.
    long rays() const { return rays_.load(); }

private:
    // What the ray brings back: a light it sees, else the lit hit, else the background.
    color radiance(const ray<T>& r, const vec2<T>& light_u) const {
        rays_.fetch_add(1, std::memory_order_relaxed);
        const interval<T> visible = interval<T>::in_front_of_image_plane();
        const auto hit = ch03::closest_hit(world_.object_count(), intersect_, r, visible);
        const T nearest = hit ? hit->t : infinity<T>;
        for (const point_light& light : world_.lights) {
            if (!(light.radius > 0)) continue;  // a point light cannot be seen
            const sphere<T> glow{convert<T>(light.position), T(light.radius), 0};
            if (ch02::intersect_sphere(glow, r, interval<T>{visible.min, nearest})) return emitted(light);
        }
        if (!hit) return world_.background;
        const material m = material_at(world_, *hit);
        const vec3<T> n = hit->facing_normal(r);  // the side we see: the one face rule (common/hit_record.hpp)
        color c = world_.ambient * m.diffuse;
        for (const point_light& light : world_.lights) c += m.diffuse * irradiance(light, hit->point, n, light_u);
        return c;
    }

    // The light from `light` arriving per unit area at `point` (normal n), one sample.
    color irradiance(const point_light& light, const vec3<T>& point, const vec3<T>& n, const vec2<T>& u) const {
        const vec3<T> centre = convert<T>(light.position);
        const vec3<T> origin = ch06::shadow_ray_origin(point, n, centre - point);
        if (!(light.radius > 0)) {  // a point light, as in chapter 06
            const T cos_term = ch06::lambert(n, centre - point);
            if (!(cos_term > T(0))) return color(0.0f);
            const ch06::shadow_query<T> q = ch06::shadow_ray(point, n, centre);
            if (occluded(q.r, q.range)) return color(0.0f);
            const vec3<T> l = centre - point;
            return light.intensity * float(cos_term / dot(l, l));
        }
        const sphere<T> glow{centre, T(light.radius), 0};
        const auto s = sample_sphere_light(glow, origin, u);
        if (!s) return color(0.0f);  // inside the light: not a case this scene has
        const T cos_term = dot(n, s->direction) / length(n);
        if (!(cos_term > T(0))) return color(0.0f);  // the chosen point is below the surface
        if (occluded(ray<T>{origin, s->direction}, interval<T>{T(0), s->distance})) return color(0.0f);
        return emitted(light) * float(cos_term / s->pdf);
    }

    bool occluded(const ray<T>& r, const interval<T>& range) const {
        rays_.fetch_add(1, std::memory_order_relaxed);
        return ch03::closest_hit(world_.object_count(), intersect_, r, range).has_value();
    }

    // A sphere light's radiance: its intensity spread over its disc, pi r^2.
    static color emitted(const point_light& light) {
        return light.intensity * float(1.0 / (3.14159265358979323846 * light.radius * light.radius));
    }

    scene<T> world_;
    pinhole_camera<T> camera_;
    thin_lens<T> lens_;
    ch03::object_intersector<T> intersect_;
    mutable std::atomic<long> rays_{0};
};

// The whole picture, rows shared among the threads (common/render.hpp).
template <class T>
image render_picture(const sampled_scene<T>& scene, const picture_settings& s) {
    return render(scene.width(), scene.height(), [&](int col, int row) { return scene.pixel(col, row, s); });
}

}  // namespace rt::ch11
