#include "app/run_outputs.hpp"

#include <cerrno>
#include <cstring>

#include "core/i18n.hpp"

namespace clothlab {

bool run_outputs::open(std::string& error) {
  const struct {
    const char* option;
    const std::string& path;
    output_file& file;
    output_file::writer kind;
  } files[] = {{"--csv", o_.csv_path, csv_file_, output_file::writer::stream},
               {"--energy-csv", o_.energy_csv_path, energy_file_, output_file::writer::stream},
               {"--obj", o_.obj_path, obj_file_, output_file::writer::file_name},
               {"--png", o_.png_path, png_file_, output_file::writer::file_name}};
  for (const auto& f : files) {
    if (!f.path.empty() && !f.file.open(f.path, f.kind, error)) {
      error = std::string(f.option) + " " + f.path + colon() +
              format(tr("cannot write: %s"), error.c_str());
      return false;
    }
  }
  if (!o_.csv_path.empty()) {
    states_.reset(std::fopen(csv_file_.write_path().c_str(), "w"));
    if (!states_) {
      error =
          "--csv " + o_.csv_path + colon() + format(tr("cannot write: %s"), std::strerror(errno));
      return false;
    }
    write_csv_header(states_.get());
  }
  if (!o_.energy_csv_path.empty()) {
    energies_.open(energy_file_.write_path());
    if (!energies_) {
      error = "--energy-csv " + o_.energy_csv_path + colon() +
              format(tr("cannot write: %s"), std::strerror(errno));
      return false;
    }
    write_energy_csv_header(energies_);
  }
  return true;
}

bool run_outputs::write_obj_file(const spring_mesh& cloth, std::string& error) {
  if (o_.obj_path.empty())
    return true;
  const auto intact = [&cloth](int ku, int kv, bool upper) {
    return cloth.triangle_intact(ku, kv, upper);
  };
  if (!write_obj(obj_file_.write_path(), cloth.grid_size(), cloth.particles(), cloth.normals(),
                 intact)) {
    error = "--obj " + o_.obj_path + colon() + format(tr("cannot write: %s"), std::strerror(errno));
    obj_file_.discard();
    return false;
  }
  return true;
}

bool run_outputs::check_png(std::string& error) {
  if (!png_file_is_whole(png_file_.write_path())) {
    error = "--png " + o_.png_path + colon() + tr("error while writing (the image is incomplete)");
    png_file_.discard();
    return false;
  }
  return true;
}

bool run_outputs::close(bool keep_csvs, bool keep_images, std::string& error) {
  bool ok = true;
  if (states_) {
    bool written = std::ferror(states_.get()) == 0;
    written = std::fclose(states_.release()) == 0 && written;
    if (!written) {
      error = "--csv " + o_.csv_path + colon() +
              format(tr("error while writing: %s"), std::strerror(errno));
      csv_file_.discard();
      ok = false;
    }
  }
  if (energies_.is_open()) {
    errno = 0;
    energies_.close();
    if (!energies_) {
      error = "--energy-csv " + o_.energy_csv_path + colon() +
              (errno != 0 ? format(tr("error while writing: %s"), std::strerror(errno))
                          : std::string(tr("error while writing")));
      energy_file_.discard();
      ok = false;
    }
  }
  if (!keep_csvs || !ok) {
    csv_file_.discard();
    energy_file_.discard();
  } else {
    if (!o_.csv_path.empty())
      ok = commit(csv_file_, "--csv", error) && ok;
    if (!o_.energy_csv_path.empty())
      ok = commit(energy_file_, "--energy-csv", error) && ok;
  }
  if (!keep_images || !ok) {
    // Unlinked only: the step loop's thread may still read their names (stop_watchdog).
    obj_file_.remove_temporary();
    png_file_.remove_temporary();
  } else {
    if (!o_.obj_path.empty())
      ok = commit(obj_file_, "--obj", error) && ok;
    if (!o_.png_path.empty())
      ok = commit(png_file_, "--png", error) && ok;
  }
  return ok;
}

void run_outputs::discard() const {
  for (const output_file* file : {&csv_file_, &energy_file_, &obj_file_, &png_file_})
    file->remove_temporary();
}

bool run_outputs::commit(output_file& file, const char* option, std::string& error) {
  std::string why;
  if (file.commit(why))
    return true;
  error = std::string(option) + " " + file.target() + colon() +
          format(tr("cannot write: %s"), why.c_str());
  return false;
}

}  // namespace clothlab
