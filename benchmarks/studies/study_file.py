"""Study files (schemas/study.schema.json): reading, checking and expansion into runs.

A study names a base scene, the body files of the SIDs the scene uses, and parameters whose
values override keys of the scene (ffrsim --set) or of the body files (igaprep --set) or
fill {name} fields in the paths. Its runs are the product (or the zip) of the parameters'
values; each run knows the SIDs it needs, and each SID is named by a hash of what makes it
(igaprep's version, the body file's bytes and the overrides), so that equal bodies are built
once and reused across runs and studies.

A bad study file raises StudyError with one line naming the file, the YAML line and the key,
as the programs do:

    study: error: penalty.yaml:12: key 'parameters[0].values': expected a list, found 3e17
"""
import copy
import hashlib
import itertools
import json
import math
import os
import re
import string

import jsonschema
import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SCHEMA = os.path.join(ROOT, "schemas", "study.schema.json")


class StudyError(Exception):
    """Bad input: the message is one line naming file, line and key (exit code 2)."""


# ----------------------------------------------------------------------------- reading

class _Loader(yaml.SafeLoader):
    """YAML 1.1 reader that also takes 1e17 (YAML 1.2, as the programs' yaml-cpp) as a float."""


_Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^[-+]?(?:\d[\d_]*(?:\.[\d_]*)?|\.\d+)[eE][-+]?\d+$"),
    list("-+0123456789."))


def _key_text(path):
    text = ""
    for p in path:
        text += f"[{p}]" if isinstance(p, int) else (f".{p}" if text else str(p))
    return text or "(top level)"


class _Document:
    """The parsed study with the line of every key (1-based), for messages."""

    def __init__(self, path):
        self.path = path
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except OSError as e:
            raise StudyError(f"{path}: cannot open file ({e.strerror})")
        self.lines = {}
        self._scalars = _Loader("")  # constructs the scalars of the composed nodes
        try:
            node = yaml.compose(text, Loader=_Loader)
        except yaml.YAMLError as e:
            mark = getattr(e, "problem_mark", None)
            line = f"{mark.line + 1}:" if mark else ""
            raise StudyError(f"{path}:{line} not valid YAML: {getattr(e, 'problem', e)}")
        if node is None:
            raise StudyError(f"{path}:1: the study file is empty")
        self.data = self._build(node, ())

    def _build(self, node, path):
        self.lines[path] = node.start_mark.line + 1
        if isinstance(node, yaml.MappingNode):
            out = {}
            for k, v in node.value:
                key = k.value
                if key in out:
                    raise StudyError(f"{self.path}:{k.start_mark.line + 1}: key "
                                     f"'{_key_text(path + (key,))}': duplicate key")
                out[key] = self._build(v, path + (key,))
                self.lines[path + (key,)] = k.start_mark.line + 1
            return out
        if isinstance(node, yaml.SequenceNode):
            return [self._build(v, path + (i,)) for i, v in enumerate(node.value)]
        value = self._scalars.construct_object(node, deep=True)
        if isinstance(value, float) and not math.isfinite(value):
            raise StudyError(f"{self.path}:{self.lines[path]}: key '{_key_text(path)}': "
                             f"expected a finite number, found {node.value}")
        return value

    def error(self, path, message):
        path = tuple(path)
        probe = path
        while probe not in self.lines and probe:
            probe = probe[:-1]
        return StudyError(f"{self.path}:{self.lines.get(probe, 1)}: key '{_key_text(path)}': "
                          f"{message}")


