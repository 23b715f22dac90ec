#include "datasets/number_rows.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.hpp"
#include "core/limits.hpp"

namespace slambox {

std::vector<NumberRow> ParseNumberRows(const std::string& text, const std::string& name, const std::string& fix) {
  std::vector<NumberRow> rows;
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    limits::CheckLineLength(name, line_number, line.size());
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    std::istringstream fields(line);
    NumberRow row{line_number, {}};
    std::string token;
    while (fields >> token) {
      char* end = nullptr;
      const double x = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(x))
        throw InputError(name, line_number, "'" + token + "' is not a finite number", fix);
      row.values.push_back(x);
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace slambox
