#include "common/sid/sid_file.h"

#include <cmath>
#include <cstdio>
#include <fstream>

#include <unistd.h>

#include "common/base/error.h"
#include "common/sid/hdf5_io.h"
#include "common/base/provenance.h"

namespace ffriga {

namespace {

using h5::Context;
using h5::Handle;

// Real data read from a SID must be finite: a NaN or an infinity (a damaged or hand-edited
// file) would reach the integrator and fail far from its cause, or not at all.
std::string nonFiniteText(double v) {
  return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
}

[[noreturn]] void notFinite(const Context& c, const std::string& what, double v,
                            const std::string& at) {
  c.fail(Str() << what << ": expected a finite number, found " << nonFiniteText(v) << at);
}

// A matrix or vector read from dataset `path`; the first bad entry by its 0-based index in
// the file ([row, column] or [i]).
template <typename Derived>
void requireFinite(const Context& c, const std::string& path, const Eigen::DenseBase<Derived>& m) {
  if (m.allFinite()) return;
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.cols(); ++j) {
      if (std::isfinite(m(i, j))) continue;
      const std::string at = Derived::ColsAtCompileTime == 1
                                 ? std::string(Str() << " at [" << i << "]")
                                 : std::string(Str() << " at [" << i << ", " << j << "]");
      notFinite(c, "dataset '" + path + "'", m(i, j), at);
    }
  }
}

// A dataset of any rank read as a flat row-major array with its dimensions.
void requireFinite(const Context& c, const std::string& path, const std::vector<double>& data,
                   const std::vector<hsize_t>& dims) {
  for (std::size_t k = 0; k < data.size(); ++k) {
    if (std::isfinite(data[k])) continue;
    std::vector<hsize_t> index(dims.size());
    for (std::size_t d = dims.size(), rest = k; d-- > 0; rest /= dims[d]) index[d] = rest % dims[d];
    Str at;
    at << " at [";
    for (std::size_t d = 0; d < index.size(); ++d) at << (d ? ", " : "") << index[d];
    notFinite(c, "dataset '" + path + "'", data[k], at.str() + "]");
  }
}

// The checked readers: `group` is the group's path in the file ("/sid"), for messages.
double finiteScalar(const Context& c, hid_t g, const std::string& group, const std::string& name) {
  const double v = h5::readScalar(c, g, name);
  if (!std::isfinite(v)) notFinite(c, "dataset '" + group + "/" + name + "'", v, "");
  return v;
}

Eigen::VectorXd finiteVector(const Context& c, hid_t g, const std::string& group,
                             const std::string& name) {
  Eigen::VectorXd v = h5::readVector(c, g, name);
  requireFinite(c, group + "/" + name, v);
  return v;
}

Eigen::MatrixXd finiteMatrix(const Context& c, hid_t g, const std::string& group,
                             const std::string& name) {
  Eigen::MatrixXd m = h5::readMatrix(c, g, name);
  requireFinite(c, group + "/" + name, m);
  return m;
}

void writeSurface(const Context& c, hid_t parent, const ContactSurface& s) {
  Handle g = h5::createGroup(c, parent, s.name);
  h5::writeAttribute(c, g, "dim", s.dim);
  h5::writeAttribute(c, g, "outward_sign", s.outward_sign);
  h5::writeAttribute(c, g, "collocation_note",
                     s.collocation_points.rows() == 0
                         ? std::string("collocation points not computed: they come with the "
                                       "hierarchical contact surface (Botella points, issue 3)")
                     : s.collocation_rule == CollocationRule::kGauss
                         ? std::string("Gauss-Legendre points, p + 1 per direction and element, "
                                       "weights: quadrature weight x surface Jacobian")
                         : std::string("Botella points"));
  h5::writeInts(c, g, "degrees", s.degrees);
  h5::writeMatrix(c, g, "element_lower", s.element_lower, "1");
  h5::writeMatrix(c, g, "element_upper", s.element_upper, "1");
  h5::writeInts(c, g, "element_level", s.element_level);
  h5::writeInts(c, g, "function_offsets", s.function_offsets);
  h5::writeInts(c, g, "functions", s.functions);
  // Extraction operators stacked: rows function_offsets[e] .. [e + 1] belong to element e.
  int nbern = 1;
  for (int p : s.degrees) nbern *= p + 1;
  Eigen::MatrixXd C(s.functions.size(), nbern);
  for (std::size_t e = 0; e < s.extraction.size(); ++e) {
    C.middleRows(s.function_offsets[e], s.extraction[e].rows()) = s.extraction[e];
  }
  h5::writeMatrix(c, g, "extraction", C, "1");
  h5::writeMatrix(c, g, "collocation_points", s.collocation_points, "1");
  h5::writeInts(c, g, "collocation_element", s.collocation_element);
  h5::writeVector(c, g, "collocation_weights", s.collocation_weights, s.dim == 2 ? "m^2" : "m");
}

