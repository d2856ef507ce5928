// general_path.hpp — the renderer that does everything for every scene,
// through the chapters' exercises.
//
// Every primary ray goes through chapter 03's closest_hit, which tests every
// object through a std::function that picks chapter 02's sphere test,
// chapter 04's plane test or chapter 05's triangle test; lit scenes are
// shaded by chapter 06's shade() with its shadow rays through the same
// loop. When the plan says a tree pays, chapter 08's tree (its build_sah,
// closest_hit and any_hit) replaces the loop for spheres and triangles. So this path renders with whichever side the build selects (your
// code or the reference solutions), and it is the baseline the specialised
// path (fast_path.hpp) is measured against.
#pragma once

#include "common/heatmap.hpp"
#include "common/image.hpp"
#include "common/program.hpp"
#include "common/scene_file.hpp"

#include "scene_plan.hpp"

namespace rt::render_tool {

// In plan.prec; through chapter 08's tree when plan.tree says a tree pays,
// else through chapter 03's loop. rays counts primary and shadow rays.
image render_general(const scene_description& scene, const scene_plan& plan, int width, int height, render_stats& stats);

// --heatmap: per pixel's primary ray, in plan.prec, the boxes opened and
// objects asked by chapter 08's closest_hit over chapter 08's tree (built
// here even where the plan renders without one), and brute force's objects
// asked (chapter 03's loop). Counted on this general path whichever path drew
// the picture (the specialised path's packets are not counted).
// 08-acceleration/tree_heatmap.hpp says what is counted.
std::vector<count_map> heatmap_general(const scene_description& scene, const scene_plan& plan, int width, int height);

}  // namespace rt::render_tool
