#include "common/input/json_schema.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

namespace ffriga {

namespace {

const std::set<std::string> kKeywords = {"type",
                                         "properties",
                                         "required",
                                         "additionalProperties",
                                         "items",
                                         "minItems",
                                         "maxItems",
                                         "minimum",
                                         "maximum",
                                         "exclusiveMinimum",
                                         "exclusiveMaximum",
                                         "enum",
                                         "const",
                                         "$ref",
                                         "oneOf",
                                         "title",
                                         "description",
                                         "default",
                                         "examples",
                                         "$schema",
                                         "$id",
                                         "$comment",
                                         "x-unit",
                                         "$defs",
                                         "definitions"};

bool isQuoted(const YAML::Node& n) {
  return n.Tag() == "!";
}

bool isNumber(const YAML::Node& n, double* value = nullptr) {
  if (!n.IsScalar() || isQuoted(n)) return false;
  double v;
  if (!YAML::convert<double>::decode(n, v)) return false;
  // yaml-cpp decodes ".inf" and ".nan"; they are not valid physical input.
  if (!std::isfinite(v)) return false;
  if (value) *value = v;
  return true;
}

bool isInteger(const YAML::Node& n) {
  if (!n.IsScalar() || isQuoted(n)) return false;
  long long v;
  return YAML::convert<long long>::decode(n, v);
}

bool isBoolean(const YAML::Node& n) {
  if (!n.IsScalar() || isQuoted(n)) return false;
  bool v;
  return YAML::convert<bool>::decode(n, v);
}

bool hasType(const YAML::Node& n, const std::string& type) {
  if (type == "object") return n.IsMap();
  if (type == "array") return n.IsSequence();
  if (type == "null") return n.IsNull();
  if (type == "number") return isNumber(n);
  if (type == "integer") return isInteger(n);
  if (type == "boolean") return isBoolean(n);
  if (type == "string") return n.IsScalar() && !isNumber(n) && !isBoolean(n);
  return false;
}

std::string article(const std::string& type) {
  if (type == "object") return "a mapping";
  if (type == "array") return "a list";
  if (type == "integer") return "an integer";
  if (type == "null") return "nothing";
  return "a " + type;
}

std::string join(const std::string& key, const std::string& child) {
  return key.empty() ? child : key + "." + child;
}

// Levenshtein distance, for "did you mean" suggestions.
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
      diag = up;
    }
  }
  return row[b.size()];
}

// JSON equality, for enum and const (2020-12 Core Sect. 4.2.2): null equals null, numbers
// compare by value (1 == 1.0) and never equal a string ("1" != 1), lists item by item,
// mappings key by key in any order.
bool sameValue(const YAML::Node& a, const YAML::Node& b) {
  if (a.Type() != b.Type()) return false;
  if (a.IsNull()) return true;
  if (a.IsScalar()) {
    double x, y;
    const bool na = isNumber(a, &x), nb = isNumber(b, &y);
    if (na || nb) return na && nb && x == y;
    return a.Scalar() == b.Scalar();
  }
  if (a.size() != b.size()) return false;
  if (a.IsSequence()) {
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!sameValue(a[i], b[i])) return false;
    return true;
  }
  for (const auto& kv : a) {
    const YAML::Node other = b[kv.first.Scalar()];
    if (!other || !sameValue(kv.second, other)) return false;
  }
  return true;
}

// A boolean schema: `true` accepts anything, `false` nothing.
void checkBooleanSchema(const YamlDocument& doc, const YAML::Node& schema, const YAML::Node& node,
                        const YAML::Node& where, const std::string& key) {
  bool accept = true;
  if (schema.IsScalar() && YAML::convert<bool>::decode(schema, accept) && !accept) {
    throw inputError(doc, where, key,
                     Str() << "no value allowed here, found " << describeNode(node));
  }
}

void checkType(const YamlDocument& doc, const YAML::Node& schema, const YAML::Node& node,
               const YAML::Node& where, const std::string& key) {
  const YAML::Node t = schema["type"];
  if (!t) return;
  std::vector<std::string> types;
  if (t.IsSequence()) {
    for (const auto& x : t) types.push_back(x.Scalar());
  } else {
    types.push_back(t.Scalar());
  }
  bool ok = false;
  for (const auto& ty : types) ok = ok || hasType(node, ty);
  if (ok) return;
  Str expected;
  for (std::size_t i = 0; i < types.size(); ++i) {
    expected << (i ? " or " : "") << article(types[i]);
  }
  throw inputError(doc, where, key,
                   Str() << "expected " << expected.str() << ", found " << describeNode(node));
}

