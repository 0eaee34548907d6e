"""The type stubs (python/cloth/_cloth.pyi) are the native module's contract: every name in
them exists in the module and every public name of the module is in them, with the same
parameters and kinds (method, static method, property); values have the stubs' types; and
every public class, function, method and property has a docstring."""

from __future__ import annotations

import ast
import importlib
import importlib.util
import inspect
from pathlib import Path

import numpy as np
import pytest

import cloth
import cloth._cloth as native

REPO = Path(__file__).resolve().parents[2]
STUB_PATH = REPO / "python" / "cloth" / "_cloth.pyi"
TREE = ast.parse(STUB_PATH.read_text())


def public(name: str) -> bool:
    return not name.startswith("_")


def decorator_names(node: ast.FunctionDef) -> set[str]:
    out = set()
    for d in node.decorator_list:
        if isinstance(d, ast.Name):
            out.add(d.id)
        elif isinstance(d, ast.Attribute):
            out.add(d.attr)  # "setter" of @positions.setter
    return out


class StubClass:
    def __init__(self, node: ast.ClassDef):
        self.node = node
        self.name = node.name
        self.final = any(isinstance(d, ast.Name) and d.id == "final" for d in node.decorator_list)
        self.methods: dict[str, ast.FunctionDef] = {}
        self.properties: dict[str, ast.FunctionDef] = {}
        self.setters: set[str] = set()
        self.static: set[str] = set()
        self.attributes: dict[str, ast.expr] = {}
        for item in node.body:
            if isinstance(item, ast.FunctionDef):
                decorators = decorator_names(item)
                if "setter" in decorators:
                    self.setters.add(item.name)
                elif "property" in decorators:
                    self.properties[item.name] = item
                else:
                    self.methods[item.name] = item
                    if "staticmethod" in decorators:
                        self.static.add(item.name)
            elif isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name):
                self.attributes[item.target.id] = item.annotation

    def public_members(self) -> set[str]:
        names = set(self.methods) | set(self.properties) | set(self.attributes)
        return {n for n in names if public(n)}


CLASSES = {n.name: StubClass(n) for n in TREE.body if isinstance(n, ast.ClassDef)}
FUNCTIONS = {n.name: n for n in TREE.body if isinstance(n, ast.FunctionDef)}
VARIABLES = {
    n.target.id: n.annotation for n in TREE.body if isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name)
}


def stub_public_names() -> set[str]:
    return {n for n in [*CLASSES, *FUNCTIONS, *VARIABLES] if public(n)}


def runtime_public_names() -> set[str]:
    return {n for n in dir(native) if public(n) and not inspect.ismodule(getattr(native, n))}


# ------------------------------------------------------------------------------- names


def test_the_stub_and_the_module_name_the_same_things():
    stub, runtime = stub_public_names(), runtime_public_names()
    assert not stub - runtime, f"in the stub, missing from cloth._cloth: {sorted(stub - runtime)}"
    assert not runtime - stub, f"in cloth._cloth, missing from the stub: {sorted(runtime - stub)}"
    assert isinstance(native.__version__, str)


def test_the_package_re_exports_the_module():
    for name in runtime_public_names() | {"__version__"}:
        assert name in cloth.__all__, name
        assert getattr(cloth, name) is getattr(native, name), name
    for name in cloth.__all__:
        assert hasattr(cloth, name), name


def base_members(cls) -> set[str]:
    out = set()
    for base in cls.__mro__[1:]:
        out |= {n for n in dir(base) if public(n)}
    return out


