// Tearing (an addition of clothlab, docs/model.md): a spring stretched past (1 + strain) L0
// breaks for the rest of the run. spring_mesh keeps, for every vertex, which of its springs
// tore (spring_torn_), so that compute_force asks spring_intact in constant time.
#include <algorithm>

#include "core/spring_mesh.hpp"

namespace clothlab {

std::size_t spring_mesh::tear_springs(double strain) {
  std::span<const glm::dvec3> vertices = as_vectors(particles_.position);
  return remove_springs([&](spring_family, const spring& s) {
    return glm::length(vertices[s.a] - vertices[s.b]) > (1.0 + strain) * s.rest_length;
  });
}

std::size_t spring_mesh::remove_springs(
    const std::function<bool(spring_family, const spring&)>& torn) {
  std::size_t removed = 0;
  for (spring_family family : all_spring_families) {
    std::vector<spring>& list = springs_[static_cast<int>(family)];
    const auto first_torn = std::stable_partition(
        list.begin(), list.end(), [&](const spring& s) { return !torn(family, s); });
    for (auto it = first_torn; it != list.end(); ++it)
      set_spring_torn(*it);
    removed += static_cast<std::size_t>(list.end() - first_torn);
    list.erase(first_torn, list.end());
  }
  return removed;
}

std::size_t spring_mesh::remove_springs_if(const std::function<bool(const spring&)>& torn) {
  return remove_springs([&](spring_family, const spring& s) { return torn(s); });
}

void spring_mesh::set_spring_torn(const spring& s) {
  const int n = grid_size_;
  const int du = static_cast<int>(s.b % n) - static_cast<int>(s.a % n);
  const int dv = static_cast<int>(s.b / n) - static_cast<int>(s.a / n);
  spring_torn_[spring_slot(s.a, du, dv)] = 1;
  spring_torn_[spring_slot(s.b, -du, -dv)] = 1;
}

bool spring_mesh::triangle_intact(int ku, int kv, bool upper) const {
  // Lower (ku, kv), (ku+1, kv), (ku+1, kv+1); upper (ku, kv), (ku+1, kv+1), (ku, kv+1): both
  // share the shear diagonal (ku, kv)-(ku+1, kv+1).
  const bool diagonal = spring_intact(ku, kv, 1, 1);
  if (upper)
    return diagonal && spring_intact(ku, kv, 0, 1) && spring_intact(ku, kv + 1, 1, 0);
  return diagonal && spring_intact(ku, kv, 1, 0) && spring_intact(ku + 1, kv, 0, 1);
}

}  // namespace clothlab
