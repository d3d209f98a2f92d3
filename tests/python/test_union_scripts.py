"""The union's measuring scripts run and report what they measure (smallest cases only)."""
import json
import subprocess
import sys

import pytest

from conftest import REPO, SHARED_DATA


def run_script(name, *args):
    return subprocess.run([sys.executable, str(REPO / "scripts" / name), *args], capture_output=True, text=True,
                          timeout=600)


def table_rows(markdown):
    """The cells of each row of the first markdown table in the text, header and rule left out."""
    rows = [line.strip().strip("|").split("|") for line in markdown.splitlines() if line.startswith("| ")]
    return [[c.strip() for c in row] for row in rows[1:]]


def test_measure_union_regrid_writes_both_regrids_and_the_peer(tmp_path):
    out = tmp_path / "union_regrid.md"
    r = run_script("measure_union_regrid.py", "--cases", "two spheres", "--sizes", "2", "--out", str(out))
    assert r.returncode == 0, r.stderr
    rows = table_rows(out.read_text())
    assert [row[2] for row in rows] == ["no", "yes"]  # relax_wedges off, then on
    for row in rows:
        assert row[0] == "two spheres" and row[7] == "yes"  # closed and two-manifold
        ours, peer = float(row[3]), float(row[10])
        assert ours >= 30.0 and int(row[5]) == 0  # measured 42.51, no face under 30
        assert 0.0 < peer < ours  # MeshLab's isotropic remeshing of the same union: 27.62


def test_measure_union_regrid_refuses_an_unknown_case(tmp_path):
    r = run_script("measure_union_regrid.py", "--cases", "no such case", "--out", str(tmp_path / "x.md"))
    assert r.returncode != 0 and "unknown case" in r.stderr
    assert not (tmp_path / "x.md").exists()


def test_fuzz_union_regrid_records_seeds_and_compares_them(tmp_path):
    if not (SHARED_DATA / "cad" / "part.off").is_file():
        pytest.skip("the shared meshes are not beside the repository")
    record = tmp_path / "seeds.jsonl"
    r = run_script("fuzz_union_regrid.py", "1", "2", "--out", str(record))
    assert r.returncode == 0, r.stdout + r.stderr
    (row,) = [json.loads(line) for line in record.read_text().splitlines()]
    assert row["seed"] == 1 and row["model"] == "cad/part.off" and "error" not in row
    assert 0 < row["off"] and row["min"] <= row["off"] + 1e-9 and row["faces"] > 0
    # Against a record whose smallest angle was one degree lower, this run is better.
    older = tmp_path / "older.jsonl"
    older.write_text(json.dumps({**row, "min": row["min"] - 1.0}) + "\n")
    r = run_script("fuzz_union_regrid.py", "1", "2", "--compare", str(older))
    assert r.returncode == 0
    assert "seed 1 (cad/part.off) better" in r.stdout and "1 better, 0 worse, 0 the same" in r.stdout
