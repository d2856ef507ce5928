// instanced_path.hpp — rendering a scene with instances: a two-level tree
// (instructor side; chapter 10's exercises are the course's version).
//
// Every object a scene file defines (common/instances.hpp) gets its own tree
// over its own items: its spheres, its triangles and the instances it
// places, each instance's box being the box of the placed object's own
// tree, transformed corner by corner into this object's space and widened
// against rounding. The scene's top level is one more such object. A ray
// meets an instance by being moved into the placed object's space, by the
// inverse transform, with its direction NOT normalised: the point
// o + t d maps to o' + t d', the same t, so the closest hit so far and the
// ray's range carry over unchanged in and out of instances. A hit's normal
// comes back by the inverse transpose. Instances of instances are the same
// step again, one level down: the level-10 sphereflake is eleven small
// trees, not four billion spheres.
//
// The walk visits the nearer of two boxes first, a leaf's instances in the
// order the ray enters their boxes, and skips what lies beyond the closest
// hit so far; an instance's box is tested before the ray is moved into its
// space. Primary rays go through it 32 at a time, the rays of a tile of
// 8 x 4 pixels in the lanes of one loop (instanced_packets.cpp), each with
// the answer the one-ray walk gives it; shadow rays go one at a time. A placed object small enough when expanded (expand_at_most, off
// by default) can be stored expanded in its own space, one tree for it.
//
// Planes (unbounded, so in no tree) inside placed objects are moved out to
// the top level once, for each way they are placed.
#pragma once

#include "fast_path.hpp"  // packet_width
#include "scene_plan.hpp"

#include "common/image.hpp"
#include "common/scene_file.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace rt::render_tool {

struct instanced_scene_data;  // the trees (instanced_path.cpp)

// The scene's two-level tree, built once.
class instanced_scene {
public:
    // expand_at_most: a placed object that expands to at most this many
    // spheres and triangles is stored expanded, in its own space, in one
    // tree, so a ray pays one transform for it instead of one per level of
    // instances inside it. 0 (the default) keeps every instance: on the
    // level-8 sphereflake, expanding its level-4 sub-flakes (8192) or its
    // level-6 ones (600000) gave no clear gain: render with shadows 938 and
    // 1242 ns per ray against 884, primary rays 932 and 1182 against 1080
    // (one run under load, rt-bench section 6, tools/bench/README.md). The
    // tests use both.
    static constexpr std::uint64_t default_expand_at_most = 0;
    explicit instanced_scene(const scene_description& scene, std::uint64_t expand_at_most = default_expand_at_most);
    ~instanced_scene();
    instanced_scene(instanced_scene&&) noexcept;

    // The plan in one line: objects, instances, what they expand to, memory.
    std::string describe() const;
    double build_seconds() const;
    size_t bytes() const;

    // What one ray hits: t, the material, the unit normal in world space
    // (a sphere's outward, a triangle's or plane's facing the ray), and the
    // number of the shape in the object that holds it (for tests).
    struct hit {
        double t = 0;
        int material = -1;  // -1: a miss
        vec3d normal{0};
        vec3d point{0};         // the hit point on the surface hit, in world space (for shading)
        vec3d plane_normal{0};  // a plane's normal as the scene gives it (its checker's axes), 0 for other shapes
    };
    hit closest(const ray<double>& r, double tmin, double tmax) const;
    // The same for the 32 rays of a packet at once (a tile of primary rays),
    // each ray's answer the same as closest's (instanced_packets.cpp).
    void closest(const ray<double> (&rays)[packet_width], double tmin, double tmax, hit (&out)[packet_width]) const;
    bool blocked(const ray<double>& r, double tmin, double tmax) const;

    // The boxes of the top level's instances in world space, as its tree
    // holds them (float, rounded outwards and widened), in the order of
    // scene_description::instances (an instance of an empty object has none).
    struct placed_box {
        vec3d lo, hi;
    };
    std::vector<placed_box> top_instance_boxes() const;

private:
    std::unique_ptr<instanced_scene_data> data_;
};

// Renders the scene (shaded with chapter 06's shade() when lit, with
// shadow rays through the same tree), in double.
image render_instanced(const scene_description& scene, const instanced_scene& built, int width, int height,
                       render_stats& stats);

// Primary rays only, closest hit only, no shading: how many pixels hit
// something (the benchmark's raw intersection throughput, as
// count_primary_hits in fast_path.hpp for a flat scene).
long count_primary_hits_instanced(const scene_description& scene, const instanced_scene& built, int width, int height);

// The scene with every instance expanded into world-space shapes: spheres
// under similarity transforms only (anything else is an ellipsoid: throws
// std::invalid_argument). For comparing flat with instanced renders.
scene_description flattened(const scene_description& scene);

}  // namespace rt::render_tool
