/* ambientlight.sl: the RI 3.2 standard ambient light (no direction: ambient()). */
light
ambientlight(float intensity = 1;
             color lightcolor = 1;)
{
    Cl = intensity * lightcolor;
}
