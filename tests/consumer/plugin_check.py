"""pvbatch check that the installed plugin was auto-loaded (PV_PLUGIN_PATH or
PV_PLUGIN_CONFIG_FILE set by HybridOctreeConsumerTest.cmake): the filter
exists and image data offers the "Hybrid Octree Volume" representation."""
import os

from paraview.simple import *  # noqa: F401,F403

shown = Show(Wavelet())
offered = "Hybrid Octree Volume" in shown.GetProperty("Representation").Available
ok = "HybridOctree" in globals() and offered
os.write(1, ("installed plugin: filter %s, representation %s\n" % ("HybridOctree" in globals(), offered)).encode())
os._exit(0 if ok else 1)
