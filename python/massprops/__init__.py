"""Exact mass properties of the solids that triangle meshes bound (Python bindings of libmassprops).

    >>> import massprops
    >>> r = massprops.load("part.stl", unit="mm", density=2700)
    >>> r.mass, r.center_of_mass, r.inertia_com, r.principal_moments, r.principal_axes
    >>> r = massprops.mass_properties(vertices, faces, density=1000)    # numpy arrays
    >>> r = massprops.mass_properties(trimesh_mesh)                     # anything with .vertices/.faces

Every call goes through the same pipeline as the ``massprops`` command (checks, findings,
refusals), with the GIL released; ``Result.to_dict()`` is the command's ``--format json`` object,
number for number. Bad input raises ValueError with the command's message (worded with Python's
keywords: ``repair=True``), a file that cannot be opened raises OSError.

Keywords (all optional): ``unit`` ('m', 'cm', 'mm', 'um', 'in', 'ft'; default: what the file
declares, else metres), ``density`` (kg/m³, default 1000) or ``mass`` (kg, the total), ``repair``,
``allow_open``, ``full_check``, ``check_self_intersections``, ``shell`` (an area density in kg/m²:
the surface is a thin shell), ``wall`` (a thickness in the file's unit: a hollow part),
``winding_number`` (with ``samples``, ``seed``), ``path`` ('auto', 'triangles', 'polygons'),
``reader`` ('auto', 'assimp'), ``threads`` (0: every core; the bits do not depend on it),
``parts`` (each OBJ object or group, glTF/3MF/COLLADA node on its own: ``Result.parts``; the whole
is their composition), ``densities`` (a dict, part name or glob -> kg/m³ or ``{"mass": kg}``;
implies ``parts``). CAD files (STEP, IGES, BREP, read by OpenCASCADE): ``deflection`` (the
tessellation's chordal deflection in the file's unit; default ``relative_deflection`` = 1e-3 of
each part's diagonal, 1e-4 with ``brep=False``), ``angular_deflection`` (rad, default 0.5),
``brep`` (True, the default: the exact B-rep's integrals are the result and the tessellation
their check; False: the tessellation's numbers are the result), ``interference_pairs`` (how
many overlapping pairs of solids get their common volume measured, default 100);
``Result.brep`` holds the other side and the differences.

    >>> r = massprops.load("gearbox.step", deflection=0.01, parts=True)
    >>> r.to_dict()["brep"]["volume_difference"]
    >>> r = massprops.load("assembly.obj", densities={"steel*": 7850, "grip": {"mass": 0.1}})
    >>> [(p.part, p.mass) for p in r.parts], r.mass

``fill`` fills every link's inertial of a URDF, SDFormat or MJCF file (``massprops fill``).
"""

import json as _json

import numpy as _np

from . import _core
from ._core import dynamics  # noqa: F401  (massprops.dynamics: RigidBody, World)

__version__ = _core.__version__
__all__ = ["load", "mass_properties", "fill", "Result", "dynamics", "body", "resting_poses", "drop_batch", "main"]


class Result:
    """Mass properties of one solid, in SI units, with what the checks found.

    Attributes: volume (m³), mass (kg), density, center_of_mass (3,), inertia_com (3, 3) about the
    center of mass in the input's axes (off-diagonal entries are the negated products of inertia,
    as URDF and MJCF expect), principal_moments (3,) ascending, principal_axes (3, 3) (columns,
    right-handed), surface_area, physically_valid, warnings (list of str), mesh (dict: the mesh
    report), unit, model, standard_errors (dict of arrays, or None when the result is exact),
    parts (a list of Result, one per part, with ``parts=True``; else empty), part (the part's name
    in such a result; else None), instance (a CAD assembly component's own name, "bolt:2"; else
    None), declared_unit (the length unit a CAD part's own representation declares, as the file
    names it, "INCH"; the numbers are SI all the same; else None).
    """

    def __init__(self, record, redo=None, part_of=False):
        self._record = record
        self._redo = redo  # (path, part or None) -> draws the picture (Result.picture)
        self._part_of = part_of
        a = _np.asarray
        self.volume = record["volume"]
        self.mass = record["mass"]
        self.density = record["density"]
        self.center_of_mass = a(record["center_of_mass"], dtype=float)
        self.inertia_com = a(record["inertia_com"], dtype=float)
        self.principal_moments = a(record["principal_moments"], dtype=float)
        self.principal_axes = a(record["principal_axes"], dtype=float)
        self.surface_area = record["surface_area"]
        self.physically_valid = record["physically_valid"]
        self.warnings = list(record["warnings"])
        self.mesh = record.get("mesh")
        self.unit = record["unit"]
        self.model = record["model"]
        self.source = record["file"]
        self.part = record.get("part")
        self.instance = record.get("instance")
        self.declared_unit = record.get("declared_unit")
        self.parts = [Result(p, redo, True) for p in record.get("parts", [])]
        self.brep = record.get("brep")  # CAD files: the other side of mesh vs exact B-rep, and the differences
        self.density_source = record.get("density_source")
        estimate = record.get("estimate")
        self.standard_errors = None
        if estimate is not None:
            se = estimate["standard_errors"]
            self.standard_errors = {k: (a(v, dtype=float) if isinstance(v, list) else v) for k, v in se.items()}

    def inertia_about(self, point):
        """The inertia tensor about a point (3,) in the input's axes, metres (parallel-axis theorem)."""
        d = self.center_of_mass - _np.asarray(point, dtype=float)
        return self.inertia_com + self.mass * (d @ d * _np.eye(3) - _np.outer(d, d))

    def picture(self, path):
        """Draws this result into ``path`` (.svg or .png), as ``massprops FILE --picture PATH``: four
        views, the center of mass, the principal axes, the equivalent-inertia ellipsoid and the
        bounding box. The solid is read and computed again from where it came from (the file, or
        the arrays) with the same options; a Result rebuilt from a record (unpickled) cannot."""
        import os

        redo = getattr(self, "_redo", None)
        if redo is None:
            raise ValueError("this Result was rebuilt from a record: load the file again to draw it")
        redo(os.fspath(path), self.part if self._part_of else None)

    def to_dict(self):
        """The command's JSON object for this result (a deep copy)."""
        return _json.loads(_json.dumps(self._record))

    def __eq__(self, other):
        return isinstance(other, Result) and self._record == other._record

    def __repr__(self):
        return (f"<massprops.Result {self.source!r}: mass {self.mass:.6g} kg, volume {self.volume:.6g} m^3, "
                f"center of mass {_np.array2string(self.center_of_mass, precision=6)}"
                f"{', ' + str(len(self.warnings)) + ' warning(s)' if self.warnings else ''}>")

    # Pickled as the record: the arrays are rebuilt from it, bit for bit.
    def __getstate__(self):
        return self._record

    def __setstate__(self, record):
        self.__init__(record)


