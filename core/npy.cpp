#include "core/npy.hpp"

#include <bit>
#include <cassert>
#include <cstdint>
#include <cstring>

namespace slambox {

namespace {

std::string Npy(const std::vector<double>& values, const std::string& shape) {
  static_assert(std::endian::native == std::endian::little, "'<f8' data is written in native byte order");
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': " + shape + ", }";
  const std::size_t prefix = 10;  // magic (6) + version (2) + header length (2)
  header.append((64 - (prefix + header.size() + 1) % 64) % 64, ' ');
  header.push_back('\n');
  std::string out("\x93NUMPY\x01\x00", 8);
  out.push_back(static_cast<char>(header.size() & 0xff));
  out.push_back(static_cast<char>(header.size() >> 8));
  out += header;
  const std::size_t at = out.size();
  out.resize(at + values.size() * sizeof(double));
  if (!values.empty()) std::memcpy(&out[at], values.data(), values.size() * sizeof(double));
  return out;
}

}  // namespace

// Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "(" + std::to_string(n) + ",)".
std::string NpyFloat64(const std::vector<double>& values) {
  std::string shape("(");
  shape += std::to_string(values.size());
  shape += ",)";
  return Npy(values, shape);
}

std::string NpyFloat64Matrix(const std::vector<double>& values, int rows, int cols) {
  assert(values.size() == static_cast<std::size_t>(rows) * cols);
  std::string shape("(");
  shape += std::to_string(rows);
  shape += ", ";
  shape += std::to_string(cols);
  shape += ")";
  return Npy(values, shape);
}

}  // namespace slambox
