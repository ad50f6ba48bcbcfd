"""sampler_error.py: the error of RayDrive's two samplers at the same samples a pixel.

For each scene: a reference at --reference samples a pixel (Sobol samples, seed 7: it
shares no sample with the images it judges), then renders at each --samples count with
`--sampler independent` and `--sampler sobol` under --seeds seeds (0, 1, ...), every pixel
sampled to the count (pixelerror 1e-6). Prints the mean relative RMS error over the seeds
(RMS over pixels and RGB over the reference's mean; it includes the reference's own
noise) and the median render time (`--stats` elapsed_s), and sobol's error over
independent's. With --targets E1,E2...: renders with `--error E` instead (adaptive
sampling up to 4096 samples a pixel) and prints, per sampler, the median time to the
target, the mean true error and the mean estimated error (`--stats`), and sobol's time
over independent's. Debian's python3 for numpy and OpenImageIO (sampler_error.sh
installs them).
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from gi_vs_cycles import read_rgb, rel_rmse  # noqa: E402


def at_samples(src, samples, dst, every_pixel=True):
    """The scene with PixelSamples s s (s^2 = samples) and every pixel sampled to it
    (every_pixel), else adaptive sampling up to it."""
    s = max(1, int(round(samples ** 0.5)))
    with open(src) as f:
        text = re.sub(r"PixelSamples \d+ \d+", "PixelSamples %d %d" % (s, s), f.read())
    text = re.sub(r'Display "[^"]*"[^\n]*\n', "", text)
    if every_pixel and "pixelerror" not in text:
        text = 'Option "render" "float pixelerror" [1e-6]\n' + text
    with open(dst, "w") as f:
        f.write(text)


def render(binary, src, samples, options, out, work, adaptive=False):
    """Renders; returns the --stats document."""
    rib = os.path.join(work, "scene.rib")
    at_samples(src, samples, rib, not adaptive)
    subprocess.run([binary, "-q", "-o", out, "--stats", out + ".json"] + options + [rib],
                   check=True)
    with open(out + ".json") as f:
        return json.load(f)


def to_targets(a, src, ref, work):
    """Time to each --error target, per sampler."""
    for target in [float(x) for x in a.targets.split(",")]:
        row = {}
        for sampler in ("independent", "sobol"):
            times, trues, ests = [], [], []
            for seed in range(a.seeds):
                out = os.path.join(work, "o.exr")
                st = render(a.raydrive, src, 4096, ["--sampler", sampler, "--seed", str(seed),
                                                    "--error", str(target)], out, work, True)
                times.append(st["elapsed_s"])
                trues.append(rel_rmse(read_rgb(out), ref))
                ests.append(st["sampling"]["estimated_error"])
            row[sampler] = (statistics.median(times), sum(trues) / len(trues),
                            sum(ests) / len(ests))
            print("%-18s %8g %-12s | %9.3f s | true %9.5f | estimated %9.5f" % (
                os.path.basename(src), target, sampler, *row[sampler]), flush=True)
        print("%-18s %8g sobol's time over independent's: %.3f" % (
            os.path.basename(src), target, row["sobol"][0] / row["independent"][0]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--raydrive", required=True)
    ap.add_argument("--samples", default="4,16,64")
    ap.add_argument("--reference", type=int, default=1024)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--targets", default="", help="error targets (--error): time to each")
    ap.add_argument("scenes", nargs="+")
    a = ap.parse_args()
    work = tempfile.mkdtemp()
    if not a.targets:
        print("%-18s %7s | %11s %9s | %11s %9s | %6s" % (
            "scene", "samples", "indep_err", "indep_s", "sobol_err", "sobol_s", "ratio"))
    for src in a.scenes:
        name = os.path.basename(src)
        ref_path = os.path.join(work, "ref.exr")
        render(a.raydrive, src, a.reference, ["--seed", "7", "--sampler", "sobol"], ref_path, work)
        ref = read_rgb(ref_path)
        for sampler in ("independent", "sobol"):  # untimed warm-up: each seed's program
            for seed in range(a.seeds):
                render(a.raydrive, src, 1, ["--sampler", sampler, "--seed", str(seed)],
                       os.path.join(work, "w.exr"), work)
        if a.targets:
            to_targets(a, src, ref, work)
            continue
        for n in [int(x) for x in a.samples.split(",")]:
            row = {}
            for sampler in ("independent", "sobol"):
                errs, times = [], []
                for seed in range(a.seeds):
                    out = os.path.join(work, "o.exr")
                    times.append(render(a.raydrive, src, n, ["--sampler", sampler, "--seed",
                                                             str(seed)], out, work)["elapsed_s"])
                    errs.append(rel_rmse(read_rgb(out), ref))
                row[sampler] = (sum(errs) / len(errs), statistics.median(times))
            (ei, ti), (es, ts) = row["independent"], row["sobol"]
            print("%-18s %7d | %11.4f %9.3f | %11.4f %9.3f | %6.2f" % (
                name, n, ei, ti, es, ts, es / ei), flush=True)


if __name__ == "__main__":
    main()
