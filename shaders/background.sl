/* background: the standard imager (RI Spec 3.2): puts the background colour behind what was
   rendered, where the pixel is not wholly covered (Ci is premultiplied by alpha), and makes the
   frame opaque. Both names of its colour are read: "background" (the RI Spec's and PRMan's) and
   "bgcolor" (Larry Gritz's background.sl, which Aqsis ships and exporters such as RhinoMan write);
   the colour is their product, as in Aqsis's. */
imager background(color background = 1; color bgcolor = 1;)
{
    Ci += (1 - alpha) * (bgcolor * background);
    alpha = 1;
}
