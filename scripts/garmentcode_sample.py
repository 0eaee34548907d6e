#!/usr/bin/env python3
"""New GarmentCode designs, drawn as the shared corpus was but with another seed.

    python3 scripts/garmentcode_sample.py GARMENTCODE_DIR SEED COUNT OUT_DIR

The shared corpus (../shared/garmentcode/patterns/rand_1_NNN.json) was drawn by
GarmentCode's own design sampler from its default design space with seed 1, for its mean
body. Draping only those, the engine is tuned to 60 designs; this draws others, named
rand_SEED_NNN.json, to drape as a user would bring them.

GARMENTCODE_DIR is a checkout of maria-korosteleva/GarmentCode (MIT licence; its
pygarment package and assets/ are used from there, nothing is copied). Its Python needs
numpy<2, scipy, pyyaml, svgwrite, svgpathtools, cairosvg and matplotlib (GarmentCode's
serialiser draws each pattern as SVG and PNG beside the JSON; those are left in
OUT_DIR/drawings/).

The same seed gives the same designs (their parameters), but not the same files byte for
byte: GarmentCode writes a design's panels and stitches in an order that changes from one
run to the next, and with it the engine's particle numbering.

Each design goes through the sampler's own checks before it is kept, as in GarmentCode's
pattern_sampler.py: known bad parameter combinations, a total length that fits the body,
and no panel crossing itself; a design that fails one is drawn again, up to 100 times.
"""
import importlib.util
import random
import shutil
import sys
from pathlib import Path

TRIES = 100


def load_sampler_module(root):
    """GarmentCode's pattern_sampler.py, for its parameter checks (it runs nothing on import)."""
    spec = importlib.util.spec_from_file_location("pattern_sampler", root / "pattern_sampler.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    root, seed, count, out = Path(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), Path(sys.argv[4])
    if not (root / "pygarment").is_dir():
        sys.exit(f"{root}: not a GarmentCode checkout (no pygarment/ in it)")
    sys.path.insert(0, str(root))
    import numpy as np
    import pygarment
    from assets.bodies.body_params import BodyParameters
    from assets.garment_programs.meta_garment import (
        IncorrectElementConfiguration,
        MetaGarment,
        TotalLengthError,
    )

    checks = load_sampler_module(root)
    random.seed(seed)
    np.random.seed(seed)
    body = BodyParameters(root / "assets" / "bodies" / "mean_all.yaml")
    sampler = pygarment.DesignSampler(str(root / "assets" / "design_params" / "default.yaml"))
    out.mkdir(parents=True, exist_ok=True)
    drawings = out / "drawings"
    for k in range(1, count + 1):
        name = f"rand_{seed}_{k:03d}"
        for _ in range(TRIES):
            design = sampler.randomize()
            try:
                checks.assert_param_combinations(design)
                piece = MetaGarment(name, body, design)
                piece.assert_total_length()
            except (IncorrectElementConfiguration, TotalLengthError):
                continue
            if not piece.is_self_intersecting():
                break
        else:
            sys.exit(f"{name}: no valid design in {TRIES} draws")
        folder = piece.assembly().serialize(
            str(drawings), tag="", to_subfolder=True, with_3d=False, with_text=False, view_ids=False
        )
        spec = next(Path(folder).glob("*_specification.json"))
        shutil.copy(spec, out / f"{name}.json")
        meta = design["meta"]
        print(name, meta["upper"]["v"], meta["bottom"]["v"], meta["wb"]["v"], flush=True)


if __name__ == "__main__":
    main()
