#!/usr/bin/env python3
"""Rebuilds BENCHMARKS.md from the latest table each benchmark script wrote under benchmarks/."""
import pathlib

REPO = pathlib.Path(__file__).resolve().parents[1]
ORDER = ["features", "remesh", "remesh_200k", "union", "union_regrid", "healing", "quadsub"]


def main():
    parts = sorted((REPO / "benchmarks").glob("*.md"),
                   key=lambda p: (ORDER.index(p.stem) if p.stem in ORDER else len(ORDER), p.stem))
    text = ["# Benchmarks", "",
            "Latest table of every benchmark script, each measured against its peers in the same run.",
            "Regenerate one with its script, then this file with `scripts/collect_benchmarks.py`.", ""]
    for p in parts:
        text += [p.read_text().strip(), ""]
    (REPO / "BENCHMARKS.md").write_text("\n".join(text))
    print(f"BENCHMARKS.md: {len(parts)} sections")


if __name__ == "__main__":
    main()
