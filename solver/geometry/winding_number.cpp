#include "geometry/winding_number.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace sc {

WindingNumber::WindingNumber(const TriangleMesh& mesh) : mesh_(mesh) {
  order_.resize(mesh.triangles.size());
  std::iota(order_.begin(), order_.end(), 0u);
  nodes_.reserve(2 * order_.size() / 4 + 1);
  build(0, static_cast<std::uint32_t>(order_.size()));
}

std::int32_t WindingNumber::build(std::uint32_t first, std::uint32_t count) {
  const auto& V = mesh_.vertices;
  auto corner = [&](std::uint32_t t, int c) -> const Vec<3>& { return V[mesh_.triangles[t][c]]; };
  Node node;
  node.first = first;
  node.count = count;
  node.centre.setZero();
  node.area_normal.setZero();
  double area_sum = 0.0;
  Vec<3> lo = Vec<3>::Constant(INFINITY), hi = Vec<3>::Constant(-INFINITY);
  for (std::uint32_t k = first; k < first + count; ++k) {
    const std::uint32_t t = order_[k];
    const Vec<3> an = 0.5 * (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0));
    const Vec<3> centroid = (corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0;
    node.area_normal += an;
    node.centre += an.norm() * centroid;
    area_sum += an.norm();
    lo = lo.cwiseMin(centroid);
    hi = hi.cwiseMax(centroid);
  }
  node.centre = area_sum > 0.0 ? Vec<3>(node.centre / area_sum) : Vec<3>(0.5 * (lo + hi));
  for (std::uint32_t k = first; k < first + count; ++k)
    for (int c = 0; c < 3; ++c) node.radius = std::max(node.radius, (corner(order_[k], c) - node.centre).norm());
  const auto id = static_cast<std::int32_t>(nodes_.size());
  nodes_.push_back(node);
  if (count <= 8) return id;
  // Split at the median centroid along the widest axis of the centroids' box.
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const std::uint32_t half = count / 2;
  auto key = [&](std::uint32_t t) { return corner(t, 0)[axis] + corner(t, 1)[axis] + corner(t, 2)[axis]; };
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b) || (key(a) == key(b) && a < b); });
  const std::int32_t left = build(first, half);
  const std::int32_t right = build(first + half, count - half);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

double WindingNumber::solid_angle(std::uint32_t t, const Vec<3>& q) const {
  const auto& tri = mesh_.triangles[t];
  const Vec<3> a = mesh_.vertices[tri[0]] - q, b = mesh_.vertices[tri[1]] - q, c = mesh_.vertices[tri[2]] - q;
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double numerator = a.dot(b.cross(c));
  const double denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
  return 2.0 * std::atan2(numerator, denominator);
}

double WindingNumber::operator()(const Vec<3>& q) const {
  double omega = 0.0;
  std::vector<std::int32_t> stack{0};
  while (!stack.empty()) {
    const Node& n = nodes_[stack.back()];
    stack.pop_back();
    const Vec<3> d = n.centre - q;
    const double r = d.norm();
    if (r > far_ratio * n.radius) {
      omega += n.area_normal.dot(d) / (r * r * r);
    } else if (n.left < 0) {
      for (std::uint32_t k = n.first; k < n.first + n.count; ++k) omega += solid_angle(order_[k], q);
    } else {
      stack.push_back(n.left);
      stack.push_back(n.right);
    }
  }
  return omega / (4.0 * pi);
}

bool WindingNumber::inside(const Vec<3>& q) const { return std::abs((*this)(q)) > 0.5; }

std::vector<Vec<3>, Eigen::aligned_allocator<Vec<3>>> sample_inside(const TriangleMesh& mesh, double dx) {
  const WindingNumber w(mesh);
  const Vec<3> lo = mesh.bbox_min(), hi = mesh.bbox_max();
  std::array<long, 3> count{};
  for (int d = 0; d < 3; ++d) count[d] = std::max(1L, static_cast<long>(std::ceil((hi[d] - lo[d]) / dx)));
  const long total = count[0] * count[1] * count[2];
  std::vector<std::uint8_t> in(static_cast<std::size_t>(total));
  auto point = [&](long k) {
    return Vec<3>(lo[0] + (k % count[0] + 0.5) * dx, lo[1] + ((k / count[0]) % count[1] + 0.5) * dx,
                  lo[2] + (k / (count[0] * count[1]) + 0.5) * dx);
  };
#pragma omp parallel for schedule(dynamic, 256)
  for (long k = 0; k < total; ++k) in[k] = w.inside(point(k)) ? 1 : 0;
  std::vector<Vec<3>, Eigen::aligned_allocator<Vec<3>>> out;
  for (long k = 0; k < total; ++k)
    if (in[k]) out.push_back(point(k));
  return out;
}

}  // namespace sc
