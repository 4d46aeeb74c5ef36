"""Where `brdf fit --for` spends its time, model by model.

For each RGL file named (default: every one under $BRDF_DATA/rgl) and each
model a renderer renders exactly (the candidates of `brdf select --for` on
cc_iris_purple_gem, where every candidate is on), the model's appearance fit
as `--for` makes it (`brdf fit --model M [--lobes K] --json`), one at a
time on two threads: the 32-px mean FLIP of its best BRDF-space candidate,
of its best candidate, its 128-px mean FLIP, the seconds of its candidates
and of those in the image objective. One JSON line per model, then per
file and renderer the sums and the winner.

    BRDF_DATA=... python benches/peers/for_stages.py target/release/brdf [FILE.bsdf ...]
"""

import json
import os
import subprocess
import sys

TARGETS = ["mitsuba", "blender", "materialx", "gltf"]


def run(brdf, args):
    out = subprocess.run([brdf, *args, "--json", "--quiet"], capture_output=True, text=True)
    if out.returncode:
        raise SystemExit(f"brdf {' '.join(args)}: {out.stderr}")
    return json.loads(out.stdout)


def mean_flip(image):
    return sum(light["flip"] for light in image["lights"]) / len(image["lights"])


def main():
    brdf, names = sys.argv[1], sys.argv[2:]
    data = os.path.join(os.environ["BRDF_DATA"], "rgl")
    names = names or sorted(f for f in os.listdir(data) if f.endswith(".bsdf"))
    film = os.path.join(data, "cc_iris_purple_gem_rgb.bsdf")
    labels = {t: [c["label"] for c in run(brdf, ["select", "--data", film, "--for", t])["candidates"]]
              for t in TARGETS}
    for name in names:
        path = os.path.join(data, name)
        rows = {}
        for label in sorted({m for t in TARGETS for m in labels[t]}):
            fit = run(brdf, ["fit", "--data", path, "--model", label.split(" (")[0],
                             "--lobes", label.split("(")[1].split()[0] if "(" in label else "1"])
            row = model_row_from(fit, label)
            rows[label] = row
            print(json.dumps({"file": name, **row}), flush=True)
        for t in TARGETS:
            mine = [rows[m] for m in labels[t]]
            best = min(mine, key=lambda r: r["flip128"])
            print(json.dumps({
                "file": name, "renderer": t, "seconds": round(sum(r["seconds"] for r in mine), 1),
                "image_seconds": round(sum(r["image_seconds"] for r in mine), 1), "winner": best["model"],
                "winner_brdf_space_rank": sorted(r["brdf_space_flip32"] for r in mine).index(best["brdf_space_flip32"]) + 1,
            }), flush=True)


def model_row_from(fit, label):
    cands = fit["candidates"][0]
    refined = [c for c in cands if c["objective"] in ("image", "flip")]
    return {
        "model": label,
        "brdf_space_flip32": min(mean_flip(c["image"]) for c in cands if c not in refined),
        "best_flip32": min(mean_flip(c["image"]) for c in cands),
        "flip128": mean_flip(fit["image_errors"][0]),
        "seconds": sum(c["seconds"] for c in cands),
        "image_seconds": sum(c["seconds"] for c in refined),
    }


if __name__ == "__main__":
    main()
