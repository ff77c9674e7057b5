/* background: the standard imager (RI Spec 3.2): puts the background colour behind what was
   rendered, where the pixel is not wholly covered (Ci is premultiplied by alpha), and makes the
   frame opaque. */
imager background(color background = 1;)
{
    Ci += (1 - alpha) * background;
    alpha = 1;
}
