/* defaultsurface: what a surface without a Surface request gets (as in PRMan and
 * BMRT): lit from the eye, no light sources needed. */
surface defaultsurface(float Ka = 0.2, Kd = 0.8)
{
    float d = normalize(I) . normalize(N);
    Oi = Os;
    Ci = Os * Cs * (Ka + Kd * d * d);
}