ContactSurface readSurface(const Context& c, hid_t parent, const std::string& name) {
  Handle g = h5::openGroup(c, parent, name);
  const std::string where = "/contact_surfaces/" + name;
  ContactSurface s;
  s.name = name;
  s.dim = h5::readIntAttribute(c, g, "dim");
  s.outward_sign = h5::readDoubleAttribute(c, g, "outward_sign");
  if (!std::isfinite(s.outward_sign))
    notFinite(c, "attribute '" + where + "/outward_sign'", s.outward_sign, "");
  s.degrees = h5::readInts(c, g, "degrees");
  s.element_lower = finiteMatrix(c, g, where, "element_lower");
  s.element_upper = finiteMatrix(c, g, where, "element_upper");
  s.element_level = h5::readInts(c, g, "element_level");
  s.function_offsets = h5::readInts(c, g, "function_offsets");
  s.functions = h5::readInts(c, g, "functions");
  const Eigen::MatrixXd C = finiteMatrix(c, g, where, "extraction");
  for (std::size_t e = 0; e + 1 < s.function_offsets.size(); ++e) {
    const int a = s.function_offsets[e], b = s.function_offsets[e + 1];
    if (a < 0 || b < a || b > C.rows())
      c.fail("contact surface " + name + ": bad function_offsets");
    s.extraction.push_back(C.middleRows(a, b - a));
  }
  s.collocation_points = finiteMatrix(c, g, where, "collocation_points");
  s.collocation_element = h5::readInts(c, g, "collocation_element");
  s.collocation_weights = finiteVector(c, g, where, "collocation_weights");
  return s;
}

// single: the modes in single precision (the visualisation mesh: pictures, half the size).
void writeSamples(const Context& c, hid_t g, const SampledModes& m, bool single) {
  h5::writeMatrix(c, g, "points", m.points, "m");
  h5::writeMatrix(c, g, "parameters", m.parameters, "1");
  h5::writeMatrix(c, g, "Phi", m.Phi, "kg^(-1/2)", single);
  h5::writeMatrix(c, g, "stress", m.stress, "Pa kg^(-1/2) m^(-1)", single);
}

SampledModes readSamples(const Context& c, hid_t g, const std::string& where, int s, int nq) {
  SampledModes m;
  m.points = finiteMatrix(c, g, where, "points");
  m.parameters = finiteMatrix(c, g, where, "parameters");
  m.Phi = finiteMatrix(c, g, where, "Phi");
  m.stress = finiteMatrix(c, g, where, "stress");
  const Eigen::Index np = m.points.rows();
  if (m.points.cols() != s || m.parameters.rows() != np || m.Phi.rows() != np * s ||
      m.Phi.cols() != nq || m.stress.rows() != np * 6 || m.stress.cols() != nq) {
    c.fail(Str() << where << ": points, parameters, Phi and stress disagree in size (" << np
                 << " points, " << s << " coordinates, nq = " << nq << ")");
  }
  return m;
}

