// chapter07_reference.cpp — the compensated sphere formulation is chapter
// 07's reference solution itself: its steps (solutions/07-precision/
// robust_sphere.cpp, one file, as a submission is) are compiled into this
// object, so the robust sphere is written once for the chapter, the study
// and the numerics tests.
//
// The copy lives in namespace rt::ch07_reference, not rt::ch07: a student
// build links the student's own rt::ch07 into the same programs (the study's
// "chapter 07" row measures it beside this one), and two definitions of one
// function would collide. The macro renames the namespace of the header and
// of the solution for this file only.
#define ch07 ch07_reference
#include "../robust_sphere.cpp"
#undef ch07

#include "sphere_formulations.hpp"

namespace rt::formulations {

template <class T>
std::optional<T> sphere_compensated(const ray<T>& ray_, const sphere<T>& s, const interval<T>& range) {
    const std::optional<hit_record<T>> hit = ch07_reference::intersect_sphere_robust(s, ray_, range);
    if (!hit) return std::nullopt;
    return hit->t;
}

template std::optional<float> sphere_compensated<float>(const ray<float>&, const sphere<float>&, const interval<float>&);
template std::optional<double> sphere_compensated<double>(const ray<double>&, const sphere<double>&,
                                                          const interval<double>&);

namespace detail {
double constant_term_of_floats(const vec3<float>& o, const sphere<float>& s) {
    // Step 4 wants a direction; c does not depend on it (any non-zero one).
    const ch07_reference::scaled_problem<float> p = ch07_reference::scaled_offset(s, ray<float>{o, {1, 0, 0}});
    return std::ldexp(ch07_reference::constant_term(p), -2 * p.ef);  // float data: ef = 0, nothing to undo
}
}  // namespace detail

}  // namespace rt::formulations
