// The output files of a headless run (--csv, --energy-csv, --obj, --png; cli.md): opened before
// the run, written as it goes, put in place at the end, whole or not at all.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include "app/options.hpp"
#include "app/run_control.hpp"  // stop_signal
#include "core/energy.hpp"
#include "core/export.hpp"
#include "core/i18n.hpp"
#include "core/spring_mesh.hpp"

namespace clothlab {

// Every output file of a run, each written to a temporary file and renamed into place at the
// end (output_file, export.hpp): whole or not at all. Opened before the run, so that a path
// that cannot be written fails at once rather than after a long run.
class run_outputs {
 public:
  explicit run_outputs(const options& o) : o_(o), states_(nullptr, &std::fclose) {}

  // Prepares every file asked for; false with a message naming the option and the file.
  bool open(std::string& error);

  enum class recorded { yes, not_finite, interrupted };

  // Writes step `step` when it is one of the steps written. Writes nothing and says why
  // (`reason`) when a number to write is not finite. A stop signal while a large step is being
  // written (1M lines at N = 1024 take a second and a half) takes its lines back out: the
  // CSV then ends with the step before.
  template <class Stage>
  recorded record(long step, double time_step, const Stage& stage, std::string& reason) {
    if (step % o_.csv_every != 0 && step != o_.steps)
      return recorded::yes;
    const double t = double(step) * time_step;  // t = s dt (model.md)
    energy_breakdown energy;
    if (energies_.is_open()) {
      energy = compute_energy(stage);
      const std::pair<const char*, double> terms[] = {{N_("kinetic"), energy.kinetic},
                                                      {N_("gravity"), energy.gravity},
                                                      {N_("spring"), energy.spring},
                                                      {N_("total"), energy.total}};
      for (const auto& [name, value] : terms) {
        if (!std::isfinite(value)) {
          reason = format(tr("the %s energy %g J is not finite"), tr(name), value);
          return recorded::not_finite;
        }
      }
    }
    if (states_) {
      constexpr std::size_t rows_between_checks = 16384;
      const std::size_t count = stage.particles().size();
      const long start = std::ftell(states_.get());
      for (std::size_t first = 0; first < count; first += rows_between_checks) {
        if (first > 0 && stop_signal != 0 && start >= 0) {
          std::fflush(states_.get());
          if (::ftruncate(::fileno(states_.get()), start) == 0 &&
              std::fseek(states_.get(), start, SEEK_SET) == 0)
            return recorded::interrupted;
        }
        write_csv_rows(states_.get(), step, t, stage.particles(), first,
                       std::min(count, first + rows_between_checks));
      }
    }
    if (energies_.is_open())
      write_energy_csv_row(energies_, step, t, energy);
    return recorded::yes;
  }

  // The OBJ of the final cloth (its normals computed), into its temporary file; false with a
  // message. It is put in place by close().
  bool write_obj_file(const spring_mesh& cloth, std::string& error);

  // Where the PNG writer writes, and the check of what it wrote: stb's writer does not report
  // a failed write, so the file is read back and must be a whole PNG. Put in place by close().
  const std::string& png_write_path() const { return png_file_.write_path(); }
  bool check_png(std::string& error);

  // Closes the CSVs and puts them in place (keep_csvs), then the OBJ and the PNG (keep_images);
  // what is not kept is removed. False with a message naming the file when a write, the flush,
  // the close or the rename failed: that file is removed.
  bool close(bool keep_csvs, bool keep_images, std::string& error);

  // Removes every temporary file, the streams left open (stop_watchdog, when a write holds
  // them).
  void discard() const;

 private:
  bool commit(output_file& file, const char* option, std::string& error);

  const options& o_;
  output_file csv_file_, energy_file_, obj_file_, png_file_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> states_;
  std::ofstream energies_;
};

}  // namespace clothlab
