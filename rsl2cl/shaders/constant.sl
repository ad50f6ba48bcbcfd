/* constant.sl: the RI 3.2 standard constant surface. */
surface
constant()
{
    Oi = Os;
    Ci = Os * Cs;
}
