// The lab's parameters, one row each: the option that sets it, its unit, the field of the stage
// structs it sets (parameters.hpp holds the defaults), the range the command line accepts, the
// range of the window's slider and the help. The command line (app/command_line.cpp), the window's
// sliders (window/stage_editors.cpp) and docs/cli.md (tests/docs/parameter_table_test.cpp) read
// it, so that each of these facts is written once: a new parameter is one more row here.
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

#include "core/i18n.hpp"  // N_: the help texts, translated where shown
#include "core/parameters.hpp"

namespace clothlab {

// The three stages' parameter structs, as a run or the window holds them.
struct stage_structs {
  single_spring_parameters& spring;
  coupled_springs_parameters& coupled;
  cloth_parameters& cloth;
};

// One number of a stage's struct: a double or an int field (whole numbers: grid sizes, counts).
struct field_ref {
  double* real = nullptr;
  int* whole = nullptr;
  explicit operator bool() const { return real != nullptr || whole != nullptr; }
  double get() const { return real != nullptr ? *real : *whole; }
  void set(double value) const {  // an int field is given a whole number (the parser's)
    if (real != nullptr)
      *real = value;
    else
      *whole = static_cast<int>(value);
  }
};

// The field of `stage` that a parameter sets; empty when that stage has no such parameter.
using field_accessor = field_ref (*)(const stage_structs& structs, stage_kind stage);

// Which stages have a parameter, and which the command line sets (docs/cli.md): an option sets
// the chosen stage (--stage) and is refused, naming its stage, when that stage has no use for it.
enum class parameter_scope {
  dynamics,        // every stage's dynamics_parameters; the chosen stage's is set
  spring_stages,   // the single spring's and the chain's (the cloth has three stiffnesses)
  chain,           // the chain's
  cloth,           // the cloth's (the handout's cloth)
  cloth_addition,  // the cloth's additions: sphere, tearing, self-collision
  every_stage      // set on every stage at once (the mouse's drag spring)
};

inline constexpr double unbounded = std::numeric_limits<double>::infinity();

// The values the window's slider offers (a slider on a log scale where the range spans decades).
struct slider_range {
  double low = 0.0, high = 0.0;
  bool logarithmic = false;
};

struct parameter {
  std::string_view option = {};      // "--dt"
  std::string_view value_name = {};  // the value's name in docs/cli.md: "--dt SECONDS"
  std::string_view unit = {};        // "s", "N/m"; empty for a pure number
  parameter_scope scope = parameter_scope::cloth;
  field_accessor field = nullptr;
  // The command line's range, both ends included (docs/limits.md says why each end is there).
  // high = unbounded: "at least low".
  double low = 0.0, high = unbounded;
  std::string_view below_low = {};  // the message for a value below low, when not the range's
  // Non-empty: the default (0) means "off", named so ("never"), and lies outside the range,
  // which applies to a value given.
  std::string_view off = {};
  slider_range slider = {};  // the window's slider (of the cloth, or of every stage)
  std::optional<slider_range> spring_stages_slider = {};  // the spring and chain's, if another
  std::string_view help = {};  // the --help line (the unit, range and default are added to it)
  // docs/cli.md's row for the option: "{range}", "{default}" and "{slider_high}" stand for the
  // range, the default (range_text, default_text) and the slider's end, as docs/cli.md writes
  // them.
  std::string_view doc = {};

