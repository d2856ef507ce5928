// Chapter 01's exercise functions for the judge and the runner (table_builds.hpp explains the two halves).
#include "table_builds.hpp"
#include "01-unit-sphere/unit_sphere.hpp"

#if RT_RPC_DEFINES_STUBS
namespace rt::ch01 {
template <class T>
std::optional<T> intersect_unit_sphere(const ray<T>& r, const interval<T>& range) {
    return RT_RPC_FORWARD(intersect_unit_sphere, r, range);
}
}  // namespace rt::ch01
#endif

RT_RPC_FUNCTION(rt::ch01, intersect_unit_sphere)
