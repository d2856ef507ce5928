// fast_path_queries.hpp — part of fast_path.cpp (see fast_path_arrays.hpp):
// the two questions the pixel loops ask of the scene, each one call per
// kind of object the scene has (the others are compiled out).
#pragma once
#ifndef RT_FAST_PATH_PARTS
#error "a part of fast_path.cpp: included by it, after its headers and its target pragma"
#endif

// The closest hit of each ray of a packet: tbest[k] and object[k] (-1 for
// a miss), the scene's own number of the object (spheres, then planes, then
// triangles; with a tree too). At a tie, the lowest number.
template <class T, sphere_mode SM, bool Planes, bool Tris, bool CommonOrigin>
void closest_hits(const soa_scene<T>& s, const packet<T>& p, T tmin, T* tbest, index_t<T>* object) {
    packet_best<T> best(p);
    if constexpr (SM != sphere_mode::none) {
        if (s.tree)
            traverse_packet(s.sphere_tree, p, best.t, [&](size_t begin, size_t end) {
                spheres_closest<T, SM, CommonOrigin, true>(s, begin, end, p, tmin, best);
            });
        else
            spheres_closest<T, SM, CommonOrigin, false>(s, 0, s.sphere_count, p, tmin, best);
    }
    if constexpr (Planes) planes_closest<T, CommonOrigin>(s, p, tmin, best);
    if constexpr (Tris) triangles_closest<T, CommonOrigin>(s, p, tmin, best);
    for (int k = 0; k < W; ++k) {
        tbest[k] = best.t[k];
        object[k] = best.object[k];
    }
}

// Is anything hit with tmin < t < tmax? One ray (a shadow ray); each kind
// of object stops at its first blocker.
template <class T, sphere_mode SM, bool Planes, bool Tris>
bool any_hit(const soa_scene<T>& s, const ray<T>& light_ray, T tmin, T tmax) {
    const shadow_ray<T> r(light_ray);
    if constexpr (SM != sphere_mode::none)
        if (spheres_block<T, SM>(s, r, tmin, tmax)) return true;
    if constexpr (Planes)
        if (planes_block(s, r, tmin, tmax)) return true;
    if constexpr (Tris)
        if (triangles_block(s, r, tmin, tmax)) return true;
    return false;
}
