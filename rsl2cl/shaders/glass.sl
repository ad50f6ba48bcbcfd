/* glass.sl: a dielectric using fresnel() and trace() for reflection and refraction. */
surface
glass(float Ka = 0, Ks = .5, Kr = 1, Kt = 1, roughness = .05, eta = 1.5;
      color transmitcolor = 1;)
{
    normal Nn = normalize(N);
    vector In = normalize(I);
    normal Nf = faceforward(Nn, In);
    vector V = -In;
    float kr, kt;
    vector R, T;
    float ior = (In . Nn < 0) ? 1 / eta : eta;   /* entering or leaving */

    fresnel(In, Nf, ior, kr, kt, R, T);
    Oi = 1;
    Ci = Ka * ambient() + Ks * specular(Nf, V, roughness) +
         Kr * kr * trace(P, R);
    if (kt > 0)
        Ci += Kt * kt * transmitcolor * trace(P, T);
}
