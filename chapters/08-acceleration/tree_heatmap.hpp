// tree_heatmap.hpp — what the tree did for each pixel, counted from outside
// (--heatmap in chapter 08's program and in rt-render's general path).
//
// Given code, not an exercise. It never looks inside your traversal: it
// counts the calls your closest_hit makes to the leaf test it is handed.
//   objects asked  the calls to intersect(i, ...), one per object asked;
//   boxes opened   the tree's nodes on the way from the root to every leaf
//                  whose objects were asked: boxes the ray must have entered
//                  for your code to reach those leaves. A box tested and
//                  missed, or entered without reaching a leaf below, is not
//                  counted (the box tests are your slab test, which the
//                  traversal calls directly), so this is a lower bound.
// Both are counted for each pixel's primary ray, the ray chapter 03's loop
// answers by asking every object: brute force's count, n per pixel, is
// measured the same way, through chapter 03's closest_hit.
#pragma once

#include "scene_tree.hpp"

#include "03-scene-loop/scene_loop.hpp"

#include "common/scene_file.hpp"
#include "common/heatmap.hpp"
#include "common/render.hpp"

#include <vector>

namespace rt::ch08 {

// For every node, its parent (-1 for the root); for every object, its leaf.
struct tree_links {
    std::vector<int> parent;
    std::vector<int> leaf_of;

    template <class T>
    explicit tree_links(const bvh<T>& tree) : parent(tree.nodes.size(), -1), leaf_of(tree.order.size(), -1) {
        for (size_t n = 0; n < tree.nodes.size(); ++n) {
            const bvh_node<T>& node = tree.nodes[n];
            if (node.is_leaf())
                for (int k = node.first; k < node.first + node.count; ++k) leaf_of[size_t(tree.order[size_t(k)])] = int(n);
            else
                parent[size_t(node.first)] = parent[size_t(node.first + 1)] = int(n);
        }
    }
};

// One pixel's counts, kept by the thread that renders it.
struct pixel_counts {
    long objects = 0;
    long boxes = 0;
    std::vector<unsigned> seen;  // seen[node] == stamp: counted for this pixel already
    unsigned stamp = 0;

    void start(size_t nodes) {
        objects = boxes = 0;
        if (seen.size() != nodes) seen.assign(nodes, 0);
        ++stamp;
    }
    // The object's leaf and the nodes above it, each counted once per pixel.
    void asked(const tree_links& links, int object) {
        ++objects;
        for (int n = links.leaf_of[size_t(object)]; n >= 0 && seen[size_t(n)] != stamp; n = links.parent[size_t(n)]) {
            seen[size_t(n)] = stamp;
            ++boxes;
        }
    }
};

inline thread_local pixel_counts this_pixel;

// The three maps of one picture: the tree's boxes opened and objects asked,
// and brute force's objects asked (planes, which stay outside the tree, are
// asked by both and counted as objects in both).
template <class T, class Dispatch>
std::vector<count_map> tree_heatmap(const scene<T>& world, const scene_tree<T>& a, const Dispatch& dispatch,
                                    const scene_camera<T>& camera, int width, int height) {
    const tree_links links(a.tree);
    const leaf_intersector<T> counted_leaf = [&](int k, const ray<T>& r, const interval<T>& range, hit_record<T>& hit) {
        this_pixel.asked(links, k);
        return dispatch.object_hit(a.bounded[size_t(k)], r, range, hit);
    };
    struct counted_planes {  // scene_closest_hit asks the planes through object_hit
        const Dispatch& dispatch;
        bool object_hit(int i, const ray<T>& r, const interval<T>& range, hit_record<T>& hit) const {
            ++this_pixel.objects;  // a plane
            return dispatch.object_hit(i, r, range, hit);
        }
    };
    const counted_planes counted_dispatch{dispatch};
    const ch03::object_intersector<T> counted_brute = [&](int i, const ray<T>& r, const interval<T>& range) {
        ++this_pixel.objects;
        return dispatch.shape_hit(i, r, range);
    };

    std::vector<count_map> maps{{"tree: boxes opened", width, height},
                                {"tree: objects asked", width, height},
                                {"brute force: objects asked", width, height}};
    for_each_row(height, [&](int row) {
        for (int col = 0; col < width; ++col) {
            const ray<T> r = camera.primary_ray(col, row);
            this_pixel.start(a.tree.nodes.size());
            (void)scene_closest_hit(a, counted_leaf, counted_dispatch, r, camera.primary_range());
            maps[0].at(col, row) = this_pixel.boxes;
            maps[1].at(col, row) = this_pixel.objects;
            this_pixel.start(a.tree.nodes.size());
            (void)ch03::closest_hit(world.object_count(), counted_brute, r, camera.primary_range());
            maps[2].at(col, row) = this_pixel.objects;
        }
    });
    return maps;
}

}  // namespace rt::ch08
