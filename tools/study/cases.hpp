// cases.hpp — the study's case families: seeded, reproducible, and named cases.
//
// Each family is a list of queries (ray, primitive, range) in one precision,
// grouped (a far-sphere family has one group per distance and setup) so that
// results can be broken down. Inputs are generated in double and rounded to
// T once; the rounded inputs are the case, and the references are computed
// from exactly those inputs (reference.hpp).
#pragma once

#include "registry.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace rt::study {

using formulations::plane_query;
using formulations::sphere_query;
using formulations::triangle_query;

template <class Q>
struct family {
    std::string name;
    std::string description;
    std::vector<Q> queries;
    std::vector<int> group;  // per query: index into group_names
    std::vector<std::string> group_names;
    // Triangle meshes: queries that share one ray have the same ray_id, and
    // a ray whose line crosses the closed mesh must hit one of them (else
    // it leaks). Empty for other families.
    std::vector<int> ray_id;

    int add_group(const std::string& g) {
        group_names.push_back(g);
        return static_cast<int>(group_names.size()) - 1;
    }
    void add(const Q& q, int g, int ray = -1) {
        queries.push_back(q);
        group.push_back(g);
        if (ray >= 0) ray_id.push_back(ray);
    }
};

struct case_options {
    int per_group = 512;          // random queries per group
    std::uint64_t seed = 20261122;
};

// The far-sphere distances of the issue, in radii.
std::vector<double> far_distances();

// Sphere families: well, far, ground, grazing, origin, scale, special.
template <class T>
family<sphere_query<T>> well_sphere_family(const case_options& o);
template <class T>
family<sphere_query<T>> far_sphere_family(const case_options& o, const std::vector<double>& distances);
template <class T>
family<sphere_query<T>> ground_sphere_family(const case_options& o);
template <class T>
family<sphere_query<T>> grazing_sphere_family(const case_options& o);
template <class T>
family<sphere_query<T>> origin_sphere_family(const case_options& o);
template <class T>
family<sphere_query<T>> scale_sphere_family(const case_options& o);
template <class T>
family<sphere_query<T>> special_sphere_family();
template <class T>
std::vector<family<sphere_query<T>>> sphere_families(const case_options& o);

// Plane families: well, stiff (parallel, in the plane, nearly parallel,
// far grazing hit, large offset, invalid input).
template <class T>
std::vector<family<plane_query<T>>> plane_families(const case_options& o);

// Triangle families: well, edges (closed meshes, leaks), stiff (needle,
// tiny, far, degenerate, ray in the plane, invalid input).
template <class T>
family<triangle_query<T>> edge_triangle_family(const case_options& o);
template <class T>
std::vector<family<triangle_query<T>>> triangle_families(const case_options& o);

}  // namespace rt::study
