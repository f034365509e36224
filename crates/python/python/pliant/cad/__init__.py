"""STEP import for Pliant (OpenCASCADE through its Python binding ``OCP``).

``python -m pliant.cad import FILE.step --out FILE.glb [--tolerance METRES]`` converts a
STEP assembly (AP203, AP214, AP242) into a binary glTF with one named node per solid, in
metres; ``python -m pliant.cad curve FILE.step --name NAME --out points.json`` samples a
curve for a hose route. The ``pliant`` binary runs the same code (:mod:`.step_mesh`,
embedded in it) for ``[[parts]] step = …`` and ``pliant import``. Needs the PyPI package
``cadquery-ocp-novtk`` (``scripts/install-cad.sh``).
"""

from .step_mesh import (  # noqa: F401
    CONVERTER_VERSION,
    DEFAULT_TOLERANCE,
    StepError,
    check_part21,
    convert,
    extract_curve,
    mesh_step,
)