void checkConstAndEnum(const YamlDocument& doc, const YAML::Node& schema, const YAML::Node& node,
                       const YAML::Node& where, const std::string& key) {
  if (const YAML::Node c = schema["const"]) {
    if (!sameValue(c, node)) {
      throw inputError(doc, where, key,
                       Str() << "expected " << c.Scalar() << ", found " << describeNode(node));
    }
  }
  if (const YAML::Node e = schema["enum"]) {
    bool ok = false;
    Str allowed;
    for (std::size_t i = 0; i < e.size(); ++i) {
      ok = ok || sameValue(e[i], node);
      allowed << (i ? ", " : "") << e[i].Scalar();
    }
    if (!ok) {
      throw inputError(
          doc, where, key,
          Str() << "expected one of " << allowed.str() << "; found " << describeNode(node));
    }
  }
}

// minimum, maximum, exclusiveMinimum, exclusiveMaximum of a number, with its x-unit (none
// for a dimensionless "1").
void checkBounds(const YamlDocument& doc, const YAML::Node& schema, const YAML::Node& node,
                 const YAML::Node& where, const std::string& key) {
  double value;
  if (!isNumber(node, &value)) return;
  const bool unit_named = schema["x-unit"] && schema["x-unit"].Scalar() != "1";
  const std::string unit = unit_named ? " " + schema["x-unit"].Scalar() : "";
  auto bound = [&](const char* kw, bool violated, const char* rule) {
    if (schema[kw] && violated) {
      throw inputError(doc, where, key,
                       Str() << "expected a number " << rule << " " << schema[kw].Scalar() << unit
                             << ", found " << node.Scalar());
    }
  };
  bound("minimum", schema["minimum"] && value < schema["minimum"].as<double>(), ">=");
  bound("maximum", schema["maximum"] && value > schema["maximum"].as<double>(), "<=");
  bound("exclusiveMinimum",
        schema["exclusiveMinimum"] && value <= schema["exclusiveMinimum"].as<double>(), ">");
  bound("exclusiveMaximum",
        schema["exclusiveMaximum"] && value >= schema["exclusiveMaximum"].as<double>(), "<");
}

// "unknown key (did you mean 'NAME'?); expected one of: ..." for key `k` of a mapping whose
// schema lists `props` (may be undefined) and admits no other key.
std::string unknownKeyMessage(const YAML::Node& props, const std::string& k) {
  Str allowed;
  std::string closest;
  std::size_t best = 3;  // suggest only names at most 2 edits away
  bool first = true;
  if (props) {
    for (const auto& p : props) {
      const std::string name = p.first.Scalar();
      allowed << (first ? "" : ", ") << name;
      first = false;
      const std::size_t dist = editDistance(k, name);
      if (dist < best) best = dist, closest = name;
    }
  }
  Str msg;
  msg << "unknown key";
  if (!closest.empty()) msg << " (did you mean '" << closest << "'?)";
  msg << "; expected one of: " << allowed.str();
  return msg;
}

// A deep copy of a schema value as document nodes: scalars keep their text and tag (a quoted
// string stays a string, 1e-06 stays the number it reads as); the copy has no mark (line).
YAML::Node copyNode(const YAML::Node& v) {
  switch (v.Type()) {
    case YAML::NodeType::Scalar: {
      YAML::Node n(v.Scalar());
      n.SetTag(v.Tag());
      return n;
    }
    case YAML::NodeType::Sequence: {
      YAML::Node n(YAML::NodeType::Sequence);
      for (const auto& x : v) n.push_back(copyNode(x));
      return n;
    }
    case YAML::NodeType::Map: {
      YAML::Node n(YAML::NodeType::Map);
      for (const auto& kv : v) n[kv.first.Scalar()] = copyNode(kv.second);
      return n;
    }
    default:
      return YAML::Node(YAML::NodeType::Null);
  }
}

