#!/usr/bin/env python3
"""Lists the import cycles between the files of a Rust crate's source folder.

Usage: scripts/import_cycles.py [SRC_DIR ...]   (default: src io/src engine/src
integrators/src potentials/src)

A file depends on another when it names an item of the other's module through a path
(`use crate::a::b`, `crate::a::f()`, `super::x`, `self::m::y`, grouped `use crate::{a, b}`).
A parent module declaring `mod child;` is not a dependency (it is structure), and test
code (`#[cfg(test)]` onwards, files named tests.rs) does not count. Prints each strongly
connected component of more than one file and exits 1 when there is one.
"""
import re
import sys
from pathlib import Path

PATH = re.compile(r"\b(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)+|::\{)")


def module_of(src: Path, f: Path) -> list[str]:
    """The module path of file f (src/a/b.rs and src/a/b/mod.rs are a::b)."""
    parts = list(f.relative_to(src).with_suffix("").parts)
    if parts[-1] == "mod" or (len(parts) == 1 and parts[0] in ("lib", "main")):
        parts = parts[:-1]
    return parts


def file_of(modules: dict, path: list[str]):
    """The file that defines the longest prefix of `path` that is a module."""
    for k in range(len(path), 0, -1):
        f = modules.get(tuple(path[:k]))
        if f is not None:
            return f
    return None


def expand_braces(text: str, start: int) -> list[str]:
    """The paths of a grouped `{a, b::c, d::{e, f}}` starting at text[start] == '{'."""
    depth, i, items, cur = 0, start, [], ""
    while i < len(text):
        c = text[i]
        if c == "{":
            depth += 1
            if depth > 1:
                cur += c
        elif c == "}":
            depth -= 1
            if depth == 0:
                items.append(cur)
                break
            cur += c
        elif c == "," and depth == 1:
            items.append(cur)
            cur = ""
        elif depth >= 1:
            cur += c
        i += 1
    out = []
    for it in items:
        it = re.sub(r"\s+", "", it)
        if "{" in it:
            head, _, rest = it.partition("{")
            out += [head + p for p in expand_braces("{" + rest, 0)]
        elif it:
            out.append(it)
    return out


def code_of(f: Path) -> str:
    text = f.read_text()
    cut = text.find("#[cfg(test)]")
    if cut >= 0:
        text = text[:cut]
    # drop comments (doc links are not imports) and string literals
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r'"(?:\\.|[^"\\])*"', '""', text)
    return text


def graph(src: Path):
    files = [f for f in sorted(src.rglob("*.rs")) if f.name != "tests.rs" and "tests" not in f.relative_to(src).parts[:-1]]
    modules = {tuple(module_of(src, f)): f for f in files}
    edges = {f: set() for f in files}
    for f in files:
        here = module_of(src, f)
        code = code_of(f)
        for m in PATH.finditer(code):
            root, rest = m.group(1), m.group(2)
            if rest == "::{":
                tails = [t.split("::") for t in expand_braces(code, m.end() - 1)]
            else:
                tails = [rest.strip(":").split("::")]
            for tail in tails:
                if root == "crate":
                    path = tail
                elif root == "self":
                    path = here + tail
                else:  # super: the parent of this file's module
                    path = here[:-1] + tail
                g = file_of(modules, [p for p in path if p not in ("self", "super")])
                if g is not None and g != f:
                    edges[f].add(g)
    return files, edges


def cycles(files, edges):
    """Strongly connected components of more than one file (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges[v]:
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
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in files:
        if v not in index:
            visit(v)
    return out


def main(argv):
    root = Path(__file__).resolve().parent.parent
    dirs = argv or ["src", "io/src", "engine/src", "integrators/src", "potentials/src"]
    found = 0
    for d in dirs:
        src = (root / d) if not Path(d).is_absolute() else Path(d)
        files, edges = graph(src)
        for comp in cycles(files, edges):
            found += 1
            names = [str(f.relative_to(root)) for f in comp]
            print(f"cycle in {d}: " + " <-> ".join(names))
            for f in comp:
                inner = sorted(str(g.relative_to(root)) for g in edges[f] if g in comp)
                print(f"    {f.relative_to(root)} imports {', '.join(inner)}")
    if found == 0:
        print(f"no import cycles in {', '.join(dirs)}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
