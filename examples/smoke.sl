/* smoke.sl: a uniform scattering medium for examples/light_shaft.rib. It marches the
 * segment from the ray's origin to P in steps of about `stepsize`: what lies behind is
 * dimmed by exp(-density length), and each step adds the light it sees, dimmed by the
 * medium in front of it. RayDrive traces each light's shadow ray from one of the steps
 * (picked at random, weighted by their number), so objects cast shafts of shadow. */
volume smoke(float density = 0.15; float stepsize = 0.1; color scatter = 1;) {
    float len = length(I);
    float steps = max(1, ceil(len / stepsize));
    float dt = len / steps;
    point P0 = P - I;
    color light = 0;
    float T = 1, k;
    for (k = 0; k < steps; k += 1) {
        point Pk = P0 + I * ((k + 0.5) / steps);
        color Li = 0;
        illuminance(Pk) {
            Li += Cl;
        }
        light += T * density * dt * scatter * Li;
        T *= exp(-density * dt);
    }
    Ci = T * Ci + light;
}