void writeBodyDescription(const Context& c, hid_t file, const FlexibleBodySid& sid) {
  Handle m = h5::createGroup(c, file, "material");
  h5::writeScalar(c, m, "youngs_modulus", sid.material.youngs_modulus, "Pa");
  h5::writeScalar(c, m, "poisson_ratio", sid.material.poisson_ratio, "1");
  h5::writeScalar(c, m, "density", sid.material.density, "kg m^-3");
  Handle g = h5::createGroup(c, file, "geometry");
  h5::writeAttribute(c, g, "type", sid.geometry.type);
  h5::writeScalar(c, g, "radius", sid.geometry.radius, "m");
  h5::writeScalar(c, g, "length", sid.geometry.length, "m");
  h5::writeVector(c, g, "centre", sid.geometry.centre, "m");
  if (sid.design.present) {
    Handle d = h5::createGroup(c, file, "design");
    h5::writeScalar(c, d, "contact_radius", sid.design.contact_radius, "m");
    h5::writeScalar(c, d, "elements_per_contact_radius", sid.design.elements_per_contact_radius,
                    "1");
    h5::writeScalar(c, d, "finest_element", sid.design.finest_element, "m");
    h5::writeScalar(c, d, "approach_speed", sid.design.approach_speed, "m/s");
    h5::writeScalar(c, d, "max_pressure", sid.design.max_pressure, "Pa");
    h5::writeScalar(c, d, "surface_radius", sid.design.surface_radius, "m");
    h5::writeVector(c, d, "contact_point", sid.design.contact_point, "m");
    h5::writeVector(c, d, "contact_normal", sid.design.contact_normal, "1");
    h5::writeScalar(c, d, "contact_minor_radius", sid.design.contact_minor_radius, "m");
    h5::writeScalar(c, d, "hertz_max_force", sid.design.hertz_max_force, "N");
    h5::writeScalar(c, d, "hertz_duration", sid.design.hertz_duration, "s");
    h5::writeScalar(c, d, "mode_cutoff_hz", sid.design.mode_cutoff_hz, "Hz");
    if (sid.design.principal_curvatures.size() == 2)
      h5::writeVector(c, d, "principal_curvatures", sid.design.principal_curvatures, "1/m");
    if (sid.design.principal_direction.size() == 3)
      h5::writeVector(c, d, "principal_direction", sid.design.principal_direction, "1");
  }
  if (!sid.mesh.empty()) {
    Handle v = h5::createGroup(c, file, "visualisation");
    h5::writeAttribute(c, v, "subdivisions", sid.mesh.subdivisions);
    h5::writeIntMatrix(c, v, "cells", sid.mesh.cells);
    writeSamples(c, v, sid.mesh.samples, true);
  }
  Handle l = h5::createGroup(c, file, "stress_lines");
  for (const StressLine& line : sid.stress_lines) {
    Handle lg = h5::createGroup(c, l, line.name);
    h5::writeVector(c, lg, "from", line.from, "m");
    h5::writeVector(c, lg, "to", line.to, "m");
    writeSamples(c, lg, line.samples, false);
  }
}

