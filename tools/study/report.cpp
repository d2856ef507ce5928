// report.cpp — tables, CSV and the work-precision diagram.
#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace rt::study {
namespace {

std::string fmt(const char* format, double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, x);
    return buf;
}

std::string number(double x) {
    if (std::isinf(x)) return "inf";
    if (x == 0) return "0";
    return fmt(x >= 1e5 || x < 1e-2 ? "%.2g" : "%.3g", x);
}

std::string timing(const outcome& o) {
    if (o.ns.median == 0) return "-";
    return fmt("%.1f", o.ns.median) + " [" + fmt("%.1f", o.ns.min) + ", " + fmt("%.1f", o.ns.max) + "]";
}

std::string extra(const outcome& o) {
    std::string s;
    if (o.rays) s += "leaks " + std::to_string(o.leaks) + "/" + std::to_string(o.rays) + " rays";
    if (o.off_plane_max >= 0) s += "off-plane ULP " + number(o.off_plane_median) + " / " + number(o.off_plane_max);
    if (o.nan_hits || o.out_of_range)
        s += (s.empty() ? "" : "; ") + std::string("BROKEN: ") + std::to_string(o.nan_hits) + " NaN, " +
             std::to_string(o.out_of_range) + " out of range";
    return s.empty() ? "" : s;
}

std::ofstream open(const std::string& path) {
    std::ofstream f(path);
    if (!f) throw std::runtime_error("cannot write " + path);
    return f;
}

}  // namespace

void print_family_table(std::ostream& os, const std::string& family, const std::string& description,
                        const std::vector<outcome>& rows) {
    os << "\n### " << family << ": " << description << "\n\n";
    bool any_extra = false;
    for (const outcome& o : rows)
        if (o.family == family && !extra(o).empty()) any_extra = true;
    os << "| formulation | prec | ns/test median [min, max] | hits % | ULP med / p99 / max | rel. error med / p99 / max "
          "| false hits | false misses | wrong roots |"
       << (any_extra ? " notes |" : "") << "\n";
    os << "|---|---|---|---|---|---|---|---|---|" << (any_extra ? "---|" : "") << "\n";
    for (const outcome& o : rows) {
        if (o.family != family) continue;
        os << "| " << o.formulation << " | " << o.precision << " | ";
        if (o.failed) {
            os << o.failure << " | | | | | | |" << (any_extra ? " |" : "") << "\n";
            continue;
        }
        const error_summary& e = o.error;
        os << timing(o) << " | " << fmt("%.1f", 100 * o.hit_ratio()) << " | ";
        if (e.count)
            os << number(e.ulp_median) << " / " << number(e.ulp_p99) << " / " << number(e.ulp_max) << " | "
               << fmt("%.1e", e.rel_median) << " / " << fmt("%.1e", e.rel_p99) << " / " << fmt("%.1e", e.rel_max);
        else
            os << "- | -";
        os << " | " << o.false_hits << " | " << o.false_misses << " | " << o.wrong_roots << " |";
        if (any_extra) os << " " << extra(o) << " |";
        os << "\n";
    }
}

void print_group_table(std::ostream& os, const std::vector<std::string>& groups, std::size_t per_group,
                       const std::vector<outcome>& rows) {
    os << "\nMisclassified rays (false hits + false misses) out of " << per_group << " per group:\n\n";
    os << "| formulation | prec |";
    for (const std::string& g : groups) os << " " << g << " |";
    os << "\n|---|---|";
    for (std::size_t i = 0; i < groups.size(); ++i) os << "---|";
    os << "\n";
    for (const outcome& o : rows) {
        if (o.failed || o.misclassified_per_group.size() != groups.size()) continue;
        os << "| " << o.formulation << " | " << o.precision << " |";
        for (std::size_t n : o.misclassified_per_group) os << " " << n << " |";
        os << "\n";
    }
}

void print_group_error_table(std::ostream& os, const std::vector<std::string>& groups, const std::vector<outcome>& rows) {
    os << "\nLargest relative error of a hit on the right root, per group (- : no hit on the right root):\n\n"
          "| formulation | prec |";
    for (const std::string& g : groups) os << " " << g << " |";
    os << "\n|---|---|";
    for (std::size_t i = 0; i < groups.size(); ++i) os << "---|";
    os << "\n";
    for (const outcome& o : rows) {
        if (o.failed || o.rel_max_per_group.size() != groups.size()) continue;
        os << "| " << o.formulation << " | " << o.precision << " |";
        for (std::size_t g = 0; g < groups.size(); ++g)
            os << " " << (o.compared_per_group[g] ? fmt("%.1e", o.rel_max_per_group[g]) : "-") << " |";
        os << "\n";
    }
}

