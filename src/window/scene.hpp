// The handout's scene (section 2, question 1): load_model() runs once and sets the initial state
// of the three stages; draw_scene() runs every frame: it advances the current stage by the
// number of steps the time mode asks for, then draws it. The four parts of question 3 stay
// apart: initialisation (load_model), force computation (compute_force), numerical integration
// (apply_force), display (the renderer, which only reads the state).
//
// The class's code is in three files: scene.cpp (load_model, draw_scene: the stepping and the
// drawing), scene_cloth_path.cpp (the cloth's path, CPU or GPU, and the switch between them) and
// scene_mouse.cpp (the mouse: picking, the grab's drag, the sphere's move). What it measures of
// the run (rates, energies, the first tear) is run_statistics.hpp's.
#pragma once

#include <array>
#include <chrono>
#include <optional>

#include <glm/vec2.hpp>
#include <string>
#include <vector>

#include "core/coupled_springs.hpp"
#include "core/energy.hpp"
#include "core/single_spring.hpp"
#include "core/spring_mesh.hpp"
#include "core/stability.hpp"
#include "gl/camera.hpp"
#include "gl/cloth_paths.hpp"
#include "gl/renderer.hpp"
#include "window/frame_anatomy.hpp"
#include "window/picking.hpp"
#include "window/run_statistics.hpp"
#include "window/spring_motion.hpp"
#include "window/stability_map.hpp"
#include "window/state_images.hpp"

namespace clothlab {

// The stage in the user's words, for the messages: "the single spring", "the chain", "the cloth".
const char* stage_in_words(stage_kind stage);

// How many steps a drawn frame advances.
enum class time_mode {
  steps_per_frame,  // a fixed number of steps per frame: simulated time runs at the frame rate
  real_time         // simulated time follows the wall clock (up to max_steps_per_frame)
};

struct simulation_control {
  bool running = true;  // Space: pause / run
  time_mode mode = time_mode::real_time;
  int steps_per_frame = 10;      // steps_per_frame mode: steps per drawn frame
  double real_time_speed = 1.0;  // real_time mode: simulated seconds per wall-clock second
  // real_time mode: a slow machine falls behind real time, it never freezes; a frame stops
  // stepping at whichever of these two comes first.
  int max_steps_per_frame = 500;
  double max_simulation_seconds_per_frame = 0.05;  // s of wall-clock time
  // At start, the initial state stays in sight this long (s of wall-clock time, and at least
  // start_hold_frames frames) before the first step, so that the student sees the cloth drop.
  double start_hold_seconds = 0.8;
  int start_hold_frames = 10;
};

// Where one stage's run stands.
struct run_status {
  long step = 0;          // steps since load_model (step 0 is the initial state)
  double time = 0.0;      // t, s: the sum of the dt of every step (dt can change during a run)
  bool diverged = false;  // divergence_check (stability.hpp) failed: stepping stopped
  std::string divergence_reason;  // what the check found, e.g. a non-finite velocity
  std::string divergence_advice;  // dt omega_max and the integrator's limit when it diverged
  bool behind_real_time = false;  // real_time mode: the last frame hit one of its limits
  double start_hold_left = 0.0;   // s before the first step at start (0: running or paused)
};

class scene {
  // The cloth and the paths that can run it (questions 11 to 13); first, so that cloth_stage
  // below can name its cloth.
  cloth_paths paths_;

 public:
  // The three stages with their parameters (the command line's), `stage` shown first; nothing is
  // loaded yet.
  scene(stage_kind stage, const single_spring_parameters& spring,
        const coupled_springs_parameters& chain, const cloth_parameters& cloth);
  ~scene();  // needs the GL context still current
  scene(const scene&) = delete;
  scene& operator=(const scene&) = delete;

  // Loads the renderer's shaders and texture (needs the GL context). False with error on failure.
  bool init_renderer(std::string& error);

  // Initialisation (question 3): the initial state of every stage. Runs once at start.
  void load_model();
  // Every frame: advances the current stage by the steps of the time mode, then draws it into
  // the window's framebuffer, in the width x height area whose left edge is at x = left (the
  // part the control panel leaves free). frame_seconds: wall-clock time since the last frame.
  void draw_scene(double frame_seconds, int left, int width, int height);

  // User actions.
  void select_stage(stage_kind stage);  // keeps each stage's run; the camera takes its view
  void reset();                         // the current stage back to its initial state
  void toggle_running() { control.running = !control.running; }
  void single_step();  // pauses, then advances exactly one step
  void reset_view() { view = framed_view(); }
  // The stage's view, moved back to take in the whole chain (whose lower masses swing down far
  // below p0 when the springs are soft).
  camera framed_view() const;