void readBodyDescription(const Context& c, hid_t file, SidContent content, FlexibleBodySid* sid) {
  const int s = sid->space_dim, nq = sid->nq();
  Handle m = h5::openGroup(c, file, "material");
  sid->material.youngs_modulus = finiteScalar(c, m, "/material", "youngs_modulus");
  sid->material.poisson_ratio = finiteScalar(c, m, "/material", "poisson_ratio");
  sid->material.density = finiteScalar(c, m, "/material", "density");
  Handle g = h5::openGroup(c, file, "geometry");
  sid->geometry.type = h5::readStringAttribute(c, g, "type");
  sid->geometry.radius = finiteScalar(c, g, "/geometry", "radius");
  sid->geometry.length = finiteScalar(c, g, "/geometry", "length");
  const Eigen::VectorXd centre = finiteVector(c, g, "/geometry", "centre");
  if (centre.size() != 3) c.fail("/geometry/centre must have 3 components");
  sid->geometry.centre = centre;
  if (h5::exists(file, "design")) {
    Handle d = h5::openGroup(c, file, "design");
    sid->design.present = true;
    sid->design.contact_radius = finiteScalar(c, d, "/design", "contact_radius");
    sid->design.elements_per_contact_radius =
        finiteScalar(c, d, "/design", "elements_per_contact_radius");
    sid->design.finest_element = finiteScalar(c, d, "/design", "finest_element");
    sid->design.approach_speed = finiteScalar(c, d, "/design", "approach_speed");
    sid->design.max_pressure = finiteScalar(c, d, "/design", "max_pressure");
    // Added on 2026-12-07 within version 3: each read where present.
    const auto optional = [&](const char* name, double fallback) {
      return h5::exists(d, name) ? finiteScalar(c, d, "/design", name) : fallback;
    };
    sid->design.surface_radius = optional("surface_radius", 0.0);
    sid->design.contact_minor_radius = optional("contact_minor_radius", sid->design.contact_radius);
    sid->design.hertz_max_force = optional("hertz_max_force", 0.0);
    sid->design.hertz_duration = optional("hertz_duration", 0.0);
    sid->design.mode_cutoff_hz = optional("mode_cutoff_hz", 0.0);
    const auto optionalVector = [&](const char* name, int size, Eigen::VectorXd* out) {
      if (!h5::exists(d, name)) return;
      *out = finiteVector(c, d, "/design", name);
      if (out->size() != size)
        c.fail(Str() << "/design/" << name << " must have " << size << " components");
    };
    optionalVector("contact_point", 3, &sid->design.contact_point);
    optionalVector("contact_normal", 3, &sid->design.contact_normal);
    optionalVector("principal_curvatures", 2, &sid->design.principal_curvatures);
    optionalVector("principal_direction", 3, &sid->design.principal_direction);
  }
  if (content == SidContent::kAll && h5::exists(file, "visualisation")) {
    Handle v = h5::openGroup(c, file, "visualisation");
    sid->mesh.subdivisions = h5::readIntAttribute(c, v, "subdivisions");
    sid->mesh.cells = h5::readIntMatrix(c, v, "cells");
    sid->mesh.samples = readSamples(c, v, "/visualisation", s, nq);
    const Eigen::Index np = sid->mesh.samples.points.rows();
    if (sid->mesh.cells.size() > 0 &&
        (sid->mesh.cells.minCoeff() < 0 || sid->mesh.cells.maxCoeff() >= np)) {
      c.fail("/visualisation/cells refers to points that do not exist");
    }
  }
  Handle l = h5::openGroup(c, file, "stress_lines");
  for (const std::string& name : h5::listGroup(c, l)) {
    Handle lg = h5::openGroup(c, l, name);
    StressLine line;
    line.name = name;
    line.from = finiteVector(c, lg, "/stress_lines/" + name, "from");
    line.to = finiteVector(c, lg, "/stress_lines/" + name, "to");
    line.samples = readSamples(c, lg, "/stress_lines/" + name, s, nq);
    sid->stress_lines.push_back(std::move(line));
  }
}

