// memory_bound.hpp — a bound on the memory one call may take, so that code which makes no progress
// (a tree build that splits a node into itself, again and again) fails at once and the same way on
// every run, instead of running until a time limit that depends on the machine's load.
//
// While a memory_bound lives, this process may map at most `bytes` more than it had when the bound
// was made (RLIMIT_AS, lowered and then restored): an allocation beyond that fails with
// std::bad_alloc. Where the limit cannot be lowered (or under a sanitizer, which maps memory of its
// own), the bound does nothing and says so through active().
#pragma once

#include <sys/resource.h>
#include <unistd.h>

#include <cstddef>
#include <cstdio>

namespace rt::test {

// Bytes of address space this process has mapped now (/proc/self/statm), 0 when unknown.
inline std::size_t address_space_in_use() {
    std::FILE* f = std::fopen("/proc/self/statm", "r");
    if (f == nullptr) return 0;
    unsigned long pages = 0;
    const int read = std::fscanf(f, "%lu", &pages);
    std::fclose(f);
    const long page = ::sysconf(_SC_PAGESIZE);
    return read == 1 && page > 0 ? std::size_t(pages) * std::size_t(page) : 0;
}

// The memory a tree build over n objects may take beyond what it is given: room for many times the
// 2n - 1 nodes (of node_bytes each) it needs, and 16 MB for scratch space.
inline std::size_t tree_build_memory(std::size_t n, std::size_t node_bytes) {
    return (std::size_t(16) << 20) + 256 * (n + 1) * node_bytes;
}

class memory_bound {
public:
    explicit memory_bound(std::size_t bytes) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
        (void)bytes;
#else
        if (::getrlimit(RLIMIT_AS, &old_) != 0) return;
        const std::size_t now = address_space_in_use();
        if (now == 0) return;
        const rlim_t wanted = rlim_t(now + bytes);
        if (old_.rlim_cur != RLIM_INFINITY && old_.rlim_cur <= wanted) return;  // already tighter
        rlimit tighter = old_;
        tighter.rlim_cur = wanted;
        active_ = ::setrlimit(RLIMIT_AS, &tighter) == 0;
#endif
    }
    ~memory_bound() {
        if (active_) ::setrlimit(RLIMIT_AS, &old_);
    }
    memory_bound(const memory_bound&) = delete;
    memory_bound& operator=(const memory_bound&) = delete;

    bool active() const { return active_; }

private:
    rlimit old_{};
    bool active_ = false;
};

}  // namespace rt::test
