#include "cloth_parallel.hpp"

#include <omp.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>

namespace clothlab {
namespace {

// Adds the force of the spring (K, L0) from the particle at (xi, yi, zi) to the one at
// (xj, yj, zj) on the first one: equation 2, in the order of spring_force (spring.hpp), so that
// both paths round alike.
inline void add_spring(double xi, double yi, double zi, double xj, double yj, double zj, double K,
                       double L0, double& fx, double& fy, double& fz) {
  const double dx = xi - xj, dy = yi - yj, dz = zi - zj;
  const double L = std::sqrt(dx * dx + dy * dy + dz * dz);
  const double s = K * (L0 - L) / L;
  fx += s * dx;
  fy += s * dy;
  fz += s * dz;
}

struct neighbour {
  int du, dv, family;
};
// The order of spring_mesh::compute_force: structural, shear, bending, each in the order of its
// table there.
constexpr neighbour neighbours[12] = {{1, 0, 0}, {0, 1, 0},  {-1, 0, 0},  {0, -1, 0},
                                      {1, 1, 1}, {-1, 1, 1}, {-1, -1, 1}, {1, -1, 1},
                                      {2, 0, 2}, {0, 2, 2},  {-2, 0, 2},  {0, -2, 2}};

}  // namespace

bool cloth_parallel::supports(const cloth_parameters& p, std::string& error) {
  const integrator_kind integrator = p.dynamics.integrator;
  if (integrator != integrator_kind::semi_implicit &&
      integrator != integrator_kind::explicit_euler) {
    error = "integrator " + std::string(integrator_name(integrator)) +
            ": the cpu-parallel path runs semi-implicit or explicit only";
    return false;
  }
  if (p.tear_strain > 0.0) {
    error = "--tear-strain: the cpu-parallel path does not tear springs; use --backend cpu";
    return false;
  }
  if (p.self_collision_thickness > 0.0) {
    error = "--self-collision: the cpu-parallel path has no self-collision; use --backend cpu";
    return false;
  }
  return true;
}

int cloth_parallel::threads() const {
  return threads_ > 0 ? threads_ : omp_get_max_threads();
}

void cloth_parallel::load(const spring_mesh& cloth) {
  n_ = cloth.grid_size();
  normals_set_ = false;
  const std::size_t count = cloth.particles().size();
  for (auto* array :
       {&x_, &y_, &z_, &vx_, &vy_, &vz_, &fx_, &fy_, &fz_, &nx_, &ny_, &nz_, &moving_})
    array->assign(count, 0.0);
  const particle_system& particles = cloth.particles();
  for (std::size_t k = 0; k < count; ++k) {
    x_[k] = particles.position[3 * k];
    y_[k] = particles.position[3 * k + 1];
    z_[k] = particles.position[3 * k + 2];
    vx_[k] = particles.velocity[3 * k];
    vy_[k] = particles.velocity[3 * k + 1];
    vz_[k] = particles.velocity[3 * k + 2];
    moving_[k] = particles.is_fixed[k] ? 0.0 : 1.0;
  }
  const std::size_t n = static_cast<std::size_t>(n_);
  for (auto* array : {&su_, &sv_, &d1_, &d2_, &bu_, &bv_})
    array->assign(count, 0.0);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t ku = k % n, kv = k / n;
    if (ku + 1 < n)
      su_[k] = cloth.rest_length(k, 1, 0);
    if (kv + 1 < n)
      sv_[k] = cloth.rest_length(k, 0, 1);
    if (ku + 1 < n && kv + 1 < n)
      d1_[k] = cloth.rest_length(k, 1, 1);
    if (ku >= 1 && kv + 1 < n)
      d2_[k] = cloth.rest_length(k, -1, 1);
    if (ku + 2 < n)
      bu_[k] = cloth.rest_length(k, 2, 0);
    if (kv + 2 < n)
      bv_[k] = cloth.rest_length(k, 0, 2);
  }
}

