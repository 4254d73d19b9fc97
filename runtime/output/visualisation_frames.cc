#include "runtime/output/visualisation_frames.h"

#include <cmath>
#include <filesystem>

#include "common/base/error.h"
#include "common/mechanics/von_mises.h"
#include "runtime/output/xdmf_file.h"

namespace ffriga {

using h5::Handle;

namespace {

const double kPi = std::acos(-1.0);

// A chunked dataset [frames, n(, components)] growing in frames (n = 0: [frames]).
Handle createGrowing(const h5::Context& c, hid_t parent, const std::string& name, hsize_t n,
                     int components, hid_t type, const std::string& unit,
                     const std::string& description) {
  const int rank = n == 0 ? 1 : components > 1 ? 3 : 2;
  const hsize_t dims[3] = {0, n, static_cast<hsize_t>(components)};
  const hsize_t maxdims[3] = {H5S_UNLIMITED, n, static_cast<hsize_t>(components)};
  const hsize_t chunk[3] = {n == 0 ? hsize_t{256} : hsize_t{1}, std::max<hsize_t>(n, 1),
                            static_cast<hsize_t>(std::max(components, 1))};
  Handle space(c.check(H5Screate_simple(rank, dims, maxdims), "dataspace of " + name), H5Sclose);
  Handle plist(c.check(H5Pcreate(H5P_DATASET_CREATE), "properties of " + name), H5Pclose);
  c.check(H5Pset_chunk(plist.id(), rank, chunk), "chunks of " + name, 0);
  Handle set(c.check(H5Dcreate2(parent, name.c_str(), type, space.id(), H5P_DEFAULT, plist.id(),
                                H5P_DEFAULT),
                     "create dataset " + name),
             H5Dclose);
  h5::writeAttribute(c, set.id(), "unit", unit);
  h5::writeAttribute(c, set.id(), "description", description);
  return set;
}

// Appends `count` frames of `data` (memory type memType) after the first `written`.
void appendFrames(const h5::Context& c, hid_t set, hsize_t written, hsize_t count, hsize_t n,
                  int components, hid_t memType, const void* data) {
  if (count == 0) return;
  const int rank = n == 0 ? 1 : components > 1 ? 3 : 2;
  const hsize_t dims[3] = {written + count, n, static_cast<hsize_t>(components)};
  c.check(H5Dset_extent(set, dims), "extend frames", 0);
  Handle fspace(c.check(H5Dget_space(set), "dataspace of frames"), H5Sclose);
  const hsize_t start[3] = {written, 0, 0};
  const hsize_t cnt[3] = {count, n, static_cast<hsize_t>(components)};
  c.check(H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, start, nullptr, cnt, nullptr),
          "select frames", 0);
  Handle mspace(c.check(H5Screate_simple(rank, cnt, nullptr), "memory space of frames"), H5Sclose);
  c.check(H5Dwrite(set, memType, mspace.id(), fspace.id(), H5P_DEFAULT, data), "write frames", 0);
}

void truncateFrames(const h5::Context& c, hid_t set, hsize_t keep, hsize_t n, int components) {
  const hsize_t dims[3] = {keep, n, static_cast<hsize_t>(components)};
  c.check(H5Dset_extent(set, dims), "truncate frames", 0);
}

}  // namespace

struct FrameWriter::Body {
  int index = 0;
  std::string name;
  const VisualisationMesh* mesh = nullptr;
  bool axisymmetric = false;
  // Output point p = k np + i shows mesh point i turned by 2 pi k / segments about the y
  // axis (segments = 1: the points themselves).
  int segments = 1;
  Eigen::MatrixXi cells;
  // The mesh's modes in single precision (as the SID stores them; pictures): each frame
  // reads them once, and half the bytes are half the time.
  Eigen::MatrixXf Phi, stress;
  Handle group, points, displacement, von_mises;
  std::vector<float> pending_points, pending_displacement, pending_von_mises;
  long meshPoints() const { return static_cast<long>(mesh->samples.points.rows()); }
  long count() const { return segments * meshPoints(); }
};

std::string xdmfPathFor(const std::string& result_path) {
  std::filesystem::path p(result_path);
  if (p.extension() == ".h5") return p.replace_extension(".xdmf").string();
  return result_path + ".xdmf";
}

