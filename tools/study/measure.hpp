// measure.hpp — run one formulation over one family: errors, counts, time.
//
// The same code serves the study program (which prints and draws it) and
// the numerics tests (which assert on it), so a test asserts exactly what
// the table shows.
#pragma once

#include "cases.hpp"
#include "reference.hpp"

#include "common/error_metrics.hpp"
#include "common/timing.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <time.h>
#include <vector>

namespace rt::study {

// The CPU time this thread has used. The machine that runs the study is
// often shared: with a wall clock every time the scheduler takes the core
// away lands in the measurement (at a load of 15 on 2 cores, most of it),
// the plain quadratic's 6 ns per test read as 30, and ratios between
// formulations shrink towards 1. The thread's CPU time leaves that out.
class cpu_stopwatch {
public:
    cpu_stopwatch() : start_(now()) {}
    double seconds() const { return (now() - start_) * 1e-9; }
    double nanoseconds() const { return now() - start_; }

private:
    static double now() {
        timespec t{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
        return double(t.tv_sec) * 1e9 + double(t.tv_nsec);
    }
    double start_;
};

struct error_summary {
    std::size_t count = 0;  // hits on the right root that were compared
    double ulp_median = 0, ulp_p99 = 0, ulp_max = 0;
    double rel_median = 0, rel_p99 = 0, rel_max = 0;
};

struct outcome {
    std::string family, formulation, precision;
    std::size_t queries = 0, reference_hits = 0, hits = 0;
    std::size_t false_hits = 0, false_misses = 0, wrong_roots = 0;
    std::size_t nan_hits = 0, out_of_range = 0;  // broken contracts: must stay 0
    std::size_t rays = 0, leaks = 0;             // closed meshes only
    double off_plane_median = -1, off_plane_max = -1;  // planes only, in ULPs
    error_summary error;
    timing_summary ns;  // nanoseconds per test; zeros when not timed
    bool failed = false;         // the routine threw (e.g. an unfinished exercise)
    std::string failure;
    std::vector<std::size_t> misclassified_per_group;  // false hits + false misses
    std::vector<double> rel_max_per_group;             // largest relative error of a right-root hit
    std::vector<std::size_t> compared_per_group;       // how many right-root hits that is over

