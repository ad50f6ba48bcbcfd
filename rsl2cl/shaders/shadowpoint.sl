/* shadowpoint.sl: point light with shadows; shadowname "raytrace" casts shadow rays. */
light
shadowpoint(float intensity = 1;
            color lightcolor = 1;
            point from = point "shader" (0, 0, 0);
            string shadowname = "";
            float samples = 16;
            float width = 1;
            float bias = -1;)
{
    illuminate(from) {
        Cl = intensity * lightcolor / (L . L);
        if (shadowname != "")
            Cl *= 1 - shadow(shadowname, Ps, "samples", samples, "width", width,
                             "bias", bias);
    }
}
