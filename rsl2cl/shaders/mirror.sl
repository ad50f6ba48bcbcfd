/* mirror.sl: a perfect mirror using trace(), with optional plastic-like terms. */
surface
mirror(float Ka = 0, Kd = 0, Ks = 0, Kr = 1, roughness = .1;
       color specularcolor = 1;)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    vector R = reflect(normalize(I), Nf);
    Oi = Os;
    Ci = Os * (Cs * (Ka * ambient() + Kd * diffuse(Nf)) +
               specularcolor * Ks * specular(Nf, V, roughness) +
               Kr * trace(P, R));
}
