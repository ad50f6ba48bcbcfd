"""gi_vs_cycles.py: error against time, RayDrive against Cycles (Blender 3.4 from Debian,
CPU, the same threads), on one diffuse global-illumination scene (cornell.py: a Cornell
box, a point light, three diffuse bounces, a box pixel filter for both).

Each renderer is judged against its own reference: the same scene at --reference samples
a pixel with another seed (so it shares no sample with the images it judges). First the
two references are compared with each other (the scenes must be the same picture: least-
squares scale and relative difference). Then for each sample count: median wall time of
--runs renders (the whole command, and the render alone: RayDrive's --stats elapsed_s,
Cycles' bpy render call, which leaves out Blender's start-up), and the relative RMS error
against the reference (RMS over pixels and RGB over the reference's mean). The
figure of merit is time x error^2 (Monte Carlo efficiency): RayDrive's over Cycles' is the
time RayDrive takes for Cycles' error at that sample count, relative to Cycles' time
(below 1: RayDrive gets there first).

Run by gi_vs_cycles.sh (which installs Blender and builds RayDrive); Debian's python3 for
numpy and OpenImageIO.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import OpenImageIO as oiio

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import cornell  # noqa: E402


def read_rgb(path):
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise RuntimeError("cannot read " + path + ": " + oiio.geterror())
    pixels = inp.read_image(format="float")
    inp.close()
    return np.asarray(pixels, dtype=np.float64)[:, :, :3]


def rel_rmse(img, ref):
    return float(np.sqrt(((img - ref) ** 2).mean()) / ref.mean())


class RayDrive:
    name = "raydrive"

    def __init__(self, binary, work, depth, mesh, options=()):
        self.binary, self.work, self.depth, self.mesh = binary, work, depth, mesh
        self.options = list(options)  # e.g. --sampler sobol

    def render(self, samples, seed, out):
        rib = os.path.join(self.work, "cornell_%d.rib" % samples)
        with open(rib, "w") as f:
            f.write(cornell.rib(out, samples, self.depth, os.path.join(HERE, "scenes"), self.mesh))
        stats = out + ".json"
        t0 = time.perf_counter()
        subprocess.run([self.binary, "-q", "--seed", str(seed), "--stats", stats] +
                       self.options + [rib], check=True)
        wall = time.perf_counter() - t0
        with open(stats) as f:
            s = json.load(f)
        rays = s["rays"]["total"] if isinstance(s, dict) else s[0]["rays"]["total"]
        render = s["elapsed_s"] if isinstance(s, dict) else s[0]["elapsed_s"]
        return wall, render, rays


class Cycles:
    name = "cycles"

    def __init__(self, blender, threads, depth, mesh):
        self.blender, self.threads, self.depth, self.mesh = blender, threads, depth, mesh

    def render(self, samples, seed, out):
        t0 = time.perf_counter()
        p = subprocess.run([self.blender, "-b", "--factory-startup", "-noaudio", "-P",
                            os.path.join(HERE, "cycles_render.py"), "--", str(samples),
                            str(self.depth), str(self.threads), str(seed), out]
                           + ([self.mesh] if self.mesh else []),
                           check=True, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        render = None
        for line in p.stdout.splitlines():
            if line.startswith("cycles_render_s "):
                render = float(line.split()[1])
        if render is None or not os.path.exists(out):
            raise RuntimeError("Blender did not render:\n" + p.stdout[-2000:] + p.stderr[-2000:])
        return wall, render, None


def median(xs):
    xs = sorted(xs)
    return xs[len(xs) // 2]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--raydrive", required=True)
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--samples", default="4,16,64")
    ap.add_argument("--reference", type=int, default=1024)
    ap.add_argument("--depth", type=int, default=3)
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--mesh", help="an OFF mesh in place of the two blocks (e.g. the bunny)")
    ap.add_argument("--out", default=os.path.join(HERE, "..", "build", "gi-vs-cycles"))
    ap.add_argument("--raydrive-options", default="",
                    help="more raydrive options, e.g. '--sampler sobol' (its reference too)")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    work = tempfile.mkdtemp()
    mesh = os.path.abspath(a.mesh) if a.mesh else None
    renderers = [RayDrive(a.raydrive, work, a.depth, mesh, a.raydrive_options.split()),
                 Cycles(a.blender, a.threads, a.depth, mesh)]
    tag = "" if mesh is None else "_" + os.path.splitext(os.path.basename(mesh))[0]

    refs = {}
    for r in renderers:
        path = os.path.join(a.out, "ref_%s%s_%d_d%d_%d.exr" % (r.name, tag, a.reference, a.depth, cornell.RES))
        if not os.path.exists(path):
            print("reference: %s at %d samples a pixel ..." % (r.name, a.reference), flush=True)
            tmp = path + ".tmp.exr"
            wall, _, _ = r.render(a.reference, 1, tmp)
            os.replace(tmp, path)
            print("  %.1f s" % wall, flush=True)
        refs[r.name] = read_rgb(path)
    rd_ref, cy_ref = refs["raydrive"], refs["cycles"]
    scale = float((rd_ref * cy_ref).sum() / (cy_ref * cy_ref).sum())
    print("references: RayDrive mean %.4f, Cycles mean %.4f; least-squares scale %.4f; "
          "RMS difference after scaling %.4f of the mean (both references' noise included)"
          % (rd_ref.mean(), cy_ref.mean(), scale, rel_rmse(scale * cy_ref, rd_ref)))

    for r in renderers:  # untimed warm-up: RayDrive's program build, the file cache
        r.render(1, 0, os.path.join(work, "warm_%s.exr" % r.name))
    print("\n%7s | %9s %9s %8s %8s | %9s %9s %8s | %9s %9s" % (
        "samples", "rd_wall_s", "rd_rend_s", "rd_Mray/s", "rd_err", "cy_wall_s", "cy_rend_s",
        "cy_err", "eff_wall", "eff_rend"))
    for n in [int(x) for x in a.samples.split(",")]:
        row = {}
        for r in renderers:
            walls, renders, err, rays = [], [], None, None
            for i in range(a.runs):
                out = os.path.join(work, "%s_%d.exr" % (r.name, n))
                wall, render, rays = r.render(n, 0, out)
                walls.append(wall)
                renders.append(render)
                err = rel_rmse(read_rgb(out), refs[r.name])  # the same image every run
            row[r.name] = (median(walls), median(renders), err, rays)
        rw, rr, re, rays = row["raydrive"]
        cw, cr, ce, _ = row["cycles"]
        print("%7d | %9.3f %9.3f %8.2f %8.4f | %9.3f %9.3f %8.4f | %9.2f %9.2f" % (
            n, rw, rr, rays / rr / 1e6, re, cw, cr, ce, rw * re ** 2 / (cw * ce ** 2),
            rr * re ** 2 / (cr * ce ** 2)), flush=True)
    print("\neff = RayDrive's time x error^2 over Cycles' (wall: whole commands; rend: the "
          "render alone): below 1, RayDrive reaches Cycles' error in less time")


if __name__ == "__main__":
    main()
