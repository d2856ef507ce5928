// bvh_build.cpp — binned SAH build of the renderer's tree (see bvh_build.hpp).
//
// The surface area heuristic: a ray that hits a box hits a child box inside
// it with probability (child area / box area), so splitting n objects into
// (nL, nR) costs about   1 + (area_L * nL + area_R * nR) / area
// object tests per ray, against n for a leaf. Candidate splits are the
// boundaries between 16 equal bins of the objects' centres along the
// widest axis (fewer for a node of fewer than 16 objects); one pass counts
// each bin's objects and grows its box, a sweep from each side then prices
// every boundary (15 with 16 bins).
#include "bvh_build.hpp"

#include "common/render.hpp"
#include "common/timing.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <stdexcept>

namespace rt::render_tool {

namespace {

constexpr int max_bins = 16;
constexpr size_t min_leaf = 4;
constexpr size_t parallel_bin_threshold = size_t(1) << 18;  // bigger nodes bin in parallel chunks
constexpr size_t task_size = size_t(1) << 17;                // smaller subtrees are one task each

// The build moves these, in order, rather than indices: 32 bytes each.
struct record {
    bvh_box box;
    std::uint32_t id, pad;
};

bvh_box empty_box() {
    const float inf = std::numeric_limits<float>::infinity();
    return {{inf, inf, inf}, {-inf, -inf, -inf}};
}
void grow(bvh_box& b, const bvh_box& o) {
    for (int a = 0; a < 3; ++a) b.lo[a] = std::min(b.lo[a], o.lo[a]), b.hi[a] = std::max(b.hi[a], o.hi[a]);
}
void grow(bvh_box& b, const float p[3]) {
    for (int a = 0; a < 3; ++a) b.lo[a] = std::min(b.lo[a], p[a]), b.hi[a] = std::max(b.hi[a], p[a]);
}
double area(const bvh_box& b) {
    const double x = double(b.hi[0]) - b.lo[0], y = double(b.hi[1]) - b.lo[1], z = double(b.hi[2]) - b.lo[2];
    return x < 0 ? 0 : 2 * (x * y + y * z + z * x);
}
void centre(const record& r, float c[3]) {
    for (int a = 0; a < 3; ++a) c[a] = 0.5f * (r.box.lo[a] + r.box.hi[a]);
}

// Four floats, gcc's vector extension (SSE, part of every x86-64): a
// record's low corner and its high corner each load as one, so the pass
// below grows a bin's box and its centres' box with four instructions
// instead of twelve; it is the build's hottest loop (every record, every
// level). Lane 3 holds whatever follows in the record and is never read.
// The selects are std::min's and std::max's (b < a ? b : a), so the bins,
// and the tree, are the same bit for bit as with the scalar grow().
typedef float f4 __attribute__((vector_size(16)));
constexpr float inf_f = std::numeric_limits<float>::infinity();
constexpr f4 up4 = {inf_f, inf_f, inf_f, inf_f}, down4 = {-inf_f, -inf_f, -inf_f, -inf_f};

// One bin: its objects' box and their centres' box.
struct f4_bin {
    f4 lo = up4, hi = down4, centre_lo = up4, centre_hi = down4;
    void grow(const f4_bin& o) {
        lo = o.lo < lo ? o.lo : lo, hi = hi < o.hi ? o.hi : hi;
        centre_lo = o.centre_lo < centre_lo ? o.centre_lo : centre_lo;
        centre_hi = centre_hi < o.centre_hi ? o.centre_hi : centre_hi;
    }
    bvh_box box() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
    bvh_box centres() const { return {{centre_lo[0], centre_lo[1], centre_lo[2]}, {centre_hi[0], centre_hi[1], centre_hi[2]}}; }
};

// What one pass over a range learns: per bin, its objects' box, their
// centres' box and their number. A node of n objects uses min(n, 16) bins:
// near the leaves, where most nodes are and each holds a few objects, the
// cost of a split is its fixed work per bin (starting, merging and sweeping
// them), and 16 bins for 6 objects would be mostly empty.
struct bin_stats {
    int used;
    std::array<f4_bin, max_bins> bin;
    std::array<size_t, max_bins> count;
    bin_stats() : used(0) {}
    explicit bin_stats(int bins_used) : used(bins_used) {
        for (int i = 0; i < used; ++i) bin[size_t(i)] = f4_bin{}, count[size_t(i)] = 0;
    }
    void merge(const bin_stats& o) {
        for (int i = 0; i < used; ++i) bin[size_t(i)].grow(o.bin[size_t(i)]), count[size_t(i)] += o.count[size_t(i)];
    }
};

// Which bin a record's centre falls in, along `axis`.
struct binner {
    int axis, bins;
    float low, scale;
    int of(float centre) const { return std::clamp(int((centre - low) * scale), 0, bins - 1); }
    int operator()(const record& r) const { return of(0.5f * (r.box.lo[axis] + r.box.hi[axis])); }
};

// One record into a set of bins. Axis is a template argument so that the
// centre's coordinate is a lane of a register, not a load from the stack.
template <int Axis>
void bin_one(const record& x, const binner& which, bin_stats& acc) {
    f4 lo, hi;
    std::memcpy(&lo, x.box.lo, sizeof lo);  // lo[0..2], hi[0]
    std::memcpy(&hi, x.box.hi, sizeof hi);  // hi[0..2], id
    const f4 c = 0.5f * (lo + hi);          // lanes 0..2: centre(), bit for bit
    const auto b = size_t(which.of(c[Axis]));
    f4_bin& a = acc.bin[b];
    a.lo = lo < a.lo ? lo : a.lo, a.hi = a.hi < hi ? hi : a.hi;
    a.centre_lo = c < a.centre_lo ? c : a.centre_lo, a.centre_hi = a.centre_hi < c ? c : a.centre_hi;
    ++acc.count[b];
}

// Neighbouring records mostly fall in the same bin (a scene's objects come
// in spatial order, and the partitions keep neighbours together), and then
// each record's minimum and maximum wait for the previous record's to be
// stored. So a long range alternates between sets of bins, merged at the end:
// the waits overlap. (Merging is exact: min and max do not round.)
constexpr int bin_sets = 4;

template <int Axis>
void bin_range_along(const record* r, size_t n, const binner& which, bin_stats& s) {
    if (n < 16 * bin_sets) {
        bin_stats acc(which.bins);  // local: the compiler need not fear that writing it changes the records
        for (size_t i = 0; i < n; ++i) bin_one<Axis>(r[i], which, acc);
        s.merge(acc);
        return;
    }
    std::array<bin_stats, bin_sets> acc;
    acc.fill(bin_stats(which.bins));
    size_t i = 0;
    for (; i + bin_sets <= n; i += bin_sets)
        for (int k = 0; k < bin_sets; ++k) bin_one<Axis>(r[i + size_t(k)], which, acc[size_t(k)]);
    for (; i < n; ++i) bin_one<Axis>(r[i], which, acc[0]);
    for (const auto& a : acc) s.merge(a);
}

void bin_range(const record* r, size_t n, const binner& which, bin_stats& s) {
    switch (which.axis) {
        case 0: return bin_range_along<0>(r, n, which, s);
        case 1: return bin_range_along<1>(r, n, which, s);
        default: return bin_range_along<2>(r, n, which, s);
    }
}

// The same, split into chunks over the thread pool for big ranges.
bin_stats bin_all(const record* r, size_t n, const binner& which) {
    bin_stats total(which.bins);
    if (n < parallel_bin_threshold) {
        bin_range(r, n, which, total);
        return total;
    }
    const int chunks = 4 * render_threads();
    std::vector<bin_stats> part(static_cast<size_t>(chunks), bin_stats(which.bins));
    for_each_row(chunks, [&](int c) {
        const size_t from = n * size_t(c) / size_t(chunks), to = n * size_t(c + 1) / size_t(chunks);
        bin_range(r + from, to - from, which, part[size_t(c)]);
    });
    for (const auto& p : part) total.merge(p);
    return total;
}

// std::partition on every core, for the big nodes at the top of the tree
// (below parallel_bin_threshold, one core partitions). Each thread
// partitions its own chunk; then the chunks are joined left to right: with
// the objects that go left so far in [begin, left_end), the chunk's own
// left part L2 in [start, mid) and the right part R1 of what came before
// in [left_end, start), swapping the shorter of R1 and L2 with the far end
// of the other puts every left object before every right one (neither
// side keeps its order, which a partition never promises). The swaps too
// are split over the threads.
template <class Pred>
record* parallel_partition(record* r, size_t n, Pred goes_left) {
    if (n < parallel_bin_threshold) return std::partition(r, r + n, goes_left);
    const int chunks = render_threads();
    std::vector<size_t> mid(static_cast<size_t>(chunks));
    auto chunk_start = [&](int c) { return n * size_t(c) / size_t(chunks); };
    for_each_row(chunks, [&](int c) {
        mid[size_t(c)] = size_t(std::partition(r + chunk_start(c), r + chunk_start(c + 1), goes_left) - r);
    });
    size_t left_end = mid[0];
    for (int c = 1; c < chunks; ++c) {
        const size_t start = chunk_start(c), k = std::min(start - left_end, mid[size_t(c)] - start);
        record* a = r + left_end;
        record* b = r + mid[size_t(c)] - k;
        const int parts = 4 * chunks;
        for_each_row(parts, [&](int q) {
            const size_t from = k * size_t(q) / size_t(parts), to = k * size_t(q + 1) / size_t(parts);
            std::swap_ranges(a + from, a + to, b + from);
        });
        left_end += mid[size_t(c)] - start;
    }
    return r + left_end;
}

// The box and the centres' box of a range (used at the root, and after a
// split that had to fall back to halving by count).
void bounds_of(const record* r, size_t n, bvh_box& box, bvh_box& centres) {
    box = empty_box(), centres = empty_box();
    for (size_t i = 0; i < n; ++i) {
        float c[3];
        centre(r[i], c);
        grow(box, r[i].box), grow(centres, c);
    }
}

// Where nodes go. The tree's array is sized at the start for the most
// nodes it can need: a tree over n objects, each leaf holding at least one,
// has at most 2n - 1 nodes, plus what the tasks' blocks leave unused (a
// task's last block, fewer than task_block nodes; at most 4n / task_size + 2
// tasks: each is a child of a node of task_size objects or more, and there
// are at most 2n / task_size such nodes). That is address space only: the
// pages of a big_vector are mapped when first written, so only the nodes
// made cost memory. Slots are handed out two at a time (a node's children
// sit side by side); a task takes them from blocks of its own, so threads
// never write each other's nodes, there is nothing to copy once the tasks
// are done, and a subtree's nodes stay together in the order its walk
// visits them. The unused end of a task's last block stays in the array,
// unwritten and unreachable from the root.
constexpr size_t task_block = 4096;

class node_slots {
public:
    node_slots(std::atomic<size_t>& cursor, size_t block) : cursor_(cursor), block_(block) {}
    // The first of two new neighbouring slots.
    std::uint32_t pair() {
        if (next_ + 2 > end_) next_ = cursor_.fetch_add(block_), end_ = next_ + block_;
        next_ += 2;
        return std::uint32_t(next_ - 2);
    }

private:
    std::atomic<size_t>& cursor_;
    size_t block_, next_ = 0, end_ = 0;
};

struct job {
    size_t begin, end;
    bvh_box box, centres;
    std::uint32_t slot;  // the node this range becomes
    size_t depth;
};

class builder {
public:
    builder(big_vector<record>& records, int max_leaf) : rec_(records), max_leaf_(size_t(max_leaf)) {}