// A schema value as JSON text for messages: 1e-06, "structured", [0, 0, 0], {}.
std::string jsonText(const YAML::Node& v) {
  if (v.IsScalar()) return isQuoted(v) ? "\"" + v.Scalar() + "\"" : v.Scalar();
  if (!v.IsSequence() && !v.IsMap()) return "null";
  Str s;
  s << (v.IsSequence() ? "[" : "{");
  bool first = true;
  for (auto it = v.begin(); it != v.end(); ++it, first = false) {
    s << (first ? "" : ", ");
    if (v.IsSequence()) {
      s << jsonText(*it);
    } else {
      s << "\"" << it->first.Scalar() << "\": " << jsonText(it->second);
    }
  }
  s << (v.IsSequence() ? "]" : "}");
  return s;
}

}  // namespace

JsonSchema::JsonSchema(const std::string& text, const std::string& name) : name_(name) {
  try {
    root_ = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(Str() << "schema " << name << " is not valid JSON: " << e.msg);
  }
  checkKeywords(root_, "#");
}

void JsonSchema::checkKeywords(const YAML::Node& schema, const std::string& where) const {
  if (!schema.IsMap()) return;
  for (const auto& kv : schema) {
    const std::string k = kv.first.Scalar();
    if (!kKeywords.count(k)) {
      throw std::invalid_argument(Str() << "schema " << name_ << " uses the unsupported keyword '"
                                        << k << "' at " << where);
    }
    if (k == "properties" || k == "$defs" || k == "definitions") {
      for (const auto& p : kv.second) checkKeywords(p.second, where + "/" + p.first.Scalar());
    } else if (k == "items" || k == "additionalProperties") {
      checkKeywords(kv.second, where + "/" + k);
    } else if (k == "oneOf") {
      for (const auto& s : kv.second) checkKeywords(s, where + "/oneOf");
    }
  }
}

YAML::Node JsonSchema::resolve(const YAML::Node& schema) const {
  YAML::Node s;
  s.reset(schema);
  for (int depth = 0; s.IsMap() && s["$ref"]; ++depth) {
    const std::string ref = s["$ref"].Scalar();
    std::string name;
    YAML::Node defs;
    if (ref.rfind("#/$defs/", 0) == 0) {
      name = ref.substr(8);
      defs.reset(root_["$defs"]);
    } else if (ref.rfind("#/definitions/", 0) == 0) {
      name = ref.substr(14);
      defs.reset(root_["definitions"]);
    }
    const YAML::Node& cdefs = defs;
    if (name.empty() || !cdefs || !cdefs[name] || depth > 32) {
      throw std::invalid_argument(Str() << "schema " << name_ << ": cannot resolve $ref " << ref);
    }
    s.reset(cdefs[name]);
  }
  return s;
}

void JsonSchema::validate(const YamlDocument& doc) const {
  check(doc, root_, doc.root, doc.root, "");
}

// The phases in the order their errors take precedence: type, const and enum, numeric
// bounds, list items, mapping keys (unknown, required, each property), then oneOf.
void JsonSchema::check(const YamlDocument& doc, const YAML::Node& schemaIn, const YAML::Node& node,
                       const YAML::Node& parent, const std::string& key) const {
  const YAML::Node schema = resolve(schemaIn);
  const YAML::Node& where = node.IsDefined() ? node : parent;
  if (!schema.IsMap()) {
    checkBooleanSchema(doc, schema, node, where, key);
    return;
  }
  checkType(doc, schema, node, where, key);
  checkConstAndEnum(doc, schema, node, where, key);
  checkBounds(doc, schema, node, where, key);
  if (node.IsSequence()) checkArray(doc, schema, node, where, key);
  if (node.IsMap()) {
    checkUnknownKeys(doc, schema, node, key);
    checkRequired(doc, schema, node, where, key);
    checkProperties(doc, schema, node, key);
  }
  if (const YAML::Node one = schema["oneOf"]) checkOneOf(doc, one, node, parent, key);
}

