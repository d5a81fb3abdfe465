#include "app/options.hpp"

#include "core/contacts.hpp"

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "core/cloth_parallel.hpp"

namespace clothlab {
namespace {

constexpr int max_grid_size = 1024;  // 1M particles: well within memory, far beyond interactivity
constexpr int max_chain = 1000;
constexpr int max_image_side = 8192;

// The bounds of every number (docs/limits.md). Past them some double overflows (t = s dt, the
// energy m v^2 / 2, a force K dx, an area S^2 / N^2 that underflows) or the run would not end
// in any reasonable time. A stable run inside them writes only finite numbers.
struct bounds {
  double low, high;
  const char* unit;
};
constexpr bounds time_step_bounds{1e-9, 10.0, "s"};
constexpr bounds stiffness_bounds{0.0, 1e9, "N/m"};
constexpr bounds mass_bounds{1e-6, 1e6, "kg"};
constexpr bounds gravity_bounds{0.0, 1e3, "m/s^2"};
constexpr bounds size_bounds{1e-3, 1e3, "m"};
constexpr bounds wind_strength_bounds{-1e6, 1e6, "N"};
constexpr bounds wind_component_bounds{-1e6, 1e6, ""};
constexpr double min_wind_direction_length = 1e-6;  // normalised before use
constexpr bounds ground_height_bounds{-1e3, 1e3, "m"};
constexpr long max_steps = 1'000'000'000;                 // with dt <= 1 s: t <= 1e9 s
constexpr bounds grid_list_bounds{1, max_grid_size, ""};  // --sweep-N, whole numbers
constexpr int max_list_values = 200;
constexpr bounds position_bounds{-1e3, 1e3, "m"};  // --drag target, --sphere centre
constexpr bounds tear_strain_bounds{1e-6, 100.0, ""};
constexpr int max_threads = 256;

// A usage error: the option and what is wrong with its value.
struct usage_error {
  std::string message;
};

std::string format_number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

void require(bool ok, const std::string& option, double value, const std::string& what) {
  if (!ok)
    throw usage_error{option + " " + format_number(value) + ": " + what};
}

void require_finite(const std::string& option, double value) {
  require(std::isfinite(value), option, value, "must be a finite number");
}

// low <= value <= high, named with the bounds: "--dt 1e-320: must be between 1e-09 and 1 s".
void require_within(const std::string& option, double value, const bounds& b) {
  require_finite(option, value);
  require(value >= b.low && value <= b.high, option, value,
          "must be between " + format_number(b.low) + " and " + format_number(b.high) +
              (*b.unit != '\0' ? std::string(" ") + b.unit : std::string()));
}

// One number, the same way for every option: the whole text must be a number (strtod's
// syntax). A value too large for a double is not a finite number; one too small to be a
// normal double (1e-320) is read as it is, and the option's range then decides.
std::optional<double> parse_number(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())))
    return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size())
    return std::nullopt;
  if (errno == ERANGE && std::abs(x) == HUGE_VAL)
    return std::numeric_limits<double>::infinity();  // overflow: refused as not finite
  return x;
}

double number_or_usage_error(const std::string& option, const std::string& text,
                             const std::string& expected) {
  const std::optional<double> x = parse_number(text);
  if (!x)
    throw usage_error{option + " " + text + ": " + expected};
  return *x;
}

// "X,Y,Z" -> three finite numbers.
glm::dvec3 parse_vector(const std::string& option, const std::string& text) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const std::optional<double> x = parse_number(item);
    if (!x || !std::isfinite(*x)) {
      throw usage_error{option + " " + text + ": expected three finite numbers X,Y,Z"};
    }
    values.push_back(*x);
  }
  if (values.size() != 3 || (!text.empty() && text.back() == ',')) {
    throw usage_error{option + " " + text + ": expected three numbers X,Y,Z"};
  }
  return {values[0], values[1], values[2]};
}