def load(path, **options):
    """Reads, checks and integrates a mesh file, as the ``massprops`` command does."""
    path = str(path)

    def redo(out, part):
        _core.load(path, _picture=out, **({"_picture_part": part} if part else {}), **options)

    return Result(_json.loads(_core.load(path, **options)), redo)


def fill(path, output=None, *, density=1000.0, densities=None, keep_mass=False, source="collision",
         packages=None, repair=False, allow_open=False):
    """Every link's inertial of a URDF, SDFormat or MJCF file, from its geometries.

    Returns the report (a dict: ``links``, each with ``name``, ``status`` ('filled', 'failed',
    'no geometry'), ``mass``, ``center_of_mass``, ``inertia_com``, ``principal_moments``,
    ``message``, ``notes``) with the filled document under ``"document"``; writes it to ``output``
    when given (whole or not at all). ``densities``: link name or glob -> kg/m³ or ``{"mass": kg}``;
    ``keep_mass``: keep each link's stated mass; ``source``: 'collision' or 'visual';
    ``packages``: {name: folder} for package:// and model://. Links that cannot be computed are
    reported and left as they were.
    """
    text, document = _core.fill(str(path), float(density), densities, bool(keep_mass), source, dict(packages or {}),
                                bool(repair), bool(allow_open))
    report = _json.loads(text)
    report["document"] = document
    if output is not None:
        import os
        import tempfile

        output = os.fspath(output)
        if os.path.exists(output) and not os.path.isfile(output):
            raise ValueError(f"{output}: not a regular file; the filled document is written only to one")
        if os.path.exists(output) and os.path.samefile(output, path):
            raise ValueError(f"{output} is the input: write the filled file elsewhere")
        folder = os.path.dirname(os.path.abspath(output))
        fd, temporary = tempfile.mkstemp(dir=folder, prefix=".massprops-fill-")
        try:
            with os.fdopen(fd, "w") as f:
                f.write(document)
            os.replace(temporary, output)
        except BaseException:
            os.unlink(temporary)
            raise
        report["output"] = output
    return report


def _faces_to_arrays(faces):
    """Faces as (indices, offsets, face size): an (m, k) integer array (offsets None: every face
    has k corners; the module reads int32 and int64 in place and casts other integers), or a
    sequence of polygons."""
    if isinstance(faces, _np.ndarray) and faces.ndim == 2:
        if not _np.issubdtype(faces.dtype, _np.integer):
            raise ValueError(f"faces must be integers, not {faces.dtype}")
        k = faces.shape[1]
        return faces.reshape(-1), None, k
    polygons = [_np.asarray(f).reshape(-1) for f in faces]
    for i, f in enumerate(polygons):
        if f.size and not _np.issubdtype(f.dtype, _np.integer):
            raise ValueError(f"faces: face {i} has non-integer corners ({f.dtype})")
    sizes = _np.array([f.size for f in polygons], dtype=_np.int64)
    offsets = _np.concatenate([[0], _np.cumsum(sizes)]).astype(_np.int64)
    indices = _np.concatenate(polygons).astype(_np.int64) if polygons else _np.zeros(0, dtype=_np.int64)
    return indices, offsets, 0


