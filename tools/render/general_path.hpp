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

#include "common/image.hpp"
#include "common/program.hpp"
#include "common/scene_file.hpp"

#include "scene_plan.hpp"

namespace rt::render_tool {

// In plan.prec; through chapter 08's tree when plan.tree says a tree pays,
// else through chapter 03's loop. rays counts primary and shadow rays.
image render_general(const scene_description& scene, const scene_plan& plan, int width, int height, render_stats& stats);

}  // namespace rt::render_tool