double cloth_parallel::rest_length(std::size_t k, int du, int dv) const {
  const std::size_t n = static_cast<std::size_t>(n_);
  switch ((du + 2) * 5 + (dv + 2)) {
    case 3 * 5 + 2:
      return su_[k];  // (1, 0)
    case 1 * 5 + 2:
      return su_[k - 1];  // (-1, 0)
    case 2 * 5 + 3:
      return sv_[k];  // (0, 1)
    case 2 * 5 + 1:
      return sv_[k - n];  // (0, -1)
    case 3 * 5 + 3:
      return d1_[k];  // (1, 1)
    case 1 * 5 + 1:
      return d1_[k - n - 1];  // (-1, -1)
    case 1 * 5 + 3:
      return d2_[k];  // (-1, 1)
    case 3 * 5 + 1:
      return d2_[k - n + 1];  // (1, -1)
    case 4 * 5 + 2:
      return bu_[k];  // (2, 0)
    case 0 * 5 + 2:
      return bu_[k - 2];  // (-2, 0)
    case 2 * 5 + 4:
      return bv_[k];  // (0, 2)
    case 2 * 5 + 0:
      return bv_[k - 2 * n];  // (0, -2)
  }
  return 0.0;
}

void cloth_parallel::read_state(spring_mesh& cloth) const {
  particle_system& particles = cloth.particles();
  for (std::size_t k = 0; k < x_.size(); ++k) {
    particles.position[3 * k] = x_[k];
    particles.position[3 * k + 1] = y_[k];
    particles.position[3 * k + 2] = z_[k];
    particles.velocity[3 * k] = vx_[k];
    particles.velocity[3 * k + 1] = vy_[k];
    particles.velocity[3 * k + 2] = vz_[k];
  }
}

// n = normalize(d_u x d_v), central differences, one-sided on the border (docs/model.md).
void cloth_parallel::compute_normals() {
  const int n = n_;
  const double* x = x_.data();
  const double* y = y_.data();
  const double* z = z_.data();
#pragma omp parallel for schedule(static) num_threads(threads())
  for (int kv = 0; kv < n; ++kv) {
    const int v_plus = std::min(kv + 1, n - 1), v_minus = std::max(kv - 1, 0);
    for (int ku = 0; ku < n; ++ku) {
      const int u_plus = std::min(ku + 1, n - 1), u_minus = std::max(ku - 1, 0);
      const std::size_t a = std::size_t(u_plus) + std::size_t(n) * kv;
      const std::size_t b = std::size_t(u_minus) + std::size_t(n) * kv;
      const std::size_t c = std::size_t(ku) + std::size_t(n) * v_plus;
      const std::size_t d = std::size_t(ku) + std::size_t(n) * v_minus;
      const double ux = x[a] - x[b], uy = y[a] - y[b], uz = z[a] - z[b];
      const double wx = x[c] - x[d], wy = y[c] - y[d], wz = z[c] - z[d];
      const double cx = uy * wz - uz * wy, cy = uz * wx - ux * wz, cz = ux * wy - uy * wx;
      const double length = std::sqrt(cx * cx + cy * cy + cz * cz);
      const std::size_t k = std::size_t(ku) + std::size_t(n) * kv;
      nx_[k] = cx / length;
      ny_[k] = cy / length;
      nz_[k] = cz / length;
    }
  }
}

