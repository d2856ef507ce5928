// ch08_fields.hpp — how chapter 08's boxes and tree nodes travel (exact_bits.hpp's fields()), shared by
// the tables of the chapters that send them: chapter 08's, and chapter 10's (its top-level tree).
#pragma once

#include "08-acceleration/aabb.hpp"
#include "08-acceleration/bvh.hpp"
#include "exact_bits.hpp"

namespace rt::ch08 {
template <class T, class F>
void fields(aabb<T>& x, F&& f) {
    f(x.lo, x.hi);
}
template <class T, class F>
void fields(bvh_node<T>& x, F&& f) {
    f(x.box, x.first, x.count);
}
}  // namespace rt::ch08
