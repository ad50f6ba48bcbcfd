#!/usr/bin/env bash
# cutout_shadows.sh: leaves cut out by their shader's opacity, casting the cut-out shadows
# (session 36: transmission "shader", the shadow rays handed to the pool at each leaf).
# A generated scene of 600 quads over a floor, each leaf's Oi 1 or 0 on a checker of
# world x and y, lit by a distant light and an ambient one, rendered in one run by:
#   RayDrive with "string transmission" ["shader"] (shadows through the shader's Oi),
#   RayDrive with opaque shadows (the same leaves casting full ones: what the feature
#   costs), and POV-Ray 3.7 (Debian `povray`, +WT2 -A: a pigment whose transmit is the
#   same checker; POV-Ray's shadows go through transmitting pigments).
# 512 x 512, one sample a pixel. Reported: wall time (median of N runs, default 3, after
# an untimed warm-up that builds the OpenCL programs), the ratios, and the mean brightness
# of rows 384-447 (the floor under the leaves, the shadows, leaves): a check that the
# three render alike (POV-Ray's PNG is gamma-encoded, RayDrive's linear).
set -euo pipefail
source "$(dirname "$0")/common.sh"
runs="${1:-3}"
peer_benchmark_setup

python3 - "$work" <<'PY'
import random, sys
w = sys.argv[1]
random.seed(3)
leaves = [(random.uniform(-4, 4), random.uniform(1.0, 3.5), random.uniform(-4, 4),
           random.uniform(0, 360), random.uniform(-40, 40), random.uniform(0.3, 0.6))
          for _ in range(600)]
shader = """surface leaf(float Ka = 0.2, Kd = 0.8, freq = 12) {
  point Pw = transform("world", P);
  Oi = sin(xcomp(Pw) * freq) * sin(ycomp(Pw) * freq) >= 0 ? color(1) : color(0);
  normal Nf = faceforward(normalize(N), I);
  Ci = Oi * Cs * (Ka * ambient() + Kd * diffuse(Nf));
}
"""
open(w + "/leaf.sl", "w").write(shader)
for mode in ("shader", "opaque"):
    with open("%s/leaves_%s.rib" % (w, mode), "w") as f:
        f.write('Format 512 512 1\nPixelSamples 1 1\nProjection "perspective" "fov" 45\n'
                'Rotate -26.565 1 0 0\nTranslate 0 -6 10\nWorldBegin\n'
                'LightSource "distantlight" 1 "from" [1 3 -2] "to" [0 0 0]\n'
                'LightSource "ambientlight" 2 "intensity" 1\n'
                'Surface "matte" "Ka" 0.2 "Kd" 0.8\n'
                'Polygon "P" [-8 0 -8  -8 0 8  8 0 8  8 0 -8]\n'
                'Color [0.1 0.6 0.2]\nSurface "leaf"\n')
        f.write('Attribute "visibility" "string transmission" ["%s"]\n' % mode)
        for x, y, z, ry, rx, s in leaves:
            f.write('AttributeBegin Translate %.4f %.4f %.4f Rotate %.3f 0 1 0 Rotate %.3f 1 0 0 '
                    'Polygon "P" [%g 0 %g  %g 0 %g  %g 0 %g  %g 0 %g] AttributeEnd\n'
                    % (x, y, z, ry, rx, -s, -s, -s, s, s, s, s, -s))
        f.write('WorldEnd\n')
with open(w + "/leaves.pov", "w") as f:
    f.write('#version 3.7;\nglobal_settings { ambient_light 1 assumed_gamma 1 }\n'
            'camera { location <0, 6, -10> look_at <0, 1, 0> angle 45 }\n'
            'light_source { <1000, 3000, -2000> color rgb 1 parallel point_at <0, 0, 0> }\n'
            '#default { finish { ambient 0.2 diffuse 0.8 } }\n'
            'polygon { 5, <-8, 0, -8>, <-8, 0, 8>, <8, 0, 8>, <8, 0, -8>, <-8, 0, -8> '
            'pigment { color rgb 1 } }\n'
            '#declare Leaf = pigment { function { select(sin(x * 12) * sin(y * 12), 1, 0) }\n'
            '  color_map { [0 rgbt <0.1, 0.6, 0.2, 0>] [1 rgbt <0.1, 0.6, 0.2, 1>] } }\n')
    for x, y, z, ry, rx, s in leaves:
        f.write('polygon { 5, <%g, 0, %g>, <%g, 0, %g>, <%g, 0, %g>, <%g, 0, %g>, <%g, 0, %g> '
                'rotate <%.3f, 0, 0> rotate <0, %.3f, 0> translate <%.4f, %.4f, %.4f> '
                'pigment { Leaf } }\n'
                % (-s, -s, -s, s, s, s, s, -s, -s, -s, rx, ry, x, y, z))
PY

bin="$(readlink -f "$bin")"
cd "$work"
"$bin" -q -o shader.exr leaves_shader.rib   # warm-up: program builds
"$bin" -q -o opaque.exr leaves_opaque.rib
s=$(for i in $(seq "$runs"); do wall "$bin" -q -o shader.exr leaves_shader.rib; done | median)
o=$(for i in $(seq "$runs"); do wall "$bin" -q -o opaque.exr leaves_opaque.rib; done | median)
p=$(for i in $(seq "$runs"); do wall povray +Ileaves.pov +Opov.png +W512 +H512 +WT2 -D -A; done | median)
"$bin" -q -o shader.png leaves_shader.rib
"$bin" -q -o opaque.png leaves_opaque.rib
# the mean brightness of rows 384-447 (the floor under the leaves, their shadows, leaves)
rows_mean() {
  python3 - "$1" <<'PY'
import sys, zlib, struct
data = open(sys.argv[1], "rb").read()
pos, idat, w, h, ctype = 8, b"", 0, 0, 0
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind == b"IHDR": w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
    if kind == b"IDAT": idat += body
    pos += 12 + n
raw = zlib.decompress(idat)
ch = {2: 3, 6: 4}[ctype]
stride, prev, rows = w * ch, bytearray(w * ch), []
for y in range(h):
    f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - ch] if i >= ch else 0
        b, c = prev[i], prev[i - ch] if i >= ch else 0
        if f == 1: line[i] = (line[i] + a) & 255
        elif f == 2: line[i] = (line[i] + b) & 255
        elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif f == 4:
            pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(line)
    prev = line
sel = [rows[y][x * ch + k] for y in range(h * 3 // 4, h * 7 // 8) for x in range(w) for k in range(3)]
print("%.3f" % (sum(sel) / len(sel) / 255))
PY
}
printf '%-22s %9s %9s\n' renderer ms rows
printf '%-22s %9d %9s\n' "raydrive shader" "$s" "$(rows_mean shader.png)"
printf '%-22s %9d %9s\n' "raydrive opaque" "$o" "$(rows_mean opaque.png)"
printf '%-22s %9d %9s\n' "povray" "$p" "$(rows_mean pov.png)"
echo "shader / opaque $(ratio "$s" "$o"), shader / povray $(ratio "$s" "$p")"
[ -z "${KEEP_IMAGES:-}" ] || cp shader.png opaque.png pov.png "$KEEP_IMAGES"/