  slider_range slider_for(stage_kind stage) const {
    return stage != stage_kind::cloth && spring_stages_slider ? *spring_stages_slider : slider;
  }
};

// The accessors of the table's rows, one per kind of scope.
namespace parameter_fields {

// The field at the end of a path of members (&cloth_parameters::sphere,
// &sphere_parameters::friction).
template <auto... path>
field_ref at(auto& root) {
  auto& value = (root.*....*path);
  if constexpr (std::is_same_v<std::remove_cvref_t<decltype(value)>, int>)
    return {.whole = &value};
  else
    return {.real = &value};
}

inline dynamics_parameters& dynamics_of(const stage_structs& s, stage_kind stage) {
  return stage == stage_kind::spring    ? s.spring.dynamics
         : stage == stage_kind::coupled ? s.coupled.dynamics
                                        : s.cloth.dynamics;
}

// A field of every stage's dynamics_parameters (a path of members: &dynamics_parameters::xpbd,
// &xpbd_parameters::substeps).
template <auto... path>
field_ref dynamics(const stage_structs& s, stage_kind stage) {
  return at<path...>(dynamics_of(s, stage));
}
// A field of the single spring and one of the chain.
template <auto spring_member, auto chain_member>
field_ref spring_stages(const stage_structs& s, stage_kind stage) {
  if (stage == stage_kind::spring)
    return at<spring_member>(s.spring);
  if (stage == stage_kind::coupled)
    return at<chain_member>(s.coupled);
  return {};
}
template <auto... path>
field_ref chain(const stage_structs& s, stage_kind stage) {
  return stage == stage_kind::coupled ? at<path...>(s.coupled) : field_ref{};
}
template <auto... path>
field_ref cloth(const stage_structs& s, stage_kind stage) {
  return stage == stage_kind::cloth ? at<path...>(s.cloth) : field_ref{};
}
// The drag spring's stiffness K_d: the mouse's on every stage, and --drag's on the cloth.
inline field_ref drag_stiffness(const stage_structs& s, stage_kind stage) {
  return stage == stage_kind::spring
             ? at<&single_spring_parameters::drag, &mass_drag_parameters::stiffness>(s.spring)
         : stage == stage_kind::coupled
             ? at<&coupled_springs_parameters::drag, &mass_drag_parameters::stiffness>(s.coupled)
             : at<&cloth_parameters::drag, &drag_parameters::stiffness>(s.cloth);
}

}  // namespace parameter_fields

// The window's time-step sliders end here (s); the damping and friction sliders end at 1 / dt_max,
// so that mu dt <= 1 for every dt a slider offers.
inline constexpr double spring_stages_slider_max_time_step = 0.1;
inline constexpr double cloth_slider_max_time_step = 0.02;

// Every parameter, in the order of --help and of the checks of the command line.
inline constexpr std::array parameter_table = {
    parameter{
        .option = "--dt",
        .value_name = "SECONDS",
        .unit = "s",
        .scope = parameter_scope::dynamics,
        .field = parameter_fields::dynamics<&dynamics_parameters::time_step>,
        .low = 1e-9,
        .high = 10.0,
        .slider = {1e-4, cloth_slider_max_time_step, true},
        .spring_stages_slider = slider_range{1e-4, spring_stages_slider_max_time_step, true},
        .help = N_("Step length"),
        .doc = "step length, {range} [{default}]",
    },
    parameter{
        .option = "--mu",
        .value_name = "RATE",
        .unit = "1/s",
        .scope = parameter_scope::dynamics,
        .field = parameter_fields::dynamics<&dynamics_parameters::damping>,
        .low = 0.0,
        .high = unbounded,
        .slider = {0.0, 1.0 / cloth_slider_max_time_step},
        .spring_stages_slider = slider_range{0.0, 1.0 / spring_stages_slider_max_time_step},
        .help = N_("Damping rate mu"),
        .doc = "damping rate μ in 1/s, {range} [{default}]; μ dt must be at most 1 with the two "
               "Euler integrators, which multiply the velocity by (1 - μ dt), and μ h with "
               "`xpbd`, which multiplies it by (1 - μ h) every substep h (`verlet`, `rk4` and "
               "`implicit` apply the damping as a force)",
    },
    parameter{
        .option = "--mass",
        .value_name = "M",
        .unit = "kg",
        .scope = parameter_scope::dynamics,
        .field = parameter_fields::dynamics<&dynamics_parameters::mass>,
        .low = 1e-6,
        .high = 1e6,
        .slider = {0.01, 10.0, true},
        .help = N_("Mass of each moving particle"),
        .doc = "mass of each moving particle, {range} [{default}]",
    },
    parameter{
        .option = "--gravity",
        .value_name = "G0",
        .unit = "m/s^2",
        .scope = parameter_scope::dynamics,
        .field = parameter_fields::dynamics<&dynamics_parameters::gravity>,
        .low = 0.0,
        .high = 1e3,
        .below_low = N_("is a magnitude along -z: at least 0"),
        .slider = {0.0, 30.0},
        .help = N_("Gravity g0 along -z"),
        .doc = "magnitude of gravity along -z, {range} [{default}]",
    },
    parameter{
        .option = "--xpbd-substeps",
        .value_name = "N",
        .scope = parameter_scope::dynamics,
        .field = parameter_fields::dynamics<&dynamics_parameters::xpbd, &xpbd_parameters::substeps>,
        .low = 1,
        .high = 1000,
        .slider = {1, 100},
        .help = "XPBD: substeps per step",
        .doc = "`--integrator xpbd`: substeps per step, each of h = dt / N, {range} [{default}] "
               "(the window's slider goes to {slider_high})",
    },
    parameter{
        .option = "--xpbd-iterations",
        .value_name = "N",
        .scope = parameter_scope::dynamics,
        .field =
            parameter_fields::dynamics<&dynamics_parameters::xpbd, &xpbd_parameters::iterations>,
        .low = 1,
        .high = 1000,
        .slider = {1, 50},
        .help = "XPBD: sweeps over the constraints per substep",
        .doc = "`--integrator xpbd`: Gauss-Seidel sweeps over every spring's constraint per "
               "substep, {range} [{default}] (the window's slider goes to {slider_high})",
    },
    parameter{
        .option = "--xpbd-damping",
        .value_name = "BETA",
        .unit = "N s/m",
        .scope = parameter_scope::dynamics,
        .field = parameter_fields::dynamics<&dynamics_parameters::xpbd,
                                            &xpbd_parameters::constraint_damping>,
        .low = 0.0,
        .high = 1e9,
        .slider = {0.0, 200.0},
        .help = "XPBD: damping beta along each spring",
        .doc = "`--integrator xpbd`: the damping β of every spring's constraint (the XPBD "
               "paper's: a dashpot of β N s/m along the spring, beside μ), {range} [{default}]",
    },
    parameter{
        .option = "--K",
        .value_name = "VALUE",
        .unit = "N/m",
        .scope = parameter_scope::spring_stages,
        .field = parameter_fields::spring_stages<&single_spring_parameters::stiffness,
                                                 &coupled_springs_parameters::stiffness>,
        .low = 0.0,
        .high = 1e9,
        .slider = {0.0, 1e5, true},
        .help = N_("Stiffness of the spring stages"),
        .doc = "stiffness of the single spring and of every spring of the chain, {range} "
               "[{default}]",
    },
    parameter{
        .option = "--K-struct",
        .value_name = "K",
        .unit = "N/m",
        .scope = parameter_scope::cloth,
        .field = parameter_fields::cloth<&cloth_parameters::structural_stiffness>,
        .low = 0.0,
        .high = 1e9,
        .slider = {0.0, 1e5, true},
        .help = N_("Cloth structural stiffness"),
        .doc = "stiffness of the structural springs, {range} [{default}]",
    },
    parameter{
        .option = "--K-shear",
        .value_name = "K",
        .unit = "N/m",
        .scope = parameter_scope::cloth,
        .field = parameter_fields::cloth<&cloth_parameters::shear_stiffness>,
        .low = 0.0,
        .high = 1e9,
        .slider = {0.0, 1e5, true},
        .help = N_("Cloth shear stiffness"),
        .doc = "stiffness of the shear springs, {range} [{default}]",
    },
    parameter{
        .option = "--K-bend",
        .value_name = "K",
        .unit = "N/m",
        .scope = parameter_scope::cloth,
        .field = parameter_fields::cloth<&cloth_parameters::bending_stiffness>,
        .low = 0.0,
        .high = 1e9,
        .slider = {0.0, 1e5, true},
        .help = N_("Cloth bending stiffness"),
        .doc = "stiffness of the bending springs, {range} [{default}]",
    },
    parameter{
        .option = "--chain",
        .value_name = "N",
        .scope = parameter_scope::chain,
        .field = parameter_fields::chain<&coupled_springs_parameters::mass_count>,
        .low = 1,
        .high = 1000,
        .slider = {1, 50},
        .help = N_("Moving masses of the coupled stage"),
        .doc = "number of moving masses of the chain, {range} [{default}] (the window's slider "
               "goes to {slider_high})",
    },
    parameter{
        .option = "--N",
        .value_name = "N",
        .scope = parameter_scope::cloth,
        .field = parameter_fields::cloth<&cloth_parameters::grid_size>,
        .low = 2,
        .high = 1024,
        .slider = {2, 100},
        .help = N_("Cloth grid size: N x N particles"),
        .doc = "grid size, N x N particles, {range} [{default}] (the window's slider goes to "
               "{slider_high})",
    },
    parameter{
        .option = "--size",
        .value_name = "S",
        .unit = "m",
        .scope = parameter_scope::cloth,
        .field = parameter_fields::cloth<&cloth_parameters::side_length>,
        .low = 1e-3,
        .high = 1e3,
        .slider = {0.2, 4.0},
        .help = N_("Cloth side length"),
        .doc = "side length, {range} [{default}]",
    },
    parameter{
        .option = "--wind-strength",
        .value_name = "KW",
        .unit = "N",
        .scope = parameter_scope::cloth,
        .field = parameter_fields::cloth<&cloth_parameters::wind_strength>,
        .low = -1e6,
        .high = 1e6,
        .slider = {0.0, 20.0},  // stronger wind folds the default cloth through itself
        .help = N_("Wind strength K_w"),
        .doc = "wind strength K_w, {range} [{default}: no wind]",
    },
    parameter{
        .option = "--ground-friction",
        .value_name = "MU_G",
        .unit = "1/s",
        .scope = parameter_scope::cloth,
        .field = parameter_fields::cloth<&cloth_parameters::ground_friction>,
        .low = 0.0,
        .high = unbounded,
        .slider = {0.0, 1.0 / cloth_slider_max_time_step},
        .help = N_("Ground friction rate mu_g"),
        .doc = "ground friction rate μ_g in 1/s, {range}, with μ_g dt at most 1 [{default}]",
    },
    parameter{
        .option = "--reference-N",
        .value_name = "N_REF",
        .scope = parameter_scope::cloth,
        .field = parameter_fields::cloth<&cloth_parameters::reference_grid_size>,
        .low = 2,
        .high = 1024,
        .slider = {2, 100},
        .help = N_("Grid whose particles have --mass and springs the K (resolution-independent)"),
        .doc = "the reference grid of the `resolution-independent` scaling, {range} [{default}]",
    },
    parameter{
        .option = "--drag-stiffness",
        .value_name = "K_D",
        .unit = "N/m",
        .scope = parameter_scope::every_stage,
        .field = parameter_fields::drag_stiffness,
        .low = 0.0,
        .high = 1e9,
        .slider = {1.0, 1e5, true},
        .help = N_("Drag spring K_d (--drag, and the mouse on every stage)"),
        .doc = "the drag spring's stiffness, {range} [{default}]; on every stage, where it is "
               "also the mouse's drag spring in the window (stages 1 and 2 take it too)",
    },
    parameter{
        .option = "--sphere-friction",
        .value_name = "MU_S",
        .unit = "1/s",
        .scope = parameter_scope::cloth_addition,
        .field = parameter_fields::cloth<&cloth_parameters::sphere, &sphere_parameters::friction>,
        .low = 0.0,
        .high = unbounded,
        .slider = {0.0, 1.0 / cloth_slider_max_time_step},
        .help = N_("Sphere friction rate mu_s"),
        .doc = "the sphere's friction rate in 1/s, {range} [{default}]; μ_s dt must be at most 1",
    },
    parameter{
        .option = "--tear-strain",
        .value_name = "E",
        .scope = parameter_scope::cloth_addition,
        .field = parameter_fields::cloth<&cloth_parameters::tear_strain>,
        .low = 1e-6,
        .high = 100.0,
        .off = N_("never"),
        .slider = {0.0, 3.0},  // 0: off
        .help = N_("Tearing: a spring longer than (1 + E) L0 breaks"),
        .doc = "a spring longer than (1 + E) L0 tears for the rest of the run, E from {range} "
               "[{default}]. The OBJ (and the picture) leave out the triangles that lost a "
               "spring. Every path",
    },
    parameter{
        .option = "--self-collision",
        .value_name = "D",
        .unit = "m",
        .scope = parameter_scope::cloth_addition,
        .field = parameter_fields::cloth<&cloth_parameters::self_collision_thickness>,
        .low = 1e-3,
        .high = 1e3,
        .off = N_("off"),
        // The window's slider also stops at the shortest rest length h, where the model clamps D.
        .slider = {0.001, 0.2, true},
        .help = N_("Self-collision thickness D"),
        .doc = "non-neighbour particles are kept D apart ({range}) [{default}]; a D above the "
               "shortest rest length h = `--size` / (N - 1) is clamped to h, with a warning on "
               "standard error in a headless run (`docs/model.md`). The CPU paths only"},
};

// The row of `option`. In a constant expression an unknown option does not compile.
constexpr const parameter& parameter_named(std::string_view option) {
  for (const parameter& p : parameter_table) {
    if (p.option == option)
      return p;
  }
  // (not translated: a programming error)
  throw std::invalid_argument("no parameter named " + std::string(option));
}

// The parameter's field in the first stage that has it (a parameter set on several stages at
// once holds the same value in each).
field_ref field_of_any_stage(const parameter& p, const stage_structs& structs);

// As docs/cli.md and --help write them: a number ("1e-9", "1e9", "0.002"), the range ("1e-9 to 10
// s", "at least 0", "1 to 1000"; unit: false leaves the unit out), the default of every stage
// that has the parameter ("20", "spring and chain 0.01, cloth 0.002", or the word for off).
std::string parameter_number(double value);
std::string range_text(const parameter& p, bool unit = true);
std::string default_text(const parameter& p);
// The help line of --help: "Step length, s: 1e-9 to 10 [spring and chain 0.01, cloth 0.002]".
std::string help_text(const parameter& p);
// docs/cli.md's row: "| `--dt SECONDS` | step length, 1e-9 to 10 s [...] |".
std::string doc_row(const parameter& p);

}  // namespace clothlab
