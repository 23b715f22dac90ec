#pragma once
// Minimal RFC 4180 CSV: fields with a comma, quote or newline are quoted, quotes doubled.
#include <string>
#include <vector>

namespace slambox {

using CsvRow = std::vector<std::string>;

std::string CsvLine(const CsvRow& fields);  ///< with the trailing '\n'
/// Parses a whole file's text; throws InputError(path, line, ...) on an unterminated quote
/// or a row whose field count differs from the header's.
std::vector<CsvRow> ParseCsv(const std::string& text, const std::string& path);

}  // namespace slambox
