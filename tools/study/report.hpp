// report.hpp — the study's outputs: text tables, CSV files and the SVG diagram.
#pragma once

#include "measure.hpp"

#include <ostream>
#include <string>
#include <vector>

namespace rt::study {

// One family's table: formulation x precision, time, hit ratio, errors, counts.
void print_family_table(std::ostream& os, const std::string& family, const std::string& description,
                        const std::vector<outcome>& rows);

// Misclassified rays per group (e.g. per far-sphere distance), one row per
// formulation and precision.
void print_group_table(std::ostream& os, const std::vector<std::string>& groups, std::size_t per_group,
                       const std::vector<outcome>& rows);

// One row per formulation and precision, one column per family:
// "misclassified rays / largest ULP error / ns per test".
void print_summary_table(std::ostream& os, const std::vector<std::string>& families, const std::vector<outcome>& rows);

// Largest relative error per group (e.g. per ground-sphere radius and height).
void print_group_error_table(std::ostream& os, const std::vector<std::string>& groups, const std::vector<outcome>& rows);

void write_csv(const std::string& path, const std::vector<outcome>& rows);
void write_group_csv(const std::string& path, const std::vector<std::string>& groups, const std::vector<outcome>& rows);

// Work-precision diagram: one panel per family, log time against log error.
void write_svg(const std::string& path, const std::vector<std::string>& families, const std::vector<outcome>& rows,
               const std::string& subtitle);

}  // namespace rt::study