    std::size_t misclassified() const { return false_hits + false_misses; }
    double hit_ratio() const { return queries ? double(hits) / double(queries) : 0; }
};

struct timing_options {
    int runs = 7;                     // the median of this many runs is reported
    double seconds_per_run = 0.002;   // each run repeats the batch at least this long
    std::size_t max_queries = 4096;   // a batch small enough to stay in cache
};

// The reference answer of every query of a family.
template <class T>
std::vector<reference_answer> references(const family<sphere_query<T>>& f);
template <class T>
std::vector<reference_answer> references(const family<plane_query<T>>& f);
template <class T>
std::vector<reference_answer> references(const family<triangle_query<T>>& f);

namespace detail {
template <class T>
const T* t_of(const std::optional<T>& a) {
    return a ? &*a : nullptr;
}
template <class T>
const T* t_of(const std::optional<formulations::plane_hit<T>>& a) {
    return a ? &a->t : nullptr;
}

// A long double answer in T; beyond T's range it becomes infinite.
template <class T>
T to_scalar(long double x) {
    if (std::fabs(x) > static_cast<long double>(std::numeric_limits<T>::max()))
        return std::copysign(std::numeric_limits<T>::infinity(), static_cast<T>(x > 0 ? 1 : -1));
    return static_cast<T>(x);
}

inline double quantile(std::vector<double>& v, double q) {
    if (v.empty()) return 0;
    std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * double(v.size() - 1) + 0.5));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

inline void summarize_errors(std::vector<double> ulps, std::vector<double> rels, error_summary& e) {
    e.count = ulps.size();
    if (ulps.empty()) return;
    e.ulp_max = *std::max_element(ulps.begin(), ulps.end());
    e.rel_max = *std::max_element(rels.begin(), rels.end());
    e.ulp_p99 = quantile(ulps, 0.99);
    e.rel_p99 = quantile(rels, 0.99);
    e.ulp_median = quantile(ulps, 0.5);
    e.rel_median = quantile(rels, 0.5);
}

double off_plane(const plane<float>& p, const std::optional<formulations::plane_hit<float>>& h);
double off_plane(const plane<double>& p, const std::optional<formulations::plane_hit<double>>& h);
template <class S, class A>
double off_plane(const S&, const A&) {
    return -1;
}
}  // namespace detail

// Checks a routine's answers against the references. `fn` is called as
// fn(ray, shape, range) and returns std::optional<T> (or a plane hit).
template <class T, class Q, class Fn>
outcome evaluate(const family<Q>& fam, const std::vector<reference_answer>& refs, Fn fn) {
    outcome out;
    out.family = fam.name;
    out.precision = sizeof(T) == 4 ? "float" : "double";
    out.queries = fam.queries.size();
    out.misclassified_per_group.assign(fam.group_names.size(), 0);
    out.rel_max_per_group.assign(fam.group_names.size(), 0);
    out.compared_per_group.assign(fam.group_names.size(), 0);
    std::vector<double> ulps, rels, planes;
    std::vector<char> ray_hit, ray_ref;
    for (std::size_t i = 0; i < fam.queries.size(); ++i) {
        const Q& q = fam.queries[i];
        const reference_answer& ref = refs[i];
        auto answer = fn(q.r, q.shape, q.range);
        const T* t = detail::t_of(answer);
        if (ref.hit) ++out.reference_hits;
        if (!fam.ray_id.empty()) {
            std::size_t id = static_cast<std::size_t>(fam.ray_id[i]);
            if (ray_hit.size() <= id) ray_hit.resize(id + 1, 0), ray_ref.resize(id + 1, 0);
            ray_hit[id] |= t != nullptr;
            ray_ref[id] |= ref.hit;
        }
        if (t == nullptr) {
            if (ref.hit) ++out.false_misses, ++out.misclassified_per_group[std::size_t(fam.group[i])];
            continue;
        }
        ++out.hits;
        if (std::isnan(*t)) ++out.nan_hits;
        if (!(q.range.min < *t && *t < q.range.max)) ++out.out_of_range;
        if (!ref.hit) {
            ++out.false_hits, ++out.misclassified_per_group[std::size_t(fam.group[i])];
            continue;
        }
        // A wrong root: nearer the other crossing than the right one, when
        // the two crossings are told apart in T (more than 2 ULPs apart; a
        // grazing ray's two roots may round to neighbours).
        long double other = ref.t == ref.t_near ? ref.t_far : ref.t_near;
        bool distinct = ulp_distance<T>(detail::to_scalar<T>(ref.t_near), detail::to_scalar<T>(ref.t_far)) > 2;
        if (distinct && std::fabs(*t - other) < std::fabs(*t - ref.t)) {
            ++out.wrong_roots;
            continue;
        }
        ulps.push_back(ulp_distance<T>(*t, static_cast<T>(ref.t_rounded)));
        rels.push_back(relative_error(*t, ref.t));
        double& group_max = out.rel_max_per_group[std::size_t(fam.group[i])];
        group_max = std::max(group_max, rels.back());
        ++out.compared_per_group[std::size_t(fam.group[i])];
        double off = detail::off_plane(q.shape, answer);
        if (off >= 0) planes.push_back(off);
    }
    for (std::size_t id = 0; id < ray_hit.size(); ++id) {
        ++out.rays;
        if (ray_ref[id] && !ray_hit[id]) ++out.leaks;
    }
    detail::summarize_errors(std::move(ulps), std::move(rels), out.error);
    if (!planes.empty()) {
        out.off_plane_max = *std::max_element(planes.begin(), planes.end());
        out.off_plane_median = detail::quantile(planes, 0.5);
    }
    return out;
}

// Nanoseconds per test of a batch loop over (an evenly spaced sample of up
// to max_queries of) the family's queries: the batch is repeated long enough per run (in
// this thread's CPU time), and the median, minimum and maximum over runs are reported.
template <class Q, class Batch>
timing_summary time_batch(const family<Q>& fam, Batch batch, const timing_options& opt) {
    std::size_t n = std::min(fam.queries.size(), opt.max_queries);
    if (n == 0) return {};
    // An evenly spaced sample of the whole family, so every group is timed.
    std::vector<Q> sample;
    sample.reserve(n);
    for (std::size_t i = 0; i < n; ++i) sample.push_back(fam.queries[i * fam.queries.size() / n]);
    const Q* data = sample.data();
    volatile double sink = batch(data, n);  // warm up: data and code into cache
    cpu_stopwatch once;
    sink = sink + batch(data, n);
    double one = std::max(once.seconds(), 1e-7);
    int reps = std::max(1, static_cast<int>(opt.seconds_per_run / one));
    std::vector<double> samples;
    for (int r = 0; r < opt.runs; ++r) {
        cpu_stopwatch sw;
        double acc = 0;
        for (int k = 0; k < reps; ++k) acc += batch(data, n);
        samples.push_back(sw.nanoseconds() / (double(reps) * double(n)));
        sink = sink + acc;
    }
    (void)sink;
    return summarize(std::move(samples));
}

// Two batch loops timed in alternation on the same sample (a run of one,
// then a run of the other, opt.runs times), for a ratio of their costs. A
// shared machine slows down for stretches of a few milliseconds (another
// process's burst, a virtual CPU waiting for its host): two loops timed one
// after the other can land on either side of such a stretch, and their
// ratio is then off by as much as the slowdown. Runs taken in alternation
// see the same stretches, and the median of the per-pair ratios leaves out
// a pair that straddles one.
struct paired_timing {
    timing_summary a, b;
    double ratio = 0;  // median over pairs of b / a
};

template <class Q, class Batch>
paired_timing time_pair(const family<Q>& fam, Batch batch_a, Batch batch_b, const timing_options& opt) {
    paired_timing out;
    std::size_t n = std::min(fam.queries.size(), opt.max_queries);
    if (n == 0) return out;
    std::vector<Q> sample;
    sample.reserve(n);
    for (std::size_t i = 0; i < n; ++i) sample.push_back(fam.queries[i * fam.queries.size() / n]);
    const Q* data = sample.data();
    volatile double sink = batch_a(data, n) + batch_b(data, n);  // warm up
    auto reps_for = [&](Batch batch) {
        cpu_stopwatch once;
        sink = sink + batch(data, n);
        return std::max(1, static_cast<int>(opt.seconds_per_run / std::max(once.seconds(), 1e-7)));
    };
    const int reps_a = reps_for(batch_a), reps_b = reps_for(batch_b);
    auto run = [&](Batch batch, int reps) {
        cpu_stopwatch sw;
        double acc = 0;
        for (int k = 0; k < reps; ++k) acc += batch(data, n);
        sink = sink + acc;
        return sw.nanoseconds() / (double(reps) * double(n));
    };
    std::vector<double> as, bs, ratios;
    for (int r = 0; r < opt.runs; ++r) {
        as.push_back(run(batch_a, reps_a));
        bs.push_back(run(batch_b, reps_b));
        ratios.push_back(bs.back() / as.back());
    }
    (void)sink;
    out.a = summarize(std::move(as));
    out.b = summarize(std::move(bs));
    out.ratio = summarize(std::move(ratios)).median;
    return out;
}

}  // namespace rt::study