// Root attributes: the fixed contract for tools.
void writeRootAttributes(const Context& c, hid_t file, const FlexibleBodySid& sid) {
  h5::writeAttribute(c, file, "format", std::string(kSidFormat));
  h5::writeAttribute(c, file, "format_version", kSidFormatVersion);
  h5::writeAttribute(c, file, "created_by", sid.created_by);
  h5::writeAttribute(c, file, "name", sid.name);
  h5::writeAttribute(c, file, "model", std::string(toString(sid.model)));
  h5::writeAttribute(c, file, "space_dim", sid.space_dim);
  h5::writeAttribute(c, file, "ndof", sid.ndof);
  h5::writeAttribute(c, file, "nq", sid.nq());
  h5::writeAttribute(c, file, "nlvl", sid.nlvl);
  h5::writeAttribute(c, file, "n_elements", sid.n_elements);
  h5::writeAttribute(c, file, "n_interface_control_points", sid.n_interface_control_points);
  h5::writeAttribute(c, file, "preprocessing_time_s", sid.preprocessing_time_s);
  h5::writeAttribute(c, file, "frame", std::string(toString(sid.frame)));
  h5::writeAttribute(c, file, "reduction", std::string(toString(sid.reduction)));
  h5::writeAttribute(c, file, "normal_modes", sid.normal_modes);
  h5::writeAttribute(c, file, "constraint_modes", sid.constraint_modes);
  h5::writeAttribute(c, file, "rigid_modes_dropped", sid.rigid_modes_dropped);
  h5::writeAttribute(c, file, "interface_dofs", sid.interface_dofs);
  h5::writeAttribute(c, file, "characteristic_modes", sid.characteristic_modes);
  h5::writeAttribute(c, file, "patch_modes", sid.patch_modes);
  h5::writeAttribute(c, file, "interface_compliance_error", sid.interface_compliance_error);
}

void writeAll(const Context& c, hid_t file, const FlexibleBodySid& sid) {
  writeRootAttributes(c, file, sid);
  Handle g = h5::createGroup(c, file, "sid");
  h5::writeScalar(c, g, "mass", sid.mass, "kg");
  h5::writeVector(c, g, "first_moment", sid.first_moment, "kg m");
  h5::writeMatrix(c, g, "inertia", sid.inertia, "kg m^2");
  h5::writeVector(c, g, "frame_origin", sid.frame_origin, "m");
  h5::writeVector(c, g, "frequencies_hz", sid.frequencies_hz, "Hz");
  if (sid.characteristic_frequencies_hz.size() > 0)
    h5::writeVector(c, g, "characteristic_frequencies_hz", sid.characteristic_frequencies_hz, "Hz");
  h5::writeVector(c, g, "damping_ratio", sid.damping_ratio, "1");
  h5::writeMatrix(c, g, "Me", sid.Me, "1");
  h5::writeMatrix(c, g, "Ke", sid.Ke, "s^-2");
  h5::writeMatrix(c, g, "De", sid.De, "s^-1");
  h5::writeMatrix(c, g, "Ct", sid.Ct, "kg^(1/2)");
  h5::writeMatrix(c, g, "Cr0", sid.Cr0, "kg^(1/2) m");
  const int nq = sid.nq();
  std::vector<double> cr1(static_cast<std::size_t>(nq) * 3 * nq),
      j1(static_cast<std::size_t>(nq) * 9);
  for (int j = 0; j < nq && !sid.Cr1.empty(); ++j)
    for (int r = 0; r < 3; ++r)
      for (int i = 0; i < nq; ++i)
        cr1[(static_cast<std::size_t>(j) * 3 + r) * nq + i] = sid.Cr1[j](r, i);
  for (int j = 0; j < nq && !sid.J1.empty(); ++j)
    for (int r = 0; r < 3; ++r)
      for (int i = 0; i < 3; ++i) j1[(j * 3 + r) * 3 + i] = sid.J1[j](r, i);
  h5::writeArray(c, g, "Cr1", {hsize_t(nq), 3, hsize_t(nq)}, cr1, "1");
  h5::writeArray(c, g, "J1", {hsize_t(nq), 3, 3}, j1, "kg^(1/2) m");
  h5::writeMatrix(c, g, "Oe", sid.Oe, "kg^(1/2) m");

  Handle b = h5::createGroup(c, file, "body");
  h5::writeMatrix(c, b, "control_points", sid.control_points, "m");
  h5::writeVector(c, b, "weights", sid.weights, "1");
  h5::writeMatrix(c, b, "Phi", sid.Phi, "kg^(-1/2)");

  Handle m = h5::createGroup(c, file, "markers");
  for (const Marker& mk : sid.markers) {
    Handle mg = h5::createGroup(c, m, mk.name);
    h5::writeVector(c, mg, "position", mk.position, "m");
    h5::writeInts(c, mg, "functions", mk.functions);
    h5::writeVector(c, mg, "values", mk.values, "1");
    if (mk.Psi.size() > 0) h5::writeMatrix(c, mg, "Psi", mk.Psi, "rad kg^(-1/2) m^(-1)");
  }
  Handle s = h5::createGroup(c, file, "contact_surfaces");
  for (const ContactSurface& cs : sid.surfaces) writeSurface(c, s, cs);
  writeBodyDescription(c, file, sid);

  Handle p = h5::createGroup(c, file, "provenance");
  h5::writeAttribute(c, p, "input_yaml", sid.input_yaml);
  h5::writeAttribute(c, p, "input_path", sid.input_path);
  h5::writeAttribute(c, p, "overrides", sid.input_overrides);
  h5::writeAttribute(c, p, "created_by", sid.created_by);
  h5::writeAttribute(c, p, "git_revision", gitRevision());
  h5::writeAttribute(c, p, "dependency_versions", dependencyVersionsText());
  Handle t = h5::createGroup(c, p, "stage_times_s");
  for (std::size_t i = 0; i < sid.stage_times_s.size(); ++i) {
    // Prefix keeps the stage order in HDF5's name-ordered listing.
    char prefix[32];
    std::snprintf(prefix, sizeof(prefix), "%02zu_", i);
    h5::writeAttribute(c, t, prefix + sid.stage_times_s[i].first, sid.stage_times_s[i].second);
  }
}

