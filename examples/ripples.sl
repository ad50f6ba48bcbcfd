/* ripples.sl: a procedural displacement for examples/displacement.rib: rings spreading
 * from the object's origin, moving the surface along its normal by height * sin. */
displacement ripples(float height = 0.05; float wavelength = 0.5;) {
    point Q = transform("object", P);
    float r = sqrt(xcomp(Q) * xcomp(Q) + ycomp(Q) * ycomp(Q));
    P += height * sin(2 * PI * r / wavelength) * exp(-r) * normalize(N);
    N = calculatenormal(P);
}
