// The command line of docs/cli.md, read with CLI11. The lab's parameters come from the
// parameter table (core/parameter_table.hpp): their options, help, ranges and the stage fields
// they set are read off it in loops; this file adds the options of a run (what to run, the
// outputs, the sweep) and the checks that combine several options.
#include "app/command_line.hpp"

#include <CLI/CLI.hpp>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <regex>
#include <vector>

#include "app/option_checks.hpp"
#include "app/option_values.hpp"
#include "core/contacts.hpp"
#include "core/i18n.hpp"
#include "core/parameter_table.hpp"

namespace clothlab {
namespace {

// The bounds of the values that are not in the parameter table (docs/limits.md).
constexpr bounds position_bounds{-1e3, 1e3, "m"};  // --drag target, --sphere centre

const std::map<std::string, stage_kind> stages = {
    {"spring", stage_kind::spring}, {"coupled", stage_kind::coupled}, {"cloth", stage_kind::cloth}};
const std::map<std::string, cloth_backend> backends = {
    {"cpu", cloth_backend::cpu},
    {"cpu-parallel", cloth_backend::cpu_parallel},
    {"gpu", cloth_backend::gpu},
    {"gpu-compute", cloth_backend::gpu_compute}};
const std::map<std::string, gl_choice> gl_choices = {
    {"auto", gl_choice::automatic}, {"egl", gl_choice::egl}, {"osmesa", gl_choice::osmesa}};
const std::map<std::string, pin_mode> pins = {{"corners", pin_mode::corners},
                                              {"none", pin_mode::none}};
// The cloth's options that are not in the parameter table (the table's say their stage).
constexpr const char* other_cloth_options[] = {"--pins", "--wind-dir", "--ground-z", "--scaling"};

// Whole numbers are read in decimal, as a user types them: CLI11 alone would read "010" as
// octal (8) and "0x10" as hexadecimal (16). Leading zeros are dropped; a base prefix is refused.
// (The validators are made with the options, in the language chosen by then.)
CLI::Validator decimal() {
  return CLI::Validator(
      [](std::string& text) {
        const std::size_t sign = !text.empty() && (text[0] == '+' || text[0] == '-') ? 1 : 0;
        if (text.size() == sign)
          return std::string();  // nothing to read: the conversion says so
        const std::size_t first = text.find_first_not_of('0', sign);
        if (first != std::string::npos && first > sign && std::isalpha(text[first]))
          return format(tr("INTEGER %s: must be written in decimal digits"), text.c_str());
        if (text.find_first_not_of("0123456789", sign) != std::string::npos)
          return std::string();  // not a whole number: the conversion says so
        if (first == std::string::npos)
          text = "0";
        else
          text = text.substr(0, sign) + text.substr(first);
        return std::string();
      },
      "");
}

// A count of frames: a whole number of at least 1 (CLI::PositiveNumber's message printed the
// largest double in 309 digits).
CLI::Validator frame_count() {
  return CLI::Validator(
      [](std::string& text) {
        long count = 0;
        const bool whole = CLI::detail::lexical_cast(text, count);
        return whole && count >= 1
                   ? std::string()
                   : format(tr("COUNT %s: must be a whole number of at least 1"), text.c_str());
      },
      tr("COUNT >= 1"));
}

// --help's own words in the user's language: CLI11's labels ("Usage", "OPTIONS") and the kinds
// of value it names before a validator's ("TEXT:{cpu,gpu}", "INT").
class translated_formatter : public CLI::Formatter {
 public:
  translated_formatter() {
    // TRANSLATORS: CLI11's words in --help; it writes a colon right after "Usage" and after
    // "Options" (the group): end them with the space your language puts before a colon.
    for (const char* word : {N_("Usage"), N_("OPTIONS"), N_("REQUIRED"), N_("Positionals")})
      label(word, tr(word));
  }
  std::string make_option_opts(const CLI::Option* option) const override {
    std::string text = CLI::Formatter::make_option_opts(option);
    for (const char* kind : {N_("TEXT"), N_("INT"), N_("UINT"), N_("FLOAT")}) {
      const std::string english = std::string(" ") + kind;
      if (text.starts_with(english) &&
          (text.size() == english.size() || text[english.size()] == ':'))
        return " " + std::string(tr(kind)) + text.substr(english.size());
    }
    return text;
  }
};

// CLI11's own messages in the user's language: each kind it writes, recognised and said again
// from the catalogue; anything else as CLI11 wrote it.
std::string parse_error_message(const CLI::ParseError& error) {
  const std::string what = error.what();
  std::smatch m;
  if (std::regex_match(what, m,
                       std::regex("The following arguments? (?:was|were) not expected: (.*)"))) {
    const std::string arguments = m[1];
    const auto count =
        static_cast<unsigned long>(std::count(arguments.begin(), arguments.end(), ' ') + 1);
    return format(trn("The following argument was not expected: %s",
                      "The following arguments were not expected: %s", count),
                  arguments.c_str());
  }
  if (std::regex_match(what, m, std::regex(R"((\S+): (.*) not in (\{.*\}))")))
    return format(tr("%s: %s not in %s"), m.str(1).c_str(), m.str(2).c_str(), m.str(3).c_str());
  if (std::regex_match(what, m, std::regex(R"(Could not convert: (\S+) = (.*))")))
    return format(tr("Could not convert: %s = %s"), m.str(1).c_str(), m.str(2).c_str());
  if (std::regex_match(what, m, std::regex(R"((\S+): (\d+) required (\S+) missing)")))
    return format(tr("%s: %s required %s missing"), m.str(1).c_str(), m.str(2).c_str(),
                  tr(m.str(3).c_str()));
  if (std::regex_match(what, m, std::regex(R"((\S+): At Most (\d+) required but received (\d+))")))
    return format(tr("%s: At Most %s required but received %s"), m.str(1).c_str(), m.str(2).c_str(),
                  m.str(3).c_str());
  if (std::regex_match(what, m, std::regex(R"((--\S+): (.*))")))  // a validator's own message
    return m.str(1) + colon() + m.str(2);
  return what;
}

// --lang's help: the languages, "en | fr".
std::string language_help() {
  std::string codes;
  for (const language& l : languages())
    codes += (codes.empty() ? "" : " | ") + std::string(l.code);
  return format(tr("Language of the texts: %s (default: the locale's, from LANG)"), codes.c_str());
}

// --lang, read before anything is said, so that --help and every message are in its language.
// A language clothlab does not speak is refused, naming it and the languages there are.
bool choose_language(int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view argument = argv[i];
    std::optional<std::string_view> value;
    if (argument == "--lang" && i + 1 < argc)
      value = argv[i + 1];
    else if (argument.starts_with("--lang="))
      value = argument.substr(std::string_view("--lang=").size());
    if (value && !set_language(*value)) {
      std::fprintf(stderr, tr("clothlab: --lang %s: no such language (the languages: %s)\n"),
                   one_line(*value).c_str(), language_codes().c_str());
      return false;
    }
  }
  return true;
}

// The stage structs of the run, as the parameter table reads them.
stage_structs structs_of(options& o) {
  return {o.spring, o.coupled, o.cloth};
}

// The options, in the order of --help.
void add_options(CLI::App& app, options& o, given_values& given) {
  std::string& backend = given.backend;
  app.add_flag("--headless", o.headless, tr("Run without a window"));
  app.add_option("--frames", o.frames,
                 tr("Window: run COUNT frames, print the mean frame time, exit"))
      ->check(frame_count())
      ->transform(decimal());
  // (Read before the others, by parse_command_line: here for --help and to be accepted.)
  app.add_option("--lang", given.lang, language_help());
  app.add_option("--stage", given.stage, tr("spring | coupled | cloth (default cloth)"))
      ->check(CLI::IsMember(stages));
  // BEGIN TEACHER
  app.add_option("--backend", backend,
                 tr("cpu (default, the lab's code) | cpu-parallel | gpu (fragment shaders) | "
                    "gpu-compute: the cloth's simulation path"))
      ->check(CLI::IsMember(backends));
  app.add_option("--threads", o.threads, tr("cpu-parallel: threads (default: all cores)"))
      ->transform(decimal());
  // END TEACHER
  // COPY| app.add_option("--backend", backend,
  // COPY|                tr("cpu (default, the lab's code) | gpu (fragment shaders): the cloth's "
  // COPY|                   "path"))
  // COPY|     ->check(CLI::IsMember(backends));
  // COPY| app.add_option("--threads", o.threads)->group("");  // the teacher's parallel path's
  app.add_option("--gl", given.gl,
                 tr("auto (default: EGL on a hardware GPU, else OSMesa) | egl | osmesa: the "
                    "off-screen OpenGL of --backend gpu* and --png"))
      ->check(CLI::IsMember(gl_choices))
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  std::vector<std::string> integrators;
  for (integrator_kind kind : all_integrators)
    integrators.emplace_back(integrator_name(kind));
  app.add_option(
         "--integrator", given.integrator,
         tr("semi-implicit (default) | explicit | verlet | rk4 | implicit | xpbd (gpu: the first "
            "two; cpu-parallel and gpu-compute: these and xpbd)"))
      ->check(CLI::IsMember(integrators));
  app.add_option("--steps", o.steps, tr("Steps to run, headless (default 1000)"))
      ->transform(decimal());
  const stage_structs structs = structs_of(o);
  for (std::size_t i = 0; i < parameter_table.size(); ++i) {
    const parameter& p = parameter_table[i];
    const std::string name(p.option);
    if (field_of_any_stage(p, structs).whole != nullptr)
      app.add_option(name, given.whole_parameters[i], help_text(p))->transform(decimal());
    else
      app.add_option(name, given.real_parameters[i], help_text(p));
  }
  app.add_option("--start", given.start,
                 tr("Single spring: 3d (default, v1 = (1,-1,0)) | 1d (v1 along the spring)"))
      ->check(CLI::IsMember({"3d", "1d"}));
  app.add_option("--pins", given.pins, tr("corners (default) | none"))->check(CLI::IsMember(pins));
  app.add_option("--wind-dir", given.wind_dir, tr("Wind direction X,Y,Z (0,1,0)"));
  app.add_option("--ground-z", given.ground_z, tr("Ground height, m, or none (-1)"));
  app.add_option("--csv", o.csv_path, tr("Write the particles' states to this CSV file"));
  app.add_option("--csv-every", o.csv_every, tr("Write every K-th step (default 1)"))
      ->transform(decimal());
  app.add_option("--obj", o.obj_path, tr("Write the final cloth as a Wavefront OBJ"));
  app.add_option("--png", o.png_path, tr("Render the final state off-screen to this PNG"));
  app.add_option("--width", o.width, tr("PNG width, px (800)"))->transform(decimal());
  app.add_option("--height", o.height, tr("PNG height, px (600)"))->transform(decimal());
  app.add_option("--energy-csv", o.energy_csv_path,
                 tr("Write step,t,kinetic,gravity,spring,total (every --csv-every steps)"));
  const std::vector<std::string> scalings = {
      std::string(resolution_scaling_name(resolution_scaling::per_particle)),
      std::string(resolution_scaling_name(resolution_scaling::resolution_independent))};
  app.add_option("--scaling", given.scaling,
                 tr("per-particle (default, the handout's) | resolution-independent (question "
                    "10)"))
      ->check(CLI::IsMember(scalings));
  app.add_option(
      "--sweep", o.sweep_path,
      tr("Stability map: run every (dt, K or N) cell, write dt,K,N,integrator,diverged,step"));
  app.add_option("--sweep-dt", given.sweep_dt,
                 tr("Sweep dt values: A,B,C or FROM:TO:COUNT (log-spaced)"));
  app.add_option("--sweep-K", given.sweep_k,
                 tr("Sweep stiffnesses (cloth: K_struct, ratios kept)"));
  app.add_option("--sweep-N", given.sweep_n,
                 tr("Sweep grid sizes (cloth) or chain lengths (coupled)"));
  app.add_option("--sweep-time", given.sweep_time, tr("Simulated seconds per sweep cell (2)"));
  app.add_option("--drag", given.drag,
                 tr("Pull particle (KU,KV) towards X,Y,Z: KU,KV:X,Y,Z (cloth)"));
  app.add_option("--sphere", given.sphere, tr("A sphere to collide with: X,Y,Z,R (cloth)"));
}

// An empty value is never meant: CLI11 would read '' as 0 for a number and an empty path
// means "no file" to the options below.
void refuse_empty_values(const CLI::App& app) {
  for (const CLI::Option* option : app.get_options()) {
    if (option->count() == 0 || option->get_expected_min() == 0)
      continue;  // not given, or a flag
    for (const std::string& value : option->results()) {
      if (value.empty())
        throw usage_error{option->get_name() + " '': " + tr("the value is empty")};
    }
  }
}

// Each parameter given sets its field: of the chosen stage for the dynamics every stage has
// (the window's other stages keep their defaults), of every stage that has it otherwise.
void set_parameters(const CLI::App& app, options& o, const given_values& given) {
  const stage_structs structs = structs_of(o);
  for (std::size_t i = 0; i < parameter_table.size(); ++i) {
    const parameter& p = parameter_table[i];
    const std::string name(p.option);
    if (app.count(name) == 0)
      continue;
    const bool whole = field_of_any_stage(p, structs).whole != nullptr;
    const double value =
        whole ? given.whole_parameters[i]
              : number_or_usage_error(name, given.real_parameters[i], tr("expected a number"));
    for (const stage_kind stage : {stage_kind::spring, stage_kind::coupled, stage_kind::cloth}) {
      if (p.scope == parameter_scope::dynamics && stage != o.stage)
        continue;
      if (const field_ref field = p.field(structs, stage))
        field.set(value);
    }
  }
  if (app.count("--sweep-time") > 0)
    o.sweep_time = number_or_usage_error("--sweep-time", given.sweep_time, tr("expected a number"));
}

// --drag KU,KV:X,Y,Z and --sphere X,Y,Z,R.
void read_drag_and_sphere(cloth_parameters& cloth, const given_values& given) {
  const std::string& drag = given.drag;
  if (!drag.empty()) {
    const std::size_t separator = drag.find(':');
    if (separator == std::string::npos)
      throw usage_error{"--drag " + drag + colon() + tr("expected KU,KV:X,Y,Z")};
    const std::string grid = drag.substr(0, separator);
    const std::size_t comma = grid.find(',');
    const std::optional<double> ku = parse_number(grid.substr(0, comma));
    const std::optional<double> kv =
        comma == std::string::npos ? std::nullopt : parse_number(grid.substr(comma + 1));
    if (!ku || !kv || *ku != std::floor(*ku) || *kv != std::floor(*kv)) {
      throw usage_error{"--drag " + drag + colon() + tr("KU,KV must be two whole numbers")};
    }
    if (*ku < 0 || *kv < 0 || *ku >= cloth.grid_size || *kv >= cloth.grid_size) {
      throw usage_error{"--drag " + drag + colon() +
                        format(tr("particle (%s) is outside the %d x %d grid"), grid.c_str(),
                               cloth.grid_size, cloth.grid_size)};
    }
    cloth.drag.enabled = true;
    cloth.drag.ku = static_cast<int>(*ku);
    cloth.drag.kv = static_cast<int>(*kv);
    cloth.drag.target = parse_vector("--drag", drag.substr(separator + 1));
    for (int i = 0; i < 3; ++i)
      require_within("--drag", cloth.drag.target[i], position_bounds);
  }
  const std::string& sphere = given.sphere;
  if (!sphere.empty()) {
    const std::size_t last = sphere.rfind(',');
    if (last == std::string::npos)
      throw usage_error{"--sphere " + sphere + colon() + tr("expected X,Y,Z,R")};
    cloth.sphere.enabled = true;
    cloth.sphere.centre = parse_vector("--sphere", sphere.substr(0, last));
    cloth.sphere.radius =
        number_or_usage_error("--sphere", sphere.substr(last + 1), tr("expected X,Y,Z,R"));
    for (int i = 0; i < 3; ++i)
      require_within("--sphere", cloth.sphere.centre[i], position_bounds);
    require_within("--sphere", cloth.sphere.radius, bounds_of(parameter_named("--size")));
  }
}

// An option that the chosen stage has no use for is refused, naming the stage it belongs to.
void refuse_other_stages_options(const CLI::App& app, const options& o) {
  const std::string chosen(stage_name(o.stage));
  const auto refuse_unless = [&](bool fits, std::string_view option, const char* whose) {
    if (!fits && app.count(std::string(option)) > 0) {
      throw usage_error{
          std::string(option) + colon() +
          format(tr("%s; the %s stage has no use for it"), tr(whose), chosen.c_str())};
    }
  };
  const bool cloth = o.stage == stage_kind::cloth;
  constexpr const char* cloths = N_("the cloth's option (--stage cloth)");
  for (const parameter& p : parameter_table) {
    if (p.scope == parameter_scope::cloth)
      refuse_unless(cloth, p.option, cloths);
  }
  for (const char* option : other_cloth_options)
    refuse_unless(cloth, option, cloths);
  for (const parameter& p : parameter_table) {
    if (p.scope == parameter_scope::spring_stages) {
      refuse_unless(!cloth, p.option,
                    N_("the spring stages' stiffness (the cloth's: --K-struct, --K-shear, "
                       "--K-bend)"));
    }
  }
  refuse_unless(o.stage == stage_kind::spring, "--start",
                N_("the single spring's option (--stage spring)"));
  for (const parameter& p : parameter_table) {
    if (p.scope == parameter_scope::chain)
      refuse_unless(o.stage == stage_kind::coupled, p.option,
                    N_("the chain's option (--stage coupled)"));
  }
}

// The options that are not numbers of the table: the integrator, the scaling, the sweep's
// lists, the wind's direction and the ground.
void read_other_values(options& o, const given_values& given) {
  const std::string chosen(stage_name(o.stage));
  cloth_parameters& cloth = o.cloth;
  if (!given.integrator.empty())
    parameter_fields::dynamics_of(structs_of(o), o.stage).integrator =
        *parse_integrator(given.integrator);
  if (!given.scaling.empty())
    cloth.scaling = *parse_resolution_scaling(given.scaling);
  if (!given.sweep_dt.empty())
    o.sweep_time_steps =
        parse_list("--sweep-dt", given.sweep_dt, bounds_of(parameter_named("--dt")));
  if (!given.sweep_k.empty())
    o.sweep_stiffnesses = parse_list("--sweep-K", given.sweep_k, bounds_of(parameter_named("--K")));
  if (!given.sweep_n.empty()) {
    const int max_grid_size = static_cast<int>(parameter_named("--N").high);
    for (double n : parse_list("--sweep-N", given.sweep_n, {1, double(max_grid_size), ""})) {
      // The chain's n from 1, the cloth's N from 2 (a grid of one particle has no spring).
      const int smallest = o.stage == stage_kind::cloth ? 2 : 1;
      require(n == std::floor(n) && n >= smallest && n <= max_grid_size, "--sweep-N", n,
              format(tr("must be whole numbers between %d and %d for the %s stage"), smallest,
                     max_grid_size, chosen.c_str()));
      o.sweep_grid_sizes.push_back(static_cast<int>(n));
    }
  }
  if (!given.wind_dir.empty())
    cloth.wind_direction = parse_vector("--wind-dir", given.wind_dir);
  if (!given.ground_z.empty()) {
    if (given.ground_z == "none") {
      cloth.ground_enabled = false;
    } else {
      cloth.ground_enabled = true;
      cloth.ground_height =
          number_or_usage_error("--ground-z", given.ground_z, tr("expected a number or none"));
    }
  }
}

// Every parameter within its range: the chosen stage's for the dynamics, the one value of the
// others (a parameter off by default only when given). Each message names the option and its
// value; every bound is in docs/limits.md.
void check_parameter_ranges(const CLI::App& app, options& o) {
  const stage_structs structs = structs_of(o);
  for (const parameter& p : parameter_table) {
    const std::string name(p.option);
    if (!p.off.empty() && app.count(name) == 0)
      continue;
    const double value = p.scope == parameter_scope::dynamics
                             ? p.field(structs, o.stage).get()
                             : field_of_any_stage(p, structs).get();
    require_finite(name, value);
    if (value < p.low && !p.below_low.empty())
      throw usage_error{name + " " + format_number(value) + colon() + tr(p.below_low.data())};
    if (p.high == unbounded)
      require(value >= p.low, name, value,
              format(tr("must be at least %s"), format_number(p.low).c_str()));
    else
      require_within(name, value, bounds_of(p));
  }
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
  if (!choose_language(argc, argv))
    return {std::nullopt, 2};
  options o;
  CLI::App app{tr("clothlab: mass-spring cloth simulation, the lab of docs/lab.md (single spring, "
                  "coupled springs, cloth on the CPU and the GPU).\nWithout --headless it opens "
                  "the interactive window."),
               "clothlab"};
  app.formatter(std::make_shared<translated_formatter>());
  app.option_defaults()->group(tr("Options"));
  app.set_help_flag("-h,--help", tr("Print this help message and exit"));
  app.set_version_flag("--version", std::string("clothlab ") + CLOTHLAB_VERSION,
                       tr("Display program version information and exit"));
  app.get_formatter()->column_width(34);
  given_values given;
  add_options(app, o, given);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    app.exit(e);
    return {std::nullopt, 0};
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, tr("clothlab: %s (see --help)\n"),
                 one_line(parse_error_message(e)).c_str());
    return {std::nullopt, 2};
  }

  try {
    refuse_empty_values(app);
    o.stage = stages.at(given.stage);
    o.backend = backends.at(given.backend);
    o.gl = gl_choices.at(given.gl);
    set_parameters(app, o, given);
    read_drag_and_sphere(o.cloth, given);
    if (!given.pins.empty())
      o.cloth.pins = pins.at(given.pins);
    refuse_other_stages_options(app, o);
    o.spring_1d_start = given.start == "1d";
    read_other_values(o, given);
    check_parameter_ranges(app, o);
    const auto was_given = [&](std::string_view option) {
      return app.count(std::string(option)) > 0;
    };
    check_other_ranges(o, given);
    check_combinations(o, given, was_given);
  } catch (const usage_error& e) {
    std::fprintf(stderr, tr("clothlab: %s\n"), one_line(e.message).c_str());
    return {std::nullopt, 2};
  }
  // Self-collision runs with d no larger than the shortest rest length h (docs/model.md): a
  // larger D is accepted, clamped, and said so once by a headless run (the window's command
  // line is parsed twice, by clothlab and by clothlab-window).
  if (o.headless && o.cloth.self_collision_thickness > self_collision_distance(o.cloth)) {
    std::fprintf(stderr,
                 tr("clothlab: warning: --self-collision %g: clamped to the shortest rest length "
                    "h = %g m (--size / (N - 1))\n"),
                 o.cloth.self_collision_thickness, self_collision_distance(o.cloth));
  }
  return {o, 0};
}

}  // namespace clothlab
