// Scene files of ffrsim (schemas/scene.schema.json): bodies (flexible or frozen from SID
// files, or rigid ones given in the scene) with their initial state, joints, force
// elements, contact pairs, gravity, sensors, damping overrides, integrator and output
// settings.
//
// Checks, in this order, each error naming the scene file, the YAML line and the key (exit 2):
//   1. the schema (types, ranges: a penalty factor <= 0 is rejected here),
//   2. names: unique body names, contact pairs naming known and distinct bodies,
//   3. SID files: a relative name resolves against the scene file's folder, then against
//      each --sid-path folder in turn; the first existing file is used,
//   4. the SIDs themselves (loaded by the SidLoader given by the caller, e.g. readSid of
//      common/sid/sid_file.h; its InputError gets the scene's file, line and key prepended),
//   5. consistency: axisymmetric bodies only with their own kind, sizes of q / qdot,
//      axisymmetric bodies on the y axis, contact surfaces present,
//   6. joints and force elements (system/scene_multibody.cc): ends naming known bodies and
//      markers, no joint from a body to itself, axes where the type needs one; initial
//      joint angles assembled; the initial state satisfying every joint (positions to
//      1e-9 m, directions to 1e-9, velocities to 1e-9 m/s) and no redundant joint.
// Initial velocity and angular velocity are given in inertial components and converted to
// the body components of the state (Eq. 1).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/input/yaml_input.h"
#include "common/sid/sid.h"
#include "runtime/output/result_writer.h"
#include "runtime/scene/scene_bodies.h"
#include "runtime/simulation/simulation.h"
#include "runtime/system/multibody_system.h"
#include "runtime/system/static_preload.h"

namespace ffriga {

struct Scene {
  YamlDocument doc;
  std::string name;
  std::unique_ptr<MultibodySystem> system;
  Eigen::VectorXd y0;
  SimulationConfig settings;
  FlushConfig flush;  // outputs.flush_rows, outputs.flush_interval
  std::vector<std::string> sid_files;  // resolved path of each body's SID
  // Initial reference position (m) and velocity (m/s) of each body, inertial components,
  // as given in the scene.
  std::vector<Eigen::Vector3d> initial_position;
  std::vector<Eigen::Vector3d> initial_velocity;
  std::vector<Eigen::Matrix3d> initial_rotation;  // body to inertial components
  bool static_preload = false;  // the scene asked for it; then `preload` says how it went
  PreloadReport preload;
  // Warnings about the model (runtime/bodies/quasi_static_rule.h), one line each; ffrsim
  // prints them and stores them in the result file (root attribute `warnings`).
  std::vector<std::string> warnings;
  VisualisationFramesConfig visualisation;  // outputs.visualisation
};

// sets: command-line overrides "KEY=VALUE" (common/input/yaml_overrides.h), applied before the
// schema check.
Scene loadScene(const std::string& path, const std::vector<std::string>& sid_paths,
                const SidLoader& load_sid, const std::vector<std::string>& sets = {});

// The same for a document already in memory (tests); relative SID names resolve against
// the folder of doc.path.
Scene buildScene(YamlDocument doc, const std::vector<std::string>& sid_paths,
                 const SidLoader& load_sid);

}  // namespace ffriga