    // Builds root's subtree into `nodes` (root.slot already exists there),
    // each node's two children in a pair of slots from `slots`. Ranges below
    // `defer_below` objects (other than the root) are not built but appended
    // to `deferred`.
    void build(const job& root, bvh_node* nodes, node_slots& slots, size_t defer_below, std::vector<job>& deferred) {
        std::vector<job> stack{root};
        while (!stack.empty()) {
            job j = stack.back();
            stack.pop_back();
            depth_ = std::max(depth_, j.depth);
            const size_t n = j.end - j.begin;
            if (n < defer_below && j.slot != root.slot) {
                deferred.push_back(j);
                continue;
            }
            nodes[j.slot].box = j.box;
            job left, right;
            if (!split(j, left, right)) {
                nodes[j.slot].first = std::uint32_t(j.begin);
                nodes[j.slot].count = std::uint32_t(n);
                ++leaves_;
                continue;
            }
            const std::uint32_t first = slots.pair();
            nodes[j.slot].first = first;
            nodes[j.slot].count = 0;
            left.slot = first, right.slot = first + 1;
            left.depth = right.depth = j.depth + 1;
            stack.push_back(right);
            stack.push_back(left);
        }
    }

    size_t leaves_ = 0, depth_ = 0;

private:
    big_vector<record>& rec_;
    size_t max_leaf_;

