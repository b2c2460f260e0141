"""CAD files (STEP through the OpenCASCADE plugin) from Python and from the command: the same bits,
the exact B-rep against the closed form, the tessellation's error within its deflection's bound,
an assembly's materials and names, and a robot whose link mesh is a STEP file.
"""
import json
import math
import os
import subprocess

import pytest

import massprops

DATA = os.environ.get("MASSPROPS_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))
CLI = os.environ.get("MASSPROPS_CLI", "massprops")
PLATE = os.path.join(DATA, "cad", "drilled_plate.step")
ASSEMBLY = os.path.join(DATA, "cad", "fixture_assembly.step")
# 40 × 40 × 10 mm with a hole of radius 8 mm: volume and surface area in mm.
PLATE_V = 40 * 40 * 10 - math.pi * 64 * 10
PLATE_A = 2 * (40 * 40 - math.pi * 64) + 4 * 40 * 10 + 2 * math.pi * 8 * 10


def command_json(*args):
    out = subprocess.run([CLI, *args, "--format", "json", "-q"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def test_step_from_python_is_the_commands_result():
    r = massprops.load(PLATE, deflection=0.02)
    c = command_json(PLATE, "--deflection", "0.02")
    mine = r.to_dict()
    for key in ("volume", "mass", "center_of_mass", "inertia_com", "brep", "unit", "unit_source"):
        assert mine[key] == c[key], key
    assert r.unit == "mm"
    # The exact B-rep is the answer; the tessellation beside it is the check.
    assert r.brep["result"] == "brep" and r.brep["mesh_checked"]
    assert abs(r.volume * 1e9 - PLATE_V) < 1e-9 * PLATE_V
    assert abs(r.brep["mesh"]["volume"] * 1e9 - PLATE_V) <= 1.5 * PLATE_A * 0.02


@pytest.mark.parametrize("deflection", [0.05, 0.01])
def test_mesh_error_within_the_deflection_bound(deflection):
    r = massprops.load(PLATE, deflection=deflection, angular_deflection=3.0, brep=False)
    dv = abs(r.volume * 1e9 - PLATE_V)
    assert 0 < dv <= 1.5 * PLATE_A * deflection
    assert r.brep["deflection"] == deflection
    assert r.brep["volume_difference"] == pytest.approx((r.volume * 1e9 - PLATE_V) / PLATE_V, rel=1e-6)


def test_brep_result_is_the_closed_form():
    r = massprops.load(PLATE, brep=True)
    assert r.brep["result"] == "brep"
    assert abs(r.volume * 1e9 - PLATE_V) < 1e-9 * PLATE_V
    # Izz of the plate less the cylinder's, at 1000 kg/m^3, in kg m^2.
    a, t, rr = 0.04, 0.01, 0.008
    izz = 1000 * (a * a * t * (2 * a * a) / 12 - math.pi * rr * rr * t * rr * rr / 2)
    assert r.inertia_com[2][2] == pytest.approx(izz, rel=1e-9)


def test_assembly_materials_names_and_a_density_map():
    r = massprops.load(ASSEMBLY, densities={"pin": 8000})
    assert [p.part for p in r.parts] == ["base", "post", "pin", "pin"]
    assert [p.density for p in r.parts] == [7850, 2700, 8000, 8000]
    assert "steel" in r.parts[0].density_source and r.parts[2].density_source is None
    assert r.mass == pytest.approx(sum(p.mass for p in r.parts), rel=1e-12)
    stated = massprops.load(ASSEMBLY, density=1000)  # a stated density overrides the materials
    assert stated.density == 1000 and not stated.parts
    assert any("material" in w for w in stated.warnings)


def test_bad_keywords():
    with pytest.raises(ValueError):
        massprops.load(PLATE, deflection=-1)
    with pytest.raises(ValueError, match="interference_pairs"):
        massprops.load(PLATE, interference_pairs=-1)
    # A shell needs the mesh: computed from it, with a warning that says so.
    r = massprops.load(PLATE, brep=True, shell=1.0)
    assert any("needs a mesh" in w for w in r.warnings)


def test_fill_a_robot_whose_mesh_is_a_step_file(tmp_path):
    urdf = tmp_path / "plate.urdf"
    urdf.write_text('<robot name="r"><link name="plate"><collision><geometry><mesh filename="%s"/></geometry>'
                    '</collision></link></robot>' % PLATE)
    report = massprops.fill(str(urdf))
    link = report["links"][0]
    assert link["status"] == "filled"
    # The file declares millimetres; the mesh is within its deflection of the solid.
    assert link["mass"] == pytest.approx(1000 * PLATE_V * 1e-9, rel=1e-3)
    assert link["center_of_mass"][2] == pytest.approx(0.005, rel=1e-9)


def test_batch_reads_step_files_beside_meshes(tmp_path):
    import shutil
    for name in (PLATE, ASSEMBLY, os.path.join(DATA, "meshes", "spot.obj")):
        shutil.copy(name, tmp_path)
    out = tmp_path / "results.jsonl"
    p = subprocess.run([CLI, "batch", str(tmp_path), "-o", str(out), "-q", "--deflection", "0.02"],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    records = {os.path.basename(r["file"]): r for r in map(json.loads, out.read_text().splitlines())}
    assert all(r["status"] == "ok" for r in records.values())
    plate = records["drilled_plate.step"]["result"]
    assert plate["brep"]["deflection"] == 0.02
    assert abs(plate["volume"] * 1e9 - PLATE_V) <= 1e-9 * PLATE_V
    assert [p["part"] for p in records["fixture_assembly.step"]["result"]["parts"]] == ["base", "post", "pin", "pin"]
    assert "brep" not in records["spot.obj"]["result"]


def test_parts_carry_their_component_name_and_declared_unit():
    # An AP203 assembly whose two blocks declare inches and millimetres (written in Creo's habits
    # by tests/cad/field/make_blocks.py): composed in SI as the sum of the closed forms.
    path = os.path.join(os.path.dirname(__file__), "..", "cad", "field", "mixed_units_assembly.stp")
    r = massprops.load(path, parts=True)
    assert [(p.part, p.instance, p.declared_unit) for p in r.parts] == [
        ("INCH_BLOCK", "INCH_BLOCK:1", "INCH"), ("MM_BLOCK", "MM_BLOCK:1", "MILLIMETRE")]
    inch = 0.0254
    assert r.parts[0].volume == pytest.approx(6 * inch ** 3, rel=1e-12)
    assert r.volume == pytest.approx(6 * inch ** 3 + 6e-6, rel=1e-12)


def test_an_assembly_dropped_part_by_part_rests_as_it_was_built(tmp_path):
    """`rbsim ASSEMBLY.step --parts --separate`: each solid its own body, placed as the file places
    it; dropped from 1 cm they come to rest where the assembly had them (base on the ground, the
    post on the base, the pins in their holes), at the heights massprops gives their centers of mass.
    Without --separate the assembly falls as one body of the parts' composed mass."""
    rbsim = os.environ.get("MASSPROPS_RBSIM", "rbsim")
    parts = command_json(ASSEMBLY, "--parts")["parts"]
    out = tmp_path / "apart"
    subprocess.run([rbsim, ASSEMBLY, "--parts", "--separate", "--out", str(out), "--outputs", "csv", "-q"],
                   check=True, capture_output=True)
    rest = json.loads((out / "summary.json").read_text())
    assert rest["at_rest"] and len(rest["parts"]) == len(parts) == 4
    for p, q in zip(parts, rest["parts"]):
        assert q["name"].startswith("fixture_assembly/" + p["part"])
        assert q["com_height"] == pytest.approx(p["center_of_mass"][2], abs=2e-5), q["name"]
        assert q["support"] == "face" and q["down_in_part"] == pytest.approx([0, 0, -1], abs=1e-6)
    out = tmp_path / "whole"
    subprocess.run([rbsim, ASSEMBLY, "--parts", "--out", str(out), "--outputs", "csv", "-q"], check=True,
                   capture_output=True)
    (whole,) = json.loads((out / "summary.json").read_text())["parts"]
    composed = command_json(ASSEMBLY, "--parts")
    assert whole["com_height"] == pytest.approx(composed["center_of_mass"][2], abs=2e-5)
