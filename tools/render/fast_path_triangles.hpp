// fast_path_triangles.hpp — part of fast_path.cpp (see fast_path_arrays.hpp):
// the triangle lane loops (the kernels, triangle_t and triangle_t_exact,
// are in fast_path_kernels.hpp): brute force over a packet, the packet's
// walk of the wide tree, and the shadow ray's any hit. All three run the same
// per-lane arithmetic (triangle_lane_t), so they agree to the bit.
#pragma once
#ifndef RT_FAST_PATH_PARTS
#error "a part of fast_path.cpp: included by it, after its headers and its target pragma"
#endif

// One ray against the scene's triangle j, by the brute-force kernel: the
// per-lane work of every triangle loop below (brute force, the tree's leaves
// and the shadow test), written once so they stay the same to the bit.
template <class T>
[[gnu::always_inline]] inline T triangle_lane_t(const soa_scene<T>& s, size_t j, T ox, T oy, T oz, T dx, T dy, T dz,
                                                T d_max, T tmin, int& unsure) {
    const T sx = ox - s.ax[j], sy = oy - s.ay[j], sz = oz - s.az[j];
    const T qx = sy * s.e1z[j] - sz * s.e1y[j], qy = sz * s.e1x[j] - sx * s.e1z[j], qz = sx * s.e1y[j] - sy * s.e1x[j];
    const T flat_bound = flat_scale(s.e1x[j], s.e1y[j], s.e1z[j], s.e2x[j], s.e2y[j], s.e2z[j]) * d_max + flat_tiny<T>();
    return triangle_t(sx, sy, sz, qx, qy, qz, s.e1x[j], s.e1y[j], s.e1z[j], s.e2x[j], s.e2y[j], s.e2z[j], dx, dy, dz,
                      tmin, flat_bound, unsure);
}

// triangle_t_exact for the scene's triangle j (j < triangle_count): the
// scalar path for the rare lanes triangle_t was unsure of.
template <class T>
T triangle_exact_t(const soa_scene<T>& s, size_t j, T ox, T oy, T oz, T dx, T dy, T dz, T tmin) {
    const T sx = ox - s.ax[j], sy = oy - s.ay[j], sz = oz - s.az[j];
    const T qx = sy * s.e1z[j] - sz * s.e1y[j], qy = sz * s.e1x[j] - sx * s.e1z[j], qz = sx * s.e1y[j] - sy * s.e1x[j];
    const std::array<vec3<T>, 3> c = s.corners(j);
    return triangle_t_exact(sx, sy, sz, qx, qy, qz, s.e1x[j], s.e1y[j], s.e1z[j], s.e2x[j], s.e2y[j], s.e2z[j], dx, dy,
                            dz, tmin, c[0], c[1], c[2]);
}

// One ray against the triangles [g, g + leaf_lanes) of a tree's leaf that
// ends at e (lanes from e on, other leaves' triangles or padding, give
// infinity): t[i] for triangle g + i, by the brute-force kernel in
// leaf_lanes lanes, then triangle_t_exact for the whole group when a lane
// was unsure (as the brute-force loops do), so t is the same to the bit.
template <class T>
struct triangle_group {
    alignas(64) T t[leaf_lanes];

    triangle_group(const soa_scene<T>& s, size_t g, size_t e, T ox, T oy, T oz, T dx, T dy, T dz, T d_max, T tmin) {
        int unsure = 0;
        for (int i = 0; i < leaf_lanes; ++i) {
            const size_t j = g + size_t(i);
            const T x = triangle_lane_t(s, j, ox, oy, oz, dx, dy, dz, d_max, tmin, unsure);
            t[i] = j < e ? x : infinity<T>;
        }
        if (!unsure) return;
        for (int i = 0; i < leaf_lanes; ++i) {  // nearly parallel or degenerate: decide exactly
            const size_t j = g + size_t(i);
            if (j >= e) break;
            t[i] = triangle_exact_t(s, j, ox, oy, oz, dx, dy, dz, tmin);
        }
    }

    bool blocked_before(T tmax) const {
        int blocked = 0;
        for (int i = 0; i < leaf_lanes; ++i) blocked |= int(t[i] < tmax);
        return blocked != 0;
    }
};

