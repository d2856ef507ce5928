// fast_path_queries.hpp — part of fast_path.cpp (see fast_path_arrays.hpp):
// the two questions the pixel loops ask of the scene, each one call per
// kind of object the scene has (a kind it has none of is skipped by one
// branch per packet or shadow ray).
#pragma once
#ifndef RT_FAST_PATH_PARTS
#error "a part of fast_path.cpp: included by it, after its headers and its target pragma"
#endif

// closest_hits for a packet whose every direction is of a comfortable
// length (packet_best's d_max finite): d.d and the kernels' products
// neither underflow nor overflow. Blocking: only whether each ray hits
// anything matters (shadow rays), so a ray that has hit something is done:
// its t becomes -infinity, which enters no box and is beaten by no hit.
template <class T, sphere_mode SM, bool CommonOrigin, bool Blocking = false>
void closest_hits_comfortable(const soa_scene<T>& s, const packet<T>& p, packet_best<T>& best, T tmin, T* tbest,
                              index_t<T>* object) {
    auto finish_blocked = [&] {
        if constexpr (Blocking)
            for (int k = 0; k < W; ++k) best.t[k] = best.object[k] >= 0 ? -infinity<T> : best.t[k];
    };
    if (s.sphere_count > 0) {
        if (s.tree)
            traverse_packet(
                s.sphere_tree, p, best.t,
                [&](size_t begin, size_t end) {
                    spheres_closest<T, SM, CommonOrigin, true>(s, begin, end, p, tmin, best);
                    finish_blocked();
                },
                [&](int k, size_t begin, size_t end) {
                    spheres_closest_one<T, SM>(s, begin, end, p, k, tmin, best);
                    if constexpr (Blocking) best.t[k] = best.object[k] >= 0 ? -infinity<T> : best.t[k];
                });
        else
            spheres_closest<T, SM, CommonOrigin, false>(s, 0, s.sphere_count, p, tmin, best);
        finish_blocked();
    }
    if (s.plane_count > 0) planes_closest<T, CommonOrigin>(s, p, tmin, best);
    if (s.triangle_count > 0) triangles_closest<T, CommonOrigin>(s, p, tmin, best);
    for (int k = 0; k < W; ++k) {
        tbest[k] = best.t[k];
        object[k] = best.object[k];
    }
}

// A packet with a direction too short or too long for the kernels (a
// normal float direction of length 1e-20 has d.d = 1e-40, and 1 / d.d
// overflows): each ray goes alone, as a packet of 32 copies of itself with
// its direction scaled by 2^e (direction_scale, exact). The ray
// o + t' 2^e d is o + t d with t = 2^e t', so the range and the answer
// scale back exactly, and every kernel answers as for a comfortable
// direction. The camera makes no such ray (a primary direction is at least
// as long as the distance 1 to the image plane); a packet built otherwise
// may hold one.
template <class T, sphere_mode SM, bool CommonOrigin, bool Blocking = false>
void closest_hits_scaled(const soa_scene<T>& s, const packet<T>& p, T tmin, const T* tmax, T* tbest,
                         index_t<T>* object) {
    for (int k = 0; k < W; ++k) {
        const int o = CommonOrigin ? 0 : k;
        const int e = formulations::direction_scale(vec3<T>(p.dx[k], p.dy[k], p.dz[k]));
        packet<T> alone;
        for (int j = 0; j < W; ++j) {
            alone.ox[j] = p.ox[o], alone.oy[j] = p.oy[o], alone.oz[j] = p.oz[o];
            alone.dx[j] = std::ldexp(p.dx[k], e), alone.dy[j] = std::ldexp(p.dy[k], e), alone.dz[j] = std::ldexp(p.dz[k], e);
        }
        packet_best<T> best(alone);
        if (tmax)
            for (int j = 0; j < W; ++j) best.t[j] = std::ldexp(tmax[k], -e);
        alignas(64) T t[W];
        alignas(64) index_t<T> id[W];
        closest_hits_comfortable<T, SM, true, Blocking>(s, alone, best, std::ldexp(tmin, -e), t, id);
        tbest[k] = std::ldexp(t[0], e);  // infinity (a miss) stays infinity
        object[k] = id[0];
    }
}

// The closest hit of each ray of a packet: tbest[k] and object[k] (-1 for
// a miss), the scene's own number of the object (spheres, then planes, then
// triangles; with a tree too). At a tie, the lowest number. With tmax, only
// hits with t < tmax[k] count (a miss leaves tbest[k] = tmax[k]): ray k is
// then blocked, in any_hit's sense, exactly when object[k] >= 0, since
// every loop keeps a t only below the best so far and asks the same
// kernels any_hit asks. Blocking (shadow rays): only that is answered, and
// tbest is not a hit's t.
template <class T, sphere_mode SM, bool CommonOrigin, bool Blocking = false>
void closest_hits(const soa_scene<T>& s, const packet<T>& p, T tmin, T* tbest, index_t<T>* object,
                  const T* tmax = nullptr) {
    packet_best<T> best(p);
    if (tmax) best.limit(tmax);
    int uncomfortable = 0;  // d_max is infinite for a direction to scale (or an infinite one: e = 0, a miss)
    for (int k = 0; k < W; ++k) uncomfortable |= int(best.d_max[k] == infinity<T>);
    if (uncomfortable)
        closest_hits_scaled<T, SM, CommonOrigin, Blocking>(s, p, tmin, tmax, tbest, object);
    else
        closest_hits_comfortable<T, SM, CommonOrigin, Blocking>(s, p, best, tmin, tbest, object);
}

// Is anything hit with tmin < t < tmax? One ray (a shadow ray); each kind
// of object stops at its first blocker.
template <class T, sphere_mode SM>
bool any_hit(const soa_scene<T>& s, const ray<T>& light_ray, T tmin, T tmax) {
    const shadow_ray<T> r(light_ray);
    if (r.d_max == infinity<T>) {
        // A direction too short or too long for the kernels (see
        // closest_hits_scaled): the same ray with its direction scaled by
        // 2^e, and the range by 2^-e. A shadow ray from a hit to a light a
        // hair away from it is one.
        const int e = formulations::direction_scale(light_ray.direction);
        if (e != 0) {
            const vec3<T>& d = light_ray.direction;
            const vec3<T> scaled(std::ldexp(d.x, e), std::ldexp(d.y, e), std::ldexp(d.z, e));
            return any_hit<T, SM>(s, ray<T>{light_ray.origin, scaled}, std::ldexp(tmin, -e), std::ldexp(tmax, -e));
        }
    }
    if (s.sphere_count > 0 && spheres_block<T, SM>(s, r, tmin, tmax)) return true;
    if (s.plane_count > 0 && planes_block(s, r, tmin, tmax)) return true;
    if (s.triangle_count > 0 && triangles_block(s, r, tmin, tmax)) return true;
    return false;
}
