// fast_path_spheres.hpp — part of fast_path.cpp (see fast_path_arrays.hpp):
// the sphere kernels and their lane loops, for a packet's closest hits and
// for one shadow ray's any hit.
//
// The "robust" lane kernel is not chapter 07's robust sphere
// (solutions/07-precision/robust_sphere.cpp, which the formulation study
// runs as "compensated"): it is the study's rtg_stable form (Hearn and
// Baker's perpendicular foot, then the stable root pair) in T's own lanes,
// with 1 / a multiplied instead of divided and c compensated by fma. Its
// error grows like eps k (scene_plan.cpp's model), where chapter 07's test
// is within 0 ULPs in float and 3 in double everywhere, but at 220-490 ns a
// test in float against the plain quadratic's 13-28 and rtg_stable's 16-29
// (tools/study/results/study.md, one run), scalar, in pairs of double for
// float data: called per lane it would cost ten to thirty times this
// formula before any vectorisation (an estimate from the study, not
// measured in the renderer). The plan picks this kernel, or double, where
// its error stays within the bound.
#pragma once
#ifndef RT_FAST_PATH_PARTS
#error "a part of fast_path.cpp: included by it, after its headers and its target pragma"
#endif

// c = |f|^2 - r^2 with the rounding error of each square added back (fma
// gives a product's exact low half), so a large sphere seen from near its
// surface, where |f|^2 and r^2 agree in most digits, keeps an accurate c.
template <class T>
inline T compensated_c(T fx, T fy, T fz, T r) {
    const T xx = fx * fx, yy = fy * fy, zz = fz * fz, rr = r * r;
    const T low = (std::fma(fx, fx, -xx) + std::fma(fy, fy, -yy) + std::fma(fz, fz, -zz)) - std::fma(r, r, -rr);
    return ((xx - rr) + (yy + zz)) + low;
}

// c as the formulation wants it: plainly, or compensated for the robust test.
template <class T, sphere_mode SM>
inline T sphere_c(T fx, T fy, T fz, T r, T rr) {
    return SM == sphere_mode::plain ? fx * fx + fy * fy + fz * fz - rr : compensated_c(fx, fy, fz, r);
}

// Just the discriminant of sphere_t (the same formula, so the same sign):
// negative means the ray passes the sphere by. Used to skip a sphere that
// no ray of a packet comes near, which at large N is almost every sphere.
template <class T, sphere_mode SM>
inline T sphere_discriminant(T fx, T fy, T fz, T c, T rr, T dx, T dy, T dz, T a, T inv_a) {
    const T half_b = fx * dx + fy * dy + fz * dz;
    if constexpr (SM == sphere_mode::plain) {
        return half_b * half_b - a * c;
    } else {
        const T m = half_b * inv_a;
        const T gx = fx - m * dx, gy = fy - m * dy, gz = fz - m * dz;
        return a * (rr - (gx * gx + gy * gy + gz * gz));
    }
}

// One sphere against one ray, with f = origin - centre, c = |f|^2 - r^2,
// a = |d|^2. Returns the nearest t > tmin, or infinity. The radius is > 0
// and at most 1e15 (the scene reader refuses anything else, and one that
// rounds to 0 in float); r only enters squared, so this test itself would
// answer a negative radius as if it were positive and a zero radius as a
// point.
template <class T, sphere_mode SM>
inline T sphere_t(T fx, T fy, T fz, T c, T rr, T dx, T dy, T dz, T a, T inv_a, T tmin) {
    const T half_b = fx * dx + fy * dy + fz * dz;
    T disc, near, far;
    if constexpr (SM == sphere_mode::plain) {
        // The plain quadratic: cheapest, loses digits as (distance / radius)^2.
        disc = half_b * half_b - a * c;
        const T root = std::sqrt(disc);  // NaN when disc < 0: that lane's answer is dropped below
        near = (-half_b - root) * inv_a;
        far = (-half_b + root) * inv_a;
    } else {
        // The perpendicular foot g = f - (half_b / a) d is formed before
        // squaring, then the stable root pair c / q and q / a.
        const T m = half_b * inv_a;
        const T gx = fx - m * dx, gy = fy - m * dy, gz = fz - m * dz;
        disc = a * (rr - (gx * gx + gy * gy + gz * gz));
        const T root = std::sqrt(disc);
        const T q = -(half_b + std::copysign(root, half_b));
        const T r1 = c / q, r2 = q * inv_a;
        near = r1 < r2 ? r1 : r2;
        far = r1 < r2 ? r2 : r1;
    }
    const T t = near > tmin ? near : far;
    return ((disc >= T(0)) & (t > tmin)) ? t : infinity<T>;
}

