/* pointlight.sl: the RI 3.2 standard point light (inverse-square falloff). */
light
pointlight(float intensity = 1;
           color lightcolor = 1;
           point from = point "shader" (0, 0, 0);)
{
    illuminate(from)
        Cl = intensity * lightcolor / (L . L);
}
