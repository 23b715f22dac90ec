#pragma once
// NumPy .npy files (format version 1.0, numpy/lib/format.py): magic "\x93NUMPY", version,
// a little-endian header length, a Python dict literal {'descr', 'fortran_order',
// 'shape'} padded with spaces to a multiple of 64 bytes and ended by '\n', then the data.
#include <string>
#include <vector>

namespace slambox {

/// A 1-D float64 array ('<f8', shape (n,)) as .npy bytes.
std::string NpyFloat64(const std::vector<double>& values);

/// A C-order rows x cols float64 array ('<f8', shape (rows, cols)); `values` row-major.
std::string NpyFloat64Matrix(const std::vector<double>& values, int rows, int cols);

}  // namespace slambox
