// fast_path_dispatch.cpp — picks the copy of the specialised path
// (fast_path.cpp, compiled once per instruction set) that this CPU can run,
// once, at the first call.
//
// RT_ISA=baseline|avx2|avx512 in the environment forces a copy (to measure
// it, or to test the plain x86-64 path on a machine with wider units); a
// copy the CPU cannot run is refused with a message, not run into an
// illegal instruction.
#include "fast_path.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace rt::render_tool {

// The three copies' entry points.
#define RT_DECLARE_FAST_PATH(ns)                                                                               \
    namespace ns {                                                                                             \
    image render_fast(const scene_description&, const scene_plan&, int, int, long&);                           \
    primary_hits trace_primary(const scene_description&, const scene_plan&, int, int);                        \
    primary_hits trace_primary_reference(const scene_description&, int, int);                                 \
    long count_primary_hits(const scene_description&, const scene_plan&, int, int, int);                           \
    tree_figures build_trees_only(const scene_description&);                                                  \
    }
RT_DECLARE_FAST_PATH(isa_baseline)
RT_DECLARE_FAST_PATH(isa_avx2)
RT_DECLARE_FAST_PATH(isa_avx512)
#undef RT_DECLARE_FAST_PATH

namespace {

enum class isa { baseline, avx2, avx512 };

bool cpu_has(isa i) {
#if RT_FAST_BASELINE_ONLY
    return i == isa::baseline;  // the sanitizer build compiles the plain copy only
#endif
    __builtin_cpu_init();
    switch (i) {
        case isa::baseline: return true;
        case isa::avx2: return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
        case isa::avx512:
            return cpu_has(isa::avx2) && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                   __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
    }
    return false;
}

const char* name_of(isa i) { return i == isa::avx512 ? "avx512" : i == isa::avx2 ? "avx2" : "baseline"; }

isa choose() {
    if (const char* forced = std::getenv("RT_ISA"); forced && *forced) {
        for (isa i : {isa::baseline, isa::avx2, isa::avx512})
            if (std::string(forced) == name_of(i)) {
                if (!cpu_has(i))
                    throw std::runtime_error(std::string("RT_ISA=") + forced + ": this CPU cannot run it");
                return i;
            }
        throw std::runtime_error(std::string("RT_ISA=") + forced + ": expected baseline, avx2 or avx512");
    }
    return cpu_has(isa::avx512) ? isa::avx512 : cpu_has(isa::avx2) ? isa::avx2 : isa::baseline;
}

isa chosen() {
    static const isa once = choose();
    return once;
}

}  // namespace

const char* fast_path_isa() { return name_of(chosen()); }

#if RT_FAST_BASELINE_ONLY
#define RT_DISPATCH(call)  \
    (void)chosen();        \
    return isa_baseline::call;
#else
#define RT_DISPATCH(call)                                        \
    switch (chosen()) {                                          \
        case isa::avx512: return isa_avx512::call;               \
        case isa::avx2: return isa_avx2::call;                   \
        default: return isa_baseline::call;                      \
    }
#endif

image render_fast(const scene_description& d, const scene_plan& plan, int width, int height, long& rays) {
    RT_DISPATCH(render_fast(d, plan, width, height, rays))
}
primary_hits trace_primary(const scene_description& d, const scene_plan& plan, int width, int height) {
    RT_DISPATCH(trace_primary(d, plan, width, height))
}
primary_hits trace_primary_reference(const scene_description& d, int width, int height) {
    RT_DISPATCH(trace_primary_reference(d, width, height))
}
long count_primary_hits(const scene_description& d, const scene_plan& plan, int width, int height, int repeat) {
    RT_DISPATCH(count_primary_hits(d, plan, width, height, repeat))
}

tree_figures build_trees_only(const scene_description& d) { RT_DISPATCH(build_trees_only(d)) }

}  // namespace rt::render_tool