FrameWriter::FrameWriter(ResultFile& file, const OutputLayout& layout,
                         const VisualisationFramesConfig& settings, double resume_time)
    : path_(file.path()), file_(file.id()), settings_(settings) {
  const h5::Context c{path_};
  const bool appending = resume_time >= 0.0;
  for (int i = 0; i < static_cast<int>(layout.bodies.size()); ++i) {
    const BodyLayout& body = layout.bodies[i];
    if (body.sid->mesh.empty()) continue;
    auto b = std::make_unique<Body>();
    b->index = i;
    b->name = body.name;
    b->mesh = &body.sid->mesh;
    b->axisymmetric = body.sid->model == ModelKind::kAxisymmetric;
    b->Phi = b->mesh->samples.Phi.cast<float>();
    b->stress = b->mesh->samples.stress.cast<float>();
    const int np = static_cast<int>(b->meshPoints());
    const int segments = b->axisymmetric && settings_.revolve >= 3 ? settings_.revolve : 1;
    b->segments = segments;
    if (segments == 1) {
      b->cells = b->mesh->cells;
    } else {  // each quadrilateral swept from ring k to ring k + 1 (closed)
      const Eigen::MatrixXi& q = b->mesh->cells;
      b->cells.resize(q.rows() * segments, 8);
      for (int k = 0; k < segments; ++k)
        for (Eigen::Index e = 0; e < q.rows(); ++e)
          for (int corner = 0; corner < 4; ++corner) {
            b->cells(k * q.rows() + e, corner) = k * np + q(e, corner);
            b->cells(k * q.rows() + e, 4 + corner) = ((k + 1) % segments) * np + q(e, corner);
          }
    }
    bodies_.push_back(std::move(b));
  }
  if (!appending) {
    group_ = h5::createGroup(c, file_, "visualisation");
    h5::writeAttribute(c, group_.id(), "interval_s", settings_.interval);
    h5::writeAttribute(c, group_.id(), "magnification", settings_.magnification);
    h5::writeAttribute(c, group_.id(), "revolve", settings_.revolve);
    h5::writeAttribute(c, group_.id(), "xdmf", std::filesystem::path(xdmfPathFor(path_)).filename().string());
    time_ = createGrowing(c, group_.id(), "time", 0, 0, H5T_IEEE_F64LE, "s", "frame times");
    for (auto& b : bodies_) createBody(*b, group_.id());
    return;
  }
  // A restart: keep the frames up to the restart time.
  group_ = h5::openGroup(c, file_, "visualisation");
  std::vector<hsize_t> dims;
  const std::vector<double> t = h5::readArray(c, group_.id(), "time", &dims);
  for (double ti : t) {
    if (ti > resume_time * (1.0 + 1e-12)) break;
    times_.push_back(ti);
  }
  written_ = static_cast<long>(times_.size());
  time_ = Handle(c.check(H5Dopen2(group_.id(), "time", H5P_DEFAULT), "open /visualisation/time"),
                 H5Dclose);
  truncateFrames(c, time_.id(), written_, 0, 0);
  for (auto& b : bodies_) openBody(*b, group_.id(), written_);
  next_ = times_.empty() ? 0.0 : frameAfter(times_.back());
}

double FrameWriter::frameAfter(double t) const {
  return (std::floor(t / settings_.interval * (1.0 + 1e-12)) + 1.0) * settings_.interval;
}

FrameWriter::~FrameWriter() = default;

void FrameWriter::createBody(Body& b, hid_t parent) {
  const h5::Context c{path_};
  b.group = h5::createGroup(c, parent, b.name);
  h5::writeAttribute(c, b.group.id(), "cell_type",
                     std::string(b.cells.cols() == 8 ? "hexahedron" : "quadrilateral"));
  h5::writeIntMatrix(c, b.group.id(), "cells", b.cells);
  const hsize_t n = static_cast<hsize_t>(b.count());
  b.points = createGrowing(c, b.group.id(), "points", n, 3, H5T_IEEE_F32LE, "m",
                           "deformed positions r_R + A (x0 + m Phi q), inertial (m: magnification)");
  b.displacement = createGrowing(c, b.group.id(), "displacement", n, 3, H5T_IEEE_F32LE, "m",
                                 "elastic displacement A Phi q, inertial");
  b.von_mises = createGrowing(c, b.group.id(), "von_mises", n, 1, H5T_IEEE_F32LE, "Pa",
                              "von Mises stress of the reduced model");
}

void FrameWriter::openBody(Body& b, hid_t parent, long keep) {
  const h5::Context c{path_};
  b.group = h5::openGroup(c, parent, b.name);
  auto open = [&](const char* name) {
    return Handle(c.check(H5Dopen2(b.group.id(), name, H5P_DEFAULT),
                          "open /visualisation/" + b.name + "/" + name),
                  H5Dclose);
  };
  const hsize_t n = static_cast<hsize_t>(b.count());
  b.points = open("points");
  b.displacement = open("displacement");
  b.von_mises = open("von_mises");
  truncateFrames(c, b.points.id(), keep, n, 3);
  truncateFrames(c, b.displacement.id(), keep, n, 3);
  truncateFrames(c, b.von_mises.id(), keep, n, 1);
}

bool FrameWriter::due(double t) const {
  return t >= next_ - 1e-9 * settings_.interval;
}

