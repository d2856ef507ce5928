// Chapter 07's exercise functions for the judge and the runner (table.hpp explains the two halves).
#include "07-precision/robust_sphere.hpp"
#include "table.hpp"

#if RT_RPC_DEFINES_STUBS
namespace rt::ch07 {
template <class T>
std::optional<hit_record<T>> intersect_sphere_robust(const sphere<T>& s, const ray<T>& r, const interval<T>& range) {
    return RT_RPC_FORWARD(intersect_sphere_robust, s, r, range);
}
}  // namespace rt::ch07
#endif

RT_RPC_FUNCTION(rt::ch07, intersect_sphere_robust)
