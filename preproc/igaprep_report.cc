#include "preproc/igaprep_report.h"

#include <sys/resource.h>

#include <cstdio>

#include "common/base/version.h"

namespace ffriga {

namespace {

const char* kDirectionNames[3] = {"xi", "eta", "zeta"};

double peakMemoryMiB() {
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) != 0) return -1.0;
  return u.ru_maxrss / 1024.0;  // Linux: kilobytes
}

// User + system CPU time of this process (all threads), s: next to the wall time it shows
// how much of the machine the run had.
double cpuSeconds() {
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) != 0) return -1.0;
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

void printGeometry(const BodyConfig& c, const NurbsPatch& patch, int verbosity) {
  if (verbosity == 0) return;
  const int d = patch.paramDim();
  std::printf("igaprep %s: body '%s' from %s\n", kVersion, c.name.c_str(),
              c.source.path.c_str());
  std::printf("  model      %s, geometry %s\n", toString(c.model), toString(c.geometry.kind));
  std::printf("  material   E = %.6g Pa, nu = %.6g, rho = %.6g kg/m^3\n", c.material.youngs_modulus,
              c.material.poisson_ratio, c.material.density);
  std::printf("  %-9s %7s %9s %15s\n", "direction", "degree", "elements", "control points");
  for (int a = 0; a < d; ++a) {
    std::printf("  %-9s %7d %9d %15d\n", kDirectionNames[a], patch.degree(a),
                patch.knots(a).numElements(), patch.numBasis(a));
  }
  std::printf("  %-9s %7s %9d %15d   (level 0)\n", "total", "", patch.numElements(),
              patch.numControlPoints());
  if (verbosity >= 2) {
    for (int a = 0; a < d; ++a) {
      std::printf("  knots %s:", kDirectionNames[a]);
      for (double u : patch.knots(a).knots()) std::printf(" %.6g", u);
      std::printf("\n");
    }
  }
}

void printDesign(const ImpactDesign& design) {
  std::printf("  design (derived from the body file's 'design' block):\n");
  for (const std::string& line : design.reasons) std::printf("    %s\n", line.c_str());
}

void printHierarchy(const BodyConfig& c, const HierarchicalSpace& space) {
  const int s = space.spaceDim();
  if (c.global_reference) {
    std::printf(
        "  global reference of a %d-level hierarchy: knot lines of every level inserted "
        "across the domain\n",
        c.hierarchy.levels);
  }
  std::printf("  hierarchy  %d level(s), %s\n", space.numLevels(),
              space.truncated() ? "truncated (THB)" : "non-truncated (HB)");
  std::printf("  %-6s %9s %18s  %s\n", "level", "elements", "active functions", "region");
  for (int l = 0; l < space.numLevels(); ++l) {
    std::printf("  %-6d %9d %18d  ", l, space.numElementsOnLevel(l), space.numFunctionsOnLevel(l));
    const LevelBoxes& boxes = space.region(l);
    for (std::size_t k = 0; k < boxes.size(); ++k) {
      if (k) std::printf("  and  ");
      for (int a = 0; a < space.paramDim(); ++a)
        std::printf("%s[%.9g, %.9g]", a ? " x " : "", boxes[k].lower[a], boxes[k].upper[a]);
    }
    std::printf("\n");
  }
  std::printf("  %-6s %9d %18d\n", "total", space.numElements(), space.numFunctions());
  const DofCount n = countDofs(space, c.model == ModelKind::kAxisymmetric);
  std::printf("  coincident control points: %d groups (%d points tied to another)\n", n.groups,
              n.tied);
  if (c.model == ModelKind::kAxisymmetric) {
    std::printf("  distinct control points on the axis (u_r = 0): %d\n", n.on_axis);
  }
  std::printf("  displacement DOFs: %d x %d functions = %d before tying; ndof = %d\n", s,
              space.numFunctions(), s * space.numFunctions(), n.ndof);
}

// The interface reduction (sid.h), if any: one line, its label printed with label_format.
void printInterfaceReduction(const FlexibleBodySid& s, const char* label_format) {
  if (s.characteristic_modes == 0 && s.patch_modes == 0) return;
  std::printf(label_format, "interface reduction");
  std::printf(
      "%d interface DOFs -> %d characteristic modes (rigid ones included) + %d pressure "
      "patch modes",
      s.interface_dofs, s.characteristic_modes, s.patch_modes);
  if (s.interface_compliance_error >= 0.0)
    std::printf("; static compliance missed <= %.3g", s.interface_compliance_error);
  std::printf("\n");
}

