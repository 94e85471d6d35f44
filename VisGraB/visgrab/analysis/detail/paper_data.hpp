#pragma once

#include <string_view>

namespace visgrab::analysis::detail {

/// docs/paper-tables.csv, compiled in (generated paper_tables_csv.cpp).
std::string_view paperTablesCsv();

/// docs/paper-comparison.md, compiled in (generated paper_comparison_md.cpp).
std::string_view paperComparisonMarkdown();

}  // namespace visgrab::analysis::detail