  stage_kind stage() const { return stage_; }
  // True when the next frame would look like the last one unless the user acts: paused or
  // diverged, no step asked for, no stability map being computed.
  bool idle() const {
    return (!control.running || status().diverged) && !single_step_requested_ &&
           !stability_explorer.running();
  }
  const run_status& status() const { return status_[static_cast<int>(stage_)]; }
  // Questions 1 and 3: what ran in the last whole frame and how long each phase took
  // (frame_anatomy.hpp). The main loop adds its own phases with finish_frame_anatomy after the
  // swap.
  const frame_anatomy& last_frame_anatomy() const { return last_anatomy_; }
  void finish_frame_anatomy(double poll_and_panel_seconds, double panel_and_swap_seconds,
                            double frame_seconds);
  // True when the current stage fell below the view at the last frame: every particle under its
  // bottom edge (framing.hpp), e.g. a cloth that nothing holds up. The panel says what to do.
  bool fell_out_of_view() const { return fell_out_of_view_; }
  double current_time_step() const;  // dt of the current stage, s
  // Question 4: the energies after the last frame's steps, and each of them (J) after each of
  // the last frames since the stage was selected or reset, oldest first: kinetic, gravity,
  // spring, total.
  const energy_breakdown& energy() const { return energy_history_.latest(); }
  const std::array<std::vector<float>, 4>& energy_history() const {
    return energy_history_.values();
  }
  const std::vector<float>& energy_times() const { return energy_history_.times(); }  // t, s
  // Question 2: the single spring's extension against the exact solution of the 1D model.
  const spring_motion& motion() const { return spring_motion_; }
  double steps_per_second() const { return rates_.steps_per_second(); }
  double frames_per_second() const { return rates_.frames_per_second(); }
  // Steps taken since the program started, every stage and path together (--frames reports it).
  long steps_taken() const { return steps_taken_; }

  // Questions 11 and 12: the cloth's path. switch_cloth_backend carries the current state across
  // (to a GPU path: its load; back: its read_state), so the cloth goes on from where it is. It
  // refuses a GPU path when the cloth as set up cannot run there (gpu_can_run), and then says
  // why in backend_message(). Works whatever stage is shown; reset() keeps the path.
  void switch_cloth_backend(cloth_backend target);
  void toggle_cloth_backend();  // key G: CPU -> GPU -> GPU compute (where offered) -> CPU
  // Where key G takes the cloth from its path now (XPBD goes from the CPU to GPU compute).
  cloth_backend next_cloth_backend() const;
  cloth_backend backend() const { return paths_.backend(); }
  // True when the cloth as now set up can run on that GPU path; otherwise false with the reason
  // (the integrator, tearing or self-collision, the grid size, or a context older than 4.3).
  bool gpu_can_run(cloth_backend target, std::string& why) const {
    return paths_.gpu_can_run(target, why);
  }
  // Whether the window's context has compute shaders (OpenGL 4.3); otherwise false with why.
  bool compute_offered(std::string& why) const { return paths_.compute_offered(why); }
  // Set by the panel every frame: whether what it shows needs the cloth's state on the CPU (the
  // energy plot, the state images). On the GPU paths the state is read back only then, at most
  // max_readbacks_per_second times a second, and so while the springs overlay shows a cloth that
  // can tear (its lines are cloth_stage's springs); otherwise never (the divergence check runs on
  // the GPU and the drawing reads the GPU's own buffers).
  bool panel_needs_state = true;
  static constexpr double max_readbacks_per_second = 10.0;
  long readbacks() const { return paths_.readbacks(); }  // GPU -> CPU read-backs of the state
  // The last switch, refusal or fallback to the CPU, as a sentence ("" before any).
  const std::string& backend_message() const { return backend_message_; }
  // Steps per second of the live path's stepping alone (not drawing nor the panel), measured
  // continuously over about half a second; for the GPU, between two glFinish.
  double stepping_rate() const { return rates_.stepping_rate(); }
  // Question 12: times `steps` steps of every path on copies of the current cloth.
  void measure_backends(int steps);
  const backend_comparison& comparison() const { return comparison_; }
  // Question 11: the cloth's state as the GPU's N x N textures hold it, as small images; made
  // again when the cloth stepped since the last call (needs the GL context).
  const state_images& state_textures();
  bool state_textures_from_gpu() const { return state_images_from_gpu_; }
  // The mouse on the cloth and on the masses of stages 1 and 2 (model.md, "drag").
  // At a left press, grab_particle picks what is under the ray (picking.hpp): on the cloth the
  // particle, from its current positions (on the GPU path read back once, at the press); on
  // stages 1 and 2 the mass whose drawn sphere the ray crosses. A pinned particle or the fixed
  // p0 cannot be dragged: nothing is grabbed and it returns false (the press then orbits). While
  // the button is held, drag_grabbed sets the drag target every frame: the point of the ray in
  // the plane that faces the camera through the grabbed point (as it was at the press).
  // release_grab ends the drag (selecting another stage does too). Each prints a line.
  bool grab_particle(const pick_ray& ray, double max_angle);
  void drag_grabbed(const pick_ray& ray);
  void release_grab();
  bool grabbing() const;  // a particle or mass of the current stage is being dragged
  // The dragged particle's position now (on the GPU path one texel read back), m.
  glm::dvec3 grabbed_position();
  glm::dvec3 drag_target() const;  // q, m: where the current stage's drag pulls
  // Shift + left drag: the sphere follows the cursor in the plane facing the camera through its
  // centre (as it was at the press).
  void start_sphere_move(const pick_ray& ray);
  void move_sphere(const pick_ray& ray);
  // The ray through a point of the window's framebuffer (pixels, from its top-left corner), in
  // the scene's viewport as last drawn; and how many radians of the view one pixel spans.
  pick_ray ray_at(double x, double y) const;
  double radians_per_pixel() const;
  // Where a point of the scene is drawn in the framebuffer (pixels from its top-left corner);
  // nullopt behind the eye.
  std::optional<glm::dvec2> framebuffer_point(const glm::dvec3& point) const;

