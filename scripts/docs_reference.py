#!/usr/bin/env python3
"""Writes the documentation site's reference pages from the code, so they cannot drift
from it: the scene file's tables from the Rust records that read them (their doc
comments, their keys, which are required), the Python API from the type stubs and
`cloth.batch` (signatures and docstrings), and the worked examples from their scripts.

    python3 scripts/docs_reference.py            # writes docs/scene.md, python.md, examples.md
    python3 scripts/docs_reference.py --check    # exits 1 naming a page that is stale

Only the standard library: it parses the Rust source for `pub struct` / `pub enum`
bodies (doc comments, `#[serde(...)]` attributes, `pub key: Type`), and the Python with
`ast`.
"""

from __future__ import annotations

import argparse
import ast
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]

# The scene file's tables: (heading, how the file writes it, the Rust file, the type).
# Each type's fields are the table's keys.
TABLES = [
    ("The scene", "top level", "src/scene_file/records.rs", "SceneFile"),
    ("The cloth", "[cloth.<kind>]", "src/scene_file/records.rs", "ClothSpec"),
    ("A garment's pin", "pins = [{ ... }]", "src/scene_file/records.rs", "GarmentPin"),
    ("A body", "[[bodies]]", "src/scene_file/records.rs", "BodyTable"),
    ("A mannequin", "[[bodies]] mannequin = { ... }", "crates/cloth-garment/src/mannequin/measurements.rs", "Measurements"),
    ("The solver", "[solver]", "crates/cloth-core/src/solver/settings.rs", "SolverSettings"),
    ("At rest", "[rest]", "crates/cloth-core/src/solver/rest.rs", "RestCriteria"),
    ("Sewing", "[sewing]", "crates/cloth-garment/src/sewing/settings.rs", "SewingSettings"),
    ("Draping", "[drape]", "crates/cloth-garment/src/sewing/settings.rs", "DrapeSettings"),
    ("Self-collision", "[self_collision]", "crates/cloth-core/src/self_contact/settings.rs", "SelfCollision"),
    ("Outputs", "[output]", "src/scene_file/records.rs", "OutputSpec"),
    ("Animation formats", "[output] animation = \"...\"", "src/scene_file/records.rs", "AnimationFormat"),
]


@dataclass
class Key:
    name: str
    kind: str
    doc: str
    optional: bool


@dataclass
class Item:
    """A struct's fields, or an enum's variants (each with its fields)."""

    doc: str
    keys: list[Key] = field(default_factory=list)
    variants: list[tuple[str, str, list[Key]]] = field(default_factory=list)


def snake(name: str) -> str:
    return re.sub(r"(?<!^)(?=[A-Z])", "_", name).lower()


def docs_and_attrs(lines: list[str]) -> tuple[str, str]:
    """The doc comment and the `#[...]` attributes among `lines`, each joined."""
    doc = " ".join(l.strip()[3:].strip() for l in lines if l.strip().startswith("///"))
    attrs = " ".join(l.strip() for l in lines if l.strip().startswith("#["))
    return doc, attrs


def parse_fields(body: str, all_default: bool) -> list[Key]:
    """`pub name: Type,` entries of a brace body, their docs and serde attributes."""
    keys: list[Key] = []
    pending: list[str] = []
    depth = 0
    for raw in body.splitlines():
        line = raw.strip()
        if depth == 0 and (line.startswith("///") or line.startswith("#[")):
            pending.append(line)
            continue
        m = re.match(r"(?:pub(?:\([a-z]+\))?\s+)?([a-z_][a-z0-9_]*)\s*:\s*(.+?),?$", line) if depth == 0 else None
        if m and not line.startswith("//"):
            doc, attrs = docs_and_attrs(pending)
            pending = []
            if "skip" in attrs:
                continue
            rename = re.search(r'rename\s*=\s*"([^"]+)"', attrs)
            kind = m.group(2).rstrip(",")
            optional = all_default or "default" in attrs or kind.startswith("Option<") or kind.startswith("Vec<")
            keys.append(Key(rename.group(1) if rename else m.group(1), kind, doc, optional))
        elif line and not line.startswith("//"):
            pending = []
        depth += raw.count("{") + raw.count("(") + raw.count("[") - raw.count("}") - raw.count(")") - raw.count("]")
    return keys


