#!/usr/bin/env python3
"""Import loops and upward imports between the crate's files.

Reads every `src/**/*.rs` except the CLI (`src/bin`), the C++ bridge
(`src/ffi*.rs`) and the crate root (`src/lib.rs`, which only declares and
re-exports), maps each file to its module path, and follows its
`use crate::...`, `use super::...`, `crate::x::` and `super::x::` references
(through `pub use` re-exports) to the file that defines what is named. Code
under `#[cfg(test)]` is left out: a test may use anything.

It prints
  (a) the import cycles: strongly connected components of the file graph;
  (b) the upward imports: a file of a lower layer naming a file of a higher
      one, in the order of LAYERS below.

Exit status 1 when there is a cycle or more than MAX_UPWARD upward imports.
Python 3 standard library only.
"""

import os
import re
import sys

# The layers, lowest first. A module may use its own layer and the layers
# below it; top-level modules on the same line are one layer and may use
# each other (as long as no file cycle results).
LAYERS = [
    ["base"],  # the error type, memory and message limits
    ["geometry", "data"],  # three-vectors and the camera; grids, volumes, spacings
    ["datasets", "io"],  # inputs: generated datasets, volume files
    ["octree"],  # the Volume Octree
    ["store"],  # the Volume Octree and its volume on disk (OME-Zarr)
    ["surface"],  # the Surface Octree
    ["transfer"],  # transfer functions
    ["points"],  # the hybrid point/volume representation
    ["plan"],  # budget selection, order, slabs, the draw list
    ["render", "ftb"],  # the compositor, the reference ray caster; front-to-back display
    ["hybrid"],  # what the bridge builds in one call
]
MAX_UPWARD = 2

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src")


def layer_of(module):
    top = module.split("::")[0]
    for rank, names in enumerate(LAYERS):
        if top in names:
            return rank
    return None