// A root attribute naming one of the body kinds (common/sid/body_kinds.h).
template <class Kind>
void readKind(const Context& c, hid_t file, const char* name, Kind* kind) {
  const std::string text = h5::readStringAttribute(c, file, name);
  if (!parseKind(text, kind)) c.fail(Str() << "attribute '" << name << "' is '" << text << "', no "
                                           << name << " this program knows; rerun igaprep");
}

// Root attributes: the format and its version first, then the body's identity and counts.
void readHeader(const Context& c, hid_t file, FlexibleBodySid* sid) {
  if (!h5::hasAttribute(file, "format")) c.fail("not a SID file (no root attribute 'format')");
  const std::string format = h5::readStringAttribute(c, file, "format");
  if (format != kSidFormat) {
    c.fail(Str() << "not a SID file: format is '" << format << "', expected '" << kSidFormat
                 << "'");
  }
  const int version = h5::readIntAttribute(c, file, "format_version");
  if (version != kSidFormatVersion) {
    c.fail(Str() << "SID format_version " << version << " is not supported (this program reads "
                 << "version " << kSidFormatVersion << "); rerun igaprep");
  }
  sid->created_by = h5::readStringAttribute(c, file, "created_by");
  sid->name = h5::readStringAttribute(c, file, "name");
  readKind(c, file, "model", &sid->model);
  sid->space_dim = h5::readIntAttribute(c, file, "space_dim");
  sid->ndof = h5::readIntAttribute(c, file, "ndof");
  sid->nlvl = h5::readIntAttribute(c, file, "nlvl");
  sid->n_elements = h5::readIntAttribute(c, file, "n_elements");
  sid->n_interface_control_points = h5::readIntAttribute(c, file, "n_interface_control_points");
  sid->preprocessing_time_s = h5::readDoubleAttribute(c, file, "preprocessing_time_s");
  readKind(c, file, "frame", &sid->frame);
  readKind(c, file, "reduction", &sid->reduction);
  sid->normal_modes = h5::readIntAttribute(c, file, "normal_modes");
  sid->constraint_modes = h5::readIntAttribute(c, file, "constraint_modes");
  sid->rigid_modes_dropped = h5::readIntAttribute(c, file, "rigid_modes_dropped");
  // Added on 2026-12-07 within version 3: read where present (else sid.h's defaults).
  const auto optionalInt = [&](const char* name, int* out) {
    if (h5::hasAttribute(file, name)) *out = h5::readIntAttribute(c, file, name);
  };
  optionalInt("interface_dofs", &sid->interface_dofs);
  optionalInt("characteristic_modes", &sid->characteristic_modes);
  optionalInt("patch_modes", &sid->patch_modes);
  if (h5::hasAttribute(file, "interface_compliance_error"))
    sid->interface_compliance_error =
        h5::readDoubleAttribute(c, file, "interface_compliance_error");
}

