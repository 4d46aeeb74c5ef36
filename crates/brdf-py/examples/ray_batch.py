"""Fit every material x model of a database as Ray tasks, and write what
`brdf batch` writes: OUT/fits.jsonl (one JSON line per fit) and the summary
OUT/summary.csv, OUT/summary.md (sorted by material and model, so the same
for any number of workers or completion order).

On this machine (Ray starts a local cluster):

    python ray_batch.py --data "$BRDF_DATA/curet/abrdf.dat" \
        --models lambert,blinn-phong --out fits

On a cluster, the same script with the head node's address (every node needs
the `brdf` wheel installed and the data at the same path):

    python ray_batch.py --address ray://HEAD:10001 --data ... --models ... --out ...

A material is one Ray task, fitted with every model as `brdf batch` fits
(by its path: renderer models fitted for appearance on data that can be
rendered, each line with its image errors). A rerun skips the fits already
in OUT/fits.jsonl.
"""

import argparse
import csv
import json
import os
import sys
import time
from typing import Any, Optional, Union

import brdf
import ray

FITS = "fits.jsonl"
TITLE = "brdf batch: every material x model fit"
Fits = dict[tuple[str, str], dict[str, Any]]
Cell = tuple[Any, ...]

COLUMNS = ["data", "model", "samples used", "samples present", "Ngan L2",
           "FLIP sky", "FLIP studio", "dE2000 (max)", "termination", "seconds"]


@ray.remote
def fit_material(material: str, name: str, models: list[str], channels: str, limit: float,
                 starts: int) -> list[Union[str, dict[str, Any]]]:
    """Load one material and fit every model: batch lines, or error strings.
    Fitted by its path, as `brdf batch` fits: renderer models for appearance
    on data that can be rendered, with its image errors."""
    try:
        brdf.load(material)
    except brdf.BrdfError as e:
        return [str(e) for _ in models]
    out: list[Union[str, dict[str, Any]]] = []
    for model in models:
        t0 = time.perf_counter()
        try:
            report = brdf.fit(material, model, channels=channels,
                              limit_deg=limit, starts=starts).report
        except brdf.BrdfError as e:
            out.append(f"{name} x {model}: {e}")
            continue
        fit = report["fits"][0]
        candidates = report["candidates"][0]
        chosen = next((c for c in candidates if c["chosen"]), None)
        out.append({
            "data": name,
            "model": model,
            "samples_used": fit["samples"],
            "samples_present": report["samples_present"],
            "limit_deg": limit,
            "fit": fit,
            "seconds": time.perf_counter() - t0,
            "for_appearance": None if chosen is None else {
                "objective": chosen["objective"], "lobes": chosen["lobes"],
                "candidates": len(candidates)},
            "image_error": report["image_errors"][0],
            "image_note": report["image_notes"][0],
            "notes": report["notes"][0],
        })
    return out


def read_fits(path: str) -> Fits:
    """The fits already in a fits.jsonl by (data, model); a truncated last
    line (a killed run) is ignored."""
    fits: Fits = {}
    if not os.path.exists(path):
        return fits
    with open(path) as f:
        for line in f:
            try:
                v = json.loads(line)
            except json.JSONDecodeError:
                continue
            fits[(v.get("data", ""), v.get("model", ""))] = v
    return fits


def read_bytes(path: str) -> bytes:
    with open(path, "rb") as f:
        return f.read()


def full(x: Optional[float]) -> str:
    """A CSV cell: the number in full, as `brdf batch` writes it."""
    return "NaN" if x is None else brdf.format_full(x)


def sig(x: Optional[float], digits: int) -> str:
    """A Markdown cell: `digits` significant digits, as `brdf batch`."""
    return "NaN" if x is None else brdf.format_number(x, digits)


def summary_rows(fits: Fits) -> list[list[Cell]]:
    """Rows of the summary: (text cells, numbers with their digits)."""
    rows: list[list[Cell]] = []
    for (data, model) in sorted(fits):
        v = fits[(data, model)]
        f = v["fit"]
        lights = {l["light"]: l for l in (v.get("image_error") or {}).get("lights", [])}
        des = [l["delta_e"] for l in lights.values()]

        def image(x: Optional[float], digits: int) -> Cell:
            return ("text", "-") if x is None else ("num", x, digits)
        rows.append([
            ("text", data), ("text", model),
            ("text", json.dumps(v["samples_used"])),
            ("text", json.dumps(v["samples_present"])),
            ("num", f.get("ngan_l2"), 6),
            image(lights.get("sky", {}).get("flip"), 3),
            image(lights.get("studio", {}).get("flip"), 3),
            image(max(des) if des else None, 2),
            ("text", f.get("termination") or ""),
            ("num", v.get("seconds", f.get("seconds")), 3),
        ])
    return rows


def write_summary(out: str, fits: Fits) -> None:
    """summary.csv (numbers in full) and summary.md, as `brdf batch`."""
    rows = summary_rows(fits)
    with open(os.path.join(out, "summary.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow([full(c[1]) if c[0] == "num" else c[1] for c in r])
    lines = [f"## {TITLE}", "", "| " + " | ".join(COLUMNS) + " |",
             "|" + " --- |" * len(COLUMNS)]
    for r in rows:
        cells = [sig(c[1], c[2]) if c[0] == "num" else c[1] for c in r]
        lines.append("| " + " | ".join(cells) + " |")
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main(argv: Optional[list[str]] = None) -> int:
    p = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    p.add_argument("--data", nargs="+", required=True,
                   help="folders, files, or a CUReT abrdf.dat (every sample)")
    p.add_argument("--models", required=True, help="comma-separated model names")
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--channels", default="rgb", choices=["rgb", "grey"])
    p.add_argument("--limit", type=float, default=80.0, help="angle limit (degrees)")
    p.add_argument("--starts", type=int, default=12, help="multi-start count")
    p.add_argument("--address", default=None,
                   help="Ray cluster address (default: start Ray on this machine)")
    a = p.parse_args(argv)

    models = [brdf.canonical_name(m) for m in a.models.split(",") if m]
    materials = sorted({m for d in a.data for m in brdf.materials(d)})
    os.makedirs(a.out, exist_ok=True)
    path = os.path.join(a.out, FITS)
    done = read_fits(path)
    todo: dict[str, list[str]] = {}
    for m in materials:
        left = [x for x in models if (brdf.data_name(m), x) not in done]
        if left:
            todo[m] = left
    print(f"ray_batch: {len(materials) * len(models)} fits, "
          f"{sum(map(len, todo.values()))} to run", file=sys.stderr)

    ray.init(address=a.address)
    tasks = [fit_material.remote(m, brdf.data_name(m), x, a.channels, a.limit, a.starts)
             for m, x in todo.items()]
    failures: list[str] = []
    # A killed run may have left half a line: end it first.
    half_line = os.path.exists(path) and not read_bytes(path).endswith(b"\n") \
        and os.path.getsize(path) > 0
    with open(path, "a") as f:
        if half_line:
            f.write("\n")
        pending = list(tasks)
        while pending:
            ready, pending = ray.wait(pending, num_returns=1)
            for line in ray.get(ready[0]):
                if isinstance(line, str):
                    failures.append(line)
                else:
                    f.write(json.dumps(line, separators=(",", ":")) + "\n")
                    f.flush()
            print(f"ray_batch: {len(tasks) - len(pending)} of {len(tasks)} materials done",
                  file=sys.stderr)
    ray.shutdown()
    write_summary(a.out, read_fits(path))
    for e in failures:
        print(f"ray_batch: {e}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