void print_summary_table(std::ostream& os, const std::vector<std::string>& families, const std::vector<outcome>& rows) {
    os << "\n| formulation | prec |";
    for (const std::string& f : families) os << " " << f << " |";
    os << "\n|---|---|";
    for (std::size_t i = 0; i < families.size(); ++i) os << "---|";
    os << "\n";
    std::vector<std::pair<std::string, std::string>> keys;
    for (const outcome& o : rows) {
        if (std::find(families.begin(), families.end(), o.family) == families.end()) continue;
        std::pair<std::string, std::string> k{o.formulation, o.precision};
        if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    }
    for (const auto& [name, precision] : keys) {
        os << "| " << name << " | " << precision << " |";
        for (const std::string& f : families) {
            const outcome* found = nullptr;
            for (const outcome& o : rows)
                if (o.family == f && o.formulation == name && o.precision == precision) found = &o;
            if (!found || found->failed) {
                os << " - |";
                continue;
            }
            os << " " << found->misclassified() << " / " << (found->error.count ? number(found->error.ulp_max) : "-")
               << " / " << fmt("%.0f", found->ns.median);
            if (found->rays) os << " (leaks " << found->leaks << ")";
            os << " |";
        }
        os << "\n";
    }
}

void write_csv(const std::string& path, const std::vector<outcome>& rows) {
    std::ofstream f = open(path);
    f << "family,formulation,precision,queries,hit_ratio,ns_median,ns_min,ns_max,ulp_median,ulp_p99,ulp_max,"
         "rel_median,rel_p99,rel_max,compared,false_hits,false_misses,wrong_roots,nan_hits,out_of_range,rays,leaks,"
         "off_plane_median_ulp,off_plane_max_ulp,failed\n";
    for (const outcome& o : rows) {
        const error_summary& e = o.error;
        f << o.family << "," << o.formulation << "," << o.precision << "," << o.queries << "," << o.hit_ratio() << ","
          << o.ns.median << "," << o.ns.min << "," << o.ns.max << "," << e.ulp_median << "," << e.ulp_p99 << ","
          << e.ulp_max << "," << e.rel_median << "," << e.rel_p99 << "," << e.rel_max << "," << e.count << ","
          << o.false_hits << "," << o.false_misses << "," << o.wrong_roots << "," << o.nan_hits << ","
          << o.out_of_range << "," << o.rays << "," << o.leaks << "," << o.off_plane_median << ","
          << o.off_plane_max << "," << (o.failed ? 1 : 0) << "\n";
    }
}

void write_group_csv(const std::string& path, const std::vector<std::string>& groups, const std::vector<outcome>& rows) {
    std::ofstream f = open(path);
    f << "group,formulation,precision,misclassified\n";
    for (const outcome& o : rows) {
        if (o.misclassified_per_group.size() != groups.size()) continue;
        for (std::size_t i = 0; i < groups.size(); ++i)
            f << groups[i] << "," << o.formulation << "," << o.precision << "," << o.misclassified_per_group[i] << "\n";
    }
}

