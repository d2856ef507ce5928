// Chapter 05's exercise functions for the judge and the runner (table_builds.hpp explains the two halves).
#include "table_builds.hpp"
#include "05-triangle/triangle.hpp"

#if RT_RPC_DEFINES_STUBS
namespace rt::ch05 {
template <class T>
vec3<T> barycentric(const triangle<T>& tri, const vec3<T>& p) {
    return RT_RPC_FORWARD(barycentric, tri, p);
}
template <class T>
std::optional<hit_record<T>> intersect_triangle(const triangle<T>& tri, const ray<T>& r, const interval<T>& range) {
    return RT_RPC_FORWARD(intersect_triangle, tri, r, range);
}
}  // namespace rt::ch05
#endif

RT_RPC_FUNCTION(rt::ch05, barycentric)
RT_RPC_FUNCTION(rt::ch05, intersect_triangle)
