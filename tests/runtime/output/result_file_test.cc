#include <sys/resource.h>

#include <csignal>
#include <cstdio>
#include <filesystem>

#include <catch2/catch.hpp>

#include "common/base/error.h"
#include "runtime/bodies/floating_body.h"
#include "runtime/output/result_writer.h"
#include "runtime/simulation/output_sampler.h"
#include "runtime/simulation/simulation.h"
#include "tests/support/synthetic_bodies.h"

using namespace ffriga;

namespace {

// Reads a whole double dataset (rows x cols; cols = 1 for 1D).
Eigen::MatrixXd readDataset(hid_t file, const std::string& name) {
  const h5::Context c{"test"};
  h5::Handle ds(c.check(H5Dopen2(file, name.c_str(), H5P_DEFAULT), "open " + name), H5Dclose);
  h5::Handle space(H5Dget_space(ds.id()), H5Sclose);
  hsize_t dims[2] = {0, 1};
  const int rank = H5Sget_simple_extent_dims(space.id(), dims, nullptr);
  if (rank == 1) dims[1] = 1;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> m(dims[0], dims[1]);
  if (dims[0] > 0)
    c.check(H5Dread(ds.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, m.data()),
            "read " + name, 0);
  return m;
}

// Free fall of a rigid body; the system asks for an interrupt once t passes `stop_at`.
class FallingBody : public MultibodySystem {
 public:
  explicit FallingBody(double stop_at) : stop_at_(stop_at) {
    addBody(std::make_unique<FloatingBody3d>(
        "ball", std::make_shared<FlexibleBodySid>(test::rigidBody(1.0, {0.1, 0.1, 0.1}))));
    setGravity({0.0, 0.0, -9.81});
  }
  void rhs(double t, const double* y, double* ydot) override {
    if (t > stop_at_) requestInterrupt();
    MultibodySystem::rhs(t, y, ydot);
  }

 private:
  double stop_at_;
};

SimulationConfig settings() {
  SimulationConfig s;
  s.end_time = 0.5;
  s.output_interval = 0.05;
  s.integrator.rtol = 1e-10;
  s.integrator.atol = Eigen::VectorXd::Constant(13, 1e-12);
  s.verbosity = 0;
  return s;
}

Eigen::VectorXd initialState() {
  Eigen::VectorXd y0(13);
  y0 << 0, 0, 10, 1, 0, 0, 0, 1.0, 0, 0, 0, 0, 0;
  return y0;
}

}  // namespace

TEST_CASE("result file: round trip of a free fall", "[result]") {
  const std::string path = "result_roundtrip_test.h5";
  FallingBody sys(1e9);
  {
    ResultWriter w(path, outputLayout(sys), "unit test", "scene: none\n", FlushConfig{});
    const SimulationReport r = simulate(sys, initialState(), settings(), w);
    REQUIRE(r.completed);
    w.close();
  }
  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  REQUIRE(f.id() >= 0);
  REQUIRE(h5::readStringAttribute(h5::Context{path}, f.id(), "format") == kResultFormat);
  REQUIRE(h5::readStringAttribute(h5::Context{path}, f.id(), "status") == "completed");
  REQUIRE(h5::readStringAttribute(h5::Context{path}, f.id(), "scene_yaml") == "scene: none\n");
  const Eigen::MatrixXd t = readDataset(f.id(), "time");
  const Eigen::MatrixXd r = readDataset(f.id(), "bodies/ball/position");
  REQUIRE(t.rows() == 11);
  REQUIRE(r.rows() == 11);
  REQUIRE(r.cols() == 3);
  for (int i = 0; i < t.rows(); ++i) {
    REQUIRE(t(i, 0) == Approx(0.05 * i).margin(1e-15));
    // Interpolated output of an exact-polynomial solution with rtol 1e-10: 1e-8 m is safe.
    REQUIRE(std::abs(r(i, 0) - t(i, 0)) < 1e-8);
    REQUIRE(std::abs(r(i, 2) - (10.0 - 0.5 * 9.81 * t(i, 0) * t(i, 0))) < 1e-8);
  }
  const Eigen::MatrixXd ek = readDataset(f.id(), "energy/kinetic");
  const Eigen::MatrixXd eg = readDataset(f.id(), "energy/gravity");
  // Energy balance of the free fall: same integration error budget.
  REQUIRE(std::abs((ek(10, 0) + eg(10, 0)) - (ek(0, 0) + eg(0, 0))) < 1e-6);
  std::remove(path.c_str());
}