def find_item(text: str, name: str) -> Item:
    """The struct or enum `name` of a Rust file."""
    m = re.search(rf"((?:^[ \t]*(?:///[^\n]*|#\[[^\n]*)\n)*)^(?:pub )?(struct|enum) {name}\b[^{{]*\{{", text, re.M)
    if not m:
        raise SystemExit(f"docs_reference: no `pub struct` or `pub enum` {name}")
    doc, attrs = docs_and_attrs(m.group(1).splitlines())
    start, depth, i = m.end(), 1, m.end()
    while depth:
        depth += {"{": 1, "}": -1}.get(text[i], 0)
        i += 1
    body = text[start : i - 1]
    all_default = bool(re.search(r"serde\([^)]*\bdefault\b", attrs))
    item = Item(doc)
    if m.group(2) == "struct":
        item.keys = parse_fields(body, all_default)
        return item
    lowercase = "lowercase" in attrs
    pending: list[str] = []
    lines = body.splitlines()
    k = 0
    while k < len(lines):
        line = lines[k].strip()
        if line.startswith("///") or line.startswith("#["):
            pending.append(line)
        else:
            v = re.match(r"([A-Z][A-Za-z0-9]*)\s*(\{|\(|,|$)", line)
            if v:
                vdoc, _ = docs_and_attrs(pending)
                name_of = v.group(1).lower() if lowercase else snake(v.group(1))
                fields: list[Key] = []
                if v.group(2) == "{" and not line.endswith("},"):
                    depth, inner = 1, []
                    k += 1
                    while depth:
                        depth += lines[k].count("{") - lines[k].count("}")
                        if depth:
                            inner.append(lines[k])
                        k += 1
                    fields = parse_fields("\n".join(inner), False)
                    item.variants.append((name_of, vdoc, fields))
                    pending = []
                    continue
                if v.group(2) == "{":
                    fields = parse_fields(line[line.index("{") + 1 : line.rindex("}")].replace(",", ",\n"), False)
                item.variants.append((name_of, vdoc, fields))
            pending = []
        k += 1
    return item


SCALARS = {
    "String": "string",
    "PathBuf": "path",
    "f64": "number",
    "f32": "number",
    "bool": "true or false",
    "Vec3": "[x, y, z]",
    "UpAxis": '"y" or "z"',
    "EdgeRef": "edge name or index",
    "Integrator": '"explicit_euler" or "implicit_euler"',
    "AnimationFormat": '"pc2" or "gltf"',
}


def toml_type(rust: str) -> str:
    """How a key of Rust type `rust` is written in TOML."""
    rust = rust.strip()
    if m := re.fullmatch(r"Option<(.+)>", rust):
        return toml_type(m.group(1))
    if m := re.fullmatch(r"(?:Vec|Box)<(.+)>", rust):
        inner = toml_type(m.group(1))
        return f"array of {inner}" if rust.startswith("Vec") else inner
    if m := re.fullmatch(r"\[(.+);\s*(\d+)\]", rust):
        return f"{m.group(2)} {toml_type(m.group(1))}s"
    if rust in SCALARS:
        return SCALARS[rust]
    if re.fullmatch(r"[ui](8|16|32|64|size)", rust):
        return "integer"
    return f"table ({rust})"


def key_table(keys: list[Key]) -> list[str]:
    if not keys:
        return []
    out = ["| key | type | | meaning |", "|---|---|---|---|"]
    for k in keys:
        kind = toml_type(k.kind).replace("|", "\\|")
        out.append(f"| `{k.name}` | {kind} | {'optional' if k.optional else '**required**'} | {k.doc} |")
    return out


def scene_page() -> str:
    out = [
        "# Scene file reference",
        "",
        "<!-- Written by scripts/docs_reference.py from the Rust records that read scene",
        "files: do not edit; run the script. -->",
        "",
        "A scene is one TOML file: the cloth, its fabric, the bodies, the solver and its stages,",
        "and the outputs. Paths in it are relative to the file; unknown keys are refused, and",
        "every error names the file, the line or key, and what was expected. The shipped",
        "scenes under `assets/scenes` are worked examples.",
    ]
    for heading, written, path, name in TABLES:
        item = find_item((REPO / path).read_text(), name)
        out += ["", f"## {heading}: `{written}`", ""]
        if item.doc:
            out += [item.doc, ""]
        out += key_table(item.keys)
        for vname, vdoc, fields in item.variants:
            out += ["", f"### `{vname}`", ""]
            if vdoc:
                out += [vdoc, ""]
            out += key_table(fields)
    return "\n".join(out).rstrip() + "\n"


