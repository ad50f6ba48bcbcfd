/* arealight.sl: the RI 3.2 area light: every point of the light's surface emits into
   the hemisphere around its normal. */
#define PI 3.14159265358979

light
arealight(float intensity = 1;
          color lightcolor = 1;)
{
    illuminate(P, N, PI / 2)
        Cl = (intensity / (L . L)) * lightcolor;
}