def _schema_message(error):
    """(path, message) of a jsonschema error, in the programs' words."""
    path = list(error.absolute_path)
    v, inst = error.validator, error.instance
    if v == "additionalProperties":
        allowed = set(error.schema.get("properties", {}))
        extra = sorted(k for k in inst if k not in allowed)
        if extra:
            known = ", ".join(sorted(allowed))
            return path + [extra[0]], f"unknown key (expected one of: {known})"
    if v == "required":
        missing = re.findall(r"'([^']+)' is a required property", error.message)
        return path, f"missing required key '{missing[0] if missing else error.validator_value}'"
    if v == "oneOf" and len(path) >= 2 and path[-2] == "parameters":
        return path, "expected exactly one of 'values' and 'range'"
    if v == "type":
        words = {"array": "a list", "object": "a mapping", "number": "a number",
                 "integer": "an integer", "string": "a string", "boolean": "true or false"}
        return path, f"expected {words.get(error.validator_value, error.validator_value)}, " \
                     f"found {json.dumps(inst)}"
    if v == "enum":
        return path, (f"expected one of {', '.join(map(str, error.validator_value))}, "
                      f"found {json.dumps(inst)}")
    if v in ("minimum", "maximum"):
        sign = ">=" if v == "minimum" else "<="
        return path, f"expected a number {sign} {error.validator_value}, found {json.dumps(inst)}"
    if v in ("minItems", "minLength"):
        return path, f"expected at least {error.validator_value} " \
                     f"{'items' if v == 'minItems' else 'characters'}, found {json.dumps(inst)}"
    if v == "pattern":
        return path, f"expected a name matching {error.validator_value}, found {json.dumps(inst)}"
    return path, error.message


def _schema():
    with open(SCHEMA, encoding="utf-8") as f:
        schema = json.load(f)
    # Its $id is a name, not an address: local references (#/$defs/...) resolve in the file.
    schema.pop("$id", None)
    return schema


def _resolve(schema, root):
    """A schema with its local $ref (#/$defs/NAME) followed."""
    while isinstance(schema, dict) and "$ref" in schema:
        ref = schema["$ref"]
        node = root
        for part in ref.lstrip("#/").split("/"):
            node = node[part]
        schema = {**{k: v for k, v in schema.items() if k != "$ref"}, **node}
    return schema


def fill_defaults(data, schema, root=None):
    """Inserts the schema's `default`s into a validated document, recursively (the same rule
    as common/input/json_schema.cc's applyDefaults: absent properties with a default, then
    the properties and array items in turn), so that no default is typed twice."""
    root = schema if root is None else root
    schema = _resolve(schema, root)
    if isinstance(data, dict):
        for name, sub in schema.get("properties", {}).items():
            sub_resolved = _resolve(sub, root)
            if name not in data and "default" in sub_resolved:
                data[name] = copy.deepcopy(sub_resolved["default"])
            if name in data:
                fill_defaults(data[name], sub, root)
    elif isinstance(data, list) and "items" in schema:
        for item in data:
            fill_defaults(item, schema["items"], root)
    return data


def _validate(doc, schema):
    validator = jsonschema.Draft202012Validator(schema)
    errors = sorted(validator.iter_errors(doc.data),
                    key=lambda e: (doc.lines.get(tuple(e.absolute_path), 0), len(e.path)))
    if errors:
        path, message = _schema_message(errors[0])
        raise doc.error(path, message)


# ----------------------------------------------------------------------------- the study

class Parameter:
    def __init__(self, spec, index, doc):
        self.name = spec["name"]
        self.unit = spec.get("unit", "")
        self.description = spec.get("description", self.name)
        self.scene_key = spec.get("scene_key")
        self.body_key = spec.get("body_key")
        self.body = spec.get("body")
        self.path = ("parameters", index)
        self.values = spec["values"] if "values" in spec else _range_values(
            spec["range"], doc, self.path + ("range",))


