"""Load every exported Mitsuba scene (`brdf export --to mitsuba --scene`)
with `mi.load_file`, as `mitsuba scene.xml` does, and render it at a few
samples per pixel; print, per file, its text, what the scene holds and the
render's mean radiance as JSON."""

import json
import sys

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")


def main():
    out = []
    for f in sys.argv[1:]:
        scene = mi.load_file(f)
        img = np.array(mi.render(scene, spp=16, seed=1))[:, :, :3]
        sphere = [s for s in scene.shapes() if not s.is_emitter()]
        out.append({
            "file": f, "text": open(f).read(), "mitsuba": mi.__version__,
            "shapes": len(scene.shapes()), "emitters": len(scene.emitters()),
            "sphere_bsdf": str(sphere[0].bsdf()).splitlines()[0].split("[")[0].strip(" :")
            if sphere else None,
            "size": list(img.shape[:2]), "finite": bool(np.isfinite(img).all()),
            "mean": [float(x) for x in img.reshape(-1, 3).mean(axis=0)],
        })
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
