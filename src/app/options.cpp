#include "options.hpp"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <vector>

namespace clothlab {
namespace {

constexpr int max_grid_size = 1024;  // 1M particles: well within memory, far beyond interactivity
constexpr int max_chain = 1000;
constexpr int max_image_side = 8192;

// A usage error: the option and what is wrong with its value.
struct usage_error {
  std::string message;
};

std::string format_number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

void require(bool ok, const std::string& option, double value, const std::string& what) {
  if (!ok)
    throw usage_error{option + " " + format_number(value) + ": " + what};
}

void require_finite(const std::string& option, double value) {
  require(std::isfinite(value), option, value, "must be a finite number");
}

// "X,Y,Z" -> three finite numbers.
glm::dvec3 parse_vector(const std::string& option, const std::string& text) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    double x = 0.0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(x)) {
      throw usage_error{option + " " + text + ": expected three finite numbers X,Y,Z"};
    }
    values.push_back(x);
  }
  if (values.size() != 3 || (!text.empty() && text.back() == ',')) {
    throw usage_error{option + " " + text + ": expected three numbers X,Y,Z"};
  }
  return {values[0], values[1], values[2]};
}

// "A,B,C" (the values) or "FROM:TO:COUNT" (COUNT values spaced evenly on a log scale, both ends
// included), all positive and finite.
std::vector<double> parse_list(const std::string& option, const std::string& text) {
  auto number = [&](const std::string& item) {
    std::size_t used = 0;
    double x = NAN;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(x)) {
      throw usage_error{option + " " + text + ": '" + item + "' is not a finite number"};
    }
    return x;
  };
  std::vector<std::string> items;
  const char separator = text.find(':') != std::string::npos ? ':' : ',';
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, separator);)
    items.push_back(item);
  if (items.empty() || text.back() == separator) {
    throw usage_error{option + " " + text + ": expected A,B,C or FROM:TO:COUNT"};
  }
  std::vector<double> values;
  if (separator == ':') {
    if (items.size() != 3)
      throw usage_error{option + " " + text + ": expected FROM:TO:COUNT"};
    const double from = number(items[0]);
    const double to = number(items[1]);
    const double count = number(items[2]);
    if (!(from > 0 && to > 0) || count != std::floor(count) || count < 2 || count > 200) {
      throw usage_error{option + " " + text +
                        ": FROM and TO must be positive and COUNT a whole number from 2 to 200"};
    }
    for (int i = 0; i < int(count); ++i) {
      values.push_back(from * std::pow(to / from, i / (count - 1)));
    }
  } else {
    for (const std::string& item : items)
      values.push_back(number(item));
    if (values.size() > 200)
      throw usage_error{option + " " + text + ": at most 200 values"};
  }
  return values;
}

}  // namespace

