// fast_path_planes.hpp — part of fast_path.cpp (see fast_path_arrays.hpp):
// the plane lane loops (the kernels, plane_t and plane_t_exact, are in
// fast_path_kernels.hpp). Planes are unbounded: no tree, every plane is
// asked.
#pragma once
#ifndef RT_FAST_PATH_PARTS
#error "a part of fast_path.cpp: included by it, after its headers and its target pragma"
#endif

// n . (point - origin) for plane i and one origin.
template <class T>
[[gnu::always_inline]] inline T plane_numerator(const soa_scene<T>& s, size_t i, T ox, T oy, T oz) {
    return s.nx[i] * (s.px[i] - ox) + s.ny[i] * (s.py[i] - oy) + s.nz[i] * (s.pz[i] - oz);
}

// Every plane against the packet (objects numbered after the spheres).
template <class T, bool CommonOrigin>
[[gnu::always_inline]] inline void planes_closest(const soa_scene<T>& s, const packet<T>& p, T tmin, packet_best<T>& best) {
    using I = index_t<T>;
    const I base = I(s.sphere_count);
    for (size_t i = 0; i < s.plane_count; ++i) {
        const T nx = s.nx[i], ny = s.ny[i], nz = s.nz[i];
        int unsure = 0;
        for (int k = 0; k < W; ++k) {
            const int o = CommonOrigin ? 0 : k;
            const T num = plane_numerator(s, i, p.ox[o], p.oy[o], p.oz[o]);
            best.keep(k, plane_t(num, nx, ny, nz, p.dx[k], p.dy[k], p.dz[k], tmin, unsure), base + I(i));
        }
        if (unsure)  // a ray nearly or exactly parallel: decide exactly (keep takes a t once)
            for (int k = 0; k < W; ++k) {
                const int o = CommonOrigin ? 0 : k;
                const T num = plane_numerator(s, i, p.ox[o], p.oy[o], p.oz[o]);
                best.keep(k, plane_t_exact(num, nx, ny, nz, p.dx[k], p.dy[k], p.dz[k], tmin, s.plane_normal(i)),
                          base + I(i));
            }
    }
}

// Is the shadow ray blocked by a plane? shadow_group planes at a time.
template <class T>
[[gnu::always_inline]] inline bool planes_block(const soa_scene<T>& s, const shadow_ray<T>& r, T tmin, T tmax) {
    for (size_t i = 0; i < shadow_groups(s.plane_count); i += shadow_group) {
        int blocked = 0, unsure = 0;
        for (int k = 0; k < shadow_group; ++k) {
            const size_t j = i + size_t(k);
            const T num = plane_numerator(s, j, r.ox, r.oy, r.oz);
            blocked |= int(plane_t(num, s.nx[j], s.ny[j], s.nz[j], r.dx, r.dy, r.dz, tmin, unsure) < tmax);
        }
        if (unsure && !blocked)  // nearly parallel: decide exactly
            for (size_t j = i; j < i + shadow_group && j < s.plane_count; ++j) {  // past the count: padding
                const T num = plane_numerator(s, j, r.ox, r.oy, r.oz);
                blocked |= int(plane_t_exact(num, s.nx[j], s.ny[j], s.nz[j], r.dx, r.dy, r.dz, tmin,
                                             s.plane_normal(j)) < tmax);
            }
        if (blocked) return true;
    }
    return false;
}
