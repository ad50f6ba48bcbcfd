"""cycles_render.py: run by Blender (blender -b --factory-startup -P cycles_render.py --
SAMPLES DEPTH THREADS SEED OUT.exr [MESH.off]): renders cornell.py's scene with Cycles and prints the
render's own time (without Blender's start-up) as "cycles_render_s S"."""
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cornell  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:]
samples, depth, threads, seed, out = args[:5]
mesh = args[5] if len(args) > 5 else None
scene = cornell.build_blender(bpy, int(samples), int(depth), int(threads), int(seed), mesh)
scene.render.filepath = out
t0 = time.perf_counter()
bpy.ops.render.render(write_still=True)
print("cycles_render_s %.4f" % (time.perf_counter() - t0))
