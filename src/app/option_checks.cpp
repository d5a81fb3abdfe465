#include "app/option_checks.hpp"

#include <glm/geometric.hpp>

#include <cmath>
#include <vector>

#include "core/cloth_parallel.hpp"
#include "core/i18n.hpp"
#include "core/xpbd.hpp"

namespace clothlab {
namespace {

// The bounds of the run's numbers and of the values that are not in the parameter table
// (docs/limits.md). Past them some double overflows or the run would not end in any reasonable
// time. A stable run inside them writes only finite numbers.
constexpr int max_image_side = 8192;
constexpr bounds wind_component_bounds{-1e6, 1e6, ""};
constexpr double min_wind_direction_length = 1e-6;  // normalised before use
constexpr bounds ground_height_bounds{-1e3, 1e3, "m"};
constexpr long max_steps = 1'000'000'000;  // with dt <= 1 s: t <= 1e9 s
constexpr int max_threads = 256;
constexpr double max_sweep_time = 1000.0;  // s

}  // namespace

// The ranges that combine options, and those of the run's own numbers.
void check_other_ranges(options& o, const given_values& values) {
  const std::string chosen(stage_name(o.stage));
  const cloth_parameters& cloth = o.cloth;
  const dynamics_parameters& d =
      parameter_fields::dynamics_of({o.spring, o.coupled, o.cloth}, o.stage);
  // (1 - mu dt) must not be negative, for the two Euler schemes that multiply the velocity by
  // it (the others apply the damping as a force).
  if (d.integrator == integrator_kind::semi_implicit ||
      d.integrator == integrator_kind::explicit_euler) {
    require(d.damping * d.time_step <= 1, "--mu", d.damping,
            format(tr("mu dt = %s for the %s stage (dt = %s) must be at most 1 (the damping factor "
                      "1 - mu dt would be negative)"),
                   format_number(d.damping * d.time_step).c_str(), chosen.c_str(),
                   format_number(d.time_step).c_str()));
  }
  // XPBD multiplies the velocity by (1 - mu h) every substep h = dt / substeps.
  if (d.integrator == integrator_kind::xpbd) {
    const double substep = d.time_step / d.xpbd.substeps;
    require(d.damping * substep <= 1, "--mu", d.damping,
            format(tr("mu h = %s for the %s stage (XPBD's substep h = dt / %d = %s) must be at "
                      "most 1 (the damping factor 1 - mu h would be negative)"),
                   format_number(d.damping * substep).c_str(), chosen.c_str(), d.xpbd.substeps,
                   format_number(substep).c_str()));
  }
  const std::string& wind_dir = values.wind_dir;
  if (cloth.wind_direction == glm::dvec3(0.0))
    throw usage_error{"--wind-dir " + wind_dir + colon() +
                      tr("the wind direction must not be zero")};
  for (int i = 0; i < 3; ++i) {
    const double c = cloth.wind_direction[i];
    if (!(c >= wind_component_bounds.low && c <= wind_component_bounds.high)) {
      throw usage_error{"--wind-dir " + wind_dir + colon() +
                        format(tr("each component must be between %s and %s"),
                               format_number(wind_component_bounds.low).c_str(),
                               format_number(wind_component_bounds.high).c_str())};
    }
  }
  // |u| is computed before normalising: its square must not underflow.
  const double wind_length = std::sqrt(glm::dot(cloth.wind_direction, cloth.wind_direction));
  if (!(wind_length >= min_wind_direction_length)) {
    throw usage_error{"--wind-dir " + wind_dir + colon() +
                      format(tr("the direction's length %s must be at least %s"),
                             format_number(wind_length).c_str(),
                             format_number(min_wind_direction_length).c_str())};
  }
  if (cloth.ground_enabled)
    require_within("--ground-z", cloth.ground_height, ground_height_bounds);
  require(o.stage != stage_kind::cloth || cloth.ground_friction * cloth.dynamics.time_step <= 1,
          "--ground-friction", cloth.ground_friction,
          format(tr("mu_g dt = %s must be at most 1"),
                 format_number(cloth.ground_friction * cloth.dynamics.time_step).c_str()));
  require(o.stage != stage_kind::cloth || cloth.sphere.friction * cloth.dynamics.time_step <= 1,
          "--sphere-friction", cloth.sphere.friction,
          format(tr("mu_s dt = %s must be at most 1"),
                 format_number(cloth.sphere.friction * cloth.dynamics.time_step).c_str()));
  require(o.threads >= 0 && o.threads <= max_threads, "--threads", o.threads,
          format(tr("must be between 1 and %d (0: all cores)"), max_threads));
  require(o.steps >= 0 && o.steps <= max_steps, "--steps", double(o.steps),
          format(tr("must be between %s and %s"), "0", format_number(double(max_steps)).c_str()));
  require(o.csv_every >= 1, "--csv-every", double(o.csv_every),
          format(tr("must be at least %s"), "1"));
  require(o.width >= 1 && o.width <= max_image_side, "--width", o.width,
          format(tr("must be between %s and %s"), "1", std::to_string(max_image_side).c_str()));
  require(o.height >= 1 && o.height <= max_image_side, "--height", o.height,
          format(tr("must be between %s and %s"), "1", std::to_string(max_image_side).c_str()));
  // Every value of a sweep list within the single option's bounds, not only its ends.
  for (double x : o.sweep_time_steps)
    require_within("--sweep-dt", x, bounds_of(parameter_named("--dt")));
  for (double x : o.sweep_stiffnesses)
    require_within("--sweep-K", x, bounds_of(parameter_named("--K")));
  require_finite("--sweep-time", o.sweep_time);
  require(o.sweep_time > 0 && o.sweep_time <= max_sweep_time, "--sweep-time", o.sweep_time,
          format(tr("must be positive and at most %s s"), format_number(max_sweep_time).c_str()));
}

// The options that do not fit the others.
void check_combinations(const options& o, const given_values& values, const given_option& given) {
  const cloth_parameters& cloth = o.cloth;
  if (o.backend != cloth_backend::cpu && o.stage != stage_kind::cloth) {
    throw usage_error{"--backend " + values.backend + colon() +
                      tr("this path simulates the cloth; use it with --stage cloth")};
  }
  const integrator_kind integrator = o.stage == stage_kind::spring ? o.spring.dynamics.integrator
                                     : o.stage == stage_kind::coupled
                                         ? o.coupled.dynamics.integrator
                                         : o.cloth.dynamics.integrator;
  if (integrator == integrator_kind::xpbd && !xpbd_available())
    throw usage_error{"--integrator " + values.integrator + colon() + xpbd_unavailable_reason()};
  if (integrator == integrator_kind::xpbd && o.backend == cloth_backend::gpu) {
    throw usage_error{std::string("--integrator xpbd") +  // (not translated: the option)
                      colon() +
                      tr("the gpu path (--backend gpu, the handout's fragment shaders) runs the "
                         "mass-spring integrators semi-implicit and explicit only; XPBD runs "
                         "with --backend cpu, cpu-parallel or gpu-compute")};
  }
  if (o.backend != cloth_backend::cpu && integrator != integrator_kind::semi_implicit &&
      integrator != integrator_kind::explicit_euler && integrator != integrator_kind::xpbd) {
    throw usage_error{"--integrator " + values.integrator + colon() +
                      format(tr("the %s path runs semi-implicit, explicit or xpbd only; use "
                                "--backend cpu"),
                             values.backend.c_str())};
  }
  if (integrator != integrator_kind::xpbd) {
    for (const auto* option : {"--xpbd-substeps", "--xpbd-iterations", "--xpbd-damping"}) {
      if (given(option))
        throw usage_error{std::string(option) + colon() +
                          tr("XPBD's; use it with --integrator xpbd")};
    }
  }
  if (o.backend != cloth_backend::cpu && o.backend != cloth_backend::cpu_parallel) {
    for (const auto* option : {"--tear-strain", "--self-collision"}) {
      const bool gpu_tears =
          std::string_view(option) == "--tear-strain" &&
          (o.backend == cloth_backend::gpu || o.backend == cloth_backend::gpu_compute);
      if (given(option) && !gpu_tears) {
        throw usage_error{std::string(option) + colon() +
                          format(tr("only the cpu and cpu-parallel paths have it, not --backend "
                                    "%s"),
                                 values.backend.c_str())};
      }
    }
  }
  if (given("--threads") && o.backend != cloth_backend::cpu_parallel)
    throw usage_error{"--threads" + std::string(colon()) + tr("only with --backend cpu-parallel")};
  if (o.stage != stage_kind::cloth) {
    // The cloth's additions: --drag, --sphere and the table's (--sphere-friction, ...).
    std::vector<std::string_view> additions = {"--drag", "--sphere"};
    for (const parameter& p : parameter_table) {
      if (p.scope == parameter_scope::cloth_addition)
        additions.push_back(p.option);
    }
    for (const std::string_view option : additions) {
      if (given(option))
        throw usage_error{std::string(option) + colon() +
                          tr("the cloth's; use it with --stage cloth")};
    }
  }
  if (cloth.drag.enabled && cloth.pins == pin_mode::corners && cloth.drag.kv == 0 &&
      (cloth.drag.ku == 0 || cloth.drag.ku == cloth.grid_size - 1)) {
    throw usage_error{"--drag " + values.drag + colon() +
                      format(tr("particle (%d,0) is pinned (--pins corners): a pinned particle "
                                "cannot be dragged"),
                             cloth.drag.ku)};
  }
  if (!o.sweep_path.empty()) {
    if (!o.sweep_stiffnesses.empty() && !o.sweep_grid_sizes.empty()) {
      throw usage_error{"--sweep-N " + values.sweep_n + colon() +
                        tr("sweep either K (--sweep-K) or N, not both")};
    }
    if (!o.sweep_grid_sizes.empty() && o.stage == stage_kind::spring) {
      throw usage_error{"--sweep-N " + values.sweep_n + colon() +
                        tr("the single spring has no size; use --stage coupled or cloth")};
    }
    if (o.backend != cloth_backend::cpu) {
      throw usage_error{"--sweep: " +
                        format(tr("the stability map runs on the cpu path; drop --backend %s"),
                               values.backend.c_str())};
    }
    for (const auto* option : {"--csv", "--obj", "--png", "--energy-csv"}) {
      if (given(option)) {
        throw usage_error{std::string(option) + colon() +
                          tr("not with --sweep (a sweep runs many cells)")};
      }
    }
  } else {
    for (const auto* option : {"--sweep-dt", "--sweep-K", "--sweep-N", "--sweep-time"}) {
      if (given(option))
        throw usage_error{std::string(option) + colon() + tr("only with --sweep")};
    }
  }
  if (!o.obj_path.empty() && o.stage != stage_kind::cloth) {
    throw usage_error{"--obj " + o.obj_path + colon() +
                      tr("the OBJ is the cloth's; use it with --stage cloth")};
  }
  if (o.backend == cloth_backend::cpu_parallel && !cloth_parallel::available())
    throw usage_error{"--backend " + values.backend + colon() +
                      cloth_parallel::unavailable_reason()};
  if (!o.headless && o.backend == cloth_backend::cpu_parallel) {
    throw usage_error{"--backend " + values.backend + colon() +
                      tr("headless only; the window runs the cpu, gpu and gpu-compute paths "
                         "(key G)")};
  }
  if (!o.headless && given("--gl"))
    throw usage_error{"--gl" + std::string(colon()) +
                      tr("only with --headless (the window has its own context)")};
  if (!o.headless) {
    for (const auto* option :
         {"--csv", "--csv-every", "--obj", "--png", "--steps", "--energy-csv", "--sweep"}) {
      if (given(option)) {
        throw usage_error{std::string(option) + colon() +
                          tr("only with --headless (the window runs live)")};
      }
    }
  }
}

}  // namespace clothlab
