// chapters_setup.hpp — what the paths that draw with the chapters' own code
// (general_path.cpp, whitted_path.cpp; sampled_path.cpp times its set-up
// alike) set up before the first ray: the scene in T with its camera, and the
// time the set-up took (render_stats' setup times, which rays per second
// leaves out).
#pragma once

#include "scene_plan.hpp"

#include "common/scene_file.hpp"
#include "common/timing.hpp"

namespace rt::render_tool {

// The scene file's world converted to T, as the chapters draw it, and its
// camera for a width x height picture.
template <class T>
struct chapters_scene {
    chapters_scene(const scene_description& d, int width, int height)
        : world(convert_scene<T>(d.world)), camera(d.camera, width, height) {}
    scene<T> world;
    scene_camera<T> camera;
};

// Times a set-up from its construction on: done() writes the wall-clock and
// CPU seconds since then into stats.
class setup_timer {
public:
    void done(render_stats& stats) const {
        stats.setup_seconds = wall_.seconds();
        stats.setup_cpu_seconds = process_cpu_seconds() - cpu_start_;
    }

private:
    stopwatch wall_;
    double cpu_start_ = process_cpu_seconds();
};

}  // namespace rt::render_tool
