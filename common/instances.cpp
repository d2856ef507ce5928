// instances.cpp — counting what instances place (see instances.hpp).
#include "instances.hpp"

#include <algorithm>
#include <functional>
#include <limits>

namespace rt {

namespace {
constexpr std::uint64_t most = std::numeric_limits<std::uint64_t>::max();
}

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) { return a > most - b ? most : a + b; }

std::uint64_t saturating_multiply(std::uint64_t a, std::uint64_t n) {
    return n != 0 && a > most / n ? most : a * n;
}

std::uint64_t expanded_counts::total() const { return saturating_add(saturating_add(spheres, planes), triangles); }

// Depth-first with memory: each object is counted once, however often it is
// placed, so the level-10 sphereflake's eleven objects take eleven steps.
std::vector<expanded_counts> expanded_counts_of(const std::vector<object_definition>& objects) {
    std::vector<expanded_counts> counts(objects.size());
    std::vector<bool> done(objects.size(), false);
    std::function<void(size_t)> count = [&](size_t o) {
        if (done[o]) return;
        expanded_counts c;
        c.spheres = objects[o].spheres.size();
        c.planes = objects[o].planes.size();
        c.triangles = objects[o].triangles.size();
        for (const auto& i : objects[o].instances) {
            count(size_t(i.object));
            const expanded_counts& child = counts[size_t(i.object)];
            c.spheres = saturating_add(c.spheres, child.spheres);
            c.planes = saturating_add(c.planes, child.planes);
            c.triangles = saturating_add(c.triangles, child.triangles);
        }
        counts[o] = c;
        done[o] = true;
    };
    for (size_t o = 0; o < objects.size(); ++o) count(o);
    return counts;
}

std::vector<int> nesting_depths(const std::vector<object_definition>& objects) {
    std::vector<int> depth(objects.size(), -1);
    std::function<int(size_t)> of = [&](size_t o) {
        if (depth[o] >= 0) return depth[o];
        int d = 0;
        for (const auto& i : objects[o].instances) d = std::max(d, 1 + of(size_t(i.object)));
        return depth[o] = d;
    };
    for (size_t o = 0; o < objects.size(); ++o) of(o);
    return depth;
}

}  // namespace rt
