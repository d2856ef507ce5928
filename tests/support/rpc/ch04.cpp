// Chapter 04's exercise functions for the judge and the runner (table_builds.hpp explains the two halves).
#include "04-plane/plane.hpp"
#include "table_builds.hpp"

#if RT_RPC_DEFINES_STUBS
namespace rt::ch04 {
template <class T>
std::optional<hit_record<T>> intersect_plane(const plane<T>& p, const ray<T>& r, const interval<T>& range) {
    return RT_RPC_FORWARD(intersect_plane, p, r, range);
}
}  // namespace rt::ch04
#endif

RT_RPC_FUNCTION(rt::ch04, intersect_plane)