void cloth_parallel::compute_forces(const cloth_parameters& p) {
  const int n = n_;
  const double K[3] = {p.structural_stiffness, p.shear_stiffness, p.bending_stiffness};
  const double wind = p.wind_strength;
  const double wind_length =
      std::sqrt(p.wind_direction.x * p.wind_direction.x + p.wind_direction.y * p.wind_direction.y +
                p.wind_direction.z * p.wind_direction.z);
  const double ux = p.wind_direction.x / wind_length, uy = p.wind_direction.y / wind_length,
               uz = p.wind_direction.z / wind_length;
  const double* x = x_.data();
  const double* y = y_.data();
  const double* z = z_.data();
  double* fx = fx_.data();
  double* fy = fy_.data();
  double* fz = fz_.data();
  const std::ptrdiff_t N = n;

  const double* nx = nx_.data();
  const double* ny = ny_.data();
  const double* nz = nz_.data();
  // The wind, F_w = K_w <n, u_w> n, added last as in compute_force; without wind the normals
  // are 0 and it adds +0, as compute_force does.
  const auto add_wind = [&](std::size_t k, double& gx, double& gy, double& gz) {
    const double along = nx[k] * ux + ny[k] * uy + nz[k] * uz;
    gx += wind * along * nx[k];
    gy += wind * along * ny[k];
    gz += wind * along * nz[k];
  };

#pragma omp parallel for schedule(static) num_threads(threads())
  for (int kv = 0; kv < n; ++kv) {
    // A particle near the border has only the neighbours inside the grid: the general loop.
    const auto border_particle = [&](int ku) {
      const std::size_t k = std::size_t(ku) + std::size_t(n) * kv;
      double gx = 0.0, gy = 0.0, gz = 0.0;
      for (const neighbour& o : neighbours) {
        const int u = ku + o.du, v = kv + o.dv;
        if (u < 0 || u >= n || v < 0 || v >= n)
          continue;
        const std::size_t j = std::size_t(u) + std::size_t(n) * v;
        add_spring(x[k], y[k], z[k], x[j], y[j], z[j], K[o.family], rest_length(k, o.du, o.dv), gx,
                   gy, gz);
      }
      add_wind(k, gx, gy, gz);
      fx[k] = gx;
      fy[k] = gy;
      fz[k] = gz;
    };
    const bool interior_row = kv >= 2 && kv < n - 2;
    if (!interior_row || n < 5) {
      for (int ku = 0; ku < n; ++ku)
        border_particle(ku);
      continue;
    }
    border_particle(0);
    border_particle(1);
    // The interior of the row: all 12 neighbours exist, at fixed offsets of the flat index.
    const std::ptrdiff_t row = N * kv;
    const double Ks = K[0], Kh = K[1], Kb = K[2];
    const double* su = su_.data();
    const double* sv = sv_.data();
    const double* d1 = d1_.data();
    const double* d2 = d2_.data();
    const double* bu = bu_.data();
    const double* bv = bv_.data();
#pragma omp simd
    for (std::ptrdiff_t k = row + 2; k < row + N - 2; ++k) {
      double gx = 0.0, gy = 0.0, gz = 0.0;
      const double xi = x[k], yi = y[k], zi = z[k];
      add_spring(xi, yi, zi, x[k + 1], y[k + 1], z[k + 1], Ks, su[k], gx, gy, gz);
      add_spring(xi, yi, zi, x[k + N], y[k + N], z[k + N], Ks, sv[k], gx, gy, gz);
      add_spring(xi, yi, zi, x[k - 1], y[k - 1], z[k - 1], Ks, su[k - 1], gx, gy, gz);
      add_spring(xi, yi, zi, x[k - N], y[k - N], z[k - N], Ks, sv[k - N], gx, gy, gz);
      add_spring(xi, yi, zi, x[k + N + 1], y[k + N + 1], z[k + N + 1], Kh, d1[k], gx, gy, gz);
      add_spring(xi, yi, zi, x[k + N - 1], y[k + N - 1], z[k + N - 1], Kh, d2[k], gx, gy, gz);
      add_spring(xi, yi, zi, x[k - N - 1], y[k - N - 1], z[k - N - 1], Kh, d1[k - N - 1], gx, gy,
                 gz);
      add_spring(xi, yi, zi, x[k - N + 1], y[k - N + 1], z[k - N + 1], Kh, d2[k - N + 1], gx, gy,
                 gz);
      add_spring(xi, yi, zi, x[k + 2], y[k + 2], z[k + 2], Kb, bu[k], gx, gy, gz);
      add_spring(xi, yi, zi, x[k + 2 * N], y[k + 2 * N], z[k + 2 * N], Kb, bv[k], gx, gy, gz);
      add_spring(xi, yi, zi, x[k - 2], y[k - 2], z[k - 2], Kb, bu[k - 2], gx, gy, gz);
      add_spring(xi, yi, zi, x[k - 2 * N], y[k - 2 * N], z[k - 2 * N], Kb, bv[k - 2 * N], gx, gy,
                 gz);
      // The wind (its normals are 0 when there is none: it adds +0, as compute_force does).
      const double along = nx[k] * ux + ny[k] * uy + nz[k] * uz;
      gx += wind * along * nx[k];
      gy += wind * along * ny[k];
      gz += wind * along * nz[k];
      fx[k] = gx;
      fy[k] = gy;
      fz[k] = gz;
    }
    border_particle(n - 2);
    border_particle(n - 1);
  }

  // The drag: F_d = K_d (q - p) on one particle, unless it is pinned.
  const drag_parameters& drag = p.drag;
  if (drag.enabled && drag.ku >= 0 && drag.ku < n && drag.kv >= 0 && drag.kv < n) {
    const std::size_t k = std::size_t(drag.ku) + std::size_t(n) * drag.kv;
    if (moving_[k] != 0.0) {
      fx[k] += drag.stiffness * (drag.target.x - x[k]);
      fy[k] += drag.stiffness * (drag.target.y - y[k]);
      fz[k] += drag.stiffness * (drag.target.z - z[k]);
    }
  }
}

