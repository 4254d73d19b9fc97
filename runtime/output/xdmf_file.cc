#include "runtime/output/xdmf_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "common/base/error.h"

namespace ffriga {

namespace {

// `text` with XML's special characters as entities, for attribute values and text content
// (body names are any string a scene gives, schemas/scene.schema.json).
std::string xmlEscaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

// A [1, n(, 3)] slab of frame f of a [frames, n(, 3)] dataset.
void hyperslab(std::ostringstream& x, const std::string& h5, const std::string& dataset,
               long frames, long f, long n, int components, const std::string& indent) {
  const bool vector = components > 1;
  x << indent << "<DataItem ItemType=\"HyperSlab\" Dimensions=\"" << n;
  if (vector) x << " " << components;
  x << "\" Type=\"HyperSlab\">\n";
  x << indent << "  <DataItem Dimensions=\"3 " << (vector ? 3 : 2) << "\" Format=\"XML\">";
  if (vector) {
    x << f << " 0 0 1 1 1 1 " << n << " " << components;
  } else {
    x << f << " 0 1 1 1 " << n;
  }
  x << "</DataItem>\n";
  x << indent << "  <DataItem Dimensions=\"" << frames << " " << n;
  if (vector) x << " " << components;
  x << "\" NumberType=\"Float\" Precision=\"4\" Format=\"HDF\">" << h5 << ":" << dataset
    << "</DataItem>\n";
  x << indent << "</DataItem>\n";
}

}  // namespace

std::string xdmfText(const std::string& h5File, const std::vector<double>& times,
                     const std::vector<XdmfBody>& bodies) {
  const std::string h5 = xmlEscaped(h5File);
  std::ostringstream x;
  x.precision(17);
  const long frames = static_cast<long>(times.size());
  x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    << "<Xdmf Version=\"2.0\">\n  <Domain>\n"
    << "    <Grid Name=\"bodies\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (long f = 0; f < frames; ++f) {
    x << "      <Grid Name=\"frame " << f << "\" GridType=\"Collection\" "
      << "CollectionType=\"Spatial\">\n";
    x << "        <Time Value=\"" << times[f] << "\" />\n";
    for (const XdmfBody& b : bodies) {
      const std::string in = "            ";
      x << "        <Grid Name=\"" << xmlEscaped(b.name) << "\" GridType=\"Uniform\">\n";
      x << "          <Topology TopologyType=\"" << (b.corners == 8 ? "Hexahedron" : "Quadrilateral")
        << "\" NumberOfElements=\"" << b.cells << "\">\n";
      x << in << "<DataItem Dimensions=\"" << b.cells << " " << b.corners
        << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << h5 << ":" << xmlEscaped(b.cells_dataset)
        << "</DataItem>\n";
      x << "          </Topology>\n";
      x << "          <Geometry GeometryType=\"XYZ\">\n";
      hyperslab(x, h5, xmlEscaped(b.points_dataset), frames, f, b.points, 3, in);
      x << "          </Geometry>\n";
      for (const XdmfField& field : b.fields) {
        x << "          <Attribute Name=\"" << xmlEscaped(field.name) << "\" AttributeType=\""
          << (field.components > 1 ? "Vector" : "Scalar") << "\" Center=\"Node\">\n";
        hyperslab(x, h5, xmlEscaped(field.dataset), frames, f, b.points, field.components, in);
        x << "          </Attribute>\n";
      }
      x << "        </Grid>\n";
    }
    x << "      </Grid>\n";
  }
  x << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return x.str();
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = Str() << path << ".tmp-" << getpid();
  {
    errno = 0;
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out) {
      const std::string reason = errno != 0 ? std::string(std::strerror(errno)) : "write failed";
      std::remove(tmp.c_str());
      throw ComputeError(Str() << path << ": cannot write (temporary file " << tmp << ": "
                               << reason << ")");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw ComputeError(Str() << path << ": cannot rename " << tmp << " to it");
  }
}

}  // namespace ffriga