@pytest.mark.parametrize("name", sorted(CLASSES))
def test_class_members_match_the_stub(name):
    stub = CLASSES[name]
    cls = getattr(native, name)
    assert inspect.isclass(cls)
    runtime = {n for n in dir(cls) if public(n)} - base_members(cls)
    expected = stub.public_members()
    if issubclass(cls, BaseException):
        # An exception's fields are set on each instance (see test_errors).
        expected -= set(stub.attributes)
    assert not expected - runtime, f"{name}: in the stub, missing: {sorted(expected - runtime)}"
    assert not runtime - stub.public_members(), f"{name}: not in the stub: {sorted(runtime - stub.public_members())}"
    for m in stub.properties:
        if public(m):
            assert inspect.isdatadescriptor(inspect.getattr_static(cls, m)), f"{name}.{m} is not a property"
    for m in stub.static:
        assert isinstance(inspect.getattr_static(cls, m), staticmethod), f"{name}.{m} is not a static method"
    for m in set(stub.methods) - stub.static:
        if public(m):
            raw = inspect.getattr_static(cls, m)
            assert callable(raw) and not isinstance(raw, (staticmethod, classmethod)), f"{name}.{m} is not a method"
    for a in stub.attributes:
        if not issubclass(cls, BaseException):
            assert inspect.isdatadescriptor(inspect.getattr_static(cls, a)), f"{name}.{a} is not an attribute"


def test_simulation_error_is_a_runtime_error():
    assert issubclass(native.SimulationError, RuntimeError)
    assert not issubclass(native.SimulationError, ValueError)


@pytest.mark.parametrize("name", sorted(n for n, c in CLASSES.items() if c.final))
def test_final_classes_cannot_be_subclassed(name):
    with pytest.raises(TypeError):
        type("Sub", (getattr(native, name),), {})


# ---------------------------------------------------------------------------- signatures


def stub_parameters(node: ast.FunctionDef, drop_self: bool) -> list[tuple[str, str, bool]]:
    a = node.args
    out = []
    positional = a.posonlyargs + a.args
    defaults = [False] * (len(positional) - len(a.defaults)) + [True] * len(a.defaults)
    for arg, has_default in zip(positional, defaults):
        out.append((arg.arg, "positional", has_default))
    if a.vararg:
        out.append((a.vararg.arg, "var_positional", False))
    for arg, default in zip(a.kwonlyargs, a.kw_defaults):
        out.append((arg.arg, "keyword", default is not None))
    if a.kwarg:
        out.append((a.kwarg.arg, "var_keyword", False))
    if drop_self and out and out[0][0] in ("self", "cls"):
        out = out[1:]
    return out


KINDS = {
    inspect.Parameter.POSITIONAL_ONLY: "positional",
    inspect.Parameter.POSITIONAL_OR_KEYWORD: "positional",
    inspect.Parameter.VAR_POSITIONAL: "var_positional",
    inspect.Parameter.KEYWORD_ONLY: "keyword",
    inspect.Parameter.VAR_KEYWORD: "var_keyword",
}


def runtime_parameters(obj, drop_self: bool):
    try:
        sig = inspect.signature(obj)
    except (ValueError, TypeError):
        return None
    out = [(p.name, KINDS[p.kind], p.default is not inspect.Parameter.empty) for p in sig.parameters.values()]
    if drop_self and out and out[0][0] in ("self", "$self", "cls"):
        out = out[1:]
    return out


def signature_cases():
    for name, node in FUNCTIONS.items():
        yield name, lambda n=name: getattr(native, n), node, False
    for cname, c in CLASSES.items():
        for m, node in c.methods.items():
            if m == "__init__":
                yield f"{cname}()", lambda cn=cname: getattr(native, cn), node, True
            elif public(m):
                static = m in c.static
                yield f"{cname}.{m}", lambda cn=cname, mm=m: getattr(getattr(native, cn), mm), node, not static


SIGNATURES = list(signature_cases())


@pytest.mark.parametrize("case", SIGNATURES, ids=[c[0] for c in SIGNATURES])
def test_parameters_match_the_stub(case):
    label, get, node, drop_self = case
    expected = stub_parameters(node, drop_self)
    obj = get()
    got = runtime_parameters(obj, drop_self if not inspect.isclass(obj) else False)
    if got is None:
        pytest.skip(f"{label}: no introspectable signature")
    assert got == expected, f"{label}: runtime {got} != stub {expected}"


# ------------------------------------------------------------------------------ values


