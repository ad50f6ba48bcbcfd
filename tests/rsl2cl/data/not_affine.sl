/* not_affine.sl: Ci multiplies two trace() results (rejected by rsl2cl). */
surface not_affine()
{
    vector R = reflect(I, N);
    Ci = trace(P, R) * trace(P, -R);
}