// "A,B,C" (the values) or "FROM:TO:COUNT" (COUNT values spaced evenly on a log scale, both ends
// included), every one of them within `range` (checked before the values are computed, so that
// a range like 1e-300:1e300 cannot overflow on the way).
std::vector<double> parse_list(const std::string& option, const std::string& text,
                               const bounds& range) {
  auto number = [&](const std::string& item) {
    const std::optional<double> x = parse_number(item);
    if (!x || !std::isfinite(*x)) {
      throw usage_error{option + " " + text + ": '" + item + "' is not a finite number"};
    }
    return *x;
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
    if (!(from > 0 && to > 0) || count != std::floor(count) || count < 2 ||
        count > max_list_values) {
      throw usage_error{option + " " + text +
                        ": FROM and TO must be positive and COUNT a whole number from 2 to " +
                        std::to_string(max_list_values)};
    }
    require_within(option, from, range);
    require_within(option, to, range);
    // x_i = from (to / from)^(i / (count - 1)); through logarithms when to / from is not a
    // finite positive double (1e-320:1 would make it infinite, 1:1e-320 zero).
    const double ratio = to / from;
    const bool ratio_finite = std::isfinite(ratio) && ratio > 0;
    for (int i = 0; i < int(count); ++i) {
      const double fraction = i / (count - 1);
      values.push_back(ratio_finite
                           ? from * std::pow(ratio, fraction)
                           : std::exp(std::log(from) + fraction * (std::log(to) - std::log(from))));
    }
    values.front() = from;  // exactly, not within rounding of the bounds
    values.back() = to;
  } else {
    for (const std::string& item : items)
      values.push_back(number(item));
    for (double x : values)
      require_within(option, x, range);
    if (values.size() > max_list_values)
      throw usage_error{option + " " + text + ": at most " + std::to_string(max_list_values) +
                        " values"};
  }
  return values;
}

}  // namespace

