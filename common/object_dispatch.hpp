// object_dispatch.hpp — "does the ray hit object i of the scene?", written once.
//
// Every program that draws a scene (chapters 03 to 06, the renderer's
// general path, chapter 08's tree leaves) must turn an object number into a
// call of the right shape's test. This class does only that bookkeeping:
// objects are numbered spheres, then planes, then triangles (scene.hpp). The
// tests themselves are the chapters' exercises, so they are passed in; no
// formula lives here. A program that cannot draw planes or triangles yet
// passes no test for them, and then its scene must have none of them
// (program.hpp's chapter_program::draws removes them, and says so).
//
// Two questions, two names:
//   shape_hit(i, r, range)        the shape's own answer, an optional hit whose
//                                 `object` field is left for the loop to set
//                                 (chapter 03's object_intersector contract);
//   object_hit(i, r, range, hit)  true on a hit, and then `hit` holds it with
//                                 hit.object = i (chapter 08's leaf contract).
//
//   const ch03::object_intersector<T> intersect =
//       object_dispatch(world, ch02::intersect_sphere<T>, ch04::intersect_plane<T>).intersector();
#pragma once

#include "hit_record.hpp"
#include "interval.hpp"
#include "ray.hpp"
#include "scene.hpp"

#include <optional>
#include <stdexcept>
#include <type_traits>

namespace rt {

// The test of a shape kind the program does not draw.
struct no_test {};

template <class T, class SphereTest, class PlaneTest = no_test, class TriangleTest = no_test>
class object_dispatch {
public:
    // Keeps a reference to s: the scene must outlive the dispatch.
    explicit object_dispatch(const scene<T>& s, SphereTest sphere, PlaneTest plane = {}, TriangleTest triangle = {})
        : scene_(&s), sphere_(sphere), plane_(plane), triangle_(triangle) {
        // Without a test for a kind, objects of that kind would be numbered but never hit.
        if (!draws<PlaneTest>() && !s.planes.empty())
            throw std::invalid_argument("this program cannot draw the scene's planes");
        if (!draws<TriangleTest>() && !s.triangles.empty())
            throw std::invalid_argument("this program cannot draw the scene's triangles");
    }

    int count() const { return scene_->object_count(); }

    // The shape's own answer, unchanged (its `object` field is the loop's to set).
    std::optional<hit_record<T>> shape_hit(int object, const ray<T>& r, const interval<T>& range) const {
        const object_ref o = locate(*scene_, object);
        if (o.kind == shape_kind::sphere) return sphere_(scene_->spheres[o.index], r, range);
        if constexpr (draws<PlaneTest>())
            if (o.kind == shape_kind::plane) return plane_(scene_->planes[o.index], r, range);
        if constexpr (draws<TriangleTest>())
            if (o.kind == shape_kind::triangle) return triangle_(scene_->triangles[o.index], r, range);
        return std::nullopt;  // unreachable: the constructor refused kinds without a test
    }

    // The same question in the form a tree's leaves ask it (chapter 08): true
    // on a hit inside range, and then `hit` holds it with hit.object = object.
    bool object_hit(int object, const ray<T>& r, const interval<T>& range, hit_record<T>& hit) const {
        const std::optional<hit_record<T>> h = shape_hit(object, r, range);
        if (!h) return false;
        hit = *h;
        hit.object = object;
        return true;
    }

    // shape_hit as a function object, for chapter 03's object_intersector. It
    // holds a copy of this dispatch (a pointer to the scene and the tests), so
    // it may outlive the dispatch, not the scene.
    auto intersector() const {
        return [dispatch = *this](int object, const ray<T>& r, const interval<T>& range) {
            return dispatch.shape_hit(object, r, range);
        };
    }

private:
    template <class Test>
    static constexpr bool draws() {
        return !std::is_same_v<Test, no_test>;
    }

    const scene<T>* scene_;
    SphereTest sphere_;
    PlaneTest plane_;
    TriangleTest triangle_;
};

// Deduction guides: the tests are usually function template specialisations
// such as ch02::intersect_sphere<T>, which decay to function pointers.
template <class T, class S>
object_dispatch(const scene<T>&, S) -> object_dispatch<T, S>;
template <class T, class S, class P>
object_dispatch(const scene<T>&, S, P) -> object_dispatch<T, S, P>;
template <class T, class S, class P, class Tr>
object_dispatch(const scene<T>&, S, P, Tr) -> object_dispatch<T, S, P, Tr>;

}  // namespace rt
