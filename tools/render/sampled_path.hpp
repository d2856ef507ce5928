// sampled_path.hpp — many samples per pixel: chapter 11's sampling and
// chapter 12's path tracer, called as the chapters' programs call them.
//
// A pixel of a sampled render is the filtered average of --spp samples. The
// samples are stratified (chapter 11's stratified_sample, through its
// pixel_sequence) and every number a pixel uses comes from its own PCG32
// stream (common/random.hpp), so the picture is the same on every run and
// every thread count. What a sample's ray brings back depends on the scene
// (scene_plan::describe says which):
//
//   path tracer (plan.path_traced)  chapter 12's path_radiance: next-event
//       estimation of the sphere lights (chapter 11's cone sample), cosine-
//       weighted bounces, Russian roulette; a box filter. The scene's sphere
//       lights become emitting spheres of radiance intensity / (pi r^2)
//       (scenes/README.md), its materials' diffuse colours the albedos.
//   mirrors or glass                chapter 09's trace of each sample's ray; a box filter.
//   otherwise                       chapter 11's picture (ch11::sampled_scene): the
//       thin lens, sphere lights sampled by cone (soft shadows), the tent filter.
//
// Every ray goes through chapter 03's loop, as in the chapters: these scenes
// are small, and the specialised kernels trace one primary ray per pixel.
#pragma once

#include "scene_plan.hpp"

#include "common/image.hpp"
#include "common/scene_file.hpp"

namespace rt::render_tool {

// In plan.prec with plan.spp samples per pixel, from plan.seed. stats.samples counts the
// samples (paths for the path tracer), stats.rays what the chapters count:
// chapter 11's primary and shadow rays; for the path tracer and chapter 09's
// trace the samples only (stats.primary_only).
// Throws std::invalid_argument for what the chapters cannot draw: an
// orthographic camera (chapter 11's lens is a pinhole's), triangles or point
// lights in a path-traced scene (chapter 12 draws spheres and planes, lit by
// sphere lights).
image render_sampled(const scene_description& scene, const scene_plan& plan, int width, int height,
                     render_stats& stats);

}  // namespace rt::render_tool
