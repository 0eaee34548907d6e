#!/usr/bin/env python3
"""Which imports run back up, in each crate of the workspace.

A crate reads bottom-up when its `lib.rs` declares its modules in order, each
after every module it uses. This script reads every `.rs` file under a crate's
`src/`, finds each path into the crate itself (`crate::a::...`, `super::...`,
grouped `use crate::{a::x, b::y}` included, in `use` lines and inline), maps it
to the top-level module it lands in, and reports:

- the cycles between top-level modules (two modules each reaching the other);
- every import from a module into one declared after it in `lib.rs` (an import
  that runs back up), with file and line, split into library code and the
  code below a file's first `#[cfg(test)]` (unit tests).

`--depth 2` also checks the submodules inside each top-level module folder
against the order its `mod.rs` declares them in.

Usage: python3 scripts/imports.py [--depth 2] [--verbose] [--check] [CRATE_DIR ...]
(default: the root crate and every crate under crates/). Standard library only.
Exit status 0, or with `--check` 1 when anything runs back up or goes round a
cycle (python/tests/test_layering.py holds the crates to it).
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

IDENT = r"[A-Za-z_][A-Za-z0-9_]*"
MOD_DECL = re.compile(rf"^\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+({IDENT})\s*;", re.M)
PATH_START = re.compile(r"\b(crate|super)::")
ROOT = "(lib.rs itself)"


def strip_comments(text: str) -> str:
    """Blank out comments and string literals, keeping line numbers."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("".join("\n" if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append("".join("\n" if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == "'" and i + 2 < n and (text[i + 2] == "'" or (text[i + 1] == "\\" and "'" in text[i + 2 : i + 8])):
            j = text.find("'", i + 2 if text[i + 1] != "\\" else i + 3) + 1
            out.append(" " * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def module_path(src: Path, file: Path) -> list[str]:
    """The module path of a file: src/a/b.rs and src/a/b/mod.rs are [a, b]."""
    parts = list(file.relative_to(src).with_suffix("").parts)
    if parts[-1] in ("mod", "lib", "main"):
        parts = parts[:-1]
    return parts


def split_group(body: str) -> list[str]:
    """Top-level items of a `{a::x, b::{y, z}}` group."""
    items, depth, cur = [], 0, []
    for ch in body:
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
        if ch == "," and depth == 0:
            items.append("".join(cur).strip())
            cur = []
        else:
            cur.append(ch)
    if "".join(cur).strip():
        items.append("".join(cur).strip())
    return items


def targets_at(text: str, i: int, base: list[str]) -> list[list[str]]:
    """Module paths named by the path starting at text[i] (after `crate::` or `super::`s)."""
    rest = text[i:]
    if rest.startswith("{"):
        depth, j = 0, 0
        for j, ch in enumerate(rest):
            depth += ch == "{"
            depth -= ch == "}"
            if depth == 0:
                break
        found = []
        for item in split_group(rest[1:j]):
            m = re.match(rf"({IDENT}(?:::{IDENT})*)", item)
            if m and m.group(1) != "self":
                found.append(base + m.group(1).split("::"))
            elif item.startswith("self"):
                found.append(base)
        return found
    m = re.match(rf"({IDENT}(?:::{IDENT})*)", rest)
    return [base + m.group(1).split("::")] if m else [base]


def imports_of(src: Path, file: Path):
    """(line, is_test, target module path) for every path into the crate in a file."""
    raw = file.read_text(encoding="utf-8")
    text = strip_comments(raw)
    own = module_path(src, file)
    test_from = text.find("#[cfg(test)]")
    test_from = len(text) if test_from < 0 else test_from
    for m in PATH_START.finditer(text):
        start = m.start()
        if start > 0 and text[start - 1] == ":":
            continue  # the middle of a longer path (e.g. `self::super::`), already counted
        is_test = start >= test_from
        if m.group(1) == "crate":
            base, i = [], m.end()
        else:
            # In a unit-test module (`mod tests` inside the file) `super` is the file's module.
            level = own if is_test else own[:-1]
            i = m.end()
            while text.startswith("super::", i):
                level = level[:-1]
                i += len("super::")
            base = list(level)
        line = text.count("\n", 0, start) + 1
        for target in targets_at(text, i, base):
            yield line, is_test, target


def declared(mod_file: Path) -> list[str]:
    return MOD_DECL.findall(strip_comments(mod_file.read_text(encoding="utf-8")))


def module_file(src: Path, path: list[str]) -> Path | None:
    if not path:
        return src / "lib.rs" if (src / "lib.rs").exists() else src / "main.rs"
    for f in (src.joinpath(*path).with_suffix(".rs"), src.joinpath(*path) / "mod.rs"):
        if f.exists():
            return f
    return None


def expand_tree(tree: str) -> list[tuple[list[str], str]]:
    """`a::{b::X, Y as Z}` as ([a, b, X], X) and ([a, Y], Z)."""
    tree = tree.strip()
    brace = tree.find("{")
    if brace < 0:
        name, _, alias = tree.partition(" as ")
        segs = [x for x in name.strip().split("::") if x]
        return [(segs, alias.strip() or (segs[-1] if segs else ""))]
    head = [x for x in tree[:brace].split("::") if x]
    out = []
    for item in split_group(tree[brace + 1 : tree.rfind("}")]):
        for segs, alias in expand_tree(item):
            out.append((head + segs, alias))
    return out


REEXPORT = re.compile(r"\bpub(?:\([^)]*\))?\s+use\s+([^;]+);")


class Resolver:
    """Follows a path through `pub use` re-exports to the module that defines the item."""

    def __init__(self, src: Path):
        self.src = src
        self.cache: dict[tuple[str, ...], tuple[list[str], dict[str, list[str]]]] = {}

    def module(self, path: list[str]):
        key = tuple(path)
        if key not in self.cache:
            f = module_file(self.src, path)
            subs, names = [], {}
            if f is not None:
                text = strip_comments(f.read_text(encoding="utf-8"))
                subs = MOD_DECL.findall(text)
                for tree in REEXPORT.findall(text):
                    for segs, alias in expand_tree(tree):
                        if not segs or alias == "*":
                            continue
                        if segs[0] == "crate":
                            full = segs[1:]
                        elif segs[0] == "self":
                            full = path + segs[1:]
                        elif segs[0] == "super":
                            up = list(path)
                            while segs and segs[0] == "super":
                                up, segs = up[:-1], segs[1:]
                            full = up + segs
                        elif segs[0] in subs:
                            full = path + segs
                        else:
                            continue  # another crate's item
                        names[alias] = full
            self.cache[key] = (subs, names)
        return self.cache[key]

    def resolve(self, path: list[str], depth: int = 0) -> list[str]:
        """The module path the item lands in, re-exports followed."""
        here: list[str] = []
        for k, seg in enumerate(path):
            subs, names = self.module(here)
            if seg in subs:
                here = here + [seg]
            elif seg in names and depth < 16:
                return self.resolve(names[seg] + path[k + 1 :], depth + 1)
            else:
                break
        return here


def check_level(src: Path, prefix: list[str], order: list[str]):
    """Upward imports and cycles between the modules `order` declared under `prefix`."""
    rank = {name: k for k, name in enumerate(order)}
    rank[ROOT] = len(order)
    resolver = Resolver(src)
    edges: dict[tuple[str, str], list[tuple[str, int, bool]]] = {}
    for file in sorted(src.rglob("*.rs")):
        own = module_path(src, file)
        if own[: len(prefix)] != prefix or len(own) <= len(prefix):
            continue
        here = own[len(prefix)]
        if here not in rank:
            continue
        for line, is_test, target in imports_of(src, file):
            named = target
            target = resolver.resolve(target)
            if not prefix and not target and named and named[0] not in ("self", "super"):
                # An item defined in lib.rs itself: the top of the crate, above every module.
                edges.setdefault((here, ROOT), []).append((str(file), line, is_test))
                continue
            if target[: len(prefix)] != prefix or len(target) <= len(prefix):
                continue
            there = target[len(prefix)]
            if there == here or there not in rank:
                continue
            edges.setdefault((here, there), []).append((str(file), line, is_test))
    up = {e: sites for e, sites in edges.items() if rank[e[1]] > rank[e[0]]}
    within = {e for e in edges if ROOT not in e}
    cycles = strongly_connected(list(order), within)
    return up, cycles, bottom_up(order, within) if not cycles else None


def bottom_up(order: list[str], edges: set[tuple[str, str]]) -> list[str]:
    """The declared order changed least to put each module after those it uses."""
    placed: list[str] = []
    left = list(order)
    while left:
        ready = next(n for n in left if all(b in placed for a, b in edges if a == n))
        placed.append(ready)
        left.remove(ready)
    return placed


def strongly_connected(nodes: list[str], edges: set[tuple[str, str]]) -> list[list[str]]:
    """Tarjan's algorithm: the components of more than one module."""
    succ = {n: [b for a, b in edges if a == n] for n in nodes}
    index, low, stack, on, comps, counter = {}, {}, [], set(), [], [0]

    def visit(v: str):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in succ[v]:
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
                comps.append(sorted(comp))

    for n in nodes:
        if n not in index:
            visit(n)
    return comps


def report(crate: Path, depth: int, verbose: bool) -> int:
    """Prints the crate's report; returns how many imports run back up and cycles it found."""
    src = crate / "src"
    root = src / "lib.rs"
    if not root.exists():
        root = src / "main.rs"
    levels = [([], declared(root))]
    if depth >= 2:
        for name in levels[0][1]:
            mod_rs = src / name / "mod.rs"
            if mod_rs.exists():
                levels.append(([name], declared(mod_rs)))
    total_lib = total_test = cycle_count = 0
    manifest = (crate / "Cargo.toml").read_text(encoding="utf-8")
    package = re.search(r'^\[package\][^\[]*?^name\s*=\s*"([^"]+)"', manifest, re.M | re.S)
    print(f"## {package.group(1) if package else crate.name} ({root.relative_to(crate)})")
    for prefix, order in levels:
        up, cycles, suggested = check_level(src, prefix, order)
        where = "::".join(prefix) or "crate"
        lib = sum(1 for sites in up.values() for s in sites if not s[2])
        test = sum(1 for sites in up.values() for s in sites if s[2])
        total_lib += lib
        total_test += test
        cycle_count += len(cycles)
        if not up and not cycles:
            if prefix == [] or verbose:
                print(f"{where}: reads bottom-up ({' < '.join(order)})")
            continue
        print(f"{where}: order {' < '.join(order)}")
        for comp in cycles:
            print(f"  cycle: {' <-> '.join(comp)}")
        if suggested:
            print(f"  bottom-up would be: {' < '.join(suggested)}")
        for (a, b), sites in sorted(up.items()):
            n_lib = sum(1 for s in sites if not s[2])
            n_test = len(sites) - n_lib
            print(f"  up: {a} -> {b}: {n_lib} in library code, {n_test} in unit tests")
            if verbose:
                for f, line, is_test in sites:
                    print(f"      {f}:{line}{' (test)' if is_test else ''}")
    print(f"total running back up: {total_lib} in library code, {total_test} in unit tests\n")
    return total_lib + total_test + cycle_count


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("crates", nargs="*", type=Path)
    parser.add_argument("--depth", type=int, default=1, choices=(1, 2))
    parser.add_argument("--verbose", "-v", action="store_true", help="list every file and line")
    parser.add_argument("--check", action="store_true", help="exit 1 when anything runs back up")
    args = parser.parse_args()
    here = Path(__file__).resolve().parent.parent
    crates = args.crates or [here] + sorted(p for p in (here / "crates").iterdir() if (p / "src").is_dir())
    wrong = sum(report(crate, args.depth, args.verbose) for crate in crates)
    return 1 if args.check and wrong else 0


if __name__ == "__main__":
    sys.exit(main())
