#!/usr/bin/env bash
# no_build_warnings.sh: renders good.rib (copied into the current directory) with each
# standard surface shader (and bumpy as a true displacement with fog as the atmosphere and
# the interior and the exterior, and a clipping plane; and a shader of its own reading
# object, raster and named spaces with per-object trace depths and diffuse visibility,
# casting shadows by its Oi),
# two lights, partial opacity, cold (no PoCL kernel cache), and
# fails if the OpenCL compiler printed any warning: PoCL's compiler writes "N warning(s)
# generated." to stderr, which a user would see with no context.
# usage: no_build_warnings.sh RAYDRIVE [WRAPPER...]: WRAPPER, when given, runs each render
# (tests/oclgrind runs them on Oclgrind: run_under_oclgrind.sh OCLGRIND LOG).
set -u
bin="$1"
shift
wrap=("$@")
# (the spaces case: a shader reading object, raster and named spaces, tracing with its
# objects' own depth limits, one object hidden from diffuse rays, shadows through the
# shader's Oi)
cat > spaces.sl <<'SL'
surface spaces() {
    point a = transform("object", P), b = transform("raster", P), c = transform("proj", P);
    normal Nf = faceforward(normalize(N), I);
    Ci = color(abs(xcomp(a)), abs(ycomp(b)), abs(zcomp(c))) * 0.1 + 0.5 * trace(P, reflect(I, Nf)) +
         0.1 * indirectdiffuse(P, Nf, 1);
    Oi = 0.6;
}
SL
for s in ${ONLY:-matte plastic metal mirror paintedplastic glass shinymetal displaced spaces}; do
    surface="Surface \"$s\""
    [ "$s" = displaced ] && surface="Attribute \"render\" \"int truedisplacement\" [1]\nDisplacement \"bumpy\"\nAtmosphere \"fog\"\nInterior \"fog\"\nExterior \"fog\"\nClippingPlane 0 0 100 0 0 1\nSurface \"plastic\""
    [ "$s" = spaces ] && surface="CoordinateSystem \"proj\"\nAttribute \"visibility\" \"string transmission\" [\"shader\"]\nAttributeBegin\nAttribute \"trace\" \"int maxspeculardepth\" [3]\nAttribute \"visibility\" \"int diffuse\" [0]\nSurface \"spaces\"\nSphere 0.2 -0.2 0.2 360\nAttributeEnd\nAttribute \"trace\" \"int maxspeculardepth\" [1]\nSurface \"spaces\""
    sed -e "s/Surface \"constant\"/LightSource \"distantlight\" 1\nLightSource \"pointlight\" 2 \"from\" [0 2 0]\nOpacity [0.5 0.5 0.5]\n$surface/" \
        good.rib > "$s.rib"
    if ! POCL_KERNEL_CACHE=0 "${wrap[@]}" "$bin" -q -o "$s.exr" "$s.rib" 2> "$s.err"; then
        echo "FAIL: $s.rib did not render"; cat "$s.err"; exit 1
    fi
    if grep -Eiq 'warnings? generated|warning:' "$s.err"; then
        echo "FAIL: $s.rib: compiler or render warnings"; cat "$s.err"; exit 1
    fi
done
echo "no warnings"
