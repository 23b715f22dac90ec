#include "core/csv.hpp"

#include "core/error.hpp"

namespace slambox {

std::string CsvLine(const CsvRow& fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::string& f = fields[i];
    if (i) line += ',';
    if (f.find_first_of(",\"\n\r") == std::string::npos) {
      line += f;
    } else {
      line += '"';
      for (char c : f) line += c == '"' ? std::string("\"\"") : std::string(1, c);
      line += '"';
    }
  }
  return line + "\n";
}

std::vector<CsvRow> ParseCsv(const std::string& text, const std::string& path) {
  std::vector<CsvRow> rows;
  CsvRow row;
  std::string field;
  bool quoted = false, in_row = false;
  int line = 1, row_line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') { field += '"'; ++i; }
      else if (c == '"') quoted = false;
      else { if (c == '\n') ++line; field += c; }
      continue;
    }
    if (!in_row) { in_row = true; row_line = line; }
    if (c == '"' && field.empty()) quoted = true;
    else if (c == ',') { row.push_back(field); field.clear(); }
    else if (c == '\r') continue;
    else if (c == '\n') {
      row.push_back(field);
      field.clear();
      if (!rows.empty() && row.size() != rows.front().size())
        throw InputError(path, row_line, "row has " + std::to_string(row.size()) + " fields, the header " +
                         std::to_string(rows.front().size()), "repair or regenerate the file");
      rows.push_back(row);
      row.clear();
      in_row = false;
      ++line;
    } else field += c;
  }
  if (quoted) throw InputError(path, row_line, "unterminated quoted field", "repair or regenerate the file");
  if (in_row) {
    row.push_back(field);
    if (!rows.empty() && row.size() != rows.front().size())
      throw InputError(path, row_line, "the last row is incomplete (truncated file?)", "regenerate the file");
    rows.push_back(row);
  }
  return rows;
}

}  // namespace slambox
