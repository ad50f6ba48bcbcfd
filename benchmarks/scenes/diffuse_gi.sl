/* diffuse_gi.sl: a Lambertian surface that path-traces its indirect light, for
 * benchmarks/gi_vs_cycles.py: direct light from the light shaders (each a shadow ray)
 * plus one cosine-distributed traced ray, whose pdf cancels the cosine and the 1/pi of the
 * Lambertian BRDF (the lights' intensities carry that pi: cornell.py). */
surface diffuse_gi(float Kd = 1;)
{
    normal Nf = faceforward(normalize(N), I);
    vector T = normalize((abs(xcomp(Nf)) > 0.5 ? vector(0, 1, 0) : vector(1, 0, 0)) ^ Nf);
    vector B = Nf ^ T;
    float r1 = random(), r2 = random();
    float phi = 2 * PI * r1, sr = sqrt(r2);
    vector d = sr * cos(phi) * T + sr * sin(phi) * B + sqrt(1 - r2) * Nf;
    Oi = 1;
    Ci = Kd * Cs * (diffuse(Nf) + trace(P, d));
}
