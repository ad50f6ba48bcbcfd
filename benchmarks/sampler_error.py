"""sampler_error.py: the error of RayDrive's two samplers at the same samples a pixel.

For each scene: a reference at --reference samples a pixel (independent samples, seed 7:
it shares no sample with the images it judges), then renders at each --samples count with
`--sampler independent` and `--sampler sobol` under --seeds seeds (0, 1, ...), every pixel
sampled to the count (pixelerror 1e-6). Prints the mean relative RMS error over the seeds
(RMS over pixels and RGB over the reference's mean; it includes the reference's own
noise) and the median render time (`--stats` elapsed_s), and sobol's error over
independent's. Debian's python3 for numpy and OpenImageIO (sampler_error.sh installs them).
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


def at_samples(src, samples, dst):
    """The scene with PixelSamples s s (s^2 = samples) and every pixel sampled to it."""
    s = max(1, int(round(samples ** 0.5)))
    with open(src) as f:
        text = re.sub(r"PixelSamples \d+ \d+", "PixelSamples %d %d" % (s, s), f.read())
    text = re.sub(r'Display "[^"]*"[^\n]*\n', "", text)
    if "pixelerror" not in text:
        text = 'Option "render" "float pixelerror" [1e-6]\n' + text
    with open(dst, "w") as f:
        f.write(text)


def render(binary, src, samples, options, out, work):
    rib = os.path.join(work, "scene.rib")
    at_samples(src, samples, rib)
    subprocess.run([binary, "-q", "-o", out, "--stats", out + ".json"] + options + [rib],
                   check=True)
    with open(out + ".json") as f:
        return json.load(f)["elapsed_s"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--raydrive", required=True)
    ap.add_argument("--samples", default="4,16,64")
    ap.add_argument("--reference", type=int, default=1024)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("scenes", nargs="+")
    a = ap.parse_args()
    work = tempfile.mkdtemp()
    print("%-18s %7s | %11s %9s | %11s %9s | %6s" % (
        "scene", "samples", "indep_err", "indep_s", "sobol_err", "sobol_s", "ratio"))
    for src in a.scenes:
        name = os.path.basename(src)
        ref_path = os.path.join(work, "ref.exr")
        render(a.raydrive, src, a.reference, ["--seed", "7"], ref_path, work)
        ref = read_rgb(ref_path)
        for sampler in ("independent", "sobol"):  # untimed warm-up: each seed's program
            for seed in range(a.seeds):
                render(a.raydrive, src, 1, ["--sampler", sampler, "--seed", str(seed)],
                       os.path.join(work, "w.exr"), work)
        for n in [int(x) for x in a.samples.split(",")]:
            row = {}
            for sampler in ("independent", "sobol"):
                errs, times = [], []
                for seed in range(a.seeds):
                    out = os.path.join(work, "o.exr")
                    times.append(render(a.raydrive, src, n,
                                        ["--sampler", sampler, "--seed", str(seed)], out, work))
                    errs.append(rel_rmse(read_rgb(out), ref))
                row[sampler] = (sum(errs) / len(errs), statistics.median(times))
            (ei, ti), (es, ts) = row["independent"], row["sobol"]
            print("%-18s %7d | %11.4f %9.3f | %11.4f %9.3f | %6.2f" % (
                name, n, ei, ti, es, ts, es / ei), flush=True)


if __name__ == "__main__":
    main()
