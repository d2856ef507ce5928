// whitted_path.hpp — scenes with mirrors and glass: chapter 09's recursive
// trace, called as it is.
//
// A mirror or a glass surface sends secondary rays (reflected, refracted),
// and their rules (the mirror direction, Snell's law with total internal
// reflection, Fresnel's exact reflectance, the error-bound offset of a
// spawned ray, the depth limit and the throughput cut-off) are chapter 09's
// exercises. The renderer does not write them again: every pixel's colour is
// ch09::trace of its primary ray, so rt-render's picture of
// scenes/ch09-whitted.json is chapter 09's picture (with whichever side the
// build selects, like the general path). Chapter 09's trace finds hits with
// chapter 03's loop: every object per ray, which is what the course's mirror
// scenes (a few objects) need, and no more.
#pragma once

#include "scene_plan.hpp"

#include "common/image.hpp"
#include "common/scene_file.hpp"

namespace rt::render_tool {

// In plan.prec, plan.depth bounces after the first hit. stats.rays counts the
// primary rays only (chapter 09's trace does not count the rays it makes).
image render_whitted(const scene_description& scene, const scene_plan& plan, int width, int height,
                     render_stats& stats);

}  // namespace rt::render_tool
