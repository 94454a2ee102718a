#include "flip/extrapolate.hpp"

namespace sc::flip {

template <int D>
FaceField<D> known_faces(const MacGrid<D>& grid, const std::vector<Cell>& label) {
  FaceField<D> known = grid.zero_faces();
  for (int a = 0; a < D; ++a) {
    const Index<D> dims = grid.face_dims(a);
    for (std::size_t k = 0; k < known[a].size(); ++k) {
      Index<D> f = MacGrid<D>::unflat(k, dims);
      if (grid.is_wall_face(a, f)) {
        known[a][k] = 1.0;
        continue;
      }
      const bool high = is_fluid(label[grid.cell(f)]);
      --f[a];
      known[a][k] = high || is_fluid(label[grid.cell(f)]) ? 1.0 : 0.0;
    }
  }
  return known;
}

template <int D>
void extrapolate(const MacGrid<D>& grid, FaceField<D> known, int layers, FaceField<D>& u) {
  for (int a = 0; a < D; ++a) {
    const Index<D> dims = grid.face_dims(a);
    const long faces = static_cast<long>(u[a].size());
    for (int layer = 0; layer < layers; ++layer) {
      const std::vector<double> old_u = u[a], old_known = known[a];
#pragma omp parallel for schedule(dynamic, 4096)
      for (long k = 0; k < faces; ++k) {
        if (old_known[k] != 0.0) continue;
        const Index<D> f = MacGrid<D>::unflat(static_cast<std::size_t>(k), dims);
        double sum = 0.0, count = 0.0;
        for (int d = 0; d < D; ++d)
          for (const int s : {-1, 1}) {
            Index<D> nb = f;
            nb[d] += s;
            if (!MacGrid<D>::inside(nb, dims)) continue;
            const std::size_t j = MacGrid<D>::flat(nb, dims);
            if (old_known[j] == 0.0) continue;
            sum += old_u[j];
            count += 1.0;
          }
        if (count > 0.0) {
          u[a][k] = sum / count;
          known[a][k] = 1.0;
        }
      }
    }
    for (long k = 0; k < faces; ++k)
      if (known[a][k] == 0.0) u[a][k] = 0.0;
  }
}

template FaceField<2> known_faces<2>(const MacGrid<2>&, const std::vector<Cell>&);
template FaceField<3> known_faces<3>(const MacGrid<3>&, const std::vector<Cell>&);
template void extrapolate<2>(const MacGrid<2>&, FaceField<2>, int, FaceField<2>&);
template void extrapolate<3>(const MacGrid<3>&, FaceField<3>, int, FaceField<3>&);

}  // namespace sc::flip