def conforms(value, ann: ast.expr) -> bool:
    """Whether `value` has the stub's type `ann` (the forms the stub uses)."""
    if isinstance(ann, ast.Constant):
        if ann.value is None:
            return value is None
        if isinstance(ann.value, str):  # a forward reference
            return conforms(value, ast.parse(ann.value, mode="eval").body)
        return True
    if isinstance(ann, ast.BinOp) and isinstance(ann.op, ast.BitOr):
        return conforms(value, ann.left) or conforms(value, ann.right)
    if isinstance(ann, ast.Name):
        simple = {"int": int, "float": (float, int), "bool": bool, "str": str, "object": object}
        if ann.id in simple:
            if ann.id in ("int", "float") and isinstance(value, bool):
                return False
            return isinstance(value, simple[ann.id])
        if ann.id == "Any":
            return True
        if hasattr(native, ann.id):
            return isinstance(value, getattr(native, ann.id))
        return True
    if isinstance(ann, ast.Subscript):
        head = ann.value
        head_name = head.attr if isinstance(head, ast.Attribute) else getattr(head, "id", "")
        args = ann.slice.elts if isinstance(ann.slice, ast.Tuple) else [ann.slice]
        if head_name == "Literal":
            return value in [a.value for a in args]
        if head_name == "list":
            return isinstance(value, list) and all(conforms(v, args[0]) for v in value)
        if head_name == "dict":
            return isinstance(value, dict) and all(conforms(k, args[0]) and conforms(v, args[1]) for k, v in value.items())
        if head_name == "tuple":
            return isinstance(value, tuple) and len(value) == len(args) and all(conforms(v, a) for v, a in zip(value, args))
        if head_name == "NDArray":
            if not isinstance(value, np.ndarray):
                return False
            dtype = args[0].attr if isinstance(args[0], ast.Attribute) else None
            return dtype is None or value.dtype == np.dtype(dtype)
        return True
    return True


@pytest.fixture(scope="module")
def instances(tmp_path_factory):
    """One instance of each class, made the cheap way."""
    assets = REPO / "assets"
    tmp = tmp_path_factory.mktemp("stub-values")
    fabric = cloth.Fabric.preset("cotton_poplin")
    mesh = cloth.ClothMesh.grid(5, 4, (0.3, 0.2), origin=(0.0, 0.0, 1.0))
    body = cloth.Body.sphere(0.1, position=(0.15, 0.1, 0.5))
    sim = cloth.Simulation(mesh, fabric, bodies=[body], pins=[0])
    snaps = []
    outcome = sim.run_to_rest(max_steps=3, tolerance=1e-12, callback=snaps.append)
    stats = sim.step()
    pattern = cloth.Pattern.load(assets / "patterns" / "skirt.toml")
    garment = cloth.Garment(pattern, 0.06)
    mannequin = cloth.Body.load(assets / "bodies" / "mannequin.obj")
    sewn = garment.sew([mannequin], fabric)
    draped = sewn.drape([mannequin], settings={"max_steps": 3})
    scene = cloth.Scene.from_toml(
        '[cloth.grid]\nnx = 4\nny = 4\nsize = [0.2, 0.2]\n[fabric]\npreset = "silk"\n'
        "[rest]\ntolerance = 1e-5\nconsecutive_steps = 2\nmax_steps = 3\n"
        "[output]\npng = false\nglb = false\n"
    )
    result = scene.run(tmp / "run")
    return {
        "Fabric": fabric,
        "ClothMesh": mesh,
        "Body": body,
        "Pattern": pattern,
        "Garment": garment,
        "SewnGarment": sewn,
        "Draped": draped,
        "StepStats": stats,
        "RestOutcome": outcome,
        "Snapshot": snaps[0],
        "Strain": sim.strain(),
        "Simulation": sim,
        "RunResult": result,
        "Scene": scene,
    }


# Methods without required arguments and without side effects, to call for their values.
PURE_METHODS = {
    ("Fabric", "to_si"),
    ("Fabric", "to_kes"),
    ("Fabric", "presets"),
    ("Garment", "widest_gap"),
    ("Simulation", "strain"),
    ("Simulation", "grid_stretch"),
    ("Simulation", "deepest_penetration"),
    ("StepStats", "to_dict"),
    ("Scene", "check"),
}