// The number a hit on stored sphere i is kept under: with Ties (a tree's
// leaf) the scene's own number, from another array, so asked for only once
// some ray comes near the sphere; without, its place in brute force's order.
template <bool Ties, class T>
[[gnu::always_inline]] inline index_t<T> sphere_id(const soa_scene<T>& s, size_t i) {
    return Ties ? index_t<T>(s.sphere_number(i)) : index_t<T>(i);
}

// Sphere i against a packet whose rays share the origin of lane 0: f and c
// leave the lane loop. Cull first: the full test (square root, division,
// the update of the closest hit) only when some ray of the packet passes
// within the sphere's radius.
template <class T, sphere_mode SM, bool Ties>
[[gnu::always_inline]] inline void sphere_closest_common_origin(const soa_scene<T>& s, size_t i, const packet<T>& p,
                                                                T tmin, packet_best<T>& best) {
    const T fx = p.ox[0] - s.cx[i], fy = p.oy[0] - s.cy[i], fz = p.oz[0] - s.cz[i], rr = s.radius_squared(i);
    const T c = sphere_c<T, SM>(fx, fy, fz, s.radius[i], rr);
    int near_any = 0;
    for (int k = 0; k < W; ++k)
        near_any |= int(sphere_discriminant<T, SM>(fx, fy, fz, c, rr, p.dx[k], p.dy[k], p.dz[k], best.a[k],
                                                   best.inv_a[k]) >= T(0));
    if (!near_any) return;
    const index_t<T> id = sphere_id<Ties>(s, i);
    for (int k = 0; k < W; ++k)
        best.template keep<Ties>(
            k, sphere_t<T, SM>(fx, fy, fz, c, rr, p.dx[k], p.dy[k], p.dz[k], best.a[k], best.inv_a[k], tmin), id);
}

// The same for rays with origins of their own (an orthographic camera).
template <class T, sphere_mode SM, bool Ties>
[[gnu::always_inline]] inline void sphere_closest_own_origins(const soa_scene<T>& s, size_t i, const packet<T>& p,
                                                              T tmin, packet_best<T>& best) {
    const T cx = s.cx[i], cy = s.cy[i], cz = s.cz[i], r = s.radius[i], rr = r * r;
    int near_any = 0;
    for (int k = 0; k < W; ++k) {
        const T fx = p.ox[k] - cx, fy = p.oy[k] - cy, fz = p.oz[k] - cz;
        const T c = fx * fx + fy * fy + fz * fz - rr;  // only the plain form's sign test uses it
        near_any |= int(sphere_discriminant<T, SM>(fx, fy, fz, c, rr, p.dx[k], p.dy[k], p.dz[k], best.a[k],
                                                   best.inv_a[k]) >= T(0));
    }
    if (!near_any) return;
    const index_t<T> id = sphere_id<Ties>(s, i);
    for (int k = 0; k < W; ++k) {
        const T fx = p.ox[k] - cx, fy = p.oy[k] - cy, fz = p.oz[k] - cz;
        const T c = sphere_c<T, SM>(fx, fy, fz, r, rr);
        best.template keep<Ties>(
            k, sphere_t<T, SM>(fx, fy, fz, c, rr, p.dx[k], p.dy[k], p.dz[k], best.a[k], best.inv_a[k], tmin), id);
    }
}

