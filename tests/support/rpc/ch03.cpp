// Chapter 03's exercise functions for the judge and the runner (table.hpp explains the two halves).
// The intersector is a callback: the student's loop calls it in the runner, it runs in the judge.
#include "table.hpp"
#include "03-scene-loop/scene_loop.hpp"

#if RT_RPC_DEFINES_STUBS
namespace rt::ch03 {
template <class T>
std::optional<hit_record<T>> closest_hit(int object_count, const object_intersector<T>& intersect, const ray<T>& r,
                                         interval<T> range) {
    return RT_RPC_FORWARD(closest_hit, object_count, intersect, r, range);
}
}  // namespace rt::ch03
#endif

RT_RPC_FUNCTION(rt::ch03, closest_hit)
