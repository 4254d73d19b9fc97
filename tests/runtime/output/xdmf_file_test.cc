// The XDMF description of the visualisation frames (runtime/output/xdmf_file.h), directly:
// well-formed nesting, one spatial collection per frame with its exact time, hyperslabs that
// select frame f of each [frames, points(, 3)] dataset, and the atomic write.
#include "runtime/output/xdmf_file.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>
#include <catch2/catch.hpp>

#include "common/base/error.h"

using namespace ffriga;

namespace {

// A minimal XML well-formedness check: tags nest and match, attribute values are quoted and
// hold no '<', and every '&' starts one of the five predefined entities. Returns an empty
// string or the first problem.
std::string xmlProblem(const std::string& text) {
  std::vector<std::string> open;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '&') {
      bool entity = false;
      for (const char* e : {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"})
        entity = entity || text.compare(i, std::string(e).size(), e) == 0;
      if (!entity) return "bare '&' at offset " + std::to_string(i);
    }
    if (text[i] != '<') continue;
    if (text.compare(i, 2, "<?") == 0 || text.compare(i, 2, "<!") == 0) {
      i = text.find('>', i);
      if (i == std::string::npos) return "unterminated declaration";
      continue;
    }
    // Scan the tag to its '>', skipping quoted attribute values.
    std::size_t j = i + 1;
    bool quoted = false;
    for (; j < text.size() && (quoted || text[j] != '>'); ++j) {
      if (text[j] == '"') quoted = !quoted;
      if (quoted && text[j] == '<')
        return "'<' in an attribute value at offset " + std::to_string(j);
    }
    if (j == text.size()) return "unterminated tag at offset " + std::to_string(i);
    const std::string tag = text.substr(i + 1, j - i - 1);
    const bool closing = tag[0] == '/', selfClosing = tag.back() == '/';
    const std::string name =
        tag.substr(closing ? 1 : 0, tag.find_first_of(" /", 1) - (closing ? 1 : 0));
    // Inside the tag, attributes are name="value" pairs: an even number of quotes.
    if (std::count(tag.begin(), tag.end(), '"') % 2 != 0) return "odd quotes in <" + tag + ">";
    if (closing) {
      if (open.empty() || open.back() != name) return "</" + name + "> closes nothing open";
      open.pop_back();
    } else if (!selfClosing) {
      open.push_back(name);
    }
    i = j;
  }
  return open.empty() ? "" : "<" + open.back() + "> not closed";
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t i = text.find(what); i != std::string::npos; i = text.find(what, i + 1)) ++n;
  return n;
}

std::vector<XdmfBody> twoBodies() {
  XdmfBody hex{"sphere",
               125,
               64,
               8,
               "/visualisation/sphere/cells",
               "/visualisation/sphere/points",
               {{"displacement", "/visualisation/sphere/displacement", 3},
                {"von_mises", "/visualisation/sphere/von_mises", 1}}};
  XdmfBody quad{"disk", 36, 25, 4, "/visualisation/disk/cells", "/visualisation/disk/points", {}};
  return {hex, quad};
}

}  // namespace

