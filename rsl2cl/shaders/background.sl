/* background.sl: the RI 3.2 standard imager: the background colour behind what is not
 * covered (premultiplied colour: Ci + (1 - alpha) bgcolor), leaving the image opaque. */
imager
background(color bgcolor = 1;)
{
    Ci += (1 - alpha) * bgcolor;
    Oi = 1;
    alpha = 1;
}