TEST_CASE("result file: an interrupted run leaves a readable file", "[result]") {
  const std::string path = "result_interrupted_test.h5";
  clearInterrupt();
  FallingBody sys(0.2);
  {
    ResultWriter w(path, outputLayout(sys), "unit test", "", FlushConfig{});
    const SimulationReport r = simulate(sys, initialState(), settings(), w);
    REQUIRE(r.interrupted);
    REQUIRE_FALSE(r.completed);
    // No explicit close: the writer's destructor (as on any exit path) closes the file.
  }
  clearInterrupt();
  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  REQUIRE(f.id() >= 0);
  const std::string status = h5::readStringAttribute(h5::Context{path}, f.id(), "status");
  REQUIRE(status.rfind("interrupted by SIGINT at t = ", 0) == 0);
  const Eigen::MatrixXd t = readDataset(f.id(), "time");
  REQUIRE(t.rows() >= 4);  // outputs up to ~0.2 s
  REQUIRE(t.rows() < 11);  // but not the whole run
  REQUIRE(readDataset(f.id(), "bodies/ball/position").rows() == t.rows());
  std::remove(path.c_str());
}

TEST_CASE("result file: SWMR mode keeps the final attributes for the close", "[result]") {
  const std::string path = "result_swmr_test.h5";
  FallingBody sys(1e9);
  {
    ResultWriter w(path, outputLayout(sys), "unit test", "", FlushConfig{});
    w.startSwmr();
    REQUIRE(w.file().swmr());
    const SimulationReport r = simulate(sys, initialState(), settings(), w);
    REQUIRE(r.completed);
    // In SWMR mode a new attribute cannot be written: it is kept for the close.
    w.file().setAttribute("test_figure", 2.5);
    w.close();
  }
  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  REQUIRE(f.id() >= 0);  // closed: no SWMR needed to read it
  const h5::Context c{path};
  REQUIRE(h5::readStringAttribute(c, f.id(), "status") == "completed");
  REQUIRE(h5::readDoubleAttribute(c, f.id(), "test_figure") == 2.5);
  REQUIRE(readDataset(f.id(), "time").rows() == 11);
  std::remove(path.c_str());
}

TEST_CASE("result file: a file size limit stops the rows between two flushes", "[result]") {
  const std::string path = "result_size_limit_test.h5";
  FallingBody sys(1e9);
  ResultWriter w(path, outputLayout(sys), "unit test", "", FlushConfig{});
  w.startSwmr();
  const OutputSample sample = outputSample(sys, 0.0, initialState());
  for (int i = 0; i < 20; ++i) w.append(sample);
  w.flush();
  const long flushed = w.rows();
  // A limit just above the file's size: the next flush's reservation cannot be made.
  struct rlimit old;
  REQUIRE(getrlimit(RLIMIT_FSIZE, &old) == 0);
  void (*previous)(int) = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit tight = old;
  tight.rlim_cur = static_cast<rlim_t>(std::filesystem::file_size(path) + 4096);
  REQUIRE(setrlimit(RLIMIT_FSIZE, &tight) == 0);
  bool refused = false;
  try {
    for (int i = 0; i < 300; ++i) w.append(sample);  // 16 rows per flush: the limit is met
    w.flush();
  } catch (const ComputeError& e) {
    refused = std::string(e.what()).find("file size limit") != std::string::npos;
  }
  REQUIRE(setrlimit(RLIMIT_FSIZE, &old) == 0);
  std::signal(SIGXFSZ, previous);
  CHECK(refused);
  w.file().setAttribute("status", std::string("failed: size limit"));
  w.close();
  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  REQUIRE(f.id() >= 0);
  REQUIRE(h5::readStringAttribute(h5::Context{path}, f.id(), "status") == "failed: size limit");
  const long rows = readDataset(f.id(), "time").rows();
  CHECK(rows >= flushed);  // every row of the flushes before the limit
  CHECK(rows < flushed + 300);
  std::remove(path.c_str());
}

