// fast_path.hpp — the specialised renderer: brute force over
// structure-of-arrays data, 32 rays (an 8 x 4 tile) at a time, a BVH from a few
// hundred objects on, compiled for exactly what the scene needs.
//
// This is the instructor-side renderer. Its intersection formulas are
// written for speed (32 rays per loop so the compiler can put one ray
// in each lane of a vector register), not for teaching; the course's
// formulas are the chapters' exercises, which the general path
// (general_path.hpp) calls.
#pragma once

#include "scene_plan.hpp"

#include "common/image.hpp"
#include "common/scene_file.hpp"

#include <functional>
#include <vector>

namespace rt::render_tool {

// Renders with the plan's precision and formulation, leaving out the loops
// the plan leaves out. Shading of lit scenes uses chapter 06's shade().
// stats (scene_plan.hpp) receives the rays traced and the time spent on
// setup (the scene's arrays and trees) before the first ray.
image render_fast(const scene_description& scene, const scene_plan& plan, int width, int height, render_stats& stats);

// The primary hit of every pixel, for measuring error: object number
// (spheres, then planes, then triangles; -1 for a miss) and t.
struct primary_hits {
    std::vector<int> object;
    std::vector<long double> t;
};

// Primary hits in the plan's precision and formulation.
primary_hits trace_primary(const scene_description& scene, const scene_plan& plan, int width, int height);

// Primary hits in long double with the robust formulation, from the file's
// numbers: the reference the error report compares with.
primary_hits trace_primary_reference(const scene_description& scene, int width, int height);

// How a benchmark times a pass it is handed: it may run it several times
// and returns the seconds of one pass (rt-bench keeps the fastest sample).
using pass_timer = std::function<double(const std::function<void()>& pass)>;

// Primary rays only, closest hit only, no shading: how many pixels hit
// something. The benchmark's measure of raw intersection throughput (the
// same work Embree's rtcIntersect does). The scene's arrays and trees are
// built first, untimed; then the image is traced once, or under `timed`
// when one is given, which puts the seconds of one trace in
// *trace_seconds: a benchmark times traces, not the build.
long count_primary_hits(const scene_description& scene, const scene_plan& plan, int width, int height,
                        const pass_timer& timed = nullptr, double* trace_seconds = nullptr);

// One lit render's shadow rays against its primary rays, apart from the
// shading. Every primary hit is found once; then each pass runs on every
// core under `timed` (which may run it several times: rt-bench keeps the
// fastest): the primary rays alone (ask_seconds excluded: a primary ray is
// made by the camera in a few operations); the shadow rays built as
// render_fast asks them ahead of chapter 06's shade() (its lambert and
// shadow_ray); those rays traced as render_fast traces them, 32 at a time
// (fast_path_shadows.hpp); the same rays one at a time (any_hit). Both ways
// must find the same blocked rays, and shade(), given the packets'
// answers, must ask no ray that was not asked ahead.
// rt-bench's measure of what a light's shadow rays cost.
struct shadow_figures {
    long primary_rays = 0, primary_hits = 0;
    long shadow_rays = 0, occluded = 0, occluded_one_at_a_time = 0;
    long asked_but_not_ahead = 0;
    double primary_seconds = 0, ask_seconds = 0, shadow_seconds = 0, one_at_a_time_seconds = 0;
};
shadow_figures time_shadow_rays(const scene_description& scene, const scene_plan& plan, int width, int height,
                                const pass_timer& timed);
// What building the scene's trees costs, apart from tracing: the boxes,
// the trees and the objects' float arrays in leaf order, as the specialised
// path would make them (rt-bench subtracts this from a traced run).
struct tree_figures {
    double build_seconds = 0;  // wall clock, inside the build
    size_t bytes = 0, leaves = 0, depth = 0;
};
tree_figures build_trees_only(const scene_description& scene);

// Which copy of the specialised path runs: "baseline" (any x86-64),
// "avx2" (AVX2 + FMA) or "avx512", chosen at start-up from the CPU (the
// environment variable RT_ISA forces one; see fast_path_dispatch.cpp).
const char* fast_path_isa();

// Rays per packet: a tile of 8 x 4 pixels. Four AVX2 registers of floats
// per quantity: the cost of fetching a sphere and deciding whether to skip
// it is shared by 32 rays.
inline constexpr int packet_width = 32;

}  // namespace rt::render_tool
