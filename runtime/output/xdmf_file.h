// The XDMF (version 2) description of a result file's visualisation frames, for ParaView
// and VisIt: a temporal collection of frames, each a spatial collection with one
// unstructured grid per body whose geometry, topology and point fields are HDF5 hyperslabs
// of the result file (schemas/result_format.md, group /visualisation). The XDMF file holds
// no data itself; it sits beside the result file and names it relative to itself.
// Reference: the XDMF model and format, www.xdmf.org (Xdmf2: Domain, Grid
// GridType="Collection" CollectionType="Temporal", Topology, Geometry XYZ, Attribute,
// DataItem ItemType="HyperSlab" with a 3 x rank start/stride/count item).
#pragma once

#include <string>
#include <vector>

namespace ffriga {

struct XdmfField {
  std::string name;     // as ParaView shows it, e.g. "displacement"
  std::string dataset;  // HDF5 path of the [frames, points(, 3)] dataset
  int components = 1;   // 1 (scalar) or 3 (vector)
};

struct XdmfBody {
  std::string name;
  long points = 0;
  long cells = 0;
  int corners = 4;            // 4: Quadrilateral, 8: Hexahedron
  std::string cells_dataset;  // [cells, corners], point numbers from 0
  std::string points_dataset; // [frames, points, 3], m
  std::vector<XdmfField> fields;
};

// The XDMF text for `frames` frames at `times` of the HDF5 file `h5_name` (relative to the
// XDMF file, usually its bare name).
std::string xdmfText(const std::string& h5_name, const std::vector<double>& times,
                     const std::vector<XdmfBody>& bodies);

// Writes `text` to `path` atomically (a temporary file beside it, then rename).
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace ffriga