def _range_values(r, doc, path):
    n, a, b = r["num"], float(r["start"]), float(r["stop"])
    if r["spacing"] == "log":
        if a <= 0 or b <= 0:
            raise doc.error(path, f"log spacing needs start and stop > 0, found {a:g} and {b:g}")
        la, lb = math.log10(a), math.log10(b)
        vals = [10 ** (la + (lb - la) * i / (n - 1)) if n > 1 else a for i in range(n)]
        # 10**x is not exact: keep the ends and round the rest to 12 significant digits.
        vals = [float(f"{v:.12g}") for v in vals]
        vals[0], vals[-1] = a, (b if n > 1 else a)
    else:
        vals = [a + (b - a) * i / (n - 1) if n > 1 else a for i in range(n)]
    if r["integer"]:
        vals = [int(round(v)) for v in vals]
    return vals


def _shortest(x):
    """The shortest text that reads back as x exactly: 1e+15, not 1000000000000000.0."""
    text = repr(x)
    for digits in range(17):
        e = f"{x:.{digits}e}"
        if float(e) == x:
            mantissa, exponent = e.split("e")
            e = f"{mantissa}e{exponent[0]}{exponent[1:].lstrip('0') or '0'}"
            return e if len(e) < len(text) - 1 else text
    return text


def value_text(value):
    """A parameter value as the YAML of --set KEY=VALUE and as the table shows it."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return _shortest(value)
    if isinstance(value, (int, str)):
        return str(value)
    return json.dumps(value)


def _template_fields(text):
    return [f for _, f, _, _ in string.Formatter().parse(text) if f is not None]


class Study:
    """A checked study file: its parameters and everything needed to expand its runs."""

    def __init__(self, path):
        self.path = os.path.abspath(path)
        self.file = path
        self.folder = os.path.dirname(self.path)
        self._doc = doc = _Document(path)
        schema = _schema()
        _validate(doc, schema)
        d = fill_defaults(doc.data, schema)
        self.name = d["study"]
        self.description = d.get("description", "")
        self.scene = d["scene"]
        self.bodies = d["bodies"]
        self.parameters = [Parameter(p, i, doc) for i, p in enumerate(d["parameters"])]
        self.combine = d["combine"]
        self.collect = d["collect"]
        self.plot = d["plot"]
        self.resources = d["resources"]
        self._check()

    def error(self, path, message):
        return self._doc.error(path, message)

    def _check(self):
        names = [p.name for p in self.parameters]
        for i, p in enumerate(self.parameters):
            if p.name in names[:i]:
                raise self.error(p.path + ("name",), f"parameter '{p.name}' is given twice")
            if p.body is not None and p.body_key is None:
                raise self.error(p.path + ("body",), "'body' needs a 'body_key'")
            if p.body is not None and p.body not in self.bodies:
                raise self.error(p.path + ("body",), f"no SID '{p.body}' in 'bodies' "
                                 f"(it has {', '.join(self.bodies) or 'none'})")
            if p.body_key is not None and not self.bodies:
                raise self.error(p.path + ("body_key",), "the study has no 'bodies' to override")
        if self.combine == "zip":
            counts = {len(p.values) for p in self.parameters}
            if len(counts) > 1:
                raise self.error(("combine",), "zip needs the same number of values for every "
                                 "parameter, found " + ", ".join(
                                     f"{p.name}: {len(p.values)}" for p in self.parameters))
        for path, text in [(("scene",), self.scene)] + [
                (("bodies", k), k) for k in self.bodies] + [
                (("bodies", k), v) for k, v in self.bodies.items()]:
            try:
                fields = _template_fields(text)
            except ValueError as e:
                raise self.error(path, f"bad {{...}} field in '{text}': {e}")
            for f in fields:
                if f not in names:
                    raise self.error(path, f"'{{{f}}}' names no parameter (parameters: "
                                     f"{', '.join(names)})")
        for i, f in enumerate(self.plot):
            if f not in self.collect:
                raise self.error(("plot", i), f"'{f}' is not collected (collect: "
                                 f"{', '.join(self.collect)})")

    def combinations(self):
        values = [p.values for p in self.parameters]
        rows = zip(*values) if self.combine == "zip" else itertools.product(*values)
        return [dict(zip((p.name for p in self.parameters), r)) for r in rows]

    def runs(self, versions):
        """Every run of the study, in the order of combinations(). versions: the programs'
        --version lines, {'igaprep': ..., 'ffrsim': ...}, part of every hash."""
        return [Run(self, values, versions) for values in self.combinations()]


# ----------------------------------------------------------------------------- runs

def _sha(*parts):
    h = hashlib.sha256()
    for p in parts:
        h.update(p if isinstance(p, bytes) else p.encode("utf-8"))
        h.update(b"\0")
    return h.hexdigest()


class Sid:
    """One SID a run needs: its body file, the overrides and the cache name from their hash."""

    def __init__(self, study, key, name, body_file, overrides, version):
        """key: the study's 'bodies' key (for messages); name: the SID name it gives here."""
        self.name = name
        self.body_file = os.path.normpath(os.path.join(study.folder, body_file))
        try:
            with open(self.body_file, "rb") as f:
                body = f.read()
        except OSError as e:
            raise study.error(("bodies", key),
                              f"cannot read body file '{self.body_file}': {e.strerror}")
        self.overrides = overrides
        # The body file's own bytes, not its path: the same body from two checkouts (a
        # workstation and a cluster) has the same hash.
        self.hash = _sha("sid", version, body, *overrides)[:16]
        stem = os.path.splitext(os.path.basename(self.body_file))[0]
        self.stem = f"{stem}-{self.hash}"


