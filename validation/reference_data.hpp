// Experimental tables and other reference data kept as CSV under reference/data/, with a header
// of '#' comment lines (source, units, time scale) and one line of column names.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace sc {

using Columns = std::map<std::string, std::vector<double>>;

/// Reads a reference CSV; throws InputError naming the file and line on any problem.
Columns read_reference_csv(const std::string& path);

/// Linear interpolation of (x, y) at xq; xs must be increasing. Outside the range: the end value.
double interpolate_linear(const std::vector<double>& xs, const std::vector<double>& ys, double xq);

}  // namespace sc
