#include "render_planned.hpp"

#include "fast_path.hpp"
#include "general_path.hpp"
#include "sampled_path.hpp"
#include "whitted_path.hpp"

namespace rt::render_tool {

image render_planned(const scene_description& scene, const scene_plan& plan, int width, int height,
                     render_stats& stats) {
    if (plan.sampled()) return render_sampled(scene, plan, width, height, stats);
    if (plan.secondary_rays()) return render_whitted(scene, plan, width, height, stats);
    if (plan.general) return render_general(scene, plan, width, height, stats);
    return render_fast(scene, plan, width, height, stats);
}

const char* renderer_name(const scene_plan& plan) {
    if (plan.sampled()) return plan.path_traced ? "path-traced (chapter 12)" : plan.secondary_rays() ? "sampled (chapters 11 and 09)" : "sampled (chapter 11)";
    if (plan.secondary_rays()) return "recursive (chapter 09)";
    return plan.general ? "general" : "specialised";
}

}  // namespace rt::render_tool