std::string one_line(std::string_view text) {
  std::string line;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n') {
      line += "\\n";
    } else if (c == '\t') {
      line += "\\t";
    } else if (c == '\r') {
      line += "\\r";
    } else if (byte < 0x20 || byte == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      line += escaped;
    } else {
      line += c;
    }
  }
  return line;
}

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
  std::string scaling, sweep_dt, sweep_k, sweep_n, gl = "auto", drag, sphere;
  double sphere_friction = o.cloth.sphere.friction, drag_stiffness = o.cloth.drag.stiffness;
  double tear_strain = 0.0, self_collision = 0.0;
  const std::map<std::string, stage_kind> stages = {{"spring", stage_kind::spring},
                                                    {"coupled", stage_kind::coupled},
                                                    {"cloth", stage_kind::cloth}};
  const std::map<std::string, cloth_backend> backends = {
      {"cpu", cloth_backend::cpu},
      {"cpu-parallel", cloth_backend::cpu_parallel},
      {"gpu", cloth_backend::gpu},
      {"gpu-compute", cloth_backend::gpu_compute}};
  const std::map<std::string, gl_choice> gl_choices = {
      {"auto", gl_choice::automatic}, {"egl", gl_choice::egl}, {"osmesa", gl_choice::osmesa}};
  std::vector<std::string> integrators;
  for (integrator_kind kind : all_integrators)
    integrators.emplace_back(integrator_name(kind));
  const std::vector<std::string> scalings = {
      std::string(resolution_scaling_name(resolution_scaling::per_particle)),
      std::string(resolution_scaling_name(resolution_scaling::resolution_independent))};
  const std::map<std::string, pin_mode> pins = {{"corners", pin_mode::corners},
                                                {"none", pin_mode::none}};

  cloth_parameters& cloth = o.cloth;
  // Every number is read as text and converted by parse_number after CLI11 is done, so that
  // "1e-320", "inf" and "1e999" mean the same whatever the option (docs/limits.md).
  std::map<std::string, std::pair<std::string, double*>> numbers;  // option -> (text, target)
  // show_default: the target holds the default (a parameter struct's field), shown by --help.
  auto add_number = [&](const std::string& name, double& target, const std::string& help,
                        bool show_default = true) {
    numbers[name].second = &target;
    CLI::Option* option = app.add_option(name, numbers[name].first, help);
    if (show_default)
      option->default_str(format_number(target));
    return option;
  };
  // Whole numbers are read in decimal, as a user types them: CLI11 alone would read "010" as
  // octal (8) and "0x10" as hexadecimal (16). Leading zeros are dropped; a base prefix is refused.
  const CLI::Validator decimal(
      [](std::string& text) {
        const std::size_t sign = !text.empty() && (text[0] == '+' || text[0] == '-') ? 1 : 0;
        if (text.size() == sign)
          return std::string();  // nothing to read: the conversion says so
        const std::size_t first = text.find_first_not_of('0', sign);
        if (first != std::string::npos && first > sign && std::isalpha(text[first]))
          return "INTEGER " + text + ": must be written in decimal digits";
        if (text.find_first_not_of("0123456789", sign) != std::string::npos)
          return std::string();  // not a whole number: the conversion says so
        if (first == std::string::npos)
          text = "0";
        else
          text = text.substr(0, sign) + text.substr(first);
        return std::string();
      },
      "");
  app.add_flag("--headless", o.headless, "Run without a window");
  app.add_option("--frames", o.frames, "Window: run COUNT frames, print the mean frame time, exit")
      ->check(CLI::Validator(
          [](std::string& text) {
            // A count of frames: a whole number of at least 1 (CLI::PositiveNumber's message
            // printed the largest double in 309 digits).
            long count = 0;
            const bool whole = CLI::detail::lexical_cast(text, count);
            return whole && count >= 1 ? std::string()
                                       : "COUNT " + text + ": must be a whole number of at least 1";
          },
          "COUNT >= 1"))
      ->transform(decimal);
  app.add_option("--stage", stage, "spring | coupled | cloth (default cloth)")
      ->check(CLI::IsMember(stages));
  // BEGIN TEACHER
  app.add_option("--backend", backend,
                 "cpu (default, the lab's code) | cpu-parallel | gpu (fragment shaders) | "
                 "gpu-compute: the cloth's simulation path")
      ->check(CLI::IsMember(backends));
  app.add_option("--threads", o.threads, "cpu-parallel: threads (default: all cores)")
      ->transform(decimal);
  // END TEACHER
  // COPY| app.add_option("--backend", backend,
  // COPY|                "cpu (default, the lab's code) | gpu (fragment shaders): the cloth's path")
  // COPY|     ->check(CLI::IsMember(backends));
  // COPY| app.add_option("--threads", o.threads)->group("");  // the teacher's parallel path's
  app.add_option("--gl", gl,
                 "auto (default: EGL on a hardware GPU, else OSMesa) | egl | osmesa: the "
                 "off-screen OpenGL of --backend gpu* and --png")
      ->check(CLI::IsMember(gl_choices))
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.add_option(
         "--integrator", integrator,
         "semi-implicit (default) | explicit | verlet | rk4 | implicit (GPU: the first two)")
      ->check(CLI::IsMember(integrators));
  app.add_option("--steps", o.steps, "Steps to run, headless (default 1000)")->transform(decimal);
  auto* dt_option = add_number("--dt", dt, "Step length, s (spring 0.01, cloth 0.002)", false);
  auto* k_option = add_number("--K", stiffness, "Stiffness of the spring stages, N/m (20)", false);
  add_number("--K-struct", cloth.structural_stiffness, "Cloth structural stiffness, N/m");
  add_number("--K-shear", cloth.shear_stiffness, "Cloth shear stiffness, N/m");
  add_number("--K-bend", cloth.bending_stiffness, "Cloth bending stiffness, N/m");
  auto* mu_option =
      add_number("--mu", damping, "Damping rate mu, 1/s (spring 0.2, cloth 0.5)", false);
  auto* mass_option = add_number("--mass", mass, "Mass of each moving particle, kg (1)", false);
  auto* gravity_option =
      add_number("--gravity", gravity, "Gravity g0 along -z, m/s^2 (9.8)", false);
  std::string start;
  app.add_option("--start", start,
                 "Single spring: 3d (default, v1 = (1,-1,0)) | 1d (v1 along the spring)")
      ->check(CLI::IsMember({"3d", "1d"}));
  app.add_option("--chain", o.coupled.mass_count, "Moving masses of the coupled stage")
      ->capture_default_str()
      ->transform(decimal);
  app.add_option("--N", cloth.grid_size, "Cloth grid size: N x N particles")
      ->capture_default_str()
      ->transform(decimal);
  add_number("--size", cloth.side_length, "Cloth side length, m");
  app.add_option("--pins", pin_choice, "corners (default) | none")->check(CLI::IsMember(pins));
  add_number("--wind-strength", cloth.wind_strength, "Wind strength K_w, N");
  auto* wind_dir_option = app.add_option("--wind-dir", wind_dir, "Wind direction X,Y,Z (0,1,0)");
  auto* ground_option = app.add_option("--ground-z", ground_z, "Ground height, m, or none (-1)");
  add_number("--ground-friction", cloth.ground_friction, "Ground friction rate mu_g, 1/s");
  app.add_option("--csv", o.csv_path, "Write the particles' states to this CSV file");
  app.add_option("--csv-every", o.csv_every, "Write every K-th step (default 1)")
      ->transform(decimal);
  app.add_option("--obj", o.obj_path, "Write the final cloth as a Wavefront OBJ");
  app.add_option("--png", o.png_path, "Render the final state off-screen to this PNG");
  app.add_option("--width", o.width, "PNG width, px (800)")->transform(decimal);
  app.add_option("--height", o.height, "PNG height, px (600)")->transform(decimal);
  app.add_option("--energy-csv", o.energy_csv_path,
                 "Write step,t,kinetic,gravity,spring,total (every --csv-every steps)");
  app.add_option("--scaling", scaling,
                 "per-particle (default, the handout's) | resolution-independent (question 10)")
      ->check(CLI::IsMember(scalings));
  app.add_option("--reference-N", cloth.reference_grid_size,
                 "Grid whose particles have --mass and springs the K (resolution-independent)")
      ->capture_default_str()
      ->transform(decimal);
  app.add_option(
      "--sweep", o.sweep_path,
      "Stability map: run every (dt, K or N) cell, write dt,K,N,integrator,diverged,step");
  app.add_option("--sweep-dt", sweep_dt, "Sweep dt values: A,B,C or FROM:TO:COUNT (log-spaced)");
  app.add_option("--sweep-K", sweep_k, "Sweep stiffnesses (cloth: K_struct, ratios kept)");
  app.add_option("--sweep-N", sweep_n, "Sweep grid sizes (cloth) or chain lengths (coupled)");
  add_number("--sweep-time", o.sweep_time, "Simulated seconds per sweep cell (2)", false);
  app.add_option("--drag", drag, "Pull particle (KU,KV) towards X,Y,Z: KU,KV:X,Y,Z (cloth)");
  add_number("--drag-stiffness", drag_stiffness,
             "Drag spring K_d, N/m (--drag, and the mouse on every stage)", false)
      ->default_str(format_number(cloth.drag.stiffness));
  app.add_option("--sphere", sphere, "A sphere to collide with: X,Y,Z,R (cloth)");
  add_number("--sphere-friction", sphere_friction, "Sphere friction rate mu_s, 1/s", false)
      ->default_str(format_number(cloth.sphere.friction));
  add_number("--tear-strain", tear_strain,
             "Tearing: a spring longer than (1 + E) L0 breaks (default: never)", false);
  add_number("--self-collision", self_collision, "Self-collision thickness D, m (default: none)",
             false);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    app.exit(e);
    return {std::nullopt, 0};
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "clothlab: %s (see --help)\n", one_line(e.what()).c_str());
    return {std::nullopt, 2};
  }

  try {
    // An empty value is never meant: CLI11 would read '' as 0 for a number and an empty path
    // means "no file" to the options below.
    for (const CLI::Option* option : app.get_options()) {
      if (option->count() == 0 || option->get_expected_min() == 0)
        continue;  // not given, or a flag
      for (const std::string& value : option->results()) {
        if (value.empty())
          throw usage_error{option->get_name() + " '': the value is empty"};
      }
    }
    for (auto& [name, entry] : numbers) {
      if (app.count(name) > 0)
        *entry.second = number_or_usage_error(name, entry.first, "expected a number");
    }
    o.stage = stages.at(stage);
    o.backend = backends.at(backend);
    o.gl = gl_choices.at(gl);
    cloth.drag.stiffness = drag_stiffness;
    cloth.sphere.friction = sphere_friction;
    cloth.tear_strain = tear_strain;
    cloth.self_collision_thickness = self_collision;
    if (!drag.empty()) {
      // KU,KV:X,Y,Z
      const std::size_t colon = drag.find(':');
      if (colon == std::string::npos)
        throw usage_error{"--drag " + drag + ": expected KU,KV:X,Y,Z"};
      const std::string grid = drag.substr(0, colon);
      const std::size_t comma = grid.find(',');
      const std::optional<double> ku = parse_number(grid.substr(0, comma));
      const std::optional<double> kv =
          comma == std::string::npos ? std::nullopt : parse_number(grid.substr(comma + 1));
      if (!ku || !kv || *ku != std::floor(*ku) || *kv != std::floor(*kv)) {
        throw usage_error{"--drag " + drag + ": KU,KV must be two whole numbers"};
      }
      if (*ku < 0 || *kv < 0 || *ku >= cloth.grid_size || *kv >= cloth.grid_size) {
        throw usage_error{"--drag " + drag + ": particle (" + grid + ") is outside the " +
                          std::to_string(cloth.grid_size) + " x " +
                          std::to_string(cloth.grid_size) + " grid"};
      }
      cloth.drag.enabled = true;
      cloth.drag.ku = static_cast<int>(*ku);
      cloth.drag.kv = static_cast<int>(*kv);
      cloth.drag.target = parse_vector("--drag", drag.substr(colon + 1));
      for (int i = 0; i < 3; ++i)
        require_within("--drag", cloth.drag.target[i], position_bounds);
    }
    if (!sphere.empty()) {
      const std::size_t last = sphere.rfind(',');
      if (last == std::string::npos)
        throw usage_error{"--sphere " + sphere + ": expected X,Y,Z,R"};
      cloth.sphere.enabled = true;
      cloth.sphere.centre = parse_vector("--sphere", sphere.substr(0, last));
      cloth.sphere.radius =
          number_or_usage_error("--sphere", sphere.substr(last + 1), "expected X,Y,Z,R");
      for (int i = 0; i < 3; ++i)
        require_within("--sphere", cloth.sphere.centre[i], position_bounds);
      require_within("--sphere", cloth.sphere.radius, size_bounds);
    }
    if (!pin_choice.empty())
      cloth.pins = pins.at(pin_choice);
    // One rule for every option: it sets the chosen stage (--stage, default cloth) and no other
    // (the window's other stages keep their defaults), and an option that the chosen stage has
    // no use for is refused, naming the stage it belongs to.
    const std::string chosen(stage_name(o.stage));
    const auto refuse_unless = [&](bool fits, const char* const* names, std::size_t count,
                                   const std::string& whose) {
      for (std::size_t i = 0; i < count && !fits; ++i) {
        if (app.count(names[i]) > 0) {
          throw usage_error{std::string(names[i]) + ": " + whose + " the " + chosen +
                            " stage has no use for it"};
        }
      }
    };
    const char* cloth_options[] = {
        "--N",       "--size",          "--pins",     "--K-struct", "--K-shear",
        "--K-bend",  "--wind-strength", "--wind-dir", "--ground-z", "--ground-friction",
        "--scaling", "--reference-N"};
    refuse_unless(o.stage == stage_kind::cloth, cloth_options, std::size(cloth_options),
                  "the cloth's option (--stage cloth);");
    const char* spring_options[] = {"--K"};
    refuse_unless(o.stage != stage_kind::cloth, spring_options, std::size(spring_options),
                  "the spring stages' stiffness (the cloth's: --K-struct, --K-shear, --K-bend);");
    const char* single_spring_options[] = {"--start"};
    refuse_unless(o.stage == stage_kind::spring, single_spring_options,
                  std::size(single_spring_options), "the single spring's option (--stage spring);");
    o.spring_1d_start = start == "1d";
    const char* chain_options[] = {"--chain"};
    refuse_unless(o.stage == stage_kind::coupled, chain_options, std::size(chain_options),
                  "the chain's option (--stage coupled);");
    dynamics_parameters* chosen_dynamics = o.stage == stage_kind::spring    ? &o.spring.dynamics
                                           : o.stage == stage_kind::coupled ? &o.coupled.dynamics
                                                                            : &o.cloth.dynamics;
    for (dynamics_parameters* d : {chosen_dynamics}) {
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
      o.sweep_time_steps = parse_list("--sweep-dt", sweep_dt, time_step_bounds);
    if (!sweep_k.empty())
      o.sweep_stiffnesses = parse_list("--sweep-K", sweep_k, stiffness_bounds);
    if (!sweep_n.empty()) {
      for (double n : parse_list("--sweep-N", sweep_n, grid_list_bounds)) {
        // The chain's n from 1, the cloth's N from 2 (a grid of one particle has no spring).
        const int smallest = o.stage == stage_kind::cloth ? 2 : 1;
        require(n == std::floor(n) && n >= smallest && n <= max_grid_size, "--sweep-N", n,
                "must be whole numbers between " + std::to_string(smallest) + " and " +
                    std::to_string(max_grid_size) + " for the " + chosen + " stage");
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
        cloth.ground_enabled = true;
        cloth.ground_height =
            number_or_usage_error("--ground-z", ground_z, "expected a number or none");
      }
    }

    // Ranges. Each message names the option and its value.
    const dynamics_parameters& d = o.stage == stage_kind::spring    ? o.spring.dynamics
                                   : o.stage == stage_kind::coupled ? o.coupled.dynamics
                                                                    : o.cloth.dynamics;
    // Every bound is in docs/limits.md.
    require_within("--dt", d.time_step, time_step_bounds);
    require_finite("--mu", d.damping);
    require(d.damping >= 0, "--mu", d.damping, "must be at least 0");
    // (1 - mu dt) must not be negative, for the two Euler schemes that multiply the velocity by
    // it (the others apply the damping as a force).
    if (d.integrator == integrator_kind::semi_implicit ||
        d.integrator == integrator_kind::explicit_euler) {
      require(d.damping * d.time_step <= 1, "--mu", d.damping,
              "mu dt = " + format_number(d.damping * d.time_step) + " for the " + chosen +
                  " stage (dt = " + format_number(d.time_step) +
                  ") must be at most 1 (the damping factor 1 - mu dt would be negative)");
    }
    require_within("--mass", d.mass, mass_bounds);
    require_finite("--gravity", d.gravity);
    require(d.gravity >= 0, "--gravity", d.gravity, "is a magnitude along -z: at least 0");
    require_within("--gravity", d.gravity, gravity_bounds);
    require_within("--K", o.spring.stiffness, stiffness_bounds);
    const std::pair<const char*, double> cloth_stiffnesses[] = {
        {"--K-struct", cloth.structural_stiffness},
        {"--K-shear", cloth.shear_stiffness},
        {"--K-bend", cloth.bending_stiffness}};
    for (const auto& [name, value] : cloth_stiffnesses)
      require_within(name, value, stiffness_bounds);
    require(o.coupled.mass_count >= 1 && o.coupled.mass_count <= max_chain, "--chain",
            o.coupled.mass_count, "must be between 1 and " + std::to_string(max_chain));
    require(cloth.grid_size >= 2 && cloth.grid_size <= max_grid_size, "--N", cloth.grid_size,
            "must be between 2 and " + std::to_string(max_grid_size));
    require_within("--size", cloth.side_length, size_bounds);
    require_within("--wind-strength", cloth.wind_strength, wind_strength_bounds);
    if (cloth.wind_direction == glm::dvec3(0.0)) {
      throw usage_error{"--wind-dir " + wind_dir + ": the wind direction must not be zero"};
    }
    for (int i = 0; i < 3; ++i) {
      const double c = cloth.wind_direction[i];
      if (!(c >= wind_component_bounds.low && c <= wind_component_bounds.high)) {
        throw usage_error{"--wind-dir " + wind_dir + ": each component must be between " +
                          format_number(wind_component_bounds.low) + " and " +
                          format_number(wind_component_bounds.high)};
      }
    }
    // |u| is computed before normalising: its square must not underflow.
    const double wind_length = std::sqrt(glm::dot(cloth.wind_direction, cloth.wind_direction));
    if (!(wind_length >= min_wind_direction_length)) {
      throw usage_error{"--wind-dir " + wind_dir + ": the direction's length " +
                        format_number(wind_length) + " must be at least " +
                        format_number(min_wind_direction_length)};
    }
    if (cloth.ground_enabled)
      require_within("--ground-z", cloth.ground_height, ground_height_bounds);
    require_finite("--ground-friction", cloth.ground_friction);
    require(cloth.ground_friction >= 0, "--ground-friction", cloth.ground_friction,
            "must be at least 0");
    require(o.stage != stage_kind::cloth || cloth.ground_friction * cloth.dynamics.time_step <= 1,
            "--ground-friction", cloth.ground_friction,
            "mu_g dt = " + format_number(cloth.ground_friction * cloth.dynamics.time_step) +
                " must be at most 1");
    require_within("--drag-stiffness", cloth.drag.stiffness, stiffness_bounds);
    o.spring.drag.stiffness = o.coupled.drag.stiffness = cloth.drag.stiffness;  // the mouse's
    require_finite("--sphere-friction", cloth.sphere.friction);
    require(cloth.sphere.friction >= 0, "--sphere-friction", cloth.sphere.friction,
            "must be at least 0");
    require(o.stage != stage_kind::cloth || cloth.sphere.friction * cloth.dynamics.time_step <= 1,
            "--sphere-friction", cloth.sphere.friction,
            "mu_s dt = " + format_number(cloth.sphere.friction * cloth.dynamics.time_step) +
                " must be at most 1");
    if (app.count("--tear-strain") > 0)
      require_within("--tear-strain", cloth.tear_strain, tear_strain_bounds);
    if (app.count("--self-collision") > 0)
      require_within("--self-collision", cloth.self_collision_thickness, size_bounds);
    require(o.threads >= 0 && o.threads <= max_threads, "--threads", o.threads,
            "must be between 1 and " + std::to_string(max_threads) + " (0: all cores)");
    require(o.steps >= 0 && o.steps <= max_steps, "--steps", double(o.steps),
            "must be between 0 and " + format_number(double(max_steps)));
    require(o.csv_every >= 1, "--csv-every", double(o.csv_every), "must be at least 1");
    require(o.width >= 1 && o.width <= max_image_side, "--width", o.width,
            "must be between 1 and " + std::to_string(max_image_side));
    require(o.height >= 1 && o.height <= max_image_side, "--height", o.height,
            "must be between 1 and " + std::to_string(max_image_side));

    require(cloth.reference_grid_size >= 2 && cloth.reference_grid_size <= max_grid_size,
            "--reference-N", cloth.reference_grid_size,
            "must be between 2 and " + std::to_string(max_grid_size));
    // Every value of a sweep list within the single option's bounds, not only its ends.
    for (double x : o.sweep_time_steps)
      require_within("--sweep-dt", x, time_step_bounds);
    for (double x : o.sweep_stiffnesses)
      require_within("--sweep-K", x, stiffness_bounds);
    require_finite("--sweep-time", o.sweep_time);
    require(o.sweep_time > 0 && o.sweep_time <= 1000, "--sweep-time", o.sweep_time,
            "must be positive and at most 1000 s");

    // Combinations.
    if (o.backend != cloth_backend::cpu && o.stage != stage_kind::cloth) {
      throw usage_error{"--backend " + backend +
                        ": this path simulates the cloth; use it with "
                        "--stage cloth"};
    }
    if (o.backend != cloth_backend::cpu &&
        o.cloth.dynamics.integrator != integrator_kind::semi_implicit &&
        o.cloth.dynamics.integrator != integrator_kind::explicit_euler) {
      throw usage_error{"--integrator " + integrator + ": the " + backend +
                        " path runs semi-implicit or explicit only; use --backend cpu"};
    }
    if (o.backend != cloth_backend::cpu && o.backend != cloth_backend::cpu_parallel) {
      for (const auto* option : {"--tear-strain", "--self-collision"}) {
        const bool gpu_tears =
            std::string_view(option) == "--tear-strain" &&
            (o.backend == cloth_backend::gpu || o.backend == cloth_backend::gpu_compute);
        if (app.count(option) > 0 && !gpu_tears) {
          throw usage_error{std::string(option) +
                            ": only the cpu and cpu-parallel paths have it, not --backend " +
                            backend};
        }
      }
    }
    if (app.count("--threads") > 0 && o.backend != cloth_backend::cpu_parallel)
      throw usage_error{"--threads: only with --backend cpu-parallel"};
    if (o.stage != stage_kind::cloth) {
      for (const auto* option :
           {"--drag", "--sphere", "--sphere-friction", "--tear-strain", "--self-collision"}) {
        if (app.count(option) > 0)
          throw usage_error{std::string(option) + ": the cloth's; use it with --stage cloth"};
      }
    }
    if (cloth.drag.enabled && cloth.pins == pin_mode::corners && cloth.drag.kv == 0 &&
        (cloth.drag.ku == 0 || cloth.drag.ku == cloth.grid_size - 1)) {
      throw usage_error{"--drag " + drag + ": particle (" + std::to_string(cloth.drag.ku) +
                        ",0) is pinned (--pins corners): a pinned particle cannot be dragged"};
    }
    if (!o.sweep_path.empty()) {
      if (!o.sweep_stiffnesses.empty() && !o.sweep_grid_sizes.empty()) {
        throw usage_error{"--sweep-N " + sweep_n + ": sweep either K (--sweep-K) or N, not both"};
      }
      if (!o.sweep_grid_sizes.empty() && o.stage == stage_kind::spring) {
        throw usage_error{"--sweep-N " + sweep_n +
                          ": the single spring has no size; use --stage coupled or cloth"};
      }
      if (o.backend != cloth_backend::cpu) {
        throw usage_error{"--sweep: the stability map runs on the cpu path; drop --backend " +
                          backend};
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
    if (o.backend == cloth_backend::cpu_parallel && !cloth_parallel::available())
      throw usage_error{"--backend " + backend + ": " + cloth_parallel::unavailable_reason()};
    if (!o.headless && o.backend == cloth_backend::cpu_parallel) {
      throw usage_error{"--backend " + backend +
                        ": headless only; the window runs the cpu, gpu and gpu-compute paths "
                        "(key G)"};
    }
    if (!o.headless && app.count("--gl") > 0)
      throw usage_error{"--gl: only with --headless (the window has its own context)"};
    if (!o.headless) {
      for (const auto* option :
           {"--csv", "--csv-every", "--obj", "--png", "--steps", "--energy-csv", "--sweep"}) {
        if (app.count(option) > 0) {
          throw usage_error{std::string(option) + ": only with --headless (the window runs live)"};
        }
      }
    }
  } catch (const usage_error& e) {
    std::fprintf(stderr, "clothlab: %s\n", one_line(e.message).c_str());
    return {std::nullopt, 2};
  }
  // Self-collision runs with d no larger than the shortest rest length h (docs/model.md): a
  // larger D is accepted, clamped, and said so once by a headless run (the window's command
  // line is parsed twice, by clothlab and by clothlab-window).
  if (o.headless && o.cloth.self_collision_thickness > self_collision_distance(o.cloth)) {
    std::fprintf(stderr,
                 "clothlab: warning: --self-collision %g: clamped to the shortest rest length "
                 "h = %g m (--size / (N - 1))\n",
                 o.cloth.self_collision_thickness, self_collision_distance(o.cloth));
  }
  return {o, 0};
}

}  // namespace clothlab