// /sid/Cr1 and /sid/J1: the first-order terms in q, stored as [nq, 3, nq] and [nq, 3, 3].
void readFirstOrderTerms(const Context& c, hid_t g, FlexibleBodySid* sid) {
  const int nq = sid->nq();
  std::vector<hsize_t> dims;
  const std::vector<double> cr1 = h5::readArray(c, g, "Cr1", &dims);
  if (dims != std::vector<hsize_t>{hsize_t(nq), 3, hsize_t(nq)})
    c.fail("/sid/Cr1 has wrong dimensions");
  requireFinite(c, "/sid/Cr1", cr1, dims);
  sid->Cr1.assign(nq, Eigen::MatrixXd(3, nq));
  for (int j = 0; j < nq; ++j)
    for (int r = 0; r < 3; ++r)
      for (int i = 0; i < nq; ++i)
        sid->Cr1[j](r, i) = cr1[(static_cast<std::size_t>(j) * 3 + r) * nq + i];
  const std::vector<double> j1 = h5::readArray(c, g, "J1", &dims);
  if (dims != std::vector<hsize_t>{hsize_t(nq), 3, 3}) c.fail("/sid/J1 has wrong dimensions");
  requireFinite(c, "/sid/J1", j1, dims);
  sid->J1.assign(nq, Eigen::Matrix3d::Zero());
  for (int j = 0; j < nq; ++j)
    for (int r = 0; r < 3; ++r)
      for (int i = 0; i < 3; ++i) sid->J1[j](r, i) = j1[(j * 3 + r) * 3 + i];
}

// /sid: the rigid-body and elastic invariants.
void readInvariants(const Context& c, hid_t file, FlexibleBodySid* sid) {
  Handle g = h5::openGroup(c, file, "sid");
  sid->mass = finiteScalar(c, g, "/sid", "mass");
  sid->first_moment = finiteVector(c, g, "/sid", "first_moment");
  sid->inertia = finiteMatrix(c, g, "/sid", "inertia");
  sid->frame_origin = finiteVector(c, g, "/sid", "frame_origin");
  sid->frequencies_hz = finiteVector(c, g, "/sid", "frequencies_hz");
  if (h5::exists(g, "characteristic_frequencies_hz"))  // optional (sid.h)
    sid->characteristic_frequencies_hz =
        finiteVector(c, g, "/sid", "characteristic_frequencies_hz");
  sid->damping_ratio = finiteVector(c, g, "/sid", "damping_ratio");
  sid->Me = finiteMatrix(c, g, "/sid", "Me");
  sid->Ke = finiteMatrix(c, g, "/sid", "Ke");
  sid->De = finiteMatrix(c, g, "/sid", "De");
  sid->Ct = finiteMatrix(c, g, "/sid", "Ct");
  sid->Cr0 = finiteMatrix(c, g, "/sid", "Cr0");
  if (h5::readIntAttribute(c, file, "nq") != sid->nq())
    c.fail("root attribute nq disagrees with /sid");
  readFirstOrderTerms(c, g, sid);
  sid->Oe = finiteMatrix(c, g, "/sid", "Oe");
}

// /body: the control points, their weights and the modes at them.
void readBodyModes(const Context& c, hid_t file, FlexibleBodySid* sid) {
  Handle b = h5::openGroup(c, file, "body");
  sid->control_points = finiteMatrix(c, b, "/body", "control_points");
  sid->weights = finiteVector(c, b, "/body", "weights");
  sid->Phi = finiteMatrix(c, b, "/body", "Phi");
}

