// big_array.hpp — memory for arrays of hundreds of megabytes.
//
// The 48-million-sphere sphereflake needs about 6 GB: the scene, the tree's
// build records, its nodes, the renderer's copies of the spheres. Two of the
// costs of such arrays are not the program's arithmetic:
//   * Linux maps memory on first touch, one 4 KB page per fault, and zeroes
//     each page; 6 GB are a million and a half faults. In 2 MB pages
//     ("transparent huge pages") they are 3,000. Debian's kernel gives them
//     to a range that asks (madvise mode), so advise_huge_pages asks.
//   * std::vector's resize first writes every element (zeros, for a plain
//     struct), on one core, before the program writes its own values.
// big_vector<T> is a std::vector whose allocator asks for huge pages for
// blocks of 8 MB and more and whose resize leaves an element of a trivial
// type unwritten, like `new T[n]`: for arrays the program fills itself,
// every element, preferably on every core (the first touch is then on every
// core too). Its elements are not zero: read none before writing it.
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace rt {

// Asks the kernel to back [p, p + bytes) with 2 MB pages where it can (the
// whole 2 MB-aligned pages inside the range). Only advice: where huge pages
// are off or unsupported, nothing changes. Call it before the first write:
// pages already mapped stay small.
void advise_huge_pages(const void* p, std::size_t bytes);

template <class T>
struct big_allocator {
    using value_type = T;
    static constexpr std::size_t huge_from = std::size_t(8) << 20;  // bytes

    big_allocator() = default;
    template <class U>
    big_allocator(const big_allocator<U>&) {}

    // Every block starts on a cache line, and a block of huge_from bytes or
    // more on a 2 MB page. malloc's own blocks start 16 bytes into a line
    // (its header), so a 32-byte tree node pair or a group of 8 floats that
    // the code lays out as one line would straddle two, and each read of it
    // would cost two cache misses where one was meant.
    static constexpr std::size_t cache_line = 64, huge_page = std::size_t(2) << 20;
    static constexpr std::size_t alignment(std::size_t n) {
        const std::size_t at_least = alignof(T) > cache_line ? alignof(T) : cache_line;
        return n * sizeof(T) >= huge_from ? (huge_page > at_least ? huge_page : at_least) : at_least;
    }

    T* allocate(std::size_t n) {
        void* p = ::operator new(n * sizeof(T), std::align_val_t(alignment(n)));
        if (n * sizeof(T) >= huge_from) advise_huge_pages(p, n * sizeof(T));
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t n) { ::operator delete(p, std::align_val_t(alignment(n))); }

    // resize() and vector(n) construct with no arguments: default-initialise
    // (nothing is written for a trivial type) instead of value-initialising.
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        if constexpr (sizeof...(Args) == 0) ::new (static_cast<void*>(p)) U;
        else ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }

    template <class U>
    bool operator==(const big_allocator<U>&) const { return true; }
    template <class U>
    bool operator!=(const big_allocator<U>&) const { return false; }
};

template <class T>
using big_vector = std::vector<T, big_allocator<T>>;

}  // namespace rt