namespace {

// Two contact pairs as the outputs see them: "ab" with both roles (3 + 2 points, factor 1/2)
// and "floor" with one role (2 points); no bodies.
OutputLayout twoPairs() {
  OutputLayout layout;
  layout.state_size = 1;
  ConnectionLayout ab("ab", "contact", "a", "b", 1e17);
  ConnectionLayout floor("floor", "contact", "a", "plane", 1e17);
  ab.collocation_role = {0, 0, 0, 1, 1};
  ab.collocation_weight = Eigen::VectorXd::LinSpaced(5, 1e-9, 5e-9);
  ab.role_factor = 0.5;
  floor.collocation_role = {0, 0};
  floor.collocation_weight = Eigen::VectorXd::Constant(2, 2e-9);
  layout.contacts = {ab, floor};
  return layout;
}

PressureSample pressureSample(int n, double scale) {
  PressureSample s;
  s.position = scale * Eigen::MatrixXd::Random(n, 3);
  s.pressure = scale * Eigen::VectorXd::LinSpaced(n, 0.0, 2e9);
  s.normal = Eigen::MatrixXd::Zero(n, 3);
  s.normal.col(1).setOnes();
  return s;
}

}  // namespace

TEST_CASE("result file: each pair's pressure field at its force peak, in place, over a restart",
          "[result]") {
  const std::string path = "result_peak_pressure_test.h5";
  const OutputLayout layout = twoPairs();
  const PressureSample first = pressureSample(5, 1.0), larger = pressureSample(5, 2.0);
  {
    ResultWriter w(path, layout, "unit test", "", FlushConfig{});
    w.startSwmr();  // the groups exist before: written in place from now on
    CHECK(w.pressurePeakForce(0) == 0.0);
    w.recordPressurePeak(0, 1e-5, 100.0, first);
    w.flush();
    w.recordPressurePeak(0, 2e-5, 150.0, larger);
    CHECK(w.pressurePeakForce(0) == 150.0);
    CHECK(w.pressurePeakForce(1) == 0.0);
    w.close();
  }
  auto check = [&](const PressureSample& expected, double time, double force) {
    h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    REQUIRE(f.id() >= 0);
    const h5::Context c{path};
    h5::Handle g = h5::openGroup(c, f.id(), "contacts/ab/peak_pressure");
    CHECK(h5::readDoubleAttribute(c, g.id(), "time_s") == time);
    CHECK(h5::readDoubleAttribute(c, g.id(), "normal_force_N") == force);
    CHECK(h5::readDoubleAttribute(c, g.id(), "role_factor") == 0.5);
    CHECK(readDataset(g.id(), "position") == expected.position);
    CHECK(readDataset(g.id(), "pressure") == expected.pressure);
    CHECK(readDataset(g.id(), "normal") == expected.normal);
    CHECK(readDataset(g.id(), "weight") == layout.contacts[0].collocation_weight);
    CHECK(h5::readInts(c, g.id(), "role") == layout.contacts[0].collocation_role);
    h5::Handle p(H5Dopen2(g.id(), "pressure", H5P_DEFAULT), H5Dclose);
    CHECK(h5::readStringAttribute(c, p.id(), "unit") == "Pa");
    // The pair that never touched has no group.
    CHECK_FALSE(h5::exists(f.id(), "contacts/floor/peak_pressure"));
  };
  check(larger, 2e-5, 150.0);
  // A restart keeps the recorded peak: a smaller force is no peak, a larger one replaces it.
  RestartRecord resume;
  resume.state = Eigen::VectorXd::Zero(1);
  {
    ResultWriter w(path, layout, "unit test", "", FlushConfig{}, &resume);
    w.startSwmr();
    CHECK(w.pressurePeakForce(0) == 150.0);
    w.close();
  }
  check(larger, 2e-5, 150.0);
  std::remove(path.c_str());
}
