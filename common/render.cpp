#include "render.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include <unistd.h>

namespace rt {

int render_threads() {
    unsigned n = std::thread::hardware_concurrency();
    return n == 0 ? 1 : int(n);
}

namespace {

// Prints "rendering: 42% of 480 rows" on a terminal, at most ten times a second,
// and only once the render has run for a second: short renders stay silent.
class progress_line {
public:
    explicit progress_line(int rows) : rows_(rows), start_(clock::now()), enabled_(isatty(STDERR_FILENO) != 0) {}

    void row_done(int done) {
        if (!enabled_) return;
        auto now = clock::now();
        if (now - start_ < std::chrono::seconds(1)) return;
        std::lock_guard<std::mutex> lock(mutex_);
        if (now - last_ < std::chrono::milliseconds(100) && done != rows_) return;
        last_ = now;
        shown_ = true;
        std::fprintf(stderr, "\rrendering: %3d%% of %d rows", int(100.0 * done / rows_), rows_);
        std::fflush(stderr);
    }

    ~progress_line() {
        if (shown_) std::fprintf(stderr, "\r%*s\r", 40, "");
    }

private:
    using clock = std::chrono::steady_clock;
    int rows_;
    clock::time_point start_, last_{};
    bool enabled_;
    bool shown_ = false;
    std::mutex mutex_;
};

}  // namespace

void for_each_row(int rows, const std::function<void(int row)>& body) {
    std::atomic<int> next_row{0};
    std::atomic<bool> failed{false};
    std::exception_ptr error;
    std::mutex error_mutex;
    auto worker = [&] {
        try {
            for (int row; !failed && (row = next_row++) < rows;) body(row);
        } catch (...) {
            std::lock_guard<std::mutex> lock(error_mutex);
            if (!error) error = std::current_exception();
            failed = true;
        }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < render_threads(); ++i) pool.emplace_back(worker);
    worker();  // the calling thread works too
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

image render(int width, int height, const pixel_shader& shade) {
    image img(width, height);
    std::atomic<int> rows_done{0};
    progress_line progress(height);
    for_each_row(height, [&](int row) {
        for (int col = 0; col < width; ++col) img.at(col, row) = shade(col, row);
        progress.row_done(++rows_done);
    });
    return img;
}

}  // namespace rt
