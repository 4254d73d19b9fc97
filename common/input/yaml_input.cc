#include "common/input/yaml_input.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace ffriga {

namespace {

// A plain (unquoted) scalar that YAML or strtod reads as a number that is not finite:
// .inf, -.Inf, .nan, .NaN, ..., or a literal beyond the range of double (1e999).
bool isNonFiniteNumber(const YAML::Node& node) {
  if (!node.IsScalar() || node.Tag() != "?") return false;
  std::string t = node.Scalar();
  if (!t.empty() && (t[0] == '+' || t[0] == '-')) t = t.substr(1);
  for (const char* special : {".inf", ".Inf", ".INF", ".nan", ".NaN", ".NAN"})
    if (t == special) return true;
  const char* c = node.Scalar().c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(c, &end);
  const bool number = end != c && *end == '\0' && std::isdigit(static_cast<unsigned char>(t[0]));
  return number && (!std::isfinite(v) || (errno == ERANGE && std::abs(v) > 1.0));
}

std::string childKey(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

// Limits on a document's tree with its aliases expanded. yaml-cpp keeps an alias as the node
// it names (shared, not copied), so nine lines of nested aliases make a tree of 9^9 nodes (an
// "alias bomb") that a walk takes minutes for, and an alias inside the node it names makes a
// cycle that a walk never leaves. The largest shipped file (configs/scenes/
// pendulums_rigid.yaml) has 243 values and nests 7 levels; a hand-written explicit NURBS
// patch of 10^5 control points stays below the million, which this walk refuses after
// 0.1 s, and 64 levels keep the recursive walks (here, the schema check, inputError) far
// from the end of the stack.
constexpr std::size_t kMaxNodes = 1000000;
constexpr std::size_t kMaxDepth = 64;

// Walks the whole tree once, before anything else does: duplicate keys of a mapping
// (yaml-cpp keeps both and a lookup sees one of them: the other would be ignored without a
// word) and numbers that are not finite are errors, naming the key path and the lines; so
// are trees beyond the limits above.
class TreeCheck {
 public:
  explicit TreeCheck(const YamlDocument& doc) : doc_(doc) {}

  void visit(const YAML::Node& node) {
    checkLimits(node);
    if (node.IsMap()) {
      path_.push_back(node);
      visitMap(node);
      path_.pop_back();
    } else if (node.IsSequence()) {
      path_.push_back(node);
      std::size_t i = 0;
      for (auto it = node.begin(); it != node.end(); ++it, ++i) {
        keys_.push_back({nullptr, i});
        visit(*it);
        keys_.pop_back();
      }
      path_.pop_back();
    } else if (isNonFiniteNumber(node)) {
      throw inputError(doc_, node, key(),
                       Str() << "expected a finite number, found " << node.Scalar());
    }
  }

 private:
  // A step of the key path: a mapping's key, or (name null) a list's index.
  struct Step {
    const std::string* name;
    std::size_t index;
  };

  void visitMap(const YAML::Node& node) {
    std::map<std::string, int> seen;  // key -> its line
    for (auto it = node.begin(); it != node.end(); ++it) {
      const std::string name = it->first.IsScalar() ? it->first.Scalar() : describeNode(it->first);
      const auto [prev, inserted] = seen.emplace(name, yamlLine(it->first));
      keys_.push_back({&name, 0});
      if (!inserted) {
        throw inputError(doc_, it->first, key(),
                         Str() << "duplicate key: also given on line " << prev->second
                               << " (each key may appear once in a mapping)");
      }
      visit(it->second);
      keys_.pop_back();
    }
  }

  void checkLimits(const YAML::Node& node) {
    if (++nodes_ > kMaxNodes) {
      throw inputError(doc_, node, key(),
                       Str() << "expected at most " << kMaxNodes
                             << " values in the document with its aliases expanded, found more "
                             << "(aliases nested in aliases?)");
    }
    if (!node.IsMap() && !node.IsSequence()) return;
    for (const YAML::Node& open : path_) {
      if (node.is(open)) {
        throw inputError(doc_, node, key(),
                         "expected a tree, found an alias of a mapping or list that contains "
                         "it (a cycle)");
      }
    }
    if (path_.size() >= kMaxDepth) {
      throw inputError(
          doc_, node, key(),
          Str() << "expected at most " << kMaxDepth << " levels of nesting, found more");
    }
  }

  // The key path of the node visited, as errors name it: "a.b[2].c" (built only for errors:
  // the walk may visit a million nodes).
  std::string key() const {
    std::string k;
    for (const Step& s : keys_) {
      if (s.name) {
        k = childKey(k, *s.name);
      } else {
        k += "[" + std::to_string(s.index) + "]";
      }
    }
    return k;
  }

  const YamlDocument& doc_;
  std::size_t nodes_ = 0;
  std::vector<YAML::Node> path_;  // the mappings and lists that hold the node visited
  std::vector<Step> keys_;        // the path to it
};

}  // namespace

YamlDocument parseYamlText(const std::string& text, const std::string& path) {
  YamlDocument doc;
  doc.path = path;
  doc.text = text;
  try {
    doc.root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(Str() << path << ":" << e.mark.line + 1 << ": invalid YAML: " << e.msg);
  }
  if (!doc.root || doc.root.IsNull()) {
    throw InputError(Str() << path << ":1: the file is empty, expected a YAML mapping");
  }
  TreeCheck(doc).visit(doc.root);
  return doc;
}

YamlDocument loadYamlFile(const std::string& path) {
  // A folder opens as a file that reads as empty: name it.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(Str() << path << ": is a folder, expected a YAML file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(Str() << path << ": cannot open file (" << std::strerror(errno) << ")");
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parseYamlText(buffer.str(), path);
}

int yamlLine(const YAML::Node& node) {
  if (!node.IsDefined()) return 0;
  const YAML::Mark m = node.Mark();
  return m.line >= 0 ? m.line + 1 : 0;
}

namespace {

// Whether `node` is `tree` or lies inside it (identity, not equality).
bool within(const YAML::Node& node, const YAML::Node& tree) {
  if (!node.IsDefined() || !tree.IsDefined()) return false;
  if (node.is(tree)) return true;
  if (tree.IsSequence()) {
    for (const YAML::Node& child : tree)
      if (within(node, child)) return true;
  } else if (tree.IsMap()) {
    for (const auto& kv : tree)
      if (within(node, kv.second)) return true;
  }
  return false;
}

// An error key "a.b[2].c" as an override's dotted key "a.b.2.c".
std::string dotted(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '[') {
      out += '.';
    } else if (c != ']') {
      out += c;
    }
  }
  return out;
}