// Spheres [begin, end) against the packet; Ties: a tree's leaf, the
// spheres numbered as in the scene (packet_best::keep).
template <class T, sphere_mode SM, bool CommonOrigin, bool Ties>
[[gnu::always_inline]] inline void spheres_closest(const soa_scene<T>& s, size_t begin, size_t end, const packet<T>& p,
                                                   T tmin, packet_best<T>& best) {
    for (size_t i = begin; i < end; ++i) {
        if constexpr (CommonOrigin)
            sphere_closest_common_origin<T, SM, Ties>(s, i, p, tmin, best);
        else
            sphere_closest_own_origins<T, SM, Ties>(s, i, p, tmin, best);
    }
}

// Spheres [begin, end) of a tree's leaf against ray k of the packet alone
// (traverse_packet hands a box that few of its rays enter to them one by
// one): the lane loops' arithmetic for that lane, so the same t and object.
// (With a common origin every lane's origin is lane 0's.) One ray passes
// most spheres of the leaves it meets by: their discriminant, the same
// formula as sphere_t's, is negative, and sphere_t would answer infinity,
// which keep() ignores; so the square root and the division are left out
// for them. The sphere's scene number is another array, looked up only
// for a hit at or before the ray's best (keep's tie rule needs it then).
template <class T, sphere_mode SM>
[[gnu::always_inline]] inline void spheres_closest_one(const soa_scene<T>& s, size_t begin, size_t end,
                                                       const packet<T>& p, int k, T tmin, packet_best<T>& best) {
    for (size_t i = begin; i < end; ++i) {
        const T fx = p.ox[k] - s.cx[i], fy = p.oy[k] - s.cy[i], fz = p.oz[k] - s.cz[i], rr = s.radius_squared(i);
        // The plain discriminant needs c; the robust one does not, and its
        // compensated c waits for a sphere the ray comes near.
        T c = SM == sphere_mode::plain ? sphere_c<T, SM>(fx, fy, fz, s.radius[i], rr) : T(0);
        if (!(sphere_discriminant<T, SM>(fx, fy, fz, c, rr, p.dx[k], p.dy[k], p.dz[k], best.a[k], best.inv_a[k]) >= T(0)))
            continue;
        if constexpr (SM == sphere_mode::robust) c = sphere_c<T, SM>(fx, fy, fz, s.radius[i], rr);
        const T t = sphere_t<T, SM>(fx, fy, fz, c, rr, p.dx[k], p.dy[k], p.dz[k], best.a[k], best.inv_a[k], tmin);
        if (t <= best.t[k]) best.template keep<true>(k, t, index_t<T>(s.sphere_number(i)));
    }
}

// One shadow ray against sphere j: is it hit with tmin < t < tmax?
template <class T, sphere_mode SM>
[[gnu::always_inline]] inline bool sphere_blocks(const soa_scene<T>& s, size_t j, const shadow_ray<T>& r, T tmin, T tmax) {
    const T fx = r.ox - s.cx[j], fy = r.oy - s.cy[j], fz = r.oz - s.cz[j];
    const T rr = s.radius_squared(j);
    const T c = sphere_c<T, SM>(fx, fy, fz, s.radius[j], rr);
    return sphere_t<T, SM>(fx, fy, fz, c, rr, r.dx, r.dy, r.dz, r.a, r.inv_a, tmin) < tmax;
}

// Is the shadow ray blocked by a sphere? With a tree, only the leaves whose
// boxes the ray crosses, one sphere at a time; without, groups of
// shadow_group spheres in lanes.
template <class T, sphere_mode SM>
[[gnu::always_inline]] inline bool spheres_block(const soa_scene<T>& s, const shadow_ray<T>& r, T tmin, T tmax) {
    if (s.tree)
        return traverse_wide<true>(s.sphere_tree, r.origin, r.direction, tmax, [&](std::uint32_t b, std::uint32_t n) {
            for (size_t j = b; j < size_t(b) + n; ++j)
                if (sphere_blocks<T, SM>(s, j, r, tmin, tmax)) return true;
            return false;
        });
    for (size_t i = 0; i < shadow_groups(s.sphere_count); i += shadow_group) {
        int blocked = 0;
        for (int k = 0; k < shadow_group; ++k) blocked |= int(sphere_blocks<T, SM>(s, i + size_t(k), r, tmin, tmax));
        if (blocked) return true;
    }
    return false;
}
