"""The house's structure, measured from the source: function lengths and include arrows
between folders (issue 30).

usage: check_structure.py SOURCE_DIR [--layers BUILD/layers.txt] [--report] [--max-lines N]

Checks, each failure one line (exit code 1):
  * no function outside tests/ and benchmarks/ longer than --max-lines (80) lines, from the
    first line of its signature to its closing brace (lambdas and local classes count
    towards the function that holds them);
  * with --layers (written by CMake from the rooms' libraries, common/cmake/FfrigaLayers.cmake:
    "ROOM: ROOMS IT MAY INCLUDE" per line), every include between two rooms runs the way the
    libraries allow (the build enforces the same through include views; this names them).
--report also prints the longest functions and the table of include arrows between folders
(how many includes run from each folder to each other), which DESIGN notes quote.

Functions are found by a small scanner (comments, strings and preprocessor lines removed;
a brace that follows a parameter list at namespace or class scope opens a function body),
not a compiler: it reads this project's style, not every C++.
"""
import argparse
import os
import re
import sys
from collections import defaultdict

def load_layers(path):
    """{room: [rooms it may include]} from CMake's layers.txt (`ROOM: ROOMS ...` lines); a
    program folder (preproc, runtime) may include every room inside it."""
    layers = {}
    if not path:
        return None
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            folder, _, allowed = line.partition(":")
            layers[folder.strip()] = allowed.split()
    return layers


SOURCE_EXT = (".h", ".cc", ".cpp", ".hpp")
PROGRAMS = ("preproc", "runtime")  # the programs' own folders, above their rooms
SKIP_TOP = ("tests", "benchmarks", "build", ".git")


def source_files(source):
    for top, dirs, files in os.walk(source):
        rel = os.path.relpath(top, source)
        first = rel.split(os.sep)[0]
        if rel != "." and (first in SKIP_TOP or first.startswith("build") or first.startswith(".")):
            dirs[:] = []
            continue
        for name in sorted(files):
            if name.endswith(SOURCE_EXT):
                yield os.path.normpath(os.path.join(rel, name))


def strip_code(text):
    """The text with comments, string and character literals and preprocessor lines blanked
    (newlines kept, so line numbers stay)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
            continue
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
            continue
        m = re.match(r'R"([^(\s]*)\(', text[i:i + 20])
        if m:
            end = ")" + m.group(1) + '"'
            j = text.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append('""' + re.sub(r"[^\n]", "", text[i:j]))
            i = j
            continue
        if c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
            continue
        if c == "#" and (i == 0 or text[text.rfind("\n", 0, i) + 1:i].strip() == ""):
            j = i
            while True:  # a preprocessor line with its continuations
                k = text.find("\n", j)
                if k < 0:
                    k = n
                    break
                if text[k - 1] != "\\":
                    break
                j = k + 1
            out.append(re.sub(r"[^\n]", " ", text[i:k]))
            i = k
            continue
        out.append(c)
        i += 1
    return "".join(out)


HEAD_FUNCTION = re.compile(
    r"\)\s*(const\s*)?(noexcept\s*(\([^)]*\))?\s*)?(override\s*|final\s*)*(->[^{;]*)?$")
HEAD_CTOR = re.compile(r"\)\s*:\s*[\w:<>,\s]+[({]")  # constructor with an initialiser list


def functions(path):
    """(name, first line, last line) of every function body at namespace or class scope."""
    with open(path, encoding="utf-8") as f:
        text = strip_code(f.read())
    found = []
    stack = []  # per open brace: "scope" (namespace, class, enum, extern) or "function", "block"
    last_end = 0  # where the current statement began (after ; { or })
    i = 0
    for m in re.finditer(r"[{};]", text):
        c = m.group(0)
        i = m.start()
        if c == ";":
            last_end = i + 1
            continue
        if c == "}":
            kind, name, start = stack.pop() if stack else ("block", "", 0)
            if kind == "function":
                found.append((name, text.count("\n", 0, start) + 1, text.count("\n", 0, i) + 1))
            last_end = i + 1
            continue
        head = text[last_end:i]
        in_function = any(k == "function" for k, _, _ in stack)
        stripped = head.strip()
        if in_function:
            stack.append(("block", "", 0))
        elif re.search(r"\b(namespace|class|struct|union|enum)\b[^()]*$", stripped) or \
                re.match(r'^extern\s*""', stripped):
            stack.append(("scope", "", 0))
        elif HEAD_FUNCTION.search(stripped) or HEAD_CTOR.search(stripped):
            paren = stripped.find("(")
            name = stripped[:paren].split()[-1] if paren > 0 and stripped[:paren].split() else "?"
            offset = last_end + (len(head) - len(head.lstrip()))
            stack.append(("function", name, offset))
        else:
            stack.append(("block", "", 0))  # an initialiser, array or lambda at file scope
        last_end = i + 1
    return found


INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def folder_of(path):
    return os.path.dirname(path)


def includes(source, path):
    with open(os.path.join(source, path), encoding="utf-8") as f:
        return INCLUDE.findall(f.read())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source")
    parser.add_argument("--layers", help="layers.txt of a configured build tree")
    parser.add_argument("--report", action="store_true")
    parser.add_argument("--max-lines", type=int, default=80)
    args = parser.parse_args()
    source = os.path.abspath(args.source)
    layers = load_layers(args.layers)
    failures = []
    lengths = []
    arrows = defaultdict(int)
    for path in source_files(source):
        for name, first, last in functions(os.path.join(source, path)):
            lengths.append((last - first + 1, f"{path}:{first}", name))
        here = folder_of(path)
        for inc in includes(source, path):
            if not os.path.exists(os.path.join(source, inc)):
                continue  # generated headers (common/version.h ...) and system ones
            there = folder_of(inc)
            if there == here:
                continue
            arrows[(here, there)] += 1
            if layers is None:
                continue
            allowed = layers.get(here)
            if here in PROGRAMS:  # a program's own folder: its main and phases use every room
                allowed = (allowed or []) + [r for r in layers if r.startswith(here + "/")] + \
                    [r for r in layers if r.startswith("common/")]
            if allowed is None:
                failures.append(f"{path}: folder '{here}' is no room of {args.layers}")
            elif there not in allowed:
                failures.append(f"{path}: includes {inc}, but room '{here}' may include only "
                                f"{', '.join(allowed) or 'nothing outside itself'}")
    lengths.sort(reverse=True)
    for n, where, name in lengths:
        if n > args.max_lines:
            failures.append(f"{where}: function '{name}' has {n} lines (at most {args.max_lines})")
    if args.report:
        print(f"functions: {len(lengths)}; longest:")
        for n, where, name in lengths[:15]:
            print(f"  {n:5d}  {name}  ({where})")
        print("include arrows between folders (from -> to: includes):")
        for (a, b), k in sorted(arrows.items()):
            print(f"  {a} -> {b}: {k}")
    for f in failures:
        print("FAIL " + f)
    print(f"structure: {len(lengths)} functions, longest {lengths[0][0] if lengths else 0} lines; "
          f"{sum(arrows.values())} includes between folders; {len(failures)} problem(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