void cloth_parallel::integrate(const cloth_parameters& p) {
  const dynamics_parameters& d = p.dynamics;
  const double dt = d.time_step;
  const double damping_factor = 1.0 - dt * d.damping;
  const double m = d.mass;
  const double inverse_mass = 1.0 / d.mass;
  const double g0 = d.gravity;
  const bool explicit_euler = d.integrator == integrator_kind::explicit_euler;
  const double z_g = p.ground_enabled ? p.ground_height : -HUGE_VAL;  // no ground: never below
  const double ground_factor = 1.0 - p.ground_friction * dt;
  const sphere_parameters& sphere = p.sphere;
  const double sphere_factor = 1.0 - sphere.friction * dt;
  const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(x_.size());
  double* x = x_.data();
  double* y = y_.data();
  double* z = z_.data();
  double* vx = vx_.data();
  double* vy = vy_.data();
  double* vz = vz_.data();
  const double* fx = fx_.data();
  const double* fy = fy_.data();
  const double* fz = fz_.data();
  const double* moving = moving_.data();

  // The integrator, then the sphere (in the readable path's order), then the ground; written
  // with selections rather than branches so that the loop vectorises. A pinned particle keeps
  // its position and its zero velocity.
#pragma omp parallel num_threads(threads())
  {
    if (explicit_euler) {
#pragma omp for simd schedule(static)
      for (std::ptrdiff_t k = 0; k < count; ++k) {
        // p_new = p + dt v and v_new = (1 - mu dt) v + dt a(p), both from the old state. A
        // pinned particle (moving 0: v = 0) gets dt 0 and damping factor 1: it stays put.
        const double dt_k = dt * moving[k];
        const double damping_k = damping_factor * moving[k] + (1.0 - moving[k]);
        const double ux = vx[k], uy = vy[k], uz = vz[k];
        x[k] = x[k] + dt_k * ux;
        y[k] = y[k] + dt_k * uy;
        z[k] = z[k] + dt_k * uz;
        vx[k] = damping_k * ux + dt_k * (fx[k] * inverse_mass + 0.0);
        vy[k] = damping_k * uy + dt_k * (fy[k] * inverse_mass + 0.0);
        vz[k] = damping_k * uz + dt_k * (fz[k] * inverse_mass - g0);
      }
    } else {
#pragma omp for simd schedule(static)
      for (std::ptrdiff_t k = 0; k < count; ++k) {
        // v = (1 - dt mu) v + dt (F / m + g), then p = p + dt v with the new v (0 when pinned).
        const double dt_k = dt * moving[k];
        const double damping_k = damping_factor * moving[k] + (1.0 - moving[k]);
        const double ux = damping_k * vx[k] + dt_k * (fx[k] / m + 0.0);
        const double uy = damping_k * vy[k] + dt_k * (fy[k] / m + 0.0);
        const double uz = damping_k * vz[k] + dt_k * (fz[k] / m + -g0);
        vx[k] = ux;
        vy[k] = uy;
        vz[k] = uz;
        x[k] = x[k] + dt * ux;
        y[k] = y[k] + dt * uy;
        z[k] = z[k] + dt * uz;
      }
    }
    if (sphere.enabled) {
#pragma omp for schedule(static)
      for (std::ptrdiff_t k = 0; k < count; ++k) {
        const double cx = x[k] - sphere.centre.x, cy = y[k] - sphere.centre.y,
                     cz = z[k] - sphere.centre.z;
        const double distance = std::sqrt(cx * cx + cy * cy + cz * cz);
        if (moving[k] == 0.0 || !(distance < sphere.radius))
          continue;
        double ex = 0.0, ey = 0.0, ez = 1.0;  // n = (0, 0, 1) at the centre
        if (distance > 0.0) {
          ex = cx / distance;
          ey = cy / distance;
          ez = cz / distance;
        }
        double ux = vx[k], uy = vy[k], uz = vz[k];
        const double inward = std::min(ux * ex + uy * ey + uz * ez, 0.0);
        ux -= inward * ex;
        uy -= inward * ey;
        uz -= inward * ez;
        const double along = ux * ex + uy * ey + uz * ez;
        vx[k] = along * ex + sphere_factor * (ux - along * ex);
        vy[k] = along * ey + sphere_factor * (uy - along * ey);
        vz[k] = along * ez + sphere_factor * (uz - along * ez);
        x[k] = sphere.centre.x + sphere.radius * ex;
        y[k] = sphere.centre.y + sphere.radius * ey;
        z[k] = sphere.centre.z + sphere.radius * ez;
      }
    }
#pragma omp for simd schedule(static)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      // The ground z = z_g: back on it, no downward velocity, the sliding damped.
      const double pz = z[k], ux = vx[k], uy = vy[k], uz = vz[k];
      const bool below = moving[k] != 0.0 && pz < z_g;
      z[k] = below ? z_g : pz;
      vz[k] = below ? std::max(uz, 0.0) : uz;
      vx[k] = below ? ux * ground_factor : ux;
      vy[k] = below ? uy * ground_factor : uy;
    }
  }
}