    // Splits j by the SAH; false when a leaf is cheaper (and allowed).
    bool split(const job& j, job& left, job& right) {
        const size_t n = j.end - j.begin;
        // Below min_leaf objects a split never pays here: a packet's box
        // test costs about what its test of a few objects costs, and every
        // split adds two 32-byte nodes (48 million spheres in leaves of one
        // would need 3 GB of nodes).
        if (n <= min_leaf) return false;
        // Past bvh_max_sah_depth a node is halved by count, so the tree is
        // never deeper than bvh_max_depth, which the walks' stacks are sized for.
        if (j.depth >= bvh_max_sah_depth) return halve(j, left, right);
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (j.centres.hi[a] - j.centres.lo[a] > j.centres.hi[axis] - j.centres.lo[axis]) axis = a;
        const float extent = j.centres.hi[axis] - j.centres.lo[axis];
        record* r = rec_.data() + j.begin;
        if (!(extent > 0)) {  // all centres in one point: no split tells them apart
            if (n <= max_leaf_) return false;
            return halve(j, left, right);
        }
        const int bins = int(std::min<size_t>(max_bins, n));
        const binner which{axis, bins, j.centres.lo[axis], float(bins) * 0.99999f / extent};
        const bin_stats s = bin_all(r, n, which);
        // Sweep: the box and count left of each boundary, then right of it.
        std::array<double, max_bins> left_cost;
        f4_bin b;
        size_t count = 0;
        for (int i = 0; i < bins - 1; ++i) {
            b.grow(s.bin[size_t(i)]), count += s.count[size_t(i)];
            left_cost[size_t(i)] = area(b.box()) * double(count);
        }
        double best = std::numeric_limits<double>::infinity();
        int best_split = -1;
        b = f4_bin{}, count = 0;
        for (int i = bins - 1; i > 0; --i) {
            b.grow(s.bin[size_t(i)]), count += s.count[size_t(i)];
            const double cost = left_cost[size_t(i - 1)] + area(b.box()) * double(count);
            if (count < n && count > 0 && cost < best) best = cost, best_split = i;
        }
        const double parent = area(j.box);
        const bool leaf_cheaper = !(parent > 0) || double(n) * parent <= parent + best;
        if (n <= max_leaf_ && (best_split < 0 || leaf_cheaper)) return false;
        if (best_split < 0) return halve(j, left, right);
        record* mid = parallel_partition(r, n, [&](const record& x) { return which(x) < best_split; });
        f4_bin left_bins, right_bins;
        for (int i = 0; i < bins; ++i) (i < best_split ? left_bins : right_bins).grow(s.bin[size_t(i)]);
        left = job{j.begin, j.begin + size_t(mid - r), left_bins.box(), left_bins.centres(), 0, 0};
        right = job{left.end, j.end, right_bins.box(), right_bins.centres(), 0, 0};
        return true;
    }