// /markers and /contact_surfaces.
void readMarkersAndSurfaces(const Context& c, hid_t file, FlexibleBodySid* sid) {
  Handle m = h5::openGroup(c, file, "markers");
  for (const std::string& name : h5::listGroup(c, m)) {
    Handle mg = h5::openGroup(c, m, name);
    const std::string where = "/markers/" + name;
    Marker mk;
    mk.name = name;
    mk.position = finiteVector(c, mg, where, "position");
    mk.functions = h5::readInts(c, mg, "functions");
    mk.values = finiteVector(c, mg, where, "values");
    if (h5::exists(mg, "Psi")) {
      mk.Psi = finiteMatrix(c, mg, where, "Psi");
      if (mk.Psi.rows() != 3 || mk.Psi.cols() != sid->nq())
        c.fail(Str() << "/markers/" << name << "/Psi is " << mk.Psi.rows() << "x" << mk.Psi.cols()
                     << ", expected 3x" << sid->nq());
    }
    sid->markers.push_back(std::move(mk));
  }
  Handle s = h5::openGroup(c, file, "contact_surfaces");
  for (const std::string& name : h5::listGroup(c, s))
    sid->surfaces.push_back(readSurface(c, s, name));
}

// /provenance: the body file, its overrides and the stage times (not checked: records only).
void readProvenance(const Context& c, hid_t file, FlexibleBodySid* sid) {
  Handle p = h5::openGroup(c, file, "provenance");
  sid->input_yaml = h5::readStringAttribute(c, p, "input_yaml");
  sid->input_path = h5::readStringAttribute(c, p, "input_path");
  if (h5::hasAttribute(p, "overrides"))  // provenance only: optional
    sid->input_overrides = h5::readStringAttribute(c, p, "overrides");
  Handle t = h5::openGroup(c, p, "stage_times_s");
  const int na = H5Aget_num_attrs(t);
  if (na < 0) c.fail("stage_times_s: cannot count attributes");
  for (int i = 0; i < na; ++i) {
    Handle attr(
        c.check(H5Aopen_by_idx(t, ".", H5_INDEX_NAME, H5_ITER_INC, i, H5P_DEFAULT, H5P_DEFAULT),
                "open stage time"),
        H5Aclose);
    char name[256] = {0};
    if (H5Aget_name(attr, sizeof(name), name) < 0) c.fail("stage time name");
    double v = 0.0;
    c.check(H5Aread(attr, H5T_NATIVE_DOUBLE, &v), "read stage time", 0);
    std::string n = name;
    if (n.size() > 3 && n[2] == '_') n = n.substr(3);
    sid->stage_times_s.emplace_back(n, v);
  }
}

}  // namespace

void writeSid(const FlexibleBodySid& sid, const std::string& path) {
  h5::silenceErrors();
  const std::string tmp = Str() << path << ".tmp-" << getpid();
  Context c{path, false};
  try {
    {
      Handle file(c.check(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                          "create " + tmp + " (is the directory writable?)"),
                  H5Fclose);
      writeAll(c, file, sid);
      c.check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush", 0);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
      c.fail("cannot rename " + tmp + " to " + path);
    }
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

FlexibleBodySid readSid(const std::string& path, SidContent content) {
  h5::silenceErrors();
  Context c{path, true};
  {
    std::ifstream probe(path);
    if (!probe) throw InputError(path + ": cannot open file");
  }
  if (H5Fis_hdf5(path.c_str()) <= 0) throw InputError(path + ": not an HDF5 file");
  Handle file(c.check(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open file"), H5Fclose);
  FlexibleBodySid sid;
  readHeader(c, file, &sid);
  readInvariants(c, file, &sid);
  readBodyModes(c, file, &sid);
  readMarkersAndSurfaces(c, file, &sid);
  readBodyDescription(c, file, content, &sid);
  readProvenance(c, file, &sid);
  return sid;
}

}  // namespace ffriga