def signature(fn: ast.FunctionDef) -> str:
    args = ast.unparse(fn.args)
    returns = f" -> {ast.unparse(fn.returns)}" if fn.returns else ""
    return f"{fn.name}({args}){returns}"


def clean(doc: str | None) -> str:
    """A docstring's reStructuredText roles and literals as Markdown code."""
    doc = re.sub(r":[a-z]+:`~?([^`]+)`", r"`\1`", doc or "")
    return doc.replace("``", "`")


def python_items(tree: ast.Module, public: set[str] | None) -> list[str]:
    out: list[str] = []
    for node in tree.body:
        if not isinstance(node, (ast.ClassDef, ast.FunctionDef)) or node.name.startswith("_"):
            continue
        if public is not None and node.name not in public:
            continue
        if isinstance(node, ast.FunctionDef):
            out += ["", f"### `{signature(node)}`", "", clean(ast.get_docstring(node))]
            continue
        out += ["", f"### class `{node.name}`", "", clean(ast.get_docstring(node))]
        for member in node.body:
            if not isinstance(member, ast.FunctionDef) or (member.name.startswith("_") and member.name != "__init__"):
                continue
            decorators = {ast.unparse(d) for d in member.decorator_list}
            if any(d.endswith(".setter") for d in decorators):
                continue
            what = "property " if "property" in decorators else ""
            shown = member.name if what else signature(member)
            doc = clean(ast.get_docstring(member))
            out += ["", f"- {what}`{shown}`" + (f": {' '.join(doc.split())}" if doc else "")]
    return out


def python_page() -> str:
    stubs = ast.parse((REPO / "python/cloth/_cloth.pyi").read_text())
    batch = ast.parse((REPO / "python/cloth/batch.py").read_text())
    exported: set[str] = set()
    for node in batch.body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", "") == "__all__" for t in node.targets):
            exported = {ast.literal_eval(e) for e in node.value.elts}
    out = [
        "# Python reference",
        "",
        "<!-- Written by scripts/docs_reference.py from python/cloth/_cloth.pyi and",
        "python/cloth/batch.py: do not edit; run the script. -->",
        "",
        "`pip install cloth-drape` (the import is `cloth`). Arrays are numpy, units SI.",
        "",
        "## `cloth`",
        "",
        clean(ast.get_docstring(stubs)),
    ]
    out += python_items(stubs, None)
    out += ["", "## `cloth.batch`", "", clean(ast.get_docstring(batch))]
    out += python_items(batch, exported)
    return "\n".join(out).rstrip() + "\n"


def examples_page() -> str:
    out = [
        "# Worked examples",
        "",
        "<!-- Written by scripts/docs_reference.py from python/examples: do not edit; run",
        "the script. The test suite runs every example. -->",
        "",
        "Each is a script under `python/examples` that takes an output folder.",
    ]
    for path in sorted((REPO / "python/examples").glob("*.py")):
        source = path.read_text()
        doc = ast.get_docstring(ast.parse(source)) or ""
        out += ["", f"## {path.stem.replace('_', ' ').capitalize()}", "", doc, "", "```python", source.rstrip(), "```"]
    return "\n".join(out).rstrip() + "\n"


PAGES = {"docs/scene.md": scene_page, "docs/python.md": python_page, "docs/examples.md": examples_page}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if a page is not what the code says")
    parser.add_argument("--out", type=Path, default=REPO, help="write the pages under this folder (default: the repository)")
    args = parser.parse_args()
    stale = []
    for path, make in PAGES.items():
        text = make()
        target = args.out / path
        if args.check:
            if not target.exists() or target.read_text() != text:
                stale.append(path)
        else:
            target.parent.mkdir(exist_ok=True)
            target.write_text(text)
    for path in stale:
        print(f"{path} is stale: run python3 scripts/docs_reference.py", file=sys.stderr)
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