  // Question 12: the OpenGL renderer (GL_RENDERER), e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  const std::string& renderer_name() const { return renderer_name_; }

  // The three stages of the lab; the control panel edits their public `parameters`.
  single_spring spring_stage;   // stage 1, section 3
  coupled_springs chain_stage;  // stage 2, question 5
  spring_mesh& cloth_stage;     // stage 3, section 4: paths_'s cloth

  // Question 2: the single spring starts with its velocity along the spring (its component along
  // the rest direction), so that the motion is exactly the 1D model's. Applied at load and reset.
  bool spring_one_dimensional_start = false;

  simulation_control control;
  render_settings display = {.show_wind = true};
  camera view;
  stability_map stability_explorer;  // question 4: runs on background threads when started

 private:
  // Calls f on the object of the current stage (all three have the same step interface).
  template <class F>
  decltype(auto) with_current_stage(F&& f) {
    switch (stage_) {
      case stage_kind::spring:
        return f(spring_stage);
      case stage_kind::coupled:
        return f(chain_stage);
      case stage_kind::cloth:
        break;
    }
    return f(cloth_stage);
  }

  int steps_for_this_frame(double frame_seconds);
  void simulate(int steps, double wall_clock_budget);
  void step_current_stage();
  void draw(int left, int width, int height);
  void draw_stage(int left, int width, int height);
  void check_in_view();
  bool cloth_on_gpu() const { return stage_ == stage_kind::cloth && on_gpu(paths_.backend()); }
  bool load_gpu_path(cloth_backend target, std::string& why);
  void read_gpu_state();  // the current GPU path's state into cloth_stage
  void count_step(double time_step);
  void count_grab_stillness(double time_step);
  void report_divergence(divergence_status check);
  void fall_back_to_cpu(const std::string& reason);
  void reload_gpu_cloth();
  void record_energy();
  void record_spring_motion();
  void restart_energy_history();
  void load_spring_stage();
  // The mouse drag of the current stage when it is stage 1 or 2; nullptr on the cloth (whose
  // drag, cloth_stage.parameters.drag, names the particle by (ku, kv)).
  mass_drag_parameters* mass_drag();
  const mass_drag_parameters* mass_drag() const;
  const particle_system& mass_particles() const;  // the particles of stage 1 or 2 (current)

  run_status& current_status() { return status_[static_cast<int>(stage_)]; }

  stage_kind stage_;
  std::array<run_status, 3> status_{};  // indexed by stage_kind
  bool single_step_requested_ = false;
  double unsimulated_seconds_ = 0.0;  // real_time mode: wall-clock time not yet simulated
  double start_hold_seconds_left_ = 0.0;
  int start_hold_frames_left_ = 0;

  energy_record energy_history_;  // of the stage shown, since it was selected or reset
  spring_motion spring_motion_;

  renderer renderer_;

  using clock = std::chrono::steady_clock;
  rate_meter rates_;
  long steps_taken_ = 0;
  tear_report tear_report_;
  bool fell_out_of_view_ = false;
  frame_anatomy anatomy_;                 // this frame's, being measured
  frame_anatomy last_anatomy_;            // the last whole frame's
  std::array<double, 3> load_seconds_{};  // the last load_model of each stage, s

  // The GPU paths (questions 11 and 12): while one holds the cloth's state (paths_),
  // cloth_stage holds a copy read back only when the panel needs it (panel_needs_state), at a
  // switch, a measurement, a press of the mouse or a divergence. The divergence check runs on
  // the GPU (cloth_paths::run).
  bool state_fresh_ = false;  // the GPU state was read back this frame
  std::string backend_message_;
  backend_comparison comparison_;
  std::string renderer_name_;

  // The scene's part of the framebuffer at the last draw (pixels): left edge, width, height.
  int viewport_left_ = 0;
  int viewport_width_ = 1;
  int viewport_height_ = 1;
  glm::dvec3 grab_plane_point_{0.0};    // the grabbed particle at the press, m
  glm::dvec3 grab_target_{0.0};         // the drag's target at the last step, m
  double grab_still_seconds_ = 0.0;     // simulated time since the target last moved, s
  glm::dvec3 sphere_grab_offset_{0.0};  // Shift + drag: cursor point - sphere centre at the press
  glm::dvec3 sphere_plane_point_{0.0};  // the sphere's centre at the press, m

  state_images state_images_;
  long state_images_step_ = -1;  // the cloth's step they show (-1: none yet)
  bool state_images_from_gpu_ = false;
  std::vector<double> normal_scratch_;
  std::vector<float> texel_scratch_;  // the GPU's normals, RGBA
};

}  // namespace clothlab
