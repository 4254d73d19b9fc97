#include "common/yaml_input.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace ffriga {

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
  return doc;
}

YamlDocument loadYamlFile(const std::string& path) {
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

InputError inputError(const YamlDocument& doc, const YAML::Node& node, const std::string& key,
                      const std::string& message) {
  Str s;
  s << doc.path;
  const int line = yamlLine(node);
  if (line > 0) s << ":" << line;
  s << ": ";
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
  return v;
}

int getInt(const YamlDocument& doc, const YAML::Node& node, const std::string& key) {
  int v = 0;
  if (!node.IsScalar() || !YAML::convert<int>::decode(node, v)) {
    throw inputError(doc, node, key, Str() << "expected an integer, found " << describeNode(node));
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
