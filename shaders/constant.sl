/* constant: the surface's colour, unlit (RI Spec 3.2, appendix A). */
surface constant()
{
    Oi = Os;
    Ci = Os * Cs;
}
