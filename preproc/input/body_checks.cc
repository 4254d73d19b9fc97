#include "preproc/input/body_checks.h"

#include <stdexcept>

#include "common/splines/knot_vector.h"
#include "preproc/geometry/contact_region.h"
#include "preproc/geometry/size_estimate.h"

namespace ffriga {

namespace {

// The common end of the error messages about degenerate faces.
const char* const kDegenerateRule =
    "boxes and contact regions must stay off collapsed faces and seams (faces on the "
    "symmetry axis of an axisymmetric section are allowed)";

// Refuses a body whose estimated matrices and factor exceed the memory limit (key
// 'refinement'), before the refinement allocates.
void checkSizeLimit(const YamlDocument& doc, const SizeEstimate& e, double limit_bytes) {
  if (!(limit_bytes > 0.0) || e.bytes <= limit_bytes) return;
  const double GiB = 1024.0 * 1024.0 * 1024.0;
  const YAML::Node refinement = doc.root["refinement"];
  throw inputError(doc, refinement ? refinement : doc.root, "refinement",
                   Str() << "the refined body has " << e.control_points << " control points, "
                         << e.dofs << " DOFs and " << e.nonzeros << " stored entries of K: at "
                         << "least " << e.bytes / GiB << " GiB of matrices and factor, above "
                         << "the limit of " << limit_bytes / GiB << " GiB; refine less, or "
                         << "raise the limit with --max-memory GIB on a machine that has it");
}

// The exact patch of `geometry` (a built-in shape's sizes may be refused).
NurbsPatch checkedExactPatch(const BodyConfig& c) {
  try {
    return exactPatch(c.geometry);
  } catch (const std::invalid_argument& e) {
    throw inputError(c.source, c.source.root["geometry"], "geometry", e.what());
  }
}

// Degree elevation within the supported degrees, the size limit, then the refined patch.
NurbsPatch checkedRefinedPatch(const BodyConfig& c, const NurbsPatch& exact, double limit) {
  const YamlDocument& doc = c.source;
  const YAML::Node r = doc.root["refinement"];
  for (int a = 0; a < exact.paramDim(); ++a) {
    if (exact.degree(a) + c.refinement.elevate_degree[a] > kMaxDegree) {
      throw inputError(doc, r["elevate_degree"][a],
                       Str() << "refinement.elevate_degree[" << a << "]",
                       Str() << "degree " << exact.degree(a) << " + "
                             << c.refinement.elevate_degree[a] << " exceeds the maximum degree "
                             << kMaxDegree);
    }
  }
  checkSizeLimit(doc, estimateSize(exact, c.refinement), limit);  // before the refinement
  try {
    return refinedPatch(exact, c.refinement);
  } catch (const std::invalid_argument& e) {
    throw inputError(doc, r["insert"], "refinement.insert", e.what());
  }
}

// Box `member` of level b + 1 (snapped: exact bounds) off the patch's degenerate faces.
void checkBoxOffDegenerateFaces(const YamlDocument& doc, const YAML::Node& level, int b, int member,
                                const ParamBox& box, const NurbsPatch& patch) {
  for (int a = 0; a < patch.paramDim(); ++a) {
    for (const bool up : {false, true}) {
      if (up ? box.upper[a] < patch.knots(a).back() : box.lower[a] > patch.knots(a).front())
        continue;
      const std::string why = degenerateFace(patch, a, up);
      if (!why.empty()) {
        throw inputError(doc, hierarchyBoxNode(level, member)[a],
                         Str() << hierarchyBoxKey(level, b, member) << "[" << a << "]",
                         Str() << "box of level " << b + 1 << " touches the degenerate face "
                               << faceName(a, up) << " (" << why << "); " << kDegenerateRule);
      }
    }
  }
}

// The levels and the boxes of `hierarchy` (one entry per refined level) against the level grids
// of the refined patch (snapped in place), and off its degenerate faces.
void checkHierarchy(BodyConfig& c, const NurbsPatch& patch) {
  const YamlDocument& doc = c.source;
  const YAML::Node h = doc.root["hierarchy"];
  if (!h) return;
  const std::string levelProblem = checkLevels(patch, c.hierarchy.levels);
  if (!levelProblem.empty()) throw inputError(doc, h["levels"], "hierarchy.levels", levelProblem);
  const YAML::Node boxes = h["boxes"];
  const int nb = static_cast<int>(c.hierarchy.boxes.size());
  if (nb != c.hierarchy.levels - 1) {
    throw inputError(
        doc, boxes ? boxes : h["levels"], boxes ? "hierarchy.boxes" : "hierarchy.levels",
        Str() << "expected one box (or list of boxes) per refined level (" << c.hierarchy.levels - 1
              << " for levels = " << c.hierarchy.levels << "), found " << nb);
  }
  const BoxProblem problem = validateBoxes(patch, c.hierarchy);
  if (!problem.reason.empty()) {
    if (problem.box < 0) throw inputError(doc, h["levels"], "hierarchy.levels", problem.reason);
    const YAML::Node box = hierarchyBoxNode(boxes[problem.box], problem.member);
    std::string key = hierarchyBoxKey(boxes[problem.box], problem.box, problem.member);
    if (problem.dir >= 0) key = Str() << key << "[" << problem.dir << "]";
    throw inputError(doc, problem.dir < 0 ? box : box[problem.dir], key,
                     Str() << "box of level " << problem.box + 1 << ": " << problem.reason);
  }
  for (int b = 0; b < static_cast<int>(c.hierarchy.boxes.size()); ++b)
    for (int k = 0; k < static_cast<int>(c.hierarchy.boxes[b].size()); ++k)
      checkBoxOffDegenerateFaces(doc, boxes[b], b, k, c.hierarchy.boxes[b][k], patch);
}

// One contact region: its face off degenerate faces, its box inside the knot range and off
// them.
void checkContact(const YamlDocument& doc, const ContactConfig& c, const NurbsPatch& patch) {
  const YAML::Node node = contactNode(doc, c);
  const std::string face = faceName(c.direction, c.upper);
  const std::string faceWhy = degenerateFace(patch, c.direction, c.upper);
  if (!faceWhy.empty()) {
    throw inputError(
        doc, c.designed ? node : node["face"], c.key + ".face",
        Str() << "face '" << face << "' is degenerate (" << faceWhy << "); " << kDegenerateRule);
  }
  int s = 0;
  for (int a = 0; a < patch.paramDim(); ++a) {
    if (a == c.direction) continue;
    const YAML::Node region = c.designed ? node : node["region"][s];
    const std::string key = Str() << c.key << ".region[" << s << "]";
    const double lo = c.bounds[s][0], hi = c.bounds[s][1];
    const double u0 = patch.knots(a).front(), u1 = patch.knots(a).back();
    if (!(lo < hi) || lo < u0 || hi > u1) {
      throw inputError(doc, region, key,
                       Str() << "expected lo < hi inside the knot range [" << u0 << ", " << u1
                             << "] of direction " << a << ", found [" << lo << ", " << hi << "]");
    }
    for (const bool up : {false, true}) {
      if ((up ? hi < u1 : lo > u0)) continue;
      const std::string why = degenerateFace(patch, a, up);
      if (!why.empty()) {
        throw inputError(doc, region, key,
                         Str() << "the region touches the degenerate face " << faceName(a, up)
                               << " (" << why << "); " << kDegenerateRule);
      }
    }
    ++s;
  }
}

// Two regions on one face share no area: the open intervals of their boxes must miss each
// other in some direction along the face (touching is fine). Overlapping regions would
// share interface control points and collocation points: a body touched there through both
// surfaces would feel its contact pressure twice.
void checkContactOverlaps(const YamlDocument& doc, const std::vector<ContactConfig>& contacts) {
  for (std::size_t j = 1; j < contacts.size(); ++j) {
    const ContactConfig& b = contacts[j];
    for (std::size_t i = 0; i < j; ++i) {
      const ContactConfig& a = contacts[i];
      if (a.direction != b.direction || a.upper != b.upper) continue;
      bool overlap = true;
      for (std::size_t s = 0; s < a.bounds.size(); ++s)
        overlap = overlap && a.bounds[s][0] < b.bounds[s][1] && b.bounds[s][0] < a.bounds[s][1];
      if (!overlap) continue;
      const YAML::Node node = contactNode(doc, b);
      throw inputError(doc, b.designed ? node : node["region"], b.key + ".region",
                       Str() << "the region overlaps " << a.key << " ('" << a.name << "') on face "
                             << faceName(a.direction, a.upper)
                             << ": they would share interface control points and collocation "
                             << "points; make the regions disjoint (touching is fine)");
    }
  }
}

// Face markers off degenerate faces, point markers inside the knot ranges.
void checkMarkers(const BodyConfig& c, const NurbsPatch& patch) {
  const YamlDocument& doc = c.source;
  for (std::size_t i = 0; i < c.markers.size(); ++i) {
    const MarkerConfig& m = c.markers[i];
    const YAML::Node node = doc.root["markers"][i];
    const std::string key = Str() << "markers[" << i << "]";
    if (m.face) {
      const std::string why = degenerateFace(patch, m.face_direction, m.face_upper);
      if (!why.empty())
        throw inputError(doc, node["face"], key + ".face",
                         Str() << "face '" << getString(doc, node["face"], key + ".face")
                               << "' is degenerate (" << why << ")");
      continue;
    }
    for (int a = 0; a < patch.paramDim(); ++a) {
      const double v = m.parameters[a];
      if (v < patch.knots(a).front() || v > patch.knots(a).back()) {
        throw inputError(doc, node["parameters"][a], key + ".parameters",
                         Str() << "parameter " << a << " = " << v << " lies outside the knot "
                               << "range [" << patch.knots(a).front() << ", "
                               << patch.knots(a).back() << "]");
      }
    }
  }
}

}  // namespace

void checkBodyConfig(BodyConfig& c, double memory_limit_bytes) {
  const YamlDocument& doc = c.source;
  const double limit = memory_limit_bytes > 0.0 ? memory_limit_bytes : physicalMemoryBytes();
  const NurbsPatch exact = checkedExactPatch(c);
  const NurbsPatch refined = checkedRefinedPatch(c, exact, limit);
  checkHierarchy(c, refined);
  if (c.global_reference)
    checkSizeLimit(doc, estimateGlobalReferenceSize(refined, c.hierarchy), limit);
  if (!c.hierarchy.truncated && !c.global_reference) {
    try {
      HierarchicalSpace(refined, c.hierarchy);  // HB can fail (zero weights): report it now
    } catch (const std::invalid_argument& e) {
      throw inputError(doc, doc.root["hierarchy"]["truncated"], "hierarchy.truncated", e.what());
    }
  }
  for (const ContactConfig& contact : c.contacts) checkContact(doc, contact, exact);
  checkContactOverlaps(doc, c.contacts);
  checkMarkers(c, exact);
  invertStressLines(doc, exact, c.visualisation);
}

}  // namespace ffriga
