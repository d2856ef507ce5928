// Chapter 03's exercise functions for the judge and the runner (table_builds.hpp explains the two halves).
// The intersector travels as a number: the judge answers each object the student's loop asks about
// (served_by_judge.hpp) with the object's own test, and its record of those calls decides the test's rules
// (served.hpp).
#include "served_by_judge.hpp"
#include "table_builds.hpp"
#include "03-scene-loop/scene_loop.hpp"

#if RT_RPC_DEFINES_STUBS
namespace rt::ch03 {
template <class T>
std::optional<hit_record<T>> closest_hit(int object_count, const object_intersector<T>& intersect, const ray<T>& r,
                                         interval<T> range) {
    return RT_RPC_FORWARD_SERVED(std::optional<hit_record<T>>, closest_hit, intersect, r, object_count, served, r,
                                 range);
}
}  // namespace rt::ch03
#endif

RT_RPC_FUNCTION(rt::ch03, closest_hit)
