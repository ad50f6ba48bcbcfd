/* matte.sl: the RI 3.2 standard matte (Lambertian) surface. */
surface
matte(float Ka = 1, Kd = 1;)
{
    normal Nf = faceforward(normalize(N), I);
    Oi = Os;
    Ci = Os * Cs * (Ka * ambient() + Kd * diffuse(Nf));
}