def mass_properties(vertices, faces=None, *, name="<arrays>", **options):
    """Mass properties of the solid a mesh in memory bounds.

    ``vertices``: (n, 3) float64 or float32; ``faces``: an (m, 3) (or (m, k)) integer array of
    0-based vertex indices, or a sequence of polygons. Or pass one object with ``vertices`` and
    ``faces`` attributes (a trimesh.Trimesh, for instance) as the only argument.

    C-contiguous float64 vertices and int32 or int64 faces are used without a cast; other dtypes
    and memory orders are cast once (the faces' dtype changes no bit of the result). Either way
    the library's mesh takes one copy of them, checked as it is copied. The GIL is released
    while the mesh is checked and integrated.
    """
    if faces is None:
        if not (hasattr(vertices, "vertices") and hasattr(vertices, "faces")):
            raise TypeError("mass_properties needs vertices and faces, or one object with .vertices and .faces")
        vertices, faces = vertices.vertices, vertices.faces
    v = _np.asarray(vertices)
    if v.ndim != 2 or v.shape[1] != 3:
        raise ValueError(f"vertices must have shape (n, 3), not {v.shape}")
    if not _np.issubdtype(v.dtype, _np.floating) and not _np.issubdtype(v.dtype, _np.integer):
        raise ValueError(f"vertices must be numbers, not {v.dtype}")
    float32 = v.dtype == _np.float32
    indices, offsets, k = _faces_to_arrays(faces)
    v = _np.ascontiguousarray(v, dtype=_np.float64)

    def redo(out, part):
        _core.solve_arrays(v, indices, offsets, k, float32, name, _picture=out,
                           **({"_picture_part": part} if part else {}), **options)

    return Result(_json.loads(_core.solve_arrays(v, indices, offsets, k, float32, name, **options)), redo)


def body(result):
    """A dynamics.RigidBody from a Result: its center of mass where the mesh's is, its frame the
    principal axes (so the mesh frame is the world frame at the start)."""
    return dynamics.body_from_mass_properties(result.mass, result.center_of_mass, result.inertia_com)


def drop_batch(path, first, count, **options):
    """The outcomes of drops first .. first+count-1 of a part (`resting_poses` takes the same
    keywords): a list of (pose, seconds to rest), the pose an index into the report's "poses", -1
    for a drop that did not come to rest, -2 for one at rest on no stable face. Drop k depends only on (seed, k), so batches run
    anywhere (threads, processes, a Dask cluster) add up to the same drops."""
    return [tuple(o) for o in _core.resting_poses(str(path), int(first), int(count), None, **options)[1]]


def resting_poses(path, drops=1000, *, client=None, drops_per_task=250, **options):
    """On which face of its convex hull a part comes to rest, and how often: the quasi-static
    estimate and `drops` simulated drops, as ``rbsim poses --format json`` reports them (a dict:
    "poses" with "normal", "quasi_static", "drops", "drops_interval95", "drops_simultaneous95",
    "transform", ...).

    Keywords: ``height`` (m, default 0.1), ``seed``, ``ground`` and ``material`` (static friction,
    kinetic friction, restitution; default (0.6, 0.5, 0)), ``collision`` ('hull' or 'mesh'),
    ``dt``, ``max_time``, ``threads`` (0: every core), ``merge_degrees``, and those of
    :func:`load` (``unit``, ``density``, ``mass``, ``repair``, ...).

    With a Dask ``client``, the drops run on the cluster in tasks of ``drops_per_task``
    (massprops.dask.map_tasks); the result is the same as on one machine, to the bit."""
    drops = int(drops)
    if client is None:
        report, _ = _core.resting_poses(str(path), 0, drops, None, **options)
        return _json.loads(report)
    from .dask import map_tasks

    step = max(1, int(drops_per_task))
    items = [(path, first, min(step, drops - first), options) for first in range(0, drops, step)]
    outcomes = [pose for batch in map_tasks(_drop_task, items, client=client) for pose in batch]
    report, _ = _core.resting_poses(str(path), 0, drops, outcomes, **options)
    return _json.loads(report)


def _drop_task(path, first, count, options):
    return drop_batch(path, first, count, **options)


def _command():
    """The ``massprops`` program this module was built with: the one beside it in ``_bin/`` (pip puts
    it there; in the build tree it links to the build's), else the first on PATH."""
    import os
    import shutil

    beside = os.path.join(os.path.dirname(os.path.abspath(__file__)), "_bin", "massprops")
    if os.access(beside, os.X_OK):
        return beside
    found = shutil.which("massprops")
    if found is None:
        raise FileNotFoundError("the massprops command was not found beside the module (_bin/) or on PATH")
    return found


def main(argv=None):
    """``python -m massprops FILE... [options]``: runs the ``massprops`` command with these arguments
    (the same options, outputs and exit status) and returns its exit status."""
    import subprocess
    import sys

    args = list(sys.argv[1:] if argv is None else argv)
    try:
        return subprocess.call([_command()] + args)
    except KeyboardInterrupt:
        return 130
