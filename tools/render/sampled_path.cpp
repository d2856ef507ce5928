#include "sampled_path.hpp"

#include "chapters_setup.hpp"

#include "09-reflection/whitted.hpp"
#include "11-sampling/picture.hpp"
#include "11-sampling/sample_sequences.hpp"
#include "12-path-tracing/path_tracing.hpp"
#include "12-path-tracing/picture.hpp"  // max_vertices: the longest path, as chapter 12 draws it

#include "common/random.hpp"
#include "common/render.hpp"

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace rt::render_tool {

namespace {

// The numbers one path uses, five per vertex, from the pixel's path stream.
template <class T>
std::vector<ch12::bounce_numbers<T>> path_numbers(pcg32& stream, int vertices) {
    std::vector<ch12::bounce_numbers<T>> out(static_cast<size_t>(vertices));
    for (ch12::bounce_numbers<T>& b : out) {
        b.light_u1 = stream.uniform<T>();
        b.light_u2 = stream.uniform<T>();
        b.bounce_u1 = stream.uniform<T>();
        b.bounce_u2 = stream.uniform<T>();
        b.roulette_u = stream.uniform<T>();
    }
    return out;
}

// The camera with its lens, as chapter 11's sampled_scene makes it: focused
// on the point the camera looks at unless the file says otherwise.
template <class T>
struct lens_camera {
    pinhole_camera<T> camera;
    ch11::thin_lens<T> lens;

    lens_camera(const camera_description& d, int width, int height)
        : camera(camera_frame<T>::look_at(convert<T>(d.eye), convert<T>(d.look_at), convert<T>(d.up)),
                 T(d.fov_degrees), width, height) {
        lens.aperture = T(d.aperture);
        lens.focus_distance = T(d.focus_distance > 0 ? d.focus_distance : length(d.look_at - d.eye));
    }
};

// One pixel: spp stratified samples, a box filter, each sample's ray through
// the lens and its colour from radiance(ray, stream). The pixel's stream gives
// the film and lens points (chapter 11's pixel_sequence); a second stream,
// its number past every pixel's, gives what the radiance draws.
template <class T, class Radiance>
color box_filtered_pixel(const lens_camera<T>& c, int col, int row, int spp, std::uint64_t seed,
                         const Radiance& radiance) {
    const int width = c.camera.width;
    ch11::pixel_sequence<T> sequence(ch11::sequence_kind::stratified, spp, pixel_stream(seed, col, row, width));
    pcg32 path_stream(seed, std::uint64_t(width) * std::uint64_t(c.camera.height) +
                                std::uint64_t(row) * std::uint64_t(width) + std::uint64_t(col));
    const T radius = ch11::filter_radius<T>(ch11::filter_kind::box);
    std::vector<ch11::pixel_sample<T>> samples(static_cast<size_t>(spp));
    for (int k = 0; k < spp; ++k) {
        const ch11::vec2<T> offset = (T(2) * sequence.point(0, k) - T(1)) * radius;
        const ray<T> r = ch11::thin_lens_ray(c.camera, c.lens, T(col) + T(0.5) + offset.x,
                                             T(row) + T(0.5) + offset.y, sequence.point(1, k));
        samples[size_t(k)] = {offset, radiance(r, path_stream)};
    }
    return ch11::pixel_estimate(ch11::filter_kind::box, samples);
}

template <class T>
image render_typed(const scene_description& d, const scene_plan& plan, int width, int height, render_stats& stats) {
    const std::uint64_t seed = plan.seed;
    if (d.camera.type != camera_description::kind::pinhole)
        throw scene_error(d.source, 0, 0, "camera.type",
                          "several samples per pixel, sphere lights and the path tracer draw a pinhole camera "
                          "(chapter 11's thin lens), not an orthographic one");
    const setup_timer setup;
    const int spp = plan.spp;
    stats.samples = long(width) * long(height) * long(spp);
    if (plan.path_traced) {
        // The scene as chapter 12 sees it (path_scene_of: emitting spheres and
        // sphere lights are its lights; what a matte path tracer has no use
        // for is left out, and the plan line says what).
        const ch12::path_scene<T> s = ch12::path_scene_of<T>(d);
        if (s.lights.empty() && !plan.emitting_planes)
            throw scene_error(d.source, 0, 0, "materials",
                              "the path tracer (chapter 12) needs light a path can meet: a material with "
                              "\"emission\" on a shape, or a light with a \"radius\"; this scene has " +
                                  std::to_string(d.world.lights.size()) + " point lights and nothing that emits");
        const lens_camera<T> c(d.camera, width, height);
        ch12::path_settings settings;
        settings.next_event = !s.lights.empty();
        settings.cosine_sampling = true;
        const int vertices = plan.bounces ? ch12::max_vertices : 1;
        setup.done(stats);
        const interval<T> camera_range = interval<T>::in_front_of_image_plane();
        image img = render(width, height, [&](int col, int row) {
            return box_filtered_pixel(c, col, row, spp, seed, [&](const ray<T>& r, pcg32& stream) {
                return ch12::path_radiance(s, r, camera_range, path_numbers<T>(stream, vertices), settings);
            });
        });
        stats.rays = stats.samples;  // paths: the chapter's loop does not count its rays
        stats.primary_only = true;
        return img;
    }
    if (plan.secondary_rays()) {
        const scene<T> world = convert_scene<T>(d.world);
        const lens_camera<T> c(d.camera, width, height);
        setup.done(stats);
        image img = render(width, height, [&](int col, int row) {
            return box_filtered_pixel(c, col, row, spp, seed, [&](const ray<T>& r, pcg32&) {
                return ch09::trace(world, r, interval<T>::in_front_of_image_plane(), plan.depth, 1.0f);
            });
        });
        stats.rays = stats.samples;
        stats.primary_only = true;
        return img;
    }
    const ch11::sampled_scene<T> s(d, width, height);
    ch11::picture_settings settings;
    settings.samples = spp;
    settings.sequence = ch11::sequence_kind::stratified;
    settings.filter = ch11::filter_kind::tent;
    settings.seed = seed;
    setup.done(stats);
    image img = ch11::render_picture(s, settings);
    stats.rays = s.rays();
    return img;
}

}  // namespace

image render_sampled(const scene_description& scene, const scene_plan& plan, int width, int height,
                     render_stats& stats) {
    return plan.prec == precision::single ? render_typed<float>(scene, plan, width, height, stats)
                                          : render_typed<double>(scene, plan, width, height, stats);
}

}  // namespace rt::render_tool
