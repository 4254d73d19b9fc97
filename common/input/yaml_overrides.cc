#include "common/input/yaml_overrides.h"

#include <cctype>
#include <sstream>

namespace ffriga {

namespace {

InputError overrideError(const YamlDocument& doc, const std::string& set, const std::string& what) {
  return InputError(Str() << doc.path << ": --set '" << set << "': " << what);
}

bool isIndex(const std::string& part) {
  if (part.empty() || part.size() > 9) return false;
  for (char c : part)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

std::vector<std::string> splitKey(const std::string& key) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(key);
  while (std::getline(in, part, '.')) parts.push_back(part);
  if (!key.empty() && key.back() == '.') parts.push_back("");
  return parts;
}

YAML::Node parseValue(const YamlDocument& doc, const std::string& set, const std::string& value) {
  try {
    YAML::Node v = YAML::Load(value);
    return v.IsDefined() ? v : YAML::Node(YAML::NodeType::Null);
  } catch (const YAML::Exception& e) {
    throw overrideError(doc, set, Str() << "the value is not valid YAML: " << e.msg);
  }
}

}  // namespace

void applyOverrides(YamlDocument& doc, const std::vector<std::string>& sets) {
  for (const std::string& set : sets) {
    const std::size_t eq = set.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw overrideError(doc, set, "expected KEY=VALUE (a dotted key such as "
                                    "contacts.0.penalty_factor, then '=' and a YAML value)");
    }
    const std::string key = set.substr(0, eq);
    const std::vector<std::string> parts = splitKey(key);
    YAML::Node value = parseValue(doc, set, set.substr(eq + 1));
    // Walk to the parent of the last component; yaml-cpp nodes are handles, so assigning
    // through `at` changes the document.
    YAML::Node at = doc.root;
    std::string path;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const std::string& p = parts[i];
      const bool last = i + 1 == parts.size();
      if (p.empty()) throw overrideError(doc, set, "the key has an empty component");
      const std::string here = path.empty() ? p : path + "." + p;
      if (at.IsSequence()) {
        if (!isIndex(p) || std::stoul(p) >= at.size()) {
          throw overrideError(doc, set, Str() << "'" << (path.empty() ? "the document" : path)
                                              << "' is a list of " << at.size()
                                              << " items: expected an index 0.." << at.size() - 1
                                              << ", found '" << p << "'");
        }
        const std::size_t index = std::stoul(p);
        if (last) {
          at[index] = value;
          value = at[index];
        } else {
          at.reset(at[index]);
        }
      } else if (at.IsMap()) {
        if (!last && !at[p]) {
          throw overrideError(doc, set, Str() << "there is no key '" << here << "' in the file "
                                              << "(only the last component may be new)");
        }
        if (last) {
          at[p] = value;
          value = at[p];
        } else {
          const YAML::Node child = at[p];
          at.reset(child);
        }
      } else {
        throw overrideError(doc, set, Str() << "'" << path << "' is "
                                            << describeNode(at) << ", not a mapping or a list");
      }
      path = here;
    }
    doc.overrides.push_back({set, key, value});
  }
}

std::string overridesText(const std::vector<std::string>& sets) {
  std::string out;
  for (const std::string& s : sets) out += s + "\n";
  return out;
}

std::vector<std::string> overridesFromText(const std::string& text) {
  std::vector<std::string> sets;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) sets.push_back(line);
  return sets;
}

}  // namespace ffriga
