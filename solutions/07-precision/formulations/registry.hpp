// registry.hpp — every formulation by name, in float and in double.
//
// The study tool and the numerics tests walk these tables, so a new
// formulation is measured and tested everywhere once it is listed in
// registry.cpp. Each entry holds, per precision, the routine itself (for
// checking answers) and a batch loop with the routine inlined into it (for
// timing: a call through a pointer per test would add the same few
// nanoseconds to everyone and hide the differences).
#pragma once

#include "plane_formulations.hpp"
#include "sphere_formulations.hpp"
#include "triangle_formulations.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace rt::formulations {

// One query: what each routine is asked.
template <class T, class Shape>
struct query {
    ray<T> r;
    Shape shape;
    interval<T> range;
};

template <class T>
using sphere_query = query<T, sphere<T>>;
template <class T>
using plane_query = query<T, plane<T>>;
template <class T>
using triangle_query = query<T, triangle<T>>;

template <class T>
using sphere_fn = std::optional<T> (*)(const ray<T>&, const sphere<T>&, const interval<T>&);
template <class T>
using plane_fn = std::optional<plane_hit<T>> (*)(const ray<T>&, const plane<T>&, const interval<T>&);
template <class T>
using triangle_fn = std::optional<T> (*)(const ray<T>&, const triangle<T>&, const interval<T>&);

// A batch loop returns a number that depends on every answer, so the
// compiler cannot drop the work being timed.
template <class Q>
using batch_fn = double (*)(const Q* queries, std::size_t count);

template <class T>
double answer_weight(const std::optional<T>& t) {
    return t ? static_cast<double>(*t) : 0.5;
}
template <class T>
double answer_weight(const std::optional<plane_hit<T>>& h) {
    return h ? static_cast<double>(h->t + h->point.x) : 0.5;
}

template <class Q, auto F>
double run_batch(const Q* queries, std::size_t count) {
    double sum = 0;
    for (std::size_t i = 0; i < count; ++i) sum += answer_weight(F(queries[i].r, queries[i].shape, queries[i].range));
    return sum;
}

// One formulation of one primitive, in both precisions.
template <template <class> class Fn, template <class> class Q>
struct formulation {
    std::string name;
    std::string idea;  // one line: what it does about rounding
    Fn<float> f32;
    Fn<double> f64;
    batch_fn<Q<float>> batch32;
    batch_fn<Q<double>> batch64;

    template <class T>
    Fn<T> fn() const {
        if constexpr (sizeof(T) == sizeof(float)) return f32; else return f64;
    }
    template <class T>
    batch_fn<Q<T>> batch() const {
        if constexpr (sizeof(T) == sizeof(float)) return batch32; else return batch64;
    }
};

using sphere_formulation = formulation<sphere_fn, sphere_query>;
using plane_formulation = formulation<plane_fn, plane_query>;
using triangle_formulation = formulation<triangle_fn, triangle_query>;

const std::vector<sphere_formulation>& sphere_formulations();
const std::vector<plane_formulation>& plane_formulations();
const std::vector<triangle_formulation>& triangle_formulations();

// The entry with this name; throws std::out_of_range when there is none.
const sphere_formulation& sphere_formulation_named(const std::string& name);
const triangle_formulation& triangle_formulation_named(const std::string& name);
const plane_formulation& plane_formulation_named(const std::string& name);

}  // namespace rt::formulations