int cloth_parallel::run(const cloth_parameters& p, int count, double speed_bound) {
  for (int s = 1; s <= count; ++s) {
    step(p);
    if (speed_bound > 0.0 && diverged(speed_bound))
      return s;
  }
  return 0;
}

bool cloth_parallel::diverged(double speed_bound) const {
  const double bound_squared = speed_bound * speed_bound;
  const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(x_.size());
  int found = 0;
#pragma omp parallel for simd schedule(static) reduction(| : found) num_threads(threads())
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const double speed_squared = vx_[k] * vx_[k] + vy_[k] * vy_[k] + vz_[k] * vz_[k];
    // !(a <= b) is true for NaN as well.
    const bool finite =
        std::abs(x_[k]) <= DBL_MAX && std::abs(y_[k]) <= DBL_MAX && std::abs(z_[k]) <= DBL_MAX;
    found |= static_cast<int>(!(speed_squared <= bound_squared) || !finite);
  }
  return found != 0;
}

void cloth_parallel::step(const cloth_parameters& given) {
  if (std::string error; !supports(given, error))
    throw std::invalid_argument("cloth_parallel::step: " + error);
  if (n_ == 0)
    throw std::logic_error("cloth_parallel::step called before load");
  cloth_parameters resolved = given;
  resolved.grid_size = n_;
  const cloth_parameters p = effective_cloth_parameters(resolved);
  if (p.wind_strength != 0.0) {
    compute_normals();
    normals_set_ = true;
  } else if (normals_set_) {  // no wind: zero normals, so that the wind term adds +0
    std::fill(nx_.begin(), nx_.end(), 0.0);
    std::fill(ny_.begin(), ny_.end(), 0.0);
    std::fill(nz_.begin(), nz_.end(), 0.0);
    normals_set_ = false;
  }
  compute_forces(p);
  integrate(p);
}

}  // namespace clothlab