// The override that put `node` into the tree, or, for nodes without a place in the file
// (a key an override added), the last override whose key is the error's key or above it.
const YamlOverride* overrideOf(const YamlDocument& doc, const YAML::Node& node,
                               const std::string& key) {
  const YamlOverride* from = nullptr;
  for (const YamlOverride& o : doc.overrides)
    if (within(node, o.node)) from = &o;
  if (from || doc.overrides.empty() || yamlLine(node) > 0) return from;
  const std::string k = dotted(key);
  for (const YamlOverride& o : doc.overrides)
    if (k == o.key || k.rfind(o.key + ".", 0) == 0) from = &o;
  return from;
}

// The innermost schema default that holds `node` (defaults are recorded outside in).
const YamlDefault* defaultOf(const YamlDocument& doc, const YAML::Node& node) {
  const YamlDefault* from = nullptr;
  for (const YamlDefault& d : doc.defaults)
    if (within(node, d.node)) from = &d;
  return from;
}

}  // namespace

YAML::Node nodeAt(const YamlDocument& doc, const std::string& key) {
  YAML::Node node(doc.root);  // rebound with reset() and read through const: no insertion
  std::size_t i = 0;
  while (i < key.size() && node) {
    if (key[i] == '.') ++i;
    if (key[i] == '[') {
      const std::size_t close = key.find(']', i);
      if (close == std::string::npos || !node.IsSequence())
        return YAML::Node(YAML::NodeType::Undefined);
      const std::size_t index = std::stoul(key.substr(i + 1, close - i - 1));
      if (index >= node.size()) return YAML::Node(YAML::NodeType::Undefined);
      node.reset(node[index]);
      i = close + 1;
      continue;
    }
    const std::size_t end = key.find_first_of(".[", i);
    const std::string name = key.substr(i, end == std::string::npos ? std::string::npos : end - i);
    if (!node.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
    const YAML::Node child = static_cast<const YAML::Node&>(node)[name];
    if (!child) return YAML::Node(YAML::NodeType::Undefined);
    node.reset(child);
    i = end == std::string::npos ? key.size() : end;
  }
  return node;
}

InputError inputErrorAt(const YamlDocument& doc, const ParameterError& e) {
  return inputError(doc, nodeAt(doc, e.key()), e.key(), e.message());
}

bool isSchemaDefault(const YamlDocument& doc, const YAML::Node& node) {
  return defaultOf(doc, node) != nullptr;
}

InputError inputError(const YamlDocument& doc, const YAML::Node& node, const std::string& key,
                      const std::string& message) {
  Str s;
  s << doc.path;
  // A default lies inside the mapping it completes, which an override may have put there:
  // the default is the nearer cause.
  if (const YamlDefault* d = defaultOf(doc, node)) {
    s << ": key '" << (key.empty() ? d->key : key) << "' (schema default " << d->text
      << "): " << message;
    return InputError(s);
  }
  const YamlOverride* from = overrideOf(doc, node, key);
  const int line = from ? 0 : yamlLine(node);
  if (line > 0) s << ":" << line;
  s << ": ";
  if (from) s << "--set '" << from->text << "': ";
  if (!key.empty()) s << "key '" << key << "': ";
  s << message;
  return InputError(s);
}

std::string describeNode(const YAML::Node& node) {
  if (!node.IsDefined()) return "nothing";
  switch (node.Type()) {
    case YAML::NodeType::Null:
      return "an empty value";
    case YAML::NodeType::Scalar:
      return node.Tag() == "!" ? "\"" + node.Scalar() + "\"" : node.Scalar();
    case YAML::NodeType::Sequence:
      return Str() << "a list of " << node.size() << " items";
    case YAML::NodeType::Map:
      return "a mapping";
    default:
      return "an undefined value";
  }
}

double getDouble(const YamlDocument& doc, const YAML::Node& node, const std::string& key) {
  double v = 0.0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, v)) {
    throw inputError(doc, node, key, Str() << "expected a number, found " << describeNode(node));
  }
  if (!std::isfinite(v)) {
    throw inputError(doc, node, key, Str() << "expected a finite number, found " << node.Scalar());
  }
  return v;
}

int getInt(const YamlDocument& doc, const YAML::Node& node, const std::string& key) {
  int v = 0;
  if (!node.IsScalar() || !YAML::convert<int>::decode(node, v)) {
    throw inputError(doc, node, key, Str() << "expected an integer, found " << describeNode(node));
  }
  return v;
}

bool getBool(const YamlDocument& doc, const YAML::Node& node, const std::string& key) {
  bool v = false;
  if (!node.IsScalar() || !YAML::convert<bool>::decode(node, v)) {
    throw inputError(doc, node, key,
                     Str() << "expected true or false, found " << describeNode(node));
  }
  return v;
}

std::string getString(const YamlDocument& doc, const YAML::Node& node, const std::string& key) {
  if (!node.IsScalar()) {
    throw inputError(doc, node, key, Str() << "expected a string, found " << describeNode(node));
  }
  return node.Scalar();
}

}  // namespace ffriga
