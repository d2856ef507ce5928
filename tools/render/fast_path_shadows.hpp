// fast_path_shadows.hpp — part of fast_path.cpp (see fast_path_arrays.hpp):
// shadow rays asked ahead and answered W at a time.
//
// Chapter 06's shade() asks its occlusion test one ray at a time and waits
// for the answer, and one ray alone cannot fill a packet's lanes (any_hit
// puts objects in them instead). But which rays shade() will ask is known
// before it runs: for each light, in order, a shadow ray exactly when the
// light is above the surface (lambert(normal, to_light) > 0; shading.hpp),
// built by chapter 06's own shadow_ray(). So the pixel loop asks those rays
// first (ask), answers them in packets of W rays with origins of their own
// (answer: the closest-hit walk, limited to each ray's range and stopping a
// ray at its first hit), and shade()'s test then takes the answers (replay).
// replay checks every query against the one asked ahead and traces a query
// it was not asked one at a time, so the picture can only be the one
// any_hit gives, whatever shade() asks.
#pragma once
#ifndef RT_FAST_PATH_PARTS
#error "a part of fast_path.cpp: included by it, after its headers and its target pragma"
#endif

template <class T>
class shadow_batch {
public:
    void clear() {
        queries_.clear();
        for (auto& lane : asked_) lane.clear();
        for (size_t& next : next_) next = 0;
    }
    size_t size() const { return queries_.size(); }

    // Lane k's shadow ray to the light at light_position from its hit
    // (point, normal), if shade() will ask it.
    void ask(int k, const vec3<T>& point, const vec3<T>& normal, const vec3<T>& light_position) {
        if (!(ch06::lambert(normal, light_position - point) > T(0))) return;  // below the surface: shade() asks nothing
        const ch06::shadow_query<T> q = ch06::shadow_ray(point, normal, light_position);
        asked_[size_t(k)].push_back(queries_.size());
        queries_.push_back({q.r, q.range, false});
    }

    // Every query asked, answered W rays at a time. A packet's rays share
    // their tmin (all of chapter 06's are 0); a query with an empty range
    // (a light on the ray's origin) is not blocked and takes no lane. The
    // lanes past a packet's last ray repeat its first.
    template <sphere_mode SM>
    void answer(const soa_scene<T>& s) {
        packet<T> p;
        alignas(64) T tmax[W], t[W];
        alignas(64) index_t<T> object[W];
        size_t lane_query[W];
        for (size_t i = 0; i < queries_.size();) {
            int n = 0;
            const T tmin = queries_[i].range.min;
            do {
                if (queries_[i].range.min < queries_[i].range.max) lane_query[n++] = i;
                ++i;
            } while (i < queries_.size() && n < W && queries_[i].range.min == tmin);
            if (n == 0) continue;
            for (int k = 0; k < W; ++k) {
                const query& q = queries_[lane_query[k < n ? k : 0]];
                p.ox[k] = q.r.origin.x, p.oy[k] = q.r.origin.y, p.oz[k] = q.r.origin.z;
                p.dx[k] = q.r.direction.x, p.dy[k] = q.r.direction.y, p.dz[k] = q.r.direction.z;
                tmax[k] = q.range.max;
            }
            closest_hits<T, SM, false, true>(s, p, tmin, t, object, tmax);
            for (int k = 0; k < n; ++k) queries_[lane_query[k]].blocked = object[k] >= 0;
        }
    }

    // The same answers from any_hit, one ray at a time (what the packets
    // are measured and tested against).
    template <sphere_mode SM>
    void answer_one_at_a_time(const soa_scene<T>& s) {
        for (query& q : queries_) q.blocked = any_hit<T, SM>(s, q.r, q.range.min, q.range.max);
    }

    long blocked() const {
        long n = 0;
        for (const query& q : queries_) n += q.blocked;
        return n;
    }

    // Whether lane k's shadow ray (r, range) is blocked: the packet's answer
    // when it is the next ray lane k asked; else (never, while shade() asks
    // as its header says) any_hit's, and `alone` counts it.
    template <sphere_mode SM>
    bool replay(const soa_scene<T>& s, int k, const ray<T>& r, const interval<T>& range) {
        const std::vector<size_t>& asked = asked_[size_t(k)];
        size_t& next = next_[size_t(k)];
        if (next < asked.size() && same(queries_[asked[next]], r, range)) return queries_[asked[next++]].blocked;
        next = asked.size();  // out of step: this lane's later answers are not trusted either
        ++alone;
        return any_hit<T, SM>(s, r, range.min, range.max);
    }

    long alone = 0;  // queries replay traced one at a time

private:
    struct query {
        ray<T> r;
        interval<T> range;
        bool blocked;
    };
    static bool same(const query& q, const ray<T>& r, const interval<T>& range) {
        return q.r.origin == r.origin && q.r.direction == r.direction && q.range.min == range.min &&
               q.range.max == range.max;
    }
    std::vector<query> queries_;
    std::array<std::vector<size_t>, W> asked_;  // each lane's queries, in the order it asked them
    std::array<size_t, W> next_{};              // each lane's next query to replay
};

// Every shadow ray shade() will ask for the lanes with a hit (has_hit[k]),
// one light after another: a light's rays side by side in the packets, as
// they converge on it.
template <class T, class SurfaceHit>
void ask_every_light(shadow_batch<T>& batch, const std::vector<point_light>& lights, const SurfaceHit* hit,
                     const bool* has_hit) {
    batch.clear();
    for (const point_light& light : lights)
        for (int k = 0; k < W; ++k)
            if (has_hit[k]) batch.ask(k, hit[k].point, hit[k].normal, convert<T>(light.position));
}