void JsonSchema::checkArray(const YamlDocument& doc, const YAML::Node& schema,
                            const YAML::Node& node, const YAML::Node& where,
                            const std::string& key) const {
  const int n = static_cast<int>(node.size());
  auto count = [](int k) -> std::string { return Str() << k << (k == 1 ? " item" : " items"); };
  if (schema["minItems"] && n < schema["minItems"].as<int>()) {
    throw inputError(
        doc, where, key,
        Str() << "expected at least " << count(schema["minItems"].as<int>()) << ", found " << n);
  }
  if (schema["maxItems"] && n > schema["maxItems"].as<int>()) {
    throw inputError(
        doc, where, key,
        Str() << "expected at most " << count(schema["maxItems"].as<int>()) << ", found " << n);
  }
  if (const YAML::Node items = schema["items"]) {
    for (int i = 0; i < n; ++i) {
      check(doc, items, node[i], node, Str() << key << "[" << i << "]");
    }
  }
}

// Unknown keys first: a misspelt key also explains a "missing" required one.
void JsonSchema::checkUnknownKeys(const YamlDocument& doc, const YAML::Node& schema,
                                  const YAML::Node& node, const std::string& key) const {
  const YAML::Node props = schema["properties"];
  const YAML::Node additional = schema["additionalProperties"];
  for (const auto& kv : node) {
    const std::string k = kv.first.Scalar();
    if (props && props[k]) continue;
    if (additional && additional.IsScalar() && !additional.as<bool>()) {
      throw inputError(doc, kv.first, join(key, k), unknownKeyMessage(props, k));
    } else if (additional && additional.IsMap()) {
      check(doc, additional, kv.second, kv.first, join(key, k));
    }
  }
}

void JsonSchema::checkRequired(const YamlDocument& doc, const YAML::Node& schema,
                               const YAML::Node& node, const YAML::Node& where,
                               const std::string& key) const {
  const YAML::Node req = schema["required"];
  if (!req) return;
  const YAML::Node props = schema["properties"];
  for (const auto& r : req) {
    if (node[r.Scalar()]) continue;
    Str msg;
    msg << "missing required key '" << r.Scalar() << "'";
    const YAML::Node ps = props ? resolve(props[r.Scalar()]) : YAML::Node();
    if (ps && ps.IsMap() && ps["description"]) msg << " (" << ps["description"].Scalar() << ")";
    throw inputError(doc, where, key.empty() ? "(top level)" : key, msg);
  }
}

void JsonSchema::checkProperties(const YamlDocument& doc, const YAML::Node& schema,
                                 const YAML::Node& node, const std::string& key) const {
  const YAML::Node props = schema["properties"];
  if (!props) return;
  for (const auto& kv : node) {
    const std::string k = kv.first.Scalar();
    if (props[k]) check(doc, props[k], kv.second, kv.first, join(key, k));
  }
}

// The property every branch of a oneOf fixes with `const` (a discriminator such as
// geometry.type), or "" when the branches fix none.
std::string JsonSchema::discriminatorOf(const YAML::Node& one) const {
  std::string name;
  for (const auto& branch : one) {
    const YAML::Node b = resolve(branch);
    if (!b.IsMap() || !b["properties"]) continue;
    for (const auto& p : b["properties"]) {
      const YAML::Node ps = resolve(p.second);
      if (ps.IsMap() && ps["const"]) name = p.first.Scalar();
    }
  }
  return name;
}

// The (resolved) branch of a discriminated oneOf whose `const` equals `tag`, or an undefined
// node.
YAML::Node JsonSchema::branchFor(const YAML::Node& one, const std::string& discriminator,
                                 const YAML::Node& tag) const {
  const YAML::Node none(YAML::NodeType::Undefined);  // YAML::Node() would be a defined null
  if (!tag) return none;
  for (const auto& branch : one) {
    const YAML::Node b = resolve(branch);
    if (sameValue(resolve(b["properties"][discriminator])["const"], tag)) return b;
  }
  return none;
}

// The values a discriminated oneOf allows, comma-separated.
std::string JsonSchema::branchValues(const YAML::Node& one,
                                     const std::string& discriminator) const {
  Str allowed;
  for (std::size_t i = 0; i < one.size(); ++i) {
    const YAML::Node b = resolve(one[i]);
    allowed << (i ? ", " : "") << resolve(b["properties"][discriminator])["const"].Scalar();
  }
  return allowed;
}