void FrameWriter::write(const OutputSample& sample) {
  if (!due(sample.time)) return;
  const double t = sample.time;
  times_.push_back(t);
  next_ = frameAfter(t);
  const double m = settings_.magnification;
  for (auto& bp : bodies_) {
    Body& b = *bp;
    const BodySample& pose = sample.bodies[b.index];
    const SampledModes& S = b.mesh->samples;
    const int s = static_cast<int>(S.points.cols());
    const Eigen::Index np = S.points.rows();
    // Frozen bodies have no elastic coordinates: rigid motion only.
    const bool elastic = pose.pose_q.size() > 0 && pose.pose_q.size() == b.Phi.cols();
    Eigen::VectorXf u = Eigen::VectorXf::Zero(np * s), sigmaf = Eigen::VectorXf::Zero(np * 6);
    if (elastic) {
      const Eigen::VectorXf q = pose.pose_q.cast<float>();
      u.noalias() = b.Phi * q;
      sigmaf.noalias() = b.stress * q;
    }
    const Eigen::VectorXd sigma = sigmaf.cast<double>();
    // Per mesh point: deformed position and displacement in the world (or meridian) frame.
    std::vector<double> vm(np), xw(3 * np, 0.0), dw(3 * np, 0.0);
    for (Eigen::Index i = 0; i < np; ++i) {
      vm[i] = vonMises(sigma.data() + 6 * i);
      for (int r = 0; r < s; ++r) {
        double x = pose.origin(r), dr = 0.0;
        for (int c = 0; c < s; ++c) {
          const double ui = u(s * i + c);
          x += pose.A(r, c) * (S.points(i, c) + m * ui);
          dr += pose.A(r, c) * ui;
        }
        xw[3 * i + r] = x, dw[3 * i + r] = dr;
      }
    }
    for (int k = 0; k < b.segments; ++k) {
      const double angle = 2.0 * kPi * k / b.segments;
      const double ca = std::cos(angle), sa = std::sin(angle);
      for (Eigen::Index i = 0; i < np; ++i) {
        const double* X = &xw[3 * i];
        const double* D = &dw[3 * i];
        // Solids and the unturned section as they are; a meridian plane (x = radius,
        // y = axis) turned about y.
        const bool turned = s == 2 && k > 0;
        const double Xr[3] = {turned ? X[0] * ca : X[0], X[1], turned ? X[0] * sa : X[2]};
        const double Dr[3] = {turned ? D[0] * ca : D[0], D[1], turned ? D[0] * sa : D[2]};
        for (int c = 0; c < 3; ++c) {
          b.pending_points.push_back(static_cast<float>(Xr[c]));
          b.pending_displacement.push_back(static_cast<float>(Dr[c]));
        }
        b.pending_von_mises.push_back(static_cast<float>(vm[i]));
      }
    }
  }
}

std::uint64_t FrameWriter::pendingBytes() const {
  std::uint64_t bytes = 8 * (times_.size() - static_cast<std::size_t>(written_)) + 8 * 256;
  for (const auto& b : bodies_) {
    bytes += sizeof(float) * (b->pending_points.size() + b->pending_displacement.size() +
                              b->pending_von_mises.size());
  }
  return bytes;
}

void FrameWriter::abandon() {
  group_.release(), time_.release();
  for (auto& b : bodies_) b->group.release(), b->points.release(), b->displacement.release(),
                          b->von_mises.release();
}

void FrameWriter::flush() {
  const h5::Context c{path_};
  const long count = static_cast<long>(times_.size()) - written_;
  if (count > 0) {
    const hsize_t w = static_cast<hsize_t>(written_), k = static_cast<hsize_t>(count);
    appendFrames(c, time_.id(), w, k, 0, 0, H5T_NATIVE_DOUBLE, times_.data() + written_);
    for (auto& bp : bodies_) {
      Body& b = *bp;
      const hsize_t n = static_cast<hsize_t>(b.count());
      appendFrames(c, b.points.id(), w, k, n, 3, H5T_NATIVE_FLOAT, b.pending_points.data());
      appendFrames(c, b.displacement.id(), w, k, n, 3, H5T_NATIVE_FLOAT,
                   b.pending_displacement.data());
      appendFrames(c, b.von_mises.id(), w, k, n, 1, H5T_NATIVE_FLOAT, b.pending_von_mises.data());
      b.pending_points.clear();
      b.pending_displacement.clear();
      b.pending_von_mises.clear();
    }
    written_ = static_cast<long>(times_.size());
  }
}

void FrameWriter::writeXdmf() const {
  std::vector<XdmfBody> xb;
  for (const auto& bp : bodies_) {
    XdmfBody x;
    x.name = bp->name;
    x.points = bp->count();
    x.cells = bp->cells.rows();
    x.corners = static_cast<int>(bp->cells.cols());
    const std::string g = "/visualisation/" + bp->name;
    x.cells_dataset = g + "/cells";
    x.points_dataset = g + "/points";
    x.fields = {{"displacement", g + "/displacement", 3}, {"von_mises", g + "/von_mises", 1}};
    xb.push_back(x);
  }
  const std::vector<double> onDisk(times_.begin(), times_.begin() + written_);
  writeFileAtomically(xdmfPathFor(path_),
                      xdmfText(std::filesystem::path(path_).filename().string(), onDisk, xb));
}

}  // namespace ffriga