// The cull sphere's squared radius for a ray whose origin is f from its
// centre, with the cull's own rounding taken in. Why it is conservative
// (u = epsilon / 2, no underflow or overflow: the renderer's directions are
// scaled to a comfortable length, shadow_ray and packet_best): the computed
// perpendicular g = fl(f - fl(fl(f.d) / fl(d.d)) d) is within about 11 u |f|
// of the exact one (f within u |f|, the quotient within 8 u |f| / |d|, the
// product and the difference u more each; |g| <= |f|), and
// (r + x)^2 <= 1.01 r^2 + 101 x^2 for every x (AM-GM). So with
// x = 16 u |f| a ray that passes within r of the centre has
// |g|^2 <= 1.01 r^2 + 101 x^2, and the 1.02 that br2 and this term carry
// leaves room for the rounding of the squares and sums (a few u). The
// term x^2 matters only for a triangle smaller than float's rounding of
// its distance (a few 1e-6 of it); the 1% and the boxes' padding are the
// rest (add_triangle).
template <class T>
inline T cull_radius2(T br2, T fx, T fy, T fz) {
    constexpr T u = std::numeric_limits<T>::epsilon() / 2;
    constexpr T rounding = T(1.02 * 101 * 256) * u * u;
    return br2 + rounding * (fx * fx + fy * fy + fz * fz);
}

// Does some ray of the packet come near triangle i's bounding sphere? (The
// robust discriminant: accurate even when the triangle is small and far away.)
// Never drops a triangle whose kernel would report a hit the tree's padded
// boxes let through (cull_radius2), so brute force and the tree agree to the
// bit. Written !(disc < 0): a NaN keeps the triangle.
template <class T, bool CommonOrigin>
[[gnu::always_inline]] inline bool triangle_near_packet(const soa_scene<T>& s, size_t i, const packet<T>& p, const packet_best<T>& best) {
    int near_any = 0;
    if constexpr (CommonOrigin) {
        const T fx = p.ox[0] - s.bx[i], fy = p.oy[0] - s.by[i], fz = p.oz[0] - s.bz[i];
        const T rr = cull_radius2(s.br2[i], fx, fy, fz);
        for (int k = 0; k < W; ++k)
            near_any |= int(!(sphere_discriminant<T, sphere_mode::robust>(fx, fy, fz, T(0), rr, p.dx[k], p.dy[k],
                                                                          p.dz[k], best.a[k], best.inv_a[k]) < T(0)));
    } else {
        for (int k = 0; k < W; ++k) {
            const T fx = p.ox[k] - s.bx[i], fy = p.oy[k] - s.by[i], fz = p.oz[k] - s.bz[i];
            const T rr = cull_radius2(s.br2[i], fx, fy, fz);
            near_any |= int(!(sphere_discriminant<T, sphere_mode::robust>(fx, fy, fz, T(0), rr, p.dx[k], p.dy[k],
                                                                          p.dz[k], best.a[k], best.inv_a[k]) < T(0)));
        }
    }
    return near_any != 0;
}

// Triangle i against the packet. In brute force (InTree false) it is
// skipped when no ray comes near it; in a tree's leaf the boxes have done
// that, and the hits carry the scene's numbers with the tie rule
// (packet_best::keep). With a common origin, s = origin - a and q = s x e1
// leave the lane loop.
template <class T, bool CommonOrigin, bool InTree = false>
[[gnu::always_inline]] inline void triangle_closest(const soa_scene<T>& s, size_t i, const packet<T>& p, T tmin, packet_best<T>& best) {
    using I = index_t<T>;
    const I id = InTree ? I(s.triangle_number(i)) : I(s.sphere_count + s.plane_count) + I(i);
    if (!InTree && !triangle_near_packet<T, CommonOrigin>(s, i, p, best)) return;
    const T e1x = s.e1x[i], e1y = s.e1y[i], e1z = s.e1z[i], e2x = s.e2x[i], e2y = s.e2y[i], e2z = s.e2z[i];
    const T scale = flat_scale(e1x, e1y, e1z, e2x, e2y, e2z), tiny = flat_tiny<T>();
    int unsure = 0;
    if constexpr (CommonOrigin) {
        const T sx = p.ox[0] - s.ax[i], sy = p.oy[0] - s.ay[i], sz = p.oz[0] - s.az[i];
        const T qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
        for (int k = 0; k < W; ++k)
            best.template keep<InTree>(k,
                      triangle_t(sx, sy, sz, qx, qy, qz, e1x, e1y, e1z, e2x, e2y, e2z, p.dx[k], p.dy[k], p.dz[k], tmin,
                                 scale * best.d_max[k] + tiny, unsure),
                      id);
    } else {
        for (int k = 0; k < W; ++k) {
            const T sx = p.ox[k] - s.ax[i], sy = p.oy[k] - s.ay[i], sz = p.oz[k] - s.az[i];
            const T qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
            best.template keep<InTree>(k,
                      triangle_t(sx, sy, sz, qx, qy, qz, e1x, e1y, e1z, e2x, e2y, e2z, p.dx[k], p.dy[k], p.dz[k], tmin,
                                 scale * best.d_max[k] + tiny, unsure),
                      id);
        }
    }
    if (unsure)  // nearly parallel or degenerate: decide exactly (keep takes a t once)
        for (int k = 0; k < W; ++k) {
            const int o = CommonOrigin ? 0 : k;
            best.template keep<InTree>(k, triangle_exact_t(s, i, p.ox[o], p.oy[o], p.oz[o], p.dx[k], p.dy[k], p.dz[k], tmin), id);
        }
}