class Run:
    """One ffrsim run: parameter values, scene, overrides, SIDs and an id from their hash."""

    def __init__(self, study, values, versions):
        self.values = values
        self.scene = os.path.normpath(os.path.join(study.folder, study.scene.format(**values)))
        try:
            with open(self.scene, "rb") as f:
                scene_bytes = f.read()
        except OSError as e:
            raise study.error(("scene",), f"cannot read scene file '{self.scene}': {e.strerror}")
        self.sids = {}
        for name, body in study.bodies.items():
            sid_name = name.format(**values)
            overrides = [f"{p.body_key}={value_text(values[p.name])}" for p in study.parameters
                         if p.body_key is not None and p.body in (None, name)]
            self.sids[sid_name] = Sid(study, name, sid_name, body.format(**values), overrides,
                                      versions["igaprep"])
        self.scene_overrides = [f"{p.scene_key}={value_text(values[p.name])}"
                                for p in study.parameters if p.scene_key is not None]
        self.sid_bodies = self._scene_sid_bodies(study, scene_bytes)
        self.id = _sha("run", versions["ffrsim"], scene_bytes, *self.scene_overrides,
                       *(f"{i}:{self.sids[n].hash}" for i, n in self.sid_bodies))[:12]

    def _scene_sid_bodies(self, study, scene_bytes):
        """(index, SID name) of the scene's bodies that use a SID: each must be the study's."""
        try:
            scene = yaml.load(scene_bytes, Loader=_Loader) or {}
        except yaml.YAMLError as e:
            raise study.error(("scene",), f"scene file '{self.scene}' is not valid YAML: {e}")
        out = []
        for i, b in enumerate(scene.get("bodies", []) if isinstance(scene, dict) else []):
            sid = b.get("sid") if isinstance(b, dict) else None
            if sid is None:
                continue
            if sid not in self.sids:
                raise study.error(("bodies",) if study.bodies else ("scene",), f"the scene '{self.scene}' uses SID '{sid}' "
                                  f"(body {i}), which 'bodies' does not build "
                                  f"(it builds {', '.join(self.sids) or 'none'})")
            out.append((i, sid))
        return out

    def ffrsim_sets(self, sid_dir):
        """ffrsim's --set arguments: the scene's own overrides, then the cached SIDs."""
        return self.scene_overrides + [
            f"bodies.{i}.sid={os.path.abspath(os.path.join(sid_dir, self.sids[n].stem))}.sid.h5"
            for i, n in self.sid_bodies]
