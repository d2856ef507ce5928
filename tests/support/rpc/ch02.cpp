// Chapter 02's exercise functions for the judge and the runner (table_builds.hpp explains the two halves).
#include "table_builds.hpp"
#include "02-sphere/sphere.hpp"

#if RT_RPC_DEFINES_STUBS
namespace rt::ch02 {
template <class T>
std::optional<hit_record<T>> intersect_sphere(const sphere<T>& s, const ray<T>& r, const interval<T>& range) {
    return RT_RPC_FORWARD(intersect_sphere, s, r, range);
}
}  // namespace rt::ch02
#endif

RT_RPC_FUNCTION(rt::ch02, intersect_sphere)