TEST_CASE("XDMF text: well formed, one frame per time, hyperslabs of frame f", "[xdmf]") {
  // Times that need all 17 digits to round-trip.
  const std::vector<double> times = {0.0, 1.0 / 3.0, 2.0e-5 + 1e-21, 0.1 + 0.2};
  const std::string x = xdmfText("run.h5", times, twoBodies());
  INFO(x.substr(0, 3000));
  CHECK(xmlProblem(x).empty());
  CHECK(xmlProblem("<a><b></a></b>") != "");  // the checker itself can fail
  CHECK(count(x, "<Time Value=") == 4);
  CHECK(count(x, "CollectionType=\"Spatial\"") == 4);
  CHECK(count(x, "<Grid Name=\"sphere\"") == 4);
  CHECK(count(x, "<Grid Name=\"disk\"") == 4);
  CHECK(count(x, "TopologyType=\"Hexahedron\" NumberOfElements=\"64\"") == 4);
  CHECK(count(x, "TopologyType=\"Quadrilateral\" NumberOfElements=\"25\"") == 4);
  // The times are written exactly.
  std::size_t at = 0;
  for (const double t : times) {
    at = x.find("<Time Value=\"", at);
    REQUIRE(at != std::string::npos);
    at += 13;
    CHECK(std::strtod(x.c_str() + at, nullptr) == t);
  }
  // Frame f selects row f of each dataset: start f 0 (0), stride 1, count 1 x n (x 3), from a
  // [frames, n(, 3)] HDF dataset of run.h5.
  for (int f = 0; f < 4; ++f) {
    const std::string fs = std::to_string(f);
    // sphere: points and displacement (vectors), von_mises (scalar); disk: points.
    CHECK(count(x, ">" + fs + " 0 0 1 1 1 1 125 3</DataItem>") == 2);
    CHECK(count(x, ">" + fs + " 0 1 1 1 125</DataItem>") == 1);
    CHECK(count(x, ">" + fs + " 0 0 1 1 1 1 36 3</DataItem>") == 1);
  }
  CHECK(count(x,
              "Dimensions=\"4 125 3\" NumberType=\"Float\" Precision=\"4\" Format=\"HDF\">"
              "run.h5:/visualisation/sphere/points<") == 4);
  CHECK(count(x,
              "Dimensions=\"4 125\" NumberType=\"Float\" Precision=\"4\" Format=\"HDF\">"
              "run.h5:/visualisation/sphere/von_mises<") == 4);
  CHECK(count(x,
              "Dimensions=\"64 8\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">"
              "run.h5:/visualisation/sphere/cells<") == 4);
  CHECK(count(x, "<Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">") ==
        4);
  CHECK(count(x, "<Attribute Name=\"von_mises\" AttributeType=\"Scalar\" Center=\"Node\">") == 4);
  // No frames: an empty temporal collection, still well formed.
  const std::string empty = xdmfText("run.h5", {}, twoBodies());
  CHECK(xmlProblem(empty).empty());
  CHECK(count(empty, "<Grid") == 1);
}

TEST_CASE("XDMF text: names with XML's special characters are escaped", "[xdmf]") {
  // Body names (any string in a scene, schemas/scene.schema.json) and the HDF5 file name
  // once went into the XML unescaped: a body called a&b <"c"> made the file unreadable.
  std::vector<XdmfBody> bodies = twoBodies();
  bodies[1].name = "a&b <\"c\">";
  const std::string x = xdmfText("r&d.h5", {0.0}, bodies);
  INFO(x);
  CHECK(xmlProblem(x).empty());
  CHECK(count(x, "<Grid Name=\"a&amp;b &lt;&quot;c&quot;") == 1);
}

TEST_CASE("writeFileAtomically: writes, replaces, leaves no temporary file", "[xdmf]") {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("ffriga_xdmf_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "frames.xdmf").string();
  auto read = [](const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  };
  const std::string first = xdmfText("a.h5", {0.0, 1.0}, twoBodies());
  writeFileAtomically(path, first);
  CHECK(read(path) == first);
  const std::string second = "replaced\n";
  writeFileAtomically(path, second);
  CHECK(read(path) == second);
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    (void)e;
    ++files;
  }
  CHECK(files == 1);  // the temporary file was renamed, not left behind
  // A folder that does not exist: a ComputeError naming the path.
  const std::string bad = (dir / "missing" / "frames.xdmf").string();
  try {
    writeFileAtomically(bad, first);
    FAIL("no error for a missing folder");
  } catch (const ComputeError& e) {
    CHECK(std::string(e.what()).find(bad) != std::string::npos);
  }
  std::filesystem::remove_all(dir);
}
