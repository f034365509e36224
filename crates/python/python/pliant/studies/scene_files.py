"""The files a scene reads — meshes, STEP files with their cache entries, route and
motion CSVs — sent to a study's workers as bytes, so that a cluster needs no shared file
system: the driver reads each file once, a Dask worker plugin
(:class:`SceneFilesPlugin`) writes them into the worker's local directory when the
worker starts (also a worker that joins or is restarted later), and each run's scene
names them relative to that folder.

Layout of the folder on a worker: ``files/<n>/<name>`` for the n-th referenced file
(its own name kept: a STEP file's cache entry is named after it), and the STEP cache
entries of those files in ``.pliant-cache/`` (the scene's cache folder,
``crates/scene/src/step_cache.rs``), so a worker without OpenCASCADE reads the meshes
the driver's machine converted.
"""

from __future__ import annotations

import glob
import hashlib
import os
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, Iterator, Optional, Tuple

from .spec import StudyError

try:
    from distributed.diagnostics.plugin import WorkerPlugin
except ImportError:  # studies without Dask fail later, with a message saying what to install
    WorkerPlugin = object  # type: ignore

CACHE_DIR = ".pliant-cache"  # as crates/scene/src/step_cache.rs CACHE_DIR
MAX_UPLOAD_BYTES = 1 << 30  # larger scenes need a shared file system

# where the worker plugins wrote each upload, by its key (in the worker's process)
_FOLDERS: Dict[str, str] = {}


def references(scene: Dict[str, Any]) -> Iterator[Tuple[Dict[str, Any], str, str]]:
    """Every file a scene names: (the table holding it, its key, the field's path for
    messages) — ``parts[i].mesh``, ``parts[i].step``, ``parts[i].motion.file``,
    ``hoses[i].route.step``, ``hoses[i].route.csv``."""
    for i, part in enumerate(scene.get("parts", [])):
        for key in ("mesh", "step"):
            if isinstance(part.get(key), str):
                yield part, key, f"parts[{i}].{key}"
        motion = part.get("motion")
        if isinstance(motion, dict) and isinstance(motion.get("file"), str):
            yield motion, "file", f"parts[{i}].motion.file"
    for i, hose in enumerate(scene.get("hoses", [])):
        route = hose.get("route")
        if isinstance(route, dict):
            for key in ("step", "csv"):
                if isinstance(route.get(key), str):
                    yield route, key, f"hoses[{i}].route.{key}"


def change_paths(scene: Dict[str, Any], change: Callable[[str], str]) -> Dict[str, Any]:
    """Changes every file path of the scene in place (see :func:`references`); returns it."""
    for table, key, _ in references(scene):
        table[key] = change(table[key])
    return scene


@dataclass
class SceneFiles:
    """A scene's files as bytes, by their name in the workers' folder."""

    key: str  # SHA-256 of names and contents: the upload's name
    files: Dict[str, bytes] = field(repr=False)
    names: Dict[str, str]  # the driver's absolute path -> name in the folder

    @property
    def size(self) -> int:
        return sum(len(b) for b in self.files.values())

    def scene_for_workers(self, scene: Dict[str, Any]) -> Dict[str, Any]:
        """The scene (absolute paths, changed in place) with its paths relative to the
        workers' folder."""
        def sent(path: str) -> str:
            name = self.names.get(os.path.normpath(path))
            if name is None:  # a variant names a file its base scene does not
                raise StudyError(f"{path}: a file the base scene does not name, so the workers were not sent it")
            return name

        return change_paths(scene, sent)


def collect(scene: Dict[str, Any], scene_dir: str) -> SceneFiles:
    """Reads the files ``scene`` names (absolute paths, or relative to ``scene_dir``)
    and the STEP cache entries of its STEP files in ``scene_dir/.pliant-cache``. The sizes
    are checked before anything is read: more than :data:`MAX_UPLOAD_BYTES` is refused."""
    paths: Dict[str, str] = {}  # absolute path -> field that names it first
    for table, key, where in references(scene):
        path = os.path.normpath(os.path.join(scene_dir, table[key]))
        if not os.path.isfile(path):
            raise StudyError(f"{where} = {table[key]}: no such file ({path}); the study's workers need it")
        paths.setdefault(path, where)
    names: Dict[str, str] = {}
    for n, path in enumerate(sorted(paths)):
        names[path] = f"files/{n}/{os.path.basename(path)}"
    steps = [p for p, where in paths.items() if where.endswith(".step")]
    for path in sorted(steps):
        stem = _cache_stem(os.path.basename(path))
        for entry in sorted(glob.glob(os.path.join(glob.escape(scene_dir), CACHE_DIR, glob.escape(stem) + "-*"))):
            names[os.path.normpath(entry)] = f"{CACHE_DIR}/{os.path.basename(entry)}"
    total = sum(os.path.getsize(p) for p in names)
    if total > MAX_UPLOAD_BYTES:
        raise StudyError(
            f"the scene's files take {total / 2**20:.0f} MiB, more than the {MAX_UPLOAD_BYTES / 2**20:.0f} MiB "
            "a study sends to its workers; run the study where the workers share a file system with it")
    files, digest = {}, hashlib.sha256()
    for path, name in sorted(names.items(), key=lambda kv: kv[1]):
        with open(path, "rb") as f:
            files[name] = f.read()
        digest.update(name.encode() + b"\0" + hashlib.sha256(files[name]).digest())
    return SceneFiles(digest.hexdigest()[:16], files, names)


def _cache_stem(step_name: str) -> str:
    """The stem a STEP file's cache entries start with (step_cache.rs ``cache_name``)."""
    stem = os.path.splitext(step_name)[0] or "step"
    return "".join(c if c.isascii() and (c.isalnum() or c in "-_") else "_" for c in stem)


def folder(key: str) -> str:
    """The folder this worker wrote the upload ``key`` into."""
    try:
        return _FOLDERS[key]
    except KeyError:
        raise RuntimeError(f"the scene's files (upload {key}) never reached this worker") from None


class SceneFilesPlugin(WorkerPlugin):
    """A Dask worker plugin: writes an upload's files into the worker's local directory
    at setup (atomically, file by file) and removes them at teardown."""

    def __init__(self, upload: SceneFiles):
        self.upload = upload
        self.name = f"pliant-scene-files-{upload.key}"

    def setup(self, worker):
        root = os.path.join(worker.local_directory, f"pliant-scene-{self.upload.key}")
        os.makedirs(root, exist_ok=True)
        for name, data in self.upload.files.items():
            path = os.path.join(root, name)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            tmp = path + ".tmp"
            with open(tmp, "wb") as f:
                f.write(data)
            os.replace(tmp, path)
        _FOLDERS[self.upload.key] = root

    def teardown(self, worker):
        import shutil

        root = _FOLDERS.pop(self.upload.key, None)
        if root:
            shutil.rmtree(root, ignore_errors=True)


def upload(client, files: SceneFiles) -> None:
    """Registers the plugin with the cluster: every worker, present or to come, gets the
    files before it runs a task."""
    plugin = SceneFilesPlugin(files)
    register: Optional[Callable] = getattr(client, "register_plugin", None)
    if register is not None:
        register(plugin, name=plugin.name)
    else:  # distributed < 2023.9.2
        client.register_worker_plugin(plugin, name=plugin.name)