def strip_comments_and_strings(text):
    """Blanks comments, string and char literals (keeping newlines)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
        elif text.startswith("/*", i):
            depth, i = 1, i + 2
            while i < n and depth:
                if text.startswith("/*", i):
                    depth, i = depth + 1, i + 2
                elif text.startswith("*/", i):
                    depth, i = depth - 1, i + 2
                else:
                    if text[i] == "\n":
                        out.append("\n")
                    i += 1
        elif c == "r" and re.match(r'r#*"', text[i:i + 10]) and not (i and (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'r(#*)"', text[i:])
            end = '"' + m.group(1)
            j = text.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j + 1
        elif c == "'":
            m = re.match(r"'(\\.[^']*|[^\\'])'", text[i:])
            if m:
                out.append("' '")
                i += m.end()
            else:
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def matching_brace(text, i):
    """Index just past the brace block opening at text[i] == '{'."""
    depth = 0
    for j in range(i, len(text)):
        if text[j] == "{":
            depth += 1
        elif text[j] == "}":
            depth -= 1
            if depth == 0:
                return j + 1
    return len(text)


CFG_TEST = re.compile(r"#\[cfg\(test\)\]")


def strip_test_items(text):
    """Removes `#[cfg(test)]` items; returns the text and test-only module names."""
    test_mods = []
    while True:
        m = CFG_TEST.search(text)
        if not m:
            return text, test_mods
        rest = text[m.end():]
        decl = re.match(r"\s*(?:#\[[^\]]*\]\s*)*(?:pub(?:\([^)]*\))?\s+)?mod\s+(\w+)\s*;", rest)
        if decl:
            test_mods.append(decl.group(1))
            end = m.end() + decl.end()
        else:
            semi, brace = rest.find(";"), rest.find("{")
            if brace < 0 or (0 <= semi < brace):
                end = m.end() + semi + 1
            else:
                end = matching_brace(text, m.end() + brace)
        text = text[:m.start()] + "\n" * text.count("\n", m.start(), end) + text[end:]


def split_top(s):
    """Splits a use-tree list at top-level commas."""
    parts, depth, cur = [], 0, []
    for c in s:
        if c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
        if c == "," and depth == 0:
            parts.append("".join(cur))
            cur = []
        else:
            cur.append(c)
    parts.append("".join(cur))
    return [p.strip() for p in parts if p.strip()]


def use_leaves(tree, prefix=()):
    """(path segments, alias) for every leaf of a use tree."""
    tree = tree.strip()
    brace = tree.find("{")
    if brace >= 0:
        head = [s for s in tree[:brace].split("::") if s.strip()]
        inner = tree[brace + 1:tree.rfind("}")]
        leaves = []
        for part in split_top(inner):
            leaves += use_leaves(part, prefix + tuple(s.strip() for s in head))
        return leaves
    alias = None
    m = re.match(r"(.*)\s+as\s+(\w+)$", tree)
    if m:
        tree, alias = m.group(1), m.group(2)
    segs = prefix + tuple(s.strip() for s in tree.split("::") if s.strip())
    if segs and segs[-1] == "self":
        segs = segs[:-1]
    if alias is None and segs:
        alias = segs[-1]
    return [(segs, alias)]


USE = re.compile(r"(?:^|[;{}\s])(pub(?:\([^)]*\))?\s+)?use\s+([^;]+);")
PATH = re.compile(r"(?<![\w:])((?:crate|super|self)(?:\s*::\s*\w+)+)")
MOD = re.compile(r"(?:^|[;{}\s])(?:pub(?:\([^)]*\))?\s+)?mod\s+(\w+)\s*;")


class Crate:
    def __init__(self, root):
        self.files = {}  # module path -> file path
        self.code = {}  # module path -> stripped code
        self.test_only = set()
        self.reexports = {}  # module -> {name: absolute segments}
        self.uses = {}  # module -> [(absolute segments, is_pub, alias)]
        for dirpath, dirnames, filenames in os.walk(root):
            rel = os.path.relpath(dirpath, root)
            if rel == "bin" or rel.startswith("bin" + os.sep):
                continue
            for name in filenames:
                if not name.endswith(".rs"):
                    continue
                path = os.path.normpath(os.path.join(dirpath, name))
                parts = [] if rel == "." else rel.split(os.sep)
                stem = name[:-3]
                if stem not in ("mod", "lib"):
                    parts.append(stem)
                self.files["::".join(parts) if parts else "crate"] = path
        for module, path in self.files.items():
            with open(path, encoding="utf-8") as f:
                code = strip_comments_and_strings(f.read())
            code, test_mods = strip_test_items(code)
            base = "" if module == "crate" else module
            for t in test_mods:
                self.test_only.add(f"{base}::{t}" if base else t)
            self.code[module] = code
        # a test-only module's submodules are test-only too
        for module in list(self.files):
            if any(module.startswith(t + "::") for t in self.test_only):
                self.test_only.add(module)
        for module, code in self.code.items():
            uses = []
            reexports = {}
            for m in USE.finditer(code):
                is_pub = bool(m.group(1))
                for segs, alias in use_leaves(m.group(2)):
                    absolute = self.absolute(module, segs)
                    if absolute is None:
                        continue
                    uses.append((absolute, is_pub, alias))
                    if is_pub and alias and alias != "*":
                        reexports[alias] = absolute
            self.uses[module] = uses
            self.reexports[module] = reexports

    def parent(self, module):
        if module == "crate":
            return None
        return module.rsplit("::", 1)[0] if "::" in module else "crate"

    def absolute(self, module, segs):
        """Absolute segments (without `crate`) of a path used in `module`, or None if external."""
        segs = list(segs)
        if not segs:
            return None
        here = module  # `self`; `super` is its parent, whether a folder or a file
        if segs[0] == "crate":
            return segs[1:]
        if segs[0] in ("self", "super"):
            cur = here
            while segs and segs[0] in ("self", "super"):
                if segs[0] == "super":
                    cur = self.parent(cur) or "crate"
                segs = segs[1:]
            return ([] if cur == "crate" else cur.split("::")) + segs
        # a 2018 relative path: a child module of the current module
        base = [] if here == "crate" else here.split("::")
        if "::".join(base + [segs[0]]) in self.files:
            return base + segs
        return None

    def resolve(self, segs, depth=0):
        """The module file that defines what the absolute path `segs` names."""
        segs = [s for s in segs if s]
        if depth > 20:
            return None
        best = 0
        for k in range(len(segs), 0, -1):
            if "::".join(segs[:k]) in self.files:
                best = k
                break
        module = "::".join(segs[:best]) if best else "crate"
        rest = segs[best:]
        if rest and rest[0] in self.reexports.get(module, {}):
            return self.resolve(self.reexports[module][rest[0]] + rest[1:], depth + 1)
        return module

    def graph(self):
        """module -> {module: [reasons]} for the files analysed."""
        edges = {}
        for module, code in self.code.items():
            if not self.analysed(module):
                continue
            out = {}
            aliases = {}

            def add(target, why):
                if target and target != module and target != "crate" and self.analysed(target):
                    out.setdefault(target, []).append(why)

            for absolute, _, alias in self.uses[module]:
                if absolute and absolute[-1] == "*":
                    add(self.resolve(absolute[:-1]), "::".join(absolute))
                    continue
                target = self.resolve(absolute)
                add(target, "::".join(absolute))
                if alias and target == "::".join(absolute):
                    aliases[alias] = absolute  # a module: `alias::item` names go on
            body = USE.sub(" ", code)
            for m in PATH.finditer(body):
                segs = [s.strip() for s in m.group(1).split("::")]
                absolute = self.absolute(module, segs)
                if absolute is not None:
                    add(self.resolve(absolute), m.group(1).replace(" ", ""))
            for alias, absolute in aliases.items():
                for m in re.finditer(r"(?<![\w:])" + re.escape(alias) + r"((?:\s*::\s*\w+)+)", body):
                    more = [s.strip() for s in m.group(1).split("::") if s.strip()]
                    add(self.resolve(absolute + more), alias + m.group(1).replace(" ", ""))
            edges[module] = out
        return edges

    def analysed(self, module):
        if module == "crate" or module in self.test_only:
            return False
        return not module.split("::")[0].startswith("ffi")


def strongly_connected(edges):
    index, low, stack, on, comps = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, {}):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            comps.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(edges):
        if v not in index:
            visit(v)
    return [c for c in comps if len(c) > 1]


def main():
    crate = Crate(ROOT)
    edges = crate.graph()
    status = 0

    cycles = strongly_connected(edges)
    print(f"== import cycles (file level): {len(cycles)}")
    for comp in cycles:
        print("  " + " <-> ".join(comp))
        members = set(comp)
        for a in comp:
            for b, why in sorted(edges[a].items()):
                if b in members:
                    print(f"      {a} -> {b}  ({why[0]})")
    if cycles:
        status = 1

    upward = []
    unknown = set()
    for a, outs in sorted(edges.items()):
        la = layer_of(a)
        if la is None:
            unknown.add(a.split("::")[0])
            continue
        for b, why in sorted(outs.items()):
            lb = layer_of(b)
            if lb is None:
                unknown.add(b.split("::")[0])
            elif lb > la:
                upward.append((a, b, why[0]))
    print(f"== upward imports (layer order below): {len(upward)}")
    for a, b, why in upward:
        print(f"  {a} -> {b}  ({why})")
    print("== layers, lowest first")
    for rank, names in enumerate(LAYERS):
        print(f"  {rank}: {', '.join(names)}")
    if unknown:
        print(f"== modules in no layer: {', '.join(sorted(unknown))}")
        status = 1
    if len(upward) > MAX_UPWARD:
        status = 1
    print(f"== files analysed: {len(edges)}; result: {'FAIL' if status else 'ok'}")
    return status


if __name__ == "__main__":
    sys.exit(main())
