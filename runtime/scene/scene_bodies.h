// The bodies of a scene (schemas/scene.schema.json `bodies`) for runtime/scene/scene.cc: their
// data (SID files resolved and read, frozen SIDs, rigid bodies given in the scene), their
// initial pose and the body models with the scene's damping and quasi-static choices; each
// error names the scene file, the YAML line and the key.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/input/yaml_input.h"
#include "common/sid/sid.h"
#include "common/sid/sid_file.h"
#include "runtime/bodies/body_model.h"

namespace ffriga {

// Reads the SID file at `path`; `content` is SidContent::kWithoutMesh when the scene draws
// no visualisation frames (the loader may then skip the mesh's sampled modes).
using SidLoader = std::function<FlexibleBodySid(const std::string& path, SidContent content)>;

// Initial pose of one body while the scene is assembled: inertial components.
struct InitialPose {
  Eigen::Vector3d r, v, w;  // position (m), velocity (m/s), angular velocity (rad/s)
  Eigen::Matrix3d A;        // body -> inertial
  Eigen::VectorXd q, qd;
};

// Unique body and obstacle names ("ground" reserved) and contact pairs of known, distinct
// bodies or a body and an obstacle: the index of each body by name.
std::map<std::string, int> checkBodyNames(const YamlDocument& doc);

// A contact pair's entry BODY or BODY.REGION (contacts[].bodies[i]): the body (or obstacle)
// name and the contact region's name ("" if none is given).
std::string pairBodyName(const std::string& entry);
std::string pairRegionName(const std::string& entry);

// The body data: SID files (all resolved before any is read, so that a missing file is
// reported at once; `files` gets each body's path, "" for rigid bodies), frozen SIDs, rigid
// bodies defined in the scene. Bodies of one SID file share its data.
std::vector<std::shared_ptr<FlexibleBodySid>> loadBodyData(
    const YamlDocument& doc, const std::vector<std::string>& sid_paths, const SidLoader& load_sid,
    std::vector<std::string>& files);

// Body b's initial pose as the scene gives it (q and qdot of the SID's size).
InitialPose readInitialPose(const YamlDocument& doc, int b, const FlexibleBodySid& sid);

// Body b's model: flexible 3D or, in an axisymmetric scene, axisymmetric (its axis on the
// inertial y axis), with the scene's damping override and quasi-static coordinates.
std::unique_ptr<BodyModel> makeBody(const YamlDocument& doc, int b,
                                    std::shared_ptr<const FlexibleBodySid> sid, bool axisymmetric,
                                    const InitialPose& pose);

}  // namespace ffriga
