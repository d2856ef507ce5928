// study — error against run time for every formulation, in float and double.
//
//   study                 the default run (about a minute): tables on stdout,
//                         out/study/study.csv, far_groups.csv, study.svg, study.md
//   study --long          more cases and more timing runs: steadier figures
//   study --quick         a few seconds (the ctest smoke run)
//
// For every case family it prints one table: formulation x precision ->
// nanoseconds per test (median over runs [min, max], data in cache, hit
// ratio), error in ULPs and relative (median, 99th percentile, max) against
// MPFR references from the same inputs, and counts of false hits, false
// misses and wrong roots. Chapter 07's own intersect_sphere_robust (the
// student's code, or the solution in a solution build) is measured in the
// same tables when this program is linked with it.
#include "build_info.hpp"
#include "report.hpp"

#include "common/timing.hpp"

#include <CLI/CLI.hpp>

#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#ifdef RT_STUDY_HAS_CH07
#include "07-precision/robust_sphere.hpp"
#endif

namespace {

using namespace rt;
using namespace rt::study;
namespace fm = rt::formulations;

// Each family's group names (e.g. the far family's distances), by family.
using group_names = std::map<std::string, std::vector<std::string>>;

struct settings {
    case_options cases;
    timing_options timing;
    bool student = true;
};

std::string machine_name() {
    std::ifstream cpu("/proc/cpuinfo");
    std::string line;
    while (std::getline(cpu, line))
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

#ifdef RT_STUDY_HAS_CH07
template <class T>
std::optional<T> chapter07(const ray<T>& r, const sphere<T>& s, const interval<T>& range) {
    auto h = rt::ch07::intersect_sphere_robust(s, r, range);
    return h ? std::optional<T>(h->t) : std::nullopt;
}
#endif

// Measures one routine on one family: answers, then time.
template <class T, class Q, class Fn, class Batch>
outcome measure_one(const family<Q>& fam, const std::vector<reference_answer>& refs, const std::string& name, Fn fn,
                    Batch batch, const settings& s) {
    outcome o;
    try {
        o = evaluate<T>(fam, refs, fn);
        o.ns = time_batch(fam, batch, s.timing);
    } catch (const std::exception& e) {
        o = outcome{};
        o.family = fam.name;
        o.precision = sizeof(T) == 4 ? "float" : "double";
        o.failed = true;
        o.failure = e.what();
    }
    o.formulation = name;
    return o;
}

template <class T, class Q, class Table>
void measure_families(const std::vector<family<Q>>& families, const Table& table, const settings& s,
                      std::vector<outcome>& rows, group_names& groups) {
    for (const family<Q>& fam : families) {
        groups[fam.name] = fam.group_names;
        std::vector<reference_answer> refs = references(fam);
        for (const auto& entry : table)
            rows.push_back(measure_one<T>(fam, refs, entry.name, entry.template fn<T>(), entry.template batch<T>(), s));
        if constexpr (std::is_same_v<Q, sphere_query<T>>) {
#ifdef RT_STUDY_HAS_CH07
            if (s.student)
                rows.push_back(measure_one<T>(fam, refs, "chapter 07", &chapter07<T>,
                                              &fm::run_batch<sphere_query<T>, &chapter07<T>>, s));
#endif

        }
    }
}

template <class T>
void measure_precision(const settings& s, std::vector<outcome>& rows, group_names& groups,
                       std::vector<std::pair<std::string, std::string>>& families) {
    auto spheres = sphere_families<T>(s.cases);
    auto planes = plane_families<T>(s.cases);
    auto triangles = triangle_families<T>(s.cases);
    auto note = [&families](const auto& list) {
        for (const auto& f : list) {
            bool known = false;
            for (const auto& k : families) known |= k.first == f.name;
            if (!known) families.emplace_back(f.name, f.description);
        }
    };
    note(spheres), note(planes), note(triangles);
    measure_families<T>(spheres, fm::sphere_formulations(), s, rows, groups);
    measure_families<T>(planes, fm::plane_formulations(), s, rows, groups);
    measure_families<T>(triangles, fm::triangle_formulations(), s, rows, groups);
}

// The second copy of a batch loop: the same loop as the registry's
// run_batch, but a function of this file only (internal linkage). An
// instance of run_batch itself here would be the very same symbol as the
// registry's, and the linker keeps one of the two: both columns would time
// one piece of code.
template <auto F>
double second_copy(const sphere_query<float>* queries, std::size_t count) {
    double sum = 0;
    for (std::size_t i = 0; i < count; ++i)
        sum += fm::answer_weight(F(queries[i].r, queries[i].shape, queries[i].range));
    return sum;
}

// The cost of the robust float sphere against the plain float quadratic, in
// two copies of each batch loop: the registry's (compiled in registry.cpp,
// as in the tables) and a second one compiled here. The same source runs
// up to twice as fast or slow depending on where the linker puts a loop (the
// plain quadratic's loop has been measured at 5.5 and at 11 ns per test in
// two binaries), so one copy alone can flatter either side.
void print_cost_table(std::ostream& os, const settings& s) {
    using Q = sphere_query<float>;
    // At least 15 pairs: the table is small, and its ratios are what the
    // course promises (mixed at most 2x plain), so they get the steadier figure.
    timing_options timing = s.timing;
    timing.runs = std::max(timing.runs, 15);
    const fm::batch_fn<Q> plain[2] = {fm::sphere_formulation_named("plain").batch32,
                                      &second_copy<&fm::sphere_plain<float>>};
    const fm::batch_fn<Q> mixed[2] = {fm::sphere_formulation_named("mixed").batch32,
                                      &second_copy<&fm::sphere_mixed<float>>};
    os << "\n## Cost of the robust float sphere (mixed / plain, float)\n\n"
       << "ns per test (median of the runs) in the registry's copy of the loops and in a second copy compiled in "
          "study.cpp, and mixed / plain in each: the median over runs of plain and mixed timed in alternation ("
       << timing.runs << " pairs), so it can differ a little from the quotient of the two medians. The larger "
          "ratio is the one to quote.\n\n"
       << "| family | plain | mixed | ratio | plain (2nd copy) | mixed (2nd copy) | ratio (2nd copy) |\n"
       << "|---|---|---|---|---|---|---|\n";
    os << std::fixed << std::setprecision(1);
    for (const family<Q>& fam : sphere_families<float>(s.cases)) {
        paired_timing t[2];
        for (int copy = 0; copy < 2; ++copy) t[copy] = time_pair(fam, plain[copy], mixed[copy], timing);
        os << "| " << fam.name;
        for (int copy = 0; copy < 2; ++copy)
            os << " | " << t[copy].a.median << " | " << t[copy].b.median << " | " << std::setprecision(2)
               << t[copy].ratio << std::setprecision(1);
        os << " |\n";
    }
    os << std::defaultfloat;
}

// Rows of one family next to each other: formulation, then float before double.
std::vector<outcome> ordered(const std::vector<outcome>& rows) {
    std::vector<outcome> out;
    std::vector<std::string> names;
    for (const outcome& o : rows)
        if (std::find(names.begin(), names.end(), o.formulation) == names.end()) names.push_back(o.formulation);
    for (const std::string& n : names)
        for (const char* p : {"float", "double"})
            for (const outcome& o : rows)
                if (o.formulation == n && o.precision == p) out.push_back(o);
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Formulation study: error against run time of ray-sphere, ray-plane and ray-triangle tests"};
    settings s;
    bool quick = false, longer = false;
    std::string out_dir = "out/study";
    app.add_flag("--quick", quick, "a few seconds: few cases, few timing runs (the smoke test)");
    app.add_flag("--long", longer, "more cases and timing runs for steadier figures (several minutes)");
    app.add_option("--out", out_dir, "folder for study.csv, far_groups.csv, study.svg and study.md");
    app.add_option("--seed", s.cases.seed, "seed of the random case families");
    int per_group = 0;
    app.add_option("--per-group", per_group, "random queries per group (overrides the run's default)")->check(CLI::Range(1, 1 << 20));
    std::size_t timed_queries = 0;
    app.add_option("--timed-queries", timed_queries,
                   "queries per timed batch (default 4096, held in cache; more distinct queries keep the branch "
                   "predictor from learning the batch's hit/miss pattern)")
        ->check(CLI::Range(1, 1 << 20));
    app.add_flag("!--no-student", s.student, "leave out chapter 07's intersect_sphere_robust");
    CLI11_PARSE(app, argc, argv);
    if (quick && longer) {
        std::cerr << "study: choose --quick or --long, not both\n";
        return 2;
    }
    if (quick) s.cases.per_group = 32, s.timing = {3, 0.0002, 512};
    if (longer) s.cases.per_group = 65536, s.timing = {31, 0.02, 4096};
    else if (!quick) s.cases.per_group = 16384, s.timing = {15, 0.01, 4096};
    if (per_group > 0) s.cases.per_group = per_group;
    if (timed_queries > 0) s.timing.max_queries = timed_queries;

    std::ostringstream machine;
    std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    machine << "Machine: " << machine_name() << " (" << std::thread::hardware_concurrency()
            << " logical CPUs); compiler: " << RT_STUDY_COMPILER << "; flags: " << RT_STUDY_FLAGS << "; " << date;
    std::ostringstream text;
    text << "# Formulation study\n\n" << machine.str() << "\n\n"
         << "Run: " << (quick ? "--quick" : longer ? "--long" : "default") << ", " << s.cases.per_group
         << " random queries per group, seed " << s.cases.seed << "; time: median of " << s.timing.runs
         << " runs over up to " << s.timing.max_queries
         << " queries held in cache, each run at least " << s.timing.seconds_per_run * 1e3
         << " ms of this thread's CPU time, routine inlined into the timing loop; \"hits %\" is the routine's own hit ratio on the timed data's "
            "family. ULPs and relative error are over hits on the reference's root.\n";

    rt::stopwatch clock;
    std::vector<outcome> rows;
    group_names groups;
    std::vector<std::pair<std::string, std::string>> families;
    measure_precision<float>(s, rows, groups, families);
    measure_precision<double>(s, rows, groups, families);
    rows = ordered(rows);

    std::vector<std::string> sphere_names, other_names;
    for (const auto& f : families)
        (f.first.rfind("plane", 0) == 0 || f.first.rfind("tri", 0) == 0 ? other_names : sphere_names).push_back(f.first);
    text << "\n## Summary\n\nEach cell: misclassified queries (false hits + false misses) / largest error in ULPs of a "
            "hit on the right root / median ns per test; for closed meshes also the leaks (rays that hit none of the "
            "triangles around the edge or corner they cross).\n\nSpheres:\n";
    print_summary_table(text, sphere_names, rows);
    text << "\nPlanes and triangles:\n";
    print_summary_table(text, other_names, rows);
    print_cost_table(text, s);
    text << "\n## Tables by family\n";
    for (const auto& [name, description] : families) {
        print_family_table(text, name, description, rows);
        if (name == "far") {
            std::vector<outcome> far_rows;
            for (const outcome& o : rows)
                if (o.family == "far") far_rows.push_back(o);
            print_group_table(text, groups["far"], static_cast<std::size_t>(s.cases.per_group), far_rows);
        }
        if (name == "ground") {
            std::vector<outcome> ground_rows;
            for (const outcome& o : rows)
                if (o.family == "ground") ground_rows.push_back(o);
            print_group_error_table(text, groups["ground"], ground_rows);
        }
    }
    text << "\nTotal run time " << clock.seconds() << " s.\n";
    std::cout << text.str();

    try {
        std::filesystem::create_directories(out_dir);
        std::vector<std::string> names;
        for (const auto& f : families) names.push_back(f.first);
        std::vector<outcome> far_rows;
        for (const outcome& o : rows)
            if (o.family == "far") far_rows.push_back(o);
        write_csv(out_dir + "/study.csv", rows);
        write_group_csv(out_dir + "/far_groups.csv", groups["far"], far_rows);
        write_svg(out_dir + "/study.svg", names, rows, machine.str());
        std::ofstream md(out_dir + "/study.md");
        md << text.str();
        std::cout << "\nWrote " << out_dir << "/study.csv, far_groups.csv, study.svg, study.md\n";
    } catch (const std::exception& e) {
        std::cerr << "study: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
