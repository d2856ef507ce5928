#include "whitted_path.hpp"

#include "chapters_setup.hpp"

#include "09-reflection/whitted.hpp"

#include "common/render.hpp"

namespace rt::render_tool {

namespace {

template <class T>
image render_typed(const scene_description& d, int depth, int width, int height, render_stats& stats) {
    const setup_timer setup;
    const chapters_scene<T> s(d, width, height);
    setup.done(stats);
    image img = render(width, height, [&](int col, int row) {
        const ray<T> r = s.camera.primary_ray(col, row);
        return ch09::trace(s.world, r, s.camera.primary_range(), depth, 1.0f);  // throughput 1: a primary ray
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