void printSidSummary(const FlexibleBodySid& s, const std::string& path) {
  std::printf("SID file %s (%s)\n", path.c_str(), s.created_by.c_str());
  std::printf("  body                 %s (%s, %dD data), from %s\n", s.name.c_str(),
              toString(s.model), s.space_dim, s.input_path.c_str());
  std::printf("  ndof                 %d\n", s.ndof);
  std::printf("  elements / levels    %d / %d\n", s.n_elements, s.nlvl);
  std::printf("  reduction            %s, frame %s\n", toString(s.reduction), toString(s.frame));
  std::printf("  nq                   %d = %d normal + %d constraint - %d rigid\n", s.nq(),
              s.normal_modes, s.constraint_modes, s.rigid_modes_dropped);
  std::printf("  interface points     %d\n", s.n_interface_control_points);
  printInterfaceReduction(s, "  %-20s ");
  if (s.nq() > 0) {
    std::printf("  frequencies          %.6g .. %.6g Hz\n", s.frequencies_hz.minCoeff(),
                s.frequencies_hz.maxCoeff());
    int damped = 0;
    for (int i = 0; i < s.nq(); ++i) damped += s.damping_ratio(i) > 0.0;
    std::printf("  damped modes         %d of %d\n", damped, s.nq());
  }
  std::printf("  material             E = %.6g Pa, nu = %.6g, rho = %.6g kg/m^3\n",
              s.material.youngs_modulus, s.material.poisson_ratio, s.material.density);
  std::printf("  geometry             %s", s.geometry.type.c_str());
  if (s.geometry.radius > 0.0) std::printf(", radius %.6g m", s.geometry.radius);
  if (s.geometry.length > 0.0) std::printf(", length %.6g m", s.geometry.length);
  std::printf("\n");
  if (s.design.present) {
    std::printf("  design               contact radius %.6g m, N = %.4g, finest %.4g m",
                s.design.contact_radius, s.design.elements_per_contact_radius,
                s.design.finest_element);
    if (s.design.approach_speed > 0.0) std::printf(", impact at %.6g m/s", s.design.approach_speed);
    std::printf("\n");
    if (s.design.contact_minor_radius > 0.0 &&
        s.design.contact_minor_radius < s.design.contact_radius)
      std::printf("                       elliptical: semi-axes %.6g x %.6g m\n",
                  s.design.contact_radius, s.design.contact_minor_radius);
    if (s.design.surface_radius > 0.0 && s.geometry.type == "nurbs")
      std::printf("                       surface radius %.6g m at the contact point\n",
                  s.design.surface_radius);
    if (s.design.mode_cutoff_hz > 0.0)
      std::printf("                       normal modes: every one below %.6g Hz\n",
                  s.design.mode_cutoff_hz);
  }
  if (s.mesh.empty()) {
    std::printf("  visualisation mesh   none\n");
  } else {
    std::printf("  visualisation mesh   %d points, %d cells (%d per element and direction)\n",
                static_cast<int>(s.mesh.samples.points.rows()), static_cast<int>(s.mesh.cells.rows()),
                s.mesh.subdivisions);
  }
  for (const auto& l : s.stress_lines) {
    std::printf("  stress line          '%s': %d points\n", l.name.c_str(),
                static_cast<int>(l.samples.points.rows()));
  }
  std::printf("  mass                 %.10g kg\n", s.mass);
  std::printf("  frame origin         (%.6g, %.6g, %.6g) m\n", s.frame_origin(0), s.frame_origin(1),
              s.frame_origin(2));
  std::printf("  inertia diag         (%.6g, %.6g, %.6g) kg m^2\n", s.inertia(0, 0),
              s.inertia(1, 1), s.inertia(2, 2));
  std::printf("  control points       %d\n", static_cast<int>(s.control_points.rows()));
  for (const auto& c : s.surfaces) {
    std::printf("  contact surface      '%s': %zu elements, %zu functions, %d collocation points\n",
                c.name.c_str(), c.element_level.size(), c.functions.size(),
                static_cast<int>(c.collocation_points.rows()));
  }
  for (const auto& m : s.markers) std::printf("  marker               '%s'\n", m.name.c_str());
  std::printf("  preprocessing time   %.3f s\n", s.preprocessing_time_s);
  for (const auto& [stage, t] : s.stage_times_s)
    std::printf("    %-18s %.3f s\n", stage.c_str(), t);
}

void printPreprocessSummary(const BodyConfig& config, const FlexibleBodySid& sid,
                            const PreprocessSummary& summary, const std::string& output,
                            double write_s, double total_s) {
  std::printf("igaprep %s: %s -> %s\n", kVersion, config.source.path.c_str(), output.c_str());
  std::printf("  %-28s %s, %s frame\n", "model", toString(sid.model), toString(sid.frame));
  if (config.design) {
    std::printf("  %-28s a = %.6g m, %d levels, finest %.4g m (a / %.4g)\n", "design",
                config.design->contact_radius, config.hierarchy.levels, sid.design.finest_element,
                config.design->contact_radius / sid.design.finest_element);
  }
  std::printf("  %-28s %d (%d control points, %d tied, %d fixed on the axis)\n", "ndof",
              summary.ndof, summary.num_control_points, summary.tied_points, summary.fixed_dofs);
  std::printf("  %-28s %d (%d DOFs)\n", "interface control points",
              summary.interface_control_points, summary.interface_dofs);
  std::printf("  %-28s %d = %d normal + %d constraint - %d rigid\n", "nq", sid.nq(),
              sid.normal_modes, sid.constraint_modes, sid.rigid_modes_dropped);
  printInterfaceReduction(sid, "  %-28s ");
  if (sid.nq() > 0) {
    std::printf("  %-28s %.6g .. %.6g Hz\n", "frequencies", sid.frequencies_hz.minCoeff(),
                sid.frequencies_hz.maxCoeff());
  }
  std::printf("  %-28s %.10g kg\n", "mass", sid.mass);
  for (const auto& [stage, t] : sid.stage_times_s)
    std::printf("  time %-23s %.3f s\n", stage.c_str(), t);
  std::printf("  time %-23s %.3f s\n", "write", write_s);
  std::printf("  %-28s %.3f s\n", "total wall time", total_s);
  std::printf("  %-28s %.3f s\n", "total CPU time", cpuSeconds());
  std::printf("  %-28s %.1f MiB\n", "peak memory", peakMemoryMiB());
}

}  // namespace ffriga
