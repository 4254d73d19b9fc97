#include "runtime/output/restart_record.h"

#include <sstream>

#include "common/base/error.h"
#include "common/input/yaml_overrides.h"
#include "common/sid/hdf5_io.h"
#include "runtime/output/run_figures.h"
#include "runtime/output/writer_lock.h"

namespace ffriga {

RestartRecordWriter::RestartRecordWriter(ResultFile& file, int state_size, long rows)
    : file_(file), rows_(rows) {
  const h5::Context c = file_.context();
  if (file_.appending()) {
    group_ = h5::openGroup(c, file_.id(), "restart");
    state_ = h5::Handle(c.check(H5Dopen2(group_.id(), "state", H5P_DEFAULT), "H5Dopen2 'state'"),
                        H5Dclose);
    return;
  }
  group_ = file_.group(file_.id(), "restart");
  const hsize_t dims[1] = {static_cast<hsize_t>(state_size)};
  h5::Handle space(c.check(H5Screate_simple(1, dims, nullptr), "H5Screate_simple"), H5Sclose);
  state_ = h5::Handle(c.check(H5Dcreate2(group_.id(), "state", H5T_NATIVE_DOUBLE, space.id(),
                                         H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                              "H5Dcreate2 'state'"),
                      H5Dclose);
  h5::writeAttribute(c, state_.id(), "unit", std::string("SI"));
  h5::writeAttribute(c, state_.id(), "description",
                     std::string("full state vector y at the last row on disk (the layout of "
                                 "MultibodySystem: positions, then velocities)"));
  // Every attribute a flush writes exists from the start: in SWMR mode they are written in
  // place (runtime/output/result_file.h).
  h5::writeAttribute(c, group_.id(), "time_s", 0.0);
  h5::writeAttribute(c, group_.id(), "dissipated_J", 0.0);
  for (const auto& [name, value] : restartFigures(RunFigures{}, 0, 0.0))
    h5::writeAttribute(c, group_.id(), "figure_" + name, value);
  h5::writeAttribute(c, group_.id(), "rows", 0.0);
}

void RestartRecordWriter::write(const OutputSample& sample) {
  ++rows_;
  time_ = sample.time;
  dissipated_ = sample.energy.dissipated;
  y_ = sample.state;
  pending_ = true;
}

void RestartRecordWriter::flush() {
  if (!pending_) return;
  const h5::Context c = file_.context();
  c.check(H5Dwrite(state_.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, y_.data()),
          "H5Dwrite 'restart/state'");
  h5::writeAttribute(c, group_.id(), "time_s", time_);
  h5::writeAttribute(c, group_.id(), "dissipated_J", dissipated_);
  for (const auto& [name, value] : figures_)
    h5::writeAttribute(c, group_.id(), "figure_" + name, value);
  h5::writeAttribute(c, group_.id(), "rows", static_cast<double>(rows_));
  pending_ = false;
}

RestartRecord readRestartRecord(const std::string& path) {
  // Another ffrsim still writing the file is the reason to give, whatever its record holds.
  WriterLock::refuseIfHeld(path);
  h5::silenceErrors();
  const h5::Context c{path, true};
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  // A run killed in SWMR mode left the "open for writing" mark: SWMR readers still open it.
  if (f < 0) f = H5Fopen(path.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT);
  if (f < 0) throw InputError(Str() << path << ": cannot open as an HDF5 result file");
  h5::Handle file(f, H5Fclose);
  if (!H5Aexists(f, "format") || h5::readStringAttribute(c, f, "format") != kResultFormat) {
    throw InputError(Str() << path << ": not a result file of ffrsim (root attribute 'format' is "
                           << "not '" << kResultFormat << "')");
  }
  const int version = h5::readIntAttribute(c, f, "format_version");
  if (version != kResultFormatVersion) {
    throw InputError(Str() << path << ": result format version " << version << ", this ffrsim "
                           << "restarts version " << kResultFormatVersion << " only");
  }
  if (!h5::exists(f, "restart") || !H5Aexists(f, "scene_path")) {
    throw InputError(Str() << path << ": the file holds no restart record (the run stopped "
                           << "before its first flush)");
  }
  RestartRecord r;
  r.status = h5::readStringAttribute(c, f, "status");
  r.scene_yaml = h5::readStringAttribute(c, f, "scene_yaml");
  if (h5::hasAttribute(f, "overrides"))
    r.overrides = overridesFromText(h5::readStringAttribute(c, f, "overrides"));
  r.scene_path = h5::readStringAttribute(c, f, "scene_path");
  r.end_time = h5::readDoubleAttribute(c, f, "end_time_s");
  r.restarts = H5Aexists(f, "restarts") ? h5::readIntAttribute(c, f, "restarts") : 0;
  std::istringstream sids(h5::readStringAttribute(c, f, "sid_files"));
  for (std::string line; std::getline(sids, line);)
    if (!line.empty()) r.sid_files.push_back(line);
  h5::Handle g = h5::openGroup(c, f, "restart");
  r.time = h5::readDoubleAttribute(c, g.id(), "time_s");
  r.rows = static_cast<long>(h5::readDoubleAttribute(c, g.id(), "rows"));
  if (r.rows < 1) throw InputError(Str() << path << ": the restart record holds no row yet");
  r.state = h5::readVector(c, g.id(), "state");
  if (H5Aexists(g.id(), "dissipated_J")) r.dissipated = h5::readDoubleAttribute(c, g.id(), "dissipated_J");
  const int n = static_cast<int>(H5Aget_num_attrs(g.id()));
  for (int i = 0; i < n; ++i) {
    char name[256];
    h5::Handle a(H5Aopen_by_idx(g.id(), ".", H5_INDEX_NAME, H5_ITER_INC, i, H5P_DEFAULT,
                                H5P_DEFAULT),
                 H5Aclose);
    if (a.id() < 0 || H5Aget_name(a.id(), sizeof name, name) < 0) continue;
    const std::string key(name);
    if (key.rfind("figure_", 0) == 0)
      r.figures[key.substr(7)] = h5::readDoubleAttribute(c, g.id(), key);
  }
  return r;
}

}  // namespace ffriga