// The packet's walk of the wide tree (traverse_packet, see soa_scene): a
// leaf's triangles against every ray, by triangle_closest with the scene's
// numbers and the tie rule; a box few rays enter, against each of those
// rays alone, as one group of leaf_lanes lanes with the same arithmetic.
// Either way t is the brute-force kernel's to the bit.
template <class T, bool CommonOrigin>
[[gnu::always_inline]] inline void triangles_closest_in_tree(const soa_scene<T>& s, const packet<T>& p, T tmin, packet_best<T>& best) {
    using I = index_t<T>;
    traverse_packet(
        s.triangle_tree, p, best.t,
        [&](size_t b, size_t e) {
            for (size_t i = b; i < e; ++i) triangle_closest<T, CommonOrigin, true>(s, i, p, tmin, best);
        },
        [&](int k, size_t b, size_t e) {
            const int o = CommonOrigin ? 0 : k;
            const T ox = p.ox[o], oy = p.oy[o], oz = p.oz[o], dx = p.dx[k], dy = p.dy[k], dz = p.dz[k];
            for (size_t g = b; g < e; g += leaf_lanes) {
                const triangle_group<T> group(s, g, e, ox, oy, oz, dx, dy, dz, best.d_max[k], tmin);
                for (int i = 0; i < leaf_lanes && g + size_t(i) < e; ++i)
                    if (group.t[i] <= best.t[k])  // the usual case, a miss, needs no number
                        best.template keep<true>(k, group.t[i], I(s.triangle_number(g + size_t(i))));
            }
        });
}

// Every triangle against the packet.
template <class T, bool CommonOrigin>
[[gnu::always_inline]] inline void triangles_closest(const soa_scene<T>& s, const packet<T>& p, T tmin, packet_best<T>& best) {
    if (s.tree) {
        triangles_closest_in_tree<T, CommonOrigin>(s, p, tmin, best);
        return;
    }
    for (size_t i = 0; i < s.triangle_count; ++i) triangle_closest<T, CommonOrigin>(s, i, p, tmin, best);
}

// Is the shadow ray blocked by a triangle? The wide tree's leaves, or
// brute force's groups of shadow_group triangles.
template <class T>
[[gnu::always_inline]] inline bool triangles_block(const soa_scene<T>& s, const shadow_ray<T>& r, T tmin, T tmax) {
    if (s.tree)
        return traverse_wide<true>(s.triangle_tree, r.origin, r.direction, tmax, [&](std::uint32_t b, std::uint32_t n) {
            const size_t e = size_t(b) + n;
            for (size_t g = b; g < e; g += leaf_lanes)
                if (triangle_group<T>(s, g, e, r.ox, r.oy, r.oz, r.dx, r.dy, r.dz, r.d_max, tmin).blocked_before(tmax))
                    return true;
            return false;
        });
    for (size_t i = 0; i < shadow_groups(s.triangle_count); i += shadow_group) {
        int blocked = 0, unsure = 0;
        for (int k = 0; k < shadow_group; ++k)
            blocked |= int(triangle_lane_t(s, i + size_t(k), r.ox, r.oy, r.oz, r.dx, r.dy, r.dz, r.d_max, tmin,
                                           unsure) < tmax);
        if (unsure && !blocked)  // nearly parallel or degenerate: decide exactly
            for (size_t j = i; j < i + shadow_group && j < s.triangle_count; ++j)  // past the count: padding
                blocked |= int(triangle_exact_t(s, j, r.ox, r.oy, r.oz, r.dx, r.dy, r.dz, tmin) < tmax);
        if (blocked) return true;
    }
    return false;
}
