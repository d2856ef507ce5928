// timing.hpp — wall-clock measurement for programs and benchmarks.
//
// Timings in this course are reported, never asserted: a test that fails
// because the machine was busy teaches nothing.
#pragma once

#include <algorithm>
#include <chrono>
#include <ctime>
#include <vector>

namespace rt {

// The CPU time this process has used, all its threads together. Other jobs
// on a shared machine do not advance it, so work timed with it reads the
// same at any load (divide by the threads that did the work).
inline double process_cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + double(t.tv_nsec) * 1e-9;
}

class stopwatch {
public:
    stopwatch() : start_(clock::now()) {}
    double seconds() const { return std::chrono::duration<double>(clock::now() - start_).count(); }
    double nanoseconds() const { return std::chrono::duration<double, std::nano>(clock::now() - start_).count(); }

private:
    using clock = std::chrono::steady_clock;
    clock::time_point start_;
};

// Summary of repeated timings: the median is the figure to quote; min and
// max show how steady the machine was.
struct timing_summary {
    double median = 0, min = 0, max = 0;
};

inline timing_summary summarize(std::vector<double> samples) {
    timing_summary s;
    if (samples.empty()) return s;
    std::sort(samples.begin(), samples.end());
    s.min = samples.front();
    s.max = samples.back();
    size_t n = samples.size();
    s.median = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
    return s;
}

}  // namespace rt
