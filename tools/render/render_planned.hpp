// render_planned.hpp — the one place that turns a plan into the renderer
// that draws it (rt-render and rt-bench both call it).
//
//   plan.sampled()         the chapters' samplers (sampled_path.hpp): the path
//                          tracer, chapter 11's picture, or chapter 09's trace per sample
//   plan.secondary_rays()  chapter 09's trace, one ray per pixel (whitted_path.hpp)
//   plan.general           the general path (general_path.hpp)
//   otherwise              the specialised path (fast_path.hpp), plan.spp rays per pixel
#pragma once

#include "scene_plan.hpp"

#include "common/image.hpp"
#include "common/scene_file.hpp"

namespace rt::render_tool {

image render_planned(const scene_description& scene, const scene_plan& plan, int width, int height,
                     render_stats& stats);

// Which renderer render_planned uses, for the render line: "specialised",
// "general", "recursive (chapter 09)", "sampled (chapter 11)", "path-traced (chapter 12)".
const char* renderer_name(const scene_plan& plan);

}  // namespace rt::render_tool
