#include "reference_data.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"

namespace sc {

Columns read_reference_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "reference data file cannot be opened");
  std::string line;
  std::vector<std::string> names;
  Columns out;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (names.empty()) {
      names = cells;
      continue;
    }
    if (cells.size() != names.size())
      throw InputError(path, "line " + std::to_string(line_no), "expected " + std::to_string(names.size()) + " columns");
    for (std::size_t k = 0; k < cells.size(); ++k) {
      char* end = nullptr;
      const double v = std::strtod(cells[k].c_str(), &end);
      if (end == cells[k].c_str() || !std::isfinite(v))
        throw InputError(path, "line " + std::to_string(line_no), "'" + cells[k] + "' is not a number");
      out[names[k]].push_back(v);
    }
  }
  if (names.empty() || out.empty()) throw InputError(path, "", "no data rows");
  return out;
}

double interpolate_linear(const std::vector<double>& xs, const std::vector<double>& ys, double xq) {
  if (xs.empty()) return NAN;
  if (xq <= xs.front()) return ys.front();
  if (xq >= xs.back()) return ys.back();
  const auto it = std::upper_bound(xs.begin(), xs.end(), xq);
  const std::size_t k = static_cast<std::size_t>(it - xs.begin());
  const double w = (xq - xs[k - 1]) / (xs[k] - xs[k - 1]);
  return ys[k - 1] + w * (ys[k] - ys[k - 1]);
}

}  // namespace sc