void write_svg(const std::string& path, const std::vector<std::string>& families, const std::vector<outcome>& rows,
               const std::string& subtitle) {
    const int columns = 4, panel_w = 330, panel_h = 300, margin = 50, top = 70;
    const int panel_rows = static_cast<int>((families.size() + columns - 1) / columns);
    const int legend_y = top + panel_rows * panel_h + 10;
    const int width = columns * panel_w + 20, height = legend_y + 60;
    const char* palette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
                             "#17becf", "#bcbd22", "#393b79", "#637939", "#e7969c", "#7f7f7f", "#000000"};
    const int palette_size = static_cast<int>(sizeof palette / sizeof palette[0]);
    // One colour per formulation name across all panels.
    std::vector<std::string> names;
    for (const outcome& o : rows)
        if (std::find(names.begin(), names.end(), o.formulation) == names.end()) names.push_back(o.formulation);
    auto colour = [&](const std::string& name) {
        auto i = std::find(names.begin(), names.end(), name) - names.begin();
        return palette[i % palette_size];
    };
    // Shared axes: time 1..1000 ns, error 1e-18..1 (smaller errors, and exact answers, sit on the floor).
    const int plot_w = panel_w - margin - 20, plot_h = panel_h - 30 - margin;
    auto x_of = [&](double ns) { return margin + (std::log10(std::clamp(ns, 1.0, 1000.0)) / 3.0) * plot_w; };
    auto y_of = [&](double err) { return 30 + (-std::log10(std::clamp(err, 1e-18, 1.0)) / 18.0) * plot_h; };
    std::ofstream f = open(path);
    f << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
      << "' font-family='sans-serif' font-size='11'>\n<rect width='100%' height='100%' fill='white'/>\n";
    f << "<text x='10' y='22' font-size='16'>Work-precision: error against time, one point per formulation and "
         "precision</text>\n";
    f << "<text x='10' y='40'>" << subtitle << "</text>\n";
    f << "<text x='10' y='56'>x: nanoseconds per test (median, log scale); y: largest relative error of a hit on the "
         "right root (log scale). Circle: float; square: double. A red ring marks misclassified rays (for meshes: "
         "leaks), count beside it.</text>\n";
    for (std::size_t p = 0; p < families.size(); ++p) {
        int ox = 10 + static_cast<int>(p % columns) * panel_w, oy = top + static_cast<int>(p / columns) * panel_h;
        f << "<g transform='translate(" << ox << "," << oy << ")'>\n";
        f << "<rect x='" << margin << "' y='30' width='" << plot_w << "' height='" << plot_h
          << "' fill='none' stroke='#999'/>\n";
        f << "<text x='" << margin << "' y='22' font-size='13' font-weight='bold'>" << families[p] << "</text>\n";
        for (int e = 0; e <= 18; e += 3)
            f << "<text x='" << margin - 4 << "' y='" << y_of(std::pow(10.0, -e)) + 4 << "' text-anchor='end'>1e-" << e
              << "</text>\n";
        for (double ns : {1.0, 10.0, 100.0, 1000.0})
            f << "<text x='" << x_of(ns) << "' y='" << panel_h - margin + 14 << "' text-anchor='middle'>" << ns
              << "</text>\n";
        f << "<text x='" << margin + plot_w / 2 << "' y='" << panel_h - margin + 28 << "' text-anchor='middle' "
             "fill='#555'>ns per test</text>\n";
        for (const outcome& o : rows) {
            if (o.family != families[p] || o.failed || o.ns.median <= 0 || o.error.count == 0) continue;
            double x = x_of(o.ns.median), y = y_of(o.error.rel_max);
            const char* c = colour(o.formulation);
            if (o.precision == "float")
                f << "<circle cx='" << x << "' cy='" << y << "' r='5' fill='" << c << "' fill-opacity='0.85'/>\n";
            else
                f << "<rect x='" << x - 4.5 << "' y='" << y - 4.5 << "' width='9' height='9' fill='" << c
                  << "' fill-opacity='0.85'/>\n";
            // For closed meshes the count that matters is the leaks: rays
            // through a shared edge may go to either neighbour, not to neither.
            std::size_t bad = o.rays ? o.leaks : o.misclassified();
            if (bad)
                f << "<circle cx='" << x << "' cy='" << y << "' r='8' fill='none' stroke='red' stroke-width='1.2'/>"
                  << "<text x='" << x + 9 << "' y='" << y - 6 << "' fill='red' font-size='9'>" << bad << "</text>\n";
        }
        f << "</g>\n";
    }
    // The legend: every formulation's colour, in table order.
    int lx = 10, ly = legend_y;
    for (const std::string& n : names) {
        int w = 24 + 7 * static_cast<int>(n.size());
        if (lx + w > width - 10) lx = 10, ly += 18;
        f << "<rect x='" << lx << "' y='" << ly << "' width='10' height='10' fill='" << colour(n) << "'/><text x='"
          << lx + 14 << "' y='" << ly + 9 << "'>" << n << "</text>\n";
        lx += w;
    }
    f << "</svg>\n";
}

}  // namespace rt::study
