#include "whitted_path.hpp"

#include "09-reflection/whitted.hpp"

#include "common/render.hpp"
#include "common/timing.hpp"

namespace rt::render_tool {

namespace {

template <class T>
image render_typed(const scene_description& d, int depth, int width, int height, render_stats& stats) {
    const stopwatch setup;
    const double setup_cpu = process_cpu_seconds();
    const scene<T> world = convert_scene<T>(d.world);
    const scene_camera<T> camera(d.camera, width, height);
    stats.setup_seconds = setup.seconds();
    stats.setup_cpu_seconds = process_cpu_seconds() - setup_cpu;
    image img = render(width, height, [&](int col, int row) {
        const ray<T> r = camera.primary_ray(col, row);
        return ch09::trace(world, r, camera.primary_range(), depth, 1.0f);  // throughput 1: a primary ray
    });
    stats.rays = long(width) * long(height);
    stats.primary_only = true;
    return img;
}

}  // namespace

image render_whitted(const scene_description& scene, const scene_plan& plan, int width, int height,
                     render_stats& stats) {
    return plan.prec == precision::single ? render_typed<float>(scene, plan.depth, width, height, stats)
                                          : render_typed<double>(scene, plan.depth, width, height, stats);
}

}  // namespace rt::render_tool