void JsonSchema::checkOneOf(const YamlDocument& doc, const YAML::Node& one, const YAML::Node& node,
                            const YAML::Node& parent, const std::string& key) const {
  // Discriminated union: each branch fixes one property with const.
  const std::string d = discriminatorOf(one);
  if (d.empty() || !node.IsMap()) {
    checkExactlyOne(doc, one, node, parent, key);
    return;
  }
  const YAML::Node tag = node[d];
  if (const YAML::Node b = branchFor(one, d, tag)) {
    check(doc, b, node, parent, key);
    return;
  }
  throw inputError(
      doc, tag ? tag : node, join(key, d),
      Str() << "expected one of " << branchValues(one, d) << "; found " << describeNode(tag));
}

// What a oneOf branch of scalars accepts, for a message ("a number > 0", "'auto'", "one of
// same, plane"); empty if the branch is not one of scalars alone (an object, a list, or
// keywords beyond type, bounds, const and enum).
std::string scalarAlternative(const YAML::Node& b) {
  if (!b.IsMap()) return "";
  Str out;
  for (const auto& kv : b) {
    const std::string k = kv.first.Scalar();
    if (k != "type" && k != "const" && k != "enum" && k != "minimum" && k != "maximum" &&
        k != "exclusiveMinimum" && k != "exclusiveMaximum" && k != "description" &&
        k != "x-unit" && k != "default")
      return "";
  }
  if (const YAML::Node c = b["const"]) return c.IsScalar() ? "'" + c.Scalar() + "'" : "";
  if (const YAML::Node e = b["enum"]) {
    out << "one of ";
    for (std::size_t i = 0; i < e.size(); ++i) out << (i ? ", " : "") << e[i].Scalar();
    return out.str();
  }
  const YAML::Node t = b["type"];
  if (!t || !t.IsScalar() || t.Scalar() == "object" || t.Scalar() == "array") return "";
  out << article(t.Scalar());
  for (const auto& [kw, rule] : {std::pair<const char*, const char*>{"exclusiveMinimum", ">"},
                                 {"minimum", ">="}, {"exclusiveMaximum", "<"}, {"maximum", "<="}})
    if (b[kw]) out << " " << rule << " " << b[kw].Scalar();
  return out.str();
}

// Where in the document an error's key lies, for comparing how far branches of a oneOf got:
// its depth (the number of '.' and '[' in the key the message names: "key
// 'hierarchy.boxes[0][1][1]': ..." has 4; 0 without a key), then its list indices in order
// (a later item is further).
std::vector<int> errorPosition(const std::string& message) {
  std::vector<int> position{0};
  const std::size_t start = message.find("key '");
  if (start == std::string::npos) return position;
  const std::size_t end = message.find('\'', start + 5);
  for (std::size_t i = start + 5; i < end && i < message.size(); ++i) {
    if (message[i] == '.' || message[i] == '[') ++position[0];
    if (message[i] == '[') position.push_back(std::atoi(message.c_str() + i + 1));
  }
  return position;
}

// Exactly one branch must accept the node; if none does: for a scalar against branches of
// scalars alone, every alternative in one line ("expected a number > 0 or 'auto'"); else the
// error of the branch of the node's kind (a mapping against the object branch) that got
// deepest into the node, so that the message names the offending inner key rather than
// "expected a boolean".
void JsonSchema::checkExactlyOne(const YamlDocument& doc, const YAML::Node& one,
                                 const YAML::Node& node, const YAML::Node& parent,
                                 const std::string& key) const {
  std::string firstError, kindError;
  int accepted = -1;
  for (int i = 0; i < static_cast<int>(one.size()); ++i) {
    try {
      check(doc, one[i], node, parent, key);
    } catch (const InputError& e) {
      if (firstError.empty()) firstError = e.what();
      const YAML::Node b = resolve(one[i]);
      const YAML::Node type = b.IsMap() ? b["type"] : YAML::Node();
      const bool sameKind = type && type.IsScalar() &&
                            ((type.Scalar() == "object") == node.IsMap()) &&
                            ((type.Scalar() == "array") == node.IsSequence());
      // Of several branches of the node's kind, the one whose error lies deepest in the
      // node (then furthest along it) got furthest: its error names the offending item (a
      // list of boxes against a single box: the interval that is too short, not the box
      // read as an interval).
      if (sameKind && (kindError.empty() || errorPosition(e.what()) > errorPosition(kindError)))
        kindError = e.what();
      continue;
    }
    if (accepted >= 0) {
      const YAML::Node& where = node.IsDefined() ? node : parent;
      throw inputError(doc, where, key,
                       Str() << "matches alternatives " << accepted + 1 << " and " << i + 1
                             << " of a oneOf, expected exactly one; found " << describeNode(node));
    }
    accepted = i;
  }
  if (accepted >= 0) return;
  if (node.IsScalar()) {
    Str alternatives;
    bool scalars = true;
    for (int i = 0; i < static_cast<int>(one.size()) && scalars; ++i) {
      const std::string a = scalarAlternative(resolve(one[i]));
      scalars = !a.empty();
      alternatives << (i ? " or " : "") << a;
    }
    if (scalars) {
      throw inputError(doc, node, key,
                       Str() << "expected " << alternatives.str() << "; found "
                             << describeNode(node));
    }
  }
  throw InputError(kindError.empty() ? firstError : kindError);
}

