"""The module as a Python package: every public function and class documented, type stubs that
mypy's stubtest accepts, and ``python -m massprops`` doing what the command does (same bytes)."""

import inspect
import os
import subprocess
import sys

import massprops
import massprops.dask

DATA = os.environ.get("MASSPROPS_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))


def _own_doc(obj, name):
    doc = inspect.getdoc(obj) or ""
    # pybind11 puts the signature first ("name(self: ..., ...) -> ..."); a docstring is more.
    return any(line.strip() and not line.lstrip().startswith(name + "(") for line in doc.splitlines())


def test_every_public_function_and_class_has_a_docstring():
    missing = []
    for mod in (massprops, massprops.dynamics, massprops.dask):
        names = getattr(mod, "__all__", None) or [n for n in dir(mod) if not n.startswith("_")]
        for n in names:
            o = getattr(mod, n)
            if inspect.ismodule(o) or not callable(o):
                continue
            if not _own_doc(o, n):
                missing.append(f"{mod.__name__}.{n}")
            if inspect.isclass(o):
                missing += [f"{mod.__name__}.{n}.{k}" for k, v in vars(o).items()
                            if not k.startswith("_") and not _own_doc(v, k)]
    assert not missing, "no docstring: " + ", ".join(missing)


def test_stubs_pass_stubtest():
    run = subprocess.run([sys.executable, "-m", "mypy.stubtest", "massprops"], capture_output=True, text=True,
                         cwd="/")
    assert run.returncode == 0, run.stdout + run.stderr


def test_python_m_massprops_is_the_command():
    mesh = os.path.join(DATA, "meshes", "t_handle.obj")
    args = [mesh, "--unit", "m", "--format", "json"]
    module = subprocess.run([sys.executable, "-m", "massprops"] + args, capture_output=True)
    command = subprocess.run([os.environ["MASSPROPS_CLI"]] + args, capture_output=True)
    assert module.returncode == 0 and module.stdout == command.stdout
    bad = subprocess.run([sys.executable, "-m", "massprops", "--density", "-1", mesh], capture_output=True)
    assert bad.returncode == 2 and b"density" in bad.stderr
