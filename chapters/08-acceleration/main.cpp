// main.cpp — chapter 08's program (first version): a block of spheres found
// through the tree instead of brute force, shaded by their normals.
#include "bvh.hpp"

#include "common/camera.hpp"
#include "common/program.hpp"
#include "common/render.hpp"
#include "common/scene.hpp"
#include "sphere.hpp"

namespace {

using namespace rt;

template <class T>
image render_scene(const program_options& opt, long& rays) {
    std::vector<sphere<T>> spheres;
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j)
            for (int k = 0; k < 16; ++k)
                spheres.push_back({{T(i - 7.5), T(j - 7.5), T(-k * 1.5 - 12)}, T(0.3)});
    std::vector<ch08::aabb<T>> boxes;
    for (const auto& s : spheres) boxes.push_back(ch08::bounds(s));
    const ch08::bvh<T> tree = ch08::build_sah(boxes);
    const ch08::leaf_intersector<T> intersect = [&](int i, const ray<T>& r, const interval<T>& range,
                                                    hit_record<T>& hit) {
        const auto h = ch02::intersect_sphere(spheres[size_t(i)], r, range);
        if (h) hit = *h;
        return h.has_value();
    };
    camera_description view;
    view.eye = {0, 0, 0};
    view.look_at = {0, 0, -1};
    view.fov_degrees = 60;
    const scene_camera<T> camera(view, opt.width, opt.height);
    rays = long(opt.width) * opt.height;
    return render(opt.width, opt.height, [&](int col, int row) {
        const ray<T> r = camera.primary_ray(col, row);
        const auto hit = ch08::closest_hit(tree, intersect, r, camera.primary_range());
        if (!hit) return color(0.5f, 0.7f, 1.0f);
        const vec3<T> n = hit->normal;
        return color(float(n.x + 1) * 0.5f, float(n.y + 1) * 0.5f, float(n.z + 1) * 0.5f);
    });
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch08";
    program.title = "acceleration";
    program.render = [](const rt::program_options& opt, long& rays) {
        return opt.prec == rt::precision::single ? render_scene<float>(opt, rays) : render_scene<double>(opt, rays);
    };
    return rt::run_chapter_program(argc, argv, program);
}