@pytest.mark.parametrize("name", sorted(n for n in CLASSES if n != "SimulationError"))
def test_values_have_the_stubs_types(instances, name):
    stub = CLASSES[name]
    obj = instances[name]
    assert isinstance(obj, getattr(native, name))
    wrong = []
    for attr, node in stub.properties.items():
        value = getattr(obj, attr)
        if node.returns is not None and not conforms(value, node.returns):
            wrong.append(f"{name}.{attr} = {value!r:.80} is not {ast.unparse(node.returns)}")
    for attr, ann in stub.attributes.items():
        value = getattr(obj, attr)
        if not conforms(value, ann):
            wrong.append(f"{name}.{attr} = {value!r:.80} is not {ast.unparse(ann)}")
    for cls_name, method in PURE_METHODS:
        if cls_name == name:
            node = stub.methods[method]
            value = getattr(obj, method)()
            if not conforms(value, node.returns):
                wrong.append(f"{name}.{method}() = {value!r:.80} is not {ast.unparse(node.returns)}")
    assert not wrong, "\n".join(wrong)


def test_module_functions_return_the_stubs_types(instances):
    mesh = instances["ClothMesh"]
    for name in ("strain", "grid_stretch"):
        value = getattr(native, name)(mesh, mesh.positions)
        assert conforms(value, FUNCTIONS[name].returns), (name, value)


def test_read_only_properties_cannot_be_set(instances):
    wrong = []
    for name, stub in CLASSES.items():
        if name not in instances:
            continue
        obj = instances[name]
        for attr in stub.properties:
            if attr in stub.setters:
                continue
            try:
                setattr(obj, attr, getattr(obj, attr))
            except AttributeError:
                continue
            wrong.append(f"{name}.{attr}")
    assert not wrong, f"settable, but read-only in the stub: {wrong}"


# -------------------------------------------------------------------------- docstrings


def has_doc(obj) -> bool:
    doc = getattr(obj, "__doc__", None)
    return isinstance(doc, str) and doc.strip() != ""


def undocumented_members(cls, names) -> list[str]:
    missing = []
    for m in sorted(names):
        raw = inspect.getattr_static(cls, m)
        if isinstance(raw, (staticmethod, classmethod)):
            raw = raw.__func__
        if not has_doc(raw):
            missing.append(f"{cls.__name__}.{m}")
    return missing


def test_every_public_name_of_the_native_module_has_a_docstring():
    assert has_doc(native) and has_doc(cloth)
    missing = []
    for name in sorted(runtime_public_names()):
        obj = getattr(native, name)
        if inspect.isclass(obj):
            if not has_doc(obj):
                missing.append(name)
            members = {n for n in dir(obj) if public(n)} - base_members(obj)
            missing += undocumented_members(obj, members)
        elif callable(obj) and not has_doc(obj):
            missing.append(name)
    assert not missing, f"no docstring: {missing}"


def test_the_batch_module_is_documented_if_present():
    if importlib.util.find_spec("cloth.batch") is None:
        pytest.skip("cloth.batch is not installed")
    batch = importlib.import_module("cloth.batch")
    assert has_doc(batch)
    missing = []
    for name in getattr(batch, "__all__", [n for n in dir(batch) if public(n)]):
        obj = getattr(batch, name)
        if getattr(obj, "__module__", None) != "cloth.batch":
            continue
        if (inspect.isclass(obj) or inspect.isfunction(obj)) and not has_doc(obj):
            missing.append(name)
        if inspect.isclass(obj):
            for m, raw in vars(obj).items():
                if public(m) and (inspect.isfunction(raw) or isinstance(raw, (property, staticmethod, classmethod))):
                    target = raw.__func__ if isinstance(raw, (staticmethod, classmethod)) else raw
                    if not has_doc(target):
                        missing.append(f"{name}.{m}")
    assert not missing, f"no docstring: {missing}"


def test_the_package_is_typed():
    folder = Path(cloth.__file__).parent
    assert (folder / "py.typed").is_file()
    assert (folder / "_cloth.pyi").is_file()