parse_result parse_command_line(int argc, const char* const* argv) {
  options o;
  CLI::App app{
      "clothlab: mass-spring cloth simulation, the lab of shared/handout (single spring, "
      "coupled springs, cloth on the CPU and the GPU).\nWithout --headless it opens the "
      "interactive window.",
      "clothlab"};
  app.set_version_flag("--version", std::string("clothlab ") + CLOTHLAB_VERSION);
  app.get_formatter()->column_width(34);

  // Values given on the command line; defaults come from the parameter structs.
  double dt = 0, stiffness = 0, damping = 0, mass = 0, gravity = 0;
  std::string stage = "cloth", backend = "cpu", integrator, pin_choice, ground_z, wind_dir;
  std::string scaling, sweep_dt, sweep_k, sweep_n;
  const std::map<std::string, stage_kind> stages = {{"spring", stage_kind::spring},
                                                    {"coupled", stage_kind::coupled},
                                                    {"cloth", stage_kind::cloth}};
  const std::map<std::string, backend_kind> backends = {{"cpu", backend_kind::cpu},
                                                        {"gpu", backend_kind::gpu}};
  std::vector<std::string> integrators;
  for (integrator_kind kind : all_integrators)
    integrators.emplace_back(integrator_name(kind));
  const std::vector<std::string> scalings = {
      std::string(resolution_scaling_name(resolution_scaling::per_particle)),
      std::string(resolution_scaling_name(resolution_scaling::resolution_independent))};
  const std::map<std::string, pin_mode> pins = {{"corners", pin_mode::corners},
                                                {"none", pin_mode::none}};

  cloth_parameters& cloth = o.cloth;
  app.add_flag("--headless", o.headless, "Run without a window");
  app.add_option("--frames", o.frames, "Window: run COUNT frames, print the mean frame time, exit")
      ->check(CLI::PositiveNumber);
  app.add_option("--stage", stage, "spring | coupled | cloth (default cloth)")
      ->check(CLI::IsMember(stages));
  app.add_option("--backend", backend, "cpu | gpu: the cloth's simulation path (default cpu)")
      ->check(CLI::IsMember(backends));
  app.add_option(
         "--integrator", integrator,
         "semi-implicit (default) | explicit | verlet | rk4 | implicit (GPU: the first two)")
      ->check(CLI::IsMember(integrators));
  app.add_option("--steps", o.steps, "Steps to run, headless (default 1000)");
  auto* dt_option = app.add_option("--dt", dt, "Step length, s (spring 0.01, cloth 0.002)");
  auto* k_option = app.add_option("--K", stiffness, "Stiffness of the spring stages, N/m (20)");
  app.add_option("--K-struct", cloth.structural_stiffness, "Cloth structural stiffness, N/m")
      ->capture_default_str();
  app.add_option("--K-shear", cloth.shear_stiffness, "Cloth shear stiffness, N/m")
      ->capture_default_str();
  app.add_option("--K-bend", cloth.bending_stiffness, "Cloth bending stiffness, N/m")
      ->capture_default_str();
  auto* mu_option = app.add_option("--mu", damping, "Damping rate mu, 1/s (spring 0.2, cloth 0.5)");
  auto* mass_option = app.add_option("--mass", mass, "Mass of each moving particle, kg (1)");
  auto* gravity_option = app.add_option("--gravity", gravity, "Gravity g0 along -z, m/s^2 (9.8)");
  app.add_option("--chain", o.coupled.mass_count, "Moving masses of the coupled stage")
      ->capture_default_str();
  app.add_option("--N", cloth.grid_size, "Cloth grid size: N x N particles")->capture_default_str();
  app.add_option("--size", cloth.side_length, "Cloth side length, m")->capture_default_str();
  app.add_option("--pins", pin_choice, "corners (default) | none")->check(CLI::IsMember(pins));
  app.add_option("--wind-strength", cloth.wind_strength, "Wind strength K_w, N")
      ->capture_default_str();
  auto* wind_dir_option = app.add_option("--wind-dir", wind_dir, "Wind direction X,Y,Z (0,1,0)");
  auto* ground_option = app.add_option("--ground-z", ground_z, "Ground height, m, or none (-1)");
  app.add_option("--ground-friction", cloth.ground_friction, "Ground friction rate mu_g, 1/s")
      ->capture_default_str();
  app.add_option("--csv", o.csv_path, "Write the particles' states to this CSV file");
  app.add_option("--csv-every", o.csv_every, "Write every K-th step (default 1)");
  app.add_option("--obj", o.obj_path, "Write the final cloth as a Wavefront OBJ");
  app.add_option("--png", o.png_path, "Render the final state off-screen to this PNG");
  app.add_option("--width", o.width, "PNG width, px (800)");
  app.add_option("--height", o.height, "PNG height, px (600)");
  app.add_option("--energy-csv", o.energy_csv_path,
                 "Write step,t,kinetic,gravity,spring,total (every --csv-every steps)");
  app.add_option("--scaling", scaling,
                 "per-particle (default, the handout's) | resolution-independent (question 10)")
      ->check(CLI::IsMember(scalings));
  app.add_option("--reference-N", cloth.reference_grid_size,
                 "Grid whose particles have --mass and springs the K (resolution-independent)")
      ->capture_default_str();
  app.add_option(
      "--sweep", o.sweep_path,
      "Stability map: run every (dt, K or N) cell, write dt,K,N,integrator,diverged,step");
  app.add_option("--sweep-dt", sweep_dt, "Sweep dt values: A,B,C or FROM:TO:COUNT (log-spaced)");
  app.add_option("--sweep-K", sweep_k, "Sweep stiffnesses (cloth: K_struct, ratios kept)");
  app.add_option("--sweep-N", sweep_n, "Sweep grid sizes (cloth) or chain lengths (coupled)");
  app.add_option("--sweep-time", o.sweep_time, "Simulated seconds per sweep cell (2)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    app.exit(e);
    return {std::nullopt, 0};
  } catch (const CLI::ParseError& e) {
    std::string message = e.what();
    for (char& c : message) {
      if (c == '\n')
        c = ' ';
    }
    std::fprintf(stderr, "clothlab: %s (see --help)\n", message.c_str());
    return {std::nullopt, 2};
  }

  try {
    o.stage = stages.at(stage);
    o.backend = backends.at(backend);
    if (!pin_choice.empty())
      cloth.pins = pins.at(pin_choice);
    // The options every stage shares go into all three parameter structs.
    dynamics_parameters* all[] = {&o.spring.dynamics, &o.coupled.dynamics, &o.cloth.dynamics};
    for (dynamics_parameters* d : all) {
      if (*dt_option)
        d->time_step = dt;
      if (*mu_option)
        d->damping = damping;
      if (*mass_option)
        d->mass = mass;
      if (*gravity_option)
        d->gravity = gravity;
      if (!integrator.empty())
        d->integrator = *parse_integrator(integrator);
    }
    if (!scaling.empty())
      cloth.scaling = *parse_resolution_scaling(scaling);
    if (!sweep_dt.empty())
      o.sweep_time_steps = parse_list("--sweep-dt", sweep_dt);
    if (!sweep_k.empty())
      o.sweep_stiffnesses = parse_list("--sweep-K", sweep_k);
    if (!sweep_n.empty()) {
      for (double n : parse_list("--sweep-N", sweep_n)) {
        require(n == std::floor(n) && n >= 1 && n <= max_grid_size, "--sweep-N", n,
                "must be whole numbers between 1 and " + std::to_string(max_grid_size));
        o.sweep_grid_sizes.push_back(static_cast<int>(n));
      }
    }
    if (*k_option)
      o.spring.stiffness = o.coupled.stiffness = stiffness;
    if (*wind_dir_option)
      cloth.wind_direction = parse_vector("--wind-dir", wind_dir);
    if (*ground_option) {
      if (ground_z == "none") {
        cloth.ground_enabled = false;
      } else {
        std::size_t used = 0;
        double z = NAN;
        try {
          z = std::stod(ground_z, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != ground_z.size() || !std::isfinite(z)) {
          throw usage_error{"--ground-z " + ground_z + ": expected a number or none"};
        }
        cloth.ground_enabled = true;
        cloth.ground_height = z;
      }
    }

    // Ranges. Each message names the option and its value.
    const dynamics_parameters& d = o.stage == stage_kind::spring    ? o.spring.dynamics
                                   : o.stage == stage_kind::coupled ? o.coupled.dynamics
                                                                    : o.cloth.dynamics;
    require_finite("--dt", d.time_step);
    require(d.time_step > 0, "--dt", d.time_step, "must be positive");
    require_finite("--mu", d.damping);
    require(d.damping >= 0, "--mu", d.damping, "must be at least 0");
    // (1 - mu dt) must not be negative: for the run's stage headless, for every stage in the
    // window, where each stage keeps its own dt and the same mu.
    for (stage_kind checked : {stage_kind::spring, stage_kind::coupled, stage_kind::cloth}) {
      if (o.headless && checked != o.stage)
        continue;
      const dynamics_parameters& c = checked == stage_kind::spring    ? o.spring.dynamics
                                     : checked == stage_kind::coupled ? o.coupled.dynamics
                                                                      : o.cloth.dynamics;
      require(c.damping * c.time_step <= 1, "--mu", c.damping,
              "mu dt = " + format_number(c.damping * c.time_step) + " for the " +
                  std::string(stage_name(checked)) + " stage (dt = " + format_number(c.time_step) +
                  ") must be at most 1 (the damping factor 1 - mu dt would be negative)");
    }
    require_finite("--mass", d.mass);
    require(d.mass > 0, "--mass", d.mass, "must be positive");
    require_finite("--gravity", d.gravity);
    require(d.gravity >= 0, "--gravity", d.gravity, "is a magnitude along -z: at least 0");
    require_finite("--K", o.spring.stiffness);
    require(o.spring.stiffness >= 0, "--K", o.spring.stiffness, "must be at least 0");
    const std::pair<const char*, double> cloth_stiffnesses[] = {
        {"--K-struct", cloth.structural_stiffness},
        {"--K-shear", cloth.shear_stiffness},
        {"--K-bend", cloth.bending_stiffness}};
    for (const auto& [name, value] : cloth_stiffnesses) {
      require_finite(name, value);
      require(value >= 0, name, value, "must be at least 0");
    }
    require(o.coupled.mass_count >= 1 && o.coupled.mass_count <= max_chain, "--chain",
            o.coupled.mass_count, "must be between 1 and " + std::to_string(max_chain));
    require(cloth.grid_size >= 2 && cloth.grid_size <= max_grid_size, "--N", cloth.grid_size,
            "must be between 2 and " + std::to_string(max_grid_size));
    require_finite("--size", cloth.side_length);
    require(cloth.side_length > 0, "--size", cloth.side_length, "must be positive");
    require_finite("--wind-strength", cloth.wind_strength);
    if (cloth.wind_direction == glm::dvec3(0.0)) {
      throw usage_error{"--wind-dir " + wind_dir + ": the wind direction must not be zero"};
    }
    require_finite("--ground-friction", cloth.ground_friction);
    require(cloth.ground_friction >= 0, "--ground-friction", cloth.ground_friction,
            "must be at least 0");
    require(cloth.ground_friction * cloth.dynamics.time_step <= 1, "--ground-friction",
            cloth.ground_friction,
            "mu_g dt = " + format_number(cloth.ground_friction * cloth.dynamics.time_step) +
                " must be at most 1");
    require(o.steps >= 0, "--steps", double(o.steps), "must be at least 0");
    require(o.csv_every >= 1, "--csv-every", double(o.csv_every), "must be at least 1");
    require(o.width >= 1 && o.width <= max_image_side, "--width", o.width,
            "must be between 1 and " + std::to_string(max_image_side));
    require(o.height >= 1 && o.height <= max_image_side, "--height", o.height,
            "must be between 1 and " + std::to_string(max_image_side));

    require(cloth.reference_grid_size >= 2 && cloth.reference_grid_size <= max_grid_size,
            "--reference-N", cloth.reference_grid_size,
            "must be between 2 and " + std::to_string(max_grid_size));
    for (double x : o.sweep_time_steps)
      require(x > 0, "--sweep-dt", x, "must be positive");
    for (double x : o.sweep_stiffnesses)
      require(x >= 0, "--sweep-K", x, "must be at least 0");
    require_finite("--sweep-time", o.sweep_time);
    require(o.sweep_time > 0 && o.sweep_time <= 1000, "--sweep-time", o.sweep_time,
            "must be positive and at most 1000 s");

    // Combinations.
    if (o.backend == backend_kind::gpu && o.stage != stage_kind::cloth) {
      throw usage_error{
          "--backend gpu: the GPU path simulates the cloth; use it with --stage cloth"};
    }
    if (o.backend == backend_kind::gpu &&
        o.cloth.dynamics.integrator != integrator_kind::semi_implicit &&
        o.cloth.dynamics.integrator != integrator_kind::explicit_euler) {
      throw usage_error{"--integrator " + integrator +
                        ": the GPU path runs semi-implicit or explicit only; use --backend cpu"};
    }
    if (!o.sweep_path.empty()) {
      if (!o.sweep_stiffnesses.empty() && !o.sweep_grid_sizes.empty()) {
        throw usage_error{"--sweep-N " + sweep_n + ": sweep either K (--sweep-K) or N, not both"};
      }
      if (!o.sweep_grid_sizes.empty() && o.stage == stage_kind::spring) {
        throw usage_error{"--sweep-N " + sweep_n +
                          ": the single spring has no size; use --stage coupled or cloth"};
      }
      if (o.backend == backend_kind::gpu) {
        throw usage_error{"--sweep: the stability map runs on the CPU; drop --backend gpu"};
      }
      for (const auto* option : {"--csv", "--obj", "--png", "--energy-csv"}) {
        if (app.count(option) > 0) {
          throw usage_error{std::string(option) + ": not with --sweep (a sweep runs many cells)"};
        }
      }
    } else {
      for (const auto* option : {"--sweep-dt", "--sweep-K", "--sweep-N", "--sweep-time"}) {
        if (app.count(option) > 0)
          throw usage_error{std::string(option) + ": only with --sweep"};
      }
    }
    if (!o.obj_path.empty() && o.stage != stage_kind::cloth) {
      throw usage_error{"--obj " + o.obj_path +
                        ": the OBJ is the cloth's; use it with --stage cloth"};
    }
    if (!o.headless) {
      for (const auto* option :
           {"--csv", "--csv-every", "--obj", "--png", "--steps", "--energy-csv", "--sweep"}) {
        if (app.count(option) > 0) {
          throw usage_error{std::string(option) + ": only with --headless (the window runs live)"};
        }
      }
    }
  } catch (const usage_error& e) {
    std::fprintf(stderr, "clothlab: %s\n", e.message.c_str());
    return {std::nullopt, 2};
  }
  return {o, 0};
}

}  // namespace clothlab
