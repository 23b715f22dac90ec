#pragma once
// Whitespace-separated numeric rows, as many datasets write them (one record per line;
// blank lines and lines starting with '#' skipped). Every token must be a finite number:
// otherwise an InputError names the file, the line and `fix`.
#include <string>
#include <vector>

namespace slambox {

struct NumberRow {
  int line = 0;                ///< 1-based line number in the file
  std::vector<double> values;  ///< the row's numbers, in order
};

std::vector<NumberRow> ParseNumberRows(const std::string& text, const std::string& name, const std::string& fix);

}  // namespace slambox
