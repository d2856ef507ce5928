// describe.cpp — what one wrong scene loop does to chapter 03's picture.
//
//   ch03_describe_BUG SCENE.json
//
// Linked with one wrong closest_hit (a fixture of tests/fixtures/wrong/ch03,
// patched into a copy of the solution), it traces every pixel's primary ray
// of SCENE twice: through that closest_hit, and by asking every object and
// keeping the smallest t (the definition the loop must meet). Each object is
// named by its material, a miss by "background". For every pair that
// differs it prints one line
//
//   over <shown> <hidden> <pixels>
//
// (the wrong loop shows <shown> where the picture should show <hidden>),
// then "differing <pixels> of <total>". A hit whose object index names no
// object prints "bad-object-index <index> <pixels>". check.py compares these
// lines with the statements of chapter 03's README.
#include "03-scene-loop/scene_loop.hpp"
#include "02-sphere/sphere.hpp"

#include "common/object_dispatch.hpp"
#include "common/scene_file.hpp"

#include <cstdio>
#include <exception>
#include <map>
#include <string>
#include <utility>

namespace {

using namespace rt;

std::string object_name(const scene_description& d, int object) {
    if (object < 0 || object >= d.world.object_count()) return "";
    const int m = material_index(d.world, object);
    const std::string& name = d.material_names[size_t(m)];
    return name.empty() ? "material " + std::to_string(m) : name;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s SCENE.json\n", argv[0]);
        return 64;
    }
    try {
        const scene_description d = load_scene_file(argv[1]);
        const scene<double>& world = d.world;
        const scene_camera<double> camera(d.camera);
        const object_dispatch intersect(world, ch02::intersect_sphere<double>);
        const ch03::object_intersector<double> loop_intersect = intersect.intersector();
        std::map<std::pair<std::string, std::string>, long> over;
        std::map<int, long> bad_index;
        long differing = 0;
        for (int row = 0; row < camera.height(); ++row)
            for (int col = 0; col < camera.width(); ++col) {
                const ray<double> r = camera.primary_ray(col, row);
                const interval<double> range = camera.primary_range();
                // The nearest hit by definition: every object asked about the whole range, the
                // smallest t kept (the first listed on a tie, as the loop's open tmax does).
                int nearest = -1;
                double nearest_t = 0;
                for (int i = 0; i < world.object_count(); ++i)
                    if (auto h = intersect.shape_hit(i, r, range); h && (nearest < 0 || h->t < nearest_t)) {
                        nearest = i;
                        nearest_t = h->t;
                    }
                const auto hit = ch03::closest_hit(world.object_count(), loop_intersect, r, range);
                const int shown = hit ? hit->object : -1;
                if (hit && (shown < 0 || shown >= world.object_count())) {
                    ++bad_index[shown];
                    continue;
                }
                if (shown == nearest) continue;
                ++differing;
                const std::string a = hit ? object_name(d, shown) : "background";
                const std::string b = nearest >= 0 ? object_name(d, nearest) : "background";
                ++over[{a, b}];
            }
        for (const auto& [pair, pixels] : over)
            std::printf("over %s %s %ld\n", pair.first.c_str(), pair.second.c_str(), pixels);
        for (const auto& [index, pixels] : bad_index) std::printf("bad-object-index %d %ld\n", index, pixels);
        std::printf("differing %ld of %ld\n", differing, long(camera.width()) * camera.height());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 1;
    }
}