void JsonSchema::applyDefaults(YamlDocument& doc) const {
  fillDefaults(doc, root_, doc.root, "");
}

void JsonSchema::fillDefaults(YamlDocument& doc, const YAML::Node& schemaIn, const YAML::Node& node,
                              const std::string& key) const {
  const YAML::Node schema = resolve(schemaIn);
  if (!schema.IsMap()) return;
  // The oneOf branch is chosen before this level changes: a default could sway the choice.
  const YAML::Node one = schema["oneOf"];
  const YAML::Node branch =
      one ? chosenBranch(doc, one, node, key) : YAML::Node(YAML::NodeType::Undefined);
  if (node.IsSequence()) {
    if (const YAML::Node items = schema["items"]) {
      for (std::size_t i = 0; i < node.size(); ++i)
        fillDefaults(doc, items, node[i], Str() << key << "[" << i << "]");
    }
  }
  if (node.IsMap()) fillProperties(doc, schema, node, key);
  if (branch) fillDefaults(doc, branch, node, key);
}

// The properties of a mapping: absent ones with a default inserted, then each filled in turn;
// the values of other keys by additionalProperties' schema.
void JsonSchema::fillProperties(YamlDocument& doc, const YAML::Node& schema, const YAML::Node& node,
                                const std::string& key) const {
  const YAML::Node props = schema["properties"];
  if (props) {
    for (const auto& p : props) {
      const std::string name = p.first.Scalar();
      if (!node[name]) insertDefault(doc, p.second, node, name, join(key, name));
      if (const YAML::Node child = node[name]) fillDefaults(doc, p.second, child, join(key, name));
    }
  }
  const YAML::Node additional = schema["additionalProperties"];
  if (additional && additional.IsMap()) {
    for (const auto& kv : node) {
      const std::string k = kv.first.Scalar();
      if (!props || !props[k]) fillDefaults(doc, additional, kv.second, join(key, k));
    }
  }
}

// Inserts property `name`'s default, if its schema has one (beside a $ref or behind it).
void JsonSchema::insertDefault(YamlDocument& doc, const YAML::Node& propertySchema,
                               const YAML::Node& map, const std::string& name,
                               const std::string& key) const {
  YAML::Node value;
  if (propertySchema.IsMap() && propertySchema["default"]) {
    value.reset(propertySchema["default"]);
  } else if (const YAML::Node s = resolve(propertySchema); s.IsMap() && s["default"]) {
    value.reset(s["default"]);
  } else {
    return;
  }
  YAML::Node target(map);  // the same node: yaml-cpp nodes are handles
  target[name] = copyNode(value);
  doc.defaults.push_back({key, jsonText(value), map[name]});
}

// The branch of a oneOf that applies to a valid node: the one its discriminator selects,
// else the one that validates.
YAML::Node JsonSchema::chosenBranch(const YamlDocument& doc, const YAML::Node& one,
                                    const YAML::Node& node, const std::string& key) const {
  const std::string d = discriminatorOf(one);
  if (!d.empty() && node.IsMap()) return branchFor(one, d, node[d]);
  for (const auto& branch : one) {
    try {
      check(doc, branch, node, node, key);
      return branch;
    } catch (const InputError&) {
    }
  }
  return YAML::Node(YAML::NodeType::Undefined);
}

}  // namespace ffriga
