#include "core/contacts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <glm/geometric.hpp>

namespace clothlab {

void apply_sphere_contact(const sphere_parameters& sphere, double time_step,
                          particle_system& particles) {
  const glm::dvec3 c = sphere.centre;
  const double r = sphere.radius;
  const double friction_factor = 1.0 - sphere.friction * time_step;  // (1 - mu_s dt)
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (particles.is_fixed[k])
      continue;
    const glm::dvec3 p = particles.get_position(k);
    const double distance = glm::length(p - c);
    if (!(distance < r))
      continue;
    const glm::dvec3 n = distance > 0.0 ? (p - c) / distance : glm::dvec3(0.0, 0.0, 1.0);
    glm::dvec3 v = particles.get_velocity(k);
    v -= std::min(glm::dot(v, n), 0.0) * n;  // no velocity into the sphere
    const glm::dvec3 normal_part = glm::dot(v, n) * n;
    v = normal_part + friction_factor * (v - normal_part);  // v_t *= (1 - mu_s dt)
    particles.set_position(k, c + r * n);
    particles.set_velocity(k, v);
  }
}

double self_collision_distance(const cloth_parameters& p) {
  const double h = p.side_length / (p.grid_size - 1);
  return std::min(p.self_collision_thickness, h);
}

namespace {

// The cell of a position in a grid of cells of side d, hashed into `buckets` (a power of two).
std::uint32_t cell_hash(long cx, long cy, long cz, std::size_t buckets) {
  const auto h = static_cast<std::uint64_t>(cx) * 73856093u ^
                 static_cast<std::uint64_t>(cy) * 19349663u ^
                 static_cast<std::uint64_t>(cz) * 83492791u;
  return static_cast<std::uint32_t>(h & (buckets - 1));
}

long cell_of(double x, double d) {
  return static_cast<long>(std::floor(x / d));
}

}  // namespace

std::size_t self_collision::apply(int grid_size, double thickness, particle_system& particles) {
  const std::size_t count = particles.size();
  const double d = thickness;
  if (count == 0 || !(d > 0.0) || !particles.is_finite())
    return 0;
  std::size_t buckets = 1;
  while (buckets < 2 * count)
    buckets *= 2;
  cell_start_.assign(buckets + 1, 0);
  sorted_.resize(count);
  bucket_.resize(count);
  position_delta_.assign(3 * count, 0.0);
  velocity_delta_.assign(3 * count, 0.0);

  // Counting sort of the particles by bucket.
  for (std::size_t k = 0; k < count; ++k) {
    const glm::dvec3 p = particles.get_position(k);
    bucket_[k] = cell_hash(cell_of(p.x, d), cell_of(p.y, d), cell_of(p.z, d), buckets);
    ++cell_start_[bucket_[k] + 1];
  }
  for (std::size_t b = 0; b < buckets; ++b)
    cell_start_[b + 1] += cell_start_[b];
  next_slot_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t k = 0; k < count; ++k)
    sorted_[next_slot_[bucket_[k]]++] = static_cast<std::uint32_t>(k);

  std::size_t pairs = 0;
  const auto n = static_cast<std::size_t>(grid_size);
  for (std::size_t i = 0; i < count; ++i) {
    const glm::dvec3 p_i = particles.get_position(i);
    const long cx = cell_of(p_i.x, d), cy = cell_of(p_i.y, d), cz = cell_of(p_i.z, d);
    const long ku_i = static_cast<long>(i % n), kv_i = static_cast<long>(i / n);
    for (long dz = -1; dz <= 1; ++dz) {
      for (long dy = -1; dy <= 1; ++dy) {
        for (long dx = -1; dx <= 1; ++dx) {
          const std::uint32_t b = cell_hash(cx + dx, cy + dy, cz + dz, buckets);
          for (std::uint32_t s = cell_start_[b]; s < cell_start_[b + 1]; ++s) {
            const std::size_t j = sorted_[s];
            if (j <= i)
              continue;  // each pair once, from its lower index
            // Two hashed cells may share a bucket: the distance test below decides.
            const glm::dvec3 p_j = particles.get_position(j);
            const glm::dvec3 apart = p_i - p_j;
            const double L = glm::length(apart);
            if (!(L > 0.0 && L < d))
              continue;
            const long ku_j = static_cast<long>(j % n), kv_j = static_cast<long>(j / n);
            if (std::labs(ku_i - ku_j) <= 2 && std::labs(kv_i - kv_j) <= 2)
              continue;  // grid neighbours: their springs keep them apart
            // A pair can be met again from another cell with the same bucket: count it once,
            // from the cell of p_j itself.
            if (cell_of(p_j.x, d) != cx + dx || cell_of(p_j.y, d) != cy + dy ||
                cell_of(p_j.z, d) != cz + dz)
              continue;
            const bool fixed_i = particles.is_fixed[i] != 0;
            const bool fixed_j = particles.is_fixed[j] != 0;
            if (fixed_i && fixed_j)
              continue;
            ++pairs;
            const glm::dvec3 u = apart / L;
            const double c = (d - L) / 2;
            const double w = glm::dot(particles.get_velocity(i) - particles.get_velocity(j), u);
            const double share_i = fixed_i ? 0.0 : fixed_j ? 2.0 : 1.0;
            const double share_j = fixed_j ? 0.0 : fixed_i ? 2.0 : 1.0;
            for (int a = 0; a < 3; ++a) {
              position_delta_[3 * i + a] += share_i * c * u[a];
              position_delta_[3 * j + a] -= share_j * c * u[a];
              if (w < 0) {
                velocity_delta_[3 * i + a] -= share_i * (w / 2) * u[a];
                velocity_delta_[3 * j + a] += share_j * (w / 2) * u[a];
              }
            }
          }
        }
      }
    }
  }
  for (std::size_t i = 0; i < 3 * count; ++i) {
    particles.position[i] += position_delta_[i];
    particles.velocity[i] += velocity_delta_[i];
  }
  return pairs;
}

}  // namespace clothlab