    // Half the objects each side (any half: their centres coincide).
    bool halve(const job& j, job& left, job& right) {
        record* r = rec_.data() + j.begin;
        const size_t n = j.end - j.begin, half = n / 2;
        std::nth_element(r, r + half, r + n, [](const record& a, const record& b) { return a.id < b.id; });
        left = job{j.begin, j.begin + half, {}, {}, 0, 0};
        right = job{j.begin + half, j.end, {}, {}, 0, 0};
        bounds_of(rec_.data() + left.begin, half, left.box, left.centres);
        bounds_of(rec_.data() + right.begin, n - half, right.box, right.centres);
        return true;
    }
};

}  // namespace

bvh_tree build_bvh(size_t count, const std::function<bvh_box(size_t)>& box_of, int max_leaf) {
    stopwatch clock;
    bvh_tree tree;
    if (count == 0) return tree;
    // Node numbers and object numbers are 32-bit: room for 2 * count nodes.
    if (count > (size_t(1) << bvh_max_objects_log2))
        throw std::length_error("build_bvh: more than 2^30 objects in one tree");
    // The records and the root's bounds, in chunks on every core (a
    // big_vector is not written before this: its pages are first touched
    // here, on both cores).
    big_vector<record> rec(count);
    job root{0, rec.size(), empty_box(), empty_box(), 0, 0};
    {
        const int chunks = 4 * render_threads();
        std::mutex merge;
        for_each_row(chunks, [&](int c) {
            const size_t from = rec.size() * size_t(c) / size_t(chunks), to = rec.size() * size_t(c + 1) / size_t(chunks);
            for (size_t i = from; i < to; ++i) rec[i] = {box_of(i), std::uint32_t(i), 0};
            bvh_box b, k;
            bounds_of(rec.data() + from, to - from, b, k);
            const std::lock_guard<std::mutex> lock(merge);
            grow(root.box, b), grow(root.centres, k);
        });
    }
    // The nodes: address space for the most the tree can need, mapped only
    // where nodes are written (node_slots).
    const size_t most_tasks = 4 * count / task_size + 2;
    tree.nodes.resize(2 * count + most_tasks * task_block);
    // nodes[0] is the root and nodes[1] stays unused, so that every pair of
    // children starts at an even slot: with the array on a cache line
    // (big_vector), the two boxes instanced_packets.cpp's push_children
    // reads are one line.
    tree.nodes[1] = bvh_node{empty_box(), 0, 0};
    std::atomic<size_t> cursor{2};

    // The top of the tree, one node at a time with parallel binning; every
    // range below task_size is left for the second phase.
    builder top(rec, max_leaf);
    std::vector<job> tasks;
    node_slots top_slots(cursor, 2);
    top.build(root, tree.nodes.data(), top_slots, task_size, tasks);

    // The subtrees, one task each, each writing its nodes into blocks of
    // the same array that no other task writes.
    std::vector<size_t> leaves(tasks.size()), depths(tasks.size());
    for_each_row(int(tasks.size()), [&](int t) {
        builder b(rec, max_leaf);
        node_slots slots(cursor, task_block);
        std::vector<job> none;
        b.build(tasks[size_t(t)], tree.nodes.data(), slots, 0, none);
        leaves[size_t(t)] = b.leaves_, depths[size_t(t)] = b.depth_;
    });
    tree.nodes.resize(cursor);  // the end of the last block taken (nothing past it was written)
    tree.leaves = top.leaves_, tree.depth = top.depth_;
    for (size_t t = 0; t < tasks.size(); ++t) tree.leaves += leaves[t], tree.depth = std::max(tree.depth, depths[t]);
    tree.order.resize(rec.size());
    const int chunks = 4 * render_threads();
    for_each_row(chunks, [&](int c) {
        const size_t from = rec.size() * size_t(c) / size_t(chunks), to = rec.size() * size_t(c + 1) / size_t(chunks);
        for (size_t i = from; i < to; ++i) tree.order[i] = rec[i].id;
    });
    tree.build_seconds = clock.seconds();
    return tree;
}

namespace {

// Writes the wide node for binary inner node `b` (and, depth first, the
// wide nodes below it); returns its index. Children are numbered after
// their parent, so a ray's walk reads the array mostly forwards.
std::uint32_t collapse(const big_vector<bvh_node>& bin, std::uint32_t b, big_vector<bvh_wide_node>& out) {
    // Open the largest inner child until there are `wide` of them: the
    // largest box is the one most rays enter, so it is the one most worth
    // replacing by its children's tighter boxes.
    std::uint32_t slot[wide] = {bin[b].first, bin[b].first + 1};
    int n = 2;
    while (n < wide) {
        int best = -1;
        double best_area = -1;
        for (int i = 0; i < n; ++i) {
            const bvh_node& c = bin[slot[i]];
            if (c.count > 0) continue;
            const double a = area(c.box);
            if (a > best_area) best_area = a, best = i;
        }
        if (best < 0) break;
        const std::uint32_t opened = slot[best];
        slot[best] = bin[opened].first;
        slot[n++] = bin[opened].first + 1;
    }
    const auto index = std::uint32_t(out.size());
    out.emplace_back();
    std::uint32_t child[wide], count[wide];
    for (int i = 0; i < wide; ++i) {
        if (i >= n) {
            child[i] = 0, count[i] = bvh_wide_node::empty_slot;
            continue;
        }
        const bvh_node& c = bin[slot[i]];
        child[i] = c.count > 0 ? c.first : collapse(bin, slot[i], out);
        count[i] = c.count;
    }
    bvh_wide_node& w = out[index];  // after the recursion: `out` may have moved
    for (int i = 0; i < wide; ++i) {
        // An empty slot gets the inverted box (low +inf, high -inf), which no ray enters (fast_path.cpp).
        const bvh_box box = i < n ? bin[slot[i]].box : empty_box();
        for (int a = 0; a < 3; ++a) w.lo[a][i] = box.lo[a], w.hi[a][i] = box.hi[a];
        w.child[i] = child[i], w.count[i] = count[i];
    }
    return index;
}

}  // namespace

bvh_wide_tree collapse_to_wide(bvh_tree&& binary) {
    stopwatch clock;
    bvh_wide_tree tree;
    tree.order = std::move(binary.order);
    tree.leaves = binary.leaves, tree.depth = binary.depth;
    if (!binary.nodes.empty()) {
        const bvh_node& root = binary.nodes[0];
        if (root.count > 0) {  // a single leaf: a wide root with one child
            bvh_wide_node w{};
            for (int i = 0; i < wide; ++i) {
                const bvh_box box = i == 0 ? root.box : empty_box();
                for (int a = 0; a < 3; ++a) w.lo[a][i] = box.lo[a], w.hi[a][i] = box.hi[a];
                w.child[i] = 0, w.count[i] = bvh_wide_node::empty_slot;
            }
            w.child[0] = root.first, w.count[0] = root.count;
            tree.nodes.push_back(w);
        } else {
            // A wide node replaces at least two binary inner nodes (the
            // tree has leaves - 1 of them) unless its children are leaves.
            tree.nodes.reserve(binary.leaves / 2 + 1);
            collapse(binary.nodes, 0, tree.nodes);
        }
    }
    big_vector<bvh_node>().swap(binary.nodes);
    tree.build_seconds = binary.build_seconds + clock.seconds();
    return tree;
}

}  // namespace rt::render_tool
